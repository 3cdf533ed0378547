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
/// through it (`SLAB_INSET` in `ism_lookup.wgsl`, which must match). Behind a narrow face of a
/// deep solid (a 0.2 m jamb of a wall running on 2.8 m) this leaves no slab; a cap of 1 cm was
/// tried and not kept (`docs/notes/ism-tuning.md`, "Stop 62").
pub const SLAB_INSET: f32 = 0.05;

impl IsmLookupData {
    /// Whether the ray from `o` along unit `dir` passes, before `dist`, through the solid behind
    /// pool point `j`'s face near it: the slab from the face to the solid's depth (the point's
    /// w, 0: none), inset by [`SLAB_INSET`] of its depth, bounded by its clip lines as faces
    /// square to its plane, with the middle of the ray's way through it within `reach` x t of
    /// the point across its normal. The twin of `slab_blocks` in `ism_lookup.wgsl`.
    pub fn slab_blocks(&self, j: u32, o: Vec3, dir: Vec3, dist: f32, reach: f32) -> bool {
        let Some(point) = self.points.get(j as usize) else { return false };
        let depth = point[3];
        if depth <= 0.0 {
            return false;
        }
        let p = Vec3::from_slice(&point[..3]);
        let n = self.normals.get(j as usize).map_or(Vec3::ZERO, |v| Vec3::from_slice(&v[..3]));
        let inset = SLAB_INSET * depth;
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
