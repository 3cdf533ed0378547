//! MRT's light-field propagation through a block (Loos 2015 §3.4.1 / §4.2.2, the operators R ahead,
//! left and right): light entering a block through one opening and leaving, unchanged, through the
//! opening straight ahead, on the left or on the right. Each target sample (position over the
//! exit, direction cell, supersampled) is traced backwards into the block; where the ray crosses
//! the entry opening it reads the entering light field there (quadrilinear), anywhere else (a
//! wall, another opening) it reads 0: light that hits a wall is that block's surface response,
//! not propagation. W is that resampling; the reduced operators are R = U~^T W U~.
//!
//! Canonical geometry: light enters through the +z side travelling -z (the dictionary's dead
//! end, whose one opening is +z); ahead is -z, left is -x and right is +x (facing -z with +y up,
//! the right hand points to +x). The frames are intrinsic, so a block's real entry side maps
//! here by a rotation about up.

use glam::{Vec2, Vec3};
use rayon::prelude::*;

use super::lightfield::{self, LightFieldRes};
use super::shape::{Face, exit};

/// The entry side of the canonical block.
pub const ENTRY: Face = Face::PosZ;

/// Where light leaves after entering through [`ENTRY`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Turn {
    /// Straight through: -z.
    Ahead,
    /// The traveller's left: -x.
    Left,
    /// The traveller's right: +x.
    Right,
}

impl Turn {
    /// All three.
    pub const ALL: [Turn; 3] = [Turn::Ahead, Turn::Left, Turn::Right];

    /// The exit side in the canonical block.
    pub fn exit(self) -> Face {
        match self {
            Turn::Ahead => Face::NegZ,
            Turn::Left => Face::NegX,
            Turn::Right => Face::PosX,
        }
    }
}

/// The point at opening coordinates (pu, pv) of `face` in the frame of light leaving through it.
fn opening_point(face: Face, pu: f32, pv: f32) -> Vec3 {
    let (u, v, _) = lightfield::frame(face);
    face.point(0.5, 0.5) + u * (pu - 0.5) + v * (pv - 0.5)
}

/// Applies W for `turn` to the k columns of `field` (s x k, row-major, light entering through
/// [`ENTRY`] in the frame of light leaving the previous block through the shared side): the
/// light leaving through the turn's exit, s x k.
pub fn resample(res: &LightFieldRes, turn: Turn, field: &[f64], k: usize) -> Vec<f64> {
    let target = turn.exit();
    let (tu, tv, tn) = lightfield::frame(target);
    // Light entering through the +z side travels -z: the frame of leaving a block through -z.
    let (eu, ev, en) = lightfield::frame(ENTRY.opposite());
    let entry_centre = ENTRY.point(0.5, 0.5);
    let (p, d, ss) = (res.positions, res.directions, res.supersample);
    let per_cell = (ss * ss) as f64;
    let rows: Vec<Vec<f64>> = (0..res.len())
        .into_par_iter()
        .map(|sample| {
            let (a, b) = (sample % d, sample / d % d);
            let pos = sample / (d * d);
            let (i, j) = (pos % p, pos / p);
            let origin = opening_point(target, (i as f32 + 0.5) / p as f32, (j as f32 + 0.5) / p as f32);
            let mut row = vec![0.0f64; k];
            for q in 0..ss * ss {
                let (x, y) = (q % ss, q / ss);
                let sq = Vec2::new(
                    ((a * ss + x) as f32 + 0.5) / (d * ss) as f32 * 2.0 - 1.0,
                    ((b * ss + y) as f32 + 0.5) / (d * ss) as f32 * 2.0 - 1.0,
                );
                let h = lightfield::square_to_hemisphere(sq);
                let dir = (tu * h.x + tv * h.y + tn * h.z).normalize();
                let (hit, _, _, t) = exit(origin, -dir);
                if hit != ENTRY {
                    continue;
                }
                let at = origin - dir * t - entry_centre;
                let (pu, pv) = (at.dot(eu) + 0.5, at.dot(ev) + 0.5);
                let local = Vec3::new(dir.dot(eu), dir.dot(ev), dir.dot(en));
                for (src, w) in lightfield::taps(res, (pu, pv), lightfield::hemisphere_to_square(local)) {
                    if w > 0.0 {
                        let from = &field[src * k..(src + 1) * k];
                        row.iter_mut().zip(from).for_each(|(r, f)| *r += f64::from(w) * f);
                    }
                }
            }
            row.iter_mut().for_each(|r| *r /= per_cell);
            row
        })
        .collect();
    rows.into_iter().flatten().collect()
}

/// R = U~^T W U~ (k x k, row-major) for the orthonormal basis `u` (s x k).
pub fn reduced(res: &LightFieldRes, turn: Turn, u: &[f64], k: usize) -> Vec<f64> {
    let wu = resample(res, turn, u, k);
    let s = res.len();
    let mut r = vec![0.0; k * k];
    for i in 0..s {
        for m in 0..k {
            let um = u[i * k + m];
            if um != 0.0 {
                let row = &wu[i * k..(i + 1) * k];
                r[m * k..(m + 1) * k].iter_mut().zip(row).for_each(|(x, w)| *x += um * w);
            }
        }
    }
    r
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::precompute::mrt::lightfield::index;

    #[test]
    fn a_uniform_light_field_passes_where_the_backward_ray_reaches_the_entry() {
        let res = LightFieldRes { positions: 4, directions: 8, supersample: 2 };
        let ones = vec![1.0; res.len()];
        let ahead = resample(&res, Turn::Ahead, &ones, 1);
        // Straight ahead from the middle of the exit: the backward ray crosses the entry.
        let straight = ahead[index(&res, (1, 1), (3, 3))].min(ahead[index(&res, (2, 2), (4, 4))]);
        assert!(straight > 0.99, "straight through {straight}");
        // Grazing sideways from the exit's edge: the ray hits a side wall first.
        let grazing = ahead[index(&res, (0, 1), (0, 4))];
        assert!(grazing < 1e-9, "grazing {grazing}");
        assert!(ahead.iter().all(|v| (-1e-6..=1.0 + 1e-6).contains(v)), "a reprojection never adds light");
        // Leaving on the left (-x side, whose frame has u = -z): light travelling on towards
        // -z, seen near the entry, came through the entry; light travelling back towards +z
        // came from the far side.
        let left = resample(&res, Turn::Left, &ones, 1);
        assert_eq!(lightfield::frame(Face::NegX).0, Vec3::NEG_Z);
        let onwards = left[index(&res, (0, 1), (7, 4))];
        let backwards = left[index(&res, (0, 1), (0, 4))];
        assert!(onwards > 0.5 && backwards < 1e-9, "onwards {onwards}, backwards {backwards}");
    }

    #[test]
    fn a_light_field_that_varies_is_carried_to_where_its_rays_go() {
        // Light entering only on the entry's +u half (u = +x in the frame of light travelling
        // -z) keeps its side straight ahead, where u is +x as well (a mirrored frame would swap
        // the halves). Central direction cells tilt at most about 10 degrees.
        let res = LightFieldRes { positions: 8, directions: 16, supersample: 2 };
        let mut field = vec![0.0; res.len()];
        for j in 0..8 {
            for i in 4..8 {
                for a in 0..16 {
                    for b in 0..16 {
                        field[index(&res, (i, j), (a, b))] = 1.0;
                    }
                }
            }
        }
        let ahead = resample(&res, Turn::Ahead, &field, 1);
        let central = |i: usize| {
            [(7, 7), (8, 7), (7, 8), (8, 8)].iter().map(|&c| ahead[index(&res, (i, 3), c)]).sum::<f64>() / 4.0
        };
        let (lit, dark) = (central(6), central(1));
        assert!(lit > 0.95 && dark < 0.05, "lit {lit}, dark {dark}");
    }
}
