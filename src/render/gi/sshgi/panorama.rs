//! `sshgi`'s panorama: what the screen cannot send, from a low-resolution cube G-buffer around
//! the camera (an extension of Soler et al. 2010, whose gathers read the view alone). Each
//! frame the six faces (F x F texels, 90 degrees each) are rasterised with the view's G-buffer
//! and emission passes, lit by its direct-light pass (the same lights and shadow maps, and the
//! emission: an emissive panel behind the camera sends its light), and packed
//! (`sshgi_panorama_pack.wgsl`) into a list of senders: the surfaces around the camera that the
//! view does not show, each with its point, area, normal, reflectance and outgoing radiance. In every
//! bounce the start level gathers N of them per texel (`sshgi_panorama_gather.wgsl`) beside
//! the screen's own gathers, and the senders gather that bounce's light from the screen and
//! from each other (`sshgi_panorama_receive.wgsl`) for their radiance of the next: light that
//! leaves the view, lights a wall behind the camera and comes back is carried too.
//!
//! It reaches surfaces beside and behind the camera but not those hidden from the camera's
//! position (the back of a pillar: [`super::hidden`] adds those after the panorama's in the same
//! list), and has no visibility: light passes through whatever lies between a receiver and a
//! panorama sender.

use bytemuck::{Pod, Zeroable};
use glam::{Mat4, Quat, Vec3};

use super::hidden::{HiddenSenders, PanoramaLists};

use crate::render::gbuffer::GbufferPass;
use crate::render::gi::inputs::GiInputs;
use crate::render::gi::technique::texture_bytes;
use crate::render::layouts::{
    Layouts, compute_pipeline, storage_entry, storage_rw_entry, storage_texture_entry, texture_entry, uniform_entry,
};
use crate::render::lighting::{LightingInputs, LightingPass, TILE};
use crate::render::shaders::{self, ShaderError};
use crate::render::targets::{ViewTargets, formats};
use crate::render::uniforms::FrameUniforms;
use crate::scene::{Camera, rotation_looking};

/// The cube faces' view directions.
const FACES: [Vec3; 6] = [Vec3::X, Vec3::NEG_X, Vec3::Y, Vec3::NEG_Y, Vec3::Z, Vec3::NEG_Z];

/// Bytes of one sender (`Sender` in the WGSL: point and area, normal, reflectance).
const SENDER_BYTES: u64 = 48;
/// Bytes of one sender's radiance (rgb and a pad).
const RADIANCE_BYTES: u64 = 16;

/// The pack's parameters (`PackParams` in `sshgi_panorama_pack.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct PackParams {
    /// Face index, face size F, unused x2.
    pub face: [u32; 4],
}

/// The gather's and the receive's parameters (`PanoramaParams` in
/// `sshgi_panorama_common.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct PanoramaParams {
    /// Senders in the list, samples per texel, frame seed, face size F.
    pub counts: [u32; 4],
    /// The start level's width and height; threads per texel of the gather and per sender of
    /// the receive.
    pub screen: [u32; 4],
    /// Solid angle of one start-level texel on the optical axis (sr); a voxel column's width
    /// per metre of view depth where a segment in view walks the world grid when its voxel is
    /// smaller (0: never, `SshgiSettings::world_grid_in_view` off); the share of the sender
    /// picks drawn by power (`SshgiSettings::sender_power_share`); unused.
    pub geo: [f32; 4],
    /// The camera's forward axis, unused.
    pub forward: [f32; 4],
    /// Voxel slices: near, far, slices per metre, on (the hidden senders' visibility).
    pub vox: [f32; 4],
    /// Voxel columns: width, view pixels per column, height, unused.
    pub grid: [u32; 4],
    /// The world grid's origin and voxel side (m).
    pub world: [f32; 4],
    /// The world grid's voxels along x, y, z (0: none) and its bricks' first word.
    pub world_dims: [u32; 4],
}

/// What the panorama hands `sshgi`'s steps: the sender list, the ping-pong radiance buffers
/// (the first holds the first bounce's after the pack), the prefix sums of a bounce's sender
/// power, the face size and the hidden senders after the faces' in the list.
#[derive(Clone, Copy)]
pub struct Senders<'a> {
    pub list: &'a wgpu::Buffer,
    pub radiance: [&'a wgpu::Buffer; 2],
    /// The prefix sums of the senders' power in the bounce being gathered
    /// (`sshgi_sender_cdf.wgsl`, written before each bounce's gather and receive).
    pub cdf: &'a wgpu::Buffer,
    /// The face size F.
    pub face: u32,
    /// Hidden senders after the faces' 6 F^2 ([`super::hidden`]; 0: none).
    pub hidden: u32,
    /// The world's surface voxels, where their segments leave the view ([`super::world_grid`]).
    pub world: Option<super::world_grid::WorldGridRef<'a>>,
}

const _: () = assert!(std::mem::size_of::<PackParams>() == 16);
const _: () = assert!(std::mem::size_of::<PanoramaParams>() == 128);

/// One cube face: its G-buffer and direct light, camera constants and bind groups.
struct Face {
    targets: ViewTargets,
    frame: wgpu::Buffer,
    frame_group: wgpu::BindGroup,
    lighting_targets: wgpu::BindGroup,
    params: wgpu::Buffer,
}

/// The textures and buffers the per-face bind groups name besides the faces' own: when one of
/// them is another object than last frame's, the groups are rebuilt.
#[derive(PartialEq)]
struct GroupKey {
    lights: wgpu::Buffer,
    shadow_views: wgpu::Buffer,
    shadow_maps: wgpu::TextureView,
    view_frame: wgpu::Buffer,
}

/// The faces of one size and the sender list.
struct Faces {
    size: u32,
    /// Hidden senders in the list after the faces'.
    hidden: u32,
    faces: Vec<Face>,
    /// Each face texel's distance to its surface (the hidden senders' test).
    distances: wgpu::Buffer,
    senders: wgpu::Buffer,
    radiance: [wgpu::Buffer; 2],
    /// The prefix sums of a bounce's sender power: per sender within its block, then per block
    /// ([`super::passes::sender_cdf`]).
    cdf: wgpu::Buffer,
    /// Per face: the lighting inputs' and the pack's bind groups, for the inputs they name.
    groups: Option<(GroupKey, Vec<(wgpu::BindGroup, wgpu::BindGroup)>)>,
}

/// The panorama's passes and targets.
pub struct Panorama {
    gbuffer: GbufferPass,
    emission: crate::render::emission::EmissionPass,
    lighting: LightingPass,
    /// No sky (never synced): the faces' background is no sender (the sky pass,
    /// `sshgi_sky.wgsl`, brings the sky's light).
    sky: crate::render::sky::SkyGpu,
    pack_layout: wgpu::BindGroupLayout,
    pack: wgpu::ComputePipeline,
    hidden: HiddenSenders,
    /// The world's surface voxels for the hidden senders' segments that leave the view.
    world: super::world_grid::WorldGrid,
    faces: Option<Faces>,
}

impl Senders<'_> {
    /// Senders in the list: six faces of F^2, then the hidden ones.
    pub fn count(&self) -> u32 {
        FACES.len() as u32 * self.face * self.face + self.hidden
    }
}

impl Panorama {
    /// Creates the pipelines.
    pub fn new(device: &wgpu::Device, layouts: &Layouts) -> Result<Self, ShaderError> {
        let c = wgpu::ShaderStages::COMPUTE;
        let float = wgpu::TextureSampleType::Float { filterable: false };
        let pack_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("sshgi panorama pack layout"),
            entries: &[
                uniform_entry(0, c, false),
                uniform_entry(1, c, false),
                uniform_entry(2, c, false),
                texture_entry(3, c, wgpu::TextureSampleType::Depth),
                texture_entry(4, c, float),
                texture_entry(5, c, float),
                storage_rw_entry(6),
                storage_rw_entry(7),
                texture_entry(8, c, float),
                storage_rw_entry(9),
                texture_entry(10, c, float),
            ],
        });
        let module = shaders::module(device, "render/gi/sshgi/sshgi_panorama_pack.wgsl")?;
        let lighting = LightingPass::new(device)?;
        Ok(Self {
            gbuffer: GbufferPass::new(device, layouts)?,
            emission: crate::render::emission::EmissionPass::new(device, layouts)?,
            hidden: HiddenSenders::new(device, &lighting)?,
            lighting,
            sky: crate::render::sky::SkyGpu::new(device),
            pack: compute_pipeline(device, "sshgi panorama pack", &pack_layout, &module, "pack"),
            pack_layout,
            world: super::world_grid::WorldGrid::default(),
            faces: None,
        })
    }

    /// Renders, lights and packs the faces (`size` texels a side) and `hidden` hidden senders
    /// ([`super::hidden`]); returns the senders.
    pub fn record(&mut self, inputs: &mut GiInputs<'_>, size: u32, hidden: u32) -> Option<Senders<'_>> {
        self.ensure(inputs.device, inputs.layouts, size, hidden);
        if hidden == 0 {
            self.hidden.release();
        }
        let Self { gbuffer, emission, lighting, sky, pack_layout, pack, hidden: hidden_pass, world, faces } = self;
        let faces = faces.as_mut()?;
        let turn = frame_rotation(inputs.frame_index);
        let matrices = write_frames(inputs.queue, faces, inputs.frame, inputs.scene.camera(), turn);
        let key = GroupKey {
            lights: inputs.lights.buffer.clone(),
            shadow_views: inputs.lights.shadow_views.clone(),
            shadow_maps: inputs.lights.shadow_maps.clone(),
            view_frame: inputs.frame_buffer.clone(),
        };
        if faces.groups.as_ref().is_none_or(|(k, _)| *k != key) {
            let groups = faces
                .faces
                .iter()
                .map(|f| {
                    face_groups(
                        lighting,
                        sky,
                        pack_layout,
                        inputs.device,
                        f,
                        &key,
                        [&faces.senders, &faces.radiance[0], &faces.distances],
                    )
                })
                .collect();
            faces.groups = Some((key, groups));
        }
        let Some((_, groups)) = &faces.groups else { return None };
        let GiInputs { encoder, timer, scene_gpu, .. } = inputs;
        let last = faces.faces.len() - 1;
        let emissive = scene_gpu.has_emissive();
        {
            // The scope ends with the last face's emission pass where something emits.
            let scope = timer.scope("sshgi panorama raster");
            for (i, face) in faces.faces.iter().enumerate() {
                let (first, ends) = (i == 0, i == last && !emissive);
                let writes = scope.as_ref().filter(|_| first || ends).map(|t| t.render_writes(first, ends));
                gbuffer.record(encoder, &face.targets, &face.frame_group, scene_gpu, writes);
                if emissive {
                    let writes = scope.as_ref().filter(|_| i == last).map(|t| t.render_writes(false, true));
                    emission.record(encoder, &face.targets, &face.frame_group, scene_gpu, writes);
                }
            }
        }
        let scope = timer.scope("sshgi panorama lighting");
        for (i, (face, (inputs_group, _))) in faces.faces.iter().zip(groups).enumerate() {
            let writes = scope.as_ref().filter(|_| i == 0).map(|t| t.compute_begin_writes());
            lighting.record(encoder, inputs_group, &face.lighting_targets, (size, size), writes);
        }
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("sshgi panorama pack"),
            timestamp_writes: scope.as_ref().map(|t| t.compute_end_writes()),
        });
        pass.set_pipeline(pack);
        for (_, group) in groups {
            pass.set_bind_group(0, group, &[]);
            pass.dispatch_workgroups(size.div_ceil(TILE), size.div_ceil(TILE), 1);
        }
        drop(pass);
        if hidden > 0 {
            let lists = PanoramaLists {
                distances: &faces.distances,
                senders: &faces.senders,
                radiance: &faces.radiance[0],
                faces: matrices,
                face: size,
            };
            hidden_pass.record(inputs, hidden, lighting, sky, &lists);
        }
        let along = if hidden > 0 { inputs.settings.sshgi.world_voxels } else { 0 };
        let world = world.update(inputs.device, inputs.queue, inputs.scene, along);
        let [first, second] = &faces.radiance;
        Some(Senders { list: &faces.senders, radiance: [first, second], cdf: &faces.cdf, face: size, hidden, world })
    }

    /// Creates the faces and the list when their size or the hidden senders' count changes.
    fn ensure(&mut self, device: &wgpu::Device, layouts: &Layouts, size: u32, hidden: u32) {
        if self.faces.as_ref().is_some_and(|f| f.size == size && f.hidden == hidden) {
            return;
        }
        let faces = (0..FACES.len() as u32).map(|i| self.face(device, layouts, i, size)).collect();
        let texels = FACES.len() as u64 * u64::from(size * size);
        let count = texels + u64::from(hidden);
        let buffer = |label: &str, bytes: u64| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: count * bytes,
                usage: wgpu::BufferUsages::STORAGE,
                mapped_at_creation: false,
            })
        };
        let senders = buffer("sshgi panorama senders", SENDER_BYTES);
        let radiance =
            [buffer("sshgi panorama radiance", RADIANCE_BYTES), buffer("sshgi panorama radiance", RADIANCE_BYTES)];
        let cdf = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("sshgi sender power prefix sums"),
            size: 4 * super::passes::sender_cdf::floats(count),
            usage: wgpu::BufferUsages::STORAGE,
            mapped_at_creation: false,
        });
        let distances = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("sshgi panorama distances"),
            size: texels * 4,
            usage: wgpu::BufferUsages::STORAGE,
            mapped_at_creation: false,
        });
        self.faces = Some(Faces { size, hidden, faces, distances, senders, radiance, cdf, groups: None });
    }

    /// Face `index`'s targets, constants and fixed bind groups.
    fn face(&self, device: &wgpu::Device, layouts: &Layouts, index: u32, size: u32) -> Face {
        use wgpu::util::DeviceExt as _;
        let targets = ViewTargets::new(device, (size, size));
        let frame = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("sshgi panorama face frame"),
            size: std::mem::size_of::<FrameUniforms>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let frame_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("sshgi panorama face frame bind group"),
            layout: &layouts.frame,
            entries: &[wgpu::BindGroupEntry { binding: 0, resource: frame.as_entire_binding() }],
        });
        let params = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("sshgi panorama pack params"),
            contents: bytemuck::bytes_of(&PackParams { face: [index, size, 0, 0] }),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let lighting_targets = self.lighting.targets_bind_group(device, &targets);
        Face { targets, frame, frame_group, lighting_targets, params }
    }

    /// Frees the faces and the hidden senders.
    pub fn release(&mut self) {
        self.faces = None;
        self.hidden.release();
        self.world.release();
    }

    /// Bytes of the faces' targets and the sender list.
    pub fn gpu_bytes(&self) -> u64 {
        let Some(f) = &self.faces else { return 0 };
        let targets: u64 =
            f.faces.iter().flat_map(|face| face.targets.all()).map(|target| texture_bytes(&target.texture)).sum();
        let lists = f.senders.size()
            + f.distances.size()
            + f.cdf.size()
            + f.radiance.iter().map(wgpu::Buffer::size).sum::<u64>();
        targets + lists + self.hidden.gpu_bytes() + self.world.gpu_bytes()
    }
}

/// The lighting inputs' and the pack's bind groups of `face`.
fn face_groups(
    lighting: &LightingPass,
    sky: &crate::render::sky::SkyGpu,
    pack_layout: &wgpu::BindGroupLayout,
    device: &wgpu::Device,
    face: &Face,
    key: &GroupKey,
    [senders, radiance, distances]: [&wgpu::Buffer; 3],
) -> (wgpu::BindGroup, wgpu::BindGroup) {
    let lighting = lighting.inputs_bind_group(
        device,
        &LightingInputs {
            frame: &face.frame,
            lights: &key.lights,
            shadow_views: &key.shadow_views,
            shadow_maps: &key.shadow_maps,
            sky,
        },
    );
    let view = |binding, view| wgpu::BindGroupEntry { binding, resource: wgpu::BindingResource::TextureView(view) };
    let pack = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("sshgi panorama pack bind group"),
        layout: pack_layout,
        entries: &[
            wgpu::BindGroupEntry { binding: 0, resource: face.frame.as_entire_binding() },
            wgpu::BindGroupEntry { binding: 1, resource: key.view_frame.as_entire_binding() },
            wgpu::BindGroupEntry { binding: 2, resource: face.params.as_entire_binding() },
            view(3, &face.targets.depth.view),
            view(4, &face.targets.normal.view),
            view(5, &face.targets.exitance.view),
            wgpu::BindGroupEntry { binding: 6, resource: senders.as_entire_binding() },
            wgpu::BindGroupEntry { binding: 7, resource: radiance.as_entire_binding() },
            view(8, &face.targets.albedo.view),
            wgpu::BindGroupEntry { binding: 9, resource: distances.as_entire_binding() },
            view(10, &face.targets.material.view),
        ],
    });
    (lighting, pack)
}

/// The cube's orientation in frame `index`: a rotation drawn uniformly (Shoemake 1992) from a
/// hash of the index. A fixed cube samples each texel's light at its centre and lets that
/// stand for the whole texel: a sunlit patch a texel's centre falls on is counted over the
/// whole texel in every frame (the suite's window room read 1.26 of the path tracer's energy
/// with 16-texel faces, 0.79 with 32 and 0.82 with 64); a new orientation each frame makes the
/// temporal filter's average an unbiased estimate of the sphere's light.
fn frame_rotation(index: u32) -> Quat {
    let unit = |k: u64| (crate::precompute::rng::hash64(u64::from(index) * 3 + k) >> 40) as f32 / (1u64 << 24) as f32;
    let (u1, u2, u3) = (unit(0), unit(1), unit(2));
    let tau = std::f32::consts::TAU;
    let (a, b) = ((1.0 - u1).sqrt(), u1.sqrt());
    Quat::from_xyzw(a * (tau * u2).sin(), a * (tau * u2).cos(), b * (tau * u3).sin(), b * (tau * u3).cos()).normalize()
}

/// Each face's frame constants: the view's, from the camera's position along the face's axis
/// (the cube turned by `turn`) with a 90-degree square frustum. Returns each face's
/// clip_from_world.
fn write_frames(queue: &wgpu::Queue, faces: &Faces, view: &FrameUniforms, camera: &Camera, turn: Quat) -> [Mat4; 6] {
    let size = faces.size as f32;
    let mut matrices = [Mat4::IDENTITY; 6];
    for ((face, forward), out) in faces.faces.iter().zip(FACES).zip(&mut matrices) {
        let rotation = turn * rotation_looking(forward);
        let cube = Camera { rotation, yfov: std::f32::consts::FRAC_PI_2, ..*camera };
        let clip_from_world = cube.clip_from_view(1.0) * cube.view_from_world();
        let frame = FrameUniforms {
            clip_from_world: clip_from_world.to_cols_array_2d(),
            world_from_clip: clip_from_world.inverse().to_cols_array_2d(),
            prev_clip_from_world: clip_from_world.to_cols_array_2d(),
            size: [size, size, 1.0 / size, 1.0 / size],
            ..*view
        };
        queue.write_buffer(&face.frame, 0, bytemuck::bytes_of(&frame));
        *out = clip_from_world;
    }
    matrices
}

/// The gather's bind group layout and pipeline (dispatched among `sshgi`'s steps,
/// [`super::passes`]): the view's frame constants, its parameters (a dynamic slot of the
/// steps' parameter buffer), the start level's geometry, the screen's bounce, the output, the
/// sender list, the senders' radiance of the bounce, the voxel columns, the world grid (the
/// hidden senders' visibility) and the prefix sums of the senders' power.
pub fn gather_pipeline(device: &wgpu::Device) -> Result<(wgpu::BindGroupLayout, wgpu::ComputePipeline), ShaderError> {
    let c = wgpu::ShaderStages::COMPUTE;
    let rest = [
        storage_texture_entry(4, formats::HDR),
        storage_entry(5, c),
        storage_entry(6, c),
        storage_entry(7, c),
        storage_entry(8, c),
        storage_entry(9, c),
    ];
    step_pipeline(device, "sshgi panorama gather", "render/gi/sshgi/sshgi_panorama_gather.wgsl", "gather", &rest)
}

/// The receive's bind group layout and pipeline (dispatched among `sshgi`'s steps after each
/// bounce but the last): the view's frame constants, the parameter slot, the start level's
/// geometry and this bounce's screen radiance, the sender list, this bounce's and the next
/// bounce's sender radiance, the voxel columns, the world grid and the prefix sums of this
/// bounce's sender power.
pub fn receive_pipeline(device: &wgpu::Device) -> Result<(wgpu::BindGroupLayout, wgpu::ComputePipeline), ShaderError> {
    let c = wgpu::ShaderStages::COMPUTE;
    let rest = [
        storage_entry(4, c),
        storage_entry(5, c),
        storage_rw_entry(6),
        storage_entry(7, c),
        storage_entry(8, c),
        storage_entry(9, c),
    ];
    step_pipeline(device, "sshgi panorama receive", "render/gi/sshgi/sshgi_panorama_receive.wgsl", "receive", &rest)
}

/// A pipeline whose bindings start with the view's frame constants, a dynamic parameter slot
/// and two start-level textures, followed by `rest`.
fn step_pipeline(
    device: &wgpu::Device,
    label: &str,
    file: &str,
    entry: &str,
    rest: &[wgpu::BindGroupLayoutEntry],
) -> Result<(wgpu::BindGroupLayout, wgpu::ComputePipeline), ShaderError> {
    let c = wgpu::ShaderStages::COMPUTE;
    let float = wgpu::TextureSampleType::Float { filterable: false };
    let mut entries = vec![uniform_entry(0, c, false), uniform_entry(1, c, true)];
    entries.extend([texture_entry(2, c, float), texture_entry(3, c, float)]);
    entries.extend_from_slice(rest);
    let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some(&format!("{label} layout")),
        entries: &entries,
    });
    let module = shaders::module(device, file)?;
    let pipeline = compute_pipeline(device, label, &layout, &module, entry);
    Ok((layout, pipeline))
}
