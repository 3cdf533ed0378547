//! Render and GI settings that are part of a project file.
//!
//! Pure data (no wgpu): the renderer reads them, the project file stores them, the editor edits
//! them. Each field documents its cost/quality trade-off. Each technique's settings and their
//! validation live in their own file (`ism.rs`).

use serde::{Deserialize, Serialize};

mod ism;
mod mrt;
pub mod mrt_params;
mod preview;
mod rcs;
mod sshgi;
mod vo;

pub use ism::{BouncePick, IsmSettings, MAX_ATLAS_SIDE, ShadeResolution, TailRatio};
pub use mrt::{BlockOverride, DrtSettings, MrtSettings};
pub use rcs::RcsSettings;
pub use sshgi::SshgiSettings;
pub use vo::VoSettings;

/// The GI technique that produces indirect light.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum GiMode {
    /// Direct light only (shadowed punctual lights), no indirect term.
    #[default]
    Direct,
    /// Knecht 2009: instant radiosity with imperfect shadow maps and temporal reuse.
    Ism,
    /// Ritschel 2008: the same ISM pipeline without temporal reuse (baseline).
    IsmRitschel,
    /// Modular / delta radiance transfer (Loos 2015).
    Mrt,
    /// Screen-space hierarchical GI (Soler et al. 2010).
    Sshgi,
    /// Radiance cache splatting (Gautron et al.).
    Rcs,
    /// The progressive reference path tracer.
    Reference,
}

impl GiMode {
    /// Every mode, in the order the GI panel and the command line list them.
    pub const ALL: [Self; 7] =
        [Self::Direct, Self::Ism, Self::IsmRitschel, Self::Mrt, Self::Sshgi, Self::Rcs, Self::Reference];

    /// The mode whose [`GiMode::name`] is `name` (ASCII case ignored).
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|m| m.name().eq_ignore_ascii_case(name))
    }

    /// The name used on the command line and in the UI.
    pub fn name(self) -> &'static str {
        match self {
            Self::Direct => "direct",
            Self::Ism => "ism",
            Self::IsmRitschel => "ism-ritschel",
            Self::Mrt => "mrt",
            Self::Sshgi => "sshgi",
            Self::Rcs => "rcs",
            Self::Reference => "reference",
        }
    }
}

/// The operator that maps exposed linear radiance to display values.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum Tonemap {
    /// Clamp to [0, 1]: shows radiance exactly where it is below 1 (best for comparisons).
    Clamp,
    /// Reinhard on luminance: keeps hue, compresses highlights.
    Reinhard,
    /// Narkowicz's ACES fit: filmic contrast (the default for viewing).
    #[default]
    Aces,
}

/// Shadow map settings for the direct light.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ShadowSettings {
    /// Side of each shadow map (per cube face for point lights). Cost: memory and raster time
    /// grow with its square; quality: sharper, less aliased shadow edges.
    pub resolution: u32,
    /// PCF kernel radius in texels (taps = (2r+1)^2, each a 2x2 hardware comparison). Cost:
    /// linear in taps; quality: softer, less aliased edges.
    pub pcf_radius: u32,
    /// Receiver offset along the geometric normal, in shadow-map texels, on top of the
    /// receiver-plane depth bias. Free; too large: light leaks at contacts (peter-panning).
    pub normal_bias_texels: f32,
}

impl Default for ShadowSettings {
    fn default() -> Self {
        Self { resolution: 1024, pcf_radius: 1, normal_bias_texels: 0.5 }
    }
}

/// Exposure and tonemapping for the displayed image (EXR output is before both).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ViewSettings {
    /// Exposure in stops: displayed = radiance * 2^ev. Free.
    pub exposure_ev: f32,
    /// Tonemapping operator. Free.
    pub tonemap: Tonemap,
}

impl Default for ViewSettings {
    fn default() -> Self {
        Self { exposure_ev: 0.0, tonemap: Tonemap::Aces }
    }
}

/// The reference path tracer's settings.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ReferenceSettings {
    /// Samples per pixel to converge to. Cost: linear; noise falls as 1/sqrt(spp) or faster
    /// (the samples are stratified).
    pub spp: u32,
    /// Longest path in bounces (1 = direct light only). Cost: grows with each bounce until
    /// Russian roulette ends most paths; cutting it biases the result dark.
    pub max_bounces: u32,
    /// Bounce from which Russian roulette may end paths (unbiased). Lower: faster, noisier.
    /// 5 (Mitsuba's default too) reached a given FLIP on the Cornell box in 10% less time than
    /// 3 and 6% less than 8 (docs/notes/reference-tracer.md).
    pub rr_start: u32,
    /// Random seed; the same seed gives the same image.
    pub seed: u64,
    /// Optional clamp of each path's radiance (biased; removes fireflies). `None` = unbiased.
    pub clamp: Option<f32>,
    /// Path guiding (unbiased): bounces learn from earlier passes where the light came from
    /// (`precompute/guiding.rs`). Off by default: it costs 30-80% more a sample (two machines)
    /// and, against Mitsuba 3, reached a given FLIP faster only on the Cornell box (1.47-1.58x
    /// Mitsuba's time against 1.69-1.80x without) and on `rooms` at 64-128 spp; on `clutter` it
    /// was slower (docs/notes/reference-tracer.md).
    pub guiding: bool,
}

impl Default for ReferenceSettings {
    fn default() -> Self {
        Self { spp: 256, max_bounces: 64, rr_start: 5, seed: 0, clamp: None, guiding: false }
    }
}

/// Everything that selects and tunes the renderer.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RenderSettings {
    /// The active GI technique.
    pub mode: GiMode,
    /// Shadow maps for the direct term.
    pub shadows: ShadowSettings,
    /// Exposure and tonemapping.
    pub view: ViewSettings,
    /// The reference path tracer.
    pub reference: ReferenceSettings,
    /// ISM temporal GI.
    pub ism: IsmSettings,
    /// Screen-space hierarchical GI.
    pub sshgi: SshgiSettings,
    /// Modular radiance transfer over proxy blocks.
    pub mrt: MrtSettings,
    /// Radiance cache splatting.
    pub rcs: RcsSettings,
    /// Volumetric obscurance on the indirect term.
    pub vo: VoSettings,
}

/// A settings value outside its valid range.
#[derive(Debug, thiserror::Error, PartialEq)]
#[error("setting {name} = {value} is outside {range}")]
pub struct SettingsError {
    /// Field path.
    pub name: &'static str,
    /// Offending value.
    pub value: String,
    /// Valid range.
    pub range: &'static str,
}

impl RenderSettings {
    /// Checks ranges (absurd values are errors, never silently clamped).
    pub fn validate(&self) -> Result<(), SettingsError> {
        let s = &self.shadows;
        if !(64..=8192).contains(&s.resolution) {
            return Err(SettingsError {
                name: "shadows.resolution",
                value: s.resolution.to_string(),
                range: "64..=8192",
            });
        }
        if s.pcf_radius > 4 {
            return Err(SettingsError { name: "shadows.pcf_radius", value: s.pcf_radius.to_string(), range: "0..=4" });
        }
        if !(0.0..=16.0).contains(&s.normal_bias_texels) {
            return Err(SettingsError {
                name: "shadows.normal_bias_texels",
                value: s.normal_bias_texels.to_string(),
                range: "0..=16",
            });
        }
        let r = &self.reference;
        if !(1..=1_000_000).contains(&r.spp) {
            return Err(SettingsError { name: "reference.spp", value: r.spp.to_string(), range: "1..=1000000" });
        }
        if !(1..=1024).contains(&r.max_bounces) {
            return Err(SettingsError {
                name: "reference.max_bounces",
                value: r.max_bounces.to_string(),
                range: "1..=1024",
            });
        }
        if r.clamp.is_some_and(|c| !(c > 0.0 && c.is_finite())) {
            return Err(SettingsError { name: "reference.clamp", value: format!("{:?}", r.clamp), range: "> 0" });
        }
        self.ism.validate()?;
        self.sshgi.validate()?;
        self.mrt.validate()?;
        self.rcs.validate()?;
        self.vo.validate()?;
        if !(-32.0..=32.0).contains(&self.view.exposure_ev) {
            return Err(SettingsError {
                name: "view.exposure_ev",
                value: self.view.exposure_ev.to_string(),
                range: "-32..=32",
            });
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_mode_is_listed_once_and_found_by_its_name() {
        for mode in GiMode::ALL {
            // A new variant fails to compile here until it is listed.
            let listed = match mode {
                GiMode::Direct
                | GiMode::Ism
                | GiMode::IsmRitschel
                | GiMode::Mrt
                | GiMode::Sshgi
                | GiMode::Rcs
                | GiMode::Reference => true,
            };
            assert!(listed);
            assert_eq!(GiMode::from_name(mode.name()), Some(mode));
            assert_eq!(GiMode::from_name(&mode.name().to_uppercase()), Some(mode));
            assert_eq!(GiMode::ALL.iter().filter(|m| **m == mode).count(), 1);
        }
        assert_eq!(GiMode::from_name("bogus"), None);
    }

    #[test]
    fn defaults_are_valid_and_absurd_values_are_named() {
        assert!(RenderSettings::default().validate().is_ok());
        let mut s = RenderSettings::default();
        s.ism.vpl_count = 1024;
        s.ism.ism_resolution = 256;
        let e = s.validate().expect_err("a 8192-texel atlas");
        assert!(e.name.contains("ism atlas"), "{e}");
        let mut s = RenderSettings::default();
        s.ism.base_confidence = 1.5;
        assert_eq!(s.validate().expect_err("confidence > 1").name, "ism.base_confidence");
        let mut s = RenderSettings::default();
        s.ism.w_illumination = f32::NAN;
        assert!(s.validate().is_err());
    }
}
