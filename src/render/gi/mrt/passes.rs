//! MRT's GPU passes (the per-frame steps of Loos 2015 §3.6.3 as compute passes, where §4.4-§4.5
//! used render-target passes over records): A direct light at the texels (`mrt_direct.wgsl`),
//! B b = T_{d->b} l_d (`mrt_reduce.wgsl`), C r = T_{b->r} b (`mrt_interface.wgsl`), D the texels'
//! indirect light U_b b + U_r r (`mrt_reconstruct.wgsl`), E the light on the closed part of partly
//! open sides (`mrt_sides.wgsl`), F the lightmap on the view (`mrt_apply.wgsl`). Each is its own
//! timed compute pass. The level's buffers are uploaded when the level changes; the per-frame ones
//! (l_d, b, r, the texels' indirect light) live with them, so the texels' light of the last frame
//! is there for the feedback and the inspector.

use bytemuck::{Pod, Zeroable};
use wgpu::util::DeviceExt;

use super::drt_passes::DrtBuffers;
use super::pack::Packed;
use crate::render::gi::inputs::GiInputs;
use crate::render::readback;
use crate::render::shaders::{self, ShaderError};
use crate::render::targets::{Target, formats};

/// `MrtParams` in `mrt_common.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct MrtParams {
    /// Blocks, texels, directed interfaces, k_b.
    pub counts: [u32; 4],
    /// k_r, texels per face side, padding on (1) or off (0), unused.
    pub sizes: [u32; 4],
    /// Feedback gain, unused x3.
    pub gains: [f32; 4],
    /// Opening positions per side P, partly open sides, side texels, unused.
    pub sides: [u32; 4],
}

const _: () = assert!(std::mem::size_of::<MrtParams>() == 64);

/// What a binding is (each maps to one of `render::layouts`' entries).
#[derive(Clone, Copy)]
enum Kind {
    Uniform,
    Read,
    Write,
    Depth,
    DepthArray,
    Comparison,
    Float,
    Uint,
    StorageTexture,
}

/// One pipeline and its bind group layout.
struct Pass {
    layout: wgpu::BindGroupLayout,
    pipeline: wgpu::ComputePipeline,
}

impl Pass {
    fn new(device: &wgpu::Device, name: &str, kinds: &[Kind]) -> Result<Self, ShaderError> {
        use crate::render::layouts::{
            comparison_sampler_entry, depth_array_entry, storage_entry, storage_rw_entry, storage_texture_entry,
            texture_entry, uniform_entry,
        };
        let c = wgpu::ShaderStages::COMPUTE;
        let entries: Vec<wgpu::BindGroupLayoutEntry> = kinds
            .iter()
            .zip(0u32..)
            .map(|(k, i)| match k {
                Kind::Uniform => uniform_entry(i, c, false),
                Kind::Read => storage_entry(i, c),
                Kind::Write => storage_rw_entry(i),
                Kind::Depth => texture_entry(i, c, wgpu::TextureSampleType::Depth),
                Kind::DepthArray => depth_array_entry(i, c),
                Kind::Comparison => comparison_sampler_entry(i, c),
                Kind::Float => texture_entry(i, c, wgpu::TextureSampleType::Float { filterable: false }),
                Kind::Uint => texture_entry(i, c, wgpu::TextureSampleType::Uint),
                Kind::StorageTexture => storage_texture_entry(i, formats::HDR),
            })
            .collect();
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(&format!("{name} layout")),
            entries: &entries,
        });
        let module = shaders::module(device, &format!("render/gi/mrt/{name}.wgsl"))?;
        let pipeline = crate::render::layouts::compute_pipeline(device, name, &layout, &module, "cs_main");
        Ok(Self { layout, pipeline })
    }

    /// A bind group of `resources` in binding order.
    fn bind(&self, device: &wgpu::Device, name: &str, resources: &[wgpu::BindingResource<'_>]) -> wgpu::BindGroup {
        let entries: Vec<wgpu::BindGroupEntry<'_>> = resources
            .iter()
            .enumerate()
            .map(|(i, r)| wgpu::BindGroupEntry { binding: i as u32, resource: r.clone() })
            .collect();
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(&format!("{name} bind group")),
            layout: &self.layout,
            entries: &entries,
        })
    }
}

/// The level's buffers.
struct LevelBuffers {
    params: wgpu::Buffer,
    texels: wgpu::Buffer,
    blocks: wgpu::Buffer,
    matrices: wgpu::Buffer,
    u_r: wgpu::Buffer,
    transfer: wgpu::Buffer,
    entries: wgpu::Buffer,
    slots: wgpu::Buffer,
    rows: wgpu::Buffer,
    row_scales: wgpu::Buffer,
    own_scales: wgpu::Buffer,
    object_block: wgpu::Buffer,
    sides: wgpu::Buffer,
    side_entries: wgpu::Buffer,
    side_matrices: wgpu::Buffer,
    l_d: wgpu::Buffer,
    b: wgpu::Buffer,
    r: wgpu::Buffer,
    indirect: wgpu::Buffer,
    within: wgpu::Buffer,
    drt: DrtBuffers,
    counts: MrtParams,
}

impl LevelBuffers {
    fn all(&self) -> [&wgpu::Buffer; 20] {
        [
            &self.params,
            &self.texels,
            &self.blocks,
            &self.matrices,
            &self.u_r,
            &self.transfer,
            &self.entries,
            &self.slots,
            &self.rows,
            &self.row_scales,
            &self.own_scales,
            &self.object_block,
            &self.sides,
            &self.side_entries,
            &self.side_matrices,
            &self.l_d,
            &self.b,
            &self.r,
            &self.indirect,
            &self.within,
        ]
    }
}

/// A storage buffer holding `data` (at least 16 bytes: wgpu refuses empty bindings).
pub(super) fn upload<T: Pod>(device: &wgpu::Device, label: &str, data: &[T]) -> wgpu::Buffer {
    let mut bytes = bytemuck::cast_slice::<T, u8>(data).to_vec();
    bytes.resize(bytes.len().max(16), 0);
    device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some(label),
        contents: &bytes,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
    })
}

/// A zeroed per-frame storage buffer of `count` vec4s.
pub(super) fn vec4s(device: &wgpu::Device, label: &str, count: usize) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: (16 * count.max(1)) as u64,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

/// The bind groups made once per level.
struct LevelGroups {
    reduce: wgpu::BindGroup,
    interface: wgpu::BindGroup,
    reconstruct: wgpu::BindGroup,
    sides: wgpu::BindGroup,
    drt_patches: wgpu::BindGroup,
    drt_rows: wgpu::BindGroup,
    drt_inpaint: wgpu::BindGroup,
}

/// A whole buffer as a binding.
fn buf(b: &wgpu::Buffer) -> wgpu::BindingResource<'_> {
    b.as_entire_binding()
}

/// The passes, their level buffers and the view's block assignment.
pub struct MrtPasses {
    direct: Pass,
    reduce: Pass,
    interface: Pass,
    reconstruct: Pass,
    sides: Pass,
    drt_patches: Pass,
    drt_rows: Pass,
    apply: Pass,
    shadow_sampler: wgpu::Sampler,
    level: Option<LevelBuffers>,
    level_groups: Option<LevelGroups>,
    /// Per pixel: block, canonical face, distance to the box (m).
    assignment: Option<Target>,
}

impl MrtPasses {
    /// Creates the pipelines.
    pub fn new(device: &wgpu::Device) -> Result<Self, ShaderError> {
        use Kind::*;
        Ok(Self {
            direct: Pass::new(
                device,
                "mrt_direct",
                &[Uniform, Read, Read, DepthArray, Comparison, Uniform, Read, Read, Write],
            )?,
            reduce: Pass::new(device, "mrt_reduce", &[Uniform, Read, Read, Read, Write])?,
            interface: Pass::new(device, "mrt_interface", &[Uniform, Read, Read, Read, Read, Write])?,
            reconstruct: Pass::new(
                device,
                "mrt_reconstruct",
                &[Uniform, Read, Read, Read, Read, Read, Read, Read, Read, Write, Write, Read, Read],
            )?,
            sides: Pass::new(device, "mrt_sides", &[Uniform, Read, Read, Read, Read, Write])?,
            drt_patches: Pass::new(device, "drt_patches", &[Uniform, Read, Read, Read, Write])?,
            drt_rows: Pass::new(device, "drt_rows", &[Uniform, Read, Read, Read, Write, Write, Write, Write])?,
            apply: Pass::new(
                device,
                "mrt_apply",
                &[
                    Uniform,
                    Uniform,
                    Read,
                    Read,
                    Depth,
                    Float,
                    StorageTexture,
                    StorageTexture,
                    Uint,
                    Read,
                    Read,
                    Read,
                    Read,
                ],
            )?,
            shadow_sampler: crate::render::layouts::shadow_sampler(device, "mrt shadow comparison sampler"),
            level: None,
            level_groups: None,
            assignment: None,
        })
    }

    /// Uploads a level (replacing the previous one; its texels' light starts at zero).
    pub fn upload(&mut self, device: &wgpu::Device, p: &Packed) {
        let texels = p.texels.len();
        let side_texels = p.sides.len() * (p.positions * p.positions) as usize;
        let counts = MrtParams {
            counts: [p.blocks.len() as u32, texels as u32, p.slots.len() as u32, p.k_b],
            sizes: [p.k_r, p.res, 0, 0],
            gains: [0.0; 4],
            sides: [p.positions, p.sides.len() as u32, side_texels as u32, 0],
        };
        self.level = Some(LevelBuffers {
            params: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("mrt params"),
                size: std::mem::size_of::<MrtParams>() as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
            texels: upload(device, "mrt texels", &p.texels),
            blocks: upload(device, "mrt blocks", &p.blocks),
            matrices: upload(device, "mrt T_db and U_b", &p.matrices),
            u_r: upload(device, "mrt U_r", &p.u_r),
            transfer: upload(device, "mrt T_br", &p.transfer),
            entries: upload(device, "mrt T_br entries", &p.entries),
            slots: upload(device, "mrt interfaces", &p.slots),
            rows: upload(device, "mrt response rows", &p.rows),
            row_scales: upload(device, "mrt response stretch corrections", &p.row_scales),
            own_scales: upload(device, "mrt own-light stretch corrections", &p.own_scales),
            object_block: upload(device, "mrt object block overrides", &p.object_block),
            sides: upload(device, "mrt partly open sides", &p.sides),
            side_entries: upload(device, "mrt side matrix entries", &p.side_entries),
            side_matrices: upload(device, "mrt side matrices", &p.side_matrices),
            l_d: vec4s(device, "mrt l_d", texels),
            b: vec4s(device, "mrt b per face", p.blocks.len() * 6 * p.k_b as usize),
            r: vec4s(device, "mrt r", p.slots.len() * p.k_r as usize),
            indirect: vec4s(device, "mrt texel indirect (block texels, then side texels)", texels + side_texels),
            within: vec4s(device, "mrt texel within-block indirect", texels),
            drt: DrtBuffers::new(device, p.drt.as_ref(), p.object_block.len().saturating_sub(1), texels),
            counts,
        });
        self.level_groups = self.level.as_ref().map(|l| self.level_groups_of(device, l));
    }

    /// The bind groups of the passes that read only the level's own buffers (made once per
    /// level; the direct and apply passes also read the frame's lights and targets).
    fn level_groups_of(&self, device: &wgpu::Device, l: &LevelBuffers) -> LevelGroups {
        let reduce = self.reduce.bind(
            device,
            "mrt_reduce",
            &[buf(&l.params), buf(&l.blocks), buf(&l.matrices), buf(&l.l_d), buf(&l.b)],
        );
        let interface = self.interface.bind(
            device,
            "mrt_interface",
            &[buf(&l.params), buf(&l.slots), buf(&l.entries), buf(&l.transfer), buf(&l.b), buf(&l.r)],
        );
        let reconstruct = self.reconstruct.bind(
            device,
            "mrt_reconstruct",
            &[
                buf(&l.params),
                buf(&l.blocks),
                buf(&l.texels),
                buf(&l.matrices),
                buf(&l.u_r),
                buf(&l.slots),
                buf(&l.rows),
                buf(&l.b),
                buf(&l.r),
                buf(&l.indirect),
                buf(&l.within),
                buf(&l.row_scales),
                buf(&l.own_scales),
            ],
        );
        let sides = self.sides.bind(
            device,
            "mrt_sides",
            &[buf(&l.params), buf(&l.sides), buf(&l.side_entries), buf(&l.side_matrices), buf(&l.b), buf(&l.indirect)],
        );
        let d = &l.drt;
        let drt_patches = self.drt_patches.bind(
            device,
            "drt_patches",
            &[buf(&d.patch_params), buf(&d.patches), buf(&l.l_d), buf(&d.radiance), buf(&d.patch_light)],
        );
        let rows = |params: &wgpu::Buffer, name: &str| {
            self.drt_rows.bind(
                device,
                name,
                &[
                    buf(params),
                    buf(&d.rows),
                    buf(&d.entries),
                    buf(&d.patch_light),
                    buf(&l.indirect),
                    buf(&d.gather),
                    buf(&d.occlusion),
                    buf(&d.reflection),
                ],
            )
        };
        let drt_rows = rows(&d.row_params, "drt_rows");
        let drt_inpaint = rows(&d.inpaint_params, "drt_rows inpainting");
        LevelGroups { reduce, interface, reconstruct, sides, drt_patches, drt_rows, drt_inpaint }
    }

    /// Whether a level is uploaded.
    pub fn has_level(&self) -> bool {
        self.level.is_some()
    }

    /// Records passes A-F into `inputs.targets.indirect` (E / pi) with the feedback gain and
    /// padding on or off; false without a level.
    pub fn record(&mut self, inputs: &mut GiInputs<'_>, feedback: f32, padding: bool) -> bool {
        let Some(l) = &self.level else { return false };
        let device = inputs.device;
        let size = inputs.targets.size;
        if self.assignment.as_ref().is_none_or(|t| t.texture.width() != size.0 || t.texture.height() != size.1) {
            use wgpu::TextureUsages as U;
            let usage = U::STORAGE_BINDING | U::TEXTURE_BINDING | U::COPY_SRC;
            self.assignment = Some(Target::new(device, "mrt block assignment", size, formats::HDR, usage));
        }
        let Some(assignment) = &self.assignment else { return false };
        let mut params = MrtParams { gains: [feedback, 0.0, 0.0, 0.0], ..l.counts };
        params.sizes[2] = u32::from(padding);
        inputs.queue.write_buffer(&l.params, 0, bytemuck::bytes_of(&params));
        let [blocks, texels, slots, k_b] = l.counts.counts;
        let lights = &inputs.lights;
        let direct = self.direct.bind(
            device,
            "mrt_direct",
            &[
                buf(inputs.frame_buffer),
                buf(lights.buffer),
                buf(lights.shadow_views),
                wgpu::BindingResource::TextureView(lights.shadow_maps),
                wgpu::BindingResource::Sampler(&self.shadow_sampler),
                buf(&l.params),
                buf(&l.texels),
                buf(&l.indirect),
                buf(&l.l_d),
            ],
        );
        let Some(g) = &self.level_groups else { return false };
        let t = inputs.targets;
        let apply = self.apply.bind(
            device,
            "mrt_apply",
            &[
                buf(inputs.frame_buffer),
                buf(&l.params),
                buf(&l.blocks),
                buf(&l.indirect),
                wgpu::BindingResource::TextureView(&t.depth.view),
                wgpu::BindingResource::TextureView(&t.normal.view),
                wgpu::BindingResource::TextureView(&t.indirect.view),
                wgpu::BindingResource::TextureView(&assignment.view),
                wgpu::BindingResource::TextureView(&t.object_id.view),
                buf(&l.object_block),
                buf(&l.drt.clutter),
                buf(&l.drt.object_clutter),
                buf(&l.drt.gather),
            ],
        );
        // G0: the clutter texels' radiance, pass A's shader over the clutter texels.
        let d = &l.drt;
        let drt_direct = (d.counts[0] > 0).then(|| {
            let params = MrtParams { gains: [feedback, 0.0, 0.0, 0.0], ..d.direct };
            inputs.queue.write_buffer(&d.direct_params, 0, bytemuck::bytes_of(&params));
            self.direct.bind(
                device,
                "mrt_direct clutter",
                &[
                    buf(inputs.frame_buffer),
                    buf(lights.buffer),
                    buf(lights.shadow_views),
                    wgpu::BindingResource::TextureView(lights.shadow_maps),
                    wgpu::BindingResource::Sampler(&self.shadow_sampler),
                    buf(&d.direct_params),
                    buf(&d.texels),
                    buf(&d.gather),
                    buf(&d.radiance),
                ],
            )
        });
        let k_r = l.counts.sizes[0];
        let [positions, sides, _, _] = l.counts.sides;
        let [clutter_texels, patches, inpaint_from, rows] = d.counts;
        let mut steps: Vec<(&str, &Pass, &wgpu::BindGroup, [u32; 3])> = vec![
            ("mrt direct texels", &self.direct, &direct, [texels.div_ceil(64), 1, 1]),
            ("mrt b", &self.reduce, &g.reduce, [k_b, blocks, 6]),
            ("mrt interfaces r", &self.interface, &g.interface, [(slots * k_r).div_ceil(64), 1, 1]),
            ("mrt reconstruct", &self.reconstruct, &g.reconstruct, [texels.div_ceil(64), 1, 1]),
        ];
        if let Some(group) = &drt_direct {
            steps.extend([
                ("drt clutter direct", &self.direct, group, [clutter_texels.div_ceil(64), 1, 1]),
                ("drt patches", &self.drt_patches, &g.drt_patches, [patches.div_ceil(64), 1, 1]),
                ("drt deltas and gather", &self.drt_rows, &g.drt_rows, [inpaint_from.div_ceil(64), 1, 1]),
                ("drt inpainting", &self.drt_rows, &g.drt_inpaint, [(rows - inpaint_from).div_ceil(64), 1, 1]),
            ]);
        }
        steps.extend([
            ("mrt sides", &self.sides, &g.sides, [(positions * positions).div_ceil(64), sides, 1]),
            ("mrt apply", &self.apply, &apply, [size.0.div_ceil(8), size.1.div_ceil(8), 1]),
        ]);
        for (name, pass, group, [x, y, z]) in steps {
            if x == 0 || y == 0 {
                continue;
            }
            let mut cp = inputs.compute_pass(name);
            cp.set_pipeline(&pass.pipeline);
            cp.set_bind_group(0, group, &[]);
            cp.dispatch_workgroups(x, y, z);
        }
        true
    }

    /// Reads a per-texel buffer ("l_d", "indirect", "within") as RGBA floats, "sides": the
    /// side texels (P^2 per partly open side, in the order of the level's side records), or the
    /// clutter texels' "clutter_radiance" or "clutter_gather" (E / pi).
    pub fn read_texels(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        which: &str,
    ) -> Option<Result<Vec<[f32; 4]>, readback::ReadbackError>> {
        let l = self.level.as_ref()?;
        let (buffer, skip) = match which {
            "l_d" => (&l.l_d, 0),
            "indirect" => (&l.indirect, 0),
            "within" => (&l.within, 0),
            "sides" => (&l.indirect, l.counts.counts[1] as usize),
            "clutter_radiance" => (&l.drt.radiance, 0),
            "clutter_gather" => (&l.drt.gather, 0),
            "drt_occlusion" => (&l.drt.occlusion, 0),
            "drt_reflection" => (&l.drt.reflection, 0),
            _ => return None,
        };
        let count = match which {
            "sides" => l.counts.sides[2] as usize,
            "clutter_radiance" | "clutter_gather" => l.drt.counts[0] as usize,
            _ => l.counts.counts[1] as usize,
        };
        Some(readback::read_buffer(device, queue, buffer).map(|bytes| {
            bytemuck::pod_collect_to_vec::<u8, [f32; 4]>(&bytes).into_iter().skip(skip).take(count).collect()
        }))
    }

    /// Reads the b coefficients (blocks x 6 face slots x k_b, rgb) or r (interfaces x k_r).
    pub fn read_coefficients(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        which: &str,
    ) -> Option<Result<Vec<[f32; 4]>, readback::ReadbackError>> {
        let l = self.level.as_ref()?;
        let buffer = if which == "b" { &l.b } else { &l.r };
        Some(readback::read_buffer(device, queue, buffer).map(|bytes| bytemuck::pod_collect_to_vec(&bytes)))
    }

    /// The view's block assignment target.
    pub fn assignment(&self) -> Option<&wgpu::Texture> {
        self.assignment.as_ref().map(|t| &t.texture)
    }

    /// Frees the buffers and targets (pipelines stay).
    pub fn release(&mut self) {
        self.level = None;
        self.level_groups = None;
        self.assignment = None;
    }

    /// Bytes of GPU memory held.
    pub fn gpu_bytes(&self) -> u64 {
        let level: u64 =
            self.level.as_ref().map_or(0, |l| l.all().iter().chain(l.drt.all().iter()).map(|b| b.size()).sum());
        level + self.assignment.as_ref().map_or(0, |t| crate::render::gi::technique::texture_bytes(&t.texture))
    }
}
