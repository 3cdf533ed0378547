//! The viewport's frame budget: which render scale the next preview frame uses.
//!
//! While something moves (camera, light, object, a setting) the controller picks the largest
//! scale of a fixed ladder whose predicted frame time fits the budget; once nothing has changed
//! for [`HOLD`], it asks for full resolution. Predictions come from the frames it has seen: the
//! measured time per ladder step (smoothed), or a fixed cost plus a cost per unit of work
//! (pixels times the technique's cost factor) fitted to the measured steps; a wrong prediction
//! is corrected by the next measurement, one frame later.
//! Pure logic, no GPU: unit-tested here.

use serde::{Deserialize, Serialize};

/// Render scales, per axis; each step roughly halves the pixel count of the one before.
/// A fixed ladder instead of a continuous scale: the view targets (and temporal history,
/// which a resize resets) change only when the step changes, not on every measurement.
pub const LADDER: [f32; 6] = [1.0, 0.71, 0.5, 0.35, 0.25, 0.18];

/// The technique's own cost at each step ([`crate::settings::RenderSettings::cheaper`]): the
/// coarse steps also use fewer VPLs, because passes such as ISM's maps do not shrink with the
/// pixel count (0.9 s of a 5.5 s `ism` frame on lavapipe at 1000x760).
pub const COST: [f32; 6] = [1.0, 1.0, 0.5, 0.5, 0.25, 0.125];

/// The share of a full frame's work at `step` (pixels times technique cost).
fn work(step: usize) -> f64 {
    f64::from(LADDER[step] * LADDER[step] * COST[step])
}

/// How long after the last change the preview still counts as moving (ms): the gaps between
/// pointer events of one drag must not start a full-resolution frame.
pub const HOLD: std::time::Duration = std::time::Duration::from_millis(300);

/// Editor preferences for the preview (persisted with the layout, not in project files).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct PreviewSettings {
    /// Viewport frame budget while something moves (ms). Cost: none; a smaller budget gives a
    /// blurrier image during a drag. Default 33 ms on a GPU, 250 ms on a software adapter
    /// (where `direct` at full 1000x760 takes about 230 ms and `ism` about 5.5 s).
    pub budget_ms: f32,
    /// Adapt the render scale to the budget; off renders every frame at full resolution.
    pub adaptive: bool,
}

impl Default for PreviewSettings {
    fn default() -> Self {
        Self { budget_ms: 33.0, adaptive: true }
    }
}

impl PreviewSettings {
    /// The defaults for an adapter: a software rasteriser gets a budget it can hold.
    pub fn for_device_type(device_type: wgpu::DeviceType) -> Self {
        match device_type {
            wgpu::DeviceType::Cpu => Self { budget_ms: 250.0, adaptive: true },
            _ => Self::default(),
        }
    }
}

/// Chooses the ladder step of the next preview frame from measured frame times.
#[derive(Clone, Debug, Default)]
pub struct ScaleController {
    /// Smoothed measured frame time per ladder step (ms).
    measured: [Option<f64>; LADDER.len()],
    /// The step last chosen.
    step: usize,
}

impl ScaleController {
    /// A controller that starts at the coarsest step: the first image comes fast on any
    /// adapter, and the idle refinement brings full resolution right after it.
    pub fn new() -> Self {
        Self { measured: [None; LADDER.len()], step: LADDER.len() - 1 }
    }

    /// Records how long a frame at `step` took (submit to image on the CPU, ms).
    pub fn record(&mut self, step: usize, ms: f64) {
        if let Some(m) = self.measured.get_mut(step) {
            *m = Some(m.map_or(ms, |old| 0.5 * old + 0.5 * ms));
        }
    }

    /// The predicted frame time at `step` (ms), if any frame was measured yet: the smoothed
    /// measurement there, else a fixed cost plus a cost per unit of work fitted (least squares)
    /// to every measured step, else (one step measured) that step scaled by the work ratio.
    pub fn predict(&self, step: usize) -> Option<f64> {
        if let Some(Some(m)) = self.measured.get(step) {
            return Some(*m);
        }
        if step >= LADDER.len() {
            return None;
        }
        let points: Vec<(f64, f64)> =
            (0..LADDER.len()).filter_map(|k| self.measured[k].map(|m| (work(k), m))).collect();
        match points.as_slice() {
            [] => return None,
            [(x, y)] => return Some(y * work(step) / x),
            _ => {}
        }
        let n = points.len() as f64;
        let (sx, sy) = points.iter().fold((0.0, 0.0), |(a, b), (px, py)| (a + px, b + py));
        let (mx, my) = (sx / n, sy / n);
        let sxx: f64 = points.iter().map(|(px, _)| (px - mx).powi(2)).sum();
        let sxy: f64 = points.iter().map(|(px, py)| (px - mx) * (py - my)).sum();
        let slope = if sxx > 0.0 { (sxy / sxx).max(0.0) } else { 0.0 };
        let fixed = (my - slope * mx).max(0.0);
        Some(fixed + slope * work(step))
    }

    /// The step for the next frame: the coarsest for the very first frame (an image fast on
    /// any adapter), then full resolution when idle (or not adaptive), else the largest scale
    /// predicted to fit `budget_ms` (the coarsest when none does).
    pub fn next(&mut self, moving: bool, settings: &PreviewSettings) -> usize {
        let measured_any = self.measured.iter().any(Option::is_some);
        self.step = if !settings.adaptive {
            0
        } else if !measured_any {
            self.step
        } else if !moving {
            0
        } else {
            (0..LADDER.len())
                .find(|&k| self.predict(k).is_some_and(|t| t <= f64::from(settings.budget_ms)))
                .unwrap_or(LADDER.len() - 1)
        };
        self.step
    }

    /// The step last chosen.
    pub fn step(&self) -> usize {
        self.step
    }
}

/// The render size for `full` at ladder `step` (at least one pixel per axis).
pub fn scaled_size(full: (u32, u32), step: usize) -> (u32, u32) {
    let s = LADDER.get(step).copied().unwrap_or(1.0);
    let f = |v: u32| ((v as f32 * s).round() as u32).clamp(1, v.max(1));
    (f(full.0), f(full.1))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fake adapter: a fixed cost plus a cost per pixel fraction.
    fn frame_ms(step: usize) -> f64 {
        100.0 + 5000.0 * work(step)
    }

    #[test]
    fn drops_under_a_tight_budget_and_returns_to_full_when_idle() {
        let settings = PreviewSettings { budget_ms: 500.0, adaptive: true };
        let mut c = ScaleController::new();
        // The first frame is the coarsest; idle after it: full resolution.
        let mut step = c.next(false, &settings);
        assert_eq!(step, LADDER.len() - 1);
        c.record(step, frame_ms(step));
        step = c.next(false, &settings);
        assert_eq!(step, 0);
        c.record(step, frame_ms(step));
        // Moving: the scale drops until a frame fits 500 ms.
        for _ in 0..6 {
            step = c.next(true, &settings);
            c.record(step, frame_ms(step));
        }
        assert!(LADDER[step] < 1.0, "scale dropped: {}", LADDER[step]);
        assert!(frame_ms(step) <= 500.0, "the chosen step fits the budget: {} ms", frame_ms(step));
        assert!(step > 0 && frame_ms(step - 1) > 500.0, "and is the largest that does");
        // Idle again: straight back to 1.0.
        assert_eq!(c.next(false, &settings), 0);
    }

    #[test]
    fn an_impossible_budget_gives_the_coarsest_step() {
        let settings = PreviewSettings { budget_ms: 1.0, adaptive: true };
        let mut c = ScaleController::new();
        for moving in [false, true, true, true] {
            let step = c.next(moving, &settings);
            c.record(step, frame_ms(step));
        }
        assert_eq!(c.step(), LADDER.len() - 1);
    }

    #[test]
    fn not_adaptive_means_full_resolution_while_moving() {
        let settings = PreviewSettings { budget_ms: 1.0, adaptive: false };
        let mut c = ScaleController::new();
        c.record(0, 5000.0);
        assert_eq!(c.next(true, &settings), 0);
    }

    #[test]
    fn prediction_scales_one_measurement_and_fits_two() {
        let mut c = ScaleController::new();
        c.record(2, 400.0);
        let p = c.predict(0).expect("predicted");
        assert!((p - 400.0 * 4.0 / COST[2] as f64).abs() < 1.0, "{p}");
        c.record(2, 200.0);
        assert_eq!(c.predict(2), Some(300.0), "smoothed");
        // Two steps of the fake adapter: its fixed cost is found, so step 3 is predicted right.
        let mut c = ScaleController::new();
        c.record(0, frame_ms(0));
        c.record(5, frame_ms(5));
        let p = c.predict(3).expect("predicted");
        assert!((p - frame_ms(3)).abs() < 1.0, "{p} vs {}", frame_ms(3));
    }

    #[test]
    fn scaled_sizes_stay_positive() {
        assert_eq!(scaled_size((1000, 760), 0), (1000, 760));
        assert_eq!(scaled_size((1000, 760), 2), (500, 380));
        assert_eq!(scaled_size((1, 1), 5), (1, 1));
    }
}
