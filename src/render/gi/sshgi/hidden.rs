//! `sshgi`'s hidden senders: the surfaces neither the screen nor the panorama shows, because
//! something nearer hides them from the camera's position (the back of a pillar, a box's far
//! side, the floor behind it). Soler et al. 2010 gather the screen alone; the panorama
//! ([`super::panorama`]) adds what lies around the camera; this adds the rest from a world-space
//! set of points spread over every surface by area (`precompute::sample_points`, the ISM's
//! stratified distribution): `BLOCKS` blocks, each a stratified sample of the whole scene, one
//! block a frame, so the temporal filter averages several point sets.
//!
//! Each frame `sshgi_hidden_pack.wgsl` tests this frame's block against what the camera sees (a
//! point it sees is left to the screen and the panorama): a point inside the view's frustum
//! against the view's own distances (the depth/normal pyramid's level 0, at the view's
//! resolution), one outside it against the panorama's; lights the hidden points with
//! the view's lights and shadow maps (as diffuse senders: a glossy lobe's share of the light too,
//! spread over the hemisphere) and their emission, and writes them after the
//! panorama's senders into its list: the gathers and receives then treat them as senders like
//! the panorama's, with one difference, visibility: their segments are marched through the view's
//! voxels, and where a segment leaves the view through the world grid of surface voxels
//! ([`super::world_grid`]; without it such a segment counts as blocked): the back of a pillar
//! lights the floor beside it, not the room behind the wall it stands against, nor a room
//! through a wall behind the camera.

use bytemuck::{Pod, Zeroable};
use glam::{Mat4, Vec2, Vec3};

use crate::precompute::sample_points::{SamplePoints, distribute};
use crate::render::gi::inputs::GiInputs;
use crate::render::layouts::{compute_pipeline_with, storage_entry, storage_rw_entry, texture_entry, uniform_entry};
use crate::render::lighting::{LightingInputs, LightingPass};
use crate::render::shaders::{self, ShaderError};
use crate::scene::Scene;

/// Point sets the points are drawn in; frame n packs set n mod `BLOCKS`.
pub const BLOCKS: u32 = 8;

/// Relative distance by which a point must lie behind every view pixel (or panorama texel)
/// around its direction to count as hidden.
const TOLERANCE: f32 = 0.02;

/// One point of the scene (`Surfel` in `sshgi_hidden_pack.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct GpuSurfel {
    /// The world point, the area it stands for (m^2; 0: none).
    pub point: [f32; 4],
    /// Geometric (front) normal, unused.
    pub normal: [f32; 4],
    /// Albedo at the point (factor x texture), unused.
    pub albedo: [f32; 4],
    /// Emitted radiance (W / (sr m^2)), unused.
    pub emission: [f32; 4],
    /// Specular colour (zero: no glossy lobe), roughness.
    pub specular: [f32; 4],
}

/// `HiddenParams` in `sshgi_hidden_pack.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct HiddenParams {
    /// Each panorama face's clip_from_world.
    pub faces: [[[f32; 4]; 4]; 6],
    /// Points this frame, this frame's first point, the list index of the first hidden sender,
    /// the face size F.
    pub counts: [u32; 4],
    /// Relative depth tolerance, unused x3.
    pub tolerance: [f32; 4],
}

const _: () = assert!(std::mem::size_of::<GpuSurfel>() == 80);
const _: () = assert!(std::mem::size_of::<HiddenParams>() == 416);

/// What a distribution of points was made from (as the ISM's: geometry, weights, scale).
#[derive(PartialEq)]
struct PointsKey {
    resources: u64,
    per_frame: u32,
    objects: Vec<(f32, bool, [f32; 3])>,
}

/// The panorama's side of the pack: its distances, sender list and first radiance, the faces'
/// matrices and size, and the lighting inputs' bind group with the view's frame.
pub struct PanoramaLists<'a> {
    pub distances: &'a wgpu::Buffer,
    pub senders: &'a wgpu::Buffer,
    pub radiance: &'a wgpu::Buffer,
    pub faces: [Mat4; 6],
    pub face: u32,
}

/// The buffers the pack's bind group names: rebuilt when one of them is another object.
#[derive(PartialEq)]
struct GroupKey {
    surfels: wgpu::Buffer,
    distances: wgpu::Buffer,
    senders: wgpu::Buffer,
    radiance: wgpu::Buffer,
    frame: wgpu::Buffer,
    lights: wgpu::Buffer,
    shadow_views: wgpu::Buffer,
    shadow_maps: wgpu::TextureView,
    view_geometry: wgpu::TextureView,
}

/// The hidden senders' pass and point set.
pub struct HiddenSenders {
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::ComputePipeline,
    params: wgpu::Buffer,
    points: Option<(PointsKey, SamplePoints)>,
    /// The points in the world, for the scene revision they were placed at.
    surfels: Option<(u64, wgpu::Buffer)>,
    groups: Option<(GroupKey, [wgpu::BindGroup; 2])>,
}

impl HiddenSenders {
    /// Creates the pipeline (group 1 is the lighting pass's inputs).
    pub fn new(device: &wgpu::Device, lighting: &LightingPass) -> Result<Self, ShaderError> {
        let c = wgpu::ShaderStages::COMPUTE;
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("sshgi hidden pack layout"),
            entries: &[
                uniform_entry(0, c, false),
                storage_entry(1, c),
                storage_entry(2, c),
                storage_rw_entry(3),
                storage_rw_entry(4),
                texture_entry(5, c, wgpu::TextureSampleType::Float { filterable: false }),
            ],
        });
        let module = shaders::module(device, "render/gi/sshgi/sshgi_hidden_pack.wgsl")?;
        let pipeline =
            compute_pipeline_with(device, "sshgi hidden pack", &[&layout, lighting.inputs_layout()], &module, "pack");
        let params = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("sshgi hidden pack params"),
            size: std::mem::size_of::<HiddenParams>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        Ok(Self { layout, pipeline, params, points: None, surfels: None, groups: None })
    }

    /// Packs this frame's `per_frame` points after the panorama's senders.
    pub fn record(
        &mut self,
        inputs: &mut GiInputs<'_>,
        per_frame: u32,
        lighting: &LightingPass,
        sky: &crate::render::sky::SkyGpu,
        lists: &PanoramaLists<'_>,
    ) {
        self.update(inputs.device, inputs.queue, inputs.scene, per_frame);
        let Some((_, surfels)) = &self.surfels else { return };
        // What the view sees at its own resolution (sshgi always builds the pyramid).
        let Some(view_geometry) = inputs.pyramid.as_ref().and_then(|p| p.levels.first()) else { return };
        let key = GroupKey {
            surfels: surfels.clone(),
            distances: lists.distances.clone(),
            senders: lists.senders.clone(),
            radiance: lists.radiance.clone(),
            frame: inputs.frame_buffer.clone(),
            lights: inputs.lights.buffer.clone(),
            shadow_views: inputs.lights.shadow_views.clone(),
            shadow_maps: inputs.lights.shadow_maps.clone(),
            view_geometry: view_geometry.view.clone(),
        };
        if self.groups.as_ref().is_none_or(|(k, _)| *k != key) {
            let groups = self.bind_groups(inputs.device, &key, lighting, sky);
            self.groups = Some((key, groups));
        }
        let block = inputs.frame_index % BLOCKS;
        let params = HiddenParams {
            faces: lists.faces.map(|m| m.to_cols_array_2d()),
            counts: [per_frame, block * per_frame, 6 * lists.face * lists.face, lists.face],
            tolerance: [TOLERANCE, 0.0, 0.0, 0.0],
        };
        inputs.queue.write_buffer(&self.params, 0, bytemuck::bytes_of(&params));
        let Some((_, [own, lights])) = &self.groups else { return };
        let mut pass = inputs.compute_pass("sshgi hidden pack");
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, own, &[]);
        pass.set_bind_group(1, lights, &[]);
        pass.dispatch_workgroups(per_frame.div_ceil(64), 1, 1);
    }

    /// The pack's own bind group and the lighting inputs' with the view's frame.
    fn bind_groups(
        &self,
        device: &wgpu::Device,
        key: &GroupKey,
        lighting: &LightingPass,
        sky: &crate::render::sky::SkyGpu,
    ) -> [wgpu::BindGroup; 2] {
        fn buffer(binding: u32, b: &wgpu::Buffer) -> wgpu::BindGroupEntry<'_> {
            wgpu::BindGroupEntry { binding, resource: b.as_entire_binding() }
        }
        let own = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("sshgi hidden pack bind group"),
            layout: &self.layout,
            entries: &[
                buffer(0, &self.params),
                buffer(1, &key.surfels),
                buffer(2, &key.distances),
                buffer(3, &key.senders),
                buffer(4, &key.radiance),
                wgpu::BindGroupEntry { binding: 5, resource: wgpu::BindingResource::TextureView(&key.view_geometry) },
            ],
        });
        let lights = lighting.inputs_bind_group(
            device,
            &LightingInputs {
                frame: &key.frame,
                lights: &key.lights,
                shadow_views: &key.shadow_views,
                shadow_maps: &key.shadow_maps,
                sky,
            },
        );
        [own, lights]
    }

    /// Draws the points when the geometry, weights or count changed, and places them in the
    /// world (with their albedo, glossy lobe and emission) when the scene changed.
    fn update(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, scene: &Scene, per_frame: u32) {
        let key = PointsKey {
            resources: scene.resources_revision(),
            per_frame,
            objects: scene
                .objects()
                .iter()
                .map(|o| (o.sampling_weight, o.is_rendered(), o.transform.scale.to_array()))
                .collect(),
        };
        if self.points.as_ref().is_none_or(|(k, _)| *k != key) {
            let total = (per_frame * BLOCKS) as usize;
            self.points = Some((key, distribute(scene, total, BLOCKS as usize, 7)));
            self.surfels = None;
        }
        let Some((_, points)) = &self.points else { return };
        if self.surfels.as_ref().is_some_and(|(revision, _)| *revision == scene.revision()) {
            return;
        }
        let mut records = surfels(scene, points);
        // Every block is `per_frame` long; a scene with no surfaces has none (zero areas).
        records.resize((per_frame * BLOCKS) as usize, GpuSurfel::default());
        let bytes: &[u8] = bytemuck::cast_slice(&records);
        match &self.surfels {
            Some((_, buffer)) if buffer.size() == bytes.len() as u64 => queue.write_buffer(buffer, 0, bytes),
            _ => {
                use wgpu::util::DeviceExt as _;
                let buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("sshgi hidden surfels"),
                    contents: bytes,
                    usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                });
                self.groups = None;
                self.surfels = Some((scene.revision(), buffer));
                return;
            }
        }
        if let Some((revision, _)) = &mut self.surfels {
            *revision = scene.revision();
        }
    }

    /// Frees the points and buffers.
    pub fn release(&mut self) {
        self.points = None;
        self.surfels = None;
        self.groups = None;
    }

    /// Bytes of the points' buffer.
    pub fn gpu_bytes(&self) -> u64 {
        self.surfels.as_ref().map_or(0, |(_, b)| b.size())
    }
}

/// Each point in the world with the area it stands for (its object's sampled area over its
/// points, over the blocks: each block covers the scene once), its albedo, glossy lobe and
/// emission.
pub fn surfels(scene: &Scene, points: &SamplePoints) -> Vec<GpuSurfel> {
    let objects = scene.objects();
    let counts = points.counts(objects.len());
    let images = &scene.resources().images;
    points
        .points
        .iter()
        .map(|p| {
            let o = p.object as usize;
            let Some(object) = objects.get(o) else { return GpuSurfel::default() };
            let Some(mesh) = scene.resources().meshes.get(object.mesh) else { return GpuSurfel::default() };
            let t = p.triangle as usize;
            if t >= mesh.triangle_count() || object.sampling_weight <= 0.0 {
                return GpuSurfel::default();
            }
            let m = object.transform.matrix();
            let [a, b, c] = mesh.triangle(t).map(|v| m.transform_point3(v));
            let point = a + (b - a) * p.bary.x + (c - a) * p.bary.y;
            let normal = (b - a).cross(c - a).normalize_or_zero();
            let area = points.weighted_area.get(o).copied().unwrap_or(0.0) / f64::from(object.sampling_weight)
                * f64::from(BLOCKS)
                / counts.get(o).copied().unwrap_or(1).max(1) as f64;
            let uv = mesh_uv(mesh, t, p.bary);
            let material = scene.materials().get(object.material).cloned().unwrap_or_default();
            let texture = |t: Option<crate::scene::TextureRef>| {
                t.and_then(|t| images.get(t.image))
                    .map_or(Vec3::ONE, |img| crate::precompute::pathtracer::sample_image(img, uv, true))
            };
            let albedo = Vec3::from_slice(&material.base_color[..3]) * texture(material.base_color_texture);
            let emission = material.emission() * texture(material.emissive_texture);
            GpuSurfel {
                point: point.extend(area as f32).to_array(),
                normal: normal.extend(0.0).to_array(),
                albedo: albedo.extend(0.0).to_array(),
                emission: emission.extend(0.0).to_array(),
                specular: Vec3::from_array(material.specular).extend(material.roughness).to_array(),
            }
        })
        .collect()
}

/// The texture coordinate at barycentrics `bary` (second and third vertex) of triangle `t`.
fn mesh_uv(mesh: &crate::scene::Mesh, t: usize, bary: Vec2) -> Vec2 {
    let uv = |k: usize| mesh.indices.get(3 * t + k).and_then(|&i| mesh.uvs.get(i as usize)).copied();
    match (uv(0), uv(1), uv(2)) {
        (Some(a), Some(b), Some(c)) => a + (b - a) * bary.x + (c - a) * bary.y,
        _ => Vec2::ZERO,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::precompute::test_scenes;

    #[test]
    fn each_block_of_points_stands_for_the_whole_surface_with_its_materials_albedo_and_lobe() {
        // A closed 4 x 3 x 4 m room of 0.2 m slabs (their outer faces see nothing and get no
        // points).
        let v = Vec3::new;
        let scene = test_scenes::scene_of_slabs(
            &[
                ("floor", v(0.0, -0.1, 0.0), v(4.4, 0.2, 4.4)),
                ("ceiling", v(0.0, 3.1, 0.0), v(4.4, 0.2, 4.4)),
                ("left", v(-2.1, 1.5, 0.0), v(0.2, 3.0, 4.0)),
                ("right", v(2.1, 1.5, 0.0), v(0.2, 3.0, 4.0)),
                ("back", v(0.0, 1.5, -2.1), v(4.4, 3.0, 0.2)),
                ("front", v(0.0, 1.5, 2.1), v(4.4, 3.0, 0.2)),
            ],
            vec![],
        );
        // A glossy floor: its points carry the lobe.
        let mut desc = scene.desc().clone();
        desc.materials.push(crate::scene::Material { specular: [0.5, 0.4, 0.3], roughness: 0.3, ..Default::default() });
        desc.objects[0].material = 1;
        let scene = Scene::new(desc, scene.resources().clone()).expect("scene");
        let per_block = 512;
        let points = distribute(&scene, per_block * BLOCKS as usize, BLOCKS as usize, 7);
        let records = surfels(&scene, &points);
        let sampled: f64 = points
            .weighted_area
            .iter()
            .zip(scene.objects())
            .map(|(a, o)| a / f64::from(o.sampling_weight.max(1e-9)))
            .sum();
        for block in records.chunks(per_block) {
            let area: f64 = block.iter().map(|r| f64::from(r.point[3])).sum();
            assert!((area / sampled - 1.0).abs() < 1e-3, "a block stands for {area:.4} m^2 of {sampled:.4}");
        }
        for (r, p) in records.iter().zip(&points.points) {
            let object = &scene.objects()[p.object as usize];
            let material = &scene.materials()[object.material];
            let albedo = material.base_color;
            assert!((0..3).all(|c| (r.albedo[c] - albedo[c]).abs() < 1e-6), "{:?} vs {albedo:?}", r.albedo);
            let lobe = [material.specular[0], material.specular[1], material.specular[2], material.roughness];
            assert_eq!(r.specular, lobe, "the surfel carries its material's glossy lobe");
            let n = Vec3::from_slice(&r.normal[..3]);
            assert!((n.length() - 1.0).abs() < 1e-4);
        }
    }
}
