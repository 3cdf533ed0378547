//! A storey's plan cut into blocks: pillars and free-standing pieces filled in (they stand in a
//! room, they do not part it), the plan divided into zones of one ceiling height (rooms of
//! different heights side by side, a lintel over a doorway as wide as its wall), and each zone
//! covered greedily by rectangles: the largest square of free cells, grown to the largest
//! rectangle it lies in, again and again until no square of a block's smallest side is left. A
//! room is one rectangle, an L- or T-shaped room two or three, a corridor its own; the narrow air
//! of a doorway in a wall is left to the doorway stage.

use std::collections::VecDeque;

use super::{MIN_SIDE, Plan};

/// A free-standing piece of at most this plan area (m²) inside a room is filled in: a pillar, a
/// wardrobe, a stub of wall.
const PILLAR_AREA: f32 = 2.0;
/// The smallest block kept (m², plan): a short corridor between two doorways is one (0.6 x 1.8 m
/// between two rooms measured 2.7x too much light when the rooms were joined across it instead).
const MIN_BLOCK_AREA: f32 = 0.5;
/// Neighbouring columns whose ceilings differ by more than this are in different zones (m).
const CEILING_STEP: f32 = 0.3;

/// A rectangle of plan cells (`x0 .. x1`, `z0 .. z1`, exclusive ends) and its zone.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Rect {
    pub(super) x0: usize,
    pub(super) x1: usize,
    pub(super) z0: usize,
    pub(super) z1: usize,
}

impl Rect {
    fn cells(&self, nx: usize) -> impl Iterator<Item = usize> + '_ {
        (self.z0..self.z1).flat_map(move |z| (self.x0..self.x1).map(move |x| z * nx + x))
    }
    fn area(&self) -> usize {
        (self.x1 - self.x0) * (self.z1 - self.z0)
    }
}

/// The 4-connected components of the cells `member` accepts, as lists of cells.
pub(super) fn components(plan: &Plan, member: &dyn Fn(usize) -> bool) -> Vec<Vec<usize>> {
    let n = plan.nx * plan.nz;
    let mut seen = vec![false; n];
    let mut out = Vec::new();
    for start in 0..n {
        if seen[start] || !member(start) {
            continue;
        }
        seen[start] = true;
        let mut cells = vec![start];
        let mut k = 0;
        while k < cells.len() {
            for m in plan.neighbours(cells[k]) {
                if !seen[m] && member(m) {
                    seen[m] = true;
                    cells.push(m);
                }
            }
            k += 1;
        }
        out.push(cells);
    }
    out
}

/// The plan with every free-standing solid piece of at most [`PILLAR_AREA`] filled with the air
/// around it (the median range of the air cells beside it).
pub(super) fn fill_pillars(plan: &Plan) -> Plan {
    let mut out = plan.clone();
    let (nx, nz) = (plan.nx, plan.nz);
    let max_cells = (PILLAR_AREA / (plan.h * plan.h)) as usize;
    let on_border = |i: usize| i.is_multiple_of(nx) || i % nx == nx - 1 || i / nx == 0 || i / nx == nz - 1;
    for piece in components(plan, &|i| plan.air[i].is_none()) {
        if piece.len() > max_cells || piece.iter().any(|&i| on_border(i)) {
            continue;
        }
        let mut lows = Vec::new();
        let mut highs = Vec::new();
        for &i in &piece {
            for m in plan.neighbours(i) {
                if let Some((a, b)) = plan.air[m] {
                    lows.push(a);
                    highs.push(b);
                }
            }
        }
        let (Some(a), Some(b)) = (median(&mut lows), median(&mut highs)) else { continue };
        for &i in &piece {
            out.air[i] = Some((a, b));
        }
    }
    out
}

/// The median of `v` (reordered), `None` when empty.
pub(super) fn median(v: &mut [i32]) -> Option<i32> {
    v.sort_unstable();
    v.get(v.len() / 2).copied()
}

/// Per cell its zone (`usize::MAX` without air): air cells joined where their ceilings differ
/// by at most [`CEILING_STEP`].
fn zones(plan: &Plan) -> Vec<usize> {
    let step = (CEILING_STEP / plan.h).round() as i32;
    let mut zone = vec![usize::MAX; plan.nx * plan.nz];
    let mut next = 0;
    for start in 0..zone.len() {
        let Some(_) = plan.air[start] else { continue };
        if zone[start] != usize::MAX {
            continue;
        }
        zone[start] = next;
        let mut queue = VecDeque::from([start]);
        while let Some(i) = queue.pop_front() {
            let Some((_, top)) = plan.air[i] else { continue };
            for m in plan.neighbours(i) {
                if zone[m] == usize::MAX
                    && let Some((_, t)) = plan.air[m]
                    && (t - top).abs() <= step
                {
                    zone[m] = next;
                    queue.push_back(m);
                }
            }
        }
        next += 1;
    }
    zone
}

/// The largest square of free cells within one zone: its top-left cell and side (0 for none).
fn largest_square(plan: &Plan, zone: &[usize], taken: &[bool]) -> (usize, usize) {
    let nx = plan.nx;
    let free = |i: usize| zone[i] != usize::MAX && !taken[i];
    // side[i]: the largest square of one zone whose bottom-right cell is i.
    let mut side = vec![0usize; zone.len()];
    let (mut best, mut best_side) = (0, 0);
    for i in 0..zone.len() {
        if !free(i) {
            continue;
        }
        let (x, z) = (i % nx, i / nx);
        side[i] = if x > 0 && z > 0 && [i - 1, i - nx, i - nx - 1].iter().all(|&j| zone[j] == zone[i]) {
            1 + side[i - 1].min(side[i - nx]).min(side[i - nx - 1])
        } else {
            1
        };
        if side[i] > best_side {
            (best, best_side) = (i, side[i]);
        }
    }
    let s = best_side.saturating_sub(1);
    (best - s * nx - s, best_side)
}

/// Grows `r` one row or column at a time, in `order` (0 -x, 1 +x, 2 -z, 3 +z), while the new
/// row or column is free and in `z`, until it grows no more.
fn grow(plan: &Plan, free: &dyn Fn(usize) -> bool, mut r: Rect, order: [usize; 4]) -> Rect {
    let nx = plan.nx;
    let column = |x: usize, r: &Rect| (r.z0..r.z1).all(|z| free(z * nx + x));
    let row = |z: usize, r: &Rect| (r.x0..r.x1).all(|x| free(z * nx + x));
    loop {
        let before = r;
        for dir in order {
            match dir {
                0 => {
                    while r.x0 > 0 && column(r.x0 - 1, &r) {
                        r.x0 -= 1;
                    }
                }
                1 => {
                    while r.x1 < nx && column(r.x1, &r) {
                        r.x1 += 1;
                    }
                }
                2 => {
                    while r.z0 > 0 && row(r.z0 - 1, &r) {
                        r.z0 -= 1;
                    }
                }
                _ => {
                    while r.z1 < plan.nz && row(r.z1, &r) {
                        r.z1 += 1;
                    }
                }
            }
        }
        if r == before {
            return r;
        }
    }
}

/// The rectangles covering `plan` (pillars already filled): largest squares first, each grown
/// to the larger of its widest-first and deepest-first rectangles. Rectangles under
/// [`MIN_BLOCK_AREA`] are left out (their cells stay to the doorway stage).
pub(super) fn decompose(plan: &Plan) -> Vec<Rect> {
    let zone = zones(plan);
    let min_side = (MIN_SIDE / plan.h).ceil() as usize;
    let min_cells = (MIN_BLOCK_AREA / (plan.h * plan.h)).ceil() as usize;
    let mut taken = vec![false; zone.len()];
    let mut out = Vec::new();
    loop {
        let (corner, side) = largest_square(plan, &zone, &taken);
        if side < min_side.max(1) {
            return out;
        }
        let (x, z) = (corner % plan.nx, corner / plan.nx);
        let seed = Rect { x0: x, x1: x + side, z0: z, z1: z + side };
        let own = zone[corner];
        let free = |i: usize| zone[i] == own && !taken[i];
        let a = grow(plan, &free, seed, [0, 1, 2, 3]);
        let b = grow(plan, &free, seed, [2, 3, 0, 1]);
        let r = if b.area() > a.area() { b } else { a };
        for i in r.cells(plan.nx) {
            taken[i] = true;
        }
        if r.area() >= min_cells {
            out.push(r);
        }
    }
}

/// The side of the largest square of cells not `taken` (any heights).
pub(super) fn square_side(plan: &Plan, taken: &[bool]) -> usize {
    largest_square(plan, &vec![0; taken.len()], taken).1
}

/// Each rectangle's air: the median floor and ceiling rows of its cells.
pub(super) fn heights(plan: &Plan, r: &Rect) -> (i32, i32) {
    let (mut lows, mut highs): (Vec<i32>, Vec<i32>) = r.cells(plan.nx).filter_map(|i| plan.air[i]).unzip();
    (median(&mut lows).unwrap_or(0), median(&mut highs).unwrap_or(0))
}

/// The cells of `r`.
pub(super) fn cells_of(plan: &Plan, r: &Rect) -> Vec<usize> {
    r.cells(plan.nx).collect()
}
