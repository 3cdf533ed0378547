//! The parameter blocks of MRT's and DRT's precomputes (the dictionary, its interface
//! operators, the delta operators): plain data that the settings hold and the precomputes take,
//! so the settings need nothing from `precompute` (docs/ARCHITECTURE.md, "Layers"). Their
//! precompute-side methods (work estimates, light-field resolutions) live with the precomputes.

use serde::{Deserialize, Serialize};

use super::SettingsError;

/// The dictionary's parameters (in parentheses: Loos 2015's values, §3.6.1 and §4.1). Cost on
/// these two cores, release build: see `bouncelab mrt-dictionary` in docs/BENCHMARKS.md.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct DictionaryParams {
    /// Texels per face side (the dissertation's 16; below 6 its artefacts are objectionable).
    /// Cost: the gather grows with res^2, the SVDs with up to res^4.
    pub res: usize,
    /// Prior columns k_d (64).
    pub k_d: usize,
    /// Indirect modes k_b (32 on desktop, 12 on the iPad).
    pub k_b: usize,
    /// Gather rays per texel (16K in the dissertation; 4K while iterating). Cost: linear.
    pub rays: usize,
    /// Enrichment passes (1). Each costs one more gather.
    pub enrichment: usize,
    /// Seed of the gather's rays.
    pub seed: u64,
    /// The interface operators'.
    pub interfaces: InterfaceParams,
}

impl Default for DictionaryParams {
    fn default() -> Self {
        Self { res: 16, k_d: 64, k_b: 32, rays: 4096, enrichment: 1, seed: 1, interfaces: InterfaceParams::default() }
    }
}

impl DictionaryParams {
    /// Checks ranges.
    pub fn validate(&self) -> Result<(), SettingsError> {
        let i = &self.interfaces;
        let checks: [(&'static str, bool, String, &'static str); 11] = [
            ("res", (2..=32).contains(&self.res), self.res.to_string(), "2..=32"),
            ("k_d", (1..=256).contains(&self.k_d), self.k_d.to_string(), "1..=256"),
            ("k_b", (1..=self.k_d).contains(&self.k_b), self.k_b.to_string(), "1..=k_d"),
            ("rays", (1..=1 << 20).contains(&self.rays), self.rays.to_string(), "1..=1048576"),
            ("enrichment", self.enrichment <= 4, self.enrichment.to_string(), "0..=4"),
            ("interfaces.positions", (2..=32).contains(&i.positions), i.positions.to_string(), "2..=32"),
            ("interfaces.directions", (2..=64).contains(&i.directions), i.directions.to_string(), "2..=64"),
            ("interfaces.supersample", (1..=8).contains(&i.supersample), i.supersample.to_string(), "1..=8"),
            ("interfaces.k_r", (1..=i.k_rlf).contains(&i.k_r), i.k_r.to_string(), "1..=k_rlf"),
            ("interfaces.k_rlf", (1..=512).contains(&i.k_rlf), i.k_rlf.to_string(), "1..=512"),
            ("interfaces.bands", i.bands <= i.positions, i.bands.to_string(), "0..=positions"),
        ];
        match checks.into_iter().find(|c| !c.1) {
            Some((name, _, value, range)) => Err(SettingsError { name, value, range }),
            None => Ok(()),
        }
    }
}

/// The interface operators' parameters (in parentheses: Loos 2015's values, §3.6.1 and §4.2).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct InterfaceParams {
    /// Light-field positions per side of an opening (12).
    pub positions: usize,
    /// Light-field direction cells per side of the concentric square (24).
    pub directions: usize,
    /// Supersamples per side of a direction cell (5).
    pub supersample: usize,
    /// Light-field modes k_rlf (128).
    pub k_rlf: usize,
    /// Surface-response modes k_r (32).
    pub k_r: usize,
    /// Enrichment passes of the light-field basis (the dissertation's 3).
    pub enrichment: usize,
    /// Bands across an opening (along u) whose masked copies of the basis join each enrichment
    /// pass, so that light crossing only part of a side (a doorway in a room's wall) keeps its
    /// place (0: the dissertation's basis, whose fields are smooth across a side). Cost: only
    /// the dictionary build (the enrichment SVDs grow with (4 + bands)^2; 27.1 s at 6, 18.1 s
    /// before bands and the per-position operators, two cores); on the suite's rooms
    /// (`bouncelab probe-mrt rooms --mimic --multi 4`:
    /// the third room 1.12 / 1.06 / 1.04 of a brute force at 4 / 6 / 12 bands).
    pub bands: usize,
}

impl Default for InterfaceParams {
    fn default() -> Self {
        Self { positions: 12, directions: 24, supersample: 5, k_rlf: 128, k_r: 32, enrichment: 3, bands: 6 }
    }
}

/// The delta operators' build parameters (what `DrtSettings::params` gives).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DrtParams {
    /// Rays per block texel (ΔU_b, ΔU_c): the dissertation's 1024.
    pub rays: usize,
    /// Rays per clutter texel (C_b).
    pub gather_rays: usize,
    /// Texels per clutter face side (the dissertation's 16).
    pub clutter_res: usize,
    /// Block texels farther from a clutter box than this many times its radius get no delta
    /// (at 16 radii a box covers under 0.4% of the cosine-weighted hemisphere).
    pub reach: f32,
    /// Texels clutter covers take their neighbours' light (§5.4.2); off, they keep their own
    /// (meaningless) deltas: the comparison of the dissertation's Fig. 5.3.
    pub inpaint: bool,
}

impl Default for DrtParams {
    fn default() -> Self {
        Self { rays: 1024, gather_rays: 256, clutter_res: 16, reach: 16.0, inpaint: true }
    }
}
