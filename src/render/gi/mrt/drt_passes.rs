//! DRT's GPU side (the runtime order of Loos 2015 §5.4 and §5.4.1), recorded by
//! [`super::passes::MrtPasses`] between the reconstruction (D) and the side texels (E): G0 the
//! clutter texels' radiance (the direct pass A's shader on the clutter texels, its feedback the
//! clutter's gathered light), G1 the patches' light (`drt_patches.wgsl`), G2 the delta and gather
//! rows, G3 the inpainting rows (`drt_rows.wgsl`). The apply pass reads the clutter's gathered
//! light for clutter pixels.

use super::drt_pack::{DrtGpuParams, DrtPacked};
use super::pack::GpuTexel;
use super::passes::{MrtParams, upload, vec4s};

/// A uniform buffer holding `data`.
fn uniform<T: bytemuck::Pod>(device: &wgpu::Device, label: &str, data: &T) -> wgpu::Buffer {
    use wgpu::util::DeviceExt;
    device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some(label),
        contents: bytemuck::bytes_of(data),
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
    })
}

/// A level's DRT buffers (present, and small, when the level has no clutter: the apply pass
/// binds them either way).
pub struct DrtBuffers {
    /// The direct pass's parameters over the clutter texels (their count, the feedback gain).
    pub direct_params: wgpu::Buffer,
    /// Patches; rows before inpainting; inpainting rows.
    pub patch_params: wgpu::Buffer,
    pub row_params: wgpu::Buffer,
    pub inpaint_params: wgpu::Buffer,
    pub clutter: wgpu::Buffer,
    pub texels: wgpu::Buffer,
    pub object_clutter: wgpu::Buffer,
    pub patches: wgpu::Buffer,
    pub rows: wgpu::Buffer,
    pub entries: wgpu::Buffer,
    /// Per frame: clutter texels' radiance, their gathered light (E / pi), the patches' light.
    pub radiance: wgpu::Buffer,
    pub gather: wgpu::Buffer,
    pub patch_light: wgpu::Buffer,
    /// Per block texel, the inspector's ΔU_b b (as the light hidden) and ΔU_c c.
    pub occlusion: wgpu::Buffer,
    pub reflection: wgpu::Buffer,
    /// Clutter texels, patches, rows before inpainting, all rows.
    pub counts: [u32; 4],
    /// The direct pass's parameters without the per-frame gain.
    pub direct: MrtParams,
}

impl DrtBuffers {
    /// Uploads `drt` (or the empty placeholders) for a level of `objects` scene objects and
    /// `block_texels` block texels.
    pub fn new(device: &wgpu::Device, drt: Option<&DrtPacked>, objects: usize, block_texels: usize) -> Self {
        let empty = DrtPacked { object_clutter: vec![super::pack::NONE; objects + 1], ..DrtPacked::default() };
        let d = drt.unwrap_or(&empty);
        let texels = d.texels.len() as u32;
        let patches = d.patches.len() as u32;
        let rows = d.rows.len() as u32;
        let direct = MrtParams { counts: [0, texels, 0, 0], ..MrtParams::default() };
        let zero_texel = [GpuTexel::default()];
        let zero_clutter = [super::drt_pack::GpuClutter::default()];
        let texel_data: &[GpuTexel] = if d.texels.is_empty() { &zero_texel } else { &d.texels };
        Self {
            direct_params: uniform(device, "drt clutter direct params", &direct),
            patch_params: uniform(device, "drt patch params", &DrtGpuParams { counts: [patches, 0, 0, texels] }),
            row_params: uniform(
                device,
                "drt row params",
                &DrtGpuParams { counts: [patches, 0, d.inpaint_from, texels] },
            ),
            inpaint_params: uniform(
                device,
                "drt inpaint params",
                &DrtGpuParams { counts: [patches, d.inpaint_from, rows, texels] },
            ),
            // One record at least: WGSL's array<Clutter> needs 48 bytes bound (the lookup never
            // reads it: no object names it).
            clutter: upload(device, "drt clutter boxes", if d.clutter.is_empty() { &zero_clutter } else { &d.clutter }),
            texels: upload(device, "drt clutter texels", texel_data),
            object_clutter: upload(device, "drt object clutter", &d.object_clutter),
            patches: upload(device, "drt patches", &d.patches),
            rows: upload(device, "drt rows", &d.rows),
            entries: upload(device, "drt entries", &d.entries),
            radiance: vec4s(device, "drt clutter radiance", d.texels.len()),
            gather: vec4s(device, "drt clutter gathered light", d.texels.len()),
            patch_light: vec4s(device, "drt patch light", d.patches.len()),
            occlusion: vec4s(device, "drt hidden light per block texel", if drt.is_some() { block_texels } else { 1 }),
            reflection: vec4s(
                device,
                "drt reflected light per block texel",
                if drt.is_some() { block_texels } else { 1 },
            ),
            counts: [texels, patches, d.inpaint_from, rows],
            direct,
        }
    }

    /// The buffers (GPU memory accounting).
    pub fn all(&self) -> [&wgpu::Buffer; 15] {
        [
            &self.direct_params,
            &self.patch_params,
            &self.row_params,
            &self.inpaint_params,
            &self.clutter,
            &self.texels,
            &self.object_clutter,
            &self.patches,
            &self.rows,
            &self.entries,
            &self.radiance,
            &self.gather,
            &self.patch_light,
            &self.occlusion,
            &self.reflection,
        ]
    }
}
