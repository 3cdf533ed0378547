//! The ISM atlas word on the CPU: what `ism_pack` in `common/vpl.wgsl` writes (a 17-bit
//! depth, the slot of the point whose splat it is, the pull-push mark) and the lookup that
//! `ism_lookup.wgsl` makes of it, for the inspector, the oracle (`examples/ism_oracle.rs`) and
//! tests. The GPU passes are the product; these twins exist so that what they compute can be
//! checked against rays.

use glam::Vec3;

use crate::precompute::open_edges::CLIPS_PER_POINT;

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

impl IsmLookupData {
    /// Whether a receiver at `dist` from the VPL at `o` along unit `dir` is lit by the VPL of
    /// atlas tile `tile`, given the atlas word `stored` its ray falls in and its normalised
    /// depth `depth`; the twin of `ism_lit` (`margin`: the relative depth margin of texels
    /// without a point).
    #[allow(clippy::too_many_arguments)]
    pub fn lit(&self, o: Vec3, tile: u32, dir: Vec3, dist: f32, depth_norm: f32, stored: u32, margin: f32) -> bool {
        if stored == u32::MAX {
            return true;
        }
        let point = slot(stored)
            .filter(|s| *s < self.per_ism)
            .and_then(|s| self.chosen_all.get((tile * self.per_ism + s) as usize))
            .filter(|j| (**j as usize) < self.points.len());
        let Some(&j) = point else { return depth_norm <= depth(stored) * (1.0 + margin) };
        let j = j as usize;
        let n = Vec3::from_slice(&self.normals[j][..3]);
        let den = dir.dot(n);
        if den.abs() <= 1e-6 {
            return true;
        }
        let t = (Vec3::from_slice(&self.points[j][..3]) - o).dot(n) / den;
        if t <= 0.0 || t >= dist * (1.0 - 1e-4) {
            return true;
        }
        !self.on_surface(j as u32, o + dir * t, 0.0)
    }

    /// Whether `h` (on pool point `j`'s plane) lies inside all of its clip lines, less `margin`:
    /// the twin of `on_surface` in `ism_clips.wgsl`.
    pub fn on_surface(&self, j: u32, h: Vec3, margin: f32) -> bool {
        let j = j as usize;
        self.clips
            .get(j * CLIPS_PER_POINT..(j + 1) * CLIPS_PER_POINT)
            .is_none_or(|lines| lines.iter().all(|c| Vec3::from_slice(&c[..3]).dot(h) >= c[3] - margin))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One pool point on a wall (plane z = 2, facing -z towards a VPL at the origin) whose open
    /// edge is at x = 1 (a door's jamb: the wall is x <= 1).
    fn wall_with_a_jamb() -> IsmLookupData {
        IsmLookupData {
            chosen_all: vec![0],
            points: vec![[0.5, 0.0, 2.0, 1.0]],
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
        let o = Vec3::ZERO;
        let stored = word(0.1, 1);
        // Receivers 4 m away behind the wall plane: one whose ray crosses z = 2 at x = 0.8
        // (on the wall), one at x = 1.2 (past the jamb, in the doorway).
        for (x, lit) in [(0.8f32, false), (1.2, true)] {
            let dir = Vec3::new(x, 0.0, 2.0).normalize();
            let dist = 4.0;
            assert_eq!(data.lit(o, 0, dir, dist, 0.2, stored, 0.06), lit, "ray through x = {x}");
        }
        // A receiver in front of the wall (its ray meets the receiver before the plane).
        let dir = Vec3::new(0.8, 0.0, 2.0).normalize();
        assert!(data.lit(o, 0, dir, 1.5, 0.05, stored, 0.06));
        // The receiver on the wall itself is not shadowed by its own plane, even at a grazing ray.
        let on_wall = Vec3::new(0.9, 0.0, 2.0);
        assert!(data.lit(o, 0, on_wall.normalize(), on_wall.length(), 0.1, stored, 0.06));
        let grazing = Vec3::new(0.95, 30.0, 2.0);
        assert!(data.lit(o, 0, grazing.normalize(), grazing.length(), 0.1, stored, 0.06));
        // Without a point (pull-push filled the texel), the depth and its margin decide.
        let filled = word(0.1, 0) | 1;
        assert!(!data.lit(o, 0, dir, 4.0, 0.2, filled, 0.06));
        assert!(data.lit(o, 0, dir, 0.4, 0.105, filled, 0.06));
    }
}
