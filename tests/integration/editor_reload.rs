//! Live reload: a level re-exported under a running editor comes in (its geometry and
//! materials), every authored light, block, weight and edit stays, the status bar names what no
//! longer matches, a file caught half-written is tried again and never loaded broken, and the
//! reload is one undo step.

use crate::common;

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use bouncelab::app::EditorApp;
use bouncelab::import::writer::{GltfWriter, NodeDesc};
use bouncelab::project_file::Project;
use bouncelab::scene::{Light, MeshSource, ObjectRole};
use egui_kittest::Harness;
use glam::Vec3;

fn temp_dir(name: &str) -> PathBuf {
    common::temp_dir("reload", name)
}

/// A level of named boxes (name, centre, size) on a floor, with a grey and a red material, as
/// an exporter writes it.
fn level(boxes: &[(&str, Vec3, f32)], red: f32) -> String {
    let mut w = GltfWriter::default();
    let grey = w.material("grey", [0.6, 0.6, 0.6, 1.0]);
    let redm = w.material("red", [red, 0.1, 0.1, 1.0]);
    let floor = bouncelab::scene::Mesh::cuboid("floor", Vec3::new(8.0, 0.2, 8.0));
    let m = w.mesh("floor", &floor.positions, Some(&floor.normals), &floor.indices, Some(grey));
    w.node(
        NodeDesc {
            name: "floor".into(),
            mesh: Some(m),
            translation: Some(Vec3::new(0.0, -0.1, 0.0)),
            ..NodeDesc::default()
        },
        true,
    );
    for (name, at, size) in boxes {
        let b = bouncelab::scene::Mesh::cuboid(name, Vec3::splat(*size));
        let m = w.mesh(name, &b.positions, Some(&b.normals), &b.indices, Some(redm));
        w.node(NodeDesc { name: (*name).into(), mesh: Some(m), translation: Some(*at), ..NodeDesc::default() }, true);
    }
    let l = w.light("file light", "point", [1.0; 3], 3.0, None);
    w.node(
        NodeDesc {
            name: "file light".into(),
            light: Some(l),
            translation: Some(Vec3::new(0.0, 3.0, 0.0)),
            ..NodeDesc::default()
        },
        true,
    );
    w.to_string_pretty()
}

const FIRST: &[(&str, Vec3, f32)] =
    &[("crate", Vec3::new(1.0, 0.5, 0.0), 1.0), ("pillar", Vec3::new(-1.0, 1.0, 0.0), 0.5)];
const SECOND: &[(&str, Vec3, f32)] =
    &[("pillar", Vec3::new(-2.0, 1.0, 0.5), 0.5), ("column", Vec3::new(2.0, 1.0, 2.0), 0.4)];

/// A project on `level.gltf` with an authored spot, a sampling weight on the pillar and a proxy
/// block, saved as `project.ron`.
fn authored(dir: &Path) -> (Project, PathBuf) {
    let gltf = dir.join("level.gltf");
    std::fs::write(&gltf, level(FIRST, 0.8)).expect("level");
    let mut p = Project::from_gltf(&gltf).expect("level opens");
    let d = p.scene.desc_mut();
    d.lights.push(Light::spot("authored spot", Vec3::new(0.0, 2.5, 1.0), Vec3::NEG_Y, 4.0, 0.2, 0.5));
    let pillar = d.objects.iter().position(|o| o.name == "pillar").expect("pillar");
    d.objects[pillar].sampling_weight = 3.0;
    d.objects.push(bouncelab::precompute::mrt::proxy::block_object(
        "room",
        Vec3::new(-4.0, 0.0, -4.0),
        Vec3::new(4.0, 3.0, 4.0),
        [false; 6],
    ));
    let desc = p.scene.desc().clone();
    p.set_desc(desc).expect("valid");
    let path = dir.join("project.ron");
    p.save(&path).expect("save");
    (p, path)
}

fn object<'a>(p: &'a Project, name: &str) -> Option<&'a bouncelab::scene::Object> {
    p.scene.objects().iter().find(|o| o.name == name)
}

/// The merge itself, without the editor: geometry and materials from the file, the rest kept.
#[test]
fn a_reloaded_asset_brings_the_files_geometry_and_keeps_what_was_authored() {
    let dir = temp_dir("merge");
    let (mut p, _) = authored(&dir);
    std::fs::write(dir.join("level.gltf"), level(SECOND, 0.3)).expect("re-export");
    let report = p.reload_asset(0).expect("reloads");
    assert_eq!(
        (report.matched, report.added.clone(), report.missing.clone()),
        (2, vec!["column".to_owned()], vec!["crate".to_owned()])
    );
    let said = report.to_string();
    assert!(said.contains("column") && said.contains("crate") && said.contains("level.gltf"), "{said}");
    let pillar = object(&p, "pillar").expect("pillar kept");
    assert_eq!(pillar.sampling_weight, 3.0, "the authored weight stays");
    assert!(pillar.transform.translation.abs_diff_eq(Vec3::new(-2.0, 1.0, 0.5), 1e-6), "the file's new place");
    assert!(object(&p, "crate").is_none() && object(&p, "column").is_some());
    assert!(
        object(&p, "room")
            .is_some_and(|o| o.role == ObjectRole::ProxyBlock && matches!(o.source, MeshSource::Cuboid { .. }))
    );
    assert_eq!(p.scene.lights().len(), 2, "the authored spot and the file's light as they were");
    assert!(p.scene.lights().iter().any(|l| l.name == "authored spot"));
    let red = p.scene.materials().iter().find(|m| m.name == "red").expect("red");
    assert!((red.base_color[0] - 0.3).abs() < 1e-6, "the file's material values");
    assert_eq!(p.scene.materials().iter().filter(|m| m.name == "red").count(), 1, "matched by name, not duplicated");
}

fn harness(project: Project, path: PathBuf) -> Harness<'static, EditorApp> {
    let mut h = Harness::builder()
        .with_size(egui::vec2(1280.0, 800.0))
        .wgpu()
        .build_eframe(move |cc| EditorApp::new(cc, project, Some(path)));
    h.run_steps(3);
    h
}

/// Steps the editor until its status bar says `needle` (at most `limit`).
fn step_until(h: &mut Harness<'static, EditorApp>, needle: &str, limit: Duration) -> String {
    let start = Instant::now();
    loop {
        h.run_steps(1);
        let status = h.state().state().status.clone();
        if status.contains(needle) || start.elapsed() > limit {
            return status;
        }
        std::thread::sleep(Duration::from_millis(50));
    }
}

#[test]
fn a_level_re_exported_under_the_running_editor_reloads_keeping_the_authored_lighting() {
    if !common::has_gpu() {
        eprintln!("skipping: no GPU adapter");
        return;
    }
    let dir = temp_dir("editor");
    let (project, path) = authored(&dir);
    let gltf = dir.join("level.gltf");
    let mut h = harness(project, path);
    // Caught half-written: the project does not change, the editor says it tries again.
    let text = level(SECOND, 0.3);
    std::fs::write(&gltf, &text[..text.len() / 3]).expect("partial write");
    let status = step_until(&mut h, "trying again", Duration::from_secs(10));
    assert!(status.contains("level.gltf") && status.contains("trying again"), "{status}");
    assert!(object(&h.state().state().project, "crate").is_some(), "a broken file is never loaded");
    // The exporter finishes: the level reloads.
    std::fs::write(&gltf, &text).expect("whole write");
    let status = step_until(&mut h, "reloaded", Duration::from_secs(15));
    assert!(
        status.contains("reloaded level.gltf") && status.contains("crate") && status.contains("column"),
        "{status}"
    );
    {
        let p = &h.state().state().project;
        assert!(object(p, "crate").is_none() && object(p, "column").is_some());
        assert_eq!(object(p, "pillar").map(|o| o.sampling_weight), Some(3.0));
        assert!(p.scene.lights().iter().any(|l| l.name == "authored spot"));
        assert!(object(p, "room").is_some());
    }
    // One undo step gives the project back as it was, geometry included.
    let state = h.state_mut().state_mut();
    assert_eq!(state.history.undo_label(), Some("Reload level.gltf"));
    state.history.undo(&mut state.project);
    let p = &h.state().state().project;
    assert!(object(p, "crate").is_some() && object(p, "column").is_none(), "undo restores the objects");
    let pillar = object(p, "pillar").expect("pillar");
    assert!(pillar.transform.translation.abs_diff_eq(Vec3::new(-1.0, 1.0, 0.0), 1e-6));
    let crate_mesh = &p.scene.resources().meshes[object(p, "crate").expect("crate").mesh];
    let extent = crate_mesh.bounds().expect("bounds");
    assert!((extent.max - extent.min).abs_diff_eq(Vec3::ONE, 1e-5), "the crate's own mesh, not another node's");
}
