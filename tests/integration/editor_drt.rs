//! Issue 13's editor promise: in `mrt`, moving a clutter object in the editor shows its new
//! shadow and bounce within five seconds, the interface stepping on meanwhile (the DRT rebuild
//! runs on the level job's thread, the viewport keeps the previous result until it lands).

use crate::common;

use std::path::Path;

use bouncelab::app::EditorApp;
use bouncelab::precompute::mrt::dictionary::DictionaryParams;
use bouncelab::precompute::mrt::operators::InterfaceParams;
use bouncelab::render::gi::Readiness;
use bouncelab::settings::{DrtSettings, GiMode, MrtSettings};
use egui_kittest::Harness;

fn gpu() -> bool {
    common::has_gpu()
}

fn counter(h: &Harness<'static, EditorApp>, name: &str) -> u64 {
    h.state().renderer().and_then(|r| r.technique_status()).map_or(0, |s| s.counter(name))
}

/// Steps the editor until the viewport's technique is ready and no level build is in flight.
fn settle(h: &mut Harness<'static, EditorApp>) {
    for _ in 0..20_000 {
        h.run_steps(1);
        h.state_mut().wait_viewport();
        let Some(r) = h.state().renderer() else { continue };
        let building =
            r.technique_status().is_some_and(|t| t.progress.as_deref().is_some_and(|p| p.contains("rebuilding")));
        if !matches!(r.readiness(), Readiness::Pending { .. }) && !building && counter(h, "level builds") > 0 {
            return;
        }
    }
    panic!("mrt never settled");
}

#[test]
fn moving_a_clutter_object_in_the_editor_shows_its_new_shadow_within_five_seconds() {
    if !gpu() {
        return;
    }
    let mut project = bouncelab::suite::scene("clutter").expect("suite").load(Path::new(".")).expect("clutter room");
    // The small test dictionary of tests/integration/drt.rs (cached) and DRT at test sizes.
    let interfaces =
        InterfaceParams { positions: 4, directions: 8, supersample: 1, k_rlf: 48, k_r: 16, enrichment: 1, bands: 2 };
    let dictionary = DictionaryParams { res: 8, k_d: 32, k_b: 16, rays: 256, enrichment: 1, seed: 3, interfaces };
    let drt = DrtSettings { rays: 256, gather_rays: 64, clutter_res: 4, ..DrtSettings::default() };
    project.render.mode = GiMode::Mrt;
    project.render.mrt = MrtSettings { dictionary, drt, ..MrtSettings::default() };
    let mut h = Harness::builder()
        .with_size(egui::vec2(640.0, 400.0))
        .wgpu()
        .build_eframe(move |cc| EditorApp::new(cc, project, None));
    h.run_steps(2);
    h.state_mut().preview_settings_mut().adaptive = false;
    settle(&mut h);
    let builds = counter(&h, "level builds");
    let before = h.state().renderer().expect("renderer").read_hdr().expect("hdr");
    // Move the first box half a metre along x, as a drag would.
    let index = {
        let objects = h.state().state().project.scene.objects();
        objects.iter().position(|o| o.name.starts_with("box_")).expect("a box")
    };
    h.state_mut().state_mut().project.scene.desc_mut().objects[index].transform.translation.x += 0.5;
    let started = std::time::Instant::now();
    let mut steps = 0;
    while counter(&h, "level builds") == builds {
        h.run_steps(1);
        h.state_mut().wait_viewport();
        steps += 1;
        // Five seconds is the product's promise, checked where it is measured (release builds:
        // `cargo test --release`); a debug build under a parallel suite only guards a hang.
        let limit = if cfg!(debug_assertions) { 600.0 } else { 5.0 };
        assert!(started.elapsed().as_secs_f64() < limit, "no rebuilt DRT within {limit} s ({steps} UI frames)");
    }
    let rebuilt = started.elapsed().as_secs_f64();
    settle(&mut h);
    let after = h.state().renderer().expect("renderer").read_hdr().expect("hdr");
    eprintln!(
        "clutter move in the editor: DRT rebuilt after {:.0} ms, {steps} UI frames meanwhile (debug build)",
        rebuilt * 1e3
    );
    assert!(steps > 1, "the interface stepped on while the rebuild ran");
    let diff: f64 = before.iter().zip(&after).map(|(a, b)| f64::from((a[1] - b[1]).abs())).sum();
    assert!(diff > 0.0, "the moved box's new shadow and bounce reached the viewport");
}
