//! The perspective view camera (glTF conventions: looks down its local -Z, +Y up).

use glam::camera::rh::proj::directx;
use glam::{Mat4, Quat, Vec3};
use serde::{Deserialize, Serialize};

use super::{SceneError, check_finite};

/// A perspective camera. The aspect ratio is always width / height of the output image.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Camera {
    /// World-space position.
    pub position: Vec3,
    /// World-space orientation; the camera looks down its local -Z.
    pub rotation: Quat,
    /// Vertical field of view in radians.
    pub yfov: f32,
    /// Near plane distance (metres).
    pub znear: f32,
    /// Far plane distance (metres); `None` is an infinite far plane.
    pub zfar: Option<f32>,
}

impl Default for Camera {
    fn default() -> Self {
        Self { position: Vec3::new(0.0, 1.0, 4.0), rotation: Quat::IDENTITY, yfov: 0.8, znear: 0.05, zfar: None }
    }
}

impl Camera {
    /// A camera at `eye` looking at `target` with +Y up.
    pub fn look_at(eye: Vec3, target: Vec3, yfov: f32) -> Self {
        let forward = (target - eye).normalize_or(Vec3::NEG_Z);
        let rotation = rotation_looking(forward);
        Self { position: eye, rotation, yfov, ..Self::default() }
    }

    /// World-from-camera matrix.
    pub fn world_from_view(&self) -> Mat4 {
        Mat4::from_rotation_translation(self.rotation, self.position)
    }

    /// Camera-from-world matrix.
    pub fn view_from_world(&self) -> Mat4 {
        self.world_from_view().inverse()
    }

    /// Clip-from-camera matrix for the given aspect ratio, with reversed depth (near = 1,
    /// far = 0): float depth then keeps metre-scale precision at any distance, so positions
    /// reconstructed from depth stay exact even with a tiny near plane.
    pub fn clip_from_view(&self, aspect: f32) -> Mat4 {
        match self.zfar {
            Some(far) => directx::perspective(self.yfov, aspect, far, self.znear),
            None => directx::perspective_infinite_reverse(self.yfov, aspect, self.znear),
        }
    }

    /// The unit forward direction (local -Z in world space).
    pub fn forward(&self) -> Vec3 {
        self.rotation * Vec3::NEG_Z
    }

    /// The world-space direction through the pixel centre `(x + 0.5, y + 0.5)` of a `width` x
    /// `height` image, rows from the top. This is the rasteriser's sampling convention.
    pub fn ray_direction(&self, x: f32, y: f32, width: u32, height: u32) -> Vec3 {
        let aspect = width as f32 / height.max(1) as f32;
        let t = (0.5 * self.yfov).tan();
        let ndc_x = (x / width.max(1) as f32) * 2.0 - 1.0;
        let ndc_y = 1.0 - (y / height.max(1) as f32) * 2.0;
        let local = Vec3::new(ndc_x * t * aspect, ndc_y * t, -1.0);
        (self.rotation * local).normalize()
    }

    /// Checks numbers and ranges.
    pub fn validate(&self) -> Result<(), SceneError> {
        check_finite("camera position", &self.position.to_array())?;
        check_finite("camera rotation", &self.rotation.to_array())?;
        check_finite("camera field of view", &[self.yfov, self.znear, self.zfar.unwrap_or(1.0)])?;
        super::limits::check_position("camera", self.position)?;
        super::limits::check_rotation("camera", self.rotation)?;
        if !(self.yfov > 1e-3 && self.yfov < std::f32::consts::PI - 1e-3) {
            return Err(SceneError::BadValue {
                what: "camera yfov".into(),
                why: format!("{} rad is outside (0, pi)", self.yfov),
            });
        }
        if self.znear <= 0.0 || self.zfar.is_some_and(|f| f <= self.znear) {
            return Err(SceneError::BadValue {
                what: "camera clip planes".into(),
                why: format!("need 0 < znear < zfar, got {} and {:?}", self.znear, self.zfar),
            });
        }
        Ok(())
    }
}

/// The rotation that maps local -Z to `forward` while keeping +Y as close to up as possible.
pub fn rotation_looking(forward: Vec3) -> Quat {
    let f = forward.normalize_or(Vec3::NEG_Z);
    let up = if f.y.abs() > 0.999 { Vec3::Z } else { Vec3::Y };
    let right = f.cross(up).normalize();
    let true_up = right.cross(f);
    Quat::from_mat3(&glam::Mat3::from_cols(right, true_up, -f)).normalize()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn centre_ray_is_forward() {
        let cam = Camera::look_at(Vec3::new(1.0, 2.0, 3.0), Vec3::ZERO, 0.7);
        let d = cam.ray_direction(32.0, 16.0, 64, 32);
        assert!((d - cam.forward()).length() < 1e-5);
        assert!((cam.forward() - (-Vec3::new(1.0, 2.0, 3.0)).normalize()).length() < 1e-5);
    }

    #[test]
    fn depth_is_reversed() {
        for zfar in [Some(100.0), None] {
            let cam = Camera { zfar, ..Camera::default() };
            let m = cam.clip_from_view(1.5);
            let depth = |z: f32| {
                let c = m * glam::Vec4::new(0.0, 0.0, -z, 1.0);
                c.z / c.w
            };
            assert!((depth(cam.znear) - 1.0).abs() < 1e-5 && depth(50.0) < depth(1.0) && depth(50.0) > 0.0);
        }
    }

    #[test]
    fn top_row_ray_is_at_half_fov() {
        let cam = Camera { yfov: 1.0, ..Camera::default() };
        let d = cam.ray_direction(8.0, 0.0, 16, 16);
        assert!((d.y.atan2(-d.z) - 0.5).abs() < 1e-5);
    }
}
