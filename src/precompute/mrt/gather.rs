//! MRT's one-bounce gather F inside a dictionary shape (Loos 2015 eq. 3.1 and §5.2.1, eq. 5.1;
//! importance-sampled gather rays as in §3.6.1): `(F l)(x_i) = (1/N) sum_k l(hit_k)` over N
//! cosine-distributed rays from sample i, each ray's hit the point where it leaves the unit cube
//! (inside an empty box, exact and analytic), read bilinearly from the hit face's texels. A ray
//! leaving through an open side adds 0: light crossing openings is the interface operators'
//! business. F is never stored; it is applied to the columns of a matrix (the scaled prior, or the
//! implicit lights) in one pass, so each ray is cast once whatever the number of columns.
//!
//! Rays are stratified (a sqrt(N) x sqrt(N) grid over the disc's square, jittered) and seeded
//! per sample, so the result is identical whatever the thread scheduling.

use glam::Vec3;
use rayon::prelude::*;

use super::shape::{Layout, exit};
use crate::precompute::rng::Pcg32;

/// Applies F to the columns of `a` (n x k, row-major: `a[i * k + j]`): returns F a, n x k.
/// `rays` per sample (rounded down to a square); `cancel` stops early with `None`.
pub fn apply(
    layout: &Layout,
    a: &[f64],
    k: usize,
    rays: usize,
    seed: u64,
    cancel: &(dyn Fn() -> bool + Sync),
) -> Option<Vec<f64>> {
    let n = layout.len();
    debug_assert_eq!(a.len(), n * k);
    let count = ray_count(rays);
    let rows: Vec<Option<Vec<f64>>> = (0..n)
        .into_par_iter()
        .map(|i| {
            if cancel() {
                return None;
            }
            let (_, _, p, normal) = layout.sample(i);
            let mut rng = Pcg32::new(seed, i as u64, 0);
            let mut row = vec![0.0f64; k];
            for dir in cosine_rays(normal, rays, &mut rng) {
                let (face, s, tt, _) = exit(p, dir);
                let Some(taps) = layout.bilinear(face, s, tt) else { continue };
                for (j, w) in taps {
                    if w > 0.0 {
                        let src = &a[j * k..(j + 1) * k];
                        row.iter_mut().zip(src).for_each(|(r, x)| *r += f64::from(w) * x);
                    }
                }
            }
            row.iter_mut().for_each(|r| *r /= count);
            Some(row)
        })
        .collect();
    let mut out = Vec::with_capacity(n * k);
    for row in rows {
        out.extend(row?);
    }
    Some(out)
}

/// About `rays` cosine-distributed directions about `normal` (rounded down to a square),
/// stratified on a sqrt(N) x sqrt(N) grid and jittered by `rng`.
pub(crate) fn cosine_rays(normal: Vec3, rays: usize, rng: &mut Pcg32) -> impl Iterator<Item = Vec3> + '_ {
    let side = (rays as f64).sqrt().floor().max(1.0) as usize;
    let (t, b) = normal.any_orthonormal_pair();
    (0..side * side).map(move |q| {
        let (u, v) = (q / side, q % side);
        let (r1, r2) = ((u as f32 + rng.next_f32()) / side as f32, (v as f32 + rng.next_f32()) / side as f32);
        cosine_direction(normal, t, b, r1, r2)
    })
}

/// The number of directions [`cosine_rays`] makes for `rays`.
pub(super) fn ray_count(rays: usize) -> f64 {
    let side = (rays as f64).sqrt().floor().max(1.0);
    side * side
}

/// A cosine-distributed direction about `n` (Malley: a uniform disc point lifted to the
/// hemisphere) from two numbers in [0, 1).
fn cosine_direction(n: Vec3, t: Vec3, b: Vec3, r1: f32, r2: f32) -> Vec3 {
    let r = r1.sqrt();
    let phi = std::f32::consts::TAU * r2;
    let (x, y) = (r * phi.cos(), r * phi.sin());
    let z = (1.0 - r1).max(0.0).sqrt();
    (t * x + b * y + n * z).normalize()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::precompute::mrt::shape::{Face, Shape};

    #[test]
    fn in_a_closed_box_every_ray_hits_a_wall_so_uniform_light_gathers_to_one() {
        let layout = Layout::new(Shape::Closed, 4);
        let ones = vec![1.0; layout.len()];
        let f = apply(&layout, &ones, 1, 64, 1, &|| false).expect("not cancelled");
        assert!(f.iter().all(|v| (v - 1.0).abs() < 1e-5), "{:?}", &f[..8]);
    }

    /// The form factor from the floor point (x, 0, z) (normal +y) to the open +z side (the
    /// unit square at z = 1), by a fine midpoint sum of cos cos / (pi r^2) over the square.
    fn to_opening(x: f64, z: f64) -> f64 {
        let m = 400;
        let da = 1.0 / (m * m) as f64;
        let mut f = 0.0;
        for a in 0..m {
            for b in 0..m {
                let q = ((a as f64 + 0.5) / m as f64, (b as f64 + 0.5) / m as f64, 1.0);
                let v = (q.0 - x, q.1, q.2 - z);
                let r2 = v.0 * v.0 + v.1 * v.1 + v.2 * v.2;
                f += v.1 * v.2 / (std::f64::consts::PI * r2 * r2) * da;
            }
        }
        f
    }

    #[test]
    fn the_floor_centre_loses_the_opening_form_factor_of_an_open_side() {
        // Uniform light on every present face: the floor centre gathers 1 minus what leaves
        // through the open +z side (a 1x1 rectangle 0.5 away, perpendicular to the floor).
        let layout = Layout::new(Shape::DeadEnd, 8);
        let ones = vec![1.0; layout.len()];
        let f = apply(&layout, &ones, 1, 40_000, 3, &|| false).expect("not cancelled");
        let floor = layout.face_start(Face::NegY).expect("floor");
        // The four texels around the centre (8x8: texels 3 and 4 straddle 0.5).
        let centre: f64 = [(3, 3), (4, 3), (3, 4), (4, 4)].iter().map(|(s, t)| f[floor + t * 8 + s]).sum::<f64>() / 4.0;
        // Texel centres sit at 0.4375 / 0.5625: average the exact value over the four.
        let expected: f64 = [(0.4375, 0.4375), (0.5625, 0.4375), (0.4375, 0.5625), (0.5625, 0.5625)]
            .iter()
            .map(|(x, z)| 1.0 - to_opening(*x, *z))
            .sum::<f64>()
            / 4.0;
        eprintln!("floor centre gathers {centre:.4}, exact {expected:.4}");
        assert!((centre - expected).abs() < 0.01, "gathered {centre:.4}, exact {expected:.4}");
    }

    #[test]
    fn the_gather_is_deterministic_and_linear() {
        let layout = Layout::new(Shape::Corner, 4);
        let a: Vec<f64> = (0..layout.len() * 2).map(|i| (i % 7) as f64).collect();
        let f1 = apply(&layout, &a, 2, 16, 5, &|| false).expect("run");
        let f2 = apply(&layout, &a, 2, 16, 5, &|| false).expect("run");
        assert_eq!(f1, f2);
        let doubled: Vec<f64> = a.iter().map(|x| 2.0 * x).collect();
        let f3 = apply(&layout, &doubled, 2, 16, 5, &|| false).expect("run");
        assert!(f1.iter().zip(&f3).all(|(x, y)| (2.0 * x - y).abs() < 1e-9));
        assert!(apply(&layout, &a, 2, 16, 5, &|| true).is_none(), "cancelled");
    }
}
