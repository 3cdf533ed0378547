//! Settings of `sshgi`, screen-space hierarchical indirect light (Soler, Hoel, Rochet and
//! Holzschuch 2010; digest part C of `technique-rcs-shfilter-sshgi.md`), and their ranges.
//! Defaults are the paper's (quarter start resolution, 4 levels, 64 samples per level).

use serde::{Deserialize, Serialize};

use super::SettingsError;

/// Settings of the `sshgi` technique.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SshgiSettings {
    /// Start resolution as a power-of-two reduction of the view (0 full, 1 half, 2 quarter: the
    /// paper's ¼ and ½). The gather of the start level dominates the cost: each step finer costs
    /// about 4x the start level's gather (the paper: 6.6 ms at ¼, 25.9 ms at ½ without
    /// visibility, GTX 260, 1280x720, 64 samples).
    pub start_level: u32,
    /// Levels gathered (1..=6, fewer where the view is too small): level k covers the ring
    /// r 2^(k-1)..r 2^k start-level texels around each pixel, so each level doubles the reach
    /// for about a quarter of the previous level's cost (the paper: a 5th level +1% time).
    pub levels: u32,
    /// Samples per texel and level, N (the paper's 64 and 256). Cost: every gather is linear in
    /// it; quality: less noise per frame.
    pub samples: u32,
    /// Outer ring radius r in texels of each level; 0 = automatic, the smallest r whose disc on
    /// the coarsest level spans the whole view (the paper's rule, which gives its r = 40 at
    /// 1280x720, ¼ start, 4 levels). Larger: the same samples spread over a larger area.
    pub radius: f32,
    /// Indirect bounces (1..=4). Each later bounce gathers albedo x the previous bounce's light
    /// from the same depth and normal levels, re-mipping only the illumination: one more gather
    /// and up-sampling chain each (linear cost). The paper shows one; the suite's Cornell box
    /// (`ism_probe` with `PROBE_SSHGI`, mean of 4 frames) reads 0.778 / 0.876 / 0.915 / 0.932 of
    /// the path tracer's energy at 1 / 2 / 3 / 4 (what is left is off-screen senders).
    pub bounces: u32,
}

impl Default for SshgiSettings {
    fn default() -> Self {
        Self { start_level: 2, levels: 4, samples: 64, radius: 0.0, bounces: 3 }
    }
}

impl SshgiSettings {
    /// Checks ranges (absurd values are errors, never silently clamped).
    pub fn validate(&self) -> Result<(), SettingsError> {
        let checks: [(&'static str, bool, String, &'static str); 5] = [
            ("sshgi.start_level", self.start_level <= 2, self.start_level.to_string(), "0..=2"),
            ("sshgi.levels", (1..=6).contains(&self.levels), self.levels.to_string(), "1..=6"),
            ("sshgi.samples", (1..=1024).contains(&self.samples), self.samples.to_string(), "1..=1024"),
            (
                "sshgi.radius",
                self.radius.is_finite() && (0.0..=512.0).contains(&self.radius),
                self.radius.to_string(),
                "0 (automatic) or up to 512 texels",
            ),
            ("sshgi.bounces", (1..=4).contains(&self.bounces), self.bounces.to_string(), "1..=4"),
        ];
        match checks.into_iter().find(|c| !c.1) {
            Some((name, _, value, range)) => Err(SettingsError { name, value, range }),
            None => Ok(()),
        }
    }

    /// The ring radius in texels for a start level of `start` texels (width, height) and
    /// `levels` levels: the setting, or the automatic one.
    pub fn ring_radius(&self, start: (u32, u32), levels: u32) -> f32 {
        if self.radius > 0.0 {
            return self.radius;
        }
        let coarsest = start.0.max(start.1) >> levels.saturating_sub(1).min(31);
        (coarsest.max(1)) as f32
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn automatic_radius_is_the_papers_forty_at_1280x720_quarter_four_levels() {
        let s = SshgiSettings::default();
        assert_eq!(s.ring_radius((320, 180), 4), 40.0);
        assert_eq!(SshgiSettings { radius: 12.0, ..s.clone() }.ring_radius((320, 180), 4), 12.0);
    }

    #[test]
    fn out_of_range_values_are_named() {
        let bad = SshgiSettings { bounces: 0, ..Default::default() };
        assert_eq!(bad.validate().map_err(|e| e.name), Err("sshgi.bounces"));
        let bad = SshgiSettings { radius: f32::NAN, ..Default::default() };
        assert_eq!(bad.validate().map_err(|e| e.name), Err("sshgi.radius"));
        assert!(SshgiSettings::default().validate().is_ok());
    }
}
