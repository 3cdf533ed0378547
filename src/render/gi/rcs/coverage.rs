//! Coverage detection (`rcs_coverage.wgsl`): after a splat, pixels with geometry that no record
//! reaches are uncovered; each 8 x 8 tile proposes the uncovered pixel nearest its centre. The
//! CPU reads the candidates back ([`order`] spreads a partial round over the view) and computes
//! the records, which are splatted at once (the notes' splat-on-create).

use bytemuck::{Pod, Zeroable};

use super::record::Candidate;
use super::store::Store;
use super::{entry, uniform};
use crate::render::gi::inputs::GiInputs;
use crate::render::gi::technique::texture_bytes;
use crate::render::layouts::{compute_pipeline, storage_rw_entry, storage_texture_entry, texture_entry, uniform_entry};
use crate::render::shaders::{self, ShaderError};
use crate::render::targets::Target;

/// Pixels per tile side.
pub const TILE: u32 = 8;

/// `CoverageParams` in `rcs_coverage.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct CoverageParams {
    /// x = round.
    pub round: [u32; 4],
}

const _: () = assert!(std::mem::size_of::<CoverageParams>() == 16);

/// Tiles of a view.
pub fn tiles(size: (u32, u32)) -> u32 {
    size.0.div_ceil(TILE) * size.1.div_ceil(TILE)
}

/// Candidates in the order records are made: by a hash of their tile, so that a round cut
/// short by the budget spreads its records over the whole view instead of filling the top rows
/// first, and the same view always picks the same records.
pub fn order(mut candidates: Vec<Candidate>) -> Vec<Candidate> {
    let key = |c: &Candidate| c.tile().wrapping_mul(0x9E37_79B9).rotate_left(13) ^ c.tile();
    candidates.sort_by_key(|c| (key(c), c.tile()));
    candidates
}

/// The coverage pipeline and its two masks (rounds alternate).
pub struct CoveragePass {
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
    params: Vec<wgpu::Buffer>,
    masks: Option<[Target; 2]>,
    /// The mask the last round wrote.
    last: usize,
}

impl CoveragePass {
    /// Creates the pipeline.
    pub fn new(device: &wgpu::Device) -> Result<Self, ShaderError> {
        let c = wgpu::ShaderStages::COMPUTE;
        let unfilterable = wgpu::TextureSampleType::Float { filterable: false };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("rcs coverage layout"),
            entries: &[
                uniform_entry(0, c, false),
                uniform_entry(1, c, false),
                texture_entry(2, c, wgpu::TextureSampleType::Depth),
                texture_entry(3, c, unfilterable),
                crate::render::layouts::storage_entry(4, c),
                texture_entry(5, c, unfilterable),
                storage_texture_entry(6, wgpu::TextureFormat::Rgba32Float),
                storage_rw_entry(7),
            ],
        });
        let module = shaders::module(device, "render/gi/rcs/rcs_coverage.wgsl")?;
        Ok(Self {
            pipeline: compute_pipeline(device, "rcs coverage", &layout, &module, "cs_main"),
            layout,
            params: Vec::new(),
            masks: None,
            last: 0,
        })
    }

    /// The masks for a view of `size` and params for `rounds` rounds.
    pub fn ensure(&mut self, device: &wgpu::Device, size: (u32, u32), rounds: u32) {
        while self.params.len() < rounds as usize + 1 {
            let label = format!("rcs coverage params {}", self.params.len());
            self.params.push(uniform(device, &label, std::mem::size_of::<CoverageParams>() as u64));
        }
        if self.masks.as_ref().is_some_and(|m| (m[0].texture.width(), m[0].texture.height()) == size) {
            return;
        }
        use wgpu::TextureUsages as U;
        let usage = U::STORAGE_BINDING | U::TEXTURE_BINDING | U::COPY_SRC;
        let f = wgpu::TextureFormat::Rgba32Float;
        self.masks = Some([
            Target::new(device, "rcs coverage mask a", size, f, usage),
            Target::new(device, "rcs coverage mask b", size, f, usage),
        ]);
    }

    /// The mask of the last round (r uncovered, g the round that placed a record, b geometry).
    pub fn mask(&self) -> Option<&Target> {
        self.masks.as_ref().map(|m| &m[self.last])
    }

    /// Finds this round's candidates (after the splat into `accum`) and copies them to the
    /// staging buffer.
    pub fn record(&mut self, inputs: &mut GiInputs<'_>, store: &Store, accum: &wgpu::Buffer, round: u32) {
        let (Some(masks), Some(params)) = (&self.masks, self.params.get(round as usize)) else { return };
        inputs.queue.write_buffer(params, 0, bytemuck::bytes_of(&CoverageParams { round: [round, 0, 0, 0] }));
        let (read, write) = if round.is_multiple_of(2) { (1, 0) } else { (0, 1) };
        inputs.encoder.clear_buffer(&store.candidates, 0, Some(16));
        let t = inputs.targets;
        let view = |b, v| wgpu::BindGroupEntry { binding: b, resource: wgpu::BindingResource::TextureView(v) };
        let bind_group = inputs.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("rcs coverage bind group"),
            layout: &self.layout,
            entries: &[
                entry(0, inputs.frame_buffer),
                entry(1, params),
                view(2, &t.depth.view),
                view(3, &t.normal.view),
                entry(4, accum),
                view(5, &masks[read].view),
                view(6, &masks[write].view),
                entry(7, &store.candidates),
            ],
        });
        let (w, h) = t.size;
        {
            let mut pass = inputs.compute_pass("rcs coverage");
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, &bind_group, &[]);
            pass.dispatch_workgroups(w.div_ceil(TILE), h.div_ceil(TILE), 1);
        }
        self.last = write;
        let l = store.layout;
        inputs.encoder.copy_buffer_to_buffer(&store.candidates, 0, &store.staging, l.candidates, l.candidates_len);
    }

    /// Frees the masks.
    pub fn release(&mut self) {
        self.masks = None;
    }

    /// Bytes held.
    pub fn gpu_bytes(&self) -> u64 {
        self.masks.as_ref().map_or(0, |m| m.iter().map(|t| texture_bytes(&t.texture)).sum())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The order is a permutation, the same for any input order, and its first quarter reaches
    /// every quarter of the tile range (a short round spreads).
    #[test]
    fn the_order_is_stable_and_spreads_a_partial_round() {
        let make = |tiles: &[u32]| -> Vec<Candidate> {
            tiles
                .iter()
                .map(|&t| Candidate { normal: [0.0, 1.0, 0.0, f32::from_bits(t)], ..Default::default() })
                .collect()
        };
        let forward: Vec<u32> = (0..400).collect();
        let backward: Vec<u32> = (0..400).rev().collect();
        let a: Vec<u32> = order(make(&forward)).iter().map(Candidate::tile).collect();
        let b: Vec<u32> = order(make(&backward)).iter().map(Candidate::tile).collect();
        assert_eq!(a, b);
        let mut sorted = a.clone();
        sorted.sort_unstable();
        assert_eq!(sorted, forward);
        for q in 0..4 {
            assert!(a[..100].iter().any(|t| t / 100 == q), "quarter {q} missing from the first 100");
        }
    }
}
