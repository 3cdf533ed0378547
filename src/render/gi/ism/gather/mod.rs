//! ISM passes P6b, P7, P8 and P11 on the GPU (docs/ARCHITECTURE.md, "ISM pass labels"): choose each
//! VPL's points from the scene's point pool by solid angle, splat them into the imperfect shadow
//! map atlas, fill holes by pull-push, and grow each further bounce's VPL set from the previous one
//! (one-pass multi-bounce). The screen passes that shade with these VPLs and maps live in
//! [`super::screen`], which this type owns and feeds.

mod access;
mod resources;

use resources::{Buffers, Groups};

use crate::render::layouts::{compute_pipeline, storage_entry, uniform_entry};
use crate::render::shaders::{self, ShaderError};
use crate::render::targets::ViewTargets;
use crate::render::timing::GpuTimer;
use crate::settings::{BouncePick, IsmSettings};

use super::params::{BounceParams, PullPushParams, SelectParams, SplatParams};
use super::screen::{IsmInputs, IsmScreen};

pub use crate::precompute::ism::atlas_word::{PULL_LEVELS, level_base};

/// The splat pass's entry point for `device`: on a GPU each workgroup deals its points' texels
/// out evenly among its threads (`splat` in `ism_splat.wgsl`: with a thread per point a 32-lane
/// warp spent 17-19% of its time walking texels on the suite's rooms and window, with the
/// texels dealt out at most 99%, its counting walk and set-ups left out; by
/// `bouncelab probe-ism LEVEL --splat-lanes`). On the software adapter (lavapipe) the dealing
/// made `ism splat` slower (the rooms 636 -> 889 ms, the window 446 -> 694 ms at 320x180)
/// although its 8-lane groups idled too (37% busy with a thread per point); my reading is that
/// its atomics run lane by lane, so idle lanes cost it little and the dealing's second walk of
/// the rows costs it more. It keeps a thread per point. Both write the same atlas, word for
/// word (`tests/integration/ism_footprint.rs`).
fn splat_entry(device: &wgpu::Device) -> &'static str {
    if device.adapter_info().device_type == wgpu::DeviceType::Cpu { "splat_per_point" } else { "splat" }
}

/// Largest splat half-extent in texels (a 33^2 box), a bound on one thread's work for points
/// right next to a VPL.
pub(crate) const MAX_SPLAT_HALF_EXTENT: f32 = 16.0;
pub(super) use crate::render::layouts::storage_rw_entry as storage_rw;

/// Sizes the atlas and view resources were made for.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Key {
    vpls: u32,
    bounces: u32,
    r: u32,
    /// Pool points.
    points: u32,
    /// Points per ISM.
    per_ism: u32,
}

/// Per scene sample point, in point order, what the ISM passes read.
#[derive(Debug, Default)]
pub struct PointData {
    /// World position, w = 1.
    pub positions: Vec<[f32; 4]>,
    /// World geometric normal, w = the object's sampling weight.
    pub normals: Vec<[f32; 4]>,
    /// Linear albedo (textures by their mean colour), w = 1.
    pub albedo: Vec<[f32; 4]>,
    /// Specular reflectance, w = Blinn-Phong exponent (0: no lobe).
    pub specular: Vec<[f32; 4]>,
    /// Splat clip lines, [`crate::precompute::open_edges::CLIPS_PER_POINT`] per point
    /// (`PointClips::world_lines`).
    pub clips: Vec<[f32; 4]>,
    /// The points' clusters (the points above are in their Morton order; [`super::clusters`]).
    pub clusters: Vec<super::params::GpuCluster>,
    /// Pool area per point at sampling weight 1 (m^2): a point of weight w stands for this / w.
    pub area_unit: f32,
}

/// Bytes of one VPL (`GpuVpl`, WGSL `Vpl`).
const VPL_BYTES: u64 = std::mem::size_of::<super::vpl_pass::GpuVpl>() as u64;

/// vec4 words one workgroup of the atlas clear fills (`BLOCK` in `ism_clear.wgsl`).
const CLEAR_BLOCK: u64 = 64 * 16;
/// Workgroups per dispatch row of the atlas clear (`GROUPS_PER_ROW` in `ism_clear.wgsl`).
const CLEAR_GROUPS_PER_ROW: u64 = 256;

/// Dynamic-offset slot size of per-set parameters.
const SLOT: u64 = 256;
/// Most VPL sets (bounces).
const MAX_SETS: u64 = 6;

struct Sized {
    key: Key,
    points: wgpu::Buffer,
    atlas: wgpu::Buffer,
    /// The atlas's coarse levels (`level_base`).
    coarse: wgpu::Buffer,
    splat_group: wgpu::BindGroup,
    all_vpls: wgpu::Buffer,
    normals: wgpu::Buffer,
    albedo: wgpu::Buffer,
    specular: wgpu::Buffer,
    selection: wgpu::Buffer,
    lit: wgpu::Buffer,
    clusters: wgpu::Buffer,
    clips: wgpu::Buffer,
    /// Clusters uploaded.
    cluster_count: u32,
    /// Pool area per point at weight 1 (m^2), as uploaded.
    area_unit: f32,
    /// Per VPL and slot: chosen pool point and its area (`ism_select.wgsl`).
    chosen: wgpu::Buffer,
    /// Per VPL of every set and slot: the chosen pool point alone (the lookups' `chosen_all`).
    chosen_all: wgpu::Buffer,
    /// The bounce tail's screen sums, their running means and last scale (`ism_bounce.wgsl`).
    tail: wgpu::Buffer,
    select_group: wgpu::BindGroup,
    /// The atlas before hole filling (inspector copy), when captured.
    splats: Option<wgpu::Buffer>,
    bounce_group: wgpu::BindGroup,
    pp_group: wgpu::BindGroup,
    /// Counts recreations, so that the screen passes rebind.
    generation: u64,
}

/// The scene-scale constants of the ISM maps: depth normalisation, lookup bias, hole-filling
/// threshold and the sample points' total area.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MapScale {
    /// Distance normalisation of the ISM depths (metres).
    pub d_max: f32,
    /// ISM lookup (`common/vpl.wgsl`): the neighbours' reach (`ism_lit`), the normal offset's constant and slope factors
    /// (`ism_offset_point`), the relative depth margin of texels without a point (`ism_lit`).
    pub bias: [f32; 4],
    /// Pull-push threshold at the finest level as a fraction of the depth compared.
    pub pull_push: f32,
    /// Sum over the scene of area x sampling weight (m^2).
    pub total_area: f32,
}

/// Pipelines and resources of the ISM gather.
pub struct IsmGather {
    /// Copy each set's atlas rows before hole filling (for the inspector).
    pub capture_splats: bool,
    /// This frame's seed of the bounce passes' random pick (the frame index).
    pub seed: u32,
    splat_layout: wgpu::BindGroupLayout,
    select_layout: wgpu::BindGroupLayout,
    select: wgpu::ComputePipeline,
    select_params: wgpu::Buffer,
    clear: wgpu::ComputePipeline,
    splat: wgpu::ComputePipeline,
    pp_layout: wgpu::BindGroupLayout,
    pull: wgpu::ComputePipeline,
    push: wgpu::ComputePipeline,
    splat_params: wgpu::Buffer,
    bounce_layout: wgpu::BindGroupLayout,
    bounce_clear: wgpu::ComputePipeline,
    bounce_select: wgpu::ComputePipeline,
    bounce_sums: wgpu::ComputePipeline,
    bounce_write: wgpu::ComputePipeline,
    bounce_tail: wgpu::ComputePipeline,
    /// `BouncePick::Resampled`: the per-source sums' prefix, then the set's systematic draws.
    bounce_scan: wgpu::ComputePipeline,
    bounce_resample: wgpu::ComputePipeline,
    bounce_params: wgpu::Buffer,
    pp_params: wgpu::Buffer,
    /// The screen passes that shade with this frame's VPLs and maps.
    pub screen: IsmScreen,
    generation: u64,
    sized: Option<Sized>,
}

impl IsmGather {
    /// Creates the pipelines.
    pub fn new(device: &wgpu::Device) -> Result<Self, ShaderError> {
        let c = wgpu::ShaderStages::COMPUTE;
        let splat_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("ism splat layout"),
            entries: &[
                uniform_entry(0, c, true),
                storage_entry(1, c),
                storage_entry(2, c),
                storage_rw(3),
                storage_entry(4, c),
                storage_entry(5, c),
                storage_entry(6, c),
            ],
        });
        let select_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("ism point selection layout"),
            entries: &[
                uniform_entry(0, c, true),
                storage_entry(1, c),
                storage_entry(2, c),
                storage_rw(3),
                storage_rw(4),
                storage_rw(5),
            ],
        });
        let select_module = shaders::module(device, "render/gi/ism/ism_select.wgsl")?;
        let splat_module = shaders::module(device, "render/gi/ism/ism_splat.wgsl")?;
        let clear_module = shaders::module(device, "render/gi/ism/ism_clear.wgsl")?;
        let pp_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("ism pull-push layout"),
            entries: &[uniform_entry(0, c, true), storage_rw(1), storage_rw(2)],
        });
        let pp_module = shaders::module(device, "render/gi/ism/pull_push.wgsl")?;
        let bounce_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("ism bounce layout"),
            entries: &[
                uniform_entry(0, c, true),
                storage_entry(1, c),
                storage_entry(2, c),
                storage_entry(3, c),
                storage_rw(4),
                storage_entry(5, c),
                storage_rw(6),
                storage_rw(7),
                storage_entry(8, c),
                storage_entry(9, c),
                storage_entry(10, c),
                storage_entry(11, c),
                storage_rw(12),
                storage_entry(13, c),
            ],
        });
        let bounce_module = shaders::module(device, "render/gi/ism/ism_bounce.wgsl")?;
        let slots = |label: &str| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: SLOT * MAX_SETS,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        };
        Ok(Self {
            seed: 0,
            bounce_clear: compute_pipeline(device, "ism bounce clear", &bounce_layout, &bounce_module, "clear"),
            bounce_select: compute_pipeline(device, "ism bounce select", &bounce_layout, &bounce_module, "pick"),
            bounce_sums: compute_pipeline(
                device,
                "ism bounce source sums",
                &bounce_layout,
                &bounce_module,
                "source_sums",
            ),
            bounce_write: compute_pipeline(device, "ism bounce write", &bounce_layout, &bounce_module, "write_winner"),
            bounce_tail: compute_pipeline(device, "ism bounce tail", &bounce_layout, &bounce_module, "tail"),
            bounce_scan: compute_pipeline(
                device,
                "ism bounce scan sources",
                &bounce_layout,
                &bounce_module,
                "scan_sources",
            ),
            bounce_resample: compute_pipeline(
                device,
                "ism bounce resample",
                &bounce_layout,
                &bounce_module,
                "resample",
            ),
            bounce_params: slots("ism bounce params"),
            bounce_layout,
            clear: compute_pipeline(device, "ism atlas clear", &splat_layout, &clear_module, "clear"),
            splat: compute_pipeline(device, "ism splat", &splat_layout, &splat_module, splat_entry(device)),
            pull: compute_pipeline(device, "ism pull", &pp_layout, &pp_module, "pull"),
            push: compute_pipeline(device, "ism push", &pp_layout, &pp_module, "push"),
            splat_params: slots("ism splat params"),
            select: compute_pipeline(device, "ism point selection", &select_layout, &select_module, "select_points"),
            select_params: slots("ism point selection params"),
            select_layout,
            pp_params: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("ism pull-push params"),
                size: SLOT * MAX_SETS * PULL_LEVELS as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
            splat_layout,
            pp_layout,
            screen: IsmScreen::new(device)?,
            capture_splats: false,
            generation: 0,
            sized: None,
        })
    }

    fn tiles_per_row(vpls: u32) -> u32 {
        (f64::from(vpls).sqrt().ceil() as u32).max(1)
    }

    /// Creates the atlas, point and bounce buffers and their bind groups for `key`, unless the
    /// current ones already fit it.
    fn ensure(&mut self, device: &wgpu::Device, key: Key) {
        if self.sized.as_ref().is_some_and(|s| s.key == key) {
            return;
        }
        let b = Buffers::new(device, key);
        let groups = self.bind_groups(device, &b);
        self.generation += 1;
        let Buffers {
            atlas,
            coarse,
            points,
            all_vpls,
            normals,
            albedo,
            specular,
            selection,
            lit,
            chosen,
            chosen_all,
            tail,
            clips,
            clusters,
        } = b;
        let Groups { splat: splat_group, select: select_group, bounce: bounce_group, pull_push: pp_group } = groups;
        self.sized = Some(Sized {
            key,
            points,
            atlas,
            splat_group,
            all_vpls,
            normals,
            albedo,
            specular,
            selection,
            lit,
            clusters,
            clips,
            cluster_count: 0,
            area_unit: 0.0,
            chosen,
            chosen_all,
            tail,
            select_group,
            splats: None,
            bounce_group,
            pp_group,
            coarse,
            generation: self.generation,
        });
    }

    /// Sizes the atlas and point buffers for `settings` and `points` pool points; returns a
    /// generation that changes whenever the buffers were recreated (their point data is then
    /// undefined until [`Self::upload_points`]).
    pub fn prepare(&mut self, device: &wgpu::Device, settings: &IsmSettings, points: u32) -> u64 {
        let key = Key {
            vpls: settings.vpl_count,
            bounces: settings.bounces.clamp(1, MAX_SETS as u32),
            r: settings.ism_resolution,
            points,
            per_ism: settings.points_per_ism,
        };
        self.ensure(device, key);
        self.generation
    }

    /// Uploads the sample points' world positions, normals (w = sampling weight), albedo and
    /// specular lobes; only needed when they or the buffers changed.
    pub fn upload_points(&mut self, queue: &wgpu::Queue, points: &PointData) {
        let Some(s) = &mut self.sized else { return };
        queue.write_buffer(&s.clusters, 0, bytemuck::cast_slice(&points.clusters));
        queue.write_buffer(&s.clips, 0, bytemuck::cast_slice(&points.clips));
        s.cluster_count = points.clusters.len() as u32;
        s.area_unit = points.area_unit;
        queue.write_buffer(&s.points, 0, bytemuck::cast_slice(&points.positions));
        queue.write_buffer(&s.normals, 0, bytemuck::cast_slice(&points.normals));
        queue.write_buffer(&s.albedo, 0, bytemuck::cast_slice(&points.albedo));
        queue.write_buffer(&s.specular, 0, bytemuck::cast_slice(&points.specular));
    }

    /// Records splat, pull-push and the further bounces' VPL sets; [`Self::record_screen`]
    /// then shades with them. With `capture_splats`, each set's atlas rows are also copied
    /// after splatting and before hole filling (the inspector's `ism_atlas_splats`).
    #[allow(clippy::too_many_arguments)]
    pub fn record_maps(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        vpls: &wgpu::Buffer,
        scale: &MapScale,
        settings: &IsmSettings,
        timer: &mut GpuTimer,
    ) {
        self.ensure_splat_copy(device);
        let Some(s) = &self.sized else { return };
        encoder.copy_buffer_to_buffer(vpls, 0, &s.all_vpls, 0, u64::from(s.key.vpls) * VPL_BYTES);
        self.write_set_params(queue, s, scale, settings);
        self.write_pull_push_params(queue, s, scale);
        self.record_sets(encoder, s, settings, timer);
    }

    /// The atlas side (texels) of these sized resources.
    fn atlas_side(s: &Sized) -> u32 {
        s.key.r * Self::tiles_per_row(s.key.vpls * s.key.bounces)
    }

    /// Creates the inspector's copy of the splatted atlas while `capture_splats` asks for it,
    /// and frees it when not.
    fn ensure_splat_copy(&mut self, device: &wgpu::Device) {
        let capture = self.capture_splats;
        let Some(s) = &mut self.sized else { return };
        let side = Self::atlas_side(s);
        if capture && s.splats.is_none() {
            s.splats = Some(device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("ism atlas splats (inspector copy)"),
                size: u64::from(side) * u64::from(side) * 4,
                usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            }));
        } else if !capture {
            s.splats = None;
        }
    }

    /// Writes each set's select, splat and (from the second set on) bounce parameter blocks.
    fn write_set_params(&self, queue: &wgpu::Queue, s: &Sized, scale: &MapScale, settings: &IsmSettings) {
        let key = s.key;
        let c = Self::tiles_per_row(key.vpls * key.bounces);
        let d_max = scale.d_max.max(1e-3);
        // A point stands for a disk of the area it was chosen to stand for; the splat is that
        // disk's footprint, its radius scaled by `settings.splat_radius`.
        let disk_r2 = settings.splat_radius.powi(2) / std::f32::consts::PI;
        let n2 = (settings.interleave * settings.interleave) as f32;
        let d_min = settings.clamp_distance;
        let counts = [key.vpls, key.per_ism, key.r, c];
        for b in 0..key.bounces {
            let select = SelectParams {
                counts: [key.vpls, key.per_ism, s.cluster_count, b * key.vpls],
                params: [s.area_unit, 0.0, 0.0, 0.0],
                seed: [self.seed.wrapping_mul(7).wrapping_add(b), 0, 0, 0],
            };
            queue.write_buffer(&self.select_params, u64::from(b) * SLOT, bytemuck::bytes_of(&select));
            let splat = SplatParams {
                counts,
                params: [1.0 / d_max, disk_r2, MAX_SPLAT_HALF_EXTENT, 0.0],
                sets: [b * key.vpls, 0, 0, 0],
            };
            queue.write_buffer(&self.splat_params, u64::from(b) * SLOT, bytemuck::bytes_of(&splat));
            if b > 0 {
                let bounce = BounceParams {
                    counts,
                    sets: [(b - 1) * key.vpls, b * key.vpls, self.seed.wrapping_add(b), settings.bounce_pick as u32],
                    // The bounce keeps a near point's power below the VPL's with the point's
                    // own disk (`incident_power`), whatever the shading's clamp.
                    params: [1.0 / d_max, 0.0, d_min * d_min, n2],
                    area: [scale.total_area, settings.tail_ratio.shader_code(), settings.view_importance, 0.0],
                    bias: scale.bias,
                };
                queue.write_buffer(&self.bounce_params, u64::from(b - 1) * SLOT, bytemuck::bytes_of(&bounce));
            }
        }
    }

    /// The first fine row and the number of rows of the atlas tiles set `b` occupies.
    fn set_rows(s: &Sized, b: u32) -> (u32, u32) {
        let c = Self::tiles_per_row(s.key.vpls * s.key.bounces);
        let first = (b * s.key.vpls) / c;
        let last = ((b + 1) * s.key.vpls - 1) / c;
        (first * s.key.r, (last + 1 - first) * s.key.r)
    }

    /// Writes the pull-push parameter blocks: per set, only the tile rows it occupies (slots:
    /// set b, level l).
    fn write_pull_push_params(&self, queue: &wgpu::Queue, s: &Sized, scale: &MapScale) {
        let side = Self::atlas_side(s);
        for b in 0..s.key.bounces {
            let (row0, _) = Self::set_rows(s, b);
            for l in 0..PULL_LEVELS {
                let params = PullPushParams {
                    counts: [side >> l, l as u32, row0 >> l, 0],
                    params: [scale.pull_push, 0.0, 0.0, 0.0],
                };
                let slot = (u64::from(b) * PULL_LEVELS as u64 + l as u64) * SLOT;
                queue.write_buffer(&self.pp_params, slot, bytemuck::bytes_of(&params));
            }
        }
    }

    /// Records the ISM maps: the atlas cleared, then set after set its bounce (from the previous
    /// set), point choice, splats, the inspector's copy, and pull-push. Each step is a compute
    /// pass of its own under its own timer scope (`ism clear`, `ism bounce`, `ism select`,
    /// `ism splat`, `ism pull-push`; the timer sums a step's passes over the sets), so the profile
    /// shows which step the maps' time goes to. Their sum stands where earlier figures had
    /// `ism maps` (less the inspector's copy and the gaps between the passes).
    fn record_sets(&self, encoder: &mut wgpu::CommandEncoder, s: &Sized, settings: &IsmSettings, timer: &mut GpuTimer) {
        let (key, side) = (s.key, Self::atlas_side(s));
        {
            let mut pass = step_pass(encoder, timer, "ism clear");
            pass.set_bind_group(0, &s.splat_group, &[0]);
            pass.set_pipeline(&self.clear);
            let (x, y) = Self::clear_groups(side);
            pass.dispatch_workgroups(x, y, 1);
        }
        for b in 0..key.bounces {
            let slot = (u64::from(b) * SLOT) as u32;
            if b > 0 {
                let mut pass = step_pass(encoder, timer, "ism bounce");
                self.record_bounce(&mut pass, s, settings, b);
            }
            {
                // This set's VPLs choose their points (after the bounce pass, which read the
                // previous set's choice).
                let mut pass = step_pass(encoder, timer, "ism select");
                pass.set_bind_group(0, &s.select_group, &[slot]);
                pass.set_pipeline(&self.select);
                pass.dispatch_workgroups(key.vpls, 1, 1);
            }
            {
                let mut pass = step_pass(encoder, timer, "ism splat");
                pass.set_bind_group(0, &s.splat_group, &[slot]);
                pass.set_pipeline(&self.splat);
                pass.dispatch_workgroups((key.vpls * key.per_ism).div_ceil(64), 1, 1);
            }
            let (row0, rows) = Self::set_rows(s, b);
            if let Some(splats) = &s.splats {
                // The inspector's copy of this set's rows before hole filling.
                let (at, bytes) = (u64::from(row0) * u64::from(side) * 4, u64::from(rows) * u64::from(side) * 4);
                encoder.copy_buffer_to_buffer(&s.atlas, at, splats, at, bytes);
            }
            let mut pass = step_pass(encoder, timer, "ism pull-push");
            self.record_pull_push(&mut pass, s, b, rows);
        }
    }

    /// The clear's workgroups for an atlas of `side`^2 words: rows of
    /// [`CLEAR_GROUPS_PER_ROW`], each group [`CLEAR_BLOCK`] vec4 words (`ism_clear.wgsl`).
    fn clear_groups(side: u32) -> (u32, u32) {
        let groups = (u64::from(side) * u64::from(side)).div_ceil(4).div_ceil(CLEAR_BLOCK);
        let rows = groups.div_ceil(CLEAR_GROUPS_PER_ROW);
        (CLEAR_GROUPS_PER_ROW.min(groups) as u32, rows as u32)
    }

    /// One-pass multi-bounce: one lit point per VPL of set b-1 (tested against the filled ISMs
    /// of that set; `settings.bounce_pick` says which) becomes a VPL of set b.
    fn record_bounce(&self, pass: &mut wgpu::ComputePass<'_>, s: &Sized, settings: &IsmSettings, b: u32) {
        let key = s.key;
        let slots = key.vpls * key.per_ism;
        let offset = [((b - 1) as u64 * SLOT) as u32];
        pass.set_bind_group(0, &s.bounce_group, &offset);
        pass.set_pipeline(&self.bounce_clear);
        pass.dispatch_workgroups(key.vpls.div_ceil(64), 1, 1);
        pass.set_pipeline(&self.bounce_select);
        pass.dispatch_workgroups(slots.div_ceil(64), 1, 1);
        pass.set_pipeline(&self.bounce_sums);
        pass.dispatch_workgroups(key.vpls, 1, 1);
        if settings.bounce_pick == BouncePick::Resampled {
            pass.set_pipeline(&self.bounce_scan);
            pass.dispatch_workgroups(1, 1, 1);
            pass.set_pipeline(&self.bounce_resample);
            pass.dispatch_workgroups(key.vpls, 1, 1);
        } else {
            pass.set_pipeline(&self.bounce_write);
            pass.dispatch_workgroups(slots.div_ceil(64), 1, 1);
        }
        if b + 1 == key.bounces && settings.bounce_tail {
            pass.set_pipeline(&self.bounce_tail);
            pass.dispatch_workgroups(1, 1, 1);
        }
    }

    /// Pull-push of set `b`'s `rows` atlas rows: the pull down [`PULL_LEVELS`] levels, then the
    /// push back up.
    fn record_pull_push(&self, pass: &mut wgpu::ComputePass<'_>, s: &Sized, b: u32, rows: u32) {
        let side = Self::atlas_side(s);
        pass.set_pipeline(&self.pull);
        for l in 0..PULL_LEVELS {
            let slot = ((u64::from(b) * PULL_LEVELS as u64 + l as u64) * SLOT) as u32;
            pass.set_bind_group(0, &s.pp_group, &[slot]);
            let coarse = (side >> (l + 1)).max(1);
            pass.dispatch_workgroups(coarse.div_ceil(8), (rows >> (l + 1)).max(1).div_ceil(8), 1);
        }
        pass.set_pipeline(&self.push);
        for l in (0..PULL_LEVELS).rev() {
            let slot = ((u64::from(b) * PULL_LEVELS as u64 + l as u64) * SLOT) as u32;
            pass.set_bind_group(0, &s.pp_group, &[slot]);
            // One thread per coarse texel (2x2 fine texels each).
            let coarse = (side >> (l + 1)).max(1);
            pass.dispatch_workgroups(coarse.div_ceil(8), (rows >> (l + 1)).max(1).div_ceil(8), 1);
        }
    }

    /// Records the screen passes of [`IsmScreen`] with this frame's VPLs and maps into
    /// `targets.indirect`.
    #[allow(clippy::too_many_arguments)]
    pub fn record_screen(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        frame_buffer: &wgpu::Buffer,
        targets: &ViewTargets,
        scale: &MapScale,
        settings: &IsmSettings,
        temporal: Option<super::screen::Blend>,
        exposure: f32,
        timer: &mut GpuTimer,
    ) {
        let Self { screen, sized, .. } = self;
        let Some(s) = sized.as_ref() else { return };
        let inputs = IsmInputs {
            vpls: &s.all_vpls,
            atlas: &s.atlas,
            coarse: &s.coarse,
            points: &s.points,
            normals: &s.normals,
            clips: &s.clips,
            chosen_all: &s.chosen_all,
            albedo: &s.albedo,
            tail: &s.tail,
            per_ism: s.key.per_ism,
            pool_points: s.key.points,
            generation: s.generation,
            vpl_count: s.key.vpls,
            sets: s.key.bounces,
            r: s.key.r,
            tiles_per_row: Self::tiles_per_row(s.key.vpls * s.key.bounces),
            d_max: scale.d_max.max(1e-3),
            bias: scale.bias,
        };
        screen.record(device, queue, encoder, frame_buffer, targets, &inputs, settings, temporal, exposure, timer);
    }

    /// Frees the atlas, the point buffers and the screen passes' targets (another mode is
    /// active); pipelines stay.
    pub fn release(&mut self) {
        self.sized = None;
        self.screen.release();
    }
}

/// A compute pass for one step of the ISM maps or of the screen's passes, timed under `name`
/// where the timer has room.
pub(super) fn step_pass<'e>(
    encoder: &'e mut wgpu::CommandEncoder,
    timer: &mut GpuTimer,
    name: &str,
) -> wgpu::ComputePass<'e> {
    let timestamps = timer.scope(name);
    encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
        label: Some(name),
        timestamp_writes: timestamps.as_ref().map(|t| t.compute_writes()),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The clear's dispatch reaches every atlas word (`ism_clear.wgsl` bounds the rest by the
    /// buffer's length) and stays inside wgpu's 65,535 groups per dimension, from one tile to
    /// 1,024 VPLs x 6 sets of 256^2 maps.
    #[test]
    fn the_clear_dispatch_covers_every_atlas_word_within_the_group_limits() {
        for (vpls, r) in [(1, 2), (1, 128), (3, 16), (256 * 6, 128), (1024 * 6, 256), (4096 * 6, 512)] {
            let side = r * IsmGather::tiles_per_row(vpls);
            let (x, y) = IsmGather::clear_groups(side);
            let words = u64::from(side) * u64::from(side);
            let filled = u64::from(x) * u64::from(y) * CLEAR_BLOCK * 4;
            assert!(filled >= words, "{vpls} tiles of {r}^2: {filled} words cleared of {words}");
            assert!(
                filled < words + CLEAR_GROUPS_PER_ROW * CLEAR_BLOCK * 4,
                "{vpls} tiles of {r}^2: a whole row of groups too many"
            );
            assert!((1..=65_535).contains(&x) && (1..=65_535).contains(&y), "{vpls} tiles of {r}^2: groups ({x}, {y})");
        }
    }
}
