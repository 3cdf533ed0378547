//! When a still view may refine past the thesis's c_base (`IsmSettings::still_frames`) and when
//! the temporal history counts as settled: the camera must stand still, and a light or object
//! edit first lets the history from before it fade at c_base, so a still view converges without
//! holding an edit's afterglow.

use super::screen::Blend;
use crate::settings::IsmSettings;

/// Frames after which the temporal blend is at its steady state: the history is the plain mean
/// of its frames until the confidence reaches its cap c (`IsmSettings::confidence_cap`), at
/// 1 / (1 - c) frames (10 at the default c_base 0.9 while anything moves, 32 for a still view
/// at the default `still_frames`), and an exponential average worth 2 / (1 - c) - 1 frames
/// after it: further frames of an unchanged view only trade one sample of it for another.
/// Without temporal reuse (`ism-ritschel`) a frame is final at once.
pub fn settle_frames(confidence_cap: f32) -> u32 {
    (1.0 / (1.0 - confidence_cap).max(1e-3)).ceil().clamp(1.0, 3000.0) as u32
}

/// Frames after a light or object edit before a still view may refine past `c_base`
/// (`IsmSettings::still_frames`): the history from before the edit is lit as the scene no longer
/// is, and at confidence c_base its weight falls below 1% after ln 0.01 / ln c_base frames (44
/// at 0.9). Refining earlier would hold that afterglow for still_frames frames instead.
pub fn refresh_frames(base_confidence: f32) -> u32 {
    if base_confidence <= 0.0 {
        return 0;
    }
    (0.01f32.ln() / base_confidence.min(0.999).ln()).ceil().clamp(0.0, 3000.0) as u32
}

/// When a still view may refine, and when the history counts as settled, in frames since the
/// history was last dropped (`TechniqueStatus::history_frames`).
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Stillness {
    /// A light or object was edited since the last frame.
    pub edited: bool,
    /// The confidence stays at c_base until this frame (the history from before an edit fades).
    refresh_until: u32,
    /// The frame by which the history will have settled if nothing changes.
    settle_at: u32,
}

impl Stillness {
    /// The temporal blend of frame `h` (frames merged since the history was dropped) and the
    /// frame the history settles by. A still view drops the illumination term as well: no light
    /// has changed, and the term, which lowers the confidence where a frame differs from the
    /// history, would weight the bright outliers of VPL noise up to 1 / (1 - cap) times their share
    /// (`ism` on the suite's Cornell box read 1.023 of the reference's energy with it, FLIP 0.16
    /// of `direct`'s).
    pub fn next(&mut self, settings: &IsmSettings, h: u32, camera_still: bool) -> (Blend, u32) {
        let settle = settle_frames(settings.confidence_cap(true));
        // A dropped history (h = 0) holds nothing from before the edit.
        if std::mem::take(&mut self.edited) && h > 0 {
            self.refresh_until = h + refresh_frames(settings.base_confidence);
            self.settle_at = self.refresh_until + settle;
        } else if !camera_still {
            self.settle_at = self.settle_at.max(h + 1 + settle);
        }
        let still = camera_still && h >= self.refresh_until && settings.still_frames > 0;
        let w_illumination = if still { 0.0 } else { settings.w_illumination };
        (Blend { confidence_cap: settings.confidence_cap(still), w_illumination }, self.settle_at.max(settle))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_still_view_refines_past_c_base_at_once_and_an_edit_waits_until_the_old_history_has_faded() {
        let s = IsmSettings::default();
        let mut still = Stillness::default();
        let thesis = Blend { confidence_cap: 0.9, w_illumination: s.w_illumination };
        let (blend, settle) = still.next(&s, 0, true);
        assert!((blend.confidence_cap - (1.0 - 1.0 / 32.0)).abs() < 1e-6, "a fresh still view refines: {blend:?}");
        assert_eq!(blend.w_illumination, 0.0, "no light changed");
        assert_eq!(settle, 32);
        assert_eq!(still.next(&s, 5, false).0, thesis, "a moving camera keeps the thesis's blend");
        still.edited = true;
        let (blend, settle) = still.next(&s, 40, true);
        assert_eq!(blend, thesis, "an edit: the thesis's blend while the old history fades");
        assert_eq!(refresh_frames(0.9), 44);
        assert_eq!(settle, 40 + 44 + 32);
        assert_eq!(still.next(&s, 83, true).0, thesis);
        assert!(still.next(&s, 84, true).0.confidence_cap > 0.96, "refines again once 0.9^44 < 1%");
        let off = IsmSettings { still_frames: 0, ..IsmSettings::default() };
        assert_eq!(Stillness::default().next(&off, 0, true), (thesis, 10), "0: the thesis's blend throughout");
    }
}
