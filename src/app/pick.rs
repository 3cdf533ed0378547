//! Picking by a ray through the full-resolution pixel against the scene's triangles (the
//! path tracer's BVH): exact whatever scale the viewport renders at, and it never waits for
//! the GPU, which may be busy with a frame for seconds on a software adapter.

use crate::precompute::bvh::SceneBvh;
use crate::scene::{Object, Scene};

/// The BVH of the last pick and what it was built from.
#[derive(Default)]
pub struct Picker {
    cached: Option<(u64, Vec<Object>, SceneBvh)>,
}

impl Picker {
    /// The object under pixel `(x, y)` (physical pixels, rows from the top) of a `size` view.
    /// Rebuilds the BVH only when objects or meshes changed since the last pick.
    pub fn pick(&mut self, scene: &Scene, x: f32, y: f32, size: (u32, u32)) -> Option<usize> {
        let fresh = self.cached.as_ref().is_some_and(|(rev, objects, _)| {
            *rev == scene.resources_revision() && objects.as_slice() == scene.objects()
        });
        if !fresh {
            self.cached = Some((scene.resources_revision(), scene.objects().to_vec(), SceneBvh::build(scene)));
        }
        let (_, _, bvh) = self.cached.as_ref()?;
        let camera = scene.camera();
        let dir = camera.ray_direction(x, y, size.0, size.1);
        let hit = bvh.intersect(camera.position, dir, f32::INFINITY)?;
        bvh.tris.get(hit.tri as usize).map(|t| t.object as usize)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn picks_something_at_the_centre_and_nothing_when_looking_away() {
        let project =
            crate::project_file::Project::load(&crate::project_file::default_project_path()).expect("default project");
        let scene = &project.scene;
        let mut picker = Picker::default();
        let size = (320, 180);
        let centre = picker.pick(scene, 160.0, 90.0, size).expect("something at the centre");
        assert!(centre < scene.objects().len());
        // A camera looking away from everything picks nothing.
        let mut away = project.scene.clone();
        let mut c = *away.camera();
        c.position += glam::Vec3::Y * 1000.0;
        c.rotation = glam::Quat::from_rotation_x(std::f32::consts::FRAC_PI_2);
        away.set_camera(c);
        assert_eq!(picker.pick(&away, 160.0, 90.0, size), None);
    }
}
