//! The environment: the light that arrives from infinitely far away in every direction no
//! surface blocks (the sky through windows and doors, the whole sky outdoors).
//!
//! It exists because the sun alone leaves an interior lit by one bright patch: the blue fill of
//! the sky is what makes rooms read, and every engine the users come from has it (Unreal's sky
//! light, Unity's environment lighting, Godot's WorldEnvironment, Blender's world). glTF has no
//! sky, so it lives in the project file (and on the command line for a bare glTF).
//!
//! Radiance is in the scene model's radiometric units, W/(sr m²), like emission
//! ([`super::Material::emission`]). An image is equirectangular (longitude x latitude, linear
//! RGB, `.hdr` or `.exr`): for a world direction `d` (after the rotation about +Y), column
//! `u = atan2(d.z, d.x) / 2π` (wrapped into [0, 1)) and row `v = acos(d.y) / π`, so the top row
//! is straight up and the image's centre column looks along -X.

use std::f32::consts::PI;

use glam::Vec3;
use serde::{Deserialize, Serialize};

use super::{SceneError, check_finite};

/// What the sky is.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub enum Sky {
    /// No environment light: everything no surface blocks is black.
    #[default]
    None,
    /// The same radiance from every direction (linear RGB, times [`Environment::intensity`]).
    Constant([f32; 3]),
    /// An equirectangular HDR image (`.hdr` or `.exr`), relative to the project file with
    /// forward slashes (or as given on the command line); its texels times
    /// [`Environment::intensity`] are radiance.
    Image(String),
    /// Preetham et al.'s analytic clear sky ([`super::preetham`]) of this turbidity, driven by
    /// the scene's sun (its first directional light; [`super::Scene::sun_direction`]), in
    /// physical units (turbidity 3, the sun 45 degrees up: a zenith of 7.3 kcd/m², 10.7 W/(sr m²)) times [`Environment::intensity`].
    Preetham {
        /// Atmospheric turbidity, 1.7 (very clear) to 10 (thin overcast).
        turbidity: f32,
    },
}

/// The environment of a scene.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Environment {
    /// The sky's kind and colour or image.
    pub sky: Sky,
    /// A scale on the sky's radiance (W/(sr m²) per unit colour, radiometric).
    pub intensity: f32,
    /// Rotation about +Y in degrees (turns an image's sun to where the level needs it).
    pub rotation_degrees: f32,
}

impl Default for Environment {
    fn default() -> Self {
        Self { sky: Sky::None, intensity: 1.0, rotation_degrees: 0.0 }
    }
}

/// A decoded equirectangular environment image: linear RGB radiance, row-major from the top.
#[derive(Clone, Debug, PartialEq)]
pub struct SkyImage {
    /// Width in texels (longitude).
    pub width: u32,
    /// Height in texels (latitude).
    pub height: u32,
    /// Linear RGB texels.
    pub texels: Vec<[f32; 3]>,
}

impl SkyImage {
    /// The texel holding direction `d` (unrotated frame), nearest.
    pub fn texel_of(&self, d: Vec3) -> (u32, u32) {
        let (u, v) = equirect_uv(d);
        let x = ((u * self.width as f32) as u32).min(self.width - 1);
        let y = ((v * self.height as f32) as u32).min(self.height - 1);
        (x, y)
    }

    /// The texel at (x, y).
    pub fn texel(&self, x: u32, y: u32) -> Vec3 {
        Vec3::from_array(self.texels[(y * self.width + x) as usize])
    }

    /// The solid angle of a texel in row `y` (rows near the poles cover less of the sphere).
    pub fn texel_solid_angle(&self, y: u32) -> f32 {
        let h = self.height as f32;
        let (t0, t1) = (PI * y as f32 / h, PI * (y + 1) as f32 / h);
        2.0 * PI / self.width as f32 * (t0.cos() - t1.cos())
    }

    /// Checks the size and that every texel is a finite radiance >= 0.
    pub fn validate(&self) -> Result<(), SceneError> {
        let what = "sky image";
        if self.width == 0 || self.height == 0 || self.texels.len() != (self.width * self.height) as usize {
            return Err(SceneError::BadValue {
                what: what.into(),
                why: format!("{}x{} with {} texels", self.width, self.height, self.texels.len()),
            });
        }
        if let Some(i) = self.texels.iter().position(|t| t.iter().any(|c| !c.is_finite() || *c < 0.0)) {
            let (x, y) = (i as u32 % self.width, i as u32 / self.width);
            return Err(SceneError::BadValue {
                what: what.into(),
                why: format!("texel ({x}, {y}) is {:?}; radiance must be finite and >= 0", self.texels[i]),
            });
        }
        Ok(())
    }
}

/// Equirectangular coordinates in [0, 1)^2 of unit direction `d` (module docs).
pub fn equirect_uv(d: Vec3) -> (f32, f32) {
    let mut u = d.z.atan2(d.x) / (2.0 * PI);
    if u < 0.0 {
        u += 1.0;
    }
    // atan2 rather than acos: acos loses half the digits near the poles.
    let v = (d.x * d.x + d.z * d.z).sqrt().atan2(d.y) / PI;
    (u.min(0.999_999), v.min(0.999_999))
}

/// The unit direction at equirectangular coordinates (u, v): the inverse of [`equirect_uv`].
pub fn equirect_direction(u: f32, v: f32) -> Vec3 {
    let (phi, theta) = (2.0 * PI * u, PI * v);
    Vec3::new(theta.sin() * phi.cos(), theta.cos(), theta.sin() * phi.sin())
}

impl Environment {
    /// Whether this is the default (no sky, intensity 1, no rotation): what files leave out.
    pub fn is_default(&self) -> bool {
        *self == Self::default()
    }

    /// Whether any light comes from the environment.
    pub fn emits(&self, image: Option<&SkyImage>) -> bool {
        self.intensity > 0.0
            && match &self.sky {
                Sky::None => false,
                Sky::Constant(c) => c.iter().any(|v| *v > 0.0),
                Sky::Image(_) | Sky::Preetham { .. } => image.is_some(),
            }
    }

    /// A direction in the world turned into the sky's own (unrotated) frame.
    pub fn to_sky(&self, d: Vec3) -> Vec3 {
        glam::Quat::from_rotation_y(-self.rotation_degrees.to_radians()) * d
    }

    /// A direction of the sky's own frame turned into the world.
    pub fn to_world(&self, d: Vec3) -> Vec3 {
        glam::Quat::from_rotation_y(self.rotation_degrees.to_radians()) * d
    }

    /// The radiance arriving from world direction `-d` along a ray travelling along `d` that
    /// leaves the scene (`image`: the decoded [`Sky::Image`] or the baked [`Sky::Preetham`],
    /// [`super::Scene::sky_texels`]).
    pub fn radiance(&self, d: Vec3, image: Option<&SkyImage>) -> Vec3 {
        match (&self.sky, image) {
            (Sky::Constant(c), _) => Vec3::from_array(*c) * self.intensity,
            (Sky::Image(_) | Sky::Preetham { .. }, Some(img)) => {
                let (x, y) = img.texel_of(self.to_sky(d));
                img.texel(x, y) * self.intensity
            }
            _ => Vec3::ZERO,
        }
    }

    /// Checks numbers and ranges.
    pub fn validate(&self) -> Result<(), SceneError> {
        let what = "environment";
        check_finite(what, &[self.intensity, self.rotation_degrees])?;
        if self.intensity < 0.0 || self.intensity > super::limits::MAX_INTENSITY {
            return Err(SceneError::BadValue {
                what: what.into(),
                why: format!("intensity {} is outside 0..={}", self.intensity, super::limits::MAX_INTENSITY),
            });
        }
        if let Sky::Constant(c) = &self.sky {
            check_finite(what, c)?;
            if c.iter().any(|v| *v < 0.0) {
                return Err(SceneError::BadValue { what: what.into(), why: "sky colour must be >= 0".into() });
            }
        }
        if let Sky::Image(path) = &self.sky
            && path.trim().is_empty()
        {
            return Err(SceneError::BadValue { what: what.into(), why: "sky image path is empty".into() });
        }
        if let Sky::Preetham { turbidity } = self.sky {
            let (lo, hi) = super::preetham::TURBIDITY_RANGE;
            if !(lo..=hi).contains(&turbidity) {
                let why = format!("turbidity {turbidity} is outside {lo}..={hi}, where the model was fitted");
                return Err(SceneError::BadValue { what: what.into(), why });
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equirect_mapping_round_trips_and_puts_up_in_the_top_row() {
        for d in [Vec3::X, Vec3::new(0.3, 0.5, -0.8).normalize(), Vec3::new(-0.6, -0.2, 0.3).normalize()] {
            let (u, v) = equirect_uv(d);
            assert!((equirect_direction(u, v) - d).length() < 1e-4, "{d}");
        }
        assert!(equirect_uv(Vec3::Y).1 < 1e-6);
        assert!(equirect_uv(Vec3::NEG_Y).1 > 0.999);
    }

    #[test]
    fn texel_solid_angles_sum_to_the_sphere() {
        let img = SkyImage { width: 16, height: 8, texels: vec![[1.0; 3]; 128] };
        let total: f32 = (0..8).map(|y| 16.0 * img.texel_solid_angle(y)).sum();
        assert!((total - 4.0 * PI).abs() < 1e-4, "{total}");
    }

    #[test]
    fn a_rotation_turns_the_image_about_up() {
        let d = Vec3::new(1.0, 0.05, 0.0).normalize();
        let mut texels = vec![[0.0; 3]; 8 * 4];
        let img_x = SkyImage { width: 8, height: 4, texels: texels.clone() }.texel_of(d);
        texels[(img_x.1 * 8 + img_x.0) as usize] = [5.0; 3];
        let img = SkyImage { width: 8, height: 4, texels };
        let env = Environment { sky: Sky::Image("sky.hdr".into()), intensity: 2.0, rotation_degrees: 90.0 };
        // +X of the image now looks along the world's rotated +X.
        assert_eq!(env.radiance(env.to_world(d), Some(&img)), Vec3::splat(10.0));
        assert_eq!(env.radiance(d, Some(&img)), Vec3::ZERO);
    }

    #[test]
    fn negative_or_empty_skies_are_refused() {
        let env = Environment { sky: Sky::Constant([-1.0, 0.0, 0.0]), ..Environment::default() };
        assert!(env.validate().is_err());
        let env = Environment { sky: Sky::Image(" ".into()), ..Environment::default() };
        assert!(env.validate().is_err());
        let img = SkyImage { width: 2, height: 1, texels: vec![[1.0; 3], [f32::NAN, 0.0, 0.0]] };
        assert!(img.validate().expect_err("a NaN texel").to_string().contains("texel (1, 0)"));
    }
}
