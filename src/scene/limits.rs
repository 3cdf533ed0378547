//! Physically meaningful bounds on scene values, beyond "finite": values that pass `is_finite`
//! but still give garbage (an object at 1e20 m makes the raster image black, `base_color` 1e10
//! makes ISM's image all NaN, an intensity of 3.4e38 overflows radiance to inf, a zero
//! quaternion is identity to the rasteriser and black to the path tracer).

use glam::{Quat, Vec3};

use super::SceneError;

/// Largest coordinate (metres): at 1e6 m an f32 step is 6 cm, and clip-space maths still has
/// headroom; beyond it depth and shading lose all precision.
pub const MAX_COORDINATE: f32 = 1e6;
/// Per-axis scale magnitudes outside this range make degenerate or overflowing geometry.
pub const SCALE_RANGE: (f32, f32) = (1e-6, 1e6);
/// Largest light intensity (W/sr for point and spot lights, W/m² for directional ones):
/// ten million times the sun's irradiance, far from where f32 radiance sums overflow.
pub const MAX_INTENSITY: f32 = 1e10;

fn bad(what: &str, why: String) -> Result<(), SceneError> {
    Err(SceneError::BadValue { what: what.to_owned(), why })
}

/// A position within [`MAX_COORDINATE`] of the origin on every axis.
pub fn check_position(what: &str, p: Vec3) -> Result<(), SceneError> {
    if p.abs().max_element() > MAX_COORDINATE {
        return bad(what, format!("position {p} is beyond {MAX_COORDINATE} m, where f32 has no precision left"));
    }
    Ok(())
}

/// A rotation quaternion of length 1 (within 1e-3: normalised data written as text).
pub fn check_rotation(what: &str, q: Quat) -> Result<(), SceneError> {
    let len = q.length();
    if (len - 1.0).abs() > 1e-3 {
        return bad(what, format!("rotation {q} has length {len}; a rotation is a unit quaternion"));
    }
    Ok(())
}

/// Per-axis scale magnitudes within [`SCALE_RANGE`].
pub fn check_scale(what: &str, s: Vec3) -> Result<(), SceneError> {
    let (lo, hi) = SCALE_RANGE;
    if s.to_array().iter().any(|v| !(lo..=hi).contains(&v.abs())) {
        return bad(what, format!("scale {s} has a component outside {lo}..={hi} in magnitude"));
    }
    Ok(())
}

/// Reflectances within 0..=1: a surface reflecting more than it receives creates energy.
pub fn check_reflectance(what: &str, name: &str, values: &[f32]) -> Result<(), SceneError> {
    if values.iter().any(|v| !(0.0..=1.0).contains(v)) {
        return bad(what, format!("{name} {values:?} must be within 0..=1 (energy conservation)"));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn extreme_but_finite_values_are_named() {
        assert!(check_position("object", Vec3::new(0.0, 1e20, 0.0)).is_err());
        assert!(check_position("object", Vec3::splat(1e5)).is_ok());
        let zero = Quat::from_xyzw(0.0, 0.0, 0.0, 0.0);
        let msg = check_rotation("camera", zero).expect_err("zero quaternion").to_string();
        assert!(msg.contains("camera") && msg.contains("unit quaternion"), "{msg}");
        assert!(check_rotation("camera", Quat::from_rotation_y(0.3)).is_ok());
        assert!(check_scale("object", Vec3::new(1.0, 0.0, 1.0)).is_err());
        assert!(check_scale("object", Vec3::new(-1.0, 2.0, 1e-3)).is_ok(), "mirroring is allowed");
        assert!(check_reflectance("material", "base colour", &[1e10, 0.5, 0.5]).is_err());
        assert!(check_reflectance("material", "base colour", &[1.0, 0.0, 0.5]).is_ok());
    }
}
