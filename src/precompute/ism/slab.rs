//! The slab test on the CPU: whether a receiver's ray runs through the solid behind a pool
//! point's face (`slab_blocks` in `ism_lookup.wgsl`, whose twin this is). A texel holds one
//! surface; where it holds a face seen past its edge (a door's head, a jamb), the ray may cross
//! that face's plane past the face and still run through the wall behind it. Each pool point
//! knows the depth of the solid behind its face (found once per distribution), and the test
//! asks whether the ray passes through that slab within the point's clip lines. The CPU twin
//! serves the oracle (`bouncelab probe-ism`) and the tests.

use glam::Vec3;

use super::atlas_word::IsmLookupData;
use crate::precompute::open_edges::CLIPS_PER_POINT;

/// The share of a slab's depth [`IsmLookupData::slab_blocks`] keeps clear of its faces and clip
/// lines: a receiver on the slab's far face, or a ray grazing its edge, is not taken for passing
/// through it (`SLAB_INSET` in `ism_lookup.wgsl`, which must match).
pub const SLAB_INSET: f32 = 0.05;

/// The most, in metres, a slab's test keeps clear of its faces and clip lines
/// (`SLAB_INSET_MAX` in `ism_lookup.wgsl`). Without it the inset of a deep solid's face was
/// wider than the face: behind a 0.2 m jamb of a wall running 2.8 m on, 5% of the depth (0.14
/// m from each side) left no slab, and rays through the wall a few centimetres behind the jamb
/// passed. On the suite's three rooms the first set's lookups into the third room passed 2.43x
/// the rays' light before, 2.37x with it (`probe-ism rooms --power --pair 0,2 --unburied`).
pub const SLAB_INSET_MAX: f32 = 0.01;

/// The inset of a slab of solid depth `depth`.
pub fn slab_inset(depth: f32) -> f32 {
    (SLAB_INSET * depth).min(SLAB_INSET_MAX)
}

impl IsmLookupData {
    /// Whether the ray from `o` along unit `dir` passes, before `dist`, through the solid behind
    /// pool point `j`'s face near it: the slab from the face to the solid's depth (the point's
    /// w, 0: none), inset by [`SLAB_INSET`] of its depth (at most [`SLAB_INSET_MAX`]), bounded
    /// by its clip lines as faces square to its plane, with the middle of the ray's way through
    /// it within `reach` x t of the point across its normal. The twin of `slab_blocks` in
    /// `ism_lookup.wgsl`.
    pub fn slab_blocks(&self, j: u32, o: Vec3, dir: Vec3, dist: f32, reach: f32) -> bool {
        let Some(point) = self.points.get(j as usize) else { return false };
        let depth = point[3];
        if depth <= 0.0 {
            return false;
        }
        let p = Vec3::from_slice(&point[..3]);
        let n = self.normals.get(j as usize).map_or(Vec3::ZERO, |v| Vec3::from_slice(&v[..3]));
        let inset = slab_inset(depth);
        let (mut lo, mut hi) = (0.0f32, dist);
        let (s0, dn) = (n.dot(p - o), n.dot(dir));
        if dn.abs() <= 1e-6 {
            if s0 <= inset || s0 >= depth - inset {
                return false;
            }
        } else {
            let (ta, tb) = ((s0 - inset) / dn, (s0 - depth + inset) / dn);
            lo = lo.max(ta.min(tb));
            hi = hi.min(ta.max(tb));
        }
        let j = j as usize;
        for c in self.clips.get(j * CLIPS_PER_POINT..(j + 1) * CLIPS_PER_POINT).unwrap_or(&[]) {
            let d = Vec3::from_slice(&c[..3]);
            let (a, b) = (d.dot(o) - c[3] - inset * d.length(), d.dot(dir));
            if b.abs() <= 1e-9 {
                if a < 0.0 {
                    return false;
                }
            } else if b > 0.0 {
                lo = lo.max(-a / b);
            } else {
                hi = hi.min(-a / b);
            }
        }
        if lo >= hi {
            return false;
        }
        let tm = 0.5 * (lo + hi);
        let e = o + dir * tm - p;
        (e - n * e.dot(n)).length_squared() <= (reach * tm) * (reach * tm)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A door's jamb: the face z = 1 (facing -z) of a wall x in 0..0.2 whose solid runs 2.8 m
    /// on in +z; its clip lines are the wall's faces x = 0 and x = 0.2.
    fn jamb() -> IsmLookupData {
        let none = [0.0, 0.0, 0.0, -1.0];
        IsmLookupData {
            chosen_all: vec![0],
            points: vec![[0.1, 0.0, 1.0, 2.8]],
            normals: vec![[0.0, 0.0, -1.0, 1.0]],
            clips: vec![[1.0, 0.0, 0.0, 0.0], [-1.0, 0.0, 0.0, -0.2], none, none],
            per_ism: 1,
        }
    }

    /// Whether the ray from `o` that passes the wall's face x = 0 at `z0` is blocked on its way
    /// to x = 3, where it has come down to z = 0.5.
    fn blocked(z0: f32) -> bool {
        let o = Vec3::new(-3.0, 0.0, 2.0 * z0 - 0.5);
        let to = Vec3::new(3.0, 0.0, 0.5) - o;
        jamb().slab_blocks(0, o, to.normalize(), to.length(), 0.1)
    }

    #[test]
    fn a_ray_through_a_deep_wall_just_behind_its_jamb_is_blocked() {
        // At z0 = 1.05 the ray runs 1.3-5 cm behind the jamb's face through the wall (a 5%
        // inset of the 2.8 m depth, 0.14 m from each side of the 0.2 m face, left no slab).
        assert!(blocked(1.05), "the ray runs through the wall just behind the jamb");
        assert!(blocked(1.2));
        // In the doorway, and grazing the corner within the inset, it passes.
        assert!(!blocked(0.9), "the ray passes in front of the jamb");
        assert!(!blocked(1.005), "a ray grazing the corner by 5 mm is not taken for passing through");
    }

    #[test]
    fn the_inset_is_a_share_of_a_thin_slabs_depth_and_capped_on_a_deep_one() {
        assert!((slab_inset(0.1) - 0.005).abs() < 1e-7);
        assert_eq!(slab_inset(2.8), SLAB_INSET_MAX);
    }
}
