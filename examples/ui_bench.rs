//! Interactivity figures per GI mode: the editor (egui_kittest, default project, the default
//! 1400x860 window) with the first light dragged for a few seconds, one step per UI frame.
//! Prints a markdown table: UI frame times during the drag (logic and paint), viewport frames
//! shown during it and their render scale, and the time to full resolution after the drop.
//!
//! `cargo run --release --example ui_bench -- [seconds of drag, default 6] [modes] [--no-paint]`
//! (`--no-paint` steps the UI without painting it: what the UI logic alone costs).

use std::time::Instant;

use bouncelab::app::EditorApp;
use bouncelab::project_file::{Project, default_project_path};
use bouncelab::settings::GiMode;
use egui_kittest::Harness;

fn percentile(v: &mut [f64], p: f64) -> f64 {
    v.sort_by(f64::total_cmp);
    v.get(((v.len() as f64 - 1.0) * p).round() as usize).copied().unwrap_or(0.0)
}

fn main() -> anyhow::Result<()> {
    let all: Vec<String> = std::env::args().collect();
    // --no-paint: step the UI without painting it (what the UI logic alone costs).
    let paint_on = !all.iter().any(|a| a == "--no-paint");
    let args: Vec<String> = all.into_iter().filter(|a| a != "--no-paint").collect();
    let drag_s: f64 = args.get(1).map_or(Ok(6.0), |s| s.parse())?;
    let modes = args.get(2).map_or("direct,ism,ism-ritschel,reference", String::as_str);
    println!(
        "| mode | UI frame median / p95 / max (ms) | egui paint on the adapter, median (ms) | viewport frames in the drag | scale in the drag | preview frame in the drag, median (ms) | full frame (ms) | full resolution after the drop (s) |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    for name in modes.split(',') {
        let mode = GiMode::from_name(name).ok_or_else(|| anyhow::anyhow!("unknown mode {name:?}"))?;
        let path = default_project_path();
        let mut project = Project::load(&path)?;
        project.render.mode = mode;
        let mut h = Harness::builder()
            .with_size(egui::vec2(1400.0, 860.0))
            .wgpu()
            .build_eframe(move |cc| EditorApp::new(cc, project, Some(path)));
        // Settle at full resolution first.
        for _ in 0..100 {
            h.run_steps(1);
            h.state_mut().wait_viewport();
            if h.state().viewport_scale() == Some(1.0) {
                break;
            }
        }
        let (frames0, _) = h.state().viewport_frames(1);
        let mut ui = Vec::new();
        let mut paint = Vec::new();
        let mut previews = Vec::new();
        let mut last_n = frames0;
        let mut scales = Vec::new();
        let start = Instant::now();
        let mut k = 0u32;
        while start.elapsed().as_secs_f64() < drag_s {
            let t = Instant::now();
            // One pointer event's worth of movement: 2 cm per UI frame, back and forth.
            let dx = if (k / 50).is_multiple_of(2) { 0.02 } else { -0.02 };
            h.state_mut().state_mut().project.scene.desc_mut().lights[0].position.x += dx;
            h.run_steps(1);
            ui.push(t.elapsed().as_secs_f64() * 1e3);
            if paint_on {
                let t = Instant::now();
                let _ = h.render();
                paint.push(t.elapsed().as_secs_f64() * 1e3);
            }
            scales.push(f64::from(h.state().viewport_scale().unwrap_or(0.0)));
            let (n, _) = h.state().viewport_frames(1);
            if n != last_n {
                last_n = n;
                if h.state().viewport_scale().is_some_and(|s| s < 1.0) {
                    previews.push(h.state().viewport_last_frame_ms());
                }
            }
            k += 1;
        }
        let (frames1, _) = h.state().viewport_frames(1);
        let dropped = Instant::now();
        // After the drop: the first frame submitted after it, at full resolution.
        let target = frames1 + u64::from(!h.state().viewport_idle()) + 1;
        let mut full_s = f64::NAN;
        while dropped.elapsed().as_secs_f64() < 120.0 {
            h.run_steps(1);
            if h.state().viewport_frames(1).0 >= target && h.state().viewport_scale() == Some(1.0) {
                full_s = dropped.elapsed().as_secs_f64();
                break;
            }
        }
        let viewport_ms = h.state().viewport_last_frame_ms();
        let frames = frames1 - frames0;
        let scale = percentile(&mut scales, 0.5);
        println!(
            "| {name} | {:.0} / {:.0} / {:.0} | {:.0} | {frames} in {drag_s:.0} s | {:.0}% (median) | {:.0} | {viewport_ms:.0} | {full_s:.1} |",
            percentile(&mut ui.clone(), 0.5),
            percentile(&mut ui.clone(), 0.95),
            percentile(&mut ui, 1.0),
            percentile(&mut paint, 0.5),
            scale * 100.0,
            percentile(&mut previews, 0.5)
        );
    }
    Ok(())
}
