//! Project files: round trip byte-identical, saving twice gives the same bytes, relative asset
//! paths, atomic save, and load errors with line and column that never lose the user's file.

use std::path::PathBuf;

use bouncelab::project_file::{Project, ProjectError, default_project_path};
use bouncelab::scene::Light;
use bouncelab::settings::GiMode;
use glam::Vec3;

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("bouncelab-proj-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

#[test]
fn default_project_round_trips_byte_identical() {
    let path = default_project_path();
    let original = std::fs::read_to_string(&path).expect("default project exists");
    let project = Project::load(&path).expect("loads");
    assert_eq!(project.to_ron(&path).expect("serialises"), original, "load + save changes nothing");
    // The box's five walls, two boxes, their group and the room's proxy block.
    assert!(project.scene.lights().len() == 1 && project.scene.objects().len() == 8);
    let blocks = project.scene.objects().iter().filter(|o| o.role == bouncelab::scene::ObjectRole::ProxyBlock).count();
    assert_eq!(blocks, 1, "the default project carries the Cornell room's proxy block");
    assert_eq!(project.render.mode, GiMode::Rcs, "the default project opens in a GI mode that settles in seconds");
}

#[test]
fn the_mrt_example_project_opens_in_mrt_with_its_blocks_and_round_trips() {
    let path = PathBuf::from("projects/rooms_mrt.ron");
    let original = std::fs::read_to_string(&path).expect("the example exists");
    let project = Project::load(&path).expect("loads");
    assert_eq!(project.render.mode, GiMode::Mrt);
    let (level, _) = bouncelab::precompute::mrt::proxy::level(&project.scene).expect("its blocks make a level");
    assert_eq!((level.blocks.len(), level.link_count()), (3, 4));
    assert_eq!(project.to_ron(&path).expect("serialises"), original, "load + save changes nothing");
}

#[test]
fn edited_project_saves_and_reopens_exactly() {
    let dir = temp_dir("edit");
    let mut project = Project::load(&default_project_path()).expect("loads");
    let desc = project.scene.desc_mut();
    desc.lights.push(Light::spot(
        "new spot",
        Vec3::new(0.5, 1.9, 0.5),
        Vec3::new(0.0, -1.0, 0.1).normalize(),
        7.5,
        0.2,
        0.5,
    ));
    desc.objects[0].sampling_weight = 2.5;
    desc.objects[1].transform.translation.x += 0.125;
    project.render.mode = GiMode::Direct;
    project.render.view.exposure_ev = 1.5;
    let path = dir.join("sub").join("edited.ron");
    std::fs::create_dir_all(path.parent().expect("parent")).expect("mkdir");
    project.save(&path).expect("saves");
    let first = std::fs::read(&path).expect("read");
    project.save(&path).expect("saves again");
    assert_eq!(std::fs::read(&path).expect("read"), first, "saving twice gives identical bytes");
    let text = String::from_utf8(first.clone()).expect("utf8");
    assert!(text.trim_start().starts_with("(\n  format_version: 2,"), "format_version comes first");
    assert!(!text.contains(&*dir.to_string_lossy()), "asset paths are relative");
    let reopened = Project::load(&path).expect("reopens");
    assert_eq!(reopened.scene.desc(), project.scene.desc());
    assert_eq!(reopened.render, project.render);
    assert_eq!(reopened.to_ron(&path).expect("ron").into_bytes(), first);
}

#[test]
fn unknown_fields_and_syntax_errors_have_line_and_column() {
    let dir = temp_dir("errors");
    let good = std::fs::read_to_string(default_project_path()).expect("default");
    let asset = std::fs::canonicalize("assets/cornell_box.gltf").expect("asset");
    let good = good.replace("\"../assets/cornell_box.gltf\"", &format!("{:?}", asset.to_string_lossy()));

    let bad = good.replacen("  render: (", "  colour: 3,\n  render: (", 1);
    let path = dir.join("unknown.ron");
    std::fs::write(&path, &bad).expect("write");
    match Project::load(&path) {
        Err(ProjectError::Parse { line, column, message, .. }) => {
            assert!(line > 1 && column > 0, "line {line} column {column}");
            assert!(message.contains("colour"), "{message}");
        }
        other => panic!("expected a parse error, got {other:?}"),
    }
    let msg = Project::load(&path).expect_err("unknown field").to_string();
    assert!(msg.contains("unknown.ron:"), "{msg}");

    std::fs::write(&path, "(format_version: 1, assets: [").expect("write");
    assert!(matches!(Project::load(&path), Err(ProjectError::Parse { .. })));

    std::fs::write(&path, good.replace("format_version: 2", "format_version: 99")).expect("write");
    assert!(matches!(Project::load(&path), Err(ProjectError::TooNew { found: 99, .. })));

    std::fs::write(&path, good.replace("format_version: 2", "format_version: 0")).expect("write");
    let msg = Project::load(&path).expect_err("version 0").to_string();
    assert!(msg.contains("unknown.ron") && msg.contains("format_version 0"), "{msg}");

    // A byte-order mark (Windows editors) is skipped, not a syntax error at 1:1.
    std::fs::write(&path, format!("\u{feff}{good}")).expect("write");
    assert!(Project::load(&path).is_ok(), "{:?}", Project::load(&path).err());

    std::fs::write(&path, good.replace("resolution: 1024", "resolution: 0")).expect("write");
    let msg = Project::load(&path).expect_err("absurd setting").to_string();
    assert!(msg.contains("shadows.resolution"), "{msg}");

    std::fs::write(&path, good.replace("sampling_weight: 1.0", "sampling_weight: -1.0")).expect("write");
    assert!(Project::load(&path).expect_err("negative weight").to_string().contains("sampling weight"));

    // Finite but absurd values are named, not rendered as NaN or black (reliability issue).
    for (from, to, want) in [
        ("base_color: (0.73, 0.73, 0.73, 1.0)", "base_color: (1e10, 0.73, 0.73, 1.0)", "base colour"),
        ("intensity: 2.5", "intensity: 3.4e38", "intensity"),
    ] {
        assert!(good.contains(from), "{from}");
        std::fs::write(&path, good.replacen(from, to, 1)).expect("write");
        let msg = Project::load(&path).expect_err(to).to_string();
        assert!(msg.contains(want) && msg.contains("unknown.ron"), "{msg}");
    }

    std::fs::write(&path, good.replace("cornell_box.gltf", "nowhere.gltf")).expect("write");
    assert!(Project::load(&path).expect_err("missing asset").to_string().contains("nowhere.gltf"));

    std::fs::write(&path, "").expect("write");
    assert!(matches!(Project::load(&path), Err(ProjectError::Parse { .. })));
}

#[test]
fn failed_save_keeps_the_previous_file() {
    let dir = temp_dir("atomic");
    let path = dir.join("p.ron");
    let project = Project::load(&default_project_path()).expect("loads");
    project.save(&path).expect("saves");
    let before = std::fs::read(&path).expect("read");
    let mut broken = project.clone();
    broken.render.shadows.pcf_radius = 99;
    assert!(broken.save(&path).is_err(), "invalid settings are refused");
    assert_eq!(std::fs::read(&path).expect("read"), before, "previous file intact");
    let leftovers: Vec<_> =
        std::fs::read_dir(&dir).expect("dir").filter_map(Result::ok).filter(|e| e.file_name() != "p.ron").collect();
    assert!(leftovers.is_empty(), "no temp files left: {leftovers:?}");
}

#[test]
fn gltf_opens_as_a_project() {
    let project = Project::open(std::path::Path::new("assets/cornell_box.gltf")).expect("opens");
    assert_eq!(project.scene.objects().len(), 7);
    assert_eq!(project.scene.lights().len(), 1);
}
