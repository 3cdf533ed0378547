//! sshgi's GPU passes and the targets they write (Soler et al. 2010): per bounce, the illumination
//! levels (`sshgi_mip.wgsl`), one gather per level (`sshgi_gather.wgsl`) and the coarse-to-fine
//! joint bilateral up-sampling that sums them (`sshgi_upsample.wgsl`); then the bounces' sum,
//! up-sampled from the start level to the view. Depth and normal levels come from the frame's
//! shared voted pyramid (`render::pyramid`), shared by every bounce. Where the scene has a sky,
//! a sky pass (`sshgi_sky.wgsl`, not in the paper) first finds the sky's light through the voxel
//! columns: it joins the first bounce's senders and the output.

use bytemuck::{Pod, Zeroable};
use glam::{Mat4, Vec3, Vec4};

use crate::render::gi::inputs::GiInputs;
use crate::render::layouts::{compute_pipeline, storage_entry, storage_texture_entry, texture_entry, uniform_entry};
use crate::render::shaders::{self, ShaderError};
use crate::render::targets::{Target, formats};
use crate::settings::SshgiSettings;

pub mod sender_cdf;
mod sky;
mod steps;
mod tail;

use super::panorama::{PanoramaParams, Senders};
pub use steps::share_samples_as_on_a_gpu;
use steps::{Shared, StepBuilder, gather_slot, panorama_slot, sky_slot, split};

/// Bytes between two parameter slots (WebGPU's minimum uniform offset alignment).
const SLOT: u64 = 256;

/// Parameter slots: 2 + levels + (bounces + 1) x levels + bounces + 1 <= 2 + 6 + 5 x 6 + 4 + 1
/// (the settings' ranges, with the inspector's unshadowed first bounce, the panorama's per bounce
/// and the sky's).
const PARAM_SLOTS: u64 = 48;

/// `MipParams` and `UpParams` in the shaders.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct Counts {
    /// The block's four values.
    pub counts: [u32; 4],
}

const _: () = assert!(std::mem::size_of::<Counts>() == 16);

/// `UpParams` in `sshgi_upsample.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct UpParams {
    /// Add the fine gather, view pixels per fine texel, per coarse texel, unused.
    pub counts: [u32; 4],
    /// Angular width of a view pixel on the axis (rad), unused x3.
    pub params: [f32; 4],
}

const _: () = assert!(std::mem::size_of::<UpParams>() == 32);

/// `GatherParams` in `sshgi_gather.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct GatherParams {
    /// Pyramid level, ring, samples, frame seed.
    pub level: [u32; 4],
    /// Ring radius, texel solid angle, pixels per texel.
    pub geo: [f32; 4],
    /// Camera forward axis.
    pub forward: [f32; 4],
    /// Voxel slices: near, far, slices per metre, on.
    pub vox: [f32; 4],
    /// Voxel columns: width, view pixels per column, height; threads per texel.
    pub grid: [u32; 4],
}

const _: () = assert!(std::mem::size_of::<GatherParams>() == 80);

/// `SkyRayParams` in `sshgi_sky.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct SkyRayParams {
    /// Rays per texel, frame seed, unused x2.
    pub counts: [u32; 4],
    /// Camera forward axis.
    pub forward: [f32; 4],
    /// Voxel slices: near, far, slices per metre, on.
    pub vox: [f32; 4],
    /// Voxel columns: width, view pixels per column, height; threads per item.
    pub grid: [u32; 4],
    /// The world grid's origin and voxel side (m) (the senders' rays).
    pub world: [f32; 4],
    /// The world grid's voxels along x, y, z (0: none) and its bricks' first word.
    pub world_dims: [u32; 4],
}

const _: () = assert!(std::mem::size_of::<SkyRayParams>() == 96);

/// The voxel columns the gathers march, with the slices' depth range.
pub struct Visibility<'a> {
    /// The columns of voxel level `level` (every gather level marches them).
    pub columns: &'a wgpu::Buffer,
    /// Their level: each column ORs 2^level x 2^level view pixels.
    pub level: u32,
    /// near, far (view depth, m).
    pub range: (f32, f32),
}

/// The camera's position, forward axis and half-field-of-view tangents, from the frame's
/// matrices.
pub struct ViewAxis {
    /// Camera position.
    pub camera: Vec3,
    /// Unit view axis.
    pub forward: Vec3,
    /// tan of half the horizontal field of view.
    pub tan_x: f32,
    /// tan of half the vertical field of view.
    pub tan_y: f32,
}

impl ViewAxis {
    /// The axis of `frame`'s camera.
    pub fn new(frame: &crate::render::uniforms::FrameUniforms) -> Self {
        let world_from_clip = Mat4::from_cols_array_2d(&frame.world_from_clip);
        let camera = Vec3::from_slice(&frame.camera_position[..3]);
        let ray = |x: f32, y: f32| {
            let h = world_from_clip * Vec4::new(x, y, 1.0, 1.0);
            (h.truncate() / h.w - camera).normalize_or_zero()
        };
        let forward = ray(0.0, 0.0);
        let tan = |edge: Vec3| {
            let c = forward.dot(edge).clamp(1e-6, 1.0);
            (1.0 - c * c).max(0.0).sqrt() / c
        };
        Self { camera, forward, tan_x: tan(ray(1.0, 0.0)), tan_y: tan(ray(0.0, 1.0)) }
    }
}

/// What a frame's gathers read besides the pyramid: the view's axis, the voxel columns (when
/// visibility is on) and the panorama's senders (when it is on).
#[derive(Clone, Copy)]
pub struct Sources<'a> {
    pub axis: &'a ViewAxis,
    pub visibility: Option<&'a Visibility<'a>>,
    pub panorama: Option<Senders<'a>>,
    /// The sky's uniforms and image, when the sky pass runs (`Plan::sky`).
    pub sky: Option<&'a crate::render::sky::SkyGpu>,
}

/// The levels a frame gathers: which pyramid level starts, how many, how many bounces.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Plan {
    /// The view size in pixels.
    pub view: (u32, u32),
    /// Pyramid level of the start level.
    pub start: u32,
    /// Levels gathered.
    pub levels: u32,
    /// Bounces.
    pub bounces: u32,
    /// Also gather the first bounce without visibility, with the same samples (the inspector's
    /// visibility on/off difference; one more gather chain while it is shown).
    pub unshadowed: bool,
    /// The panorama's senders join the first bounce ([`super::panorama`]).
    pub panorama: bool,
    /// The sky pass runs (a sky, `sky_rays` > 0 and the voxels to march).
    pub sky: bool,
    /// The bounces after the last are added as a geometric tail ([`tail`]; `bounce_tail` and at
    /// least two bounces).
    pub tail: bool,
}

impl Plan {
    /// The plan for `settings` over a pyramid of `pyramid_levels` levels: the start level
    /// ([`SshgiSettings::start_level_for`], within `max_start_texels`) and the level count are
    /// cut to what the pyramid holds.
    pub fn new(settings: &SshgiSettings, view: (u32, u32), pyramid_levels: u32) -> Self {
        let start = settings.start_level_for(view, pyramid_levels);
        let levels = settings.levels.clamp(1, (pyramid_levels - start).max(1));
        let panorama = settings.panorama > 0;
        let bounces = settings.bounces.max(1);
        let tail = settings.bounce_tail && bounces >= 2;
        Self { view, start, levels, bounces, unshadowed: false, panorama, sky: false, tail }
    }

    /// Size of gather level k (pyramid level start + k).
    pub fn level_size(&self, k: u32) -> (u32, u32) {
        let l = self.start + k;
        ((self.view.0 >> l).max(1), (self.view.1 >> l).max(1))
    }
}

/// Targets of one plan.
struct Sized {
    plan: Plan,
    /// Per level: outgoing radiance (the last bounce's).
    illumination: Vec<Target>,
    /// Per level: its gather Ind_k (the last bounce's).
    gathered: Vec<Target>,
    /// Per level below the coarsest: the up-sampled sum Acc_k (the last bounce's).
    summed: Vec<Target>,
    /// Start level: the view's reflectance as a diffuse sender (albedo + the glossy lobe's share
    /// of diffuse light), box-averaged.
    albedo: Target,
    /// Start level: each bounce's E / pi.
    bounce: Vec<Target>,
    /// Start level: running sums of the bounces (ping-pong).
    sums: [Target; 2],
    /// Start level: the first bounce gathered without visibility (when the plan asks).
    unshadowed: Option<Target>,
    /// Start level, per bounce: the screen's own gather, before the panorama's senders join it
    /// (empty without the panorama).
    screen_bounce: Vec<Target>,
    /// Start level, with the sky pass: the sky's E / pi, reflectance x it, and the direct
    /// term's box average (as diffuse senders send it) before the sky-lit light joins it.
    sky: Option<[Target; 3]>,
    /// Which of `bounce[0]` and `sums` holds the bounces' sum (and the sky's).
    total: Total,
    /// The tail's factor and per-tile sums (with `Plan::tail`), and the zeros it reads for the
    /// world's ratio without a sender list.
    tail: Option<[wgpu::Buffer; 2]>,
}

/// Where the bounces' sum lies.
#[derive(Clone, Copy)]
enum Total {
    Bounce,
    Sum(usize),
}

/// Pipelines, parameter slots and targets of sshgi.
pub struct SshgiPasses {
    /// Whether items share their samples over threads ([`steps::shares_samples`]).
    shared: bool,
    mip_layout: wgpu::BindGroupLayout,
    gather_layout: wgpu::BindGroupLayout,
    up_layout: wgpu::BindGroupLayout,
    tail_layout: wgpu::BindGroupLayout,
    /// The tail's sums, ratio and add ([`tail`]).
    tail: [wgpu::ComputePipeline; 3],
    /// The prefix sums of a bounce's sender power ([`sender_cdf`]).
    sender_cdf: (wgpu::BindGroupLayout, [wgpu::ComputePipeline; 2]),
    box_seed: wgpu::ComputePipeline,
    reflectance_seed: wgpu::ComputePipeline,
    reduce: wgpu::ComputePipeline,
    product: wgpu::ComputePipeline,
    add: wgpu::ComputePipeline,
    gather: wgpu::ComputePipeline,
    upsample: wgpu::ComputePipeline,
    add_lit: wgpu::ComputePipeline,
    sky_layout: wgpu::BindGroupLayout,
    sky: wgpu::ComputePipeline,
    sender_sky_layout: wgpu::BindGroupLayout,
    sender_sky: wgpu::ComputePipeline,
    panorama_layout: wgpu::BindGroupLayout,
    panorama: wgpu::ComputePipeline,
    receive_layout: wgpu::BindGroupLayout,
    receive: wgpu::ComputePipeline,
    params: wgpu::Buffer,
    /// Bound in place of voxel columns when visibility is off.
    no_voxels: wgpu::Buffer,
    sized: Option<Sized>,
    /// The frame's dispatches, built for the inputs they were built with.
    steps: Option<(Inputs, Vec<Step>)>,
    /// This frame's parameter slots before upload (kept to reuse its allocation).
    staging: Vec<u8>,
}

/// The textures and buffers a frame's bind groups name besides sshgi's own targets: when any of
/// them is another object than last frame's, the bind groups are rebuilt.
#[derive(PartialEq)]
struct Inputs {
    pyramid: Vec<wgpu::TextureView>,
    /// The direct term as diffuse senders send it (the first bounce's senders).
    exitance: wgpu::TextureView,
    albedo: wgpu::TextureView,
    material: wgpu::TextureView,
    out: wgpu::TextureView,
    voxels: wgpu::Buffer,
    frame: wgpu::Buffer,
    /// The panorama's sender list, radiance buffers, power prefix sums, face size and senders
    /// in the list.
    senders: Option<([wgpu::Buffer; 4], u32, u32)>,
    /// The world grid (the hidden senders' segments that leave the view; `no_voxels` for none).
    world: wgpu::Buffer,
    /// The sky's image and uniforms (the sky pass).
    sky: Option<(wgpu::TextureView, wgpu::Buffer)>,
}

/// Which pipeline a [`Step`] runs.
#[derive(Clone, Copy)]
enum Pipe {
    BoxSeed,
    ReflectanceSeed,
    Reduce,
    Product,
    Add,
    Gather,
    Upsample,
    Panorama,
    Receive,
    AddLit,
    Sky,
    SenderSky,
    TailSums,
    TailRatio,
    TailAdd,
    SenderCdfBlocks,
    SenderCdfTotals,
}

/// One dispatch: the (timed) pass it belongs to, its pipeline, bind group, parameter slot and
/// the size of the target it writes.
struct Step {
    pass: String,
    pipeline: Pipe,
    group: wgpu::BindGroup,
    slot: u32,
    size: (u32, u32),
    /// Items per workgroup along each axis: 8, or a shared pass's tile ([`steps::split`]).
    tile: u32,
}

impl SshgiPasses {
    /// Creates the pipelines.
    pub fn new(device: &wgpu::Device) -> Result<Self, ShaderError> {
        let c = wgpu::ShaderStages::COMPUTE;
        let float = wgpu::TextureSampleType::Float { filterable: false };
        let mip_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("sshgi mip layout"),
            entries: &[
                uniform_entry(0, c, true),
                texture_entry(1, c, float),
                texture_entry(2, c, float),
                storage_texture_entry(3, formats::HDR),
            ],
        });
        let gather_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("sshgi gather layout"),
            entries: &[
                uniform_entry(0, c, false),
                uniform_entry(1, c, true),
                texture_entry(2, c, float),
                texture_entry(3, c, float),
                storage_texture_entry(4, formats::HDR),
                storage_entry(5, c),
            ],
        });
        let up_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("sshgi upsample layout"),
            entries: &[
                uniform_entry(0, c, true),
                texture_entry(1, c, float),
                texture_entry(2, c, float),
                texture_entry(3, c, float),
                texture_entry(4, c, float),
                storage_texture_entry(5, formats::HDR),
                uniform_entry(6, c, false),
            ],
        });
        let mip = shaders::module(device, "render/gi/sshgi/sshgi_mip.wgsl")?;
        let gather = shaders::module(device, "render/gi/sshgi/sshgi_gather.wgsl")?;
        let up = shaders::module(device, "render/gi/sshgi/sshgi_upsample.wgsl")?;
        let (panorama_layout, panorama) = super::panorama::gather_pipeline(device)?;
        let (receive_layout, receive) = super::panorama::receive_pipeline(device)?;
        let [(sky_layout, sky), (sender_sky_layout, sender_sky)] = sky::pipelines(device)?;
        let (tail_layout, tail) = tail::pipelines(device)?;
        Ok(Self {
            shared: steps::shares_samples(device),
            tail_layout,
            tail,
            sender_cdf: sender_cdf::pipelines(device)?,
            box_seed: compute_pipeline(device, "sshgi box seed", &mip_layout, &mip, "box_seed"),
            reflectance_seed: compute_pipeline(device, "sshgi reflectance seed", &mip_layout, &mip, "reflectance_seed"),
            reduce: compute_pipeline(device, "sshgi reduce", &mip_layout, &mip, "reduce"),
            product: compute_pipeline(device, "sshgi product", &mip_layout, &mip, "product"),
            add: compute_pipeline(device, "sshgi add", &mip_layout, &mip, "add"),
            gather: compute_pipeline(device, "sshgi gather", &gather_layout, &gather, "gather"),
            upsample: compute_pipeline(device, "sshgi upsample", &up_layout, &up, "upsample"),
            add_lit: compute_pipeline(device, "sshgi add lit", &mip_layout, &mip, "add_lit"),
            sky_layout,
            sky,
            sender_sky_layout,
            sender_sky,
            panorama_layout,
            panorama,
            receive_layout,
            receive,
            params: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("sshgi params"),
                size: PARAM_SLOTS * SLOT,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
            no_voxels: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("sshgi no voxels"),
                size: 16,
                usage: wgpu::BufferUsages::STORAGE,
                mapped_at_creation: false,
            }),
            mip_layout,
            gather_layout,
            up_layout,
            sized: None,
            steps: None,
            staging: Vec::new(),
        })
    }

    fn ensure(&mut self, device: &wgpu::Device, plan: Plan) {
        if self.sized.as_ref().is_some_and(|s| s.plan == plan) {
            return;
        }
        use wgpu::TextureUsages as U;
        let usage = U::STORAGE_BINDING | U::TEXTURE_BINDING | U::COPY_SRC;
        let target = |label: &str, k: u32| Target::new(device, label, plan.level_size(k), formats::HDR, usage);
        self.steps = None;
        self.sized = Some(Sized {
            plan,
            illumination: (0..plan.levels).map(|k| target("sshgi illumination", k)).collect(),
            gathered: (0..plan.levels).map(|k| target("sshgi gather", k)).collect(),
            summed: (0..plan.levels.saturating_sub(1)).map(|k| target("sshgi upsampled sum", k)).collect(),
            albedo: target("sshgi sender reflectance", 0),
            bounce: (0..plan.bounces).map(|_| target("sshgi bounce", 0)).collect(),
            sums: [target("sshgi bounce sum", 0), target("sshgi bounce sum", 0)],
            unshadowed: plan.unshadowed.then(|| target("sshgi unshadowed bounce", 0)),
            screen_bounce: (0..if plan.panorama { plan.bounces } else { 0 })
                .map(|_| target("sshgi screen bounce", 0))
                .collect(),
            sky: plan
                .sky
                .then(|| [target("sshgi sky", 0), target("sshgi sky-lit senders", 0), target("sshgi direct start", 0)]),
            total: match plan.bounces as usize - 1 + usize::from(plan.sky) + usize::from(plan.tail) {
                0 => Total::Bounce,
                adds => Total::Sum(adds % 2),
            },
            tail: plan.tail.then(|| [tail::buffer(device, plan.level_size(0)), tail::no_world(device)]),
        });
    }

    /// Records every pass of a frame; writes E / pi into `out` (view-sized). The bind groups
    /// are built once per plan and set of input textures ([`Inputs`]); a frame only writes the
    /// parameter slots and dispatches.
    pub fn record(
        &mut self,
        inputs: &mut GiInputs<'_>,
        pyramid: &[Target],
        plan: Plan,
        sources: &Sources<'_>,
        out: &Target,
    ) {
        let Sources { axis, visibility, panorama, sky } = *sources;
        let sky = sky.filter(|_| plan.sky && visibility.is_some());
        let plan = Plan { panorama: plan.panorama && panorama.is_some(), sky: sky.is_some(), ..plan };
        self.ensure(inputs.device, plan);
        let key = Inputs {
            pyramid: pyramid.iter().map(|t| t.view.clone()).collect(),
            exitance: inputs.targets.exitance.view.clone(),
            albedo: inputs.targets.albedo.view.clone(),
            material: inputs.targets.material.view.clone(),
            out: out.view.clone(),
            voxels: visibility.map_or(&self.no_voxels, |v| v.columns).clone(),
            frame: inputs.frame_buffer.clone(),
            senders: panorama.map(|p| {
                ([p.list.clone(), p.radiance[0].clone(), p.radiance[1].clone(), p.cdf.clone()], p.face, p.count())
            }),
            sky: sky.map(|s| (s.view.clone(), s.buffer.clone())),
            world: panorama.and_then(|p| p.world).map_or(&self.no_voxels, |w| w.buffer).clone(),
        };
        if self.steps.as_ref().is_none_or(|(k, _)| *k != key) {
            let steps = self.build_steps(inputs.device, &key);
            self.steps = Some((key, steps));
        }
        let world = panorama.and_then(|p| p.world).map_or(([0.0; 4], [0; 4]), |w| (w.world, w.dims));
        self.write_params(inputs, plan, axis, visibility, panorama.map_or((0, 0), |p| (p.count(), p.face)), world);
        let Some((_, steps)) = &self.steps else { return };
        // Consecutive steps of one pass share it: bounce 1's phases are timed one by one, a later
        // bounce as a whole.
        let mut open: Option<(&str, wgpu::ComputePass<'static>)> = None;
        for step in steps {
            if open.as_ref().is_none_or(|(name, _)| *name != step.pass) {
                // The previous pass ends before the next begins (the encoder is locked meanwhile).
                drop(open.take());
                open = Some((step.pass.as_str(), inputs.compute_pass(&step.pass)));
            }
            let Some((_, pass)) = open.as_mut() else { return };
            pass.set_pipeline(match step.pipeline {
                Pipe::BoxSeed => &self.box_seed,
                Pipe::ReflectanceSeed => &self.reflectance_seed,
                Pipe::Reduce => &self.reduce,
                Pipe::Product => &self.product,
                Pipe::Add => &self.add,
                Pipe::Gather => &self.gather,
                Pipe::Upsample => &self.upsample,
                Pipe::Panorama => &self.panorama,
                Pipe::Receive => &self.receive,
                Pipe::AddLit => &self.add_lit,
                Pipe::Sky => &self.sky,
                Pipe::SenderSky => &self.sender_sky,
                Pipe::TailSums => &self.tail[0],
                Pipe::TailRatio => &self.tail[1],
                Pipe::TailAdd => &self.tail[2],
                Pipe::SenderCdfBlocks => &self.sender_cdf.1[0],
                Pipe::SenderCdfTotals => &self.sender_cdf.1[1],
            });
            pass.set_bind_group(0, &step.group, &[step.slot * SLOT as u32]);
            pass.dispatch_workgroups(step.size.0.div_ceil(step.tile), step.size.1.div_ceil(step.tile), 1);
        }
    }

    /// This frame's parameter slots: 0 the start level's box size, 1 zeros, 2 + k the
    /// up-sampling into level k (k = levels - 1: into the view), then the gathers per bounce and
    /// level ([`gather_slot`]).
    fn write_params(
        &mut self,
        inputs: &GiInputs<'_>,
        plan: Plan,
        axis: &ViewAxis,
        visibility: Option<&Visibility<'_>>,
        (senders, face): (u32, u32),
        (world, world_dims): ([f32; 4], [u32; 4]),
    ) {
        let settings = &inputs.settings.sshgi;
        let bytes = &mut self.staging;
        bytes.clear();
        let chains = plan.bounces as usize + usize::from(plan.unshadowed);
        bytes.resize((sky_slot(plan) as usize + 1) * SLOT as usize, 0);
        let mut put = |slot: u32, data: &[u8]| {
            let at = slot as usize * SLOT as usize;
            bytes[at..at + data.len()].copy_from_slice(data);
        };
        put(0, bytemuck::bytes_of(&Counts { counts: [1 << plan.start, 0, 0, 0] }));
        let pixel_sr = 4.0 * axis.tan_x * axis.tan_y / (plan.view.0 as f32 * plan.view.1 as f32);
        for k in 0..plan.levels {
            let counts = if k + 1 < plan.levels {
                [1, 1 << (plan.start + k), 1 << (plan.start + k + 1), 0]
            } else {
                [0, 1, 1 << plan.start, 0]
            };
            put(2 + k, bytemuck::bytes_of(&UpParams { counts, params: [pixel_sr.sqrt(), 0.0, 0.0, 0.0] }));
        }
        let start_size = plan.level_size(0);
        let radius = settings.ring_radius(start_size, plan.levels);
        let grid = visibility
            .map_or([0; 4], |v| [(plan.view.0 >> v.level).max(1), 1 << v.level, (plan.view.1 >> v.level).max(1), 0]);
        let vox = visibility.map_or([0.0; 4], |v| {
            let (near, far) = v.range;
            [near, far, 128.0 / (far - near).max(1e-6), 1.0]
        });
        let forward = axis.forward;
        // A voxel column is grid[1] view pixels wide: its width per metre of view depth.
        let grid_in_view = if settings.world_grid_in_view {
            2.0 * axis.tan_x * grid[1] as f32 / plan.view.0.max(1) as f32
        } else {
            0.0
        };
        for b in 0..chains as u32 {
            // The unshadowed chain repeats the first bounce's samples without the voxels.
            let (seed, vox) = if b == plan.bounces { (0, [0.0; 4]) } else { (b, vox) };
            for k in 0..plan.levels {
                let l = plan.start + k;
                let p = GatherParams {
                    level: [
                        l,
                        u32::from(k > 0),
                        settings.samples,
                        inputs.frame_index.wrapping_mul(4).wrapping_add(seed),
                    ],
                    geo: [radius, pixel_sr * (1u32 << (2 * l)) as f32, (1u32 << l) as f32, 0.0],
                    forward: [forward.x, forward.y, forward.z, 0.0],
                    // The paper's saving: later bounces may skip visibility.
                    vox: if b == 0 || settings.visibility_all_bounces { vox } else { [0.0; 4] },
                    grid: [grid[0], grid[1], grid[2], split(self.shared, Shared::Gather(k)).0],
                };
                put(gather_slot(plan, b as usize, k as usize), bytemuck::bytes_of(&p));
            }
        }
        for b in 0..plan.bounces {
            let seed = inputs.frame_index.wrapping_mul(0x9e37_79b9).wrapping_add(b);
            let p = PanoramaParams {
                counts: [senders, settings.panorama_samples, seed, face],
                screen: [
                    start_size.0,
                    start_size.1,
                    split(self.shared, Shared::Panorama).0,
                    split(self.shared, Shared::Receive).0,
                ],
                geo: [pixel_sr * (1u32 << (2 * plan.start)) as f32, grid_in_view, settings.sender_power_share, 0.0],
                forward: [forward.x, forward.y, forward.z, 0.0],
                // The hidden senders' segments are marched in every bounce: they lie behind
                // something by definition, so without it each would light through it.
                vox,
                grid,
                world,
                world_dims,
            };
            put(panorama_slot(plan, b as usize), bytemuck::bytes_of(&p));
        }
        let sky = SkyRayParams {
            counts: [
                settings.sky_rays,
                inputs.frame_index.wrapping_mul(0x2545_f491),
                if plan.panorama { face } else { 0 },
                if plan.panorama { senders } else { 0 },
            ],
            forward: [forward.x, forward.y, forward.z, 0.0],
            vox,
            grid: [grid[0], grid[1], grid[2], split(self.shared, Shared::Sky).0],
            world,
            world_dims,
        };
        put(sky_slot(plan), bytemuck::bytes_of(&sky));
        inputs.queue.write_buffer(&self.params, 0, bytes);
    }

    /// Every dispatch of a frame with its bind group, for the current plan and `key`'s inputs.
    fn build_steps(&self, device: &wgpu::Device, key: &Inputs) -> Vec<Step> {
        let Some(s) = &self.sized else { return Vec::new() };
        let plan = s.plan;
        let mut steps = StepBuilder { passes: self, device, key, s, steps: Vec::new() };
        steps.sky();
        // Chain `b` (a bounce, or `plan.bounces`: the unshadowed first bounce, recorded first so
        // the last bounce's level buffers stay the inspector's).
        let chains = (plan.unshadowed.then_some(plan.bounces as usize)).into_iter().chain(0..plan.bounces as usize);
        for b in chains {
            steps.chain(b);
            if plan.panorama && b < plan.bounces as usize {
                steps.panorama(b);
            }
        }
        let total = steps.bounce_sum();
        steps.output(total);
        steps.steps
    }

    /// The texture behind inspector buffer `name` of the last frame (see `technique::BUFFERS`).
    pub fn buffer(&self, name: &str) -> Option<&wgpu::Texture> {
        let s = self.sized.as_ref()?;
        match name {
            "sshgi_bounce_sum" => {
                return Some(match s.total {
                    Total::Bounce => &s.bounce[0].texture,
                    Total::Sum(i) => &s.sums[i].texture,
                });
            }
            "sshgi_unshadowed" => return s.unshadowed.as_ref().map(|t| &t.texture),
            "sshgi_screen_bounce" => return s.screen_bounce.first().map(|t| &t.texture),
            "sshgi_sky" => return s.sky.as_ref().map(|[sky, _, _]| &sky.texture),
            _ => {}
        }
        let (kind, index) = name.rsplit_once('_')?;
        let i: usize = index.parse().ok()?;
        let list = match kind {
            "sshgi_illumination" => &s.illumination,
            "sshgi_gather" => &s.gathered,
            "sshgi_sum" => &s.summed,
            "sshgi_bounce" => return s.bounce.get(i.checked_sub(1)?).map(|t| &t.texture),
            _ => return None,
        };
        list.get(i).map(|t| &t.texture)
    }

    /// Frees the targets.
    pub fn release(&mut self) {
        self.sized = None;
        self.steps = None;
    }

    /// Bytes of the targets.
    pub fn gpu_bytes(&self) -> u64 {
        let Some(s) = &self.sized else { return 0 };
        let all = s.illumination.iter().chain(&s.gathered).chain(&s.summed).chain(&s.bounce).chain(&s.sums);
        let all = all.chain(&s.unshadowed).chain(&s.screen_bounce).chain(s.sky.iter().flatten());
        all.chain(std::iter::once(&s.albedo)).map(|t| crate::render::gi::technique::texture_bytes(&t.texture)).sum()
    }
}
