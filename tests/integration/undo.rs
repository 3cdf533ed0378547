//! Property test: any sequence of edits followed by undo-all gives back the original project
//! byte for byte, and redo-all gives back the edited one.

use bouncelab::app::edits::{self, Selection};
use bouncelab::app::history::History;
use bouncelab::project_file::{Project, default_project_path};
use bouncelab::scene::{LightKind, ObjectRole};
use bouncelab::settings::GiMode;
use proptest::prelude::*;

#[derive(Clone, Debug)]
enum Op {
    AddLight(u8),
    AddBox(bool),
    Delete(u8, bool),
    Duplicate(u8, bool),
    MoveLight(u8, f32),
    SetWeight(u8, f32),
    DragIntensity(u8, Vec<f32>),
    SetMode(bool),
    /// The GI panel's way: `begin` and change, with the commit left to a later idle frame (a
    /// structural edit or undo may come first).
    SetModeUncommitted(bool),
    Undo,
    Redo,
}

fn op() -> impl Strategy<Value = Op> {
    prop_oneof![
        (0u8..3).prop_map(Op::AddLight),
        any::<bool>().prop_map(Op::AddBox),
        (any::<u8>(), any::<bool>()).prop_map(|(i, l)| Op::Delete(i, l)),
        (any::<u8>(), any::<bool>()).prop_map(|(i, l)| Op::Duplicate(i, l)),
        (any::<u8>(), -1.0f32..1.0).prop_map(|(i, d)| Op::MoveLight(i, d)),
        (any::<u8>(), 0.0f32..5.0).prop_map(|(i, w)| Op::SetWeight(i, w)),
        (any::<u8>(), prop::collection::vec(0.0f32..10.0, 1..5)).prop_map(|(i, v)| Op::DragIntensity(i, v)),
        any::<bool>().prop_map(Op::SetMode),
        any::<bool>().prop_map(Op::SetModeUncommitted),
        Just(Op::Undo),
        Just(Op::Redo),
    ]
}

fn apply(project: &mut Project, history: &mut History, op: &Op) {
    let lights = project.scene.lights().len();
    let objects = project.scene.objects().len();
    let pick = |i: u8, n: usize| (n > 0).then(|| i as usize % n);
    match op {
        Op::AddLight(k) => {
            let kind = [
                LightKind::Point,
                LightKind::Spot { inner_cone_angle: 0.3, outer_cone_angle: 0.6 },
                LightKind::Directional,
            ][*k as usize];
            edits::add_light(project, history, kind).expect("add light");
        }
        Op::AddBox(proxy) => {
            edits::add_box(project, history, if *proxy { ObjectRole::ProxyBlock } else { ObjectRole::Clutter })
                .expect("add box");
        }
        Op::Delete(i, light) | Op::Duplicate(i, light) => {
            let sel = match (*light, pick(*i, if *light { lights } else { objects })) {
                (true, Some(k)) => Selection::Light(k),
                (false, Some(k)) => Selection::Object(k),
                _ => return,
            };
            if matches!(op, Op::Delete(..)) {
                edits::delete(project, history, sel).expect("delete");
            } else {
                edits::duplicate(project, history, sel).expect("duplicate");
            }
        }
        Op::MoveLight(i, d) => {
            let Some(k) = pick(*i, lights) else { return };
            history.begin("Move light", project);
            project.scene.desc_mut().lights[k].position.x += d;
            history.commit(project);
        }
        Op::SetWeight(i, w) => {
            let Some(k) = pick(*i, objects) else { return };
            history.begin("Sampling weight", project);
            project.scene.desc_mut().objects[k].sampling_weight = *w;
            history.commit(project);
        }
        Op::DragIntensity(i, values) => {
            let Some(k) = pick(*i, lights) else { return };
            // A drag: many frames of changes, one undo step.
            for v in values {
                history.begin("Intensity", project);
                project.scene.desc_mut().lights[k].intensity = *v;
            }
            history.commit(project);
        }
        Op::SetMode(direct) => {
            history.begin("GI mode", project);
            project.render.mode = if *direct { GiMode::Direct } else { GiMode::Reference };
            history.commit(project);
        }
        Op::SetModeUncommitted(direct) => {
            history.begin("GI settings", project);
            project.render.mode = if *direct { GiMode::Direct } else { GiMode::Reference };
        }
        Op::Undo => {
            history.undo(project);
        }
        Op::Redo => {
            history.redo(project);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]

    #[test]
    fn undo_all_restores_the_original_bytes(ops in prop::collection::vec(op(), 1..24)) {
        let path = default_project_path();
        let mut project = Project::load(&path).expect("default project");
        let original = project.to_ron(&path).expect("ron");
        let mut history = History::default();
        for op in &ops {
            apply(&mut project, &mut history, op);
        }
        let edited = project.to_ron(&path).expect("ron");
        let mut steps = 0;
        while history.undo(&mut project).is_some() {
            steps += 1;
        }
        prop_assert_eq!(project.to_ron(&path).expect("ron"), original);
        prop_assert!(!history.is_dirty());
        for _ in 0..steps {
            prop_assert!(history.redo(&mut project).is_some());
        }
        prop_assert_eq!(project.to_ron(&path).expect("ron"), edited);
        // The scene stays consistent (meshes match objects) after all of it.
        prop_assert!(project.scene.validate().is_ok());
        // (Objects with one mesh source share a mesh, so there may be fewer meshes than objects.)
        let meshes = project.scene.resources().meshes.len();
        prop_assert!(project.scene.objects().iter().all(|o| o.mesh < meshes));
    }
}

#[test]
fn a_drag_is_one_step_and_dirty_tracks_saves() {
    let path = default_project_path();
    let mut project = Project::load(&path).expect("default project");
    let mut history = History::default();
    assert!(!history.is_dirty());
    for v in [1.0, 2.0, 3.0] {
        history.begin("Intensity", &project);
        project.scene.desc_mut().lights[0].intensity = v;
    }
    history.commit(&project);
    assert!(history.is_dirty());
    assert_eq!(history.undo_label(), Some("Intensity"));
    history.undo(&mut project);
    assert_eq!(project.scene.lights()[0].intensity, 2.5, "one undo reverts the whole drag");
    assert!(!history.is_dirty(), "back at the saved state");
    history.redo(&mut project);
    assert_eq!(project.scene.lights()[0].intensity, 3.0);
    history.mark_saved();
    assert!(!history.is_dirty());
    let sel = edits::add_light(&mut project, &mut history, LightKind::Point).expect("add");
    assert_eq!(sel, Selection::Light(1));
    assert!(history.is_dirty());
}

#[test]
fn clutter_from_a_gltf_joins_the_project_and_saves() {
    let path = default_project_path();
    let mut project = Project::load(&path).expect("default project");
    let mut history = History::default();
    let objects = project.scene.objects().len();
    let sel = edits::add_clutter_asset(&mut project, &mut history, std::path::Path::new("assets/cornell_box.gltf"))
        .expect("adds");
    assert_eq!(sel, Selection::Object(objects));
    let in_file = bouncelab::import::import_gltf(std::path::Path::new("assets/cornell_box.gltf"))
        .expect("asset")
        .scene
        .objects
        .len();
    assert_eq!(project.scene.objects().len(), objects + in_file);
    assert!(project.scene.objects()[objects..].iter().all(|o| o.role == ObjectRole::Clutter));
    let dir = std::env::temp_dir().join(format!("bouncelab-clutter-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("dir");
    let saved = dir.join("with_clutter.ron");
    project.save(&saved).expect("saves");
    let reopened = Project::load(&saved).expect("reopens");
    assert_eq!(reopened.scene.desc(), project.scene.desc());
    assert_eq!(reopened.assets.len(), 2);
    history.undo(&mut project);
    assert_eq!(project.scene.objects().len(), objects);
    assert!(edits::add_clutter_asset(&mut project, &mut history, std::path::Path::new("nowhere.gltf")).is_err());
}

#[test]
fn fitting_proxy_blocks_is_one_undo_step_and_never_replaces_blocks() {
    let mut project =
        bouncelab::suite::scene("rooms").expect("suite scene").load(std::path::Path::new(".")).expect("rooms");
    let before = project.scene.objects().len();
    let mut history = History::default();
    let fitted = edits::fit_proxy_blocks(&mut project, &mut history).expect("fits");
    assert_eq!(fitted.count, 3, "the suite's rooms fit to one block each");
    assert_eq!(fitted.selection, Selection::Object(before));
    assert!(fitted.gaps.is_empty(), "{:?}", fitted.gaps);
    assert!(fitted.status().contains("covering every enclosed space"), "{}", fitted.status());
    let blocks = || project.scene.objects().iter().filter(|o| o.role == ObjectRole::ProxyBlock).count();
    assert_eq!(blocks(), 3);
    // Again: refused, so an artist's edits to the fitted blocks are never overwritten.
    let again = edits::fit_proxy_blocks(&mut project, &mut history).expect_err("blocks exist");
    assert!(again.to_string().contains("already"), "{again}");
    history.undo(&mut project).expect("one step");
    assert_eq!(project.scene.objects().len(), before);
}

#[test]
fn a_partial_fit_names_what_it_leaves_out_in_the_status_line() {
    // Two storeys joined by a stairwell: each storey gets its blocks, the stairwell is named.
    let dir = crate::common::temp_dir("undo", "partial_fit");
    let path = dir.join("stacked.gltf");
    let level = bouncelab::precompute::mrt::fit::shapes::stacked();
    std::fs::write(&path, bouncelab::suite::shapes::gltf(&level).to_string_pretty()).expect("write");
    let mut project = bouncelab::project_file::Project::from_gltf(&path).expect("stacked");
    let mut history = History::default();
    let fitted = edits::fit_proxy_blocks(&mut project, &mut history).expect("fits");
    assert!(fitted.count >= 2, "a block per storey");
    let status = fitted.status();
    assert!(status.contains("the fit is partial") && status.contains("between storeys at x 4.0..5.5"), "{status}");
}
