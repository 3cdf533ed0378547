//! MRT's light fields at block openings (Loos 2015 §4.2.1): the radiance crossing an open side,
//! sampled on a grid of positions over the opening and of directions over the hemisphere, each
//! direction cell averaged over a supersampling grid.
//!
//! Frame: every *directed* interface has an intrinsic frame, n = the direction light travels
//! (out of the source block, into the receiving one), v = world up, u = n x v. Positions are
//! (u, v) coordinates over the opening; directions come from Shirley and Chiu's concentric map of
//! the square to the disc, lifted to the hemisphere about n with the equal-area map
//! (x sqrt(2 - r^2), y sqrt(2 - r^2), 1 - r^2). The light field leaving block X through a face is
//! then the light field entering its neighbour in identical coordinates: nothing is mirrored.
//!
//! A light field of a block's wall radiance is read by tracing each (position, direction)
//! sample backwards into the block: the wall it reaches gives its value (bilinear in the wall's
//! texels); a ray that leaves through another opening reads 0.

use glam::{Vec2, Vec3};

use super::shape::{Face, Layout, exit};

/// Light-field resolution (Loos 2015 §4.2.1: 12 x 12 positions, 24 x 24 directions, 5 x 5
/// supersampling).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LightFieldRes {
    /// Positions per side of the opening.
    pub positions: usize,
    /// Direction cells per side of the concentric square.
    pub directions: usize,
    /// Supersamples per side of a direction cell.
    pub supersample: usize,
}

impl Default for LightFieldRes {
    fn default() -> Self {
        Self { positions: 12, directions: 24, supersample: 5 }
    }
}

impl LightFieldRes {
    /// Samples s of one light field: positions^2 x directions^2.
    pub fn len(&self) -> usize {
        self.positions * self.positions * self.directions * self.directions
    }

    /// Whether there are no samples.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// The intrinsic frame (u, v, n) of light leaving the unit cube through side `face`.
pub fn frame(face: Face) -> (Vec3, Vec3, Vec3) {
    let n = -face.inward_normal();
    let v = Vec3::Y;
    (n.cross(v), v, n)
}

/// Shirley and Chiu's concentric map of [-1, 1]^2 to the unit disc.
pub fn concentric(p: Vec2) -> Vec2 {
    if p.x == 0.0 && p.y == 0.0 {
        return Vec2::ZERO;
    }
    let (r, phi) = if p.x.abs() > p.y.abs() {
        (p.x, std::f32::consts::FRAC_PI_4 * (p.y / p.x))
    } else {
        (p.y, std::f32::consts::FRAC_PI_2 - std::f32::consts::FRAC_PI_4 * (p.x / p.y))
    };
    Vec2::new(r * phi.cos(), r * phi.sin())
}

/// The hemisphere direction about +z (in the frame's (u, v, n) coordinates) of the square point
/// `p` in [-1, 1]^2: concentric map, then the equal-area lift.
pub fn square_to_hemisphere(p: Vec2) -> Vec3 {
    let d = concentric(p);
    let r2 = d.length_squared().min(1.0);
    let k = (2.0 - r2).sqrt();
    Vec3::new(d.x * k, d.y * k, 1.0 - r2)
}

/// The inverse of [`concentric`]: the square point in [-1, 1]^2 of a disc point.
pub fn concentric_inverse(d: Vec2) -> Vec2 {
    use std::f32::consts::{FRAC_PI_4, PI};
    let r = d.length();
    if r == 0.0 {
        return Vec2::ZERO;
    }
    let mut phi = d.y.atan2(d.x);
    if phi < -FRAC_PI_4 {
        phi += 2.0 * PI;
    }
    if phi < FRAC_PI_4 {
        Vec2::new(r, phi / FRAC_PI_4 * r)
    } else if phi < 3.0 * FRAC_PI_4 {
        Vec2::new(-(phi - 0.5 * PI) / FRAC_PI_4 * r, r)
    } else if phi < 5.0 * FRAC_PI_4 {
        Vec2::new(-r, -(phi - PI) / FRAC_PI_4 * r)
    } else {
        Vec2::new((phi - 1.5 * PI) / FRAC_PI_4 * r, -r)
    }
}

/// The inverse of [`square_to_hemisphere`] for a unit direction with z >= 0.
pub fn hemisphere_to_square(h: Vec3) -> Vec2 {
    let r2 = (1.0 - h.z).clamp(0.0, 1.0);
    let k = (2.0 - r2).sqrt();
    concentric_inverse(Vec2::new(h.x / k, h.y / k)).clamp(Vec2::splat(-1.0), Vec2::splat(1.0))
}

/// The quadrilinear taps (sample index, weight) of the light field at opening coordinates
/// `(pu, pv)` in [0, 1]^2 and square direction `q` in [-1, 1]^2 (clamped at the borders).
pub fn taps(res: &LightFieldRes, (pu, pv): (f32, f32), q: Vec2) -> [(usize, f32); 16] {
    let axis = |x: f32, n: usize| {
        let c = (x * n as f32 - 0.5).clamp(0.0, n as f32 - 1.0);
        let i = (c.floor() as usize).min(n - 1);
        (i, (i + 1).min(n - 1), c - i as f32)
    };
    let (i0, i1, fi) = axis(pu, res.positions);
    let (j0, j1, fj) = axis(pv, res.positions);
    let (a0, a1, fa) = axis(q.x * 0.5 + 0.5, res.directions);
    let (b0, b1, fb) = axis(q.y * 0.5 + 0.5, res.directions);
    let mut out = [(0, 0.0); 16];
    let mut n = 0;
    for (i, wi) in [(i0, 1.0 - fi), (i1, fi)] {
        for (j, wj) in [(j0, 1.0 - fj), (j1, fj)] {
            for (a, wa) in [(a0, 1.0 - fa), (a1, fa)] {
                for (b, wb) in [(b0, 1.0 - fb), (b1, fb)] {
                    out[n] = (index(res, (i, j), (a, b)), wi * wj * wa * wb);
                    n += 1;
                }
            }
        }
    }
    out
}

/// Sample index of position (i, j) and direction cell (a, b).
pub fn index(res: &LightFieldRes, (i, j): (usize, usize), (a, b): (usize, usize)) -> usize {
    ((j * res.positions + i) * res.directions + b) * res.directions + a
}

/// The light field leaving `layout`'s shape through its open side `face`, for each column of the
/// wall radiance `walls` (n x k, row-major): s x k, row-major, rows in [`index`] order.
pub fn trace(layout: &Layout, face: Face, walls: &[f64], k: usize, res: &LightFieldRes) -> Vec<f64> {
    use rayon::prelude::*;
    let (u, v, n) = frame(face);
    let centre = face.point(0.5, 0.5);
    let (p, d, ss) = (res.positions, res.directions, res.supersample);
    let per_cell = (ss * ss) as f64;
    // Directions of every supersample, per cell, in world space (shared by every position).
    let cells: Vec<Vec<Vec3>> = (0..d * d)
        .map(|c| {
            let (a, b) = (c % d, c / d);
            (0..ss * ss)
                .map(|q| {
                    let (x, y) = (q % ss, q / ss);
                    let sq = Vec2::new(
                        ((a * ss + x) as f32 + 0.5) / (d * ss) as f32 * 2.0 - 1.0,
                        ((b * ss + y) as f32 + 0.5) / (d * ss) as f32 * 2.0 - 1.0,
                    );
                    let h = square_to_hemisphere(sq);
                    (u * h.x + v * h.y + n * h.z).normalize()
                })
                .collect()
        })
        .collect();
    let rows: Vec<Vec<f64>> = (0..p * p)
        .into_par_iter()
        .flat_map_iter(|pos| {
            let (i, j) = (pos % p, pos / p);
            let origin = centre + u * ((i as f32 + 0.5) / p as f32 - 0.5) + v * ((j as f32 + 0.5) / p as f32 - 0.5);
            let cells = &cells;
            (0..d * d).map(move |c| {
                let mut row = vec![0.0f64; k];
                for dir in &cells[c] {
                    // Backwards into the block.
                    let (hit, s, t, _) = exit(origin, -*dir);
                    if hit == face {
                        continue;
                    }
                    let Some(taps) = layout.bilinear(hit, s, t) else { continue };
                    for (w_index, w) in taps {
                        if w > 0.0 {
                            let src = &walls[w_index * k..(w_index + 1) * k];
                            row.iter_mut().zip(src).for_each(|(r, x)| *r += f64::from(w) * x);
                        }
                    }
                }
                row.iter_mut().for_each(|r| *r /= per_cell);
                row
            })
        })
        .collect();
    // Rows came out in (position, cell) order; reorder to [`index`].
    let mut out = vec![0.0; p * p * d * d * k];
    for (pos, chunk) in rows.chunks(d * d).enumerate() {
        let (i, j) = (pos % p, pos / p);
        for (c, row) in chunk.iter().enumerate() {
            let at = index(res, (i, j), (c % d, c / d));
            out[at * k..(at + 1) * k].copy_from_slice(row);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::precompute::mrt::shape::Shape;

    #[test]
    fn the_lift_is_equal_area_onto_the_hemisphere() {
        // Uniform square samples land uniformly in solid angle: the mean cosine is 1/2.
        let m = 200;
        let mut mean_cos = 0.0;
        for a in 0..m {
            for b in 0..m {
                let p = Vec2::new((a as f32 + 0.5) / m as f32 * 2.0 - 1.0, (b as f32 + 0.5) / m as f32 * 2.0 - 1.0);
                let h = square_to_hemisphere(p);
                assert!((h.length() - 1.0).abs() < 1e-5 && h.z >= 0.0, "{p} -> {h}");
                mean_cos += f64::from(h.z);
            }
        }
        mean_cos /= (m * m) as f64;
        assert!((mean_cos - 0.5).abs() < 1e-3, "mean cosine {mean_cos}");
        // The square's centre is the normal, its edges the horizon.
        assert_eq!(square_to_hemisphere(Vec2::ZERO), Vec3::Z);
        assert!(square_to_hemisphere(Vec2::new(1.0, 0.3)).z.abs() < 1e-6);
    }

    #[test]
    fn the_inverse_maps_undo_the_forward_ones() {
        for a in 0..9 {
            for b in 0..9 {
                let p = Vec2::new(a as f32 / 4.0 - 1.0, b as f32 / 4.0 - 1.0);
                let back = hemisphere_to_square(square_to_hemisphere(p));
                assert!((back - p).length() < 1e-4, "{p} -> {back}");
            }
        }
        let res = LightFieldRes { positions: 4, directions: 6, supersample: 1 };
        let t = taps(&res, (0.3, 0.9), Vec2::new(-0.2, 0.7));
        assert!((t.iter().map(|x| x.1).sum::<f32>() - 1.0).abs() < 1e-6);
        assert!(t.iter().all(|x| x.0 < res.len()));
    }

    #[test]
    fn frames_follow_the_light_out_of_the_block_with_up_as_v() {
        let (u, v, n) = frame(Face::PosZ);
        assert_eq!((v, n), (Vec3::Y, Vec3::Z));
        assert!((u - Vec3::NEG_X).length() < 1e-6, "u = n x v = {u}");
        // The face opposite carries light the other way; its u flips so (u, v, n) stays right-handed.
        let (u2, _, n2) = frame(Face::NegZ);
        assert_eq!((u2, n2), (Vec3::X, Vec3::NEG_Z));
    }

    #[test]
    fn uniform_walls_fill_a_dead_ends_light_field_and_a_corridor_loses_what_flies_through() {
        let res = LightFieldRes { positions: 3, directions: 6, supersample: 3 };
        let dead_end = Layout::new(Shape::DeadEnd, 4);
        let lf = trace(&dead_end, Face::PosZ, &vec![1.0; dead_end.len()], 1, &res);
        assert!(lf.iter().all(|v| (v - 1.0).abs() < 1e-6), "every backward ray meets a wall");
        let corridor = Layout::new(Shape::Corridor, 4);
        let lf = trace(&corridor, Face::PosZ, &vec![1.0; corridor.len()], 1, &res);
        // Straight along n the backward ray leaves through the far opening: 0 at the centre
        // direction of the middle position; grazing directions hit the walls.
        let centre = lf[index(&res, (1, 1), (2, 2))].min(lf[index(&res, (1, 1), (3, 3))]);
        let grazing = lf[index(&res, (1, 1), (0, 3))];
        assert!(centre < 0.5 && grazing > 0.9, "centre {centre}, grazing {grazing}");
        // Light leaving +z read over its frame agrees with the geometry: a direction tilted
        // towards +u (= -x) comes from the +x wall's side.
        let mut walls = vec![0.0; corridor.len()];
        let start = corridor.face_start(Face::PosX).expect("+x wall");
        walls[start..start + 16].iter_mut().for_each(|w| *w = 1.0);
        let lf = trace(&corridor, Face::PosZ, &walls, 1, &res);
        let towards_u = lf[index(&res, (1, 1), (5, 3))];
        let away = lf[index(&res, (1, 1), (0, 3))];
        assert!(towards_u > 0.5 && away < 1e-6, "towards +u {towards_u}, towards -u {away}");
    }
}
