//! The timings panel: per-pass GPU times (CPU frame time where the adapter has no timestamps)
//! with a history plot.

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

    /// Draws the table and the plot.
    pub fn ui(&self, ui: &mut egui::Ui) {
        let frame = self.frame_ms.last().map_or(0.0, |p| p[1]);
        ui.horizontal_wrapped(|ui| {
            ui.label(format!("frame {frame:.1} ms"));
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
