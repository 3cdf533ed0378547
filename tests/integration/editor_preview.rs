//! The viewport preview on the software adapter: the interface steps on while a GI frame is in
//! flight, the render scale drops under a tiny frame budget and returns to full resolution when
//! nothing moves, and picking by ray agrees with the rasterised object ids.

use crate::common;

use bouncelab::app::EditorApp;
use bouncelab::app::pick::Picker;
use bouncelab::project_file::{Project, default_project_path};
use bouncelab::render::Renderer;
use bouncelab::settings::GiMode;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable as _;

fn gpu() -> bool {
    common::has_gpu()
}

fn harness(size: egui::Vec2) -> Harness<'static, EditorApp> {
    let path = default_project_path();
    let project = Project::load(&path).expect("default project");
    let mut h =
        Harness::builder().with_size(size).wgpu().build_eframe(move |cc| EditorApp::new(cc, project, Some(path)));
    h.run_steps(2);
    h
}

#[test]
fn the_interface_steps_on_while_an_ism_frame_is_in_flight() {
    if !gpu() {
        return;
    }
    let mut h = harness(egui::vec2(1280.0, 800.0));
    h.state_mut().wait_viewport();
    h.get_by_label("ism").click();
    h.run_steps(1);
    h.state_mut().wait_viewport();
    // Full resolution (nothing moves after the click has been rendered once).
    h.state_mut().preview_settings_mut().adaptive = false;
    h.run_steps(1);
    let (before, _) = h.state().viewport_frames(1);
    let started = std::time::Instant::now();
    let mut ui_ms = Vec::new();
    for _ in 0..5 {
        let t = std::time::Instant::now();
        h.run_steps(1);
        ui_ms.push(t.elapsed().as_secs_f64() * 1e3);
    }
    let (during, _) = h.state().viewport_frames(1);
    h.state_mut().wait_viewport();
    let frame_ms = started.elapsed().as_secs_f64() * 1e3;
    eprintln!(
        "ism: 5 UI frames {ui_ms:.1?} ms while one viewport frame took {frame_ms:.0} ms (software adapter, debug)"
    );
    assert_eq!(h.state().state().project.render.mode, GiMode::Ism);
    assert!(
        during - before <= 1,
        "the 5 UI frames did not wait for a viewport frame each ({} finished)",
        during - before
    );
}

#[test]
fn render_scale_drops_under_a_tiny_budget_and_returns_to_full_when_idle() {
    if !gpu() {
        return;
    }
    let mut h = harness(egui::vec2(640.0, 400.0));
    *h.state_mut().preview_settings_mut() = bouncelab::app::preview::PreviewSettings { budget_ms: 1.0, adaptive: true };
    let full = |h: &mut Harness<'static, EditorApp>| {
        let mut steps = 0;
        while h.state().viewport_scale() != Some(1.0) && steps < 200 {
            h.run_steps(1);
            h.state_mut().wait_viewport();
            steps += 1;
        }
        steps
    };
    let steps = full(&mut h);
    assert_eq!(h.state().viewport_scale(), Some(1.0), "full resolution after {steps} idle frames at start");
    let mut smallest: f32 = 1.0;
    // Move the light every UI frame, letting each viewport frame finish.
    for k in 0..8 {
        h.state_mut().state_mut().project.scene.desc_mut().lights[0].position.x += 0.01 * k as f32;
        h.run_steps(1);
        h.state_mut().wait_viewport();
        smallest = smallest.min(h.state().viewport_scale().unwrap_or(1.0));
    }
    assert!(smallest <= 0.25, "a 1 ms budget drops the scale to the coarsest steps: {smallest}");
    // Nothing moves any more: the next frames climb back to full resolution.
    let steps = full(&mut h);
    assert_eq!(h.state().viewport_scale(), Some(1.0), "full resolution after {steps} idle frames");
}

#[test]
fn picking_by_ray_matches_the_rasterised_object_ids() {
    if !gpu() {
        return;
    }
    let ctx = common::gpu().expect("adapter");
    let project = Project::load(&default_project_path()).expect("default project");
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    let size = (160, 90);
    r.render(&project.scene, &project.render, size).expect("renders");
    let mut picker = Picker::default();
    let (mut same, mut total, mut objects) = (0, 0, std::collections::BTreeSet::new());
    for y in (5..size.1).step_by(10) {
        for x in (5..size.0).step_by(10) {
            let gpu = r.pick(x, y).expect("gpu pick");
            let cpu = picker.pick(&project.scene, x as f32 + 0.5, y as f32 + 0.5, size);
            same += usize::from(gpu == cpu);
            total += 1;
            objects.extend(cpu);
        }
    }
    assert!(objects.len() >= 3, "the grid covers several objects: {objects:?}");
    assert!(same * 100 >= total * 97, "{same} of {total} pixels agree");
}

#[test]
fn an_idle_editor_stops_rendering_once_the_image_is_final() {
    if !gpu() {
        return;
    }
    let mut h = harness(egui::vec2(640.0, 400.0));
    // A selected light shows its properties panel, whose widgets must not count as edits.
    h.get_by_label("ceiling_light (point)").click();
    // The default project is in rcs: its cache fills and converges first, a round a frame.
    for _ in 0..80 {
        h.run_steps(1);
        h.state_mut().wait_viewport();
        if h.state().renderer().and_then(|r| r.technique_status()).is_some_and(|s| !s.refining) {
            break;
        }
    }
    for _ in 0..2 {
        h.run_steps(1);
        h.state_mut().wait_viewport();
    }
    let revision = h.state().state().project.scene.revision();
    let (frames, _) = h.state().viewport_frames(1);
    for _ in 0..5 {
        h.run_steps(1);
        h.state_mut().wait_viewport();
    }
    assert_eq!(h.state().state().project.scene.revision(), revision, "nothing was edited");
    assert_eq!(h.state().viewport_frames(1).0, frames, "no frame rendered for an unchanged, final view");
    assert_eq!(h.state().viewport_scale(), Some(1.0));
    assert!(!h.state().state().history.is_dirty(), "selecting is not an edit");
}

#[test]
fn a_lost_viewport_device_is_reported_and_the_viewport_renders_again_on_a_new_one() {
    if !gpu() {
        return;
    }
    let mut h = harness(egui::vec2(640.0, 400.0));
    h.state_mut().wait_viewport();
    h.run_steps(1);
    let (before, _) = h.state().viewport_frames(1);
    assert!(before > 0, "the viewport rendered before the loss");
    h.state_mut().simulate_device_loss();
    // The loss surfaces when the frame in flight ends: on a loaded machine that takes more than
    // twenty interface steps (a full suite run beside a release build once needed more).
    let mut steps = 0;
    let start = std::time::Instant::now();
    while h.state().error_shown().is_none() && (steps < 20 || start.elapsed() < std::time::Duration::from_secs(30)) {
        h.run_steps(1);
        std::thread::sleep(std::time::Duration::from_millis(5));
        steps += 1;
    }
    let message = h.state().error_shown().map(str::to_owned).unwrap_or_default();
    assert!(
        message.contains("device was lost") && message.contains("restarted"),
        "dialog after {steps} steps: {message:?}"
    );
    // The new device renders: frames finish again.
    let mut after = before;
    for _ in 0..20 {
        h.run_steps(1);
        h.state_mut().wait_viewport();
        after = h.state().viewport_frames(1).0;
        if after > before {
            break;
        }
    }
    assert!(after > before, "no frame finished on the new device ({before} before the loss, {after} after)");
    assert!(!h.state().state().history.is_dirty(), "the loss did not touch the project");
}
