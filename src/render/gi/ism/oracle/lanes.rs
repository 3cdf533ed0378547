//! How evenly the splat pass's lanes share its work (`ism_splat.wgsl`), from the last set's
//! chosen points and their footprints as the GPU made them. A GPU runs a compute pass's threads
//! in lock-step groups (32 lanes on NVIDIA, 8 on lavapipe's 256-bit SIMD): a group takes as long
//! as its busiest lane, so a few points whose footprints fill 33 rows keep the rest of their
//! group idle. The software adapter's timings cannot show what that costs a GPU; this counts it.
//! It counts the texel walks alone: the dealt-out kernel's first walk (each lane counting its own
//! point's texels, row by row) and its set-ups are left out, so its share is an upper bound.

use super::*;

/// The splat's texels as its two ways of sharing them out would walk them.
#[derive(Clone, Debug, PartialEq)]
pub struct LaneReport {
    /// Points with a footprint (the last set's), and their footprints' rows and texels walked.
    pub points: usize,
    /// Chosen points the splat drops: of dead VPLs, behind their VPL, seen edge-on from it.
    pub dropped: [usize; 3],
    pub rows: u64,
    pub texels: u64,
    /// The largest footprint: rows, texels.
    pub largest: (u32, u64),
    /// Per lane-group width: the width and the share of the lanes' time spent walking texels
    /// with a thread per point, with each workgroup's rows dealt out in equal runs, and with its
    /// texels dealt out in equal runs (what `ism_splat.wgsl` does).
    pub busy: Vec<(usize, [f64; 3])>,
}

/// The rows of one footprint and the texels each walks, as `ism_splat.wgsl` walks them (its box
/// clamped to the tile, each row's columns: `row_columns`, `row_span` in `ism_footprint.wgsl`).
fn row_walks(fp: &Footprint, r: i32) -> Vec<u64> {
    const SLACK: f32 = 0.01;
    let (ta, tb) = (fp.ta, fp.tb);
    let m00 = ta.x * ta.x + tb.x * tb.x + 0.25;
    let m01 = ta.x * ta.y + tb.x * tb.y;
    let m11 = ta.y * ta.y + tb.y * tb.y + 0.25;
    let det = m00 * m11 - m01 * m01;
    let cap = crate::render::gi::ism::gather::MAX_SPLAT_HALF_EXTENT;
    let ext = Vec2::new(m00.sqrt().min(cap), m11.sqrt().min(cap));
    let (lo, hi) = ((fp.centre - ext).floor().as_ivec2(), (fp.centre + ext).floor().as_ivec2());
    let c = fp.centre;
    (lo.y.max(0)..=hi.y.min(r - 1))
        .map(|y| {
            let qy = y as f32 + 0.5 - c.y;
            let disc = det * (m11 - qy * qy);
            let mut span = if disc >= 0.0 {
                let root = disc.sqrt();
                (
                    (c.x - 0.5 + (m01 * qy - root) / m11 - SLACK).ceil() as i32,
                    (c.x - 0.5 + (m01 * qy + root) / m11 + SLACK).floor() as i32,
                )
            } else {
                (1, 0)
            };
            if y == c.y as i32 {
                let own = c.x as i32;
                span = if span.0 > span.1 { (own, own) } else { (span.0.min(own), span.1.max(own)) };
            }
            let (x0, x1) = (lo.x.max(span.0).max(0), hi.x.min(span.1).min(r - 1));
            (x1 - x0 + 1).max(0) as u64
        })
        .collect()
}

/// The share of `groups`' lane time spent on work: sum of the lanes' work over width x the
/// busiest lane, summed over groups of `width` consecutive lanes.
fn busy_share(lanes: &[u64], width: usize) -> f64 {
    let work: u64 = lanes.iter().sum();
    let time: u64 = lanes.chunks(width).map(|g| g.iter().max().copied().unwrap_or(0) * width as u64).sum();
    if time == 0 { 1.0 } else { work as f64 / time as f64 }
}

/// Each workgroup's (64 slots) rows dealt out in equal runs of consecutive rows: per thread,
/// the texels of its run.
fn row_lanes(per_slot: &[Vec<u64>]) -> Vec<u64> {
    let mut lanes = Vec::with_capacity(per_slot.len());
    for group in per_slot.chunks(GROUP) {
        let rows: Vec<u64> = group.iter().flatten().copied().collect();
        let run = rows.len().div_ceil(GROUP).max(1);
        let mut chunks: Vec<u64> = rows.chunks(run).map(|c| c.iter().sum()).collect();
        chunks.resize(GROUP, 0);
        lanes.extend(chunks);
    }
    lanes
}

/// Each workgroup's texels dealt out in equal runs: per thread, its run's length.
fn texel_lanes(per_slot: &[Vec<u64>]) -> Vec<u64> {
    let mut lanes = Vec::with_capacity(per_slot.len());
    for group in per_slot.chunks(GROUP) {
        let total: u64 = group.iter().flatten().sum();
        let run = total.div_ceil(GROUP as u64);
        lanes.extend((0..GROUP as u64).map(|t| total.saturating_sub(t * run).min(run)));
    }
    lanes
}

/// Why the splat pass drops point `p` of `tile` (`splat_setup`): 0 its VPL is dead, 1 the point
/// lies behind it, 2 it is seen edge-on; `None` when it splats.
fn dropped(tile: &PointsReport, p: &ChosenPoint) -> Option<usize> {
    const ON_PLANE: f32 = 2.0e-3;
    let (o, n) = (Vec3::from_slice(&tile.position[..3]), Vec3::from_slice(&tile.normal[..3]));
    let (q, pn) = (Vec3::from_slice(&p.position[..3]), Vec3::from_slice(&p.normal[..3]));
    if tile.position[3] <= 0.0 {
        Some(0)
    } else if (q - o).dot(n) <= 0.0 {
        Some(1)
    } else if (q - o).dot(pn).abs() <= ON_PLANE * q.distance(o) {
        Some(2)
    } else {
        None
    }
}

/// Threads per workgroup of the splat pass.
const GROUP: usize = 64;

/// The splat lanes' report over the last set's tiles (the only ones whose splat areas the
/// renderer keeps), for lane groups of each width in `widths`.
pub fn splat_lanes(c: &Capture, renderer: &Renderer, widths: &[usize]) -> Result<LaneReport, OracleError> {
    let n = c.n().max(1);
    let last = c.ism.bounces.max(1) as usize - 1;
    let r = c.res() as i32;
    let chosen = read_chosen(renderer)?;
    let mut per_slot: Vec<Vec<u64>> = Vec::new();
    let mut drops = [0usize; 3];
    for tile in last * n..(last + 1) * n {
        let report = list_chosen_points(c, &chosen, &PointsQuery { tile, ..PointsQuery::default() })?;
        let mut slots = vec![Vec::new(); c.lookup.per_ism as usize];
        for p in &report.points {
            if let Some(why) = dropped(&report, p) {
                drops[why] += 1;
            } else if let (Some(fp), Some(slot)) = (&p.footprint, slots.get_mut(p.slot)) {
                *slot = row_walks(fp, r);
            }
        }
        per_slot.extend(slots);
    }
    let per_point: Vec<u64> = per_slot.iter().map(|rows| rows.iter().sum()).collect();
    let (rows, texels) = (row_lanes(&per_slot), texel_lanes(&per_slot));
    let largest = per_slot.iter().map(|rows| (rows.len() as u32, rows.iter().sum::<u64>())).max_by_key(|l| l.1);
    Ok(LaneReport {
        points: per_slot.iter().filter(|rows| !rows.is_empty()).count(),
        dropped: drops,
        rows: per_slot.iter().map(|rows| rows.len() as u64).sum(),
        texels: per_point.iter().sum(),
        largest: largest.unwrap_or((0, 0)),
        busy: widths
            .iter()
            .map(|&w| (w, [busy_share(&per_point, w), busy_share(&rows, w), busy_share(&texels, w)]))
            .collect(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_large_point_idles_its_group_and_shared_texels_do_not() {
        // 63 points of one row of 4 texels and one of 33 rows of 33.
        let mut slots = vec![vec![4u64]; 63];
        slots.push(vec![33; 33]);
        let per_point: Vec<u64> = slots.iter().map(|r| r.iter().sum()).collect();
        let work = 63 * 4 + 33 * 33;
        // Lanes 32-63: 31 x 4 + 1089 of work in 32 x 1089 of time.
        let expected = work as f64 / (32.0 * 4.0 + 32.0 * 1089.0);
        assert!((busy_share(&per_point, 32) - expected).abs() < 1e-12);
        let rows = row_lanes(&slots);
        assert_eq!(rows.iter().sum::<u64>(), work);
        let texels = texel_lanes(&slots);
        assert_eq!(texels.iter().sum::<u64>(), work);
        // 1341 texels in runs of 21: 63 full lanes and one of 18.
        assert_eq!(texels.iter().filter(|&&t| t == 21).count(), 63);
        assert!(busy_share(&texels, 32) > 0.99, "{}", busy_share(&texels, 32));
        assert!(busy_share(&rows, 32) < busy_share(&texels, 32));
    }
}
