//! Settings of volumetric obscurance (Loos & Sloan 2010 as Loos 2015 ch. 6 gives it): the
//! screen-space obscurance that multiplies the indirect term where the active
//! technique's own resolution misses contact detail (`mrt`'s lightmap texels are 25 cm on a 4 m
//! room). Costs are `bouncelab bench` figures.

use serde::{Deserialize, Serialize};

use super::SettingsError;

/// Volumetric obscurance.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct VoSettings {
    /// Applied to `mrt`'s indirect term.
    pub mrt: bool,
    /// Applied to the other techniques' indirect term too (`ism`, `sshgi`, `rcs`; never to
    /// `direct` or the reference).
    pub other_modes: bool,
    /// The sphere's radius in metres (object space): the contact scale it darkens. Free.
    pub radius: f32,
    /// Line samples per pixel: 5 or 9 (centre included) or 12 (centre excluded), the
    /// dissertation's low-noise counts. Cost linear in the count.
    pub samples: u32,
    /// Each surface is a slab this thick (metres): space behind it is free again, so a thin
    /// object's silhouette does not darken what lies far behind it. 0 turns the model off.
    pub thickness: f32,
    /// Only the hemisphere above the surface counts (an open plane reads 1, not 0.5).
    pub normal_clamp: bool,
    /// The edge-aware (bilateral) blur over the 4 x 4 rotation pattern.
    pub blur: bool,
}

impl Default for VoSettings {
    fn default() -> Self {
        Self { mrt: true, other_modes: false, radius: 0.1, samples: 9, thickness: 0.5, normal_clamp: true, blur: true }
    }
}

impl VoSettings {
    /// Checks ranges.
    pub fn validate(&self) -> Result<(), SettingsError> {
        if !(self.radius > 0.0 && self.radius <= 100.0) {
            return Err(SettingsError { name: "vo.radius", value: self.radius.to_string(), range: "(0, 100]" });
        }
        if ![5, 9, 12].contains(&self.samples) {
            return Err(SettingsError { name: "vo.samples", value: self.samples.to_string(), range: "5, 9 or 12" });
        }
        if !(0.0..=100.0).contains(&self.thickness) {
            return Err(SettingsError { name: "vo.thickness", value: self.thickness.to_string(), range: "0..=100" });
        }
        Ok(())
    }
}
