//! The editor driven through its UI with egui_kittest on the software adapter: add a light,
//! undo and redo with the keyboard, switch GI modes, open the buffer inspector, save and reopen.

use crate::common;

use bouncelab::app::EditorApp;
use bouncelab::app::edits::Selection;
use bouncelab::project_file::{Project, default_project_path};
use bouncelab::settings::GiMode;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable as _;

fn harness() -> Harness<'static, EditorApp> {
    harness_sized(egui::vec2(1280.0, 800.0))
}

fn harness_sized(size: egui::Vec2) -> Harness<'static, EditorApp> {
    let path = default_project_path();
    let project = Project::load(&path).expect("default project");
    let mut h =
        Harness::builder().with_size(size).wgpu().build_eframe(move |cc| EditorApp::new(cc, project, Some(path)));
    // The viewport repaints every frame, so step a fixed number of frames instead of `run`.
    h.run_steps(3);
    settle(&mut h);
    h
}

/// Lets the viewport catch up with the editor's state: its frames render on their own device
/// while the UI steps on, so wait for the frame in flight, step (which submits a frame of the
/// current state) and wait for that one too.
/// Steps until the viewport's technique has stopped refining (`rcs`: its cache filled and its
/// bounce passes converged; each frame places one round), at most `limit` frames.
fn until_final(h: &mut Harness<'static, EditorApp>, limit: usize) {
    for _ in 0..limit {
        h.run_steps(1);
        h.state_mut().wait_viewport();
        if h.state().renderer().and_then(|r| r.technique_status()).is_some_and(|s| !s.refining) {
            break;
        }
    }
}

fn settle(h: &mut Harness<'static, EditorApp>) {
    for _ in 0..2 {
        h.state_mut().wait_viewport();
        h.run_steps(1);
    }
    h.state_mut().wait_viewport();
}

#[test]
fn add_a_light_undo_and_redo() {
    if !common::has_gpu() {
        eprintln!("skipping: no GPU adapter");
        return;
    }
    let mut h = harness();
    h.get_by_label("Add").click();
    h.run_steps(2);
    h.get_by_label("Spot light").click();
    h.run_steps(2);
    let state = h.state().state();
    assert_eq!(state.project.scene.lights().len(), 2);
    assert_eq!(state.selection, Selection::Light(1));
    assert!(state.history.is_dirty());
    // The properties panel shows the new light.
    h.get_by_label("Cast shadows");
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Z);
    h.run_steps(2);
    assert_eq!(h.state().state().project.scene.lights().len(), 1, "undo removes it");
    assert!(!h.state().state().history.is_dirty());
    h.key_press_modifiers(egui::Modifiers::COMMAND | egui::Modifiers::SHIFT, egui::Key::Z);
    h.run_steps(2);
    assert_eq!(h.state().state().project.scene.lights().len(), 2, "redo adds it back");
}

#[test]
fn switch_mode_and_inspect_buffers() {
    if !common::has_gpu() {
        return;
    }
    let mut h = harness();
    h.get_by_label("reference").click();
    h.run_steps(2);
    assert_eq!(h.state().state().project.render.mode, GiMode::Reference);
    h.run_steps(3);
    settle(&mut h);
    assert!(
        !h.state().state().status.contains("failed"),
        "the viewport shows the path tracer: {}",
        h.state().state().status
    );
    h.get_by_label("direct").click();
    h.run_steps(2);
    assert_eq!(h.state().state().project.render.mode, GiMode::Direct);
    // Radiance cache splatting fills its cache over the frames and says so.
    h.get_by_label("rcs").click();
    h.run_steps(3);
    settle(&mut h);
    assert_eq!(h.state().state().project.render.mode, GiMode::Rcs);
    assert!(!h.state().state().status.contains("failed"), "{}", h.state().state().status);
    let progress = h.state().renderer().and_then(|r| r.technique_status()).and_then(|s| s.progress);
    assert!(progress.as_deref().is_some_and(|p| p.starts_with("rcs: ")), "rcs progress line: {progress:?}");
    h.get_by_label("ism").click();
    h.run_steps(3);
    settle(&mut h);
    assert_eq!(h.state().state().project.render.mode, GiMode::Ism);
    assert!(!h.state().state().status.contains("failed"), "{}", h.state().state().status);
    // The ISM technique's own buffers are there while it is active, and its memory is.
    let renderer = h.state().renderer().expect("renderer");
    assert!(renderer.read_buffer("ism_confidence").is_ok(), "ism buffers readable in ism");
    let ism_bytes = |r: &bouncelab::render::Renderer| {
        r.technique_gpu_bytes().into_iter().find(|(m, _)| *m == GiMode::Ism).map_or(0, |(_, b)| b)
    };
    assert!(ism_bytes(renderer) > 0);
    h.get_by_label("reference").click();
    h.run_steps(3);
    settle(&mut h);
    let renderer = h.state().renderer().expect("renderer");
    assert_eq!(ism_bytes(renderer), 0, "switching away releases the ISM memory");
    assert!(renderer.read_buffer("ism_confidence").is_err(), "ism buffers are not listed in reference");
    h.get_by_label("direct").click();
    h.run_steps(2);
    h.get_by_label("Buffer inspector").click();
    h.run_steps(3);
    h.get_by_label("auto range");
    let img = h.render().expect("renders on the software adapter");
    assert_eq!((img.width(), img.height()), (1280, 800));
}

#[test]
fn save_and_reopen_to_the_same_state() {
    if !common::has_gpu() {
        return;
    }
    let mut h = harness();
    h.get_by_label("Add").click();
    h.run_steps(2);
    h.get_by_label("Point light").click();
    h.run_steps(2);
    let dir = std::env::temp_dir().join(format!("bouncelab-ui-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("dir");
    let path = dir.join("saved.ron");
    h.state_mut().save_to(&path);
    h.run_steps(1);
    assert!(!h.state().state().history.is_dirty());
    let saved = h.state().state().project.to_ron(&path).expect("ron");
    let reopened = Project::load(&path).expect("reopens");
    assert_eq!(reopened.to_ron(&path).expect("ron"), saved);
    assert_eq!(reopened.scene.lights().len(), 2);
}

#[test]
fn move_a_spot_light_with_the_gizmo() {
    use bouncelab::app::gizmo::View;
    use glam::{Vec2, Vec3};
    if !common::has_gpu() {
        return;
    }
    let mut h = harness();
    h.get_by_label("Add").click();
    h.run_steps(2);
    h.get_by_label("Spot light").click();
    h.run_steps(3);
    let rect = h.state().viewport_rect().expect("viewport drawn");
    let state = h.state().state();
    let before = state.project.scene.lights()[1].position;
    let view = View { camera: *state.project.scene.camera(), size: Vec2::new(rect.width(), rect.height()) };
    let to_screen = |p: Vec3| {
        let s = view.project(p).expect("visible");
        rect.min + egui::vec2(s.x, s.y)
    };
    // Grab the X handle near its tip and drag it 0.4 m along +X.
    let len = view.world_size(before, 70.0);
    let grab = to_screen(before + Vec3::X * len * 0.8);
    let target = to_screen(before + Vec3::X * (len * 0.8 + 0.4));
    h.hover_at(grab);
    h.run_steps(1);
    h.drag_at(grab);
    h.run_steps(1);
    for k in 1..=4 {
        h.hover_at(grab + (target - grab) * (k as f32 / 4.0));
        h.run_steps(1);
    }
    h.drop_at(target);
    h.run_steps(2);
    let after = h.state().state().project.scene.lights()[1].position;
    assert!((after.x - before.x - 0.4).abs() < 0.02, "moved by {} (want 0.4)", after.x - before.x);
    assert!((after.y - before.y).abs() < 1e-4 && (after.z - before.z).abs() < 1e-4, "only along X");
    assert_eq!(h.state().state().history.undo_label(), Some("Move"), "the drag is one undo step");
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Z);
    h.run_steps(2);
    assert_eq!(h.state().state().project.scene.lights()[1].position, before);
}

#[test]
fn snapshot_of_the_default_layout() {
    if !common::has_gpu() {
        return;
    }
    let mut h = harness();
    h.run_steps(2);
    // The default project is in rcs: the snapshot shows its converged cache.
    until_final(&mut h, 80);
    settle(&mut h);
    assert_eq!(h.state().viewport_scale(), Some(1.0), "idle: the viewport shows a full-resolution image");
    // Timings and frame times change from run to run: mask the bottom dock and status bar.
    let timings = h.get_by_label("Timings").rect();
    h.mask(egui::Rect::from_min_max(egui::pos2(0.0, timings.min.y), egui::pos2(1280.0, 800.0)));
    h.snapshot("editor_default_layout");
}

#[test]
fn ism_confidence_and_reference_comparison_in_the_inspector() {
    if !common::has_gpu() {
        return;
    }
    let mut h = harness();
    h.get_by_label("ism").click();
    h.run_steps(4);
    assert_eq!(h.state().state().project.render.mode, GiMode::Ism);
    h.get_by_label("overlays").click();
    h.get_by_label("Buffer inspector").click();
    h.run_steps(2);
    settle(&mut h);
    h.state_mut().inspect("ism_confidence");
    h.get_by_label("Refresh").click();
    h.run_steps(1);
    settle(&mut h);
    h.run_steps(1);
    let (name, size) = h.state().inspected();
    assert_eq!(name, "ism_confidence");
    assert!(size.is_some_and(|(w, h)| w > 0 && h > 0), "the confidence buffer was read back");
    h.get_by_label("Compare with the reference path tracer").click();
    h.run_steps(6);
    settle(&mut h);
    assert!(!h.state().state().status.contains("failed"), "{}", h.state().state().status);
    let img = h.render().expect("renders");
    assert_eq!((img.width(), img.height()), (1280, 800));
}

#[test]
fn a_project_that_cannot_be_opened_shows_the_error_in_the_window() {
    if !common::has_gpu() {
        return;
    }
    let dir = std::env::temp_dir().join(format!("bouncelab-badstart-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("dir");
    let bad = dir.join("broken.ron");
    std::fs::write(&bad, "(format_version: 1, assets: [").expect("write");
    let startup = bouncelab::app::open_or_fallback(&bad, None).expect("a fallback project");
    let error = startup.error.clone().expect("the reason is kept for the window");
    assert!(error.contains("broken.ron") && error.contains("default project"), "{error}");
    assert_eq!(startup.path, None, "saving must not overwrite the broken file unasked");
    assert!(!startup.project.scene.objects().is_empty(), "the default project is open instead");
    let project = startup.project;
    let mut h = Harness::builder().with_size(egui::vec2(1280.0, 800.0)).wgpu().build_eframe(move |cc| {
        let mut app = EditorApp::new(cc, project, None);
        app.show_error(error);
        app
    });
    h.run_steps(2);
    assert!(h.state().error_shown().is_some_and(|m| m.contains("broken.ron")));
    h.get_by_label("OK").click();
    h.run_steps(2);
    assert!(h.state().error_shown().is_none(), "OK dismisses it");
    settle(&mut h);
}

#[test]
fn the_outliner_filters_by_name_and_lays_out_only_visible_rows() {
    if !common::has_gpu() {
        return;
    }
    let path = default_project_path();
    let mut project = Project::load(&path).expect("default project");
    let template = project.scene.objects()[0].clone();
    let first = project.scene.objects().len();
    for k in 0..1500 {
        let mut o = template.clone();
        o.name = format!("copy {k}");
        o.visible = false;
        project.scene.desc_mut().objects.push(o);
    }
    let mut h = Harness::builder()
        .with_size(egui::vec2(1280.0, 800.0))
        .wgpu()
        .build_eframe(move |cc| EditorApp::new(cc, project, Some(path)));
    h.run_steps(3);
    assert!(h.query_by_label("copy 0").is_some(), "the first rows are shown");
    assert!(h.query_by_label("copy 1499").is_none(), "rows below the fold are not laid out");
    h.ctx.data_mut(|d| d.insert_temp(egui::Id::unique("outliner filter"), "copy 1499".to_owned()));
    h.run_steps(3);
    assert!(h.query_by_label("copy 1499").is_some(), "the filter finds it");
    assert!(h.query_by_label("copy 0").is_none() && h.query_by_label("floor").is_none(), "and hides the rest");
    h.get_by_label("copy 1499").click();
    h.run_steps(2);
    assert_eq!(h.state().state().selection, Selection::Object(first + 1499));
    settle(&mut h);
}

/// A fresh folder for one recovery test: two projects (copies of the default one) and the
/// folder the editor keeps its recovery files in, standing for a fresh home folder.
fn recovery_fixture(name: &str) -> (std::path::PathBuf, std::path::PathBuf, std::path::PathBuf) {
    let dir = std::env::temp_dir().join(format!("bouncelab-recovery-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("dir");
    let project = Project::load(&default_project_path()).expect("default project");
    let (a, b) = (dir.join("a.ron"), dir.join("b.ron"));
    project.save(&a).expect("a.ron");
    project.save(&b).expect("b.ron");
    (a, b, dir.join("home-data"))
}

/// An editor on `path` with its recovery files in `recovery`.
fn editor_at(path: &std::path::Path, recovery: &std::path::Path) -> Harness<'static, EditorApp> {
    let (path, recovery) = (path.to_owned(), recovery.to_owned());
    let project = Project::load(&path).expect("project");
    let mut h = Harness::builder()
        .with_size(egui::vec2(1280.0, 800.0))
        .wgpu()
        .build_eframe(move |cc| EditorApp::with_recovery(cc, project, Some(path), Some(recovery)));
    h.run_steps(2);
    h
}

/// Adds a point light through the menus.
fn add_point_light(h: &mut Harness<'static, EditorApp>) {
    h.get_by_label("Add").click();
    h.run_steps(2);
    h.get_by_label("Point light").click();
    h.run_steps(2);
}

fn has_gpu() -> bool {
    common::has_gpu()
}

#[test]
fn restored_work_goes_back_to_its_own_project_never_the_open_one() {
    if !has_gpu() {
        return;
    }
    let (a, b, home) = recovery_fixture("cross");
    let b_before = std::fs::read(&b).expect("b");
    let mut first = editor_at(&a, &home);
    add_point_light(&mut first);
    assert!(first.state().flush_autosave().is_some_and(|f| f.exists()), "a's edit is autosaved");
    settle(&mut first);
    // Killed: the instance is gone without a clean exit, its lock with it.
    drop(first);
    let mut second = editor_at(&b, &home);
    let offered = second.state().recovery_offered().expect("the dialog is shown");
    assert!(offered.contains("a.ron") && offered.contains("UTC") && offered.contains("1 edit,"), "{offered}");
    second.get_by_label("Restore").click();
    second.run_steps(2);
    let state = second.state().state();
    assert_eq!(state.path.as_deref().and_then(|p| p.file_name()), Some(std::ffi::OsStr::new("a.ron")), "a reopened");
    assert_eq!(state.project.scene.lights().len(), 2, "with the edit");
    assert!(state.history.is_dirty(), "restored work is unsaved until saved");
    let path = state.path.clone().expect("a's path");
    second.state_mut().save_to(&path);
    assert_eq!(std::fs::read(&b).expect("b"), b_before, "b.ron untouched");
    assert_eq!(Project::load(&a).expect("a").scene.lights().len(), 2, "a.ron has the work");
    settle(&mut second);
}

#[test]
fn autosave_writes_after_an_idle_wait_without_any_repaint() {
    if !has_gpu() {
        return;
    }
    let (a, _, home) = recovery_fixture("idle");
    let mut h = editor_at(&a, &home);
    add_point_light(&mut h);
    add_point_light(&mut h);
    // No frame runs from here on: the editor is idle, as a real one is after the last edit.
    std::thread::sleep(std::time::Duration::from_secs(4));
    let files: Vec<_> = std::fs::read_dir(&home)
        .expect("recovery folder")
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "ron"))
        .collect();
    assert_eq!(files.len(), 1, "one recovery file: {files:?}");
    let saved = bouncelab::app::recovery::RecoveryFile::read(&files[0]).expect("a recovery file");
    assert_eq!(saved.scene.lights.len(), 3, "both edits are on disk");
    assert_eq!(saved.edits, 2);
    assert_eq!(saved.project.as_deref().and_then(|p| p.file_name()), Some(std::ffi::OsStr::new("a.ron")));
    settle(&mut h);
    // Killed now: the next editor on the same project gets both edits back.
    drop(h);
    let mut next = editor_at(&a, &home);
    let offered = next.state().recovery_offered().expect("offered");
    assert!(offered.contains("a.ron") && offered.contains("2 edits"), "{offered}");
    next.state_mut().answer_recovery(true);
    assert_eq!(next.state().state().project.scene.lights().len(), 3);
    settle(&mut next);
}

#[test]
fn a_second_instance_neither_offers_nor_deletes_a_running_ones_autosave() {
    if !has_gpu() {
        return;
    }
    let (a, b, home) = recovery_fixture("instances");
    let mut first = editor_at(&a, &home);
    add_point_light(&mut first);
    let file = first.state().flush_autosave().expect("first's recovery file");
    assert!(file.exists());
    let mut second = editor_at(&a, &home);
    assert_eq!(second.state().recovery_offered(), None, "the first instance still runs");
    add_point_light(&mut second);
    second.state_mut().save_to(&b);
    second.state().flush_autosave();
    assert!(file.exists(), "saving in another instance leaves the first's autosave");
    drop(second);
    settle(&mut first);
    drop(first);
    let third = editor_at(&a, &home);
    assert!(third.state().recovery_offered().is_some_and(|m| m.contains("a.ron")), "offered once the first is gone");
}

#[test]
fn the_default_project_is_never_overwritten() {
    if !has_gpu() {
        return;
    }
    let path = default_project_path();
    let before = std::fs::read(&path).expect("default project");
    let mut h = harness();
    assert!(h.state().state().read_only, "opened read-only-safe");
    add_point_light(&mut h);
    h.state_mut().save_to(&path);
    assert!(h.state().state().status.contains("never overwritten"), "{}", h.state().state().status);
    assert!(h.state().state().history.is_dirty(), "nothing was saved");
    assert_eq!(std::fs::read(&path).expect("default project"), before);
    settle(&mut h);
}

#[test]
fn the_gi_panel_says_when_the_view_cannot_be_what_was_asked_for() {
    if !has_gpu() {
        return;
    }
    let path = default_project_path();
    let mut project = Project::load(&path).expect("default project");
    project.scene.desc_mut().lights.clear();
    let mut h = Harness::builder()
        .with_size(egui::vec2(1280.0, 800.0))
        .wgpu()
        .build_eframe(move |cc| EditorApp::new(cc, project, Some(path)));
    h.run_steps(3);
    settle(&mut h);
    h.run_steps(1);
    assert!(h.query_by_label_contains("the scene has no light").is_some(), "said in the GI panel");
}

#[test]
fn restored_work_on_the_open_project_is_autosaved_before_the_old_file_goes() {
    if !has_gpu() {
        return;
    }
    let (a, _, home) = recovery_fixture("same");
    let mut first = editor_at(&a, &home);
    add_point_light(&mut first);
    first.state().flush_autosave();
    settle(&mut first);
    drop(first);
    let mut second = editor_at(&a, &home);
    assert!(second.state().recovery_offered().is_some());
    second.state_mut().answer_recovery(true);
    let own = second.state().flush_autosave().expect("this instance's recovery file");
    assert!(own.exists(), "the restored work is on disk again");
    let saved = bouncelab::app::recovery::RecoveryFile::read(&own).expect("recovery file");
    assert_eq!(saved.scene.lights.len(), 2, "with the restored edit");
    assert_eq!(saved.edits, 1, "and its count, which the cleared undo history does not hold");
    let files =
        std::fs::read_dir(&home).expect("dir").flatten().filter(|e| e.path().extension().is_some_and(|x| x == "ron"));
    assert_eq!(files.count(), 1, "the old file went once the new one held the work");
    settle(&mut second);
}

#[test]
fn opening_another_project_or_a_new_one_keeps_unsaved_work_for_later() {
    if !has_gpu() {
        return;
    }
    let (a, b, home) = recovery_fixture("switch");
    let mut h = editor_at(&a, &home);
    add_point_light(&mut h);
    h.state_mut().open(&b);
    h.run_steps(1);
    assert_eq!(h.state().recovery_offered(), None, "b has nothing to offer");
    // File → New from b: the untitled project is not b's.
    add_point_light(&mut h);
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::N);
    h.run_steps(1);
    assert_eq!(h.state().state().opened, None);
    assert!(!h.state().state().read_only);
    // Back to a: the work left there unsaved is offered.
    h.state_mut().open(&a);
    h.run_steps(1);
    let offered = h.state().recovery_offered().expect("a's unsaved work");
    assert!(offered.contains("a.ron"), "{offered}");
    h.state_mut().answer_recovery(true);
    assert_eq!(h.state().state().project.scene.lights().len(), 2);
    h.state_mut().open(&b);
    h.run_steps(1);
    assert!(h.state().recovery_offered().is_some_and(|m| m.contains("b.ron")), "b's too");
    settle(&mut h);
}

/// Steps the editor until the GI panel shows `sshgi`'s measured share of the view's indirect
/// light from surfaces off screen or hidden; returns (missing %, off screen %).
fn measured_unseen_light(h: &mut Harness<'static, EditorApp>) -> (f64, f64) {
    use egui_kittest::kittest::NodeT as _;
    let start = std::time::Instant::now();
    loop {
        h.run_steps(1);
        let text = h
            .query_by_label_contains("of this view's indirect light leaves")
            .and_then(|node| node.accesskit_node().value());
        if let Some(text) = text {
            let percent = |after: &str| -> f64 {
                let at = text.find(after).map_or(0, |i| i + after.len());
                text[at..].split('%').next().and_then(|n| n.trim().parse().ok()).expect("a percentage")
            };
            return (percent(""), percent("("));
        }
        assert!(start.elapsed().as_secs() < 180, "no measurement in the GI panel after three minutes");
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
}

#[test]
fn the_gi_panel_measures_the_light_sshgi_cannot_see_and_again_when_the_view_moves() {
    if !has_gpu() {
        return;
    }
    let mut h = harness();
    h.get_by_label("sshgi").click();
    let (whole, _) = measured_unseen_light(&mut h);
    // The Cornell box from its open side: only the hidden faces (the blocks' backs and tops).
    assert!((5.0..=40.0).contains(&whole), "the whole box in view misses {whole}%");
    // The same box in a project of its own whose camera looks down at the floor, close up.
    let mut project = Project::load(&default_project_path()).expect("default project");
    project.render.mode = GiMode::Sshgi;
    let eye = glam::Vec3::new(0.0, 1.2, 0.5);
    project.scene.set_camera(bouncelab::scene::Camera::look_at(eye, glam::Vec3::new(0.0, 0.0, 0.3), 0.5));
    let dir = std::env::temp_dir().join(format!("bouncelab-unseen-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("dir");
    let file = dir.join("close_up.ron");
    project.save(&file).expect("save");
    h.state_mut().open(&file);
    let (missing, off_screen) = measured_unseen_light(&mut h);
    assert!(
        off_screen > 50.0 && missing >= off_screen,
        "a close-up of the floor: {missing}% missing, {off_screen}% off screen"
    );
    settle(&mut h);
    let _ = std::fs::remove_dir_all(&dir);
}

/// Clicks the widgets labelled `labels` one after the other through accessibility (so widgets
/// below the fold are reached too), two frames after each.
fn click_through(h: &mut Harness<'static, EditorApp>, labels: &[&str]) {
    for label in labels {
        h.get_by_label(label).click_accesskit();
        h.run_steps(2);
    }
}

#[test]
fn a_sky_chosen_in_the_scene_panel_is_one_undo_step_shown_in_the_scenes_units() {
    if !common::has_gpu() {
        eprintln!("skipping: no GPU adapter");
        return;
    }
    let mut h = harness();
    // The Scene section sits below the fold of the GI panel: click through accessibility.
    click_through(&mut h, &["Scene", "sky", "constant colour"]);
    settle(&mut h);
    let state = h.state().state();
    assert!(
        matches!(state.project.scene.environment().sky, bouncelab::scene::Sky::Constant(_)),
        "{:?}",
        state.project.scene.environment()
    );
    assert!(state.history.is_dirty(), "an undo step");
    // The intensity shows in the scene's light units.
    assert!(h.query_all_by_label("intensity (W/(sr m²))").count() > 0, "the intensity in W/(sr m²)");
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Z);
    h.run_steps(2);
    assert_eq!(h.state().state().project.scene.environment().sky, bouncelab::scene::Sky::None, "undone");
}

/// A material's emission texture is picked among the scene's images in the properties panel:
/// one undo step, which the keyboard takes back.
#[test]
fn an_emission_texture_picked_in_the_material_panel_is_one_undo_step() {
    if !common::has_gpu() {
        eprintln!("skipping: no GPU adapter");
        return;
    }
    let path = default_project_path();
    let mut project = Project::load(&path).expect("default project");
    let screen = bouncelab::scene::Image { width: 2, height: 1, rgba8: vec![255, 255, 255, 255, 0, 0, 0, 255] };
    let resources = bouncelab::scene::Resources { images: vec![screen], ..project.scene.resources().clone() };
    project.scene = bouncelab::scene::Scene::new(project.scene.desc().clone(), resources).expect("scene");
    let material = project.scene.objects()[0].material;
    let mut h = Harness::builder()
        .with_size(egui::vec2(1280.0, 800.0))
        .wgpu()
        .build_eframe(move |cc| EditorApp::new(cc, project, Some(path)));
    h.run_steps(3);
    h.state_mut().state_mut().selection = Selection::Object(0);
    h.run_steps(2);
    h.get_by_label_contains("Material \"").click_accesskit();
    h.run_steps(2);
    click_through(&mut h, &["emission texture", "image 0 (2x1)"]);
    settle(&mut h);
    let picked = h.state().state().project.scene.materials()[material].emissive_texture;
    assert_eq!(picked.map(|t| t.image), Some(0), "the picked image");
    assert!(h.state().state().history.is_dirty(), "an undo step");
    h.key_press_modifiers(egui::Modifiers::COMMAND, egui::Key::Z);
    h.run_steps(2);
    assert_eq!(h.state().state().project.scene.materials()[material].emissive_texture, None, "undone");
    settle(&mut h);
}

/// Every mode's settings panel, at the editor's default window size, names each of its inputs
/// (egui_kittest's accessibility check: a screen reader and `get_by_label` reach them). The
/// sshgi panel's voxel depth range once had two unnamed fields, which stopped `ui_bench`.
#[test]
fn every_modes_settings_panel_names_its_inputs() {
    if !common::has_gpu() {
        return;
    }
    // The editor's default window.
    let mut h = harness_sized(egui::vec2(1400.0, 860.0));
    for mode in GiMode::ALL {
        h.get_by_label(mode.name()).click();
        h.run_steps(3);
        let unnamed = h.unnamed_widgets();
        assert!(unnamed.is_empty(), "{}'s panel: inputs without a name:\n{}", mode.name(), unnamed.join("\n"));
    }
    settle(&mut h);
}
