//! MRT's surface response to light entering a block (Loos 2015 §3.4.1 / §4.2.3, the operators G,
//! U_r and T_{rlf->r}): each basis light field placed on one canonical opening, gathered at the
//! texels of the block's other five faces with the same cosine gather as the blocks' own transfer
//! (a ray leaving through the opening reads the entering light field, quadrilinear, and carries its
//! radiance one bounce onto the wall). G = F_rlf H_rlf (columns scaled by the light-field
//! singular values so the truncation ranks modes by how much they occur), G = U_g S_g V_g^T,
//! truncated to k_r: U_r = U~_g (not scaled, unlike U_b) and, for orthonormal light-field
//! coefficients q, T_{rlf->r} = S~_g V~_g^T S_rlf^-1, so that the walls' indirect light is
//! U_r T_{rlf->r} q. One canonical opening serves every element and side by symmetry; rows of
//! faces that are open in the real receiving element are ignored there.

use faer::Mat;
use glam::Vec3;
use rayon::prelude::*;

use super::basis::BasisError;
use super::gather::{cosine_rays, ray_count};
use super::lightfield::{self, LightFieldRes};
use super::propagate::ENTRY;
use super::shape::{Layout, Shape, exit};
use crate::precompute::rng::Pcg32;

/// The receiving block's response operators.
#[derive(Clone, Debug, PartialEq)]
pub struct Response {
    /// Texels per face side.
    pub res: usize,
    /// Samples of the five faces n_r.
    pub n: usize,
    /// Modes kept k_r.
    pub k_r: usize,
    /// U_r, n x k_r (row-major).
    pub u_r: Vec<f64>,
    /// T_{rlf->r}, k_r x k_rlf (row-major; orthonormal light-field coefficients in).
    pub t_rlf_r: Vec<f64>,
    /// Singular values of G (all of them).
    pub sigma: Vec<f64>,
}

/// The layout of the receiving block: the dead end, whose one opening is the canonical entry.
pub fn layout(res: usize) -> Layout {
    debug_assert!(Shape::DeadEnd.open_faces() == [ENTRY]);
    Layout::new(Shape::DeadEnd, res)
}

/// The one-bounce light on the walls of the receiving block (n x k) from k light fields entering
/// through [`ENTRY`] (`field`, s x k).
pub fn gather_field(res: usize, lf: &LightFieldRes, field: &[f64], k: usize, rays: usize, seed: u64) -> Vec<f64> {
    let layout = layout(res);
    let (eu, ev, en) = lightfield::frame(ENTRY.opposite());
    let centre = ENTRY.point(0.5, 0.5);
    let count = ray_count(rays);
    (0..layout.len())
        .into_par_iter()
        .flat_map_iter(|i| {
            let (_, _, p, normal) = layout.sample(i);
            let mut rng = Pcg32::new(seed, i as u64, 1);
            let mut row = vec![0.0f64; k];
            for dir in cosine_rays(normal, rays, &mut rng) {
                let (face, _, _, dist) = exit(p, dir);
                if face != ENTRY {
                    continue;
                }
                // The light arriving along -dir entered through the opening there.
                let at = p + dir * dist - centre;
                let incoming = -dir;
                let local = Vec3::new(incoming.dot(eu), incoming.dot(ev), incoming.dot(en));
                let q = lightfield::hemisphere_to_square(local);
                for (src, w) in lightfield::taps(lf, (at.dot(eu) + 0.5, at.dot(ev) + 0.5), q) {
                    if w > 0.0 {
                        let from = &field[src * k..(src + 1) * k];
                        row.iter_mut().zip(from).for_each(|(r, f)| *r += f64::from(w) * f);
                    }
                }
            }
            row.iter_mut().for_each(|r| *r /= count);
            row
        })
        .collect()
}

/// Builds the response operators from the orthonormal light-field basis `u` (s x k_rlf) and its
/// singular values `sigma_rlf`.
#[allow(clippy::too_many_arguments)]
pub fn build(
    res: usize,
    lf: &LightFieldRes,
    u: &[f64],
    sigma_rlf: &[f64],
    k_rlf: usize,
    k_r: usize,
    rays: usize,
    seed: u64,
) -> Result<Response, BasisError> {
    let scaled: Vec<f64> =
        u.chunks_exact(k_rlf).flat_map(|row| row.iter().zip(sigma_rlf).map(|(x, s)| x * s)).collect();
    let g = gather_field(res, lf, &scaled, k_rlf, rays, seed);
    let n = g.len() / k_rlf.max(1);
    let m = Mat::<f64>::from_fn(n, k_rlf, |i, j| g[i * k_rlf + j]);
    let d = m.thin_svd().map_err(|_| BasisError::Svd { what: "surface response G", rows: n, cols: k_rlf })?;
    let r = n.min(k_rlf);
    let sigma: Vec<f64> = (0..r).map(|j| d.S()[j]).collect();
    let top = sigma.first().copied().unwrap_or(0.0);
    let k_r = sigma.iter().take(k_r).take_while(|x| **x > 1e-9 * top && **x > 0.0).count();
    let (ug, vg) = (d.U(), d.V());
    let u_r: Vec<f64> = (0..n).flat_map(|i| (0..k_r).map(move |j| ug[(i, j)])).collect();
    let mut t_rlf_r = vec![0.0; k_r * k_rlf];
    for j in 0..k_r {
        for c in 0..k_rlf {
            t_rlf_r[j * k_rlf + c] = sigma[j] * vg[(c, j)] / sigma_rlf[c];
        }
    }
    Ok(Response { res, n, k_r, u_r, t_rlf_r, sigma })
}

impl Response {
    /// The walls' indirect light U_r T_{rlf->r} q for orthonormal light-field coefficients q.
    pub fn walls(&self, q: &[f64]) -> Vec<f64> {
        let k_rlf = q.len();
        let r: Vec<f64> = (0..self.k_r).map(|j| (0..k_rlf).map(|c| self.t_rlf_r[j * k_rlf + c] * q[c]).sum()).collect();
        (0..self.n).map(|i| (0..self.k_r).map(|j| self.u_r[i * self.k_r + j] * r[j]).sum()).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::precompute::mrt::shape::Face;

    #[test]
    fn uniform_light_entering_lights_each_wall_by_its_view_of_the_opening() {
        // Radiance 1 entering from every direction: the floor centre gathers its form factor to
        // the opening, 1 - 0.8093 (the gather test's complement); the back wall (-z) faces it.
        let lf = LightFieldRes { positions: 4, directions: 8, supersample: 1 };
        let walls = gather_field(8, &lf, &vec![1.0; lf.len()], 1, 4096, 7);
        let layout = layout(8);
        let floor = layout.face_start(Face::NegY).expect("floor");
        let centre: f64 =
            [(3, 3), (4, 3), (3, 4), (4, 4)].iter().map(|(s, t)| walls[floor + t * 8 + s]).sum::<f64>() / 4.0;
        assert!((centre - (1.0 - 0.8093)).abs() < 0.01, "floor centre {centre:.4}");
        let back = layout.face_start(Face::NegZ).expect("back wall");
        assert!(walls[back + 3 * 8 + 3] > centre, "the back wall faces the opening");
        assert!(walls.iter().all(|v| (0.0..=1.0).contains(v)));
    }

    #[test]
    fn with_every_mode_kept_the_reduced_response_is_the_gather() {
        // An orthonormal basis of 3 smooth light fields; k_r = 3 keeps all of G.
        let lf = LightFieldRes { positions: 2, directions: 4, supersample: 1 };
        let s = lf.len();
        let raw: Vec<[f64; 3]> = (0..s).map(|i| [1.0, (i % 4) as f64, (i / 16) as f64]).collect();
        // Gram-Schmidt.
        let mut basis: Vec<Vec<f64>> = Vec::new();
        for c in 0..3 {
            let mut v: Vec<f64> = raw.iter().map(|r| r[c]).collect();
            for b in &basis {
                let d: f64 = v.iter().zip(b).map(|(x, y)| x * y).sum();
                v.iter_mut().zip(b).for_each(|(x, y)| *x -= d * y);
            }
            let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
            basis.push(v.iter().map(|x| x / norm).collect());
        }
        let u: Vec<f64> = (0..s).flat_map(|i| basis.iter().map(move |b| b[i])).collect();
        let sigma = [3.0, 2.0, 1.0];
        let response = build(4, &lf, &u, &sigma, 3, 3, 256, 5).expect("response");
        let q = [0.5, -0.2, 0.1];
        let field: Vec<f64> = (0..s).map(|i| (0..3).map(|c| u[i * 3 + c] * q[c]).sum()).collect();
        let direct = gather_field(4, &lf, &field, 1, 256, 5);
        let reduced = response.walls(&q);
        let worst = direct.iter().zip(&reduced).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
        assert!(worst < 1e-9, "worst {worst:.2e}");
    }
}
