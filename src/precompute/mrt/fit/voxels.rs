//! The voxel stages of the fitter: a grid over the level, the voxels its surfaces pass through,
//! the outside flooded from the grid's border (closed over windows), and the enclosed air that is
//! space to light (not a wall's inside, not a solid's).

use std::collections::VecDeque;

use glam::{IVec3, Vec3};

use super::{CLOSE, THIN, VOXELS_ALONG};

/// Whether `p` lies inside a closed solid: of the six axis rays from it, more meet a triangle's
/// back (its counter-clockwise side faces away) than its front. Level geometry faces the air
/// (the research note's validity test, with axis rays).
pub(super) fn inside_solid(tris: &[[Vec3; 3]], p: Vec3) -> bool {
    let (mut front, mut back) = (0, 0);
    for d in [Vec3::X, Vec3::NEG_X, Vec3::Y, Vec3::NEG_Y, Vec3::Z, Vec3::NEG_Z] {
        let mut best: Option<(f32, bool)> = None;
        for t in tris {
            let (e1, e2) = (t[1] - t[0], t[2] - t[0]);
            let q = d.cross(e2);
            let det = e1.dot(q);
            if det.abs() < 1e-12 {
                continue;
            }
            let s = p - t[0];
            let u = s.dot(q) / det;
            let r = s.cross(e1);
            let v = d.dot(r) / det;
            let dist = e2.dot(r) / det;
            if u < 0.0 || v < 0.0 || u + v > 1.0 || dist <= 0.0 || best.is_some_and(|b| b.0 <= dist) {
                continue;
            }
            best = Some((dist, e1.cross(e2).dot(d) < 0.0));
        }
        match best {
            Some((_, true)) => front += 1,
            Some((_, false)) => back += 1,
            None => {}
        }
    }
    back > front
}

/// The voxel grid of a level.
pub(super) struct Grid {
    /// The minimum corner.
    pub(super) origin: Vec3,
    /// The voxel size (m).
    pub(super) h: f32,
    /// Voxels along x, y, z.
    pub(super) dims: IVec3,
}

impl Grid {
    pub(super) fn index(&self, c: IVec3) -> usize {
        ((c.y * self.dims.z + c.z) * self.dims.x + c.x) as usize
    }
    pub(super) fn cell(&self, p: Vec3) -> IVec3 {
        ((p - self.origin) / self.h).floor().as_ivec3().clamp(IVec3::ZERO, self.dims - 1)
    }
    pub(super) fn len(&self) -> usize {
        (self.dims.x * self.dims.y * self.dims.z) as usize
    }
}

/// Marks the voxels the triangles pass through (sampled at a third of a voxel).
fn solid(grid: &Grid, tris: &[[Vec3; 3]]) -> Vec<bool> {
    let mut s = vec![false; grid.len()];
    for t in tris {
        let longest = (t[1] - t[0]).length().max((t[2] - t[0]).length()).max((t[2] - t[1]).length());
        let steps = ((longest / (grid.h / 3.0)).ceil() as usize).max(1);
        for i in 0..=steps {
            for j in 0..=steps - i {
                let (a, b) = (i as f32 / steps as f32, j as f32 / steps as f32);
                let p = t[0] + (t[1] - t[0]) * a + (t[2] - t[0]) * b;
                s[grid.index(grid.cell(p))] = true;
            }
        }
    }
    s
}

/// The six steps to a voxel's face neighbours.
const STEPS: [IVec3; 6] = [IVec3::X, IVec3::NEG_X, IVec3::Y, IVec3::NEG_Y, IVec3::Z, IVec3::NEG_Z];

/// The voxelised level, shared by the outside flood and the enclosed-air stages.
pub(super) struct Voxels {
    /// The grid over the level.
    pub(super) grid: Grid,
    /// Per voxel, whether a surface passes through it.
    pub(super) wall: Vec<bool>,
    /// The closing radius of the outside flood, in voxels.
    pub(super) close: u32,
}

/// Lays a grid over the level (about [`VOXELS_ALONG`] voxels along its longest side, padded by
/// the closing radius and two voxels so the outside flood can go round it) and marks the voxels
/// its surfaces pass through.
pub(super) fn voxelise(tris: &[[Vec3; 3]]) -> Voxels {
    let (lo, hi) =
        tris.iter().flatten().fold((Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)), |(a, b), p| (a.min(*p), b.max(*p)));
    let h = ((hi - lo).max_element() / VOXELS_ALONG).clamp(0.02, 0.25);
    // Gaps narrower than twice the closing radius (windows, an exterior door) do not let the
    // outside in: the flood runs through voxels farther than it from any surface, then spreads
    // back by it. At most an eighth of the level, so an open side of a small box stays open.
    let close = (CLOSE.min((hi - lo).max_element() / 8.0) / h).floor() as u32;
    let pad = 2 + close as i32;
    let origin = lo - Vec3::splat(pad as f32 * h);
    let dims = (((hi - lo) / h).ceil().as_ivec3() + IVec3::splat(2 * pad + 1)).max(IVec3::ONE);
    let grid = Grid { origin, h, dims };
    let wall = solid(&grid, tris);
    Voxels { grid, wall, close }
}

/// Breadth-first steps from `seeds` through voxels `pass` allows, up to `limit` steps
/// (`u32::MAX` where unreached): the distance fields the outside flood is made of.
fn spread(grid: &Grid, seeds: &[IVec3], pass: &dyn Fn(usize) -> bool, limit: u32, steps: &[IVec3]) -> Vec<u32> {
    let dims = grid.dims;
    let mut d = vec![u32::MAX; grid.len()];
    let mut queue: VecDeque<IVec3> = VecDeque::new();
    for c in seeds {
        d[grid.index(*c)] = 0;
        queue.push_back(*c);
    }
    while let Some(c) = queue.pop_front() {
        let next = d[grid.index(c)] + 1;
        if next > limit {
            continue;
        }
        for st in steps {
            let n = c + *st;
            if n.cmplt(IVec3::ZERO).any() || n.cmpge(dims).any() {
                continue;
            }
            let i = grid.index(n);
            if d[i] == u32::MAX && pass(i) {
                d[i] = next;
                queue.push_back(n);
            }
        }
    }
    d
}

/// The outside: a flood from the grid's border through voxels farther than the closing radius
/// from any surface, spread back by that radius, so that a window does not open a room.
pub(super) fn flood_outside(voxels: &Voxels) -> Vec<bool> {
    let (grid, wall, close) = (&voxels.grid, &voxels.wall, voxels.close);
    let dims = grid.dims;
    let all: Vec<IVec3> = (0..dims.y)
        .flat_map(|y| (0..dims.z).flat_map(move |z| (0..dims.x).map(move |x| IVec3::new(x, y, z))))
        .collect();
    let surfaces: Vec<IVec3> = all.iter().copied().filter(|c| wall[grid.index(*c)]).collect();
    let near = spread(grid, &surfaces, &|i| !wall[i], close, &STEPS);
    let open = |i: usize| !wall[i] && near[i] == u32::MAX;
    let border: Vec<IVec3> = all
        .iter()
        .copied()
        .filter(|c| (c.cmpeq(IVec3::ZERO).any() || c.cmpeq(dims - 1).any()) && open(grid.index(*c)))
        .collect();
    let flooded = spread(grid, &border, &open, u32::MAX - 1, &STEPS);
    let reached: Vec<IVec3> = all.iter().copied().filter(|c| flooded[grid.index(*c)] != u32::MAX).collect();
    // Back by the radius in 26-connected steps (a cube, not a diamond): the outside reaches into
    // the concave foot of a wall as far as along it, so a courtyard's edges are not enclosed.
    let cube: Vec<IVec3> = (-1..=1)
        .flat_map(|y| (-1..=1).flat_map(move |z| (-1..=1).map(move |x| IVec3::new(x, y, z))))
        .filter(|s| *s != IVec3::ZERO)
        .collect();
    let back = spread(grid, &reached, &|i| !wall[i], close, &cube);
    back.iter().map(|d| *d != u32::MAX).collect()
}

/// The enclosed air: voxels neither surface nor outside, less the pieces that are no space to
/// light. A piece thinner than [`THIN`] along some axis is the inside of a wall or slab (its two
/// faces marked, the voxels between them unreached); one inside a closed solid is a solid's.
pub(super) fn enclosed_air(voxels: &Voxels, outside: &[bool], tris: &[[Vec3; 3]]) -> Vec<bool> {
    let (grid, wall) = (&voxels.grid, &voxels.wall);
    let dims = grid.dims;
    let mut enclosed: Vec<bool> = (0..grid.len()).map(|i| !wall[i] && !outside[i]).collect();
    let mut seen = vec![false; grid.len()];
    let thin = (THIN / grid.h).ceil() as i32;
    for y in 0..dims.y {
        for z in 0..dims.z {
            for x in 0..dims.x {
                let c = IVec3::new(x, y, z);
                if !enclosed[grid.index(c)] || seen[grid.index(c)] {
                    continue;
                }
                let (piece, lo, hi) = piece_at(grid, &enclosed, &mut seen, c);
                if (hi - lo + 1).min_element() < thin || mostly_inside_solids(grid, tris, &piece) {
                    piece.iter().for_each(|p| enclosed[grid.index(*p)] = false);
                }
            }
        }
    }
    enclosed
}

/// Whether most of five voxels spread through `piece` lie inside closed solids: one voxel's
/// rays can graze an edge or meet two coincident faces (a crate standing on the floor) and
/// miscount.
fn mostly_inside_solids(grid: &Grid, tris: &[[Vec3; 3]], piece: &[IVec3]) -> bool {
    let votes = (0..5)
        .filter(|k| {
            let c = piece[(2 * k + 1) * piece.len() / 10];
            // Off the voxel's centre, so that axis rays do not run along triangles' edges.
            inside_solid(tris, grid.origin + (c.as_vec3() + Vec3::new(0.37, 0.53, 0.61)) * grid.h)
        })
        .count();
    votes >= 3
}

/// The piece of enclosed air holding `c` (its face-connected voxels, marked in `seen`) and its
/// bounds, which tell a wall's inside from a room.
fn piece_at(grid: &Grid, enclosed: &[bool], seen: &mut [bool], c: IVec3) -> (Vec<IVec3>, IVec3, IVec3) {
    let dims = grid.dims;
    let mut piece = vec![c];
    seen[grid.index(c)] = true;
    let (mut lo, mut hi) = (c, c);
    let mut k = 0;
    while k < piece.len() {
        let at = piece[k];
        for st in STEPS {
            let n = at + st;
            if n.cmplt(IVec3::ZERO).any() || n.cmpge(dims).any() {
                continue;
            }
            let i = grid.index(n);
            if enclosed[i] && !seen[i] {
                seen[i] = true;
                (lo, hi) = (lo.min(n), hi.max(n));
                piece.push(n);
            }
        }
        k += 1;
    }
    (piece, lo, hi)
}
