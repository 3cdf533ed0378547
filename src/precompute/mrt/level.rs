//! An MRT level: dictionary blocks, each a box (the unit cube warped to its size, Loos 2015
//! §3.5.2) turned a number of quarter turns about up, joined where two neighbours' open sides
//! lie on one plane and overlap (§3.5.3, §4.3.2). This module finds the links and, from the
//! transfer [`super::transfer`] assembles, evaluates a frame's indirect light from the blocks'
//! direct light in the reduced spaces, and, for tests and the inspector, gathers the same bounce by
//! brute force through the level's blocks.

use std::collections::HashMap;

use glam::Vec3;

use super::dictionary::Dictionary;
use super::gather::{cosine_rays, ray_count};
use super::opening::Opening;
use super::operators::Interfaces;
use super::propagate::{ENTRY, Turn};
use super::response;
use super::shape::{Face, Layout, Shape, exit};
pub use super::transfer::{Transfer, assemble};
use super::warp::Warp;
use crate::precompute::rng::Pcg32;

/// One block: a dictionary shape turned `turns` quarter turns about up (each maps +x to -z, as
/// [`Face::rotated_about_up`]) and stretched to the world box `origin .. origin + size`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Block {
    /// The dictionary shape.
    pub shape: Shape,
    /// The box's minimum corner (world).
    pub origin: Vec3,
    /// The box's size along world x, y, z.
    pub size: Vec3,
    /// Quarter turns about up, 0..4.
    pub turns: u8,
}

/// A vector turned `q` quarter turns about up: (x, y, z) -> (z, y, -x) per turn.
fn turn_vec(v: Vec3, q: u8) -> Vec3 {
    (0..q % 4).fold(v, |v, _| Vec3::new(v.z, v.y, -v.x))
}

impl Block {
    /// The world side of the block's canonical face `f`.
    pub fn world_face(&self, f: Face) -> Face {
        f.turned(self.turns)
    }

    /// The canonical face on world side `w`.
    pub fn local_face(&self, w: Face) -> Face {
        w.turned((4 - self.turns % 4) % 4)
    }

    /// A unit block at the grid cell `cell`.
    pub fn unit(shape: Shape, cell: [i32; 3], turns: u8) -> Self {
        let origin = Vec3::new(cell[0] as f32, cell[1] as f32, cell[2] as f32);
        Self { shape, origin, size: Vec3::ONE, turns }
    }

    /// A canonical point in world space.
    pub fn world_point(&self, p: Vec3) -> Vec3 {
        let c = Vec3::new(0.5, 0.0, 0.5);
        self.origin + (c + turn_vec(p - c, self.turns)) * self.size
    }

    /// A world point in the block's canonical frame.
    pub fn local_point(&self, w: Vec3) -> Vec3 {
        let c = Vec3::new(0.5, 0.0, 0.5);
        c + turn_vec((w - self.origin) / self.size - c, (4 - self.turns % 4) % 4)
    }

    /// A canonical direction in world space (unit length).
    pub fn world_dir(&self, d: Vec3) -> Vec3 {
        (turn_vec(d, self.turns) * self.size).normalize_or_zero()
    }

    /// A world direction in the canonical frame (unit length).
    pub fn local_dir(&self, d: Vec3) -> Vec3 {
        turn_vec(d / self.size, (4 - self.turns % 4) % 4).normalize_or_zero()
    }

    /// The world rectangle of world side `w`: its plane coordinate and its extent over the two
    /// other axes (min, max).
    fn side(&self, w: Face) -> (f32, Vec3, Vec3) {
        let a = w.axis();
        let plane = if w.positive() { self.origin[a] + self.size[a] } else { self.origin[a] };
        (plane, self.origin, self.origin + self.size)
    }
}

/// A level's blocks and the links between them.
#[derive(Clone, Debug)]
pub struct Level {
    /// The blocks.
    pub blocks: Vec<Block>,
    /// (block, world side) -> the neighbour light passes into.
    links: HashMap<(usize, Face), usize>,
    /// Per block, the flux correction of its stretch ([`super::warp`]).
    pub warps: Vec<Warp>,
    /// (block, world side) -> what the real level leaves open of the linked side, per position
    /// (fully open unless set: a doorway in a side as tall as the room passes light only where
    /// it is, and the wall around it reflects).
    openings: HashMap<(usize, Face), Opening>,
}

/// Whether block `a`'s world side `w` and block `b`'s opposite side lie on one plane (within
/// `tol`) and overlap over an area.
fn facing(a: &Block, b: &Block, w: Face, tol: f32) -> bool {
    let (pa, lo_a, hi_a) = a.side(w);
    let (pb, lo_b, hi_b) = b.side(w.opposite());
    if (pa - pb).abs() > tol {
        return false;
    }
    (0..3).filter(|&k| k != w.axis()).all(|k| hi_a[k].min(hi_b[k]) - lo_a[k].max(lo_b[k]) > tol)
}

impl Level {
    /// The level of `blocks`: two blocks are linked through a side when both leave it open and
    /// the two sides face each other (same plane within 1 cm or 1% of the smaller block,
    /// overlapping).
    pub fn new(blocks: Vec<Block>) -> Self {
        let mut links = HashMap::new();
        for (i, b) in blocks.iter().enumerate() {
            for &f in b.shape.open_faces() {
                let w = b.world_face(f);
                let found = blocks.iter().enumerate().find(|(j, o)| {
                    let tol = (0.01 * b.size.min_element().min(o.size.min_element())).max(0.01);
                    *j != i && o.shape.is_open(o.local_face(w.opposite())) && facing(b, o, w, tol)
                });
                if let Some((j, _)) = found {
                    links.insert((i, w), j);
                }
            }
        }
        let mut warps: Vec<Warp> = Vec::with_capacity(blocks.len());
        for (i, b) in blocks.iter().enumerate() {
            // Blocks of one size and shape share their correction.
            let same = blocks[..i].iter().position(|o| o.size == b.size && o.shape == b.shape && o.turns == b.turns);
            let present: Vec<Face> = b.shape.present_faces().into_iter().map(|f| b.world_face(f)).collect();
            warps.push(same.map_or_else(|| Warp::new(b.size, &present), |j| warps[j]));
        }
        Self { blocks, links, warps, openings: HashMap::new() }
    }

    /// The level without the stretch correction: the dissertation's plain warp (for
    /// comparisons).
    pub fn without_warp_correction(mut self) -> Self {
        self.warps.iter_mut().for_each(|w| *w = Warp::NONE);
        self
    }

    /// Sets what the real level leaves open of linked side `w` of block `i`.
    pub fn set_opening(&mut self, i: usize, w: Face, opening: Opening) {
        self.openings.insert((i, w), opening);
    }

    /// What the real level leaves open of linked side `w` of block `i` (`None`: all of it).
    pub fn opening(&self, i: usize, w: Face) -> Option<&Opening> {
        self.openings.get(&(i, w))
    }

    /// Every partly open side set with [`Level::set_opening`].
    pub fn openings(&self) -> impl Iterator<Item = (&(usize, Face), &Opening)> {
        self.openings.iter()
    }

    /// The share of linked side `w` of block `i` that light passes.
    pub fn transmission(&self, i: usize, w: Face) -> f64 {
        self.openings.get(&(i, w)).map_or(1.0, Opening::share)
    }

    /// Every linked (block, world side), in a fixed order.
    pub fn linked_sides(&self) -> Vec<(usize, Face)> {
        let mut v: Vec<(usize, Face)> = self.links.keys().copied().collect();
        v.sort();
        v
    }

    /// The world rectangle of block `i`'s side `w`: its plane coordinate and the box's corners.
    pub fn side_rect(&self, i: usize, w: Face) -> (f32, Vec3, Vec3) {
        self.blocks[i].side(w)
    }

    /// Open sides that lead nowhere (block, world side): light leaves the level there.
    pub fn unlinked(&self) -> Vec<(usize, Face)> {
        let mut out = Vec::new();
        for (i, b) in self.blocks.iter().enumerate() {
            for &f in b.shape.open_faces() {
                let w = b.world_face(f);
                if self.link(i, w).is_none() {
                    out.push((i, w));
                }
            }
        }
        out
    }

    /// The neighbour beyond block `i`'s world side `w`, if linked.
    pub fn link(&self, i: usize, w: Face) -> Option<usize> {
        self.links.get(&(i, w)).copied()
    }

    /// Number of links (each opening counts twice, once per direction).
    pub fn link_count(&self) -> usize {
        self.links.len()
    }

    /// Where a ray from canonical point `p` of block `i` along canonical direction `d` first
    /// meets a wall, crossing linked openings: (block, canonical face, s, t, world distance);
    /// `None` when it leaves the level through an unlinked opening or runs past `max_dist`
    /// (world units).
    pub fn trace(&self, i: usize, p: Vec3, d: Vec3, max_dist: f32) -> Option<(usize, Face, f32, f32, f32)> {
        let (mut block, mut p, mut d, mut travelled) = (i, p, d, 0.0f32);
        for _ in 0..4 * self.blocks.len() + 4 {
            let b = self.blocks[block];
            let (face, s, t, dist) = exit(p, d);
            let world = b.world_point(p + d * dist);
            let step = (world - b.world_point(p)).length();
            if travelled + step > max_dist {
                return None;
            }
            if !b.shape.is_open(face) {
                return Some((block, face, s, t, travelled + step));
            }
            let w = b.world_face(face);
            let next = self.link(block, w)?;
            let world_dir = b.world_dir(d);
            let nb = self.blocks[next];
            // Step just past the shared side so the next block's exit is not the side itself.
            p = nb.local_point(world + world_dir * 1e-5).clamp(Vec3::ZERO, Vec3::ONE);
            d = nb.local_dir(world_dir);
            travelled += step;
            block = next;
        }
        None
    }
}

/// The turn from entry side `entry` to exit side `exit` (world sides of one block), or `None`
/// where the exit is the entry itself.
pub fn turn_between(entry: Face, exit: Face) -> Option<Turn> {
    let q = (0..4u8).find(|&q| entry.turned(q) == ENTRY)?;
    match exit.turned(q) {
        f if f == Turn::Ahead.exit() => Some(Turn::Ahead),
        f if f == Turn::Left.exit() => Some(Turn::Left),
        f if f == Turn::Right.exit() => Some(Turn::Right),
        _ => None,
    }
}

/// The operators a level's transfer is assembled from.
pub struct Operators<'a> {
    /// The dictionary.
    pub dictionary: &'a Dictionary,
    /// The interface operators.
    pub interfaces: &'a Interfaces,
}

/// For block `block` entered through world side `entry`: each of its samples' row in the
/// surface response's layout (`None` on the entry side itself).
pub fn response_rows(block: &Block, entry: Face, res: usize) -> Vec<Option<usize>> {
    let layout = Layout::new(block.shape, res);
    let target = response::layout(res);
    let local_entry = block.local_face(entry);
    let q = (0..4u8).find(|&q| local_entry.turned(q) == ENTRY).unwrap_or(0);
    (0..layout.len())
        .map(|i| {
            let (face, _, p, _) = layout.sample(i);
            if face == local_entry {
                return None;
            }
            let c = Vec3::new(0.5, 0.0, 0.5);
            let p = c + turn_vec(p - c, q);
            let f = face.turned(q);
            let (a, b) = f.plane_axes();
            let taps = target.bilinear(f, p[a], p[b])?;
            taps.iter().max_by(|x, y| x.1.total_cmp(&y.1)).map(|t| t.0)
        })
        .collect()
}

/// Block `x`'s indirect light from its own direct light `l`, face by face: each present face's
/// share of b (T_{d->b} over that face's texels) reconstructed by U_b and scaled, on each
/// receiving face, by the stretch correction of light leaving the emitting face
/// ([`Warp::through`]: exact in flux for diffuse walls, which the block's own light is).
pub fn own_light(level: &Level, x: usize, e: &super::basis::Element, l: &[f64], res: usize) -> Vec<f64> {
    let layout = Layout::new(level.blocks[x].shape, res);
    let per = res * res;
    let scales = own_scales(level, x);
    let mut own = vec![0.0; layout.len()];
    for g in 0..layout.faces.len() {
        let mut lg = vec![0.0; layout.len()];
        lg[g * per..(g + 1) * per].copy_from_slice(&l[g * per..(g + 1) * per]);
        let rec = e.reconstruct(&e.project(&lg));
        for (i, (o, r)) in own.iter_mut().zip(rec).enumerate() {
            *o += scales[g][i / per] * r;
        }
    }
    own
}

/// Block `x`'s stretch corrections of its own light, `[emitting face slot][receiving face slot]`
/// in its layout's face order (6 x 6, unused slots 1): what [`own_light`] applies.
pub fn own_scales(level: &Level, x: usize) -> [[f64; 6]; 6] {
    let blk = &level.blocks[x];
    let faces = blk.shape.present_faces();
    let mut out = [[1.0; 6]; 6];
    for (g, fg) in faces.iter().enumerate() {
        for (f, ff) in faces.iter().enumerate() {
            out[g][f] = level.warps[x].through[blk.world_face(*fg) as usize][blk.world_face(*ff) as usize];
        }
    }
    out
}

/// Per sample of block `y` entered through world side `entry`: the stretch correction of the
/// entering light meeting the sample's world face ([`Warp::through`], capped at
/// [`super::warp::CAP`] as the propagation: entering light is not diffuse).
pub fn response_scales(level: &Level, y: usize, entry: Face, res: usize) -> Vec<f64> {
    let b = &level.blocks[y];
    let layout = Layout::new(b.shape, res);
    let w = &level.warps[y];
    (0..layout.len())
        .map(|i| w.through[entry as usize][b.world_face(layout.sample(i).0) as usize].min(super::warp::CAP))
        .collect()
}

/// b of each block's whole direct light `l_d` (what leaves through its openings).
fn block_b(level: &Level, ops: &Operators<'_>, l_d: &[Vec<f64>]) -> Vec<Vec<f64>> {
    level
        .blocks
        .iter()
        .zip(l_d)
        .map(|(blk, l)| ops.dictionary.element(blk.shape).map_or(Vec::new(), |e| e.project(l)))
        .collect()
}

/// A frame's one-bounce indirect light per block (each in its element's layout) from the
/// blocks' direct light `l_d` (the same layouts): the block's own U_b b plus the surface
/// response to every directed interface's r.
pub fn indirect(level: &Level, ops: &Operators<'_>, transfer: &Transfer, l_d: &[Vec<f64>]) -> Vec<Vec<f64>> {
    let b = block_b(level, ops, l_d);
    let res = ops.dictionary.params.res;
    let mut out: Vec<Vec<f64>> = level
        .blocks
        .iter()
        .zip(l_d)
        .enumerate()
        .map(|(x, (blk, l))| {
            let Some(e) = ops.dictionary.element(blk.shape) else { return Vec::new() };
            own_light(level, x, e, l, res)
        })
        .collect();
    let response = &ops.interfaces.response;
    let k_r = response.k_r;
    let mut r_sum: HashMap<(usize, Face), Vec<f64>> = HashMap::new();
    for ((x, y, entry), t) in &transfer.blocks {
        let bx = &b[*x];
        let k_b = bx.len();
        let r = r_sum.entry((*y, *entry)).or_insert_with(|| vec![0.0; k_r]);
        for (i, ri) in r.iter_mut().enumerate() {
            *ri += (0..k_b).map(|j| t[i * k_b + j] * bx[j]).sum::<f64>();
        }
    }
    for ((y, entry), r) in &r_sum {
        let rows = response_rows(&level.blocks[*y], *entry, res);
        let scales = response_scales(level, *y, *entry, res);
        let walls: Vec<f64> =
            (0..response.n).map(|i| (0..k_r).map(|j| response.u_r[i * k_r + j] * r[j]).sum()).collect();
        for ((o, row), scale) in out[*y].iter_mut().zip(rows).zip(scales) {
            if let Some(row) = row {
                *o += scale * walls[row];
            }
        }
    }
    out
}

/// A frame's light on the closed part of every partly open side ([`Transfer::sides`]) from the
/// blocks' direct light `l_d`: ((block, world side), E / pi per opening position).
pub fn side_light(
    level: &Level,
    ops: &Operators<'_>,
    transfer: &Transfer,
    l_d: &[Vec<f64>],
) -> Vec<((usize, Face), Vec<f64>)> {
    let b = block_b(level, ops, l_d);
    let mut out: HashMap<(usize, Face), Vec<f64>> = HashMap::new();
    for ((src, x, w), m) in &transfer.sides {
        let bs = &b[*src];
        let k_b = bs.len().max(1);
        let n = m.len() / k_b;
        let v = out.entry((*x, *w)).or_insert_with(|| vec![0.0; n]);
        for (i, vi) in v.iter_mut().enumerate() {
            *vi += m[i * k_b..(i + 1) * k_b].iter().zip(bs).map(|(a, c)| a * c).sum::<f64>();
        }
    }
    let mut v: Vec<((usize, Face), Vec<f64>)> = out.into_iter().collect();
    v.sort_by_key(|(k, _)| *k);
    v
}

/// The same bounce by brute force: from every sample of every block, `rays` cosine rays traced
/// through the level's linked openings to the wall they meet, which gives its direct light.
/// Rays are cosine-distributed in each block's canonical (unit-cube) frame: exact for unit
/// blocks, the warped approximation MRT itself makes for stretched ones.
pub fn brute_force(level: &Level, res: usize, l_d: &[Vec<f64>], rays: usize, seed: u64) -> Vec<Vec<f64>> {
    use rayon::prelude::*;
    let layouts: Vec<Layout> = level.blocks.iter().map(|b| Layout::new(b.shape, res)).collect();
    let count = ray_count(rays);
    layouts
        .iter()
        .enumerate()
        .map(|(x, layout)| {
            (0..layout.len())
                .into_par_iter()
                .map(|i| {
                    let (_, _, p, n) = layout.sample(i);
                    let mut rng = Pcg32::new(seed, (x * 65536 + i) as u64, 2);
                    let mut sum = 0.0;
                    for d in cosine_rays(n, rays, &mut rng) {
                        let Some((y, face, s, tt, _)) = level.trace(x, p, d, f32::INFINITY) else { continue };
                        let Some(taps) = layouts[y].bilinear(face, s, tt) else { continue };
                        sum += taps.iter().map(|(j, w)| f64::from(*w) * l_d[y][*j]).sum::<f64>();
                    }
                    sum / count
                })
                .collect()
        })
        .collect()
}

/// The direct light of a point light at world position `light` on every block's samples:
/// cos(theta) / max(d, radius)^2 where the shadow ray reaches it through linked openings.
pub fn point_light(level: &Level, res: usize, light: Vec3, radius: f32) -> Vec<Vec<f64>> {
    level
        .blocks
        .iter()
        .enumerate()
        .map(|(x, blk)| {
            let layout = Layout::new(blk.shape, res);
            (0..layout.len())
                .map(|i| {
                    let (_, _, p, n) = layout.sample(i);
                    let to = light - blk.world_point(p);
                    let d = to.length();
                    let cos = turn_vec(n, blk.turns).dot(to) / d.max(1e-9);
                    if cos <= 0.0 || level.trace(x, p, blk.local_dir(to / d.max(1e-9)), d).is_some() {
                        return 0.0;
                    }
                    f64::from(cos / d.max(radius).powi(2))
                })
                .collect()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::precompute::mrt::dictionary::{DictionaryParams, Progress};
    use crate::precompute::mrt::operators::InterfaceParams;

    /// Three blocks along +z: a dead end open towards +z, a corridor, a dead end turned to open
    /// towards -z.
    fn corridor() -> Level {
        Level::new(vec![
            Block::unit(Shape::DeadEnd, [0, 0, 0], 0),
            Block::unit(Shape::Corridor, [0, 0, 1], 0),
            Block::unit(Shape::DeadEnd, [0, 0, 2], 2),
        ])
    }

    #[test]
    fn blocks_turn_about_up_and_link_where_both_sides_are_open() {
        let b = Block::unit(Shape::DeadEnd, [0, 0, 2], 2);
        assert_eq!(b.world_face(Face::PosZ), Face::NegZ);
        let p = Vec3::new(0.2, 0.3, 0.9);
        assert!((b.local_point(b.world_point(p)) - p).length() < 1e-6);
        let level = corridor();
        assert_eq!(level.link_count(), 4, "two openings, both ways");
        assert_eq!(level.link(0, Face::PosZ), Some(1));
        assert_eq!(level.link(2, Face::NegZ), Some(1));
        assert!(level.unlinked().is_empty());
        // A stretched block keeps its links: the same corridor, twice as long and 3 m high.
        let stretched = Level::new(
            level
                .blocks
                .iter()
                .map(|b| Block { origin: b.origin * Vec3::new(1.0, 1.0, 2.0), size: Vec3::new(1.0, 3.0, 2.0), ..*b })
                .collect(),
        );
        assert_eq!(stretched.link_count(), 4);
        let sb = stretched.blocks[2];
        let q = Vec3::new(0.25, 0.5, 0.75);
        assert!((sb.local_point(sb.world_point(q)) - q).length() < 1e-5);
        assert!((sb.local_dir(sb.world_dir(Vec3::new(0.0, 0.6, 0.8))) - Vec3::new(0.0, 0.6, 0.8)).length() < 1e-5);
        // Without the last block its neighbour's far side opens onto nothing.
        let open_end = Level::new(level.blocks[..2].to_vec());
        assert_eq!(open_end.unlinked(), vec![(1, Face::PosZ)]);
        assert_eq!(turn_between(Face::NegZ, Face::PosZ), Some(Turn::Ahead));
        assert_eq!(turn_between(Face::PosZ, Face::NegX), Some(Turn::Left));
        // A ray down the middle from the first block's back wall reaches the last block's.
        let hit = level.trace(0, Vec3::new(0.5, 0.5, 0.0), Vec3::Z, f32::INFINITY).expect("a wall");
        assert_eq!((hit.0, hit.1), (2, Face::NegZ));
        assert!((hit.4 - 3.0).abs() < 1e-3, "{}", hit.4);
    }

    /// The dictionary with its interface operators at test sizes (4x4 texels, 6x6 x 10x10 x
    /// 2x2 light fields, one enrichment pass).
    fn built() -> Dictionary {
        let interfaces = InterfaceParams {
            positions: 6,
            directions: 10,
            supersample: 2,
            k_rlf: 128,
            k_r: 32,
            enrichment: 1,
            bands: 0,
        };
        let params = DictionaryParams { res: 4, k_d: 48, k_b: 24, rays: 1024, enrichment: 1, seed: 9, interfaces };
        crate::precompute::mrt::dictionary::build(&params, &Progress::default()).expect("dictionary")
    }

    /// Per block, one value per sample.
    type PerBlock = Vec<Vec<f64>>;

    /// MRT's and the brute-force bounce per block for a light at `light` (world), and the
    /// direct light.
    fn compare(d: &Dictionary, level: &Level, light: Vec3, depth: usize) -> (PerBlock, PerBlock, PerBlock) {
        let ops = Operators { dictionary: d, interfaces: &d.interfaces };
        let res = d.params.res;
        let l_d = point_light(level, res, light, 1.0 / 12.0);
        let mrt = indirect(level, &ops, &assemble(level, &ops, depth), &l_d);
        let truth = brute_force(level, res, &l_d, 4096, 3);
        for (x, (m, t)) in mrt.iter().zip(&truth).enumerate() {
            let (sm, st) = (m.iter().sum::<f64>(), t.iter().sum::<f64>());
            let rms = (m.iter().zip(t).map(|(a, b)| (a - b).powi(2)).sum::<f64>() / t.len() as f64).sqrt();
            let mean = st / t.len() as f64;
            eprintln!("block {x}: mrt / brute force {:.3}, rms error {:.3} of the mean", sm / st, rms / mean);
            // Texel by texel, not only in sum: the truncated bases blur, they must not misplace.
            assert!(rms < 0.25 * mean, "block {x}: rms error {:.3} of the mean", rms / mean);
        }
        (mrt, truth, l_d)
    }

    #[test]
    fn a_straight_three_block_corridor_matches_a_brute_force_bounce() {
        let b = built();
        let level = corridor();
        // A light in the first block, off centre.
        let (mrt, truth, l_d) = compare(&b, &level, Vec3::new(0.3, 0.6, 0.35), 4);
        let ops = Operators { dictionary: &b, interfaces: &b.interfaces };
        let ratio = |x: usize| mrt[x].iter().sum::<f64>() / truth[x].iter().sum::<f64>();
        // What the interfaces carry: without T_{b->r} each block sees only its own walls, and
        // one step short of the far block its light from the first block's walls is missing.
        let alone = indirect(&level, &ops, &Transfer::default(), &l_d);
        let shallow = indirect(&level, &ops, &assemble(&level, &ops, 0), &l_d);
        let share = |v: &[Vec<f64>], x: usize| v[x].iter().sum::<f64>() / truth[x].iter().sum::<f64>();
        eprintln!(
            "without interfaces {:.3} / {:.3} / {:.3}; depth 0 {:.3} / {:.3} / {:.3}",
            share(&alone, 0),
            share(&alone, 1),
            share(&alone, 2),
            share(&shallow, 0),
            share(&shallow, 1),
            share(&shallow, 2)
        );
        assert!(share(&alone, 1) < 0.8 && share(&shallow, 2) < 0.95, "the interfaces carry light");
        assert!((ratio(0) - 1.0).abs() < 0.1, "the lit block {:.3}", ratio(0));
        assert!((ratio(1) - 1.0).abs() < 0.15, "the next block {:.3}", ratio(1));
        assert!((ratio(2) - 1.0).abs() < 0.25, "the far block {:.3}", ratio(2));
    }

    #[test]
    fn light_turning_a_corner_matches_a_brute_force_bounce() {
        // A dead end open to +z, a corner turned to join -z and +x, a dead end turned to open
        // to -x: light from the first block turns left (facing +z, +x is on the left) into the
        // third.
        let level = Level::new(vec![
            Block::unit(Shape::DeadEnd, [0, 0, 0], 0),
            Block::unit(Shape::Corner, [0, 0, 1], 1),
            Block::unit(Shape::DeadEnd, [1, 0, 1], 3),
        ]);
        assert_eq!(level.link_count(), 4);
        assert_eq!(turn_between(Face::NegZ, Face::PosX), Some(Turn::Left));
        let (mrt, truth, _) = compare(&built(), &level, Vec3::new(0.5, 0.5, 0.3), 4);
        let ratio = |x: usize| mrt[x].iter().sum::<f64>() / truth[x].iter().sum::<f64>();
        assert!((ratio(1) - 1.0).abs() < 0.15, "the corner {:.3}", ratio(1));
        assert!((ratio(2) - 1.0).abs() < 0.25, "round the corner {:.3}", ratio(2));
    }
}
