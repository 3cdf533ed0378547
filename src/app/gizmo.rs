//! The transform gizmo's math: projecting handles, picking them, and turning mouse rays into
//! translations along an axis and rotations about it, with snapping. Pure glam (no egui), so
//! the ray math is unit-tested; `viewport.rs` draws and drives it. (No published gizmo crate
//! supports egui 0.37 on our toolchain.)

use glam::{Mat4, Quat, Vec2, Vec3};

use crate::scene::Camera;

/// Gizmo operation.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum GizmoMode {
    /// Move along an axis.
    #[default]
    Translate,
    /// Rotate about an axis.
    Rotate,
    /// Scale along an axis (objects only).
    Scale,
}

/// A camera looking at a viewport of `size` (any units, e.g. egui points).
#[derive(Clone, Copy, Debug)]
pub struct View {
    pub camera: Camera,
    pub size: Vec2,
}

impl View {
    fn clip_from_world(&self) -> Mat4 {
        self.camera.clip_from_view(self.size.x / self.size.y.max(1e-6)) * self.camera.view_from_world()
    }

    /// Screen position (origin top-left) of a world point, `None` behind the camera.
    pub fn project(&self, p: Vec3) -> Option<Vec2> {
        let c = self.clip_from_world() * p.extend(1.0);
        if c.w <= 1e-6 {
            return None;
        }
        let ndc = c.truncate() / c.w;
        Some(Vec2::new((ndc.x + 1.0) * 0.5 * self.size.x, (1.0 - ndc.y) * 0.5 * self.size.y))
    }

    /// The world ray (origin, unit direction) through a screen position.
    pub fn ray(&self, s: Vec2) -> (Vec3, Vec3) {
        let aspect = self.size.x / self.size.y.max(1e-6);
        let t = (0.5 * self.camera.yfov).tan();
        let local = Vec3::new((s.x / self.size.x * 2.0 - 1.0) * t * aspect, (1.0 - s.y / self.size.y * 2.0) * t, -1.0);
        (self.camera.position, (self.camera.rotation * local).normalize())
    }

    /// World length that appears about `pixels` long at `p`.
    pub fn world_size(&self, p: Vec3, pixels: f32) -> f32 {
        let dist = (p - self.camera.position).dot(self.camera.forward()).max(1e-3);
        pixels * 2.0 * dist * (0.5 * self.camera.yfov).tan() / self.size.y.max(1.0)
    }
}

/// Parameter along the line `p + t u` of the point closest to the ray `o + s d`.
pub fn closest_on_line(o: Vec3, d: Vec3, p: Vec3, u: Vec3) -> Option<f32> {
    let w0 = o - p;
    let (a, b, c) = (d.dot(d), d.dot(u), u.dot(u));
    let (dd, e) = (d.dot(w0), u.dot(w0));
    let denom = a * c - b * b;
    (denom.abs() > 1e-9).then(|| (a * e - b * dd) / denom)
}

/// Where the ray `o + s d` meets the plane through `p` with normal `n`.
pub fn ray_plane(o: Vec3, d: Vec3, p: Vec3, n: Vec3) -> Option<Vec3> {
    let denom = d.dot(n);
    if denom.abs() < 1e-9 {
        return None;
    }
    let s = (p - o).dot(n) / denom;
    (s > 0.0).then(|| o + d * s)
}

/// Distance from point `q` to the segment `a`-`b` (screen space).
pub fn segment_distance(q: Vec2, a: Vec2, b: Vec2) -> f32 {
    let ab = b - a;
    let t = ((q - a).dot(ab) / ab.length_squared().max(1e-9)).clamp(0.0, 1.0);
    (a + ab * t).distance(q)
}

/// Rounds `v` to a multiple of `step` (no snapping when `step` <= 0).
pub fn snap(v: f32, step: f32) -> f32 {
    if step > 0.0 { (v / step).round() * step } else { v }
}

/// The three axes, world or local to `rotation`.
pub fn axes(rotation: Quat, local: bool) -> [Vec3; 3] {
    if local { [rotation * Vec3::X, rotation * Vec3::Y, rotation * Vec3::Z] } else { [Vec3::X, Vec3::Y, Vec3::Z] }
}

/// An active drag.
#[derive(Clone, Copy, Debug)]
pub struct Drag {
    pub mode: GizmoMode,
    pub axis: Vec3,
    pub origin: Vec3,
    pub start_rotation: Quat,
    /// The object's scale when the drag started (set by the caller for scale drags).
    pub start_scale: Vec3,
    /// Translate and scale: the line parameter at the start; rotate: the start angle.
    pub start: f32,
}

fn angle_about(axis: Vec3, origin: Vec3, hit: Vec3) -> f32 {
    let (t, b) = crate::scene::basis::basis(axis.normalize());
    let v = hit - origin;
    v.dot(b).atan2(v.dot(t))
}

impl Drag {
    /// Starts a drag of `axis` at the screen position `s`.
    pub fn begin(view: &View, mode: GizmoMode, axis: Vec3, origin: Vec3, rotation: Quat, s: Vec2) -> Option<Self> {
        let (o, d) = view.ray(s);
        let start = match mode {
            GizmoMode::Translate | GizmoMode::Scale => closest_on_line(o, d, origin, axis)?,
            GizmoMode::Rotate => angle_about(axis, origin, ray_plane(o, d, origin, axis)?),
        };
        Some(Self { mode, axis, origin, start_rotation: rotation, start_scale: Vec3::ONE, start })
    }

    /// The translation offset (translate) for the current screen position, snapped.
    pub fn translation(&self, view: &View, s: Vec2, step: f32) -> Option<Vec3> {
        let (o, d) = view.ray(s);
        let t = closest_on_line(o, d, self.origin, self.axis)?;
        Some(self.axis * snap(t - self.start, step))
    }

    /// The scale factor along the axis (scale): dragging the handle end `handle` metres away
    /// from the origin doubles the size; snapped to `step` (e.g. 0.1 = 10% steps).
    pub fn scale_factor(&self, view: &View, s: Vec2, handle: f32, step: f32) -> Option<f32> {
        let (o, d) = view.ray(s);
        let t = closest_on_line(o, d, self.origin, self.axis)?;
        Some(snap(1.0 + (t - self.start) / handle.max(1e-6), step).max(0.01))
    }

    /// The new rotation (rotate) for the current screen position, snapped to `step_deg`.
    pub fn rotation(&self, view: &View, s: Vec2, step_deg: f32) -> Option<Quat> {
        let (o, d) = view.ray(s);
        let a = angle_about(self.axis, self.origin, ray_plane(o, d, self.origin, self.axis)?);
        let delta = snap((a - self.start).to_degrees(), step_deg).to_radians();
        Some((Quat::from_axis_angle(self.axis.normalize(), delta) * self.start_rotation).normalize())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn view() -> View {
        View {
            camera: Camera::look_at(Vec3::new(0.0, 1.0, 5.0), Vec3::new(0.0, 1.0, 0.0), 0.8),
            size: Vec2::new(800.0, 600.0),
        }
    }

    #[test]
    fn project_and_ray_are_inverse() {
        let v = view();
        let p = Vec3::new(0.4, 1.3, -0.5);
        let s = v.project(p).expect("in front");
        let (o, d) = v.ray(s);
        let closest = o + d * (p - o).dot(d);
        assert!(closest.distance(p) < 1e-3, "ray through the projection passes the point");
        assert!((v.project(Vec3::new(0.0, 1.0, 0.0)).expect("centre") - Vec2::new(400.0, 300.0)).length() < 1e-3);
    }

    #[test]
    fn translate_follows_the_mouse_along_the_axis() {
        let v = view();
        let origin = Vec3::new(0.0, 1.0, 0.0);
        let start = v.project(origin).expect("visible");
        let drag = Drag::begin(&v, GizmoMode::Translate, Vec3::X, origin, Quat::IDENTITY, start).expect("drag");
        let target = v.project(origin + Vec3::X * 0.7).expect("visible");
        let t = drag.translation(&v, target, 0.0).expect("moves");
        assert!((t - Vec3::X * 0.7).length() < 1e-3, "{t}");
        let snapped = drag.translation(&v, target, 0.25).expect("moves");
        assert!((snapped.x - 0.75).abs() < 1e-5);
        // Moving the mouse vertically does not move along X.
        let up = drag.translation(&v, start + Vec2::new(0.0, -50.0), 0.0).expect("moves");
        assert!(up.length() < 1e-3);
    }

    #[test]
    fn rotate_about_y_by_a_quarter_turn() {
        let v =
            View { camera: Camera::look_at(Vec3::new(0.0, 5.0, 0.01), Vec3::ZERO, 0.8), size: Vec2::new(600.0, 600.0) };
        let a = v.project(Vec3::new(1.0, 0.0, 0.0)).expect("visible");
        let b = v.project(Vec3::new(0.0, 0.0, -1.0)).expect("visible");
        let drag = Drag::begin(&v, GizmoMode::Rotate, Vec3::Y, Vec3::ZERO, Quat::IDENTITY, a).expect("drag");
        let q = drag.rotation(&v, b, 0.0).expect("rotates");
        assert!((q * Vec3::X - Vec3::new(0.0, 0.0, -1.0)).length() < 1e-3, "{}", q * Vec3::X);
        let snapped = drag.rotation(&v, b, 15.0).expect("rotates");
        assert!((snapped * Vec3::X - Vec3::new(0.0, 0.0, -1.0)).length() < 1e-3);
    }

    #[test]
    fn scale_doubles_at_one_handle_length() {
        let v = view();
        let origin = Vec3::new(0.0, 1.0, 0.0);
        let start = v.project(origin + Vec3::X * 0.5).expect("visible");
        let drag = Drag::begin(&v, GizmoMode::Scale, Vec3::X, origin, Quat::IDENTITY, start).expect("drag");
        let end = v.project(origin + Vec3::X * 1.0).expect("visible");
        let f = drag.scale_factor(&v, end, 0.5, 0.0).expect("scales");
        assert!((f - 2.0).abs() < 1e-3, "{f}");
        assert!(
            drag.scale_factor(&v, v.project(origin - Vec3::X * 2.0).expect("visible"), 0.5, 0.0).expect("scales")
                >= 0.01
        );
    }

    #[test]
    fn segment_distance_and_parallel_rays() {
        assert!((segment_distance(Vec2::new(5.0, 3.0), Vec2::ZERO, Vec2::new(10.0, 0.0)) - 3.0).abs() < 1e-6);
        assert!(closest_on_line(Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::X).is_none());
        assert!(ray_plane(Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Y).is_none());
    }
}
