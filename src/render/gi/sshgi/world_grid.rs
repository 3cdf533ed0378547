//! `sshgi`'s world grid: the scene's surface voxels ([`SurfaceVoxels`]) on the GPU, for the part
//! of a hidden sender's segment that leaves the view, where the view's voxel columns say nothing,
//! and for a segment in view where its voxels are finer than the columns
//! (`world_grid_in_view`; `sshgi_world_grid.wgsl`). Built on the CPU when the geometry changes
//! (meshes, transforms, what is rendered), never for a light or camera edit; up to
//! `world_voxels` voxels along the scene's longest side.

use crate::precompute::surface_voxels::SurfaceVoxels;
use crate::scene::Scene;

/// What the grid was built from.
#[derive(Clone, PartialEq)]
struct GeometryKey {
    resources: u64,
    along: u32,
    objects: Vec<(usize, [f32; 16], bool)>,
}

impl GeometryKey {
    fn of(scene: &Scene, along: u32) -> Self {
        Self {
            resources: scene.resources_revision(),
            along,
            objects: scene
                .objects()
                .iter()
                .map(|o| (o.mesh, o.transform.matrix().to_cols_array(), o.is_rendered()))
                .collect(),
        }
    }
}

/// The grid's buffer and its parameters (`world` and `world_dims` in `PanoramaParams`).
#[derive(Clone, Copy)]
pub struct WorldGridRef<'a> {
    pub buffer: &'a wgpu::Buffer,
    /// Origin xyz, voxel side (m).
    pub world: [f32; 4],
    /// Voxels along x, y, z; the bricks' first word.
    pub dims: [u32; 4],
}

/// The uploaded grid.
struct Uploaded {
    buffer: wgpu::Buffer,
    world: [f32; 4],
    dims: [u32; 4],
}

/// The world grid of the scene, rebuilt when its geometry changes.
#[derive(Default)]
pub struct WorldGrid {
    built: Option<(GeometryKey, Option<Uploaded>)>,
    /// The previous frame's geometry.
    last: Option<GeometryKey>,
}

/// Whether to rebuild for geometry `key`: there is no grid yet, or another resolution, or the
/// geometry changed and has stood still for a frame since (`last`). While an object is dragged
/// the grid keeps its last shape (segments in view that walk it shadow with it too): a build
/// takes tens to hundreds of milliseconds on a level (at 512 voxels, release build, two cores:
/// the suite's rooms 90 ms, the cluttered room 274 ms), too long to pay every frame.
fn should_build(built: Option<&GeometryKey>, last: Option<&GeometryKey>, key: &GeometryKey) -> bool {
    match built {
        None => true,
        Some(b) if b.along != key.along => true,
        Some(b) => b != key && last == Some(key),
    }
}

impl WorldGrid {
    /// The grid of `scene` at `along` voxels on its longest side (0: none), rebuilt and uploaded
    /// when the geometry or `along` changed ([`should_build`]); `None` for none or a scene without
    /// triangles.
    pub fn update(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        scene: &Scene,
        along: u32,
    ) -> Option<WorldGridRef<'_>> {
        if along == 0 {
            self.release();
            return None;
        }
        let key = GeometryKey::of(scene, along);
        if should_build(self.built.as_ref().map(|(k, _)| k), self.last.as_ref(), &key) {
            let uploaded = SurfaceVoxels::of_scene(scene, along).map(|grid| upload(device, queue, &grid));
            self.built = Some((key.clone(), uploaded));
        }
        self.last = Some(key);
        let (_, Some(u)) = self.built.as_ref()? else { return None };
        Some(WorldGridRef { buffer: &u.buffer, world: u.world, dims: u.dims })
    }

    /// Frees the grid.
    pub fn release(&mut self) {
        self.built = None;
        self.last = None;
    }

    /// Bytes of the grid's buffer.
    pub fn gpu_bytes(&self) -> u64 {
        match &self.built {
            Some((_, Some(u))) => u.buffer.size(),
            _ => 0,
        }
    }
}

/// The grid's bits in a storage buffer, with its parameters.
fn upload(device: &wgpu::Device, queue: &wgpu::Queue, grid: &SurfaceVoxels) -> Uploaded {
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("sshgi world grid"),
        size: (grid.bytes() as u64).max(4),
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    queue.write_buffer(&buffer, 0, bytemuck::cast_slice(&grid.words));
    Uploaded {
        buffer,
        world: grid.origin.extend(grid.h).to_array(),
        dims: [grid.dims.x, grid.dims.y, grid.dims.z, grid.bricks_at as u32],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn key(along: u32, x: f32) -> GeometryKey {
        let mut m = [0.0; 16];
        m[12] = x;
        GeometryKey { resources: 1, along, objects: vec![(0, m, true)] }
    }

    #[test]
    fn the_grid_is_built_at_once_and_rebuilt_when_a_moved_object_stands_still() {
        // No grid yet, or another resolution: at once.
        assert!(should_build(None, None, &key(256, 0.0)));
        assert!(should_build(Some(&key(128, 0.0)), Some(&key(256, 0.0)), &key(256, 0.0)));
        // Unchanged: never.
        assert!(!should_build(Some(&key(256, 0.0)), Some(&key(256, 0.0)), &key(256, 0.0)));
        // Dragged (another place each frame): not yet; stood still for a frame: now.
        assert!(!should_build(Some(&key(256, 0.0)), Some(&key(256, 1.0)), &key(256, 2.0)));
        assert!(should_build(Some(&key(256, 0.0)), Some(&key(256, 2.0)), &key(256, 2.0)));
    }
}
