//! One dictionary element's reduced direct-to-indirect transfer (Loos 2015 §3.3 and §3.3.1,
//! eqs. 3.2-3.3, built per element as in §4.1): the light prior P S from the SVD of the training
//! lights' direct light (no mean subtracted: an SVD, not PCA), the light-space indirect operator
//! M = F P S and its SVD, truncated to k_b modes: the indirect basis U_b = U~ S~ (scaled columns),
//! the projection T_{d->b} = V~^T S^-1 P^T and the implicit lights L_imp = P S V~ (kept for DRT).
//! Enrichment (App. A) re-derives the prior from the balanced concatenation
//! [P S | face constants | U_b] so that single-coloured faces, shadows the prior never saw and
//! multi-bounce feedback stay in span.
//!
//! Matrices are row-major `Vec<f64>`: element (i, j) of an r x c matrix at `i * c + j`.

use faer::Mat;
use thiserror::Error;

use super::dictionary::DictionaryParams;
use super::gather;
use super::prior;
use super::shape::{Layout, Shape};

/// What can stop an element's precompute.
#[derive(Debug, Error)]
pub enum BasisError {
    /// The SVD did not converge.
    #[error("the SVD of the {what} ({rows}x{cols}) did not converge")]
    Svd { what: &'static str, rows: usize, cols: usize },
    /// The user cancelled.
    #[error("cancelled")]
    Cancelled,
}

/// One dictionary element's operators.
#[derive(Clone, Debug, PartialEq)]
pub struct Element {
    /// The shape.
    pub shape: Shape,
    /// Texels per face side.
    pub res: usize,
    /// Samples n.
    pub n: usize,
    /// Prior columns kept (k_d, or fewer where the data has fewer independent patterns).
    pub k_d: usize,
    /// Indirect modes kept (k_b, at most k_d).
    pub k_b: usize,
    /// The scaled prior P S, n x k_d (after enrichment).
    pub prior: Vec<f64>,
    /// S, k_d.
    pub prior_sigma: Vec<f64>,
    /// Singular values of the training lights' direct light L_d (the prior's spectrum, before
    /// enrichment: the inspector's plot and the check against Loos 2015 Table 3.2).
    pub data_sigma: Vec<f64>,
    /// Singular values of M = F P S (all of them: the indirect spectrum).
    pub m_sigma: Vec<f64>,
    /// U_b, n x k_b.
    pub u_b: Vec<f64>,
    /// T_{d->b}, k_b x n.
    pub t_db: Vec<f64>,
    /// L_imp, n x k_b.
    pub l_imp: Vec<f64>,
}

/// A thin SVD: U (rows x r, row-major), singular values (r, descending), V (cols x r).
struct Svd {
    u: Vec<f64>,
    s: Vec<f64>,
    v: Vec<f64>,
    r: usize,
}

fn svd(a: &[f64], rows: usize, cols: usize, what: &'static str) -> Result<Svd, BasisError> {
    let m = Mat::<f64>::from_fn(rows, cols, |i, j| a[i * cols + j]);
    let d = m.thin_svd().map_err(|_| BasisError::Svd { what, rows, cols })?;
    let r = rows.min(cols);
    let (u, s, v) = (d.U(), d.S(), d.V());
    Ok(Svd {
        u: (0..rows).flat_map(|i| (0..r).map(move |j| u[(i, j)])).collect(),
        s: (0..r).map(|j| s[j]).collect(),
        v: (0..cols).flat_map(|i| (0..r).map(move |j| v[(i, j)])).collect(),
        r,
    })
}

/// The number of leading singular values above `1e-9` of the largest (directions the data really
/// spans; dividing by the others would blow noise up).
fn rank(s: &[f64], cap: usize) -> usize {
    let top = s.first().copied().unwrap_or(0.0);
    s.iter().take(cap).take_while(|&&x| x > 1e-9 * top && x > 0.0).count()
}

/// The first `k` columns of a row-major rows x r matrix, scaled by `scale[j]`.
fn columns(a: &[f64], rows: usize, r: usize, k: usize, scale: &[f64]) -> Vec<f64> {
    (0..rows).flat_map(|i| (0..k).map(move |j| a[i * r + j] * scale[j])).collect()
}

/// The training lights' direct light L_d, n x m.
fn training_matrix(layout: &Layout) -> (Vec<f64>, usize) {
    let lights = prior::light_positions(layout);
    let m = lights.len();
    let n = layout.len();
    let mut l = vec![0.0; n * m];
    for i in 0..n {
        for (j, light) in lights.iter().enumerate() {
            l[i * m + j] = f64::from(prior::direct(layout, i, *light));
        }
    }
    (l, m)
}

/// The reduced operators of prior (P orthonormal columns, S) through the gather.
struct Reduced {
    m_sigma: Vec<f64>,
    k_b: usize,
    u_b: Vec<f64>,
    t_db: Vec<f64>,
    l_imp: Vec<f64>,
}

fn reduce(
    layout: &Layout,
    p: &[f64],
    s: &[f64],
    params: &DictionaryParams,
    cancel: &(dyn Fn() -> bool + Sync),
) -> Result<Reduced, BasisError> {
    let n = layout.len();
    let k_d = s.len();
    let ps = columns(p, n, k_d, k_d, s);
    let m = gather::apply(layout, &ps, k_d, params.rays, params.seed, cancel).ok_or(BasisError::Cancelled)?;
    let d = svd(&m, n, k_d, "light-space indirect operator M = F P S")?;
    let k_b = rank(&d.s, params.k_b.min(k_d));
    let u_b = columns(&d.u, n, d.r, k_b, &d.s);
    // T_{d->b}[j][i] = sum_c V[c][j] / S[c] P[i][c].
    let mut t_db = vec![0.0; k_b * n];
    for j in 0..k_b {
        for i in 0..n {
            t_db[j * n + i] = (0..k_d).map(|c| d.v[c * d.r + j] / s[c] * p[i * k_d + c]).sum();
        }
    }
    // L_imp[i][j] = sum_c (P S)[i][c] V[c][j].
    let mut l_imp = vec![0.0; n * k_b];
    for i in 0..n {
        for j in 0..k_b {
            l_imp[i * k_b + j] = (0..k_d).map(|c| ps[i * k_d + c] * d.v[c * d.r + j]).sum();
        }
    }
    Ok(Reduced { m_sigma: d.s, k_b, u_b, t_db, l_imp })
}

/// Balanced concatenation (App. A): each block scaled to unit Frobenius norm, side by side.
fn balanced(blocks: &[(&[f64], usize)], n: usize) -> (Vec<f64>, usize) {
    let cols: usize = blocks.iter().map(|b| b.1).sum();
    let mut out = vec![0.0; n * cols];
    let mut at = 0;
    for (a, k) in blocks {
        let norm = a.iter().map(|x| x * x).sum::<f64>().sqrt().max(1e-300);
        for i in 0..n {
            for j in 0..*k {
                out[i * cols + at + j] = a[i * k + j] / norm;
            }
        }
        at += k;
    }
    (out, cols)
}

/// Precomputes one element. `cancel` is polled once per sample of each gather.
pub fn build(
    shape: Shape,
    params: &DictionaryParams,
    cancel: &(dyn Fn() -> bool + Sync),
) -> Result<Element, BasisError> {
    let layout = Layout::new(shape, params.res);
    let n = layout.len();
    let (l_d, m) = training_matrix(&layout);
    let data = svd(&l_d, n, m, "training lights' direct light L_d")?;
    let mut k_d = rank(&data.s, params.k_d);
    let mut p = columns(&data.u, n, data.r, k_d, &vec![1.0; k_d]);
    let mut s = data.s[..k_d].to_vec();
    let mut reduced = reduce(&layout, &p, &s, params, cancel)?;
    let faces = layout.faces.len();
    let per_face = params.res * params.res;
    let indicators: Vec<f64> =
        (0..n).flat_map(|i| (0..faces).map(move |f| if i / per_face == f { 1.0 } else { 0.0 })).collect();
    for _ in 0..params.enrichment {
        let ps = columns(&p, n, k_d, k_d, &s);
        let (a, cols) = balanced(&[(&ps, k_d), (&indicators, faces), (&reduced.u_b, reduced.k_b)], n);
        let e = svd(&a, n, cols, "enrichment concatenation")?;
        k_d = rank(&e.s, params.k_d);
        p = columns(&e.u, n, e.r, k_d, &vec![1.0; k_d]);
        s = e.s[..k_d].to_vec();
        reduced = reduce(&layout, &p, &s, params, cancel)?;
    }
    let prior = columns(&p, n, k_d, k_d, &s);
    Ok(Element {
        shape,
        res: params.res,
        n,
        k_d,
        k_b: reduced.k_b,
        prior,
        prior_sigma: s,
        data_sigma: data.s,
        m_sigma: reduced.m_sigma,
        u_b: reduced.u_b,
        t_db: reduced.t_db,
        l_imp: reduced.l_imp,
    })
}

impl Element {
    /// b = T_{d->b} l_d for direct light `l_d` (n).
    pub fn project(&self, l_d: &[f64]) -> Vec<f64> {
        (0..self.k_b).map(|j| (0..self.n).map(|i| self.t_db[j * self.n + i] * l_d[i]).sum()).collect()
    }

    /// The indirect light U_b b (n).
    pub fn reconstruct(&self, b: &[f64]) -> Vec<f64> {
        (0..self.n).map(|i| (0..self.k_b).map(|j| self.u_b[i * self.k_b + j] * b[j]).sum()).collect()
    }

    /// The share of M's energy (sum of squared singular values) in the first `k` modes.
    pub fn energy_in(&self, k: usize) -> f64 {
        let total: f64 = self.m_sigma.iter().map(|s| s * s).sum();
        self.m_sigma.iter().take(k).map(|s| s * s).sum::<f64>() / total.max(1e-300)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Small enough for a debug-build test: 4x4 texels per face.
    fn small() -> DictionaryParams {
        DictionaryParams { res: 4, k_d: 32, k_b: 16, rays: 256, enrichment: 1, seed: 11, ..Default::default() }
    }

    #[test]
    fn projecting_the_implicit_lights_gives_the_unit_coefficients() {
        // L_imp = P S V~ (Loos 2015 §3.3.1.1), so T_{d->b} L_imp = V~^T S^-1 P^T P S V~ = I.
        let e = build(Shape::Corner, &small(), &|| false).expect("element");
        for j in 0..e.k_b {
            let column: Vec<f64> = (0..e.n).map(|i| e.l_imp[i * e.k_b + j]).collect();
            let b = e.project(&column);
            for (c, v) in b.iter().enumerate() {
                let want = if c == j { 1.0 } else { 0.0 };
                assert!((v - want).abs() < 1e-8, "T L_imp [{c}][{j}] = {v}");
            }
        }
    }

    #[test]
    fn a_closed_cube_under_uniform_light_reflects_it_all_through_the_reduced_basis() {
        // The furnace test: l_d = 1 on every wall gathers to exactly 1 (every ray hits a wall);
        // the face constants of the enrichment put it in the prior's span, and 16 modes carry it.
        let e = build(Shape::Closed, &small(), &|| false).expect("element");
        let ind = e.reconstruct(&e.project(&vec![1.0; e.n]));
        let worst = ind.iter().map(|v| (v - 1.0).abs()).fold(0.0, f64::max);
        eprintln!("furnace: worst deviation {worst:.2e} with {} modes", e.k_b);
        assert!(
            worst < 0.02,
            "uniform light reflects to {:.4}..{:.4}",
            ind.iter().copied().fold(f64::MAX, f64::min),
            ind.iter().copied().fold(f64::MIN, f64::max)
        );
    }

    #[test]
    fn the_indirect_spectrum_falls_much_faster_than_the_direct_one() {
        // Digest Table 3.2: a handful of M's modes hold most of its energy.
        let e = build(Shape::Closed, &small(), &|| false).expect("element");
        let data_total: f64 = e.data_sigma.iter().map(|s| s * s).sum();
        let data_8: f64 = e.data_sigma.iter().take(8).map(|s| s * s).sum::<f64>() / data_total;
        eprintln!(
            "energy in 1 / 5 / 8 modes: M {:.3} {:.3} {:.3}, L_d 8: {data_8:.3}",
            e.energy_in(1),
            e.energy_in(5),
            e.energy_in(8)
        );
        assert!(e.energy_in(8) > 0.95, "M's first 8 modes hold {:.3}", e.energy_in(8));
        assert!(e.energy_in(8) > data_8, "M {:.3} vs the prior's {data_8:.3}", e.energy_in(8));
    }

    #[test]
    fn indirect_light_is_linear_in_the_direct_light() {
        let e = build(Shape::DeadEnd, &small(), &|| false).expect("element");
        let layout = Layout::new(Shape::DeadEnd, 4);
        let l: Vec<f64> =
            (0..e.n).map(|i| f64::from(prior::direct(&layout, i, glam::Vec3::new(0.3, 0.7, 0.4)))).collect();
        let twice: Vec<f64> = l.iter().map(|x| 2.0 * x).collect();
        let (a, b) = (e.reconstruct(&e.project(&l)), e.reconstruct(&e.project(&twice)));
        assert!(a.iter().zip(&b).all(|(x, y)| (2.0 * x - y).abs() < 1e-9 * (1.0 + y.abs())));
        assert!(a.iter().sum::<f64>() > 0.0, "a light inside bounces light");
    }
}
