//! Materials: a Lambertian albedo (`baseColorFactor` x `baseColorTexture`, linear), an optional
//! glossy part and an optional normal map. glTF's metallic factor is not used for GI.

use serde::{Deserialize, Serialize};

use super::{SceneError, check_finite};

/// A reference to an image in [`super::Resources::images`].
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TextureRef {
    /// Index into the scene's images.
    pub image: usize,
    /// Which TEXCOORD set is used (only 0 is supported; others fall back to 0 with a warning).
    pub tex_coord: u32,
}

/// A surface material.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Material {
    /// Display name.
    pub name: String,
    /// Linear RGBA base colour factor; RGB is the Lambertian albedo.
    pub base_color: [f32; 4],
    /// Optional sRGB base colour texture multiplied with `base_color`.
    pub base_color_texture: Option<TextureRef>,
    /// Optional tangent-space normal map.
    pub normal_texture: Option<TextureRef>,
    /// Normal map strength (glTF `normalTexture.scale`).
    pub normal_scale: f32,
    /// Specular colour of the optional glossy lobe (black = purely diffuse).
    pub specular: [f32; 3],
    /// Perceptual roughness of the glossy lobe in [0.02, 1].
    pub roughness: f32,
}

impl Default for Material {
    fn default() -> Self {
        Self {
            name: "default".into(),
            base_color: [0.8, 0.8, 0.8, 1.0],
            base_color_texture: None,
            normal_texture: None,
            normal_scale: 1.0,
            specular: [0.0; 3],
            roughness: 1.0,
        }
    }
}

impl Material {
    /// A plain diffuse material.
    pub fn diffuse(name: &str, albedo: [f32; 3]) -> Self {
        Self { name: name.into(), base_color: [albedo[0], albedo[1], albedo[2], 1.0], ..Self::default() }
    }

    /// Checks numbers and ranges.
    pub fn validate(&self) -> Result<(), SceneError> {
        let what = format!("material {:?}", self.name);
        check_finite(&what, &self.base_color)?;
        check_finite(&what, &self.specular)?;
        check_finite(&what, &[self.roughness, self.normal_scale])?;
        if self.base_color.iter().any(|c| *c < 0.0) || self.specular.iter().any(|c| *c < 0.0) {
            return Err(SceneError::BadValue { what, why: "colours must be >= 0".into() });
        }
        super::limits::check_reflectance(&what, "base colour", &self.base_color)?;
        super::limits::check_reflectance(&what, "specular", &self.specular)?;
        Ok(())
    }
}
