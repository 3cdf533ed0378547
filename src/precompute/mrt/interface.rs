//! MRT's reduced light-field basis at block openings (Loos 2015 §3.4.1 / §4.2.1, the basis
//! H_rlf): for every dictionary element and each of its open sides, the light fields that its 32
//! implicit lights (the columns of L_imp) send out through the opening; all of them, each
//! element's columns balanced to equal energy (eq. 4.1), reduced by an SVD to k_rlf modes. The
//! SVD goes through the Gram matrix (c x c, c = 12 openings x k_b columns) in f64, then
//! U~ = H V S^-1; enrichment through the propagation operators follows (App. A). Coefficients are orthonormal (light field ~ U~ q): R_{b->rlf} = U~^T H_lf of the
//! *unscaled* light fields, so that b maps to physical radiance.
//!
//! The propagation (R ahead / left / right) and surface-response (G, U_r, T_{rlf->r}) operators
//! and the level assembly of T_{b->r} build on this basis.

use faer::Mat;

use super::basis::BasisError;
use super::basis::Element;
use super::lightfield::{self, LightFieldRes};
use super::propagate;
use super::shape::{Face, Layout, Shape};

/// One element's operator from b to the light field leaving one of its openings.
#[derive(Clone, Debug, PartialEq)]
pub struct Exit {
    /// The element.
    pub shape: Shape,
    /// The open side.
    pub face: Face,
    /// R_{b->rlf}, k_rlf x k_b (row-major).
    pub r_b_rlf: Vec<f64>,
}

/// The reduced light-field basis and each opening's R_{b->rlf}.
#[derive(Clone, Debug, PartialEq)]
pub struct InterfaceBasis {
    /// Light-field resolution.
    pub res: LightFieldRes,
    /// Samples per light field s.
    pub s: usize,
    /// Modes kept k_rlf.
    pub k_rlf: usize,
    /// U~, s x k_rlf (row-major, orthonormal columns).
    pub u: Vec<f64>,
    /// Singular values of the balanced concatenation (all of them).
    pub sigma: Vec<f64>,
    /// Every element's openings.
    pub exits: Vec<Exit>,
}

impl InterfaceBasis {
    /// The exit operator of `shape`'s open side `face`.
    pub fn exit(&self, shape: Shape, face: Face) -> Option<&Exit> {
        self.exits.iter().find(|e| e.shape == shape && e.face == face)
    }

    /// The light field U~ q of coefficients q (s).
    pub fn light_field(&self, q: &[f64]) -> Vec<f64> {
        (0..self.s).map(|i| (0..self.k_rlf).map(|j| self.u[i * self.k_rlf + j] * q[j]).sum()).collect()
    }
}

/// An orthonormal basis of the column space of `h` (s x c) through its Gram matrix: U~ (s x k,
/// row-major) and all singular values. Modes below 1e-4 of the first are dropped: through the
/// Gram matrix an eigenvector of relative singular value x carries an error of about
/// 1e-16 / x^2 (those modes hold under 1e-8 of the energy).
fn reduce(h: &Mat<f64>, k_max: usize) -> Result<(Vec<f64>, Vec<f64>, usize), BasisError> {
    let (s, cols) = (h.nrows(), h.ncols());
    let gram = h.transpose() * h;
    let d = gram.thin_svd().map_err(|_| BasisError::Svd { what: "light-field Gram matrix", rows: cols, cols })?;
    let sigma: Vec<f64> = (0..cols).map(|j| d.S()[j].max(0.0).sqrt()).collect();
    let top = sigma.first().copied().unwrap_or(0.0);
    let k = sigma.iter().take(k_max).take_while(|x| **x > 1e-4 * top && **x > 0.0).count();
    let hv = h * d.V().subcols(0, k);
    let u = (0..s).flat_map(|i| (0..k).map(move |j| (i, j))).map(|(i, j)| hv[(i, j)] / sigma[j]).collect();
    Ok((u, sigma, k))
}

/// Side by side, each block scaled to unit Frobenius norm (App. A's balancing).
fn balanced(blocks: &[(&[f64], usize)], s: usize) -> Mat<f64> {
    let norms: Vec<f64> = blocks.iter().map(|(a, _)| a.iter().map(|x| x * x).sum::<f64>().sqrt().max(1e-300)).collect();
    let cols: usize = blocks.iter().map(|b| b.1).sum();
    Mat::<f64>::from_fn(s, cols, |i, c| {
        let mut c = c;
        for ((a, k), norm) in blocks.iter().zip(&norms) {
            if c < *k {
                return a[i * k + c] / norm;
            }
            c -= k;
        }
        0.0
    })
}

/// Builds the basis from `dictionary`'s implicit lights, keeping `k_rlf` modes (128 in the
/// dissertation), then enriches it `enrichment` times (Loos 2015 App. A; the dissertation's 3,
/// §3.6.1): the basis light fields H_rlf = U~ S pushed through the propagation operators (ahead,
/// left, right) join H_rlf, balanced, and a new basis of k_rlf modes is taken, so that light
/// carried one more block stays in span. With `bands` > 0 each pass also adds H_rlf masked to each
/// of `bands` bands across the opening (along u): light that crosses a side only at a doorway
/// ([`super::opening`]) then keeps its place instead of spreading over the side.
pub fn build(
    elements: &[Element],
    res: &LightFieldRes,
    k_rlf: usize,
    enrichment: usize,
    bands: usize,
) -> Result<InterfaceBasis, BasisError> {
    let s = res.len();
    // Each opening's light fields, s x k_b, and the element balancing of eq. 4.1.
    let mut fields: Vec<(Shape, Face, usize, Vec<f64>)> = Vec::new();
    for e in elements.iter().filter(|e| !e.shape.open_faces().is_empty()) {
        let layout = Layout::new(e.shape, e.res);
        for &face in e.shape.open_faces() {
            fields.push((e.shape, face, e.k_b, lightfield::trace(&layout, face, &e.l_imp, e.k_b, res)));
        }
    }
    let sums: Vec<(Shape, f64)> = elements
        .iter()
        .filter(|e| !e.shape.open_faces().is_empty())
        .map(|e| (e.shape, e.m_sigma.iter().map(|x| x * x).sum::<f64>()))
        .collect();
    let total: f64 = sums.iter().map(|x| x.1).sum();
    let scale = |shape: Shape| {
        let sum = sums.iter().find(|x| x.0 == shape).map_or(1.0, |x| x.1);
        (total / (sum * sums.len() as f64)).max(0.0).sqrt()
    };
    let cols: usize = fields.iter().map(|f| f.2).sum();
    let h = Mat::<f64>::from_fn(s, cols, |i, c| {
        let mut c = c;
        for (shape, _, k, data) in &fields {
            if c < *k {
                return data[i * k + c] * scale(*shape);
            }
            c -= k;
        }
        0.0
    });
    let (mut u, mut sigma, mut k) = reduce(&h, k_rlf)?;
    for _ in 0..enrichment {
        let scaled: Vec<f64> =
            u.chunks_exact(k.max(1)).flat_map(|row| row.iter().zip(&sigma).map(|(x, sg)| x * sg)).collect();
        let pushed: Vec<Vec<f64>> =
            propagate::Turn::ALL.iter().map(|&turn| propagate::resample(res, turn, &scaled, k)).collect();
        let per_position = res.directions * res.directions;
        let masked: Vec<Vec<f64>> = (0..bands)
            .map(|band| {
                let mut m = scaled.clone();
                for (row, x) in m.chunks_exact_mut(k.max(1)).enumerate() {
                    let i = (row / per_position) % res.positions;
                    if i * bands / res.positions != band {
                        x.iter_mut().for_each(|v| *v = 0.0);
                    }
                }
                m
            })
            .collect();
        let mut blocks: Vec<(&[f64], usize)> = vec![(&scaled, k)];
        blocks.extend(pushed.iter().map(|p| (p.as_slice(), k)));
        blocks.extend(masked.iter().map(|p| (p.as_slice(), k)));
        (u, sigma, k) = reduce(&balanced(&blocks, s), k_rlf)?;
    }
    let k_rlf = k;
    // R_{b->rlf} = U~^T H (unscaled).
    let exits = fields
        .iter()
        .map(|(shape, face, k, data)| {
            let mut r = vec![0.0; k_rlf * k];
            for i in 0..s {
                for m in 0..k_rlf {
                    let um = u[i * k_rlf + m];
                    if um != 0.0 {
                        for b in 0..*k {
                            r[m * k + b] += um * data[i * k + b];
                        }
                    }
                }
            }
            Exit { shape: *shape, face: *face, r_b_rlf: r }
        })
        .collect();
    Ok(InterfaceBasis { res: *res, s, k_rlf, u, sigma, exits })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::precompute::mrt::dictionary::{DictionaryParams, Progress};
    use crate::precompute::mrt::operators::InterfaceParams;

    #[test]
    fn the_basis_is_orthonormal_and_carries_each_openings_light_fields() {
        let interfaces =
            InterfaceParams { positions: 2, directions: 2, supersample: 1, k_rlf: 8, k_r: 4, enrichment: 0, bands: 0 };
        let params = DictionaryParams { res: 3, k_d: 16, k_b: 6, rays: 64, enrichment: 1, seed: 3, interfaces };
        let dictionary = crate::precompute::mrt::dictionary::build(&params, &Progress::default()).expect("dictionary");
        let res = LightFieldRes { positions: 3, directions: 4, supersample: 2 };
        let basis = build(&dictionary.elements, &res, 128, 0, 0).expect("basis");
        assert_eq!(basis.exits.len(), 12, "every open side of the dictionary");
        // Orthonormal columns.
        for a in 0..basis.k_rlf {
            for b in 0..basis.k_rlf {
                let dot: f64 = (0..basis.s).map(|i| basis.u[i * basis.k_rlf + a] * basis.u[i * basis.k_rlf + b]).sum();
                let want = if a == b { 1.0 } else { 0.0 };
                // Through the Gram matrix the condition number is squared: 1e-6.
                assert!((dot - want).abs() < 1e-6, "U^T U [{a}][{b}] = {dot}");
            }
        }
        // With every mode above 1e-4 of the first kept, U~ R_{b->rlf} b reproduces the traced
        // light field of L_imp b to 1e-3 of its largest value.
        let element = dictionary.element(Shape::Corridor).expect("corridor");
        let exit = basis.exit(Shape::Corridor, Face::PosZ).expect("exit");
        let b: Vec<f64> = (0..element.k_b).map(|j| 1.0 / (1.0 + j as f64)).collect();
        let q: Vec<f64> = (0..basis.k_rlf)
            .map(|m| (0..element.k_b).map(|j| exit.r_b_rlf[m * element.k_b + j] * b[j]).sum())
            .collect();
        let walls: Vec<f64> =
            (0..element.n).map(|i| (0..element.k_b).map(|j| element.l_imp[i * element.k_b + j] * b[j]).sum()).collect();
        let layout = Layout::new(Shape::Corridor, params.res);
        let traced = lightfield::trace(&layout, Face::PosZ, &walls, 1, &res);
        let rebuilt = basis.light_field(&q);
        let scale = traced.iter().map(|x| x.abs()).fold(0.0, f64::max);
        let worst = traced.iter().zip(&rebuilt).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
        assert!(worst < 1e-3 * scale.max(1e-12), "worst {worst:.3e} of {scale:.3e}");
    }
}
