//! `bouncelab compare CANDIDATE REFERENCE [--heatmap OUT.png]`: prints RMSE, relMSE, FLIP and the
//! mean-luminance ratio, one per line, then the same as one JSON line.

use std::path::Path;

use crate::image_io::{self, read_linear};
use crate::metrics;

/// Compares two images (EXR: linear; PNG: decoded from sRGB) and returns the printed text.
pub fn run(candidate: &Path, reference: &Path, heatmap: Option<&Path>, exposure_ev: f32) -> anyhow::Result<String> {
    // NaN compared as "identical" (FLIP 0) before this check.
    if !(-32.0..=32.0).contains(&exposure_ev) {
        anyhow::bail!("--exposure {exposure_ev} is outside -32..=32 stops");
    }
    let a = read_linear(candidate)?;
    let b = read_linear(reference)?;
    let c = metrics::compare(&a, &b, exposure_ev)?;
    if let Some(path) = heatmap {
        let map = metrics::signed_heatmap(&a, &b, 0.5)?;
        image_io::write_png(path, a.width, a.height, map)?;
    }
    let json = serde_json::to_string(&c)?;
    Ok(format!(
        "rmse: {:.6}\nrelmse: {:.6}\nflip: {:.6}\nluminance_ratio: {:.6}\n{json}",
        c.rmse, c.relmse, c.flip, c.luminance_ratio
    ))
}
