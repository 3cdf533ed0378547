//! Energy correction of warped blocks. MRT's operators are precomputed in the unit cube and a
//! level's block is the cube stretched to its box (Loos 2015 §3.5.2): radiance is carried as if
//! every face had the cube's area and saw the others as in the cube. For a stretched box both
//! are off: light entering a 0.9 m x 2.9 m doorway side of a 5 m long strip spreads over faces
//! five times its area, and most of it leaves through the long open sides rather than the
//! cube's fifth. Measured on the suite's rooms (`bouncelab probe-mrt rooms`): the next room's
//! bounce read 1.95x the brute force's, a doorway strip 4.8x.
//!
//! The dissertation re-traces a stretched prior per block (seconds per block, §3.5.2). This
//! module corrects the flux instead, per face pair, at level assembly: the share of diffuse
//! light leaving face e of the real box that first meets face f (cosine rays from uniform
//! points, exact ray-box exits) against the same share in the unit cube. Light that enters
//! through e and meets f (the surface response, the propagation out through an open side) is
//! scaled by `(F[e][f] A_e / A_f) / F_cube[e][f]`, which makes its flux the real box's for
//! uniform diffuse light; so is the block's own light, face by face (`level::own_light`: its
//! walls are diffuse, so there the correction is exact in flux); light from all the walls
//! leaving through an opening by the ratio of the walls' summed shares. A unit block's factors
//! are exactly 1 (the same rays).

use glam::Vec3;

use super::gather::cosine_rays;
use super::shape::{Face, exit};
use crate::precompute::rng::Pcg32;

/// The largest scale applied. The shares are those of diffuse light, and a light field that is
/// not diffuse can pass a stretched block very differently: a thin slab between two open sides
/// passes 63% of diffuse light straight through against the cube's 20% (a scale of 3.1), but
/// the cube already passes most of a beam square to the side, which the scale then tripled. The
/// feedback's loop gain then crossed 1 on the suite's rooms, then split into strips
/// (`bouncelab probe-mrt rooms --bounces 8`: 0.69 ... 0.95 and rising, the image's energy 108x after 32
/// frames). The cap applies where light enters or leaves through an opening (the propagation,
/// the exits and the surface response); measured there, a cap of 1 / 1.5 / 2 / 3 gave the next
/// room 0.39 / 0.81 / 0.97 / 1.16 of the brute force's bounce and a loop gain of 0.51 / 0.57 /
/// 0.60 / 0.96. A block's own light is diffuse and is not capped.
pub const CAP: f64 = 2.0;

/// Rays per face (a share's noise is about 1 / sqrt of it per face pair).
pub const RAYS: usize = 4096;

/// The flux shares of a box: `share[e][f]` of diffuse light leaving face e (inwards) that
/// first meets face f, and the faces' areas (world faces, [`Face::ALL`] order).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shares {
    pub share: [[f64; 6]; 6],
    pub area: [f64; 6],
}

/// The flux shares of a box of `size`.
pub fn shares(size: Vec3) -> Shares {
    let mut share = [[0.0; 6]; 6];
    let mut area = [0.0; 6];
    let side = (RAYS as f64).sqrt() as usize;
    for e in Face::ALL {
        let (a, b) = e.plane_axes();
        area[e as usize] = f64::from(size[a] * size[b]);
        let mut rng = Pcg32::new(11, e as u64, 5);
        let mut points = Pcg32::new(13, e as u64, 7);
        let n = e.inward_normal();
        let mut count = 0.0;
        for (q, d) in cosine_rays(n, RAYS, &mut rng).enumerate() {
            // A stratified point on the face (strata visited in a scrambled order, so that
            // position and direction are independent), the ray in the unit cube (the box scaled).
            let cell = (q * 7919) % (side * side);
            let (s, t) = (
                ((cell / side) as f32 + points.next_f32()) / side as f32,
                ((cell % side) as f32 + points.next_f32()) / side as f32,
            );
            let (f, _, _, _) = exit(e.point(s, t), d / size);
            share[e as usize][f as usize] += 1.0;
            count += 1.0;
        }
        share[e as usize].iter_mut().for_each(|v| *v /= count);
    }
    Shares { share, area }
}

/// The radiance scales of one block.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Warp {
    /// `through[e][f]`: light entering through world side e and meeting world face f.
    pub through: [[f64; 6]; 6],
    /// `walls[f]`: light from the present faces meeting world face f.
    pub walls: [f64; 6],
}

impl Warp {
    /// No correction.
    pub const NONE: Warp = Warp { through: [[1.0; 6]; 6], walls: [1.0; 6] };

    /// The scales of a box of `size` whose world faces `present` reflect light.
    pub fn new(size: Vec3, present: &[Face]) -> Self {
        let (real, cube) = (shares(size), shares(Vec3::ONE));
        let mut w = Self::NONE;
        for e in 0..6 {
            for f in 0..6 {
                let c = cube.share[e][f];
                let scale = if c > 0.0 { real.share[e][f] * real.area[e] / real.area[f] / c } else { 1.0 };
                w.through[e][f] = scale;
            }
        }
        for f in 0..6 {
            let real_in: f64 = present.iter().map(|g| real.area[*g as usize] * real.share[*g as usize][f]).sum();
            let cube_in: f64 = present.iter().map(|g| cube.share[*g as usize][f]).sum();
            let scale = if cube_in > 0.0 { real_in / real.area[f] / cube_in } else { 1.0 };
            w.walls[f] = scale;
        }
        w
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_unit_block_needs_no_correction_and_shares_sum_to_one() {
        let w = Warp::new(Vec3::ONE, &Face::ALL);
        assert!(w.through.iter().flatten().chain(&w.walls).all(|v| (v - 1.0).abs() < 1e-12), "{w:?}");
        let s = shares(Vec3::new(5.0, 2.9, 0.9));
        for row in s.share {
            assert!((row.iter().sum::<f64>() - 1.0).abs() < 1e-9);
        }
        // A face sees nothing of itself; the cube's opposite face gets about 20%.
        let c = shares(Vec3::ONE);
        assert_eq!(c.share[0][0], 0.0);
        assert!((c.share[0][1] - 0.2).abs() < 0.01, "{}", c.share[0][1]);
    }

    #[test]
    fn a_closed_box_keeps_uniform_light_uniform_and_a_long_strip_dims_entering_light() {
        // Reciprocity: in any closed box, uniform walls give uniform irradiance.
        let w = Warp::new(Vec3::new(5.0, 2.9, 0.9), &Face::ALL);
        assert!(w.walls.iter().all(|v| (v - 1.0).abs() < 0.03), "{:?}", w.walls);
        // Light entering the strip's small end spreads over a floor five times its area.
        let (e, floor) = (Face::NegX as usize, Face::NegY as usize);
        assert!(w.through[e][floor] < 0.7, "{}", w.through[e][floor]);
    }
}
