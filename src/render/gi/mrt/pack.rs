//! A level and its dictionary laid out for MRT's GPU runtime (the per-face records of Loos 2015
//! §4.4.1 as storage buffers): every block texel's geometry-image surface, one record per block
//! (its box, its faces' texel ranges, the interfaces entering it), the dictionary elements'
//! T_{d->b} and U_b, the surface response U_r, the level's sparse T_{b->r} as k_r x k_b matrices
//! grouped by the directed interface they feed, and, per entering interface, the response row of
//! each of the receiving block's texels. Built on the CPU whenever the blocks or the geometry
//! change (the suite's 11-block rooms: tens of milliseconds), uploaded once, read every frame.

use bytemuck::{Pod, Zeroable};

use crate::precompute::bvh::SceneBvh;
use crate::precompute::mrt::dictionary::Dictionary;
use crate::precompute::mrt::geometry_image::{TexelSurface, geometry_image};
use crate::precompute::mrt::level::{self, Level, Operators};
use crate::precompute::mrt::shape::{Face, Layout, Shape};
use crate::scene::Scene;

/// "None" in the index tables.
pub const NONE: u32 = u32::MAX;

/// One texel's real surface (`Texel` in `mrt_common.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct GpuTexel {
    /// World position, w = 1 where a real surface was found.
    pub position: [f32; 4],
    /// Unit normal facing into the block, w = the block's index.
    pub normal: [f32; 4],
    /// Albedo, w unused.
    pub albedo: [f32; 4],
    /// Radiance the texel sends on its own (an emissive front face, or the sky through a hole
    /// in the face), w unused.
    pub emission: [f32; 4],
}

const _: () = assert!(std::mem::size_of::<GpuTexel>() == 64);

/// One block (`Block` in `mrt_common.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct GpuBlock {
    /// Minimum corner, w = quarter turns about up.
    pub origin: [f32; 4],
    /// Size along world x, y, z; w unused.
    pub size: [f32; 4],
    /// First texel, texel count n, offset of its element's T_{d->b} (k_b x n) and of its U_b
    /// (n x k_b) in the matrix buffers.
    pub texels: [u32; 4],
    /// Per canonical face (-x, +x, -y, +y, -z, +z of the unit cube, then two unused): its first
    /// texel, or [`NONE`] where it is open.
    pub starts: [u32; 8],
    /// Per world side: the canonical face on that side (`Face` as u32).
    pub local: [u32; 8],
    /// The directed interfaces entering this block (slot indices, [`NONE`] for none).
    pub slots: [u32; 4],
    /// Per canonical face: the block beyond it where it is an opening open over its whole area
    /// (the lookup pads across it), else [`NONE`].
    pub across: [u32; 8],
    /// Per world side: the first of its P^2 side texels (in the indirect buffer) where it is
    /// partly open (the wall around a doorway), else [`NONE`].
    pub sides: [u32; 8],
}

const _: () = assert!(std::mem::size_of::<GpuBlock>() == 192);

/// The share of a linked side that must be open for the lookup to pad across it: a doorway in
/// a room's whole side is not, and padding there would carry light through the wall beside it.
pub const PAD_OPEN: f64 = 0.95;

/// One directed interface's record (`Slot`): its first entry, entry count, receiving block, and
/// where its response rows start in `rows`.
pub type GpuSlot = [u32; 4];

/// One T_{b->r} matrix (`Entry`): source block, offset of its k_r x k_b matrix, unused x2.
/// The side matrices' entries are laid out alike (P^2 x k_b).
pub type GpuEntry = [u32; 4];

/// One partly open side's record: its first side entry, entry count, first side texel (in the
/// indirect buffer, after the block texels), block.
pub type GpuSide = [u32; 4];

/// Everything the runtime uploads.
#[derive(Clone, Debug, Default)]
pub struct Packed {
    /// Per texel, block after block.
    pub texels: Vec<GpuTexel>,
    /// Per block.
    pub blocks: Vec<GpuBlock>,
    /// The elements' T_{d->b}, then their U_b (row-major, f32).
    pub matrices: Vec<f32>,
    /// U_r (n_r x k_r).
    pub u_r: Vec<f32>,
    /// The T_{b->r} matrices (k_r x k_b each).
    pub transfer: Vec<f32>,
    /// Per T_{b->r} matrix, grouped by slot.
    pub entries: Vec<GpuEntry>,
    /// Per directed interface.
    pub slots: Vec<GpuSlot>,
    /// Response row per texel of each slot's receiving block ([`NONE`] on the entry side).
    pub rows: Vec<u32>,
    /// The stretch correction of the entering light per texel of `rows`.
    pub row_scales: Vec<f32>,
    /// Per block, the stretch corrections of its own light, `[emitting slot][receiving slot]`
    /// (36 each; `level::own_scales`).
    pub own_scales: Vec<f32>,
    /// Per scene object, the block its surfaces read (an artist's override), or [`NONE`]
    /// (the nearest block to each point).
    pub object_block: Vec<u32>,
    /// Per partly open side ([`level::Transfer::sides`]).
    pub sides: Vec<GpuSide>,
    /// Per side matrix, grouped by side.
    pub side_entries: Vec<GpuEntry>,
    /// The side matrices (P^2 x k_b each).
    pub side_matrices: Vec<f32>,
    /// Opening positions per side P (a side's P^2 texels, u across, v up).
    pub positions: u32,
    /// Modes per block k_b, response modes k_r, texels per face side, texels with a surface.
    pub k_b: u32,
    pub k_r: u32,
    pub res: u32,
    pub surfaces_found: u32,
    /// Delta radiance transfer for the level's clutter (none when off or without clutter).
    pub drt: Option<super::drt_pack::DrtPacked>,
}

impl Packed {
    /// Bytes uploaded.
    pub fn bytes(&self) -> u64 {
        let words = self.matrices.len()
            + self.u_r.len()
            + self.transfer.len()
            + self.rows.len()
            + self.row_scales.len()
            + self.own_scales.len()
            + self.side_matrices.len();
        (std::mem::size_of_val(self.texels.as_slice())
            + std::mem::size_of_val(self.blocks.as_slice())
            + 16 * (self.entries.len() + self.slots.len() + self.sides.len() + self.side_entries.len())
            + 4 * words) as u64
            + self.drt.as_ref().map_or(0, |d| d.bytes())
    }
}

/// Lays out `level` with `dictionary`'s operators, propagated `depth` blocks, its texels' real
/// surfaces from `scene` (traced in `bvh`).
pub fn pack(scene: &Scene, bvh: &SceneBvh, level: &Level, dictionary: &Dictionary, depth: usize) -> Packed {
    let res = dictionary.params.res;
    let ops = Operators { dictionary, interfaces: &dictionary.interfaces };
    let transfer = level::assemble(level, &ops, depth);
    let mut p = Packed {
        k_b: dictionary.params.k_b as u32,
        k_r: dictionary.interfaces.response.k_r as u32,
        res: res as u32,
        ..Packed::default()
    };
    let (k_b, elements) = pack_elements(&mut p, dictionary);
    p.u_r = dictionary.interfaces.response.u_r.iter().map(|v| *v as f32).collect();
    let slot_of = pack_slots(&mut p, level, &transfer, res, k_b);
    let side_first = pack_sides(&mut p, level, &transfer, dictionary, res, k_b);
    let offsets = Offsets { elements, slot_of, side_first };
    let sky = scene.sky_texels();
    for (bi, b) in level.blocks.iter().enumerate() {
        let layout = Layout::new(b.shape, res);
        let first = pack_texels(&mut p, scene, sky.as_deref(), bvh, level, bi, res);
        p.blocks.push(block_record(level, bi, &layout, first, &offsets));
    }
    end_tables(&mut p);
    p
}

/// Where the stages before the blocks' records put what those records point at.
struct Offsets {
    /// Per dictionary element: its shape, the offsets of its T_{d->b} and its U_b in `matrices`.
    elements: Vec<(Shape, u32, u32)>,
    /// Per directed interface (receiving block, entry side): its slot.
    slot_of: Vec<((usize, Face), u32)>,
    /// Per partly open side (block, world side): its first side texel.
    side_first: Vec<((usize, Face), u32)>,
}

/// Lays out the elements' matrices: T_{d->b} then U_b, each element once, every one with the
/// largest element's k_b modes (an element the precompute gave fewer modes gets zero rows and
/// columns), so that one stride serves the GPU and the products equal the CPU's. Returns that
/// k_b and each element's offsets.
fn pack_elements(p: &mut Packed, dictionary: &Dictionary) -> (usize, Vec<(Shape, u32, u32)>) {
    let k_b = dictionary.elements.iter().map(|e| e.k_b).max().unwrap_or(0);
    p.k_b = k_b as u32;
    let mut offsets = Vec::new();
    for e in &dictionary.elements {
        let t = p.matrices.len() as u32;
        for j in 0..k_b {
            p.matrices.extend((0..e.n).map(|i| if j < e.k_b { e.t_db[j * e.n + i] as f32 } else { 0.0 }));
        }
        let u = p.matrices.len() as u32;
        for i in 0..e.n {
            p.matrices.extend((0..k_b).map(|j| if j < e.k_b { e.u_b[i * e.k_b + j] as f32 } else { 0.0 }));
        }
        offsets.push((e.shape, t, u));
    }
    (k_b, offsets)
}

/// Lays out the directed interfaces (receiver, entry side) in a fixed order: per interface a
/// slot with its receiving block's response rows and their stretch corrections, then the
/// T_{b->r} matrices feeding it (k_r x k_b(source), laid out with the common `k_b` stride).
/// Returns each interface's slot, which the blocks' records list.
fn pack_slots(
    p: &mut Packed,
    level: &Level,
    transfer: &level::Transfer,
    res: usize,
    k_b: usize,
) -> Vec<((usize, Face), u32)> {
    let mut keys: Vec<(usize, usize, Face)> = transfer.blocks.keys().copied().collect();
    keys.sort_by_key(|(x, y, f)| (*y, *f as usize, *x));
    let mut slot_of: Vec<((usize, Face), u32)> = Vec::new();
    for (x, y, f) in keys {
        let Some(m) = transfer.blocks.get(&(x, y, f)) else { continue };
        if slot_of.last().is_none_or(|(k, _)| *k != (y, f)) {
            let rows_at = p.rows.len() as u32;
            let rows = level::response_rows(&level.blocks[y], f, res);
            p.rows.extend(rows.iter().map(|r| r.map_or(NONE, |r| r as u32)));
            p.row_scales.extend(level::response_scales(level, y, f, res).iter().map(|v| *v as f32));
            slot_of.push(((y, f), p.slots.len() as u32));
            p.slots.push([p.entries.len() as u32, 0, y as u32, rows_at]);
        }
        if let Some(slot) = p.slots.last_mut() {
            slot[1] += 1;
        }
        p.entries.push([x as u32, p.transfer.len() as u32, 0, 0]);
        // k_r x k_b(source), laid out with the common k_b stride.
        let source = m.len() / (p.k_r as usize).max(1);
        for i in 0..p.k_r as usize {
            p.transfer.extend((0..k_b).map(|j| if j < source { m[i * source + j] as f32 } else { 0.0 }));
        }
    }
    slot_of
}

/// Lays out the partly open sides (the wall around a doorway, which has no texels of its own):
/// their P^2 texels follow the block texels in the indirect buffer; per side a record, then its
/// side matrices (P^2 x k_b(source), with the common `k_b` stride). Returns each side's first
/// side texel, which its block's record points at.
fn pack_sides(
    p: &mut Packed,
    level: &Level,
    transfer: &level::Transfer,
    dictionary: &Dictionary,
    res: usize,
    k_b: usize,
) -> Vec<((usize, Face), u32)> {
    p.positions = dictionary.interfaces.positions.positions as u32;
    let per_side = (p.positions * p.positions) as usize;
    let block_texels: usize = level.blocks.iter().map(|b| Layout::new(b.shape, res).len()).sum();
    let mut side_keys: Vec<(usize, Face, usize)> = transfer.sides.keys().map(|(src, x, w)| (*x, *w, *src)).collect();
    side_keys.sort_by_key(|(x, w, src)| (*x, *w as usize, *src));
    let mut side_first: Vec<((usize, Face), u32)> = Vec::new();
    for (x, w, src) in side_keys {
        let Some(m) = transfer.sides.get(&(src, x, w)) else { continue };
        if side_first.last().is_none_or(|(k, _)| *k != (x, w)) {
            let first = (block_texels + p.sides.len() * per_side) as u32;
            side_first.push(((x, w), first));
            p.sides.push([p.side_entries.len() as u32, 0, first, x as u32]);
        }
        if let Some(side) = p.sides.last_mut() {
            side[1] += 1;
        }
        p.side_entries.push([src as u32, p.side_matrices.len() as u32, 0, 0]);
        let source = m.len() / per_side.max(1);
        for i in 0..per_side {
            p.side_matrices.extend((0..k_b).map(|j| if j < source { m[i * source + j] as f32 } else { 0.0 }));
        }
    }
    side_first
}

/// Appends block `bi`'s texels (their real surfaces, traced in the geometry image, `sky` letting
/// in through holes) and its own light's stretch corrections; returns its first texel, which its
/// record points at.
fn pack_texels(
    p: &mut Packed,
    scene: &Scene,
    sky: Option<&crate::scene::SkyImage>,
    bvh: &SceneBvh,
    level: &Level,
    bi: usize,
    res: usize,
) -> u32 {
    let b = &level.blocks[bi];
    let first = p.texels.len() as u32;
    let surfaces: Vec<TexelSurface> = geometry_image(scene, sky, bvh, b, res);
    p.own_scales.extend(level::own_scales(level, bi).iter().flatten().map(|v| *v as f32));
    for s in &surfaces {
        p.surfaces_found += u32::from(s.found);
        p.texels.push(GpuTexel {
            position: s.position.extend(if s.found { 1.0 } else { 0.0 }).to_array(),
            normal: s.normal.extend(bi as f32).to_array(),
            albedo: s.albedo.extend(0.0).to_array(),
            emission: s.emission.extend(0.0).to_array(),
        });
    }
    first
}

/// Block `bi`'s record: its box, its texels and element's matrices, its faces' first texels and
/// world sides, and what the lookup and the runtime reach from it (the blocks across its fully
/// open faces, its partly open sides, the interfaces entering it).
fn block_record(level: &Level, bi: usize, layout: &Layout, first: u32, offsets: &Offsets) -> GpuBlock {
    let b = &level.blocks[bi];
    // Every dictionary has all six shapes (`dictionary::build`); a block of a missing one
    // would read the first element's matrices.
    let (t, u) = offsets.elements.iter().find(|o| o.0 == b.shape).map_or((0, 0), |o| (o.1, o.2));
    let (starts, local) = face_tables(b, layout, first);
    let across = pad_across(level, bi);
    let mut sides = [NONE; 8];
    for ((x, w), first) in &offsets.side_first {
        if *x == bi {
            sides[*w as usize] = *first;
        }
    }
    let mut slots = [NONE; 4];
    for (k, (_, s)) in offsets.slot_of.iter().filter(|((y, _), _)| *y == bi).take(4).enumerate() {
        slots[k] = *s;
    }
    GpuBlock {
        origin: b.origin.extend(f32::from(b.turns % 4)).to_array(),
        size: b.size.extend(0.0).to_array(),
        texels: [first, layout.len() as u32, t, u],
        starts,
        local,
        slots,
        across,
        sides,
    }
}

/// Per canonical face its first texel ([`NONE`] where open), and per world side the canonical
/// face on it: how the runtime finds a world side's texels in a turned block.
fn face_tables(b: &level::Block, layout: &Layout, first: u32) -> ([u32; 8], [u32; 8]) {
    let mut starts = [NONE; 8];
    let mut local = [0; 8];
    for (k, w) in Face::ALL.iter().enumerate() {
        let f = b.local_face(*w);
        local[k] = f as u32;
        starts[f as usize] = layout.face_start(f).map_or(NONE, |s| first + s as u32);
    }
    (starts, local)
}

/// Per canonical face of block `bi`, the block beyond it where it is linked and open over at
/// least [`PAD_OPEN`] of its area, else [`NONE`]: where the lookup may pad across.
fn pad_across(level: &Level, bi: usize) -> [u32; 8] {
    let b = &level.blocks[bi];
    let mut across = [NONE; 8];
    for f in b.shape.open_faces() {
        let w = b.world_face(*f);
        if let Some(j) = level.link(bi, w).filter(|_| level.transmission(bi, w) >= PAD_OPEN) {
            across[*f as usize] = j as u32;
        }
    }
    across
}

/// Ends each index table with one NONE: wgpu refuses empty bindings and the upload pads short
/// ones with zeros, which an index table would read as "block 0" or "row 0".
fn end_tables(p: &mut Packed) {
    p.rows.push(NONE);
    p.row_scales.push(0.0);
    p.object_block.push(NONE);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::precompute::mrt::dictionary::{Progress, build, test_params};
    use crate::precompute::mrt::level::Block;
    use crate::precompute::mrt::shape::Shape;

    #[test]
    fn a_corridor_packs_its_texels_slots_and_response_rows() {
        let d = build(&test_params(), &Progress::default()).expect("dictionary");
        let blocks = vec![
            Block::unit(Shape::DeadEnd, [0, 0, 0], 0),
            Block::unit(Shape::Corridor, [0, 0, 1], 0),
            Block::unit(Shape::DeadEnd, [0, 0, 2], 2),
        ];
        let level = Level::new(blocks);
        assert_eq!(level.link_count(), 4, "two doorways, both directions");
        let scene = Scene::new(Default::default(), Default::default()).expect("empty scene");
        let bvh = SceneBvh::build(&scene);
        let p = pack(&scene, &bvh, &level, &d, 4);
        let n = |s: Shape| Layout::new(s, 3).len();
        assert_eq!(p.texels.len(), 2 * n(Shape::DeadEnd) + n(Shape::Corridor));
        assert_eq!(p.surfaces_found, 0, "an empty scene has no surfaces");
        // Each directed interface is fed by every block whose light reaches it.
        assert_eq!(p.slots.len(), 4);
        let fed: u32 = p.slots.iter().map(|s| s[1]).sum();
        assert_eq!(fed as usize, p.entries.len());
        assert!(p.entries.len() >= 4);
        // Each slot's rows cover its receiving block, the entry side excluded.
        for s in &p.slots {
            let b = &p.blocks[s[2] as usize];
            let rows = &p.rows[s[3] as usize..(s[3] + b.texels[1]) as usize];
            let n_r = d.interfaces.response.n as u32;
            assert!(rows.iter().all(|r| *r < n_r), "the entry side is open: every texel has a response row");
            let scales = &p.row_scales[s[3] as usize..(s[3] + b.texels[1]) as usize];
            assert!(scales.iter().all(|v| (v - 1.0).abs() < 1e-6), "unit blocks need no stretch correction");
            assert!(b.slots.contains(&(p.slots.iter().position(|x| x == s).expect("slot") as u32)));
        }
        // The middle block's open sides have no texels.
        let mid = &p.blocks[1];
        assert_eq!(mid.starts.iter().take(6).filter(|s| **s == NONE).count(), 2);
        assert_eq!(p.transfer.len(), p.entries.len() * (p.k_b * p.k_r) as usize);
    }
}
