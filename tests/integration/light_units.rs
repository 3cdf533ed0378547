//! glTF light units: the specification's candela and lux by default (683 lm/W), a file's own
//! record of its units over the default, the `--light-units` choice, and the project file's
//! choice, which round-trips and reads as radiometric in files written before it existed.

use crate::common;

use std::path::{Path, PathBuf};

use bouncelab::cli::SceneArgs;
use bouncelab::cli::render::{RenderArgs, run};
use bouncelab::image_io;
use bouncelab::import::writer::{GltfWriter, NodeDesc};
use bouncelab::import::{ImportOptions, import_gltf, import_gltf_with};
use bouncelab::project_file::Project;
use bouncelab::scene::{LUMENS_PER_WATT, LightUnits};
use glam::{Quat, Vec3};
use serde_json::{Value, json};

fn temp_dir(name: &str) -> PathBuf {
    common::temp_dir("units", name)
}

fn write(dir: &Path, name: &str, doc: &Value) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, serde_json::to_vec_pretty(doc).expect("json")).expect("write");
    path
}

/// A floor lit by a point light, a spot and a sun of the given intensities (in whatever units
/// the caller writes), with a camera.
fn level(point: f32, spot: f32, sun: f32) -> GltfWriter {
    let mut w = GltfWriter::default();
    let m = w.material("floor", [0.6, 0.6, 0.6, 1.0]);
    let p =
        [Vec3::new(-3.0, 0.0, -3.0), Vec3::new(-3.0, 0.0, 3.0), Vec3::new(3.0, 0.0, 3.0), Vec3::new(3.0, 0.0, -3.0)];
    let mesh = w.mesh("floor", &p, Some(&[Vec3::Y; 4]), &[0, 1, 2, 0, 2, 3], Some(m));
    w.node(NodeDesc { name: "floor".into(), mesh: Some(mesh), ..NodeDesc::default() }, true);
    let down = Quat::from_rotation_x(-std::f32::consts::FRAC_PI_2);
    let lamp = w.light("lamp", "point", [1.0, 0.9, 0.8], point, None);
    w.node(
        NodeDesc {
            name: "lamp".into(),
            light: Some(lamp),
            translation: Some(Vec3::new(-1.0, 2.0, 0.0)),
            ..NodeDesc::default()
        },
        true,
    );
    let cone = w.light("cone", "spot", [1.0, 1.0, 1.0], spot, Some((0.2, 0.6)));
    w.node(
        NodeDesc {
            name: "cone".into(),
            light: Some(cone),
            translation: Some(Vec3::new(1.0, 2.5, 0.0)),
            rotation: Some(down),
            ..NodeDesc::default()
        },
        true,
    );
    let sun = w.light("sun", "directional", [1.0, 1.0, 1.0], sun, None);
    w.node(
        NodeDesc {
            name: "sun".into(),
            light: Some(sun),
            rotation: Some(Quat::from_rotation_x(-1.0)),
            ..NodeDesc::default()
        },
        true,
    );
    let cam = w.camera(0.9, 0.05, None);
    w.node(
        NodeDesc {
            name: "cam".into(),
            camera: Some(cam),
            translation: Some(Vec3::new(0.0, 3.0, 6.0)),
            rotation: Some(Quat::from_rotation_x(-0.45)),
            ..NodeDesc::default()
        },
        true,
    );
    w
}

/// Blender's radiometric lamps: P / (4 pi) W/sr for a P-watt point or spot, E W/m^2 for a sun.
const LAMP_W: f32 = 1000.0;
const SPOT_W: f32 = 500.0;
const SUN: f32 = 2.0;

fn per_sr(watts: f32) -> f32 {
    watts / (4.0 * std::f32::consts::PI)
}

/// The level as Blender's exporter writes it ("Standard" lighting: candela and lux, no record
/// of units, Blender's generator).
fn blender_file(dir: &Path) -> PathBuf {
    let mut doc = level(per_sr(LAMP_W) * 683.0, per_sr(SPOT_W) * 683.0, SUN * 683.0).to_json();
    let root = doc.as_object_mut().expect("object");
    root.remove("extras");
    root.insert("asset".into(), json!({"version": "2.0", "generator": "Khronos glTF Blender I/O v4.2.69"}));
    write(dir, "blender.gltf", &doc)
}

/// The same level in the scene model's units, recorded as radiometric (as Bounce Lab writes).
fn radiometric_file(dir: &Path) -> PathBuf {
    write(dir, "radiometric.gltf", &level(per_sr(LAMP_W), per_sr(SPOT_W), SUN).to_json())
}

#[test]
fn a_blender_export_renders_as_the_radiometric_file_it_came_from() {
    let dir = temp_dir("blender");
    let (blender, radiometric) = (blender_file(&dir), radiometric_file(&dir));
    let (b, r) = (import_gltf(&blender).expect("blender file"), import_gltf(&radiometric).expect("radiometric file"));
    assert_eq!(
        (b.recorded_units, b.light_units),
        (None, LightUnits::Photometric),
        "no record: the specification's units"
    );
    assert_eq!((r.recorded_units, r.light_units), (Some(LightUnits::Radiometric), LightUnits::Radiometric));
    assert_eq!(b.scene.lights.len(), 3);
    for (lb, lr) in b.scene.lights.iter().zip(&r.scene.lights) {
        let rel = (lb.intensity - lr.intensity).abs() / lr.intensity;
        assert!(rel < 1e-5, "{}: {} from the Blender file, {} radiometric", lb.name, lb.intensity, lr.intensity);
    }
    assert!((r.scene.lights[0].intensity - 79.577).abs() < 1e-3, "a 1000 W lamp is 1000 / (4 pi) W/sr");
    let Some(_gpu) = common::gpu() else { return };
    let render = |input: &Path, name: &str| {
        let out = dir.join(name);
        let args = RenderArgs {
            input: input.to_owned(),
            out: out.clone(),
            width: 48,
            height: 27,
            ssaa: 1,
            frames: Some(1),
            ..RenderArgs::default()
        };
        run(&args).expect("render");
        image_io::read_linear(&out).expect("image")
    };
    let (ib, ir) = (render(&blender, "blender.exr"), render(&radiometric, "radiometric.exr"));
    let mean = bouncelab::metrics::mean_luminance(&ir);
    assert!(mean > 1e-3, "the radiometric level is lit: {mean}");
    let worst = ib
        .pixels
        .iter()
        .zip(&ir.pixels)
        .flat_map(|(a, b)| (0..3).map(move |c| (a[c] - b[c]).abs() / (b[c].abs() + 1e-3)))
        .fold(0.0f32, f32::max);
    assert!(worst < 1e-3, "the Blender file renders differently, worst relative difference {worst}");
    // Read as radiometric numbers (the old behaviour), the Blender file is 683x too bright.
    let raw = RenderArgs {
        input: blender.clone(),
        out: dir.join("raw.exr"),
        width: 48,
        height: 27,
        ssaa: 1,
        frames: Some(1),
        units: SceneArgs { light_units: Some(LightUnits::Radiometric), ..SceneArgs::default() },
        ..RenderArgs::default()
    };
    run(&raw).expect("render radiometric");
    let ratio = bouncelab::metrics::mean_luminance(&image_io::read_linear(&dir.join("raw.exr")).expect("image")) / mean;
    assert!(
        (ratio - f64::from(LUMENS_PER_WATT)).abs() < 1.0,
        "--light-units radiometric reads the numbers as W/sr: {ratio}"
    );
}

#[test]
fn a_files_unit_record_wins_over_the_choice_and_round_trips_through_the_project() {
    let dir = temp_dir("record");
    let mut w = level(100.0, 100.0, 100.0);
    w.set_light_units(LightUnits::Photometric);
    let path = write(&dir, "photometric.gltf", &w.to_json());
    let asked = ImportOptions { light_units: LightUnits::Radiometric };
    let asset = import_gltf_with(&path, asked).expect("imports");
    assert_eq!(asset.recorded_units, Some(LightUnits::Photometric));
    assert!((asset.scene.lights[0].intensity - 100.0 / 683.0).abs() < 1e-6, "the record wins: candela");

    // The project keeps the choice; saving and loading gives it back, lights unchanged.
    let mut project = Project::from_gltf(&path).expect("project");
    assert_eq!(project.scene.desc().light_units, LightUnits::Photometric);
    project.scene.desc_mut().light_units = LightUnits::Radiometric;
    let saved = dir.join("p.ron");
    project.save(&saved).expect("save");
    let text = std::fs::read_to_string(&saved).expect("text");
    assert!(text.contains("format_version: 2") && text.contains("light_units: Radiometric"), "{text}");
    let back = Project::load(&saved).expect("load");
    assert_eq!(back.scene.desc(), project.scene.desc());

    // A version 1 file (written before the choice) means radiometric.
    let v1 = text.replace("format_version: 2", "format_version: 1").replace("light_units: Radiometric,", "");
    assert!(!v1.contains("light_units"));
    std::fs::write(dir.join("v1.ron"), v1).expect("write v1");
    let old = Project::load(&dir.join("v1.ron")).expect("v1 loads");
    assert_eq!(old.scene.desc().light_units, LightUnits::Radiometric);
    assert_eq!(old.scene.lights(), back.scene.lights());

    // A record naming unknown units is an error naming the file.
    let mut doc = w.to_json();
    doc["extras"]["bouncelab"]["light_units"] = json!("lumens");
    let err = import_gltf(&write(&dir, "bad.gltf", &doc)).expect_err("unknown units");
    assert!(err.to_string().contains("bad.gltf") && err.to_string().contains("lumens"), "{err}");
}

/// A file that does not record its units, opened with the wrong ones, is fixed from the scene
/// panel's button: the file's lights read again in the other units (unedited ones only), as one
/// change the project keeps.
#[test]
fn the_files_lights_read_again_in_other_units_leave_edited_lights_alone() {
    let dir = temp_dir("reread");
    let path = blender_file(&dir);
    let mut p = Project::from_gltf(&path).expect("opens");
    assert!(p.has_unrecorded_lights());
    let as_candela: Vec<f32> = p.scene.lights().iter().map(|l| l.intensity).collect();
    p.scene.desc_mut().lights[2].intensity = 9.0;
    let changed = p.reread_file_lights(LightUnits::Radiometric);
    assert_eq!(changed, 2, "the two unedited lights");
    assert_eq!(p.scene.desc().light_units, LightUnits::Radiometric);
    for (l, before) in p.scene.lights().iter().zip(&as_candela).take(2) {
        assert!((l.intensity / before - 683.0).abs() < 0.01, "{}: {} from {before}", l.name, l.intensity);
    }
    assert_eq!(p.scene.lights()[2].intensity, 9.0, "the edited light keeps its value");
    assert_eq!(p.reread_file_lights(LightUnits::Photometric), 2, "and back");
    assert!((p.scene.lights()[0].intensity - as_candela[0]).abs() < 1e-6);
    let recorded = Project::from_gltf(&radiometric_file(&dir)).expect("opens");
    assert!(!recorded.has_unrecorded_lights(), "a file that records its units is read as it says");
}
