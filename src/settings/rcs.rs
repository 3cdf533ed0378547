//! Settings of `rcs`, GPU irradiance caching by radiance cache splatting (Gautron et al. 2005, as
//! Gautron's SIGGRAPH 2007 course notes give it), and their ranges. The notes give no values for
//! `a` or the hemisphere resolution; the defaults are ours (a Radiance-style accuracy, and 32x32
//! planes, cheaper than 64x64), with the costs `bouncelab bench` measures.

use serde::{Deserialize, Serialize};

use super::SettingsError;

/// Settings of the `rcs` technique.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RcsSettings {
    /// Accuracy a of Ward's weight: a record reaches every point within a x R of it (R its
    /// harmonic mean distance) and contributes where w > 1 / a. Smaller: more records, each
    /// computed by rendering the scene once (1 / a^2 where zones are not clamped). Measured
    /// (`bouncelab bench`, default project at 640x360, llvmpipe): a = 0.5 / 0.25 / 0.125 made
    /// 2048 / 2784 / 3924 records (far from 1 / a^2: the gradient limit and the pixel clamp
    /// bound many zones there), FLIP 0.080 / 0.078 / 0.077, and a warm frame of 15.3 / 5.6 /
    /// 3.8 x `direct`, almost all of it the splat (larger zones overlap more).
    pub accuracy: f32,
    /// Pixels per side of each record's hemisphere plane (tan of the half aperture 2, 126.87
    /// degrees, with the border compensation for the rest). Cost: the record's render and its
    /// reduction grow with the square.
    pub hemisphere_resolution: u32,
    /// Records the cache may hold; beyond it uncovered pixels stay without indirect light
    /// (the coverage buffer shows them). Memory: 160 bytes each plus the bounce lookup grid.
    pub max_records: u32,
    /// New or renewed records computed per frame: the editor stays interactive while the cache
    /// fills (the viewport shows the fill progressing). Each costs one render of the scene. At
    /// 2048 the default project (640x360, llvmpipe) was covered after 1.9 s (3 frames) and its
    /// bounce passes converged after 8.3 s (9 frames).
    pub records_per_frame: u32,
    /// Placement rounds per frame: compute records at the uncovered pixels (one candidate per
    /// 8x8 tile) the last readback found, splat them, find the pixels still uncovered, repeat.
    /// The first round takes the readback the frame before issued, without waiting; each
    /// further round waits for the GPU once (a faster fill, a slower frame). Default 1: no
    /// frame waits for the GPU.
    pub rounds: u32,
    /// Interpolate with Ward's rotational and translational gradients (on: the notes' final
    /// quality; off: flat records, disc-shaped blotches).
    pub gradients: bool,
    /// Most bounces: 1 lights the hemispheres with the shadowed direct light only; each
    /// further bounce is a pass renewing every record in place with the cache's own irradiance
    /// added at the surfaces its hemisphere sees (and records made where no record reaches).
    /// Passes stop earlier once they converge. Cost: each pass recomputes every record (the
    /// records-per-frame budget is shared with new records); light through two doorways needs
    /// about 12.
    pub bounces: u32,
    /// The bounce passes stop when one changes the records' luminance by less than this
    /// fraction on average (each record relative to its own).
    pub convergence: f32,
    /// Smallest zone of influence a x R on screen when a record is made, in pixels (Tabellion
    /// and Lamorlette's clamp): keeps creases from getting a record per pixel.
    pub min_zone_pixels: f32,
    /// Largest zone of influence a x R on screen when a record is made, in pixels (0: none).
    pub max_zone_pixels: f32,
    /// A light edit renews the records whose irradiance from the directly lit surfaces their
    /// hemisphere saw changes by more than this fraction (checked on the stored strata).
    pub light_tolerance: f32,
    /// Debug: every surface and the background the hemispheres see emit radiance 1 (a white
    /// furnace): every record must read E = pi.
    pub furnace: bool,
}

impl Default for RcsSettings {
    fn default() -> Self {
        Self {
            accuracy: 0.25,
            hemisphere_resolution: 32,
            max_records: 16384,
            records_per_frame: 2048,
            rounds: 1,
            gradients: true,
            bounces: 16,
            convergence: 0.01,
            min_zone_pixels: 6.0,
            max_zone_pixels: 0.0,
            light_tolerance: 0.02,
            furnace: false,
        }
    }
}

impl RcsSettings {
    /// Checks ranges.
    pub fn validate(&self) -> Result<(), SettingsError> {
        let err = |name, value: String, range| Err(SettingsError { name, value, range });
        if !(self.accuracy > 0.01 && self.accuracy <= 2.0) {
            return err("rcs.accuracy", self.accuracy.to_string(), "(0.01, 2]");
        }
        if ![8, 16, 32, 64].contains(&self.hemisphere_resolution) {
            return err("rcs.hemisphere_resolution", self.hemisphere_resolution.to_string(), "8, 16, 32 or 64");
        }
        if !(16..=262_144).contains(&self.max_records) {
            return err("rcs.max_records", self.max_records.to_string(), "16..=262144");
        }
        if !(1..=16_384).contains(&self.records_per_frame) {
            return err("rcs.records_per_frame", self.records_per_frame.to_string(), "1..=16384");
        }
        if !(1..=16).contains(&self.rounds) {
            return err("rcs.rounds", self.rounds.to_string(), "1..=16");
        }
        if !(1..=16).contains(&self.bounces) {
            return err("rcs.bounces", self.bounces.to_string(), "1..=16");
        }
        if !(self.min_zone_pixels >= 1.0 && self.min_zone_pixels <= 256.0) {
            return err("rcs.min_zone_pixels", self.min_zone_pixels.to_string(), "1..=256");
        }
        if !(self.max_zone_pixels == 0.0 || self.max_zone_pixels >= self.min_zone_pixels) {
            return err("rcs.max_zone_pixels", self.max_zone_pixels.to_string(), "0 or >= min_zone_pixels");
        }
        if !(self.convergence > 0.0 && self.convergence <= 1.0) {
            return err("rcs.convergence", self.convergence.to_string(), "(0, 1]");
        }
        if !(self.light_tolerance > 0.0 && self.light_tolerance <= 1.0) {
            return err("rcs.light_tolerance", self.light_tolerance.to_string(), "(0, 1]");
        }
        Ok(())
    }
}
