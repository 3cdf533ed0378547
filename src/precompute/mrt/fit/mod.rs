//! Fitting MRT proxy blocks to a level's geometry (the "fit proxy blocks" command, for rectilinear
//! levels): voxelise the triangles, flood the outside from the grid's border (through voxels
//! farther than a closing radius from any surface, so a window does not open a room, then spread
//! back by it) and keep the enclosed air ([`voxels`]); cut it into storeys ([`storeys`]); cover
//! each storey's plan with rectangles of one ceiling height, largest squares first
//! ([`rects`]: a room is one block, an L-shaped room two, a corridor its own), snap their sides to
//! the walls' planes; grow the blocks' labels over the doorways' air so blocks that face each
//! other through a doorway meet there, and join them ([`super::doorways`]). What the blocks leave
//! out is reported, never silent ([`gaps`]): an enclosed space no block covers, a doorway between
//! blocks that are not linked, a stairwell between storeys (the 2D dictionary links blocks side by
//! side only). What it cannot fit at all is a named error: no enclosed air (an open field, a
//! courtyard), a level far from axis-aligned (a sphere).
//!
//! Loos leaves fitting to the artist (§4.3.1) and names it open research (§7.1); thresholds here
//! are starting values, each a constant below.

pub mod carve;
mod gaps;
mod rects;
pub mod shapes;
mod storeys;
mod voxels;

use std::collections::HashMap;
use std::collections::VecDeque;

use glam::Vec3;
use thiserror::Error;

pub use gaps::{Gap, GapKind, Survey, coverage, pairs_of, survey};
use voxels::{enclosed_air, flood_outside, voxelise};

/// Voxels along the level's longest side (the voxel is at most 0.25 m and at least 2 cm).
const VOXELS_ALONG: f32 = 160.0;
/// The smallest room kept (m², plan).
const MIN_ROOM_AREA: f32 = 1.0;
/// The narrowest block (m): air narrower than this (a doorway's depth in its wall, a corridor
/// shorter than this) joins the blocks on either side.
const MIN_SIDE: f32 = 0.5;
/// The widest gap between two blocks whose facing sides are joined (m): a wall, or a corridor
/// narrower than a block between two walls.
pub(super) const MAX_WALL: f32 = 1.2;
/// The closing radius of the outside flood (m): windows and exterior doors up to twice it do not
/// open a room to the outside.
const CLOSE: f32 = 1.0;
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
        "no enclosed space: the outside reaches everywhere (an open field, a courtyard open to the sky, a lone surface, or walls with gaps wider than a voxel of {voxel:.2} m)"
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
    #[error(
        "no enclosed room of at least {MIN_ROOM_AREA} m²: the outside reaches every larger space (an open field, a courtyard open to the sky)"
    )]
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

/// The fitted blocks and what they leave out.
#[derive(Clone, Debug, PartialEq)]
pub struct FitReport {
    /// The blocks.
    pub blocks: Vec<FittedBlock>,
    /// Enclosed spaces without a block, doorways without a link, stairwells (empty when the
    /// blocks cover the whole level).
    pub gaps: Vec<Gap>,
}

/// Fits blocks to the level `tris` (world triangles, y up).
pub fn fit(tris: &[[Vec3; 3]]) -> Result<Vec<FittedBlock>, FitError> {
    Ok(fit_report(tris)?.blocks)
}

/// Fits blocks to the level `tris` and reports what they leave out ([`gaps`]).
pub fn fit_report(tris: &[[Vec3; 3]]) -> Result<FitReport, FitError> {
    check_fittable(tris)?;
    let voxels = voxelise(tris);
    let outside = flood_outside(&voxels);
    let enclosed = enclosed_air(&voxels, &outside, tris);
    let storeys = storeys::storeys(&voxels.grid, &enclosed)?;
    let planes = Planes::of(tris);
    let mut rooms = Vec::new();
    let mut doors = Vec::new();
    for plan in &storeys.plans {
        let filled = rects::fill_pillars(plan);
        let found = rects::decompose(&filled);
        let mut label = vec![usize::MAX; filled.nx * filled.nz];
        for (k, r) in found.iter().enumerate() {
            rects::cells_of(&filled, r).into_iter().for_each(|i| label[i] = rooms.len() + k);
        }
        grow_labels(&filled, &mut label, (MAX_WALL / filled.h).ceil() as u32);
        doors.extend(doors_between(&filled, &label));
        rooms.extend(found.iter().map(|r| block_of(&filled, r, &planes)));
    }
    if rooms.is_empty() {
        return Err(FitError::NoRoom);
    }
    doors.sort_by_key(|d| (d.0, d.1));
    let blocks = super::doorways::split_at_doors(rooms, &doors);
    let gaps = gaps::gaps(&storeys, &blocks, &gaps::linked_pairs(&blocks));
    Ok(FitReport { blocks, gaps })
}

/// The level's axis-aligned planes, to snap a block's sides from voxel bounds to the walls.
struct Planes {
    /// Per axis (x, y, z), each plane's coordinate and whether its front faces +axis.
    per_axis: [Vec<(f32, bool)>; 3],
}

impl Planes {
    fn of(tris: &[[Vec3; 3]]) -> Self {
        let mut per_axis: [Vec<(f32, bool)>; 3] = Default::default();
        for t in tris {
            let n = (t[1] - t[0]).cross(t[2] - t[0]).normalize_or_zero();
            for (axis, list) in per_axis.iter_mut().enumerate() {
                if n[axis].abs() > 0.999 {
                    list.push((t[0][axis], n[axis] > 0.0));
                }
            }
        }
        for list in &mut per_axis {
            list.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
            list.dedup_by(|a, b| (a.0 - b.0).abs() < 1e-5 && a.1 == b.1);
        }
        Self { per_axis }
    }

    /// `v`, a side of air bounded by voxels, moved to the nearest plane within `reach` beyond it
    /// (towards +axis for a maximum side, -axis for a minimum side) that faces back into the air;
    /// `v` itself where none does.
    fn snap(&self, axis: usize, v: f32, reach: f32, max_side: bool) -> f32 {
        let facing = !max_side;
        self.per_axis[axis]
            .iter()
            .filter(|(c, front)| {
                *front == facing
                    && if max_side { *c >= v - 1e-4 && *c <= v + reach } else { *c <= v + 1e-4 && *c >= v - reach }
            })
            .map(|(c, _)| *c)
            .min_by(|a, b| (a - v).abs().total_cmp(&(b - v).abs()))
            .unwrap_or(v)
    }
}

/// The world box of rectangle `r` of `plan`: its cells' bounds and its air's median height,
/// each side snapped to the wall plane just beyond it.
fn block_of(plan: &Plan, r: &rects::Rect, planes: &Planes) -> FittedBlock {
    let (o, h) = (plan.origin, plan.h);
    let (y0, y1) = rects::heights(plan, r);
    let lo = Vec3::new(o.x + r.x0 as f32 * h, o.y + y0 as f32 * h, o.z + r.z0 as f32 * h);
    let hi = Vec3::new(o.x + r.x1 as f32 * h, o.y + (y1 + 1) as f32 * h, o.z + r.z1 as f32 * h);
    let reach = 1.01 * h;
    let min = Vec3::from_array(std::array::from_fn(|a| planes.snap(a, lo[a], reach, false)));
    let max = Vec3::from_array(std::array::from_fn(|a| planes.snap(a, hi[a], reach, true)));
    FittedBlock { min, max, openings: [false; 6] }
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

/// The plan (x, z) of the enclosed air, shared by the room stages.
#[derive(Clone)]
pub(super) struct Plan {
    /// The grid's minimum corner.
    pub(super) origin: Vec3,
    /// The voxel size.
    pub(super) h: f32,
    /// Cells along x.
    pub(super) nx: usize,
    /// Cells along z.
    pub(super) nz: usize,
    /// Per cell (z-major), the vertical range of its column's air (voxel rows), `None` without.
    pub(super) air: Vec<Option<(i32, i32)>>,
}

impl Plan {
    /// The 4-connected neighbours of cell `i` within the plan (-x, +x, -z, +z).
    pub(super) fn neighbours(&self, i: usize) -> Vec<usize> {
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

/// Grows the blocks' labels over the air (nearest block first, at most `limit` cells), so that
/// the labels of blocks that face each other through a doorway meet in it.
fn grow_labels(plan: &Plan, label: &mut [usize], limit: u32) {
    let mut dist = vec![0u32; label.len()];
    let mut queue: VecDeque<usize> = (0..plan.nx * plan.nz).filter(|&i| label[i] != usize::MAX).collect();
    while let Some(i) = queue.pop_front() {
        if dist[i] >= limit {
            continue;
        }
        for n in plan.neighbours(i) {
            if plan.air[n].is_some() && label[n] == usize::MAX {
                label[n] = label[i];
                dist[n] = dist[i] + 1;
                queue.push_back(n);
            }
        }
    }
}

/// The doorways: where two blocks' labels meet, the cells on either side as (min, max) world
/// coordinates (y 0), keyed by the blocks' labels (sorted pairs), to join them through.
fn doors_between(plan: &Plan, label: &[usize]) -> Vec<(usize, usize, (Vec3, Vec3))> {
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
    touching.into_iter().map(|((a, b), span)| (a, b, span)).collect()
}

#[cfg(test)]
mod tests;
