//! Render and GI settings that are part of a project file.
//!
//! Pure data (no wgpu): the renderer reads them, the project file stores them, the editor edits
//! them. Each field documents its cost/quality trade-off.

use serde::{Deserialize, Serialize};

/// The GI technique that produces indirect light.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, clap::ValueEnum)]
pub enum GiMode {
    /// Direct light only (shadowed punctual lights), no indirect term.
    #[default]
    #[value(name = "direct")]
    Direct,
    /// Knecht 2009: instant radiosity with imperfect shadow maps and temporal reuse.
    #[value(name = "ism")]
    Ism,
    /// Ritschel 2008: the same ISM pipeline without temporal reuse (baseline).
    #[value(name = "ism-ritschel")]
    IsmRitschel,
    /// Modular / delta radiance transfer (Loos 2015).
    #[value(name = "mrt")]
    Mrt,
    /// Screen-space hierarchical GI (Soler et al. 2010).
    #[value(name = "sshgi")]
    Sshgi,
    /// Radiance cache splatting (Gautron et al.).
    #[value(name = "rcs")]
    Rcs,
    /// The progressive reference path tracer.
    #[value(name = "reference")]
    Reference,
}

impl GiMode {
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
    /// Samples per pixel to converge to. Cost: linear; noise falls as 1/sqrt(spp).
    pub spp: u32,
    /// Longest path in bounces (1 = direct light only). Cost: grows with each bounce until
    /// Russian roulette ends most paths; cutting it biases the result dark.
    pub max_bounces: u32,
    /// Bounce from which Russian roulette may end paths (unbiased). Lower: faster, noisier.
    pub rr_start: u32,
    /// Random seed; the same seed gives the same image.
    pub seed: u64,
    /// Optional clamp of each path's radiance (biased; removes fireflies). `None` = unbiased.
    pub clamp: Option<f32>,
}

impl Default for ReferenceSettings {
    fn default() -> Self {
        Self { spp: 256, max_bounces: 64, rr_start: 3, seed: 0, clamp: None }
    }
}

/// Largest ISM atlas side: a u32 atlas of this side stays within 128 MiB.
pub const MAX_ATLAS_SIDE: u32 = 5792;

/// Settings of the ISM techniques (`ism`, `ism-ritschel`; Knecht 2009). Defaults are the
/// thesis's where it gives them (256 VPLs, 128^2 ISMs, 32k points, c_base 0.9, alpha 0.01,
/// beta 0.8, d^2 >= 1) and the digest's recommendations elsewhere.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct IsmSettings {
    /// VPLs per set (4..=1024). Cost: shading and ISM splatting grow linearly; quality: fewer
    /// blotches and less flicker (the thesis needs 256 for flicker-free results).
    pub vpl_count: u32,
    /// Side of each VPL's paraboloid ISM (64..=256). Cost: atlas memory and pull-push grow with
    /// its square; quality: sharper indirect shadows (needs enough points per ISM).
    pub ism_resolution: u32,
    /// Scene sample points splatted into the ISMs in all (each ISM gets total / VPLs). Cost:
    /// linear splatting; quality: fewer holes and light leaks.
    pub total_points: u32,
    /// Interleave size n (the G-buffer splits into n x n tiles; 1..=8). Cost: none; quality:
    /// each pixel sees N/n^2 VPLs, the n x n filter hides the pattern but blurs detail.
    pub interleave: u32,
    /// Base confidence c_base of the temporal blend (0..1). Higher: smoother, more afterglow.
    pub base_confidence: f32,
    /// Weight of the screen-space/depth movement in the confidence. Higher: history dropped
    /// sooner under motion (less ghosting, more noise).
    pub w_position: f32,
    /// Weight of the normal change in the confidence.
    pub w_normal: f32,
    /// Weight of the illumination change in the confidence. Higher: reacts faster to lighting
    /// changes (less afterglow) but lets VPL resampling noise through.
    pub w_illumination: f32,
    /// Light bounces (1..=6); each extra bounce costs one VPL generation, ISM and shading pass
    /// (shading time grows linearly). The thesis's figures use 1; the default is 6, which
    /// brings the default Cornell box within 3% of the path tracer's energy (ism-ritschel at
    /// 128x72: 4 bounces 93%, 5: 96%, 6: 97% over 8 frames; each bounce adds less than the last).
    pub bounces: u32,
    /// Geometry-aware filter threshold alpha: a neighbour farther than alpha x the scene
    /// diameter from the pixel's tangent plane is rejected (the thesis's 0.01, applied along
    /// the normal instead of the view ray so grazing walls keep their taps). Free; lower:
    /// sharper contacts, more visible interleave pattern.
    pub filter_depth: f32,
    /// Geometry-aware filter normal threshold beta (minimum cosine; the SH filter tests
    /// geometric normals only, so normal maps never break its window). Free.
    pub filter_normal: f32,
    /// Filter the incident radiance as 9 SH coefficients per colour and shade afterwards with
    /// each pixel's own normal and BRDF (Segovia & Wald): keeps glossy and normal-mapped
    /// detail. Cost: 56 bytes per pixel (f16) and 27-channel filtering, +7% (320x180) to
    /// +17% (640x360) of the `ism shade` pass time (docs/BENCHMARKS.md).
    pub sh_filter: bool,
    /// Minimum VPL distance in metres. Larger: fewer spikes near VPLs, darker corners (bias).
    /// The thesis clamps d^2 >= 1 in world units, which assumes large scenes; in a 2 m Cornell
    /// box that loses 9-11% of the one-bounce light (measured), so the default is 0.1 m.
    pub clamp_distance: f32,
}

impl Default for IsmSettings {
    fn default() -> Self {
        Self {
            vpl_count: 256,
            ism_resolution: 128,
            total_points: 32 * 1024,
            interleave: 4,
            base_confidence: 0.9,
            w_position: 20.0,
            w_normal: 10.0,
            w_illumination: 0.5,
            bounces: 6,
            filter_depth: 0.01,
            filter_normal: 0.8,
            sh_filter: false,
            clamp_distance: 0.1,
        }
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
        let m = &self.ism;
        let checks: [(&'static str, bool, String, &'static str); 9] = [
            ("ism.vpl_count", (4..=1024).contains(&m.vpl_count), m.vpl_count.to_string(), "4..=1024"),
            (
                "ism.ism_resolution",
                (64..=256).contains(&m.ism_resolution) && m.ism_resolution.is_power_of_two(),
                m.ism_resolution.to_string(),
                "64, 128 or 256",
            ),
            (
                "ism.total_points",
                (1024..=1 << 22).contains(&m.total_points),
                m.total_points.to_string(),
                "1024..=4194304",
            ),
            ("ism.interleave", (1..=8).contains(&m.interleave), m.interleave.to_string(), "1..=8"),
            ("ism.base_confidence", (0.0..=1.0).contains(&m.base_confidence), m.base_confidence.to_string(), "0..=1"),
            ("ism.bounces", (1..=6).contains(&m.bounces), m.bounces.to_string(), "1..=6"),
            ("ism.filter_normal", (-1.0..=1.0).contains(&m.filter_normal), m.filter_normal.to_string(), "-1..=1"),
            (
                "ism.clamp_distance",
                m.clamp_distance.is_finite() && m.clamp_distance >= 0.0,
                m.clamp_distance.to_string(),
                ">= 0",
            ),
            (
                "ism confidence weights",
                [m.w_position, m.w_normal, m.w_illumination, m.filter_depth].iter().all(|w| w.is_finite() && *w >= 0.0),
                format!("{} {} {} {}", m.w_position, m.w_normal, m.w_illumination, m.filter_depth),
                ">= 0",
            ),
        ];
        if let Some((name, _, value, range)) = checks.into_iter().find(|c| !c.1) {
            return Err(SettingsError { name, value, range });
        }
        // The ISM atlas holds one tile per VPL of every bounce; keep its side within 5792 texels
        // (a 5792^2 u32 atlas is just under 128 MiB, WebGPU's default storage-binding limit;
        // digest PF24), which fits 256 VPLs x 6 bounces at 128^2.
        let tiles = f64::from(m.vpl_count * m.bounces).sqrt().ceil() as u32;
        if m.ism_resolution * tiles > MAX_ATLAS_SIDE {
            return Err(SettingsError {
                name: "ism atlas (ism_resolution x sqrt(vpl_count x bounces))",
                value: format!("{} x {tiles} = {}", m.ism_resolution, m.ism_resolution * tiles),
                range: "<= 5792 texels",
            });
        }
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
