//! Cheaper settings for the editor's preview while something moves: each technique says which
//! of its settings trade quality for time without changing what the image converges to.

use super::{IsmSettings, RenderSettings};

impl RenderSettings {
    /// These settings at about `cost` (0..=1) of the active technique's own work, for preview
    /// frames while the user drags: only settings whose reduction adds noise or blur, never
    /// bias in the mean (so the preview keeps the brightness of the final image). `direct` and
    /// the reference have none (the reference is progressive already).
    pub fn cheaper(&self, cost: f32) -> Self {
        Self { ism: self.ism.cheaper(cost), ..self.clone() }
    }
}

impl IsmSettings {
    /// Fewer VPLs (at least one per interleave tile, 4 at the least); every ISM keeps its point
    /// count, so its holes and lookup offset stay as they are. Both the
    /// `ism maps` and the `ism shade` pass scale with the VPL count (measured on lavapipe at
    /// 1000x760: 0.9 s and 4.5 s at 256 VPLs). The bounce count stays: fewer bounces would
    /// darken the preview.
    pub fn cheaper(&self, cost: f32) -> Self {
        let cost = cost.clamp(0.0, 1.0);
        let tiles = (self.interleave * self.interleave).max(4);
        let vpl_count = ((self.vpl_count as f32 * cost) as u32).max(tiles.min(self.vpl_count));
        Self { vpl_count, ..self.clone() }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cheaper_ism_keeps_points_per_ism_and_validates() {
        let full = RenderSettings::default();
        let s = full.cheaper(0.25);
        assert_eq!(s.ism.vpl_count, full.ism.vpl_count / 4);
        assert_eq!(s.ism.points_per_ism, full.ism.points_per_ism);
        assert_eq!(s.ism.bounces, full.ism.bounces, "no darker preview");
        assert!(s.validate().is_ok());
        let tiny = full.cheaper(0.0);
        assert_eq!(tiny.ism.vpl_count, full.ism.interleave * full.ism.interleave);
        assert!(tiny.validate().is_ok());
        assert_eq!(full.cheaper(1.0), full, "full cost changes nothing");
    }
}
