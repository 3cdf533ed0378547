//! `bouncelab compare CANDIDATE REFERENCE [--heatmap OUT.png] [--exposure EV | --exposure-auto]`:
//! prints RMSE, relMSE, FLIP and the mean-luminance ratio, one per line (and the exposure with
//! `--exposure-auto`), then the same as one JSON line.

use std::path::Path;

use super::quality;
use crate::image_io::{self, read_linear};
use crate::metrics;

/// The exposure FLIP sees the images at.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Exposure {
    /// This many stops (`--exposure`).
    Stops(f32),
    /// The reference's mean luminance at 0.18 (`--exposure-auto`), as `bench --quality` judges
    /// every suite scene, so a held-out scene's FLIP reads on the matrix's scale.
    MatchQuality,
}

/// Compares two images (EXR: linear; PNG: decoded from sRGB) and returns the printed text.
pub fn run(candidate: &Path, reference: &Path, heatmap: Option<&Path>, exposure: Exposure) -> anyhow::Result<String> {
    // NaN compared as "identical" (FLIP 0) before this check.
    if let Exposure::Stops(ev) = exposure
        && !(-32.0..=32.0).contains(&ev)
    {
        anyhow::bail!("--exposure {ev} is outside -32..=32 stops");
    }
    if let Some(path) = heatmap {
        crate::output_path::check(path, crate::output_path::PNG, &[candidate, reference])?;
    }
    let a = read_linear(candidate)?;
    let b = read_linear(reference)?;
    let exposure_ev = match exposure {
        Exposure::Stops(ev) => ev,
        Exposure::MatchQuality => quality::exposure(&b),
    };
    let c = metrics::compare(&a, &b, exposure_ev)?;
    if let Some(path) = heatmap {
        let map = metrics::signed_heatmap(&a, &b, 0.5)?;
        image_io::write_png(path, a.width, a.height, map)?;
    }
    let json = serde_json::to_string(&c)?;
    let auto = match exposure {
        Exposure::MatchQuality => format!("exposure: {exposure_ev:.6}\n"),
        Exposure::Stops(_) => String::new(),
    };
    Ok(format!(
        "rmse: {:.6}\nrelmse: {:.6}\nflip: {:.6}\nluminance_ratio: {:.6}\n{auto}{json}",
        c.rmse, c.relmse, c.flip, c.luminance_ratio
    ))
}
