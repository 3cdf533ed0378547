//! The ISM atlas word on the CPU: what `ism_pack` in `common/vpl.wgsl` writes (a 17-bit
//! depth, the slot of the point whose splat it is, the pull-push mark) and the lookup that
//! `ism_lookup.wgsl` makes of it, for the inspector, the oracle (`render::gi::ism::oracle`,
//! `bouncelab probe-ism`) and tests. The GPU passes are the product; these twins exist so that
//! what they compute can be checked against rays.

use glam::Vec3;

use crate::precompute::open_edges::{CLIPS_PER_POINT, line_admits};

/// Pull-push levels below the finest (the thesis: "at least two mip levels"). Four instead of
/// two: the unlit room 1.21 -> 0.73, the cluttered room 0.95 -> 0.89, the Cornell box 0.95 ->
/// 0.92 of the reference's energy (`bouncelab probe`, with a bounce clamp of 0.25 in that
/// run): hole filling dilates occluders.
pub const PULL_LEVELS: usize = 2;

/// Where level `level` (>= 1) of an atlas whose finest level has side `side` starts in the
/// buffer of the coarse levels (words): every level follows the finer ones (`ism_hole_blocks`
/// in `ism_lookup.wgsl`, `coarse_base` in `pull_push.wgsl`).
pub const fn level_base(side: u32, level: u32) -> u32 {
    let mut base = 0;
    let mut l = 1;
    while l < level {
        base += (side >> l) * (side >> l);
        l += 1;
    }
    base
}
/// Depth levels of the word's 17-bit depth field (all ones is empty).
const DEPTH_MAX: f32 = 131_070.0;

/// The normalised depth of an atlas word (1.0 when empty); the twin of `ism_depth`.
pub fn depth(bits: u32) -> f32 {
    if bits >> 15 == 0x1ffff { 1.0 } else { (bits >> 15) as f32 / DEPTH_MAX }
}

/// The slot (among its VPL's points per ISM) of the point whose splat an atlas word holds, or
/// `None` (empty, filled by pull-push, or a depth only); the twin of `ism_slot1`.
pub fn slot(bits: u32) -> Option<u32> {
    let slot1 = (bits >> 1) & 0x3fff;
    (bits != u32::MAX && slot1 > 0).then(|| slot1 - 1)
}

/// An atlas word as the inspector shows it: rgb = the normalised depth (1 = empty), its lowest
/// mantissa bit set where pull-push filled the texel (one ulp, invisible); alpha = 1.
pub fn texel(bits: u32) -> [f32; 4] {
    let v = f32::from_bits((depth(bits).to_bits() & !1) | (bits & 1));
    [v, v, v, 1.0]
}

/// The buffers an ISM lookup reads besides the atlas, read back (`ism_lookup.wgsl`).
pub struct IsmLookupData {
    /// Per VPL of every set (its atlas tile) and slot: the pool point (`u32::MAX`: none).
    pub chosen_all: Vec<u32>,
    /// Pool positions (xyz) and normals (xyz; w = sampling weight).
    pub points: Vec<[f32; 4]>,
    pub normals: Vec<[f32; 4]>,
    /// Clip lines, [`CLIPS_PER_POINT`] per pool point (xyz inward direction, w offset).
    pub clips: Vec<[f32; 4]>,
    /// Points per ISM.
    pub per_ism: u32,
}

/// What one atlas word's point says of a receiver's ray (`ism_point_test` in `ism_lookup.wgsl`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PointTest {
    /// Not in front of the receiver: the point's plane lies beyond it or contains it, or only
    /// a depth is stored and it is farther.
    Clear,
    /// The ray crosses the point's surface before the receiver.
    Blocked,
    /// The ray meets the point's plane before the receiver but past its open edges, or (the
    /// texel's own point) the point is much nearer than the receiver (within [`UNVOUCHED`] of its
    /// distance) and the ray does not cross its plane before it.
    Unsure,
}

/// Where a lookup falls: the atlas (row-major words, tiles of side `r`, `c` per row) and the
/// texel `(x, y)` within its tile.
#[derive(Clone, Copy, Debug)]
pub struct AtlasTexel<'a> {
    /// The atlas words, its coarse levels after them (`IsmTechnique::read_atlas_words`; the
    /// finest level alone is enough where no coarse level is asked).
    pub words: &'a [u32],
    /// Tile side (texels).
    pub r: u32,
    /// Tiles per row.
    pub c: u32,
    /// The texel within the tile.
    pub texel: (u32, u32),
}

/// The coarse levels the lookups ask (`ISM_LEVELS` in `ism_lookup.wgsl`; every level pull-push
/// keeps).
pub const HOLE_LEVELS: u32 = PULL_LEVELS as u32;

// `ism_nearer_around` (and [`IsmLookupData::lit`]) read the second coarse level.
const _: () = assert!(PULL_LEVELS >= 2, "the lookups read the second coarse level");

impl AtlasTexel<'_> {
    /// The word of level `level` (1 = half the side) over this texel of tile `tile`: the coarse
    /// levels follow the finest in `words` (at side^2 + `level_base`); `None` when `words`
    /// holds the finest only.
    fn coarse_word(&self, tile: u32, level: u32) -> Option<u32> {
        let side = self.r * self.c.max(1);
        let (x, y) = ((tile % self.c.max(1)) * self.r + self.texel.0, (tile / self.c.max(1)) * self.r + self.texel.1);
        let at = side * side + level_base(side, level) + (y >> level) * (side >> level) + (x >> level);
        self.words.get(at as usize).copied()
    }

    /// The word of texel `(x, y)` of tile `tile`, `None` outside the tile.
    fn word(&self, tile: u32, x: i64, y: i64) -> Option<u32> {
        let r = i64::from(self.r);
        if x < 0 || y < 0 || x >= r || y >= r {
            return None;
        }
        let side = i64::from(self.r) * i64::from(self.c);
        let (x0, y0) = (i64::from((tile % self.c.max(1)) * self.r), i64::from((tile / self.c.max(1)) * self.r));
        self.words.get(((y0 + y) * side + x0 + x) as usize).copied()
    }
}

/// A neighbouring texel's point blocks a ray only within this many of the VPL's angular point
/// spacings (times the distance) of itself (`ism_lit` reads it from the lookup's bias.x). At 2
/// the held-out offices, lit through a door 11 m down a corridor, kept 0.70 of the reference's
/// energy against 0.84 at 0.75, the held-out flat 1.07 against 1.13 (before seam lines;
/// `bouncelab probe /tmp/unseen/offices.gltf,/tmp/unseen/apartment.gltf --average-from 0 --frames 32`).
pub const NEIGHBOUR_REACH: f32 = 0.75;

/// Whether offset `e` (in the plane of normal `n`) from a point lies within the disk a VPL
/// sees that point stand for along direction `dir`: radius `radius` across the ray, stretched
/// by 1 / cos along the ray's slope over the plane (a wall seen at 60 degrees off its normal
/// covers twice the length per texel). `within_disk` in `ism_lookup.wgsl` is its twin.
pub fn within_disk(e: Vec3, dir: Vec3, n: Vec3, radius: f32) -> bool {
    let c = dir.dot(n).abs().max(MIN_COS);
    let slope = dir - n * dir.dot(n);
    let along = if slope.length_squared() > 1e-12 { e.dot(slope.normalize()) } else { 0.0 };
    let across2 = (e.length_squared() - along * along).max(0.0);
    across2 + (along * c) * (along * c) <= radius * radius
}

/// The least cosine [`within_disk`] stretches by.
pub const MIN_COS: f32 = 0.05;

/// A texel's own point nearer than this share of the receiver's distance, whose plane the
/// receiver's ray does not cross, leaves the neighbours to be asked (`UNVOUCHED` in
/// `ism_lookup.wgsl`, which must match).
pub const UNVOUCHED: f32 = 0.98;

/// A texel shows the way to a receiver clear where it is empty or holds a surface at least this
/// share of the receiver's depth (`SHOWN_CLEAR` in `ism_lookup.wgsl`, which must match). A ray
/// the texel's own point cannot decide (it passes the point's open edge, or the point is much
/// nearer and its plane is not crossed) and no neighbour's point blocks is lit only where one of
/// the five texels shows the way clear: in the held-out maisonette, rays past a door's jamb or
/// head whose true occluder (the wall beside the door) no texel held were half of the first
/// set's false light into the camera's room (`probe-ism --grid 6.15,6.05 --pair -1,3`: the
/// first set's lookups read 2.73x the rays' light there, 1.86x with this test). Where the own
/// word shows the way clear, the same test says whether the texel's 4x4 block holds a nearer
/// surface (then the neighbours are asked) and which neighbours are tested.
pub const SHOWN_CLEAR: f32 = 0.9;

/// Whether atlas word `w` shows the way to a receiver at normalised depth `depth_norm` clear
/// (`ism_shows_clear`).
pub fn shows_clear(w: u32, depth_norm: f32) -> bool {
    w == u32::MAX || depth(w) >= SHOWN_CLEAR * depth_norm
}

impl IsmLookupData {
    /// What atlas word `stored` of tile `tile` says of the receiver at `dist` from the VPL at `o`
    /// along unit `dir` (normalised depth `depth_norm`). `own`: the texel's own word (a word
    /// without a point shadows by its depth, relative `margin`; its surface blocks within its
    /// open edges, past its seams too); otherwise a neighbour's or a coarse level's,
    /// whose depth never shadows and whose surface blocks only within its seams and within
    /// `reach` x t of its point. The twin of `ism_point_test`.
    #[allow(clippy::too_many_arguments)]
    pub fn point_test(
        &self,
        o: Vec3,
        tile: u32,
        dir: Vec3,
        dist: f32,
        depth_norm: f32,
        stored: u32,
        margin: f32,
        reach: f32,
        own: bool,
    ) -> PointTest {
        if stored == u32::MAX {
            return PointTest::Clear;
        }
        let point = slot(stored)
            .filter(|s| *s < self.per_ism)
            .and_then(|s| self.chosen_all.get((tile * self.per_ism + s) as usize))
            .filter(|j| (**j as usize) < self.points.len());
        let Some(&j) = point else {
            return if own && depth_norm > depth(stored) * (1.0 + margin) {
                PointTest::Blocked
            } else {
                PointTest::Clear
            };
        };
        let p = Vec3::from_slice(&self.points[j as usize][..3]);
        let n = Vec3::from_slice(&self.normals[j as usize][..3]);
        if self.slab_blocks(j, o, dir, dist, reach) {
            return PointTest::Blocked;
        }
        // The ray does not cross the point's plane before the receiver: a point much nearer
        // than the receiver still leaves the rest of the way unvouched for (`ism_lookup.wgsl`).
        let not_crossed = if own && p.distance(o) < dist * UNVOUCHED { PointTest::Unsure } else { PointTest::Clear };
        let den = dir.dot(n);
        if den.abs() <= 1e-6 {
            return not_crossed;
        }
        let t = (p - o).dot(n) / den;
        if t <= 0.0 || t >= dist * (1.0 - 1e-4) {
            return not_crossed;
        }
        let h = o + dir * t;
        if !self.on_surface(j, h, 0.0) {
            PointTest::Unsure
        } else if own || (self.within_edges(j, h, 0.0, true) && within_disk(h - p, dir, n, reach * t)) {
            PointTest::Blocked
        } else {
            PointTest::Clear
        }
    }

    /// Whether a receiver at `dist` from the VPL at `o` (angular point spacing `sigma`, its
    /// normal.w) along unit `dir` (normalised depth `depth_norm`) is lit by the VPL of atlas tile
    /// `tile`, whose map it falls in at `at`: the texel's own word blocks it, or any of the four
    /// neighbouring words whose surface it crosses (`margin`: the relative depth margin of
    /// texels without a point), also where the own word shows the way clear and the texel's
    /// 4x4 block holds a nearer surface (an occluder's edge a texel over; then only the words
    /// that do not show it clear); where the own word cannot decide (the ray passes its point's open edges,
    /// or the point is much nearer and its plane not crossed), so does no texel of the five
    /// showing the way clear ([`shows_clear`]); where a coarse level is nearer than the texel
    /// (a hole), its word's point. The twin of `ism_lit`.
    #[allow(clippy::too_many_arguments)]
    pub fn lit(
        &self,
        at: AtlasTexel<'_>,
        o: Vec3,
        sigma: f32,
        tile: u32,
        dir: Vec3,
        dist: f32,
        depth_norm: f32,
        margin: f32,
    ) -> bool {
        let (x, y) = (i64::from(at.texel.0), i64::from(at.texel.1));
        let stored = at.word(tile, x, y).unwrap_or(u32::MAX);
        let reach = NEIGHBOUR_REACH * sigma;
        let blocked = |w: u32, reach: f32| {
            self.point_test(o, tile, dir, dist, depth_norm, w, margin, reach, false) == PointTest::Blocked
        };
        let own = self.point_test(o, tile, dir, dist, depth_norm, stored, margin, reach, true);
        if own == PointTest::Blocked {
            return false;
        }
        // A neighbour whose surface the ray crosses blocks it even where the texel's own word
        // shows the way clear (an occluder's edge a texel over: `ism_lit`), when the texel's
        // 4x4 block holds a surface in front of the receiver; then only the neighbours that do
        // not show the way clear themselves are tested.
        let nearer_around = || at.coarse_word(tile, 2).is_some_and(|w| !shows_clear(w, depth_norm));
        if own == PointTest::Unsure || (own == PointTest::Clear && nearer_around()) {
            let around = [(-1, 0), (1, 0), (0, -1), (0, 1)].map(|(dx, dy)| at.word(tile, x + dx, y + dy));
            let nearer_only = own == PointTest::Clear;
            if around.iter().flatten().any(|&w| !(nearer_only && shows_clear(w, depth_norm)) && blocked(w, reach)) {
                return false;
            }
            // Where the texel cannot decide, lit only where it or a neighbour shows the way
            // clear (`ism_shows_clear`).
            if own == PointTest::Unsure
                && !std::iter::once(stored).chain(around.into_iter().flatten()).any(|w| shows_clear(w, depth_norm))
            {
                return false;
            }
        }
        // Ritschel's push, asked at lookup time (`ism_hole_blocks`).
        let own_depth = depth(stored);
        !(1..=HOLE_LEVELS).any(|level| {
            at.coarse_word(tile, level).is_some_and(|w| {
                let cd = depth(w);
                w != u32::MAX && cd < own_depth && blocked(w, reach * (1u32 << level) as f32)
            })
        })
    }

    /// Whether `h` (on pool point `j`'s plane) lies inside all of its open edges' clip lines,
    /// less `margin` (seam lines skipped): the twin of `on_surface` in `ism_clips.wgsl`.
    pub fn on_surface(&self, j: u32, h: Vec3, margin: f32) -> bool {
        self.within_edges(j, h, margin, false)
    }

    /// Whether `h` lies inside pool point `j`'s open edges' clip lines, less `margin`, and past
    /// its seams only within their overhang (stored scaled by
    /// [`crate::precompute::open_edges::SEAM_SCALE`] plus the overhang), and with `seams` inside
    /// its seams' own lines too: the twin of `within_edges`.
    pub fn within_edges(&self, j: u32, h: Vec3, margin: f32, seams: bool) -> bool {
        let j = j as usize;
        self.clips
            .get(j * CLIPS_PER_POINT..(j + 1) * CLIPS_PER_POINT)
            .is_none_or(|lines| lines.iter().all(|c| line_admits(c, h, margin, seams)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::precompute::ism::slab::SLAB_INSET;
    use crate::precompute::open_edges::SEAM_SCALE;

    /// One pool point on a wall (plane z = 2, facing -z towards a VPL at the origin) whose open
    /// edge is at x = 1 (a door's jamb: the wall is x <= 1).
    fn wall_with_a_jamb() -> IsmLookupData {
        IsmLookupData {
            chosen_all: vec![0],
            points: vec![[0.5, 0.0, 2.0, 0.0]],
            normals: vec![[0.0, 0.0, -1.0, 1.0]],
            // Inward direction -x, offset -1: on the wall when -x >= -1, i.e. x <= 1; the other
            // three lines always pass.
            clips: vec![[-1.0, 0.0, 0.0, -1.0], [0.0, 0.0, 0.0, -1.0], [0.0, 0.0, 0.0, -1.0], [0.0, 0.0, 0.0, -1.0]],
            per_ism: 1,
        }
    }

    fn word(depth: f32, slot1: u32) -> u32 {
        ((depth * DEPTH_MAX).round() as u32) << 15 | slot1 << 1
    }

    /// `lit` for a 2 x 2 map holding `stored` beside three empty texels (which show the way
    /// clear and block nothing).
    fn lit_alone(data: &IsmLookupData, dir: Vec3, dist: f32, depth_norm: f32, stored: u32) -> bool {
        let at = AtlasTexel { words: &[stored, u32::MAX, u32::MAX, u32::MAX], r: 2, c: 1, texel: (0, 0) };
        data.lit(at, Vec3::ZERO, 0.1, 0, dir, dist, depth_norm, 0.06)
    }

    #[test]
    fn the_words_fields_round_trip() {
        let w = word(0.25, 7) | 1;
        assert!((depth(w) - 0.25).abs() < 1e-5);
        assert_eq!(slot(w), Some(6));
        assert_eq!(slot(word(0.25, 0)), None);
        assert_eq!(depth(u32::MAX), 1.0);
        assert_eq!(texel(w)[0].to_bits() & 1, 1, "the pull-push mark shows as the lowest bit");
    }

    #[test]
    fn a_ray_past_the_walls_open_edge_is_lit_and_one_through_the_wall_is_not() {
        let data = wall_with_a_jamb();
        let stored = word(0.1, 1);
        // Receivers 4 m away behind the wall plane: one whose ray crosses z = 2 at x = 0.8
        // (on the wall), one at x = 1.2 (past the jamb, in the doorway).
        for (x, lit) in [(0.8f32, false), (1.2, true)] {
            let dir = Vec3::new(x, 0.0, 2.0).normalize();
            let dist = 4.0;
            assert_eq!(lit_alone(&data, dir, dist, 0.2, stored), lit, "ray through x = {x}");
        }
        // A receiver in front of the wall (its ray meets the receiver before the plane).
        let dir = Vec3::new(0.8, 0.0, 2.0).normalize();
        assert!(lit_alone(&data, dir, 1.5, 0.05, stored));
        // The receiver on the wall itself is not shadowed by its own plane, even at a grazing ray.
        let on_wall = Vec3::new(0.9, 0.0, 2.0);
        assert!(lit_alone(&data, on_wall.normalize(), on_wall.length(), 0.1, stored));
        let grazing = Vec3::new(0.95, 30.0, 2.0);
        assert!(lit_alone(&data, grazing.normalize(), grazing.length(), 0.1, stored));
        // Without a point (pull-push filled the texel), the depth and its margin decide.
        let filled = word(0.1, 0) | 1;
        assert!(!lit_alone(&data, dir, 4.0, 0.2, filled));
        assert!(lit_alone(&data, dir, 0.4, 0.105, filled));
    }

    /// A door's jamb (plane x = 1 facing the VPL at the origin, the wall's thickness z in 2..2.2)
    /// in the lookup's texel and the wall's front face beside the door (z = 2, x >= 1) in the
    /// texel to its right; the doorway is x < 1. The wall's point has a seam at y = 0.5 (it
    /// runs on into solid geometry above).
    fn jamb_and_wall() -> (IsmLookupData, [u32; 9]) {
        let none = [0.0, 0.0, 0.0, -1.0];
        let data = IsmLookupData {
            chosen_all: vec![0, 1],
            points: vec![[1.0, 0.0, 2.1, 0.0], [1.1, 0.0, 2.0, 0.0]],
            normals: vec![[-1.0, 0.0, 0.0, 1.0], [0.0, 0.0, -1.0, 1.0]],
            clips: vec![
                // The jamb: z >= 2 and z <= 2.2.
                [0.0, 0.0, 1.0, 2.0],
                [0.0, 0.0, -1.0, -2.2],
                none,
                none,
                // The wall: x >= 1 (open), y <= 0.5 (a seam, stored doubled).
                [1.0, 0.0, 0.0, 1.0],
                [0.0, -2.0, 0.0, -1.0],
                none,
                none,
            ],
            per_ism: 2,
        };
        let mut words = [u32::MAX; 9];
        words[4] = word(0.1, 1);
        words[5] = word(0.1, 2);
        (data, words)
    }

    #[test]
    fn a_ray_past_the_jambs_edge_is_shadowed_by_the_wall_in_the_next_texel_but_not_past_its_seam() {
        let (data, words) = jamb_and_wall();
        let at = AtlasTexel { words: &words, r: 3, c: 1, texel: (1, 1) };
        let lit = |dir: Vec3| data.lit(at, Vec3::ZERO, 1.0, 0, dir.normalize(), 4.0, 0.2, 0.06);
        // Past the jamb's plane in front of the wall (x = 1 at z = 1.9), into the wall's face at
        // x = 1.05: the texel's own point cannot decide, the neighbour's wall blocks it.
        assert!(!lit(Vec3::new(1.0, 0.0, 1.9)));
        assert!(lit_alone(&data, Vec3::new(1.0, 0.0, 1.9).normalize(), 4.0, 0.2, words[4]), "alone it was lit");
        // Through the doorway (z = 2 at x = 0.9, z = 2.2 at x = 0.99): lit.
        assert!(lit(Vec3::new(0.9, 0.0, 2.0)));
        // Into the wall's plane above its seam (y = 0.53): the neighbour does not vouch for it.
        assert!(lit(Vec3::new(1.0, 0.5, 1.9)));
        // The same ray with the jamb's point in the texel to the left instead: still blocked.
        let mut left = words;
        left.swap(3, 5);
        let at_left = AtlasTexel { words: &left, ..at };
        assert!(!data.lit(at_left, Vec3::ZERO, 1.0, 0, Vec3::new(1.0, 0.0, 1.9).normalize(), 4.0, 0.2, 0.06));
    }

    #[test]
    fn a_ray_past_an_open_edge_is_lit_only_where_a_texel_around_shows_the_way_clear() {
        let data = wall_with_a_jamb();
        // The doorway's ray of the test above (x = 1.2 at the wall), its receiver 4 m away at
        // normalised depth 0.2, in the middle of a 3 x 3 map whose other texels hold depths
        // without a point: nearer than the receiver, they show no clear way (a surface no
        // texel's point stands for may stop it), and it is dark.
        let dir = Vec3::new(1.2, 0.0, 2.0).normalize();
        let mut words = [word(0.1, 0); 9];
        words[4] = word(0.1, 1);
        let lit = |words: &[u32]| {
            let at = AtlasTexel { words, r: 3, c: 1, texel: (1, 1) };
            data.lit(at, Vec3::ZERO, 0.1, 0, dir, 4.0, 0.2, 0.06)
        };
        assert!(!lit(&words), "no texel shows the way clear");
        // One neighbour sees as far as the receiver (within `SHOWN_CLEAR`): lit.
        words[5] = word(0.19, 0);
        assert!(lit(&words), "the texel to the right shows the way clear");
        words[5] = word(0.17, 0);
        assert!(!lit(&words), "0.85 of the receiver's depth is a surface in front of it");
        // A diagonal neighbour is not asked.
        words[8] = u32::MAX;
        assert!(!lit(&words));
        words[7] = u32::MAX;
        assert!(lit(&words), "an empty neighbour below shows the way clear");
    }

    #[test]
    fn a_points_disk_stretches_along_the_rays_slope_only() {
        // A wall facing -z seen 60 degrees off its normal (the ray rises along y): its points'
        // disks reach twice as far along y as across.
        let n = Vec3::new(0.0, 0.0, -1.0);
        let dir = Vec3::new(0.0, 60f32.to_radians().sin(), 60f32.to_radians().cos());
        assert!(within_disk(Vec3::new(0.0, 0.3, 0.0), dir, n, 0.2));
        assert!(!within_disk(Vec3::new(0.0, 0.45, 0.0), dir, n, 0.2));
        assert!(!within_disk(Vec3::new(0.3, 0.0, 0.0), dir, n, 0.2));
        // Face-on the disk is round.
        assert!(!within_disk(Vec3::new(0.0, 0.3, 0.0), -n, n, 0.2));
    }

    /// One ISM whose pool holds `points` (position, normal), each chosen in order, without clip
    /// lines and without solid behind them.
    fn unclipped(points: &[([f32; 3], [f32; 3])]) -> IsmLookupData {
        IsmLookupData {
            chosen_all: (0..points.len() as u32).collect(),
            points: points.iter().map(|(p, _)| [p[0], p[1], p[2], 0.0]).collect(),
            normals: points.iter().map(|(_, n)| [n[0], n[1], n[2], 1.0]).collect(),
            clips: vec![[0.0, 0.0, 0.0, -1.0]; points.len() * CLIPS_PER_POINT],
            per_ism: points.len() as u32,
        }
    }

    /// A floor (y = -1) whose nearer point holds the receiver's texel, the receiver on the same
    /// floor 4 m away behind a wall (z = 2, facing the VPL) whose point is in the next texel.
    #[test]
    fn a_nearer_point_on_the_receivers_own_plane_leaves_the_wall_beside_it_to_decide() {
        let data = unclipped(&[([0.0, -1.0, 1.5], [0.0, 1.0, 0.0]), ([0.0, -0.6, 2.0], [0.0, 0.0, -1.0])]);
        let receiver = Vec3::new(0.0, -1.0, 4.0);
        let (dir, dist) = (receiver.normalize(), receiver.length());
        let mut words = [u32::MAX; 9];
        words[4] = word(0.1, 1);
        assert!(lit_alone(&data, dir, dist, 0.4, words[4]), "the floor's own point does not shadow its floor");
        let alone = words;
        let at = AtlasTexel { words: &alone, r: 3, c: 1, texel: (1, 1) };
        assert!(data.lit(at, Vec3::ZERO, 0.1, 0, dir, dist, 0.4, 0.06), "no neighbour, lit");
        words[5] = word(0.1, 2);
        let at = AtlasTexel { words: &words, ..at };
        assert!(!data.lit(at, Vec3::ZERO, 0.1, 0, dir, dist, 0.4, 0.06), "the wall in the next texel shadows it");
        // Neighbours holding only depths well in front of the receiver show no clear way.
        let mut near = [word(0.2, 0); 9];
        near[4] = words[4];
        let lit_among = |words: &[u32]| data.lit(AtlasTexel { words, ..at }, Vec3::ZERO, 0.1, 0, dir, dist, 0.4, 0.06);
        assert!(!lit_among(&near), "nothing shows the way clear");
        near[1] = word(0.39, 0);
        assert!(lit_among(&near), "the texel above sees as far");
        // A receiver on the floor in front of the wall stays lit.
        let near = Vec3::new(0.0, -1.0, 1.8);
        assert!(data.lit(at, Vec3::ZERO, 0.1, 0, near.normalize(), near.length(), 0.2, 0.06));
    }

    /// At an occluder's edge a texel's centre ray passes the occluder and the texel shows the
    /// receiver's own surface, while the receiver's ray runs into the occluder a texel over: the
    /// floor's point right at the receiver (y = -1, 4 m away) holds its texel of a 4 x 4 map, a
    /// wall (z = 2, facing the VPL) the next one; the coarse levels name a third point of the
    /// wall 3 m aside, whose disk the ray misses (so Ritschel's push does not decide it).
    #[test]
    fn the_receivers_own_surface_in_its_texel_leaves_a_nearer_wall_in_the_next_texel_to_decide() {
        let wall = [0.0, 0.0, -1.0];
        let data =
            unclipped(&[([0.0, -1.0, 3.98], [0.0, 1.0, 0.0]), ([0.0, -0.6, 2.0], wall), ([3.0, -0.6, 2.0], wall)]);
        let receiver = Vec3::new(0.0, -1.0, 4.0);
        let (dir, dist) = (receiver.normalize(), receiver.length());
        // The finest level (4 x 4), then levels 1 (2 x 2) and 2 (1 x 1).
        let mut words = [u32::MAX; 21];
        words[5] = word(0.4, 1);
        let lit = |words: &[u32]| {
            let at = AtlasTexel { words, r: 4, c: 1, texel: (1, 1) };
            data.lit(at, Vec3::ZERO, 0.1, 0, dir, dist, 0.4, 0.06)
        };
        assert!(lit(&words), "no neighbour, lit");
        words[6] = word(0.2, 2);
        assert!(lit(&words), "the 4x4 block's word shows nothing nearer: the neighbours are not read");
        words[20] = word(0.2, 3);
        assert!(!lit(&words), "the wall in the next texel shadows it");
        // A neighbour whose word shows the way clear itself (a surface near the receiver's
        // depth) is not tested, even where its point's disk lies on the ray.
        words[6] = word(0.39, 2);
        assert!(lit(&words), "a neighbour showing the way clear is not asked");
    }

    /// A receiver on a back wall (z = 4) seen through a hole in a nearer wall (z = 2): its texel
    /// holds its own surface, and only the coarse level's word names the nearer wall's point.
    #[test]
    fn a_hole_in_a_wall_is_closed_by_the_coarse_levels_point_within_its_reach() {
        let none = [0.0, 0.0, 0.0, -1.0];
        let data = |wall_x: f32| IsmLookupData {
            chosen_all: vec![0, 1],
            points: vec![[0.2, 0.0, 4.0, 0.0], [wall_x, 0.0, 2.0, 0.0]],
            normals: vec![[0.0, 0.0, -1.0, 1.0], [0.0, 0.0, -1.0, 1.0]],
            clips: vec![none; 8],
            per_ism: 2,
        };
        let receiver = Vec3::new(0.2, 0.0, 4.0);
        let (dir, dist) = (receiver.normalize(), receiver.length());
        // A 2 x 2 map (all four texels show the back wall), then its one level-1 word.
        let own = word(0.4, 1);
        let holed = [own, own, own, own, word(0.2, 2)];
        let unfilled = [own, own, own, own, u32::MAX];
        let lit = |d: &IsmLookupData, words: &[u32]| {
            let at = AtlasTexel { words, r: 2, c: 1, texel: (0, 0) };
            d.lit(at, Vec3::ZERO, 0.1, 0, dir, dist, 0.4, 0.06)
        };
        let near = data(0.1);
        assert!(lit(&near, &unfilled), "without the coarse level the hole lets the light through");
        assert!(!lit(&near, &holed), "the wall's point at level 1 closes the hole");
        // The wall's point 1 m from where the ray crosses its plane (reach: 2 x 0.75 x 0.1 x 2 m
        // = 0.3 m) vouches for nothing there.
        assert!(lit(&data(1.1), &holed), "a far point of the wall does not shadow");
        // A receiver in front of the nearer wall stays lit.
        let front = Vec3::new(0.05, 0.0, 1.5);
        let at = AtlasTexel { words: &holed, r: 2, c: 1, texel: (0, 0) };
        assert!(near.lit(at, Vec3::ZERO, 0.1, 0, front.normalize(), front.length(), 0.15, 0.06));
    }

    /// A door's head: the underside (plane y = -0.6, facing down) of a wall z in 2..2.25 whose
    /// solid runs 1 m up, seen from a VPL at the origin above it. The texel holds the head's
    /// point, and a ray that runs through the wall above the head crosses the head's plane only
    /// past the wall, at z = 3.6.
    #[test]
    fn a_ray_through_the_wall_above_a_doors_head_is_blocked_by_the_slab_behind_it() {
        let none = [0.0, 0.0, 0.0, -1.0];
        let data = |depth: f32| IsmLookupData {
            chosen_all: vec![0],
            points: vec![[0.0, -0.6, 2.1, depth]],
            normals: vec![[0.0, -1.0, 0.0, 1.0]],
            clips: vec![[0.0, 0.0, 1.0, 2.0], [0.0, 0.0, -1.0, -2.25], none, none],
            per_ism: 1,
        };
        let stored = word(0.2, 1);
        let through_wall = Vec3::new(0.0, -1.0, 6.0);
        let (dir, dist) = (through_wall.normalize(), through_wall.length());
        assert!(lit_alone(&data(0.0), dir, dist, 0.5, stored), "the head's plane alone lets it pass");
        assert!(!lit_alone(&data(1.0), dir, dist, 0.5, stored), "the wall above the head blocks it");
        let through_door = Vec3::new(0.0, -2.0, 6.0);
        assert!(lit_alone(&data(1.0), through_door.normalize(), through_door.length(), 0.5, stored));
        // A receiver on the head itself, lit from below through the doorway, stays lit.
        let o = Vec3::new(0.0, -2.0, 0.0);
        let on_head = Vec3::new(0.0, -0.6, 2.15) - o;
        assert!(!data(1.0).slab_blocks(0, o, on_head.normalize(), on_head.length(), 0.075));
    }

    #[test]
    fn the_shaders_constants_match_their_cpu_twins() {
        let wgsl = include_str!("../../../shaders/render/gi/ism/ism_lookup.wgsl");
        for line in [
            format!("const ISM_LEVELS: u32 = {HOLE_LEVELS}u;"),
            format!("const UNVOUCHED: f32 = {UNVOUCHED:?};"),
            format!("const MIN_COS: f32 = {MIN_COS:?};"),
            format!("const SLAB_INSET: f32 = {SLAB_INSET:?};"),
            format!("const SHOWN_CLEAR: f32 = {SHOWN_CLEAR:?};"),
        ] {
            assert!(wgsl.contains(&line), "ism_lookup.wgsl lacks `{line}`");
        }
        // The inset's formula too (`slab.rs`).
        assert!(wgsl.contains("let inset = SLAB_INSET * depth;"), "ism_lookup.wgsl's slab inset");
        let clips = include_str!("../../../shaders/render/gi/ism/ism_clips.wgsl");
        let line = format!("const SEAM_SCALE: f32 = {SEAM_SCALE:?};");
        assert!(clips.contains(&line), "ism_clips.wgsl lacks `{line}`");
    }
}
