//! Storeys: the enclosed air cut into horizontal bands at the floors that cover much of the
//! level's plan, each band's air projected onto its plan (where rooms are parted), and the
//! columns where air runs on from one band into the next (a stairwell, a double-height hall):
//! the 2D dictionary links blocks side by side only, so the fit reports those.

use glam::IVec3;

use super::voxels::Grid;
use super::{FitError, Plan, THIN};

/// A floor that starts a storey covers at least this share of the level's plan (a bed or a
/// stage covers less).
const STOREY_SHARE: f32 = 0.2;
/// Floors nearer than this above the previous storey's floor belong to it (m): a sunken room,
/// a raised stage.
const STOREY_MIN: f32 = 1.8;

/// The level's storeys.
pub(super) struct Storeys {
    /// Per storey (bottom up), its plan.
    pub(super) plans: Vec<Plan>,
    /// Per storey, the plan cells (z-major) whose air runs on into the storey above.
    pub(super) shafts: Vec<Vec<usize>>,
    /// Per storey, its lowest voxel row (the band's bottom).
    pub(super) bottoms: Vec<i32>,
}

/// Per voxel row, how many columns have air starting there (a floor under it).
fn floor_counts(grid: &Grid, enclosed: &[bool]) -> (Vec<usize>, usize) {
    let dims = grid.dims;
    let mut counts = vec![0usize; dims.y as usize];
    let mut columns = 0;
    for z in 0..dims.z {
        for x in 0..dims.x {
            let mut any = false;
            for y in 0..dims.y {
                let here = enclosed[grid.index(IVec3::new(x, y, z))];
                let below = y > 0 && enclosed[grid.index(IVec3::new(x, y - 1, z))];
                if here && !below {
                    counts[y as usize] += 1;
                }
                any |= here;
            }
            columns += usize::from(any);
        }
    }
    (counts, columns)
}

/// The voxel rows where storeys start above the lowest: floors under at least
/// [`STOREY_SHARE`] of the plan, at least [`STOREY_MIN`] above the storey below.
fn storey_floors(grid: &Grid, counts: &[usize], columns: usize) -> Vec<i32> {
    let min_rows = (STOREY_MIN / grid.h).ceil() as i32;
    let mut floors: Vec<i32> = Vec::new();
    for (y, count) in counts.iter().enumerate() {
        let y = y as i32;
        if (*count as f32) < STOREY_SHARE * columns as f32 {
            continue;
        }
        if floors.last().is_none_or(|last| y - last >= min_rows) {
            floors.push(y);
        }
    }
    // The lowest floor starts the first band, which begins at the grid's bottom anyway.
    floors.into_iter().skip(1).collect()
}

/// The plan of the band of rows `lo .. hi`: per column the range of its air in the band, where
/// it holds at least [`THIN`] of air; and the columns whose air runs on into row `hi`.
fn band_plan(grid: &Grid, enclosed: &[bool], lo: i32, hi: i32) -> (Plan, Vec<usize>) {
    let dims = grid.dims;
    let (nx, nz) = (dims.x as usize, dims.z as usize);
    let thin = (THIN / grid.h).ceil() as usize;
    let mut air = vec![None; nx * nz];
    let mut shaft = Vec::new();
    for z in 0..dims.z {
        for x in 0..dims.x {
            let at = |y: i32| enclosed[grid.index(IVec3::new(x, y, z))];
            let rows: Vec<i32> = (lo..hi).filter(|&y| at(y)).collect();
            let i = z as usize * nx + x as usize;
            if let (Some(a), Some(b)) = (rows.first(), rows.last())
                && rows.len() >= thin
            {
                air[i] = Some((*a, *b));
                if hi < dims.y && *b == hi - 1 && at(hi) {
                    shaft.push(i);
                }
            }
        }
    }
    (Plan { origin: grid.origin, h: grid.h, nx, nz, air }, shaft)
}

/// Cuts the enclosed air into storeys; none holding air is [`FitError::NoEnclosure`].
pub(super) fn storeys(grid: &Grid, enclosed: &[bool]) -> Result<Storeys, FitError> {
    let (counts, columns) = floor_counts(grid, enclosed);
    let mut bounds = vec![0];
    bounds.extend(storey_floors(grid, &counts, columns));
    bounds.push(grid.dims.y);
    let mut out = Storeys { plans: Vec::new(), shafts: Vec::new(), bottoms: Vec::new() };
    for w in bounds.windows(2) {
        let (plan, shaft) = band_plan(grid, enclosed, w[0], w[1]);
        out.plans.push(plan);
        out.shafts.push(shaft);
        out.bottoms.push(w[0]);
    }
    if out.plans.iter().all(|p| p.air.iter().all(Option::is_none)) {
        return Err(FitError::NoEnclosure { voxel: grid.h });
    }
    Ok(out)
}
