//! Orbit / pan / zoom camera control: the state the viewport keeps between frames and how mouse
//! input changes it. Pure math (no egui), unit-tested.

use glam::{Quat, Vec3};

use crate::scene::Camera;

/// An orbit controller around a target point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Orbit {
    /// The point orbited around.
    pub target: Vec3,
    /// Distance from the target.
    pub distance: f32,
    /// Rotation about +Y (radians).
    pub yaw: f32,
    /// Elevation (radians), clamped short of the poles.
    pub pitch: f32,
}

const PITCH_LIMIT: f32 = 1.55;

impl Orbit {
    /// The controller that reproduces `camera`, orbiting the point `distance` ahead of it.
    pub fn from_camera(camera: &Camera, distance: f32) -> Self {
        let f = camera.forward();
        let distance = distance.max(1e-3);
        Self {
            target: camera.position + f * distance,
            distance,
            yaw: (-f.x).atan2(-f.z),
            pitch: f.y.clamp(-1.0, 1.0).asin().clamp(-PITCH_LIMIT, PITCH_LIMIT),
        }
    }

    /// The camera orientation.
    pub fn rotation(&self) -> Quat {
        Quat::from_rotation_y(self.yaw) * Quat::from_rotation_x(self.pitch)
    }

    /// Writes position and orientation into `camera` (lens settings are kept).
    pub fn apply(&self, camera: &mut Camera) {
        camera.rotation = self.rotation();
        camera.position = self.target - camera.rotation * Vec3::NEG_Z * self.distance;
    }

    /// Rotates by a mouse drag of `(dx, dy)` pixels.
    pub fn rotate(&mut self, dx: f32, dy: f32) {
        self.yaw -= dx * 0.008;
        self.pitch = (self.pitch - dy * 0.008).clamp(-PITCH_LIMIT, PITCH_LIMIT);
    }

    /// Pans the target in the view plane by `(dx, dy)` pixels of a `height`-pixel view.
    pub fn pan(&mut self, dx: f32, dy: f32, height: f32, yfov: f32) {
        let per_pixel = 2.0 * self.distance * (0.5 * yfov).tan() / height.max(1.0);
        let r = self.rotation();
        self.target += (r * Vec3::NEG_X * dx + r * Vec3::Y * dy) * per_pixel;
    }

    /// Zooms by scroll `amount` (positive = closer).
    pub fn zoom(&mut self, amount: f32) {
        self.distance = (self.distance * (-amount * 0.002).exp()).clamp(1e-3, 1e5);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trips_a_camera() {
        let cam = Camera::look_at(Vec3::new(1.0, 2.0, 5.0), Vec3::new(0.0, 1.0, 0.0), 0.7);
        let orbit = Orbit::from_camera(&cam, 3.0);
        let mut out = cam;
        orbit.apply(&mut out);
        assert!((out.position - cam.position).length() < 1e-4);
        assert!((out.forward() - cam.forward()).length() < 1e-4);
    }

    #[test]
    fn rotation_keeps_distance_and_zoom_moves_closer() {
        let mut orbit = Orbit { target: Vec3::ZERO, distance: 2.0, yaw: 0.0, pitch: 0.0 };
        orbit.rotate(100.0, 50.0);
        let mut cam = Camera::default();
        orbit.apply(&mut cam);
        assert!((cam.position.length() - 2.0).abs() < 1e-4);
        orbit.zoom(100.0);
        assert!(orbit.distance < 2.0);
        orbit.rotate(0.0, 1e6);
        assert!(orbit.pitch <= PITCH_LIMIT);
    }
}
