//! MRT's inspector images built on the CPU: the per-texel atlas (one row of six face tiles per
//! block), the reduced coefficients, the dictionary's U_b and T_{d->b} as images (as Loos 2015
//! Figs. 4.10 and 4.3 show them), its singular-value spectra as a bar plot (to hold against
//! Table 3.2), and the prior's reconstruction error of this frame's direct light.

use super::pack::{NONE, Packed};
use crate::image_io::HdrImage;
use crate::precompute::mrt::basis::Element;
use crate::precompute::mrt::dictionary::Dictionary;
use crate::precompute::mrt::level::Block;

/// Lays per-texel `values` out as the atlas: one row of six tiles (canonical faces -x +x -y +y
/// -z +z) per block, each `res` x `res` with t up; open faces black.
pub fn atlas(p: &Packed, values: &[[f32; 4]]) -> HdrImage {
    let res = p.res as usize;
    let (width, height) = (6 * res, p.blocks.len() * res);
    let mut pixels = vec![[0.0, 0.0, 0.0, 1.0]; width * height];
    for (bi, b) in p.blocks.iter().enumerate() {
        for (k, start) in b.starts.iter().take(6).enumerate() {
            if *start == NONE {
                continue;
            }
            for t in 0..res {
                for s in 0..res {
                    let Some(v) = values.get(*start as usize + t * res + s) else { continue };
                    let (x, y) = (k * res + s, bi * res + (res - 1 - t));
                    pixels[y * width + x] = [v[0], v[1], v[2], 1.0];
                }
            }
        }
    }
    HdrImage { width: width.max(1) as u32, height: height.max(1) as u32, pixels }
}

/// Per-clutter-texel `values` as one row of six face tiles (-x +x -y +y -z +z of its box, t
/// up) per clutter object.
pub fn clutter_tiles(d: &super::drt_pack::DrtPacked, values: &[[f32; 4]]) -> HdrImage {
    let res = d.clutter.first().map_or(1, |c| c.texels[1] as usize).max(1);
    let (width, height) = (6 * res, d.clutter.len().max(1) * res);
    let mut pixels = vec![[0.0, 0.0, 0.0, 1.0]; width * height];
    for (ci, c) in d.clutter.iter().enumerate() {
        for face in 0..6 {
            for t in 0..res {
                for s in 0..res {
                    let at = c.texels[0] as usize + (face * res + t) * res + s;
                    let Some(v) = values.get(at) else { continue };
                    pixels[(ci * res + res - 1 - t) * width + face * res + s] = [v[0], v[1], v[2], 1.0];
                }
            }
        }
    }
    HdrImage { width: width as u32, height: height as u32, pixels }
}

/// The side texels `values` of every partly open side as P x P tiles side by side (u across,
/// up up).
pub fn side_tiles(p: &Packed, values: &[[f32; 4]]) -> HdrImage {
    let n = p.positions as usize;
    let width = (n * p.sides.len()).max(1);
    let height = n.max(1);
    let mut pixels = vec![[0.0, 0.0, 0.0, 1.0]; width * height];
    for k in 0..p.sides.len() {
        for j in 0..n {
            for i in 0..n {
                let Some(v) = values.get(k * n * n + j * n + i) else { continue };
                pixels[(n - 1 - j) * width + k * n + i] = [v[0], v[1], v[2], 1.0];
            }
        }
    }
    HdrImage { width: width as u32, height: height as u32, pixels }
}

/// `rows` rows of `cols` values.
pub fn coefficients(values: &[[f32; 4]], rows: usize, cols: usize) -> HdrImage {
    let pixels =
        (0..rows * cols).map(|i| values.get(i).map_or([0.0, 0.0, 0.0, 1.0], |v| [v[0], v[1], v[2], 1.0])).collect();
    HdrImage { width: cols.max(1) as u32, height: rows.max(1) as u32, pixels }
}

/// Each element's `n x k_b` matrix (`U_b`, or `T_{d->b}` transposed) side by side, one column
/// block per shape with a one-pixel gap: positive values red, negative blue, each mode's column
/// scaled to its largest magnitude (so every mode's pattern shows, the first smooth, later ones
/// oscillating).
pub fn matrices(dictionary: &Dictionary, transposed_t_db: bool) -> HdrImage {
    let elements = &dictionary.elements;
    let k = elements.iter().map(|e| e.k_b).max().unwrap_or(1);
    let n = elements.iter().map(|e| e.n).max().unwrap_or(1);
    let width = elements.len() * (k + 1);
    let mut pixels = vec![[0.0, 0.0, 0.0, 1.0]; width * n];
    for (ei, e) in elements.iter().enumerate() {
        let at = |i: usize, j: usize| if transposed_t_db { e.t_db[j * e.n + i] } else { e.u_b[i * e.k_b + j] };
        for j in 0..e.k_b {
            let scale = (0..e.n).map(|i| at(i, j).abs()).fold(0.0, f64::max).max(1e-30);
            for i in 0..e.n {
                let v = (at(i, j) / scale) as f32;
                pixels[i * width + ei * (k + 1) + j] = [v.max(0.0), 0.0, (-v).max(0.0), 1.0];
            }
        }
    }
    HdrImage { width: width.max(1) as u32, height: n.max(1) as u32, pixels }
}

/// Height of one shape's panel in [`spectra`].
const PANEL: usize = 48;

/// The singular values per shape (a panel each, top to bottom in dictionary order), as bars on a
/// log scale over four decades from the first: red the direct light's (the prior's training
/// data), green the indirect transfer's (M = F P S). The indirect spectrum falls much faster,
/// which is why 32 modes carry it.
pub fn spectra(dictionary: &Dictionary) -> HdrImage {
    let modes = dictionary.elements.iter().map(|e| e.data_sigma.len().max(e.m_sigma.len())).max().unwrap_or(1).min(128);
    let width = 2 * modes;
    let height = dictionary.elements.len() * (PANEL + 2);
    let mut pixels = vec![[0.0, 0.0, 0.0, 1.0]; width * height.max(1)];
    let bar = |sigma: &[f64], k: usize| {
        let first = sigma.first().copied().unwrap_or(0.0).max(1e-30);
        let v = sigma.get(k).copied().unwrap_or(0.0).max(1e-30);
        ((1.0 + (v / first).log10() / 4.0).clamp(0.0, 1.0) * PANEL as f64) as usize
    };
    for (ei, e) in dictionary.elements.iter().enumerate() {
        let bottom = ei * (PANEL + 2) + PANEL;
        for k in 0..modes {
            for (channel, sigma) in [(0, &e.data_sigma), (1, &e.m_sigma)] {
                for h in 0..bar(sigma, k) {
                    pixels[(bottom - h) * width + 2 * k + channel][channel] = 1.0;
                }
            }
        }
    }
    HdrImage { width: width.max(1) as u32, height: height.max(1) as u32, pixels }
}

/// An orthonormal basis (columns, row-major n x r) of the span of `m`'s columns (n x k),
/// by modified Gram-Schmidt.
fn orthonormal(m: &[f64], n: usize, k: usize) -> Vec<Vec<f64>> {
    let mut basis: Vec<Vec<f64>> = Vec::new();
    for j in 0..k {
        let mut v: Vec<f64> = (0..n).map(|i| m[i * k + j]).collect();
        for q in &basis {
            let d: f64 = v.iter().zip(q).map(|(a, b)| a * b).sum();
            v.iter_mut().zip(q).for_each(|(a, b)| *a -= d * b);
        }
        let norm = v.iter().map(|a| a * a).sum::<f64>().sqrt();
        if norm > 1e-9 {
            v.iter_mut().for_each(|a| *a /= norm);
            basis.push(v);
        }
    }
    basis
}

/// Per texel, the part of this frame's direct light `l_d` (rgb) that the block's prior cannot
/// represent: |l_d - Q Q^T l_d| per channel, Q an orthonormal basis of the prior P S. Large
/// where the light has detail the dictionary's training lights lack (a sharp shadow edge).
pub fn prior_error(dictionary: &Dictionary, p: &Packed, blocks: &[Block], l_d: &[[f32; 4]]) -> Vec<[f32; 4]> {
    let mut out = vec![[0.0, 0.0, 0.0, 1.0]; l_d.len()];
    let mut bases: Vec<(crate::precompute::mrt::shape::Shape, Vec<Vec<f64>>)> = Vec::new();
    for (b, g) in blocks.iter().zip(&p.blocks) {
        let Some(e): Option<&Element> = dictionary.element(b.shape) else { continue };
        if !bases.iter().any(|(s, _)| *s == b.shape) {
            bases.push((b.shape, orthonormal(&e.prior, e.n, e.prior.len() / e.n.max(1))));
        }
        let Some((_, q)) = bases.iter().find(|(s, _)| *s == b.shape) else { continue };
        let first = g.texels[0] as usize;
        for c in 0..3 {
            let l: Vec<f64> = (0..e.n).map(|i| f64::from(l_d.get(first + i).map_or(0.0, |v| v[c]))).collect();
            let mut rest = l.clone();
            for col in q {
                let d: f64 = l.iter().zip(col).map(|(a, b)| a * b).sum();
                rest.iter_mut().zip(col).for_each(|(r, b)| *r -= d * b);
            }
            for (i, r) in rest.iter().enumerate() {
                if let Some(o) = out.get_mut(first + i) {
                    o[c] = r.abs() as f32;
                }
            }
        }
    }
    out
}
