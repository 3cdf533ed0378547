//! MRT's sparse block-to-interface transfer T_{b->r} of a level (Loos 2015 §3.5.3 and §4.3.2),
//! assembled by depth-limited propagation: dynamic programming by depth, paths of equal length into
//! the same directed interface summed, never sent back out through the side they came in by. Where
//! the real level leaves a linked side only partly open (a doorway in a room's whole side,
//! [`super::opening`]), the light crossing it is masked position by position, the closed part
//! reflects back into the block, and what that part receives is kept for its own lookup.

use std::collections::HashMap;

use super::level::{Level, Operators, turn_between};
use super::opening::Opening;
use super::shape::Face;

/// T_{b->r}: for each source block and each directed interface (receiving block, its world entry
/// side) that light from the source reaches, a k_r x k_b block.
#[derive(Clone, Debug, Default)]
pub struct Transfer {
    /// ((source, receiver, entry side), k_r x k_b row-major).
    pub blocks: HashMap<(usize, usize, Face), Vec<f64>>,
    /// ((source, block, world side), P^2 x k_b row-major): the light (E / pi of a white
    /// receiver) reaching each opening position of a partly open side from inside the block:
    /// the wall around a doorway, which has no texels of its own.
    pub sides: HashMap<(usize, usize, Face), Vec<f64>>,
}

/// a (r x k) += m (r x c) * x (c x k).
fn mul_add(out: &mut [f64], m: &[f64], x: &[f64], r: usize, c: usize, k: usize) {
    for i in 0..r {
        for j in 0..c {
            let mij = m[i * c + j];
            if mij != 0.0 {
                let (row, src) = (&mut out[i * k..(i + 1) * k], &x[j * k..(j + 1) * k]);
                row.iter_mut().zip(src).for_each(|(o, s)| *o += mij * s);
            }
        }
    }
}

/// The masks and reflections of every partly open linked side, built once per assembly.
struct SideOps {
    /// (block, world side) -> M (k_rlf x k_rlf): the light that crosses.
    masks: HashMap<(usize, Face), Vec<f64>>,
    /// (block, world side) -> S (k_rlf x k_rlf): the light the closed part sends back in.
    reflections: HashMap<(usize, Face), Vec<f64>>,
    /// E_p / pi per position (P^2 x k_rlf): a white receiver's light at each position.
    receiver: Vec<f64>,
    /// (block, world side) -> R (k_rlf x k_rlf): where the neighbour's side differs from this
    /// one, the light crossing the open positions landing where it is in the world
    /// ([`super::remap`]); it replaces the side's mask.
    remaps: HashMap<(usize, Face), Vec<f64>>,
}

impl SideOps {
    fn new(level: &Level, ops: &Operators<'_>) -> Self {
        let positions = &ops.interfaces.positions;
        let n = positions.positions * positions.positions;
        let receiver = positions.irradiance.iter().map(|e| e / std::f64::consts::PI).collect();
        let mut out = Self { masks: HashMap::new(), reflections: HashMap::new(), receiver, remaps: HashMap::new() };
        if positions.k != ops.interfaces.k_rlf {
            // Operators of another basis: every side counts as fully open and matched.
            return out;
        }
        for (x, w) in level.linked_sides() {
            if let Some(mut weights) = super::remap::weights(level, x, w, positions.positions) {
                // The remap reads the irradiance of the open positions only, in place of the
                // reduced mask: masking a light field in 128 modes loses what the modes cannot
                // hold of its sharp edge (a third of the light through a 1.8 m doorway in a 4 m
                // wall, and rings negative around a small one).
                if let Some(o) = level.opening(x, w).filter(|o| o.open.len() == n) {
                    for row in weights.chunks_exact_mut(n) {
                        row.iter_mut().zip(&o.open).for_each(|(w, open)| *w *= open.clamp(0.0, 1.0));
                    }
                }
                out.remaps.insert((x, w), positions.remap(&weights));
            }
        }
        for (key, o) in level.openings() {
            // An opening sampled at another resolution counts at its mean share.
            let uniform;
            let o = if o.open.len() == n {
                o
            } else {
                let grey = o.albedo.iter().sum::<f64>() / o.albedo.len().max(1) as f64;
                uniform = Opening::uniform(positions.positions, o.share(), grey);
                &uniform
            };
            if let Some(m) = positions.mask(&o.open) {
                out.masks.insert(*key, m);
            }
            if let Some(r) = positions.reflection(&o.open, &o.albedo) {
                out.reflections.insert(*key, r);
            }
        }
        out
    }

    /// Light `a` (k_rlf x k_b, from source block `source`'s b) reaching block `x`'s linked side
    /// `w` from inside, scaled by `scale`: what crosses into `y` through the opposite side, what
    /// the closed part sends back into `x` through `w`, and (into `sides`) what the closed
    /// part receives.
    #[allow(clippy::too_many_arguments)]
    fn split(
        &self,
        (source, x, w, y): (usize, usize, Face, usize),
        a: &[f64],
        scale: f64,
        ops: &Operators<'_>,
        k_b: usize,
        into: &mut HashMap<(usize, Face), Vec<f64>>,
        sides: &mut HashMap<(usize, usize, Face), Vec<f64>>,
    ) {
        let k_rlf = ops.interfaces.k_rlf;
        let scaled: Vec<f64> = a.iter().map(|v| v * scale).collect();
        if self.reflections.contains_key(&(x, w)) {
            let n = self.receiver.len() / k_rlf.max(1);
            let out = sides.entry((source, x, w)).or_insert_with(|| vec![0.0; n * k_b]);
            mul_add(out, &self.receiver, &scaled, n, k_rlf, k_b);
        }
        let crossing = match self.masks.get(&(x, w)).filter(|_| !self.remaps.contains_key(&(x, w))) {
            Some(m) => {
                let mut c = vec![0.0; k_rlf * k_b];
                mul_add(&mut c, m, &scaled, k_rlf, k_rlf, k_b);
                c
            }
            None => scaled.clone(),
        };
        let out = into.entry((y, w.opposite())).or_insert_with(|| vec![0.0; k_rlf * k_b]);
        match self.remaps.get(&(x, w)) {
            Some(r) => mul_add(out, r, &crossing, k_rlf, k_rlf, k_b),
            None => out.iter_mut().zip(&crossing).for_each(|(o, s)| *o += s),
        }
        if let Some(r) = self.reflections.get(&(x, w)) {
            let back = into.entry((x, w)).or_insert_with(|| vec![0.0; k_rlf * k_b]);
            mul_add(back, r, &scaled, k_rlf, k_rlf, k_b);
        }
    }
}

/// Assembles T_{b->r} by propagation up to `depth` blocks beyond each source's neighbours. At a
/// partly open side ([`Level::set_opening`]) the light crossing is masked position by position
/// and the closed part reflects back into the block it came from ([`super::opening`]); what the
/// closed part receives is kept for its own lookup ([`Transfer::sides`]).
pub fn assemble(level: &Level, ops: &Operators<'_>, depth: usize) -> Transfer {
    let k_rlf = ops.interfaces.k_rlf;
    let k_r = ops.interfaces.response.k_r;
    let sides = SideOps::new(level, ops);
    let mut transfer = Transfer::default();
    for (x, bx) in level.blocks.iter().enumerate() {
        let Some(ex) = ops.dictionary.element(bx.shape) else { continue };
        let k_b = ex.k_b;
        // Light fields (as k_rlf x k_b maps from b_x) entering (block, world side).
        let mut frontier: HashMap<(usize, Face), Vec<f64>> = HashMap::new();
        for &f in bx.shape.open_faces() {
            let w = bx.world_face(f);
            let (Some(y), Some(exit)) = (level.link(x, w), ops.interfaces.exit(bx.shape, f)) else { continue };
            let scale = level.warps[x].walls[w as usize].min(super::warp::CAP);
            sides.split((x, x, w, y), &exit.r_b_rlf, scale, ops, k_b, &mut frontier, &mut transfer.sides);
        }
        for step in 0..=depth {
            let mut next: HashMap<(usize, Face), Vec<f64>> = HashMap::new();
            for ((y, entry), a) in &frontier {
                let t = transfer.blocks.entry((x, *y, *entry)).or_insert_with(|| vec![0.0; k_r * k_b]);
                mul_add(t, &ops.interfaces.response.t_rlf_r, a, k_r, k_rlf, k_b);
                if step == depth {
                    continue;
                }
                let by = level.blocks[*y];
                for &f in by.shape.open_faces() {
                    let w = by.world_face(f);
                    let (Some(z), Some(turn)) = (level.link(*y, w), turn_between(*entry, w)) else { continue };
                    let Some(r) = ops.interfaces.turn(turn) else { continue };
                    let mut leaving = vec![0.0; k_rlf * k_b];
                    mul_add(&mut leaving, r, a, k_rlf, k_rlf, k_b);
                    let scale = level.warps[*y].through[*entry as usize][w as usize].min(super::warp::CAP);
                    sides.split((x, *y, w, z), &leaving, scale, ops, k_b, &mut next, &mut transfer.sides);
                }
            }
            frontier = next;
        }
    }
    transfer
}
