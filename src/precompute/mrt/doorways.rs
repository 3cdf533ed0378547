//! Joining fitted rooms through their doorways (the second half of [`super::fit`]): which rooms
//! stay one block and which are split into strips at their doorways' jambs, and opening and
//! snapping the facing sides of blocks that meet through a doorway to the wall's mid-plane.

use std::collections::HashMap;

use glam::Vec3;

use super::fit::{FittedBlock, MAX_WALL};

/// How far a long room's cut keeps from a doorway's jambs (m): the doorway's span comes from
/// plan cells (up to 0.25 m) meeting in the wall, so it can fall short of the real jambs; a cut
/// through a 60 m hall's side doorway left the side room 0.16 of the brute force's light.
const JAMB_CLEARANCE: f32 = 0.5;
/// The thinnest strip a room is split into at a door jamb (m); jambs nearer a room's corner move
/// to the corner.
const MIN_STRIP: f32 = 0.3;

/// Joins rooms through their doorways. A room with at most one doorway per side stays one block
/// (its doorway sides open; the level passes light only where the doorway is and the wall
/// around it reflects, see
/// `geometry_image::openings`). A room with two doorways on one side is split into strips
/// at its doorways' jambs, so that each doorway is a whole side of one strip (the 2D dictionary
/// opens whole sides only, one neighbour per side), the sides between its strips open. Measured
/// on the suite's rooms (one bounce per room against a brute force in the real level,
/// `bouncelab probe-mrt rooms --rays 256`): strips everywhere 0.92 / 0.97 / 1.29, whole rooms 0.99 / 0.94 /
/// 0.87; thin strips (0.4 m x 5 m) are far from the unit cube the operators assume. A long
/// room is then cut into near-cubic parts (below), which on `tools/dev_levels.py`'s levels took
/// the second room from 1.71x to 1.09x of the brute force (16 bounces) and the suite's window,
/// clutter and hall FLIP from 0.083 / 0.192 / 0.093 to 0.080 / 0.167 / 0.084.
pub(super) fn split_at_doors(rooms: Vec<FittedBlock>, doors: &[(usize, usize, (Vec3, Vec3))]) -> Vec<FittedBlock> {
    let (mut cuts, crossings, split) = doorway_cuts(&rooms, doors);
    long_room_cuts(&rooms, &split, &crossings, &mut cuts);
    let (mut out, of_room) = cut_rooms(&rooms, &cuts);
    join_through(&mut out, &of_room, &crossings);
    out
}

/// A doorway between rooms `a` and `b`: the axis it crosses (0 x, 2 z) and its span `t0 .. t1`
/// along the other horizontal axis.
struct Crossing {
    a: usize,
    b: usize,
    axis: usize,
    t0: f32,
    t1: f32,
}

/// Per room, its cut positions along x and along z.
type Cuts = Vec<[Vec<f32>; 2]>;

/// Which axis a door between `a` and `b` crosses (0 x, 2 z), from the rooms' boxes: the one
/// across which they lie side by side (a gap of at most a wall) while overlapping along the
/// other, the wider overlap where both would do.
fn crossing_axis(a: &FittedBlock, b: &FittedBlock) -> Option<usize> {
    [0usize, 2]
        .into_iter()
        .filter_map(|axis| {
            let gap = (b.min[axis] - a.max[axis]).max(a.min[axis] - b.max[axis]);
            let other = 2 - axis;
            let overlap = a.max[other].min(b.max[other]) - a.min[other].max(b.min[other]);
            ((-MAX_WALL..=MAX_WALL).contains(&gap) && overlap > 0.0).then_some((axis, overlap))
        })
        .max_by(|x, y| x.1.total_cmp(&y.1))
        .map(|(axis, _)| axis)
}

/// The doorways as crossings, which rooms are split into strips (a side with two doorways: a
/// room whose every side has at most one stays whole, its doorway side open and masked to the
/// doorway, the level's openings), and those rooms' cuts at their doorways' jambs.
fn doorway_cuts(rooms: &[FittedBlock], doors: &[(usize, usize, (Vec3, Vec3))]) -> (Cuts, Vec<Crossing>, Vec<bool>) {
    let mut per_side: HashMap<(usize, usize, bool), usize> = HashMap::new();
    let mut crossings = Vec::new();
    for &(a, b, (lo, hi)) in doors {
        let Some(axis) = crossing_axis(&rooms[a], &rooms[b]) else { continue };
        let b_after = rooms[b].min[axis] > rooms[a].min[axis];
        *per_side.entry((a, axis, b_after)).or_default() += 1;
        *per_side.entry((b, axis, !b_after)).or_default() += 1;
        let along = 2 - axis;
        crossings.push(Crossing { a, b, axis, t0: lo[along], t1: hi[along] });
    }
    let split: Vec<bool> = (0..rooms.len()).map(|r| per_side.iter().any(|(k, n)| k.0 == r && *n > 1)).collect();
    let mut cuts: Cuts = vec![[Vec::new(), Vec::new()]; rooms.len()];
    for c in &crossings {
        for r in [c.a, c.b].into_iter().filter(|r| split[*r]) {
            cuts[r][usize::from(c.axis == 0)].extend([c.t0, c.t1]);
        }
    }
    (cuts, crossings, split)
}

/// Long rooms (Loos 2015 §3.7.1: one stretched cube carries light too far along its long axis;
/// the dissertation's fix is more blocks): a room not split at its doorways is cut into
/// near-cubic parts along each horizontal axis, each part about as long as the mean of the
/// room's other two extents. No cut passes through a doorway on a long side or within
/// [`JAMB_CLEARANCE`] of it (it moves past the nearer jamb), so each doorway opens into one part,
/// the one joined through it.
fn long_room_cuts(rooms: &[FittedBlock], split: &[bool], crossings: &[Crossing], cuts: &mut Cuts) {
    for (r, room) in rooms.iter().enumerate().filter(|(r, _)| !split[*r]) {
        for (k, axis) in [(0usize, 0usize), (1, 2)] {
            let other = 2 - axis;
            let spans: Vec<(f32, f32)> = crossings
                .iter()
                .filter(|c| (c.a == r || c.b == r) && c.axis == other)
                .map(|c| (c.t0 - JAMB_CLEARANCE, c.t1 + JAMB_CLEARANCE))
                .collect();
            let size = room.max - room.min;
            let target = 0.5 * (size[other] + size.y);
            let n = (size[axis] / target).round().max(1.0) as usize;
            cuts[r][k].extend((1..n).map(|i| {
                let c = room.min[axis] + size[axis] * i as f32 / n as f32;
                spans
                    .iter()
                    .find(|(t0, t1)| c > *t0 && c < *t1)
                    .map_or(c, |(t0, t1)| if c - t0 < t1 - c { *t0 } else { *t1 })
            }));
        }
    }
}

/// The intervals of `lo .. hi` at `cuts`, none thinner than [`MIN_STRIP`].
fn intervals(lo: f32, hi: f32, cuts: &[f32]) -> Vec<(f32, f32)> {
    let mut edges = vec![lo];
    let mut inner: Vec<f32> = cuts.iter().copied().filter(|c| *c > lo + MIN_STRIP && *c < hi - MIN_STRIP).collect();
    inner.sort_by(f32::total_cmp);
    for c in inner {
        if c - edges.last().copied().unwrap_or(lo) >= MIN_STRIP {
            edges.push(c);
        }
    }
    if hi - edges.last().copied().unwrap_or(lo) < MIN_STRIP && edges.len() > 1 {
        edges.pop();
    }
    edges.push(hi);
    edges.windows(2).map(|w| (w[0], w[1])).collect()
}

/// Each room's strips: a grid of x intervals by z intervals, open to each other; and per room
/// its strips' places in the output.
fn cut_rooms(rooms: &[FittedBlock], cuts: &Cuts) -> (Vec<FittedBlock>, Vec<Vec<usize>>) {
    let mut out: Vec<FittedBlock> = Vec::new();
    let mut of_room: Vec<Vec<usize>> = Vec::new();
    for (r, room) in rooms.iter().enumerate() {
        let xs = intervals(room.min.x, room.max.x, &cuts[r][0]);
        let zs = intervals(room.min.z, room.max.z, &cuts[r][1]);
        let mut mine = Vec::new();
        for (ix, x) in xs.iter().enumerate() {
            for (iz, z) in zs.iter().enumerate() {
                let mut openings = room.openings;
                openings[0] |= ix + 1 < xs.len();
                openings[1] |= ix > 0;
                openings[4] |= iz + 1 < zs.len();
                openings[5] |= iz > 0;
                mine.push(out.len());
                out.push(FittedBlock {
                    min: Vec3::new(x.0, room.min.y, z.0),
                    max: Vec3::new(x.1, room.max.y, z.1),
                    openings,
                });
            }
        }
        of_room.push(mine);
    }
    (out, of_room)
}

/// Through each doorway: the strips of either room inside the doorway's span (or holding its
/// centre) and on the side facing the other room are joined.
fn join_through(out: &mut [FittedBlock], of_room: &[Vec<usize>], crossings: &[Crossing]) {
    for c in crossings {
        let along = 2 - c.axis;
        let inside = |blk: &FittedBlock, whole: bool| {
            let overlap = blk.max[along].min(c.t1) - blk.min[along].max(c.t0);
            let centre = 0.5 * (c.t0 + c.t1);
            whole
                || overlap > 0.5 * (blk.max[along] - blk.min[along])
                || (blk.min[along]..blk.max[along]).contains(&centre)
        };
        for &sa in &of_room[c.a] {
            for &sb in &of_room[c.b] {
                if inside(&out[sa], of_room[c.a].len() == 1) && inside(&out[sb], of_room[c.b].len() == 1) {
                    join(out, sa, sb, c.axis);
                }
            }
        }
    }
}

/// Opens the facing sides of blocks `a` and `b` across `axis` and moves both to the mid-plane of
/// the wall between them, where one lies beside the other with at most [`MAX_WALL`] between and
/// they overlap along the other axis.
fn join(blocks: &mut [FittedBlock], a: usize, b: usize, axis: usize) {
    let (pos, neg) = if axis == 0 { (0, 1) } else { (4, 5) };
    for (first, second) in [(a, b), (b, a)] {
        let (f, s) = (&blocks[first], &blocks[second]);
        let gap = s.min[axis] - f.max[axis];
        let other = 2 - axis;
        let overlap = f.max[other].min(s.max[other]) - f.min[other].max(s.min[other]);
        if (-MAX_WALL..=MAX_WALL).contains(&gap) && overlap > 0.0 {
            let mid = 0.5 * (f.max[axis] + s.min[axis]);
            blocks[first].max[axis] = mid;
            blocks[first].openings[pos] = true;
            blocks[second].min[axis] = mid;
            blocks[second].openings[neg] = true;
            return;
        }
    }
}
