//! What a level's blocks leave out, named so that MRT is never silently partial: an enclosed
//! space no block covers (its surfaces get no indirect light), air joining two blocks that are not
//! linked (a doorway light does not pass), and air running on from one storey into the next (a
//! stairwell: the 2D dictionary links blocks side by side only). Found on the same voxels and
//! storeys as the fit, for fitted and for hand-placed blocks alike.

use std::collections::HashMap;

use glam::Vec3;

use super::rects::fill_pillars;
use super::storeys::Storeys;
use super::voxels::{enclosed_air, flood_outside, voxelise};
use super::{FitError, FittedBlock, MAX_WALL, MIN_ROOM_AREA, MIN_SIDE, Plan, grow_labels};
use crate::precompute::mrt::level::{Block, Level};
use crate::precompute::mrt::proxy::{open_faces, shape_for};
use crate::precompute::mrt::shape::Shape;

/// Uncovered air narrower than this (m) is a sliver along a wall, not a space.
const SLIVER: f32 = 0.3;

/// What is left out, and why.
#[derive(Clone, Debug, PartialEq)]
pub enum GapKind {
    /// An enclosed space no block covers, of this plan area (m²); `narrow` when it is narrower
    /// than the fitter's smallest block.
    Uncovered {
        /// Plan area (m²).
        area: f32,
        /// Narrower than [`MIN_SIDE`].
        narrow: bool,
    },
    /// Air joining blocks `a` and `b`, which are not linked.
    Unlinked {
        /// One block's index.
        a: usize,
        /// The other's.
        b: usize,
    },
    /// Air running on from one storey into the one above.
    Stairwell,
}

/// A gap in a level's blocks: what and where (world bounds).
#[derive(Clone, Debug, PartialEq)]
pub struct Gap {
    /// What.
    pub kind: GapKind,
    /// Minimum corner (m).
    pub min: Vec3,
    /// Maximum corner (m).
    pub max: Vec3,
}

impl Gap {
    /// One sentence: where, why, and what to do; `name` names block `i`.
    pub fn describe(&self, name: &dyn Fn(usize) -> String) -> String {
        let (a, b) = (self.min, self.max);
        let at = format!("x {:.1}..{:.1}, y {:.1}..{:.1}, z {:.1}..{:.1} m", a.x, b.x, a.y, b.y, a.z, b.z);
        match &self.kind {
            GapKind::Uncovered { area, narrow } => format!(
                "no proxy block covers the enclosed space at {at} ({area:.1} m²){}: its surfaces get no indirect light in mrt; add a proxy block over it (Fit proxy blocks, then edit them)",
                if *narrow {
                    format!(", narrower than the smallest block the fitter makes ({MIN_SIDE} m)")
                } else {
                    String::new()
                }
            ),
            GapKind::Unlinked { a, b } => format!(
                "the opening at {at} joins {} and {}, which are not linked: no light passes it in mrt; open the two blocks' facing sides and make them meet on one plane",
                name(*a),
                name(*b)
            ),
            GapKind::Stairwell => format!(
                "the opening between storeys at {at} passes no light in mrt: its 2D dictionary links blocks side by side only, never through a floor or ceiling; light each storey on its own"
            ),
        }
    }
}

/// The sorted pairs of blocks that `blocks`' open sides link ([`Level`]'s rule).
pub(super) fn linked_pairs(blocks: &[FittedBlock]) -> Vec<(usize, usize)> {
    let level = Level::new(
        blocks
            .iter()
            .map(|b| {
                let (shape, turns) = shape_for(&open_faces(&b.openings, 0)).unwrap_or((Shape::Closed, 0));
                Block { shape, origin: b.min, size: b.max - b.min, turns }
            })
            .collect(),
    );
    pairs_of(&level)
}

/// The sorted pairs of blocks `level` links.
pub fn pairs_of(level: &Level) -> Vec<(usize, usize)> {
    let mut out: Vec<(usize, usize)> =
        level.linked_sides().into_iter().filter_map(|(i, w)| level.link(i, w).map(|j| (i.min(j), i.max(j)))).collect();
    out.sort_unstable();
    out.dedup();
    out
}

/// A level's enclosed air cut into storeys: what the gap check reads, independent of the blocks
/// (so an editor can keep it while the artist moves blocks: the survey of the suite's three
/// rooms is most of a level build, 100-160 of 130-200 ms, release, two cores).
pub struct Survey {
    storeys: Storeys,
}

/// Surveys the level `tris` for [`Survey::gaps`].
pub fn survey(tris: &[[Vec3; 3]]) -> Result<Survey, FitError> {
    super::check_fittable(tris)?;
    let voxels = voxelise(tris);
    let outside = flood_outside(&voxels);
    let enclosed = enclosed_air(&voxels, &outside, tris);
    Ok(Survey { storeys: super::storeys::storeys(&voxels.grid, &enclosed)? })
}

impl Survey {
    /// The gaps in `boxes` (world min, max), linked as `linked` says (sorted pairs): the check
    /// for hand-placed blocks.
    pub fn gaps(&self, boxes: &[(Vec3, Vec3)], linked: &[(usize, usize)]) -> Vec<Gap> {
        let blocks: Vec<FittedBlock> =
            boxes.iter().map(|(min, max)| FittedBlock { min: *min, max: *max, openings: [false; 6] }).collect();
        gaps(&self.storeys, &blocks, linked)
    }
}

/// The gaps in `boxes` over the level `tris` ([`survey`], then [`Survey::gaps`]).
pub fn coverage(tris: &[[Vec3; 3]], boxes: &[(Vec3, Vec3)], linked: &[(usize, usize)]) -> Result<Vec<Gap>, FitError> {
    Ok(survey(tris)?.gaps(boxes, linked))
}

/// The gaps of `blocks` in `storeys`.
pub(super) fn gaps(storeys: &Storeys, blocks: &[FittedBlock], linked: &[(usize, usize)]) -> Vec<Gap> {
    let mut out = Vec::new();
    for (k, plan) in storeys.plans.iter().enumerate() {
        let plan = fill_pillars(plan);
        let cover = covering(&plan, blocks);
        out.extend(uncovered(&plan, &cover));
        out.extend(unlinked(&plan, cover, blocks, linked));
        if let Some(top) = storeys.bottoms.get(k + 1) {
            out.extend(stairwells(&plan, &storeys.shafts[k], *top));
        }
    }
    out
}

/// Per plan cell, the first block whose box holds its centre and at least half its air
/// (`usize::MAX` for none, and for cells without air).
fn covering(plan: &Plan, blocks: &[FittedBlock]) -> Vec<usize> {
    let (o, h, nx) = (plan.origin, plan.h, plan.nx);
    (0..nx * plan.nz)
        .map(|i| {
            let Some((a, b)) = plan.air[i] else { return usize::MAX };
            let (x, z) = (o.x + ((i % nx) as f32 + 0.5) * h, o.z + ((i / nx) as f32 + 0.5) * h);
            let (y0, y1) = (o.y + a as f32 * h, o.y + (b + 1) as f32 * h);
            blocks
                .iter()
                .position(|k| {
                    let overlap = k.max.y.min(y1) - k.min.y.max(y0);
                    (k.min.x..=k.max.x).contains(&x) && (k.min.z..=k.max.z).contains(&z) && overlap >= 0.5 * (y1 - y0)
                })
                .unwrap_or(usize::MAX)
        })
        .collect()
}

/// The world bounds of `cells` of `plan`, over their air's heights.
fn bounds(plan: &Plan, cells: &[usize]) -> (Vec3, Vec3) {
    let (o, h, nx) = (plan.origin, plan.h, plan.nx);
    let mut lo = Vec3::splat(f32::MAX);
    let mut hi = Vec3::splat(f32::MIN);
    for &i in cells {
        let (a, b) = plan.air[i].unwrap_or((0, -1));
        let c = Vec3::new(o.x + (i % nx) as f32 * h, o.y + a as f32 * h, o.z + (i / nx) as f32 * h);
        lo = lo.min(c);
        hi = hi.max(Vec3::new(c.x + h, o.y + (b + 1) as f32 * h, c.z + h));
    }
    (lo, hi)
}

/// The enclosed spaces no block covers: components of uncovered air of at least a room's area
/// and wider than a sliver.
fn uncovered(plan: &Plan, cover: &[usize]) -> Vec<Gap> {
    let free = |i: usize| plan.air[i].is_some() && cover[i] == usize::MAX;
    let min_cells = (MIN_ROOM_AREA / (plan.h * plan.h)).ceil() as usize;
    let sliver = ((SLIVER / plan.h).ceil() as usize).max(2);
    let mut out = Vec::new();
    for cells in super::rects::components(plan, &free) {
        if cells.len() < min_cells {
            continue;
        }
        // The component alone: every other cell taken.
        let mut alone = vec![true; cover.len()];
        cells.iter().for_each(|&i| alone[i] = false);
        let side = super::rects::square_side(plan, &alone);
        if side < sliver {
            continue;
        }
        let (min, max) = bounds(plan, &cells);
        let area = cells.len() as f32 * plan.h * plan.h;
        out.push(Gap { kind: GapKind::Uncovered { area, narrow: (side as f32) * plan.h < MIN_SIDE }, min, max });
    }
    out
}

/// The air joining two blocks that are not linked: the blocks' cells grown over uncovered air
/// (at most [`MAX_WALL`]), where two meet.
fn unlinked(plan: &Plan, mut label: Vec<usize>, blocks: &[FittedBlock], linked: &[(usize, usize)]) -> Vec<Gap> {
    grow_labels(plan, &mut label, (MAX_WALL / plan.h).ceil() as u32);
    let mut meets: HashMap<(usize, usize), Vec<usize>> = HashMap::new();
    for i in 0..label.len() {
        for n in plan.neighbours(i) {
            let (a, b) = (label[i], label[n]);
            if a != usize::MAX && b != usize::MAX && a != b && linked.binary_search(&(a.min(b), a.max(b))).is_err() {
                meets.entry((a.min(b), a.max(b))).or_default().extend([i, n]);
            }
        }
    }
    let mut out: Vec<Gap> = meets
        .into_iter()
        .map(|((a, b), cells)| {
            let (mut min, mut max) = bounds(plan, &cells);
            min.y = min.y.max(blocks[a].min.y.max(blocks[b].min.y));
            max.y = max.y.min(blocks[a].max.y.min(blocks[b].max.y)).max(min.y);
            Gap { kind: GapKind::Unlinked { a, b }, min, max }
        })
        .collect();
    out.sort_by_key(|g| match g.kind {
        GapKind::Unlinked { a, b } => (a, b),
        _ => (0, 0),
    });
    out
}

/// The stairwells: the components of the columns whose air runs on above row `top`.
fn stairwells(plan: &Plan, shaft: &[usize], top: i32) -> Vec<Gap> {
    let set: std::collections::HashSet<usize> = shaft.iter().copied().collect();
    let min_cells = ((MIN_SIDE * MIN_SIDE) / (plan.h * plan.h)).ceil() as usize;
    super::rects::components(plan, &|i| set.contains(&i))
        .into_iter()
        .filter(|cells| cells.len() >= min_cells)
        .map(|cells| {
            let (mut min, mut max) = bounds(plan, &cells);
            let y = plan.origin.y + top as f32 * plan.h;
            (min.y, max.y) = (y, y);
            Gap { kind: GapKind::Stairwell, min, max }
        })
        .collect()
}
