//! Linked block sides that the real level leaves only partly open: a room's whole side fitted
//! around a doorway. The dissertation's blocks meet over whole open sides; a fitted room meets
//! its neighbour through a side of which the doorway is a small part (15% in a 5 x 2.8 m
//! partition with a 1 x 2.1 m door). A scalar share passed the side's average light and absorbed
//! the rest: the door's place on the side was lost and the wall around it reflected nothing,
//! which took 10% off every bounce of a room with such sides (`bouncelab probe-mrt rooms
//! --multi 8`: 0.83 of a brute force's eight bounces in the lit room).
//!
//! Here the light field crossing a side is masked position by position in the reduced space:
//! with U~ the light-field basis (orthonormal, s x k_rlf) and U_p its rows at opening position
//! p, the Gram blocks G_p = U_p^T U_p sum to the identity, so M = sum_p open_p G_p carries
//! exactly the light that crosses the open positions (M = I for a fully open side). The closed
//! positions reflect diffusely back into the block: the irradiance E_p q (cosine-weighted sum of
//! the field over position p's directions) times albedo / pi, re-emitted as a uniform radiance at
//! the same place, which in the entering frame (n and u both reversed) is position p's mirror
//! in u: S = sum_p albedo_p (1 - open_p) / pi D_mirror(p) E_p^T, with D_p = U_p^T 1 the
//! coefficients of unit radiance at position p. All three come from U~ at dictionary build
//! (k_rlf^2 per position: 19 MB at 12 x 12 positions and 128 modes), so the level assembly needs
//! no light field.
//!
//! The reflection is grey (the closed positions' mean albedo over red, green and blue): T_{b->r}
//! is one matrix for all three channels.

use rayon::prelude::*;

use super::lightfield::{LightFieldRes, square_to_hemisphere};

/// The per-position operators of the reduced light-field basis.
#[derive(Clone, Debug, PartialEq)]
pub struct PositionOps {
    /// Positions per side of an opening P.
    pub positions: usize,
    /// Light-field modes k_rlf.
    pub k: usize,
    /// G_p = U_p^T U_p per position (P^2 x k x k, row-major per position).
    pub gram: Vec<f64>,
    /// E_p per position (P^2 x k): the irradiance at position p of field coefficients q is E_p . q.
    pub irradiance: Vec<f64>,
    /// D_p per position (P^2 x k): the coefficients of unit radiance over all directions at p.
    pub diffuse: Vec<f64>,
}

impl PositionOps {
    /// The operators of basis `u` (s x k, rows in `lightfield::index` order) at resolution `res`.
    pub fn build(res: &LightFieldRes, u: &[f64], k: usize) -> Self {
        let (p, d, ss) = (res.positions, res.directions, res.supersample.max(1));
        let dirs = d * d;
        // Each direction cell's mean cosine to the opening's normal, times its solid angle (the
        // equal-area lift gives every cell 2 pi / d^2).
        let weight: Vec<f64> = (0..dirs)
            .map(|c| {
                let (a, b) = (c % d, c / d);
                let mut cos = 0.0;
                for q in 0..ss * ss {
                    let (x, y) = (q % ss, q / ss);
                    let sq = glam::Vec2::new(
                        ((a * ss + x) as f32 + 0.5) / (d * ss) as f32 * 2.0 - 1.0,
                        ((b * ss + y) as f32 + 0.5) / (d * ss) as f32 * 2.0 - 1.0,
                    );
                    cos += f64::from(square_to_hemisphere(sq).z);
                }
                cos / (ss * ss) as f64 * std::f64::consts::TAU / dirs as f64
            })
            .collect();
        let per: Vec<(Vec<f64>, Vec<f64>, Vec<f64>)> = (0..p * p)
            .into_par_iter()
            .map(|pos| {
                let rows = &u[pos * dirs * k..(pos + 1) * dirs * k];
                let mut gram = vec![0.0; k * k];
                let mut irradiance = vec![0.0; k];
                let mut diffuse = vec![0.0; k];
                for (c, row) in rows.chunks_exact(k).enumerate() {
                    for (i, ri) in row.iter().enumerate() {
                        irradiance[i] += weight[c] * ri;
                        diffuse[i] += ri;
                        if *ri != 0.0 {
                            let g = &mut gram[i * k..(i + 1) * k];
                            g.iter_mut().zip(row).for_each(|(g, rj)| *g += ri * rj);
                        }
                    }
                }
                (gram, irradiance, diffuse)
            })
            .collect();
        let mut out = Self {
            positions: p,
            k,
            gram: Vec::with_capacity(p * p * k * k),
            irradiance: Vec::with_capacity(p * p * k),
            diffuse: Vec::with_capacity(p * p * k),
        };
        for (g, e, dd) in per {
            out.gram.extend(g);
            out.irradiance.extend(e);
            out.diffuse.extend(dd);
        }
        out
    }

    /// The mask M = sum_p open_p G_p (k x k, row-major) of per-position open shares `open` (P^2,
    /// position i + j P); `None` where every position is fully open (M = I).
    pub fn mask(&self, open: &[f64]) -> Option<Vec<f64>> {
        if open.iter().all(|o| *o >= 1.0) {
            return None;
        }
        let kk = self.k * self.k;
        let mut m = vec![0.0; kk];
        for (pos, o) in open.iter().enumerate().filter(|(_, o)| **o > 0.0) {
            m.iter_mut().zip(&self.gram[pos * kk..(pos + 1) * kk]).for_each(|(m, g)| *m += o * g);
        }
        Some(m)
    }

    /// The reflection S (k x k, row-major) of the closed share of each position back into the
    /// block the light came from, with the closed surfaces' albedo `albedo` (P^2 each); `None`
    /// where nothing is closed.
    pub fn reflection(&self, open: &[f64], albedo: &[f64]) -> Option<Vec<f64>> {
        let (p, k) = (self.positions, self.k);
        let mut s = vec![0.0; k * k];
        let mut any = false;
        for (pos, (o, a)) in open.iter().zip(albedo).enumerate() {
            let c = a * (1.0 - o).max(0.0) / std::f64::consts::PI;
            if c <= 0.0 {
                continue;
            }
            any = true;
            let (i, j) = (pos % p, pos / p);
            let mirror = j * p + (p - 1 - i);
            let d = &self.diffuse[mirror * k..(mirror + 1) * k];
            let e = &self.irradiance[pos * k..(pos + 1) * k];
            for (row, di) in s.chunks_exact_mut(k).zip(d) {
                row.iter_mut().zip(e).for_each(|(x, ej)| *x += c * di * ej);
            }
        }
        any.then_some(s)
    }
}

/// What the real level leaves open of one linked side, per light-field position (i + j P in the
/// frame of light leaving the block: u = n x up, v = up).
#[derive(Clone, Debug, PartialEq)]
pub struct Opening {
    /// Open share per position (0..=1).
    pub open: Vec<f64>,
    /// Mean albedo (grey) of the surface closing each position, seen from inside the block.
    pub albedo: Vec<f64>,
}

impl Opening {
    /// A side open by `share` everywhere, closed by albedo `albedo`, at `positions`^2 positions.
    pub fn uniform(positions: usize, share: f64, albedo: f64) -> Self {
        let n = positions * positions;
        Self { open: vec![share.clamp(0.0, 1.0); n], albedo: vec![albedo; n] }
    }

    /// The open share of the whole side.
    pub fn share(&self) -> f64 {
        self.open.iter().sum::<f64>() / self.open.len().max(1) as f64
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An orthonormal basis of a few smooth light fields at a tiny resolution (Gram-Schmidt).
    fn basis(res: &LightFieldRes, k: usize) -> Vec<f64> {
        let s = res.len();
        let mut cols: Vec<Vec<f64>> = Vec::new();
        for m in 0..k {
            let mut c: Vec<f64> = (0..s).map(|i| ((i * (m + 1)) as f64 * 0.37 + m as f64).sin() + 1.5).collect();
            for prev in &cols {
                let dot: f64 = c.iter().zip(prev).map(|(a, b)| a * b).sum();
                c.iter_mut().zip(prev).for_each(|(a, b)| *a -= dot * b);
            }
            let n = c.iter().map(|x| x * x).sum::<f64>().sqrt();
            c.iter_mut().for_each(|x| *x /= n);
            cols.push(c);
        }
        (0..s).flat_map(|i| cols.iter().map(move |c| c[i])).collect()
    }

    #[test]
    fn the_gram_blocks_sum_to_the_identity_and_a_half_mask_passes_half_of_a_uniform_side() {
        let res = LightFieldRes { positions: 3, directions: 4, supersample: 2 };
        let k = 6;
        let ops = PositionOps::build(&res, &basis(&res, k), k);
        assert!(ops.mask(&[1.0; 9]).is_none(), "a fully open side is the identity");
        let all = ops.mask(&[0.999_999; 9]).expect("mask");
        for i in 0..k {
            for j in 0..k {
                let want = if i == j { 1.0 } else { 0.0 };
                assert!((all[i * k + j] - want).abs() < 1e-5, "M[{i}][{j}] = {}", all[i * k + j]);
            }
        }
        // Closing the left third passes the other two thirds' share of the field's energy.
        let open: Vec<f64> = (0..9).map(|p| if p % 3 == 0 { 0.0 } else { 1.0 }).collect();
        let m = ops.mask(&open).expect("mask");
        let trace: f64 = (0..k).map(|i| m[i * k + i]).sum();
        assert!(trace > 0.2 * k as f64 && trace < 0.9 * k as f64, "trace {trace}");
    }

    #[test]
    fn a_closed_white_side_reflects_the_irradiance_it_receives() {
        // A field of unit radiance everywhere (in span: the first basis vector made uniform) has
        // irradiance pi at every position; a closed white side sends back unit radiance.
        let res = LightFieldRes { positions: 2, directions: 12, supersample: 3 };
        let s = res.len();
        let k = 1;
        let u = vec![1.0 / (s as f64).sqrt(); s];
        let ops = PositionOps::build(&res, &u, k);
        let q = (s as f64).sqrt(); // U q = 1 everywhere
        let e: f64 = ops.irradiance[..k].iter().map(|x| x * q).sum();
        assert!((e - std::f64::consts::PI).abs() < 0.01, "irradiance {e}");
        let closed = Opening::uniform(2, 0.0, 1.0);
        let r = ops.reflection(&closed.open, &closed.albedo).expect("reflection");
        assert!((r[0] * q - q).abs() < 0.01 * q, "reflected {} of {q}", r[0] * q);
        assert!(ops.reflection(&[1.0; 4], &[1.0; 4]).is_none(), "an open side reflects nothing");
        assert!((closed.share() - 0.0).abs() < 1e-12 && (Opening::uniform(2, 0.25, 0.5).share() - 0.25).abs() < 1e-12);
    }
}
