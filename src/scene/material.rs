//! Materials: a Lambertian albedo (`baseColorFactor` x `baseColorTexture`, linear), an optional
//! glossy part, an optional normal map and optional emission. glTF's metallic factor is not used
//! for GI.
//!
//! Emission is glTF's `emissiveFactor` x `emissiveTexture` (the colour) times
//! `KHR_materials_emissive_strength` (the strength), in the scene model's radiometric units: the
//! product is the front face's radiance in W/(sr m²), the same from every direction (a
//! Lambertian emitter). Surfaces emit from their front face only, as they reflect.

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
    /// Linear RGB emission colour (glTF `emissiveFactor`, each in [0, 1]); black emits nothing.
    /// Project files leave the emission fields out while they hold their defaults, so a file
    /// without emission reads and saves as it did before emission existed.
    #[serde(default, skip_serializing_if = "is_black")]
    pub emissive_color: [f32; 3],
    /// Emitted radiance per unit colour, W/(sr m²) (radiometric; glTF's
    /// `KHR_materials_emissive_strength`, converted by the scene's light units on import).
    #[serde(default = "unit_strength", skip_serializing_if = "is_unit")]
    pub emissive_strength: f32,
    /// Optional sRGB emission texture multiplied with `emissive_color`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub emissive_texture: Option<TextureRef>,
}

fn unit_strength() -> f32 {
    1.0
}

fn is_unit(v: &f32) -> bool {
    *v == 1.0
}

fn is_black(c: &[f32; 3]) -> bool {
    *c == [0.0; 3]
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
            emissive_color: [0.0; 3],
            emissive_strength: 1.0,
            emissive_texture: None,
        }
    }
}

impl Material {
    /// A plain diffuse material.
    pub fn diffuse(name: &str, albedo: [f32; 3]) -> Self {
        Self { name: name.into(), base_color: [albedo[0], albedo[1], albedo[2], 1.0], ..Self::default() }
    }

    /// The front face's emitted radiance, W/(sr m²), before the emission texture.
    pub fn emission(&self) -> glam::Vec3 {
        glam::Vec3::from_array(self.emissive_color) * self.emissive_strength
    }

    /// Whether the material gives off light.
    pub fn emits(&self) -> bool {
        self.emission().max_element() > 0.0
    }

    /// Checks numbers and ranges.
    pub fn validate(&self) -> Result<(), SceneError> {
        let what = format!("material {:?}", self.name);
        check_finite(&what, &self.base_color)?;
        check_finite(&what, &self.emissive_color)?;
        check_finite(&what, &[self.emissive_strength])?;
        if self.emissive_color.iter().any(|c| *c < 0.0) || self.emissive_strength < 0.0 {
            return Err(SceneError::BadValue { what, why: "emission must be >= 0".into() });
        }
        if self.emissive_strength > super::limits::MAX_INTENSITY {
            let why = format!("emissive strength {} is over {}", self.emissive_strength, super::limits::MAX_INTENSITY);
            return Err(SceneError::BadValue { what, why });
        }
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
