//! Linked sides of different extents. Loos links blocks on a grid, where a side always meets a
//! side of its own size; fitted levels link a corridor's end to a room's wall, a room to a taller
//! room, an L's arm to its corner. There the light field leaving one side must land where it
//! is in the world on the other, not at the same place in each side's unit square (which put a
//! third of an arm's flux into its corner, and half again of a low room's into a tall one).
//! Each position of the receiving side takes the irradiance of the leaving side's positions it
//! overlaps, area-weighted, as diffuse light: radiance per world point and the flux through the
//! overlap are kept, the direction within the crossing is not (matched sides keep it: they need
//! no remap).

use glam::Vec3;

use super::level::Level;
use super::opening::PositionOps;
use super::shape::Face;

/// Sides whose extents differ by less than this (m) count as matched.
const MATCHED: f32 = 0.01;

/// Per position index along one side axis, its world interval: `P` cells of the side's extent
/// `lo .. hi`, numbered along `sign` (+1: from `lo`, -1: from `hi`).
fn cells(lo: f32, hi: f32, sign: f32, p: usize) -> Vec<(f32, f32)> {
    let step = (hi - lo) / p as f32;
    (0..p)
        .map(|i| {
            if sign > 0.0 {
                (lo + i as f32 * step, lo + (i + 1) as f32 * step)
            } else {
                (hi - (i + 1) as f32 * step, hi - i as f32 * step)
            }
        })
        .collect()
}

/// The overlap of two intervals (0 when apart).
fn overlap(a: (f32, f32), b: (f32, f32)) -> f32 {
    (a.1.min(b.1) - a.0.max(b.0)).max(0.0)
}

/// The position weights (P² x P², row = receiving position, column = leaving position) of light
/// leaving block `x` through world side `w` into its neighbour beyond: each receiving position's
/// overlap with each leaving position over its own area; `None` when the two sides match.
pub fn weights(level: &Level, x: usize, w: Face, p: usize) -> Option<Vec<f64>> {
    let y = level.link(x, w)?;
    let (_, a_lo, a_hi) = level.side_rect(x, w);
    let (_, b_lo, b_hi) = level.side_rect(y, w.opposite());
    let axis_u = if w.axis() == 0 { 2 } else { 0 };
    let matched =
        [axis_u, 1].iter().all(|&k| (a_lo[k] - b_lo[k]).abs() < MATCHED && (a_hi[k] - b_hi[k]).abs() < MATCHED);
    if matched {
        return None;
    }
    // The frame of light leaving x: n outward, v up, u = n x v (the light field's positions).
    let mut n = Vec3::ZERO;
    n[w.axis()] = if w.positive() { 1.0 } else { -1.0 };
    let sign_u = n.cross(Vec3::Y)[axis_u].signum();
    let (au, av) = (cells(a_lo[axis_u], a_hi[axis_u], sign_u, p), cells(a_lo.y, a_hi.y, 1.0, p));
    let (bu, bv) = (cells(b_lo[axis_u], b_hi[axis_u], sign_u, p), cells(b_lo.y, b_hi.y, 1.0, p));
    let mut out = vec![0.0; p * p * p * p];
    for (rb, row) in out.chunks_exact_mut(p * p).enumerate() {
        let (ib, jb) = (rb % p, rb / p);
        let area = (bu[ib].1 - bu[ib].0) * (bv[jb].1 - bv[jb].0);
        if area <= 0.0 {
            continue;
        }
        for (ca, weight) in row.iter_mut().enumerate() {
            let (ia, ja) = (ca % p, ca / p);
            *weight = f64::from(overlap(bu[ib], au[ia]) * overlap(bv[jb], av[ja]) / area);
        }
    }
    Some(out)
}

impl PositionOps {
    /// The remap R (k x k, row-major) of position `weights` (P² x P², [`weights`]): the light
    /// at each receiving position is the weighted irradiance of the leaving positions, as
    /// diffuse radiance, R = sum_b sum_a w_ba D_b E_a^T / pi.
    /// The basis keeps only part of a lone position's diffuse light (the rest spreads to its
    /// neighbours or is lost), so R is scaled to pass the irradiance that uniform diffuse light
    /// over the leaving side brings to the receiving side's positions.
    pub fn remap(&self, weights: &[f64]) -> Vec<f64> {
        let (n, k) = (self.positions * self.positions, self.k);
        let mut r = self.diffuse_remap(weights);
        let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
        let mut uniform = vec![0.0; k];
        for a in 0..n {
            uniform.iter_mut().zip(&self.diffuse[a * k..(a + 1) * k]).for_each(|(u, d)| *u += d);
        }
        let (mut wanted, mut got) = (0.0, 0.0);
        let mut passed = vec![0.0; k];
        for (i, row) in r.chunks_exact(k).enumerate() {
            passed[i] = dot(row, &uniform);
        }
        for b in 0..n {
            let e = &self.irradiance[b * k..(b + 1) * k];
            got += dot(e, &passed);
            wanted +=
                (0..n).map(|a| weights[b * n + a] * dot(&self.irradiance[a * k..(a + 1) * k], &uniform)).sum::<f64>();
        }
        if got > 1e-12 && wanted > 0.0 {
            r.iter_mut().for_each(|x| *x *= wanted / got);
        }
        r
    }

    /// R before its scale: sum_b sum_a w_ba D_b E_a^T / pi.
    fn diffuse_remap(&self, weights: &[f64]) -> Vec<f64> {
        let (n, k) = (self.positions * self.positions, self.k);
        let mut r = vec![0.0; k * k];
        for b in 0..n {
            let mut e = vec![0.0; k];
            for (a, w) in weights[b * n..(b + 1) * n].iter().enumerate().filter(|(_, w)| **w > 0.0) {
                e.iter_mut().zip(&self.irradiance[a * k..(a + 1) * k]).for_each(|(e, x)| *e += w * x);
            }
            let d = &self.diffuse[b * k..(b + 1) * k];
            for (row, di) in r.chunks_exact_mut(k).zip(d) {
                row.iter_mut().zip(&e).for_each(|(x, ej)| *x += di * ej / std::f64::consts::PI);
            }
        }
        r
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cells_run_along_the_frames_u_and_overlaps_are_lengths() {
        assert_eq!(cells(0.0, 4.0, 1.0, 2), vec![(0.0, 2.0), (2.0, 4.0)]);
        assert_eq!(cells(0.0, 4.0, -1.0, 2), vec![(2.0, 4.0), (0.0, 2.0)]);
        assert_eq!(overlap((0.0, 2.0), (1.5, 3.0)), 0.5);
        assert_eq!(overlap((0.0, 1.0), (2.0, 3.0)), 0.0);
    }
}
