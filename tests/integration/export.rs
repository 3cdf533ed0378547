//! Export: a project written as glTF (`.glb` and `.gltf`) and imported again is the same project
//! (lights in the scene's units, proxy blocks with their openings, sampling weights, clutter
//! marks, hidden objects, materials, camera, render settings) and renders the same images, in
//! `direct` and in `mrt` (which transfers light through the proxy block); outputs never replace
//! an input; the CLI writes what it says.

use crate::common;

use std::path::{Path, PathBuf};

use bouncelab::cli::export::{ExportArgs, run};
use bouncelab::image_io::HdrImage;
use bouncelab::project_file::{Project, default_project_path};
use bouncelab::render::{Renderer, harness};
use bouncelab::scene::{Light, LightUnits, MeshSource, ObjectRole};
use bouncelab::settings::GiMode;
use glam::Vec3;

const SIZE: (u32, u32) = (64, 36);

fn temp_dir(name: &str) -> PathBuf {
    common::temp_dir("export", name)
}

/// The default project (the Cornell box and its proxy block) with an authored spot (range, no
/// shadows), a sampling weight, a clutter mark, a hidden object and a specular material, in
/// photometric units.
fn authored() -> Project {
    let mut p = Project::load(&default_project_path()).expect("default project");
    let d = p.scene.desc_mut();
    d.light_units = LightUnits::Photometric;
    let mut spot = Light::spot("key", Vec3::new(0.5, 1.8, 0.6), Vec3::new(-0.2, -1.0, -0.3), 1.5, 0.2, 0.5);
    spot.range = Some(6.0);
    spot.cast_shadows = false;
    spot.color = [1.0, 0.8, 0.6];
    d.lights.push(spot);
    let named =
        |d: &mut bouncelab::scene::SceneDesc, name: &str| d.objects.iter().position(|o| o.name == name).expect(name);
    let tall = named(d, "tall_box");
    d.objects[tall].sampling_weight = 2.5;
    let short = named(d, "short_box");
    d.objects[short].role = ObjectRole::Clutter;
    let ceiling = named(d, "ceiling");
    d.objects[ceiling].sampling_weight = 0.5;
    d.materials[0].specular = [0.04, 0.04, 0.04];
    p.render.mode = GiMode::Mrt;
    p
}

fn close(a: f32, b: f32, tol: f32) -> bool {
    (a - b).abs() <= tol * (1.0 + a.abs().max(b.abs()))
}

/// Asserts that `back` (imported from an export of `p`) is `p`: every authored field, every
/// mesh source kind (generated meshes come back generated, with their openings).
fn assert_same_project(p: &Project, back: &Project) {
    let (a, b) = (p.scene.desc(), back.scene.desc());
    assert_eq!(a.light_units, b.light_units);
    assert_eq!(p.render, back.render, "render settings");
    assert_eq!(a.materials, b.materials, "materials");
    assert_eq!(a.objects.len(), b.objects.len());
    for (o, q) in a.objects.iter().zip(&b.objects) {
        assert_eq!(
            (&o.name, o.role, o.sampling_weight, o.visible, o.material),
            (&q.name, q.role, q.sampling_weight, q.visible, q.material)
        );
        let t = (&o.transform, &q.transform);
        assert!(
            t.0.translation.abs_diff_eq(t.1.translation, 1e-6) && t.0.scale.abs_diff_eq(t.1.scale, 1e-6),
            "{}",
            o.name
        );
        assert!(
            t.0.rotation.abs_diff_eq(t.1.rotation, 1e-6) || t.0.rotation.abs_diff_eq(-t.1.rotation, 1e-6),
            "{}",
            o.name
        );
        match (&o.source, &q.source) {
            (MeshSource::Cuboid { size, openings }, MeshSource::Cuboid { size: s2, openings: o2 }) => {
                assert!(size.abs_diff_eq(*s2, 1e-6) && openings == o2, "{}: block", o.name);
            }
            (MeshSource::Plane { size }, MeshSource::Plane { size: s2 }) => assert_eq!(size, s2),
            (MeshSource::Asset { .. }, MeshSource::Asset { .. }) => {}
            (x, y) => panic!("{}: {x:?} came back as {y:?}", o.name),
        }
    }
    assert_eq!(a.lights.len(), b.lights.len());
    for (l, m) in a.lights.iter().zip(&b.lights) {
        assert_eq!(
            (&l.name, l.kind, l.color, l.range, l.cast_shadows),
            (&m.name, m.kind, m.color, m.range, m.cast_shadows)
        );
        assert!(
            close(l.intensity, m.intensity, 1e-6),
            "{}: intensity {} came back as {}",
            l.name,
            l.intensity,
            m.intensity
        );
        assert!(l.position.abs_diff_eq(m.position, 1e-5), "{}: position", l.name);
        if l.kind != bouncelab::scene::LightKind::Point {
            assert!(
                l.direction.abs_diff_eq(m.direction, 1e-5),
                "{}: direction {} came back as {}",
                l.name,
                l.direction,
                m.direction
            );
        }
    }
    let (c, d) = (&a.camera, &b.camera);
    assert!(c.position.abs_diff_eq(d.position, 1e-5) && c.rotation.abs_diff_eq(d.rotation, 1e-5), "camera");
    assert_eq!((c.yfov, c.znear, c.zfar), (d.yfov, d.znear, d.zfar));
}

#[test]
fn an_export_imports_as_the_same_project() {
    let dir = temp_dir("project");
    let p = authored();
    for name in ["scene.glb", "scene.gltf"] {
        let path = dir.join(name);
        let summary = bouncelab::export::export(&p, &path).expect("export");
        assert_eq!((summary.objects, summary.proxy_blocks, summary.lights), (p.scene.objects().len(), 1, 2));
        let back = Project::open(&path).expect("the export imports");
        assert_same_project(&p, &back);
    }
    // The file says its units: photometric numbers, 683 x the radiometric.
    let text = std::fs::read_to_string(dir.join("scene.gltf")).expect("text");
    let doc: serde_json::Value = serde_json::from_str(&text).expect("json");
    assert_eq!(doc["extras"]["bouncelab"]["light_units"], "photometric");
    let written = doc["extensions"]["KHR_lights_punctual"]["lights"][1]["intensity"].as_f64().expect("intensity");
    assert!((written - 1.5 * 683.0).abs() < 1e-3, "{written}");
}

/// Renders `p` in `mode`: `direct` one frame, `mrt` once its transfer has settled.
fn image(ctx: &bouncelab::render::GpuContext, p: &Project, mode: GiMode) -> HdrImage {
    let mut settings = p.render.clone();
    settings.mode = mode;
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    harness::until_ready(&mut r, &p.scene, &settings, SIZE, |_| {}).expect("ready");
    for _ in 0..8 {
        r.render(&p.scene, &settings, SIZE).expect("render");
    }
    HdrImage { width: SIZE.0, height: SIZE.1, pixels: r.read_hdr().expect("hdr") }
}

#[test]
fn an_export_renders_the_same_images_in_direct_and_mrt() {
    let Some(ctx) = common::gpu() else { return };
    let dir = temp_dir("images");
    let p = authored();
    let path = dir.join("scene.glb");
    bouncelab::export::export(&p, &path).expect("export");
    let back = Project::open(&path).expect("imports");
    for mode in [GiMode::Direct, GiMode::Mrt] {
        let (a, b) = (image(&ctx, &p, mode), image(&ctx, &back, mode));
        let ratio = bouncelab::metrics::luminance_ratio(&b, &a).expect("ratio");
        let flip = bouncelab::metrics::flip(&b, &a, bouncelab::metrics::judging_exposure(&a)).expect("flip").0;
        eprintln!("{}: luminance {ratio:.5}, FLIP {flip:.5}", mode.name());
        assert!(bouncelab::metrics::mean_luminance(&a) > 1e-4, "{}: the project renders light", mode.name());
        assert!(
            (ratio - 1.0).abs() < 1e-3 && flip < 0.01,
            "{}: the export renders differently: luminance {ratio}, FLIP {flip}",
            mode.name()
        );
    }
}

#[test]
fn the_export_command_writes_the_file_and_never_an_input() {
    let dir = temp_dir("cli");
    let out = dir.join("cornell.glb");
    let args = ExportArgs { input: default_project_path(), out: out.clone(), units: Default::default() };
    let said = run(&args).expect("export");
    assert!(said.contains("cornell.glb") && said.contains("proxy blocks"), "{said}");
    assert!(std::fs::metadata(&out).expect("written").len() > 1000);
    let asset = Path::new("assets/cornell_box.gltf");
    let before = std::fs::read(asset).expect("asset");
    let clobber = ExportArgs { input: default_project_path(), out: asset.to_owned(), units: Default::default() };
    let err = run(&clobber).expect_err("an input is never replaced");
    assert!(err.to_string().contains("cornell_box.gltf"), "{err}");
    assert_eq!(std::fs::read(asset).expect("asset"), before);
    let bad = ExportArgs { input: default_project_path(), out: dir.join("scene.obj"), units: Default::default() };
    assert!(run(&bad).is_err(), "only .gltf and .glb");
}

/// Textures (a base colour checker and a normal map) leave as PNG and come back texel for
/// texel, with the materials naming them; the mesh keeps its texture coordinates.
#[test]
fn textures_and_texture_coordinates_survive_an_export() {
    let dir = temp_dir("textures");
    let source = dir.join("textured.gltf");
    crate::textures::textured_floor(&source);
    let p = Project::open(&source).expect("textured level");
    let path = dir.join("textured.glb");
    let summary = bouncelab::export::export(&p, &path).expect("export");
    assert_eq!(summary.images, 2);
    let back = Project::open(&path).expect("imports");
    assert_eq!(back.scene.resources().images, p.scene.resources().images, "texels");
    assert_eq!(back.scene.materials(), p.scene.materials());
    let (a, b) = (&p.scene.resources().meshes[0], &back.scene.resources().meshes[0]);
    assert_eq!((&a.positions, &a.uvs, &a.indices), (&b.positions, &b.uvs, &b.indices));
}
