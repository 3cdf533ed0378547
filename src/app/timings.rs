//! The timings panel: per-pass GPU times of each viewport frame (submit-to-image time where
//! the adapter has no timestamps), the interface's own frame time, and a history plot.

use std::collections::BTreeMap;

use crate::render::PassTiming;

/// Frames of history kept.
const HISTORY: usize = 240;

/// Recorded timings.
#[derive(Default)]
pub struct Timings {
    frame: usize,
    frame_ms: Vec<[f64; 2]>,
    passes: BTreeMap<String, Vec<[f64; 2]>>,
    latest: Vec<PassTiming>,
    /// The interface's frame times (ms), most recent last.
    ui_ms: std::collections::VecDeque<f64>,
}

impl Timings {
    /// Adds a frame.
    pub fn push(&mut self, frame_ms: f64, passes: &[PassTiming]) {
        self.frame += 1;
        let x = self.frame as f64;
        self.frame_ms.push([x, frame_ms]);
        for p in passes {
            self.passes.entry(p.name.clone()).or_default().push([x, p.ms]);
        }
        for series in std::iter::once(&mut self.frame_ms).chain(self.passes.values_mut()) {
            let excess = series.len().saturating_sub(HISTORY);
            series.drain(..excess);
        }
        self.latest = passes.to_vec();
    }

    /// Records one interface frame (independent of viewport frames).
    pub fn push_ui(&mut self, ms: f64) {
        self.ui_ms.push_back(ms);
        if self.ui_ms.len() > HISTORY {
            self.ui_ms.pop_front();
        }
    }

    /// The slowest interface frame among the last `n` (ms).
    pub fn ui_worst(&self, n: usize) -> f64 {
        self.ui_ms.iter().rev().take(n).fold(0.0, |a, &b| a.max(b))
    }

    /// The median interface frame over the history (ms).
    pub fn ui_median(&self) -> f64 {
        let mut v: Vec<f64> = self.ui_ms.iter().copied().collect();
        v.sort_by(f64::total_cmp);
        v.get(v.len() / 2).copied().unwrap_or(0.0)
    }

    /// Draws the table and the plot.
    pub fn ui(&self, ui: &mut egui::Ui) {
        let frame = self.frame_ms.last().map_or(0.0, |p| p[1]);
        ui.horizontal_wrapped(|ui| {
            ui.label(format!("UI {:.1} ms (median) · viewport frame {frame:.1} ms", self.ui_median()));
            for t in &self.latest {
                ui.label(format!("· {} {:.2} ms", t.name, t.ms));
            }
            if self.latest.is_empty() {
                ui.label("(no GPU timestamps on this adapter: CPU frame time only)");
            }
        });
        egui_plot::Plot::new("timings plot").legend(egui_plot::Legend::default()).y_axis_label("ms").show(ui, |plot| {
            plot.line(egui_plot::Line::new("frame", self.frame_ms.clone()));
            for (name, series) in &self.passes {
                plot.line(egui_plot::Line::new(name.clone(), series.clone()));
            }
        });
    }
}
