//! A level's DRT (`precompute::drt`) laid out for the GPU: the clutter boxes and texels, which
//! object is which clutter, the patches the operators read, and the operators' sparse rows
//! (`drt_patches.wgsl`, `drt_rows.wgsl`, and the apply pass's clutter lookup).

use bytemuck::{Pod, Zeroable};

use super::pack::{GpuTexel, NONE};
use crate::precompute::drt::Drt;

/// One clutter object (`Clutter` in `mrt_apply.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct GpuClutter {
    /// World bounding box minimum, w unused.
    pub lo: [f32; 4],
    /// Maximum, w unused.
    pub hi: [f32; 4],
    /// First texel, texels per face side, unused x2.
    pub texels: [u32; 4],
}

const _: () = assert!(std::mem::size_of::<GpuClutter>() == 48);

/// `DrtParams` in `drt_rows.wgsl` and `drt_patches.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct DrtGpuParams {
    /// Patches, first row, end row, clutter texels.
    pub counts: [u32; 4],
}

const _: () = assert!(std::mem::size_of::<DrtGpuParams>() == 16);

/// Everything DRT uploads.
#[derive(Clone, Debug, Default)]
pub struct DrtPacked {
    pub clutter: Vec<GpuClutter>,
    /// Clutter texels (normal.w = the clutter record).
    pub texels: Vec<GpuTexel>,
    /// Per scene object its clutter record, or [`NONE`]; one [`NONE`] past the end.
    pub object_clutter: Vec<u32>,
    pub patches: Vec<[u32; 4]>,
    pub rows: Vec<[u32; 4]>,
    pub entries: Vec<[u32; 2]>,
    /// First inpainting row.
    pub inpaint_from: u32,
    /// Per block texel: covered by clutter (the inspector's inpainting mask).
    pub covered: Vec<bool>,
    /// Clutter objects found automatically / marked.
    pub automatic: usize,
    pub marked: usize,
    /// Rays traced, build time (ms).
    pub traced: u64,
    pub millis: f64,
}

impl DrtPacked {
    /// Lays out `drt`.
    pub fn new(drt: &Drt) -> Self {
        let res = drt.res as u32;
        let clutter = drt
            .clutter
            .iter()
            .map(|c| GpuClutter {
                lo: c.lo.extend(0.0).to_array(),
                hi: c.hi.extend(0.0).to_array(),
                texels: [c.first as u32, res, 0, 0],
            })
            .collect();
        let per = 6 * drt.res * drt.res;
        let texels = drt
            .texels
            .iter()
            .enumerate()
            .map(|(i, t)| GpuTexel {
                position: t.position.extend(if t.found { 1.0 } else { 0.0 }).to_array(),
                normal: t.normal.extend((i / per.max(1)) as f32).to_array(),
                albedo: t.albedo.extend(0.0).to_array(),
                emission: t.emission.extend(0.0).to_array(),
            })
            .collect();
        let mut object_clutter: Vec<u32> = drt.clutter_of.iter().map(|c| c.map_or(NONE, |k| k as u32)).collect();
        object_clutter.push(NONE);
        let automatic = drt.why.iter().filter(|w| **w == crate::precompute::drt::Why::Automatic).count();
        Self {
            clutter,
            texels,
            object_clutter,
            patches: drt.operators.patches.clone(),
            rows: drt.operators.rows.clone(),
            entries: drt.operators.entries.clone(),
            inpaint_from: drt.operators.inpaint_from as u32,
            covered: drt.operators.covered.clone(),
            automatic,
            marked: drt.why.len() - automatic,
            traced: drt.operators.traced,
            millis: drt.millis,
        }
    }

    /// Bytes uploaded.
    pub fn bytes(&self) -> u64 {
        (48 * self.clutter.len()
            + 48 * self.texels.len()
            + 4 * self.object_clutter.len()
            + 16 * (self.patches.len() + self.rows.len())
            + 8 * self.entries.len()) as u64
    }
}
