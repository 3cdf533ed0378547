//! Punctual lights with the KHR_lights_punctual conventions of docs/ARCHITECTURE.md,
//! "Conventions": `color * intensity` is radiant intensity in W/sr (point, spot) or irradiance in
//! W/m^2 (directional), linear RGB, pure inverse-square falloff when `range` is absent, and the
//! specification's spot falloff (scale/offset on the cosine, then squared).

use glam::Vec3;
use serde::{Deserialize, Serialize};

use super::{SceneError, check_finite};

/// The kind of a light and its kind-specific parameters.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum LightKind {
    /// Emits in all directions from `position`.
    Point,
    /// Emits in a cone around `direction` from `position`.
    Spot {
        /// Angle (radians) from the axis where the falloff starts.
        inner_cone_angle: f32,
        /// Angle (radians) from the axis where the light reaches zero.
        outer_cone_angle: f32,
    },
    /// Parallel light travelling along `direction`; `position` is unused.
    Directional,
}

/// A punctual light.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Light {
    /// Display name.
    pub name: String,
    /// Point, spot or directional.
    pub kind: LightKind,
    /// Linear RGB colour (multiplies `intensity`).
    pub color: [f32; 3],
    /// W/sr for point and spot lights, W/m^2 for directional lights.
    pub intensity: f32,
    /// Optional cut-off distance (metres) with the specification's smooth window; `None` is pure
    /// inverse-square falloff.
    pub range: Option<f32>,
    /// World-space position (point and spot).
    pub position: Vec3,
    /// World-space unit direction the light travels along (spot and directional).
    pub direction: Vec3,
    /// Whether the light casts shadows (costs one shadow map, six faces for a point light).
    pub cast_shadows: bool,
}

impl Light {
    /// A white point light.
    pub fn point(name: &str, position: Vec3, intensity: f32) -> Self {
        Self {
            name: name.to_owned(),
            kind: LightKind::Point,
            color: [1.0; 3],
            intensity,
            range: None,
            position,
            direction: Vec3::NEG_Y,
            cast_shadows: true,
        }
    }

    /// A white spot light.
    pub fn spot(name: &str, position: Vec3, direction: Vec3, intensity: f32, inner: f32, outer: f32) -> Self {
        Self {
            kind: LightKind::Spot { inner_cone_angle: inner, outer_cone_angle: outer },
            direction: direction.normalize_or(Vec3::NEG_Y),
            ..Self::point(name, position, intensity)
        }
    }

    /// A white directional light.
    pub fn directional(name: &str, direction: Vec3, irradiance: f32) -> Self {
        Self {
            kind: LightKind::Directional,
            direction: direction.normalize_or(Vec3::NEG_Y),
            ..Self::point(name, Vec3::ZERO, irradiance)
        }
    }

    /// `color * intensity`.
    pub fn radiant(&self) -> Vec3 {
        Vec3::from_array(self.color) * self.intensity
    }

    /// Distance attenuation: `1/d^2`, times the specification's window when `range` is set.
    pub fn distance_attenuation(&self, distance: f32) -> f32 {
        let inv_sq = 1.0 / (distance * distance).max(1e-8);
        match self.range {
            Some(range) if range > 0.0 => {
                let r = distance / range;
                (1.0 - r.powi(4)).clamp(0.0, 1.0) * inv_sq
            }
            _ => inv_sq,
        }
    }

    /// Irradiance-producing radiance factor at `point` for a surface: returns the incoming
    /// direction towards the light (unit) and `E / cos` (W/m^2 per unit cosine), without shadows.
    pub fn incident(&self, point: Vec3) -> (Vec3, Vec3) {
        match self.kind {
            LightKind::Directional => (-self.direction, self.radiant()),
            LightKind::Point | LightKind::Spot { .. } => {
                let to_light = self.position - point;
                let d = to_light.length();
                let l = to_light / d.max(1e-8);
                let mut e = self.radiant() * self.distance_attenuation(d);
                if let LightKind::Spot { inner_cone_angle, outer_cone_angle } = self.kind {
                    e *= spot_attenuation(self.direction.dot(-l), inner_cone_angle, outer_cone_angle);
                }
                (l, e)
            }
        }
    }

    /// Checks numbers and ranges.
    pub fn validate(&self) -> Result<(), SceneError> {
        let what = format!("light {:?}", self.name);
        check_finite(&what, &self.color)?;
        check_finite(&what, &[self.intensity, self.range.unwrap_or(1.0)])?;
        check_finite(&what, &self.position.to_array())?;
        check_finite(&what, &self.direction.to_array())?;
        let bad = |why: String| Err(SceneError::BadValue { what: what.clone(), why });
        if self.intensity < 0.0 || self.color.iter().any(|c| *c < 0.0) {
            return bad("colour and intensity must be >= 0".into());
        }
        if self.intensity > super::limits::MAX_INTENSITY {
            return bad(format!("intensity {} is over {}", self.intensity, super::limits::MAX_INTENSITY));
        }
        super::limits::check_position(&what, self.position)?;
        if self.range.is_some_and(|r| r <= 0.0) {
            return bad("range must be > 0".into());
        }
        if !matches!(self.kind, LightKind::Point) && (self.direction.length() - 1.0).abs() > 1e-3 {
            return bad("direction must be a unit vector".into());
        }
        if let LightKind::Spot { inner_cone_angle, outer_cone_angle } = self.kind {
            check_finite(&what, &[inner_cone_angle, outer_cone_angle])?;
            if !(0.0 <= inner_cone_angle
                && inner_cone_angle < outer_cone_angle
                && outer_cone_angle <= std::f32::consts::FRAC_PI_2)
            {
                return bad(format!("need 0 <= inner ({inner_cone_angle}) < outer ({outer_cone_angle}) <= pi/2"));
            }
        }
        Ok(())
    }
}

/// The KHR_lights_punctual spot falloff for `cos_angle` = cos of the angle from the spot axis.
pub fn spot_attenuation(cos_angle: f32, inner: f32, outer: f32) -> f32 {
    let scale = 1.0 / (inner.cos() - outer.cos()).max(0.001);
    let offset = -outer.cos() * scale;
    let a = (cos_angle * scale + offset).clamp(0.0, 1.0);
    a * a
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spot_falloff_edges() {
        assert_eq!(spot_attenuation(1.0, 0.2, 0.5), 1.0);
        assert_eq!(spot_attenuation(0.5f32.cos(), 0.2, 0.5), 0.0);
        let mid = 0.5 * (0.2f32.cos() + 0.5f32.cos());
        assert!((spot_attenuation(mid, 0.2, 0.5) - 0.25).abs() < 1e-5);
    }

    #[test]
    fn inverse_square() {
        let l = Light::point("p", Vec3::new(0.0, 2.0, 0.0), 4.0);
        let (dir, e) = l.incident(Vec3::ZERO);
        assert!((dir - Vec3::Y).length() < 1e-6);
        assert!((e.x - 1.0).abs() < 1e-6);
    }

    #[test]
    fn rejects_bad_cone() {
        let l = Light::spot("s", Vec3::ZERO, Vec3::NEG_Y, 1.0, 0.6, 0.5);
        assert!(l.validate().is_err());
        let mut l = Light::point("p", Vec3::ZERO, 1.0);
        l.intensity = f32::NAN;
        assert!(l.validate().is_err());
    }
}
