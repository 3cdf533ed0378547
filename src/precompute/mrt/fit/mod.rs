//! Fitting MRT proxy blocks to a level's geometry (the "fit proxy blocks" command, for rectilinear,
//! one-storey levels): voxelise the triangles, flood the outside from the grid's border (through
//! voxels farther than a closing radius from any surface, so a window does not open a room, then
//! spread back by it), keep the enclosed air; in plan, erode the air by half a doorway so rooms
//! part at their doorways, label the cores, grow the labels back over the air; each room's box is
//! its core's bounds grown back, its height the air's; rooms that touch are joined through their
//! doorways ([`super::doorways`]). What it cannot fit is a named error: no enclosed air (an open
//! field, a lone triangle), a level far from axis-aligned (a sphere).
//!
//! Loos leaves fitting to the artist (§4.3.1) and names it open research (§7.1); thresholds here
//! are starting values, each a constant below.

use std::collections::{HashMap, VecDeque};

use glam::{IVec3, Vec3};
use thiserror::Error;

/// Voxels along the level's longest side (the voxel is at most 0.25 m and at least 2 cm).
const VOXELS_ALONG: f32 = 160.0;
/// Half the widest doorway that still parts two rooms (m).
const HALF_DOORWAY: f32 = 0.6;
/// The smallest room kept (m², plan).
const MIN_ROOM_AREA: f32 = 1.0;
/// The thickest wall between two rooms whose sides are joined (m).
pub(super) const MAX_WALL: f32 = 0.8;
/// The closing radius of the outside flood (m): windows and exterior doors up to twice it do not
/// open a room to the outside.
const CLOSE: f32 = 0.65;
/// Enclosed air thinner than this along an axis is a wall's or slab's inside (m).
const THIN: f32 = 0.5;
/// Below this share of vertical area on the two grid axes the level is not rectilinear.
const MIN_RECTILINEAR: f32 = 0.6;

/// Why a level cannot be fitted.
#[derive(Debug, Error, PartialEq)]
pub enum FitError {
    /// No triangles.
    #[error("nothing to fit: the level has no triangles")]
    Empty,
    /// No air is enclosed: the flood from outside reaches everywhere.
    #[error(
        "no enclosed space: the outside reaches everywhere (an open field, a lone surface, or walls with gaps wider than a voxel of {voxel:.2} m)"
    )]
    NoEnclosure {
        /// The voxel size used.
        voxel: f32,
    },
    /// The walls are far from the grid's axes.
    #[error(
        "the level is not rectilinear: only {share:.0}% of its vertical area faces the x or z axis (the cube dictionary's blocks stand on the grid's axes)"
    )]
    NonRectilinear {
        /// Percentage of vertical area on the axes.
        share: f32,
    },
    /// Air is enclosed but no room is large enough.
    #[error("the enclosed space holds no room of at least {MIN_ROOM_AREA} m²")]
    NoRoom,
}

/// One fitted block: a world box and its open sides (+X, -X, +Y, -Y, +Z, -Z, as the scene's
/// cuboid openings).
#[derive(Clone, Debug, PartialEq)]
pub struct FittedBlock {
    /// Minimum corner.
    pub min: Vec3,
    /// Maximum corner.
    pub max: Vec3,
    /// Open sides (+X, -X, +Y, -Y, +Z, -Z).
    pub openings: [bool; 6],
}

/// Area-weighted agreement of the vertical triangles' normals with the x and z axes: the mean of
/// cos(4 theta), 1 where every wall faces an axis, 0 for walls facing every way (a sphere), -1
/// for walls at 45 degrees; `None` without vertical triangles.
fn rectilinearity(tris: &[[Vec3; 3]]) -> Option<f32> {
    let (mut re, mut total) = (0.0f32, 0.0f32);
    for t in tris {
        let c = (t[1] - t[0]).cross(t[2] - t[0]);
        let area = 0.5 * c.length();
        let n = c.normalize_or_zero();
        if area <= 0.0 || n.y.abs() >= 0.2 {
            continue;
        }
        let theta = n.z.atan2(n.x);
        re += area * (4.0 * theta).cos();
        total += area;
    }
    (total > 0.0).then(|| re / total)
}

/// Whether `p` lies inside a closed solid: of the six axis rays from it, more meet a triangle's
/// back (its counter-clockwise side faces away) than its front. Level geometry faces the air
/// (the research note's validity test, with axis rays).
fn inside_solid(tris: &[[Vec3; 3]], p: Vec3) -> bool {
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
struct Grid {
    origin: Vec3,
    h: f32,
    dims: IVec3,
}

impl Grid {
    fn index(&self, c: IVec3) -> usize {
        ((c.y * self.dims.z + c.z) * self.dims.x + c.x) as usize
    }
    fn cell(&self, p: Vec3) -> IVec3 {
        ((p - self.origin) / self.h).floor().as_ivec3().clamp(IVec3::ZERO, self.dims - 1)
    }
    fn len(&self) -> usize {
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

/// Fits blocks to the level `tris` (world triangles, y up).
pub fn fit(tris: &[[Vec3; 3]]) -> Result<Vec<FittedBlock>, FitError> {
    check_fittable(tris)?;
    let voxels = voxelise(tris);
    let outside = flood_outside(&voxels);
    let enclosed = enclosed_air(&voxels, &outside, tris);
    let plan = plan_of(&voxels.grid, &enclosed)?;
    let dist = depth_in_plan(&plan);
    let r = (HALF_DOORWAY / plan.h).ceil() as u32;
    let (mut label, cores) = room_cores(&plan, &dist, r);
    let rooms = room_boxes(&plan, &cores, r)?;
    grow_labels(&plan, &mut label);
    let doors = doors_between(&plan, &label, &rooms);
    Ok(super::doorways::split_at_doors(rooms.into_iter().map(|r| r.1).collect(), &doors))
}

/// The six steps to a voxel's face neighbours.
const STEPS: [IVec3; 6] = [IVec3::X, IVec3::NEG_X, IVec3::Y, IVec3::NEG_Y, IVec3::Z, IVec3::NEG_Z];

/// The voxelised level, shared by the outside flood and the enclosed-air stages.
struct Voxels {
    /// The grid over the level.
    grid: Grid,
    /// Per voxel, whether a surface passes through it.
    wall: Vec<bool>,
    /// The closing radius of the outside flood, in voxels.
    close: u32,
}

/// Refuses what cannot be fitted before any voxel is made: a level without triangles, or one
/// whose walls are far from the grid's axes (the dictionary's blocks stand on them).
fn check_fittable(tris: &[[Vec3; 3]]) -> Result<(), FitError> {
    if tris.is_empty() {
        return Err(FitError::Empty);
    }
    if let Some(r) = rectilinearity(tris)
        && r < MIN_RECTILINEAR
    {
        return Err(FitError::NonRectilinear { share: 100.0 * r.max(0.0) });
    }
    Ok(())
}

/// Lays a grid over the level (about [`VOXELS_ALONG`] voxels along its longest side, padded by
/// the closing radius and two voxels so the outside flood can go round it) and marks the voxels
/// its surfaces pass through.
fn voxelise(tris: &[[Vec3; 3]]) -> Voxels {
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
fn spread(grid: &Grid, seeds: &[IVec3], pass: &dyn Fn(usize) -> bool, limit: u32) -> Vec<u32> {
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
        for st in STEPS {
            let n = c + st;
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
fn flood_outside(voxels: &Voxels) -> Vec<bool> {
    let (grid, wall, close) = (&voxels.grid, &voxels.wall, voxels.close);
    let dims = grid.dims;
    let all: Vec<IVec3> = (0..dims.y)
        .flat_map(|y| (0..dims.z).flat_map(move |z| (0..dims.x).map(move |x| IVec3::new(x, y, z))))
        .collect();
    let surfaces: Vec<IVec3> = all.iter().copied().filter(|c| wall[grid.index(*c)]).collect();
    let near = spread(grid, &surfaces, &|i| !wall[i], close);
    let open = |i: usize| !wall[i] && near[i] == u32::MAX;
    let border: Vec<IVec3> = all
        .iter()
        .copied()
        .filter(|c| (c.cmpeq(IVec3::ZERO).any() || c.cmpeq(dims - 1).any()) && open(grid.index(*c)))
        .collect();
    let flooded = spread(grid, &border, &open, u32::MAX - 1);
    let reached: Vec<IVec3> = all.iter().copied().filter(|c| flooded[grid.index(*c)] != u32::MAX).collect();
    let back = spread(grid, &reached, &|i| !wall[i], close);
    back.iter().map(|d| *d != u32::MAX).collect()
}

/// The enclosed air: voxels neither surface nor outside, less the pieces that are no space to
/// light. A piece thinner than [`THIN`] along some axis is the inside of a wall or slab (its two
/// faces marked, the voxels between them unreached); one inside a closed solid is a solid's.
fn enclosed_air(voxels: &Voxels, outside: &[bool], tris: &[[Vec3; 3]]) -> Vec<bool> {
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
                let centre = grid.origin + (c.as_vec3() + 0.5) * grid.h;
                if (hi - lo + 1).min_element() < thin || inside_solid(tris, centre) {
                    piece.iter().for_each(|p| enclosed[grid.index(*p)] = false);
                }
            }
        }
    }
    enclosed
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

/// The plan (x, z) of the enclosed air, shared by the room stages.
struct Plan {
    /// The grid's minimum corner.
    origin: Vec3,
    /// The voxel size.
    h: f32,
    /// Cells along x and z.
    nx: usize,
    nz: usize,
    /// Per cell (z-major), the vertical range of its column's air (voxel rows), `None` without.
    air: Vec<Option<(i32, i32)>>,
}

impl Plan {
    /// The 4-connected neighbours of cell `i` within the plan (-x, +x, -z, +z).
    fn neighbours(&self, i: usize) -> Vec<usize> {
        let (nx, nz) = (self.nx, self.nz);
        let (x, z) = (i % nx, i / nx);
        let mut out = Vec::with_capacity(4);
        if x > 0 {
            out.push(i - 1);
        }
        if x + 1 < nx {
            out.push(i + 1);
        }
        if z > 0 {
            out.push(i - nx);
        }
        if z + 1 < nz {
            out.push(i + nx);
        }
        out
    }
}

/// Projects the enclosed air onto the plan, where rooms are parted (one storey): the columns
/// holding air, with the air's vertical range. No such column is [`FitError::NoEnclosure`].
fn plan_of(grid: &Grid, enclosed: &[bool]) -> Result<Plan, FitError> {
    let dims = grid.dims;
    let air = |c: IVec3| enclosed[grid.index(c)];
    let (nx, nz) = (dims.x as usize, dims.z as usize);
    let mut plan: Vec<Option<(i32, i32)>> = vec![None; nx * nz];
    for z in 0..dims.z {
        for x in 0..dims.x {
            let ys: Vec<i32> = (0..dims.y).filter(|&y| air(IVec3::new(x, y, z))).collect();
            if let (Some(a), Some(b)) = (ys.first(), ys.last()) {
                plan[z as usize * nx + x as usize] = Some((*a, *b));
            }
        }
    }
    if plan.iter().all(Option::is_none) {
        return Err(FitError::NoEnclosure { voxel: grid.h });
    }
    Ok(Plan { origin: grid.origin, h: grid.h, nx, nz, air: plan })
}

/// Distance (in cells, 4-connected) from each air cell to the nearest non-air cell: the depth
/// the erosion by half a doorway compares with.
fn depth_in_plan(plan: &Plan) -> Vec<u32> {
    let mut dist = vec![u32::MAX; plan.nx * plan.nz];
    let mut queue = VecDeque::new();
    for (i, p) in plan.air.iter().enumerate() {
        if p.is_none() {
            dist[i] = 0;
            queue.push_back(i);
        }
    }
    while let Some(i) = queue.pop_front() {
        for n in plan.neighbours(i) {
            if dist[n] == u32::MAX {
                dist[n] = dist[i] + 1;
                queue.push_back(n);
            }
        }
    }
    dist
}

/// Room cores: air deeper than `r` cells (half a doorway), in connected components, so rooms
/// part at their doorways. Returns each cell's core (`usize::MAX` for none) and each core's cells.
fn room_cores(plan: &Plan, dist: &[u32], r: u32) -> (Vec<usize>, Vec<Vec<usize>>) {
    let (nx, nz) = (plan.nx, plan.nz);
    let mut label = vec![usize::MAX; nx * nz];
    let mut cores: Vec<Vec<usize>> = Vec::new();
    for start in 0..nx * nz {
        if dist[start] <= r || label[start] != usize::MAX {
            continue;
        }
        let id = cores.len();
        let mut members = vec![start];
        label[start] = id;
        let mut k = 0;
        while k < members.len() {
            for n in plan.neighbours(members[k]) {
                if dist[n] > r && label[n] == usize::MAX {
                    label[n] = id;
                    members.push(n);
                }
            }
            k += 1;
        }
        cores.push(members);
    }
    (label, cores)
}

/// The rooms: each core of at least a room's cells, boxed ([`room_box`]), kept where its box's
/// plan is at least [`MIN_ROOM_AREA`], with its core's label. None is [`FitError::NoRoom`].
fn room_boxes(plan: &Plan, cores: &[Vec<usize>], r: u32) -> Result<Vec<(usize, FittedBlock)>, FitError> {
    let h = plan.h;
    let min_cells = (MIN_ROOM_AREA / (h * h)) as usize;
    let mut rooms: Vec<(usize, FittedBlock)> = Vec::new();
    for (id, members) in cores.iter().enumerate() {
        if members.len() < min_cells / 4 {
            continue;
        }
        let (min, max) = room_box(plan, members, r);
        if (max.x - min.x) * (max.z - min.z) >= MIN_ROOM_AREA {
            rooms.push((id, FittedBlock { min, max, openings: [false; 6] }));
        }
    }
    if rooms.is_empty() {
        return Err(FitError::NoRoom);
    }
    Ok(rooms)
}

/// A room's box: its core grown back by `r` cells (the erosion), its air's height. The core's
/// extent is where most of its rows and columns reach (medians): the core bulges a few cells
/// towards each doorway (the air beyond it keeps the cells in front deep).
fn room_box(plan: &Plan, members: &[usize], r: u32) -> (Vec3, Vec3) {
    let (origin, h, nx) = (plan.origin, plan.h, plan.nx);
    // Per row (z) the x range of the core's cells, per column (x) the z range.
    let mut rows: HashMap<usize, (usize, usize)> = HashMap::new();
    let mut cols: HashMap<usize, (usize, usize)> = HashMap::new();
    let (mut y0, mut y1) = (i32::MAX, i32::MIN);
    for &i in members {
        let (x, z) = (i % nx, i / nx);
        let row = rows.entry(z).or_insert((x, x));
        *row = (row.0.min(x), row.1.max(x));
        let col = cols.entry(x).or_insert((z, z));
        *col = (col.0.min(z), col.1.max(z));
        if let Some((a, b)) = plan.air[i] {
            (y0, y1) = (y0.min(a), y1.max(b));
        }
    }
    let median = |mut v: Vec<usize>| {
        v.sort_unstable();
        v[v.len() / 2]
    };
    let x0 = median(rows.values().map(|r| r.0).collect());
    let x1 = median(rows.values().map(|r| r.1).collect());
    let z0 = median(cols.values().map(|c| c.0).collect());
    let z1 = median(cols.values().map(|c| c.1).collect());
    let grow = r as f32 * h;
    let min = Vec3::new(origin.x + x0 as f32 * h - grow, origin.y + y0 as f32 * h, origin.z + z0 as f32 * h - grow);
    let max = Vec3::new(
        origin.x + (x1 + 1) as f32 * h + grow,
        origin.y + (y1 + 1) as f32 * h,
        origin.z + (z1 + 1) as f32 * h + grow,
    );
    (min, max)
}

/// Grows the core labels back over all the air (nearest core first), so that the labels of
/// rooms that touch meet at their doorways.
fn grow_labels(plan: &Plan, label: &mut [usize]) {
    let mut queue: VecDeque<usize> = (0..plan.nx * plan.nz).filter(|&i| label[i] != usize::MAX).collect();
    while let Some(i) = queue.pop_front() {
        for n in plan.neighbours(i) {
            if plan.air[n].is_some() && label[n] == usize::MAX {
                label[n] = label[i];
                queue.push_back(n);
            }
        }
    }
}

/// The doorways: where two rooms' labels meet, the cells on either side as (min, max) world
/// coordinates (y 0), keyed by the rooms' places in `rooms` and sorted, to join them through.
fn doors_between(plan: &Plan, label: &[usize], rooms: &[(usize, FittedBlock)]) -> Vec<(usize, usize, (Vec3, Vec3))> {
    let (origin, h, nx) = (plan.origin, plan.h, plan.nx);
    let mut touching: HashMap<(usize, usize), (Vec3, Vec3)> = HashMap::new();
    let at = |i: usize| Vec3::new(origin.x + (i % nx) as f32 * h, 0.0, origin.z + (i / nx) as f32 * h);
    for i in 0..nx * plan.nz {
        for n in plan.neighbours(i) {
            let (a, b) = (label[i], label[n]);
            if a != usize::MAX && b != usize::MAX && a < b {
                let e = touching.entry((a, b)).or_insert((Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)));
                for c in [at(i), at(n)] {
                    e.0 = e.0.min(c);
                    e.1 = e.1.max(c + Vec3::new(h, 0.0, h));
                }
            }
        }
    }
    let slot = |id: usize| rooms.iter().position(|r| r.0 == id);
    let mut doors: Vec<(usize, usize, (Vec3, Vec3))> =
        touching.iter().filter_map(|(&(a, b), span)| Some((slot(a)?, slot(b)?, *span))).collect();
    doors.sort_by_key(|d| (d.0, d.1));
    doors
}

#[cfg(test)]
mod tests;
