//! Emissive surfaces and the sky end to end: glTF emission read in the file's light units and
//! exported back, a sky image's path kept relative in project files and exports, `--sky` on the
//! command line, and what the camera sees of emitters in every raster mode against the
//! reference path tracer.

use crate::common;

use bouncelab::image_io::{self, HdrImage};
use bouncelab::project_file::Project;
use bouncelab::render::Renderer;
use bouncelab::scene::{Camera, Environment, Material, MeshSource, Sky, Transform};
use bouncelab::settings::{GiMode, IsmSettings, ReferenceSettings, RenderSettings};
use glam::Vec3;

/// The Cornell box as a file from another tool (no recorded light units: photometric), its
/// first material emitting `factor` x `strength`.
fn glowing_cornell(path: &std::path::Path, factor: [f32; 3], strength: f32) {
    let text = std::fs::read_to_string("assets/cornell_box.gltf").expect("cornell");
    let mut doc: serde_json::Value = serde_json::from_str(&text).expect("json");
    doc.as_object_mut().expect("root").remove("extras");
    doc["materials"][0]["emissiveFactor"] = serde_json::json!(factor);
    doc["materials"][0]["extensions"] =
        serde_json::json!({"KHR_materials_emissive_strength": {"emissiveStrength": strength}});
    doc["extensionsUsed"] = serde_json::json!(["KHR_lights_punctual", "KHR_materials_emissive_strength"]);
    std::fs::write(path, serde_json::to_string(&doc).expect("json")).expect("write");
}

#[test]
fn emission_imports_in_the_files_light_units_and_exports_back_the_same() {
    let dir = common::temp_dir("area", "emission");
    let gltf = dir.join("glow.gltf");
    // Photometric (the default): 1366 cd/m² is 2 W/(sr m²).
    glowing_cornell(&gltf, [1.0, 0.5, 0.25], 1366.0);
    let project = Project::open(&gltf).expect("open");
    let m = &project.scene.materials()[0];
    assert!((m.emission() - Vec3::new(2.0, 1.0, 0.5)).abs().max_element() < 1e-4, "{}", m.emission());
    assert!(project.shortfalls().is_empty(), "emission is light: {:?}", project.shortfalls());
    let out = dir.join("out.gltf");
    bouncelab::export::export(&project, &out).expect("export");
    let text = std::fs::read_to_string(&out).expect("read");
    assert!(text.contains("KHR_materials_emissive_strength"), "the extension is declared and used");
    let again = Project::open(&out).expect("reopen");
    let m2 = &again.scene.materials()[0];
    assert!((m2.emission() - m.emission()).abs().max_element() < 1e-4, "{} vs {}", m2.emission(), m.emission());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn an_image_sky_is_saved_relative_to_the_project_and_travels_through_export() {
    let dir = common::temp_dir("area", "sky");
    let sky = dir.join("sky.exr");
    let pixels = vec![[0.5, 0.6, 0.9, 1.0]; 16 * 8];
    image_io::write_exr(&sky, &HdrImage { width: 16, height: 8, pixels }).expect("sky");
    let mut project = Project::open(std::path::Path::new("assets/cornell_box.gltf")).expect("open");
    let mut desc = project.scene.desc().clone();
    desc.environment =
        Environment { sky: Sky::Image(sky.to_string_lossy().into_owned()), intensity: 2.0, rotation_degrees: 30.0 };
    project.set_desc(desc).expect("set sky");
    assert_eq!(project.scene.sky_image().map(|s| (s.width, s.height)), Some((16, 8)));
    assert!(project.files().contains(&sky), "an output must never replace the sky image");
    let saved = dir.join("projects").join("p.ron");
    std::fs::create_dir_all(saved.parent().expect("parent")).expect("dir");
    project.save(&saved).expect("save");
    let text = std::fs::read_to_string(&saved).expect("read");
    assert!(text.contains("Image(\"../sky.exr\")"), "relative path:\n{text}");
    let loaded = Project::load(&saved).expect("load");
    assert_eq!(loaded.scene.environment().intensity, 2.0);
    assert_eq!(loaded.scene.sky_image().map(|s| s.texels[0]), Some([0.5, 0.6, 0.9]));
    let exported = dir.join("export").join("level.gltf");
    std::fs::create_dir_all(exported.parent().expect("parent")).expect("dir");
    bouncelab::export::export(&loaded, &exported).expect("export");
    let back = Project::open(&exported).expect("reopen export");
    assert_eq!(back.scene.environment().rotation_degrees, 30.0);
    assert!(back.scene.has_sky(), "the exported sky loads again");
    // A missing sky image names the file.
    let mut desc = loaded.scene.desc().clone();
    desc.environment.sky = Sky::Image(dir.join("gone.exr").to_string_lossy().into_owned());
    let mut broken = loaded.clone();
    let err = broken.set_desc(desc).expect_err("missing image").to_string();
    assert!(err.contains("gone.exr"), "{err}");
    assert_eq!(broken.scene.environment(), loaded.scene.environment(), "a failed load changes nothing");
    let _ = std::fs::remove_dir_all(&dir);
}

/// A floor (no light on it), a glowing box and `sky`, seen from above at an angle.
fn floor_box_and_sky(sky: Sky) -> bouncelab::scene::Scene {
    let (floor, floor_material) = common::floor(6.0, 0.5);
    let lamp =
        Material { emissive_color: [1.0, 0.6, 0.3], emissive_strength: 3.0, ..Material::diffuse("lamp", [0.0; 3]) };
    let lamp_box = common::object(
        "lamp",
        MeshSource::Cuboid { size: Vec3::splat(0.8), openings: [false; 6] },
        1,
        Transform { translation: Vec3::new(0.0, 0.4, 0.0), ..Transform::default() },
    );
    let camera = Camera::look_at(Vec3::new(0.0, 2.0, 4.0), Vec3::new(0.0, 0.6, 0.0), 0.9);
    let mut scene = common::scene(vec![floor, lamp_box], vec![floor_material, lamp], Vec::new(), camera);
    scene.desc_mut().environment = Environment { sky, intensity: 2.0, rotation_degrees: 25.0 };
    scene
}

#[test]
fn the_direct_term_shows_the_emitters_and_the_sky_as_the_reference_sees_them() {
    let Some(ctx) = common::gpu() else { return };
    for sky in [Sky::Constant([0.2, 0.3, 0.5]), Sky::Preetham { turbidity: 3.0 }] {
        let scene = floor_box_and_sky(sky.clone());
        let ratio = emitters_and_sky_ratio(&ctx, &scene);
        eprintln!("{sky:?}: emitters and sky, raster / reference {ratio:.4}");
        assert!((ratio - 1.0).abs() < 0.01, "{sky:?}: raster / reference {ratio}");
    }
    // Every raster mode says it does not light the floor with them; the reference does not.
    let scene = floor_box_and_sky(Sky::Constant([0.2, 0.3, 0.5]));
    let direct = RenderSettings { mode: GiMode::Direct, ..RenderSettings::default() };
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    r.render(&scene, &direct, (32, 18)).expect("render");
    let said = r.shortfalls(&scene, &direct).join(" ");
    assert!(said.contains("the sky and 1 emissive material"), "{said}");
    let reference = RenderSettings { mode: GiMode::Reference, ..RenderSettings::default() };
    assert!(bouncelab::render::area_light_shortfall(&scene, &reference).is_none());
}

/// The raster `direct` image's pixels whose every subsample shows an emitter or the sky (the
/// floor gets no light in `direct`: no punctual light shines on it) against the one-bounce
/// reference's same pixels: the ratio of their sums.
fn emitters_and_sky_ratio(ctx: &bouncelab::render::GpuContext, scene: &bouncelab::scene::Scene) -> f64 {
    let (size, k) = ((32u32, 18u32), 4u32);
    let reference = common::reference(scene, size, ReferenceSettings { spp: 64, max_bounces: 1, ..Default::default() });
    let direct = RenderSettings { mode: GiMode::Direct, ..RenderSettings::default() };
    let big = common::render(ctx, scene, &direct, (size.0 * k, size.1 * k));
    let (mut raster_sum, mut reference_sum, mut pixels) = (0.0f64, 0.0f64, 0);
    for y in 0..size.1 {
        for x in 0..size.0 {
            let subs: Vec<[f32; 4]> =
                (0..k * k).map(|i| big[((y * k + i / k) * size.0 * k + x * k + i % k) as usize]).collect();
            if subs.iter().all(|p| p[0] + p[1] + p[2] > 0.0) {
                let mean: f32 = subs.iter().map(|p| p[0] + p[1] + p[2]).sum::<f32>() / (k * k) as f32;
                let r = reference.pixels[(y * size.0 + x) as usize];
                raster_sum += f64::from(mean);
                reference_sum += f64::from(r[0] + r[1] + r[2]);
                pixels += 1;
            }
        }
    }
    assert!(pixels > 50, "{pixels} pixels of emitters and sky");
    raster_sum / reference_sum
}

#[test]
fn render_takes_a_constant_sky_in_the_scenes_light_units() {
    if !common::has_gpu() {
        return;
    }
    let dir = common::temp_dir("area", "cli");
    let level = dir.join("level.gltf");
    glowing_cornell(&level, [0.0; 3], 1.0);
    let out = dir.join("sky.exr");
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_bouncelab"))
        .args(["render", &level.to_string_lossy(), "--mode", "direct", "--width", "32", "--height", "18"])
        .args(["--ssaa", "1", "--sky", "683,1366,2049", "--allow-partial", "--out"])
        .arg(&out)
        .output()
        .expect("run");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let img = image_io::read_linear(&out).expect("read");
    // Photometric by default: 683 cd/m² is 1 W/(sr m²). The top-left corner sees past the box.
    let corner = img.pixels[0];
    assert!((corner[0] - 1.0).abs() < 1e-3 && (corner[1] - 2.0).abs() < 1e-3, "{corner:?}");
    let bad = std::process::Command::new(env!("CARGO_BIN_EXE_bouncelab"))
        .args(["render", "assets/cornell_box.gltf", "--sky", "sky.png", "--out"])
        .arg(dir.join("x.exr"))
        .output()
        .expect("run");
    assert!(!bad.status.success() && String::from_utf8_lossy(&bad.stderr).contains("sky.png"));
    let _ = std::fs::remove_dir_all(&dir);
}

/// `ism` lights with VPLs on the emissive panels and on the sky's sphere (Ritschel's VPLs for
/// area and environment light): on the window room lit only by the sky and the room lit only by
/// emissive panels its energy is within 10% of the path tracer's and its FLIP under half of
/// `direct`'s (which lights nothing there). (A sky edit makes new candidates:
/// `emitter_points::tests`.)
#[test]
fn ism_lights_with_vpls_on_the_emitters_and_the_sky() {
    let Some(ctx) = common::gpu() else { return };
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    let render = |r: &mut Renderer, project: &Project, mode: GiMode, frames: usize, size: (u32, u32)| {
        let settings = RenderSettings { mode, ..project.render.clone() };
        for _ in 0..frames {
            r.render(&project.scene, &settings, size).expect("render");
        }
        HdrImage { width: size.0, height: size.1, pixels: r.read_hdr().expect("hdr") }
    };
    for name in ["skylight", "panels"] {
        let scene = bouncelab::suite::scene(name).expect("suite scene");
        let project = scene.load(std::path::Path::new(".")).expect("loads");
        let reference = scene.reference(std::path::Path::new(".")).expect("reference");
        let size = (reference.width, reference.height);
        let ev = bouncelab::metrics::judging_exposure(&reference);
        let ism = render(&mut r, &project, GiMode::Ism, 16, size);
        let direct = render(&mut r, &project, GiMode::Direct, 1, size);
        let (i, d) = (
            bouncelab::metrics::compare(&ism, &reference, ev).expect("same size"),
            bouncelab::metrics::compare(&direct, &reference, ev).expect("same size"),
        );
        eprintln!("{name}: ism energy {:.3} FLIP {:.4}; direct FLIP {:.4}", i.luminance_ratio, i.flip, d.flip);
        assert!((0.9..=1.1).contains(&i.luminance_ratio), "{name}: ism energy {:.3}", i.luminance_ratio);
        assert!(i.flip < 0.5 * d.flip, "{name}: ism FLIP {:.4} against direct's {:.4}", i.flip, d.flip);
        assert!(
            r.shortfalls(&project.scene, &RenderSettings { mode: GiMode::Ism, ..project.render.clone() }).is_empty()
        );
    }
}

/// The energies of `frames` consecutive `ism-ritschel` frames of suite scene `name` over its
/// reference's, at the reference's size, with `ism` changed by `change`.
fn ritschel_frames(
    ctx: &bouncelab::render::GpuContext,
    name: &str,
    frames: usize,
    change: impl Fn(&mut IsmSettings),
) -> Vec<f64> {
    let scene = bouncelab::suite::scene(name).expect("suite scene");
    let project = scene.load(std::path::Path::new(".")).expect("loads");
    let reference = scene.reference(std::path::Path::new(".")).expect("reference");
    let size = (reference.width, reference.height);
    let mut settings = RenderSettings { mode: GiMode::IsmRitschel, ..project.render.clone() };
    change(&mut settings.ism);
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    let target = bouncelab::metrics::mean_luminance(&reference);
    (0..frames)
        .map(|_| {
            r.render(&project.scene, &settings, size).expect("render");
            let frame = HdrImage { width: size.0, height: size.1, pixels: r.read_hdr().expect("hdr") };
            bouncelab::metrics::mean_luminance(&frame) / target
        })
        .collect()
}

/// The mean of `energies` and their spread ([`bouncelab::metrics::relative_spread`]).
fn mean_and_spread(energies: &[f64]) -> (f64, f64) {
    (energies.iter().sum::<f64>() / energies.len() as f64, bouncelab::metrics::relative_spread(energies))
}

/// `ism-ritschel` renders every frame afresh (no history), so one frame of sky VPLs is all it
/// shows: on the window room lit only by the sky, eight consecutive frames' energies must stay
/// within a few percent of each other. The sky's candidates lie on a grid of its directions in
/// the emitter tile's layout (`emitter_points`, "Layout"), so each frame's evenly spread VPLs
/// spread evenly over the sky; with the candidates in Halton order one frame read anywhere
/// from 0.79 to 1.21 of the reference (`probe skylight --mode ism-ritschel --trace`).
#[test]
fn ism_ritschel_frames_of_a_sky_lit_room_hold_steady() {
    let Some(ctx) = common::gpu() else { return };
    let energies = ritschel_frames(&ctx, "skylight", 8, |_| {});
    let (mean, spread) = mean_and_spread(&energies);
    eprintln!("ism-ritschel skylight frames {energies:.3?}: mean {mean:.3}, spread {:.1}%", 100.0 * spread);
    assert!(spread < 0.03, "frame-to-frame spread {:.1}% of the energy", 100.0 * spread);
    assert!(energies.iter().all(|e| (0.9..=1.15).contains(e)), "{energies:.3?}");
}

/// Under the sun and the sky (`sunsky`) the sun's share of the VPLs lands mostly on the roof,
/// and the handful on the sunlit floor in view changed in number from frame to frame. The
/// first set's seen weight (`first_set_seen_weight`) draws lit surfaces the camera sees more
/// often: single frames must spread clearly less than with the weight off, and their mean must
/// stay within 10% of the path tracer's energy.
#[test]
#[ignore = "heavy: 16 ism-ritschel frames of the sun-and-sky room at the reference's size (26 s)"]
fn ism_ritschel_frames_under_the_sun_and_the_sky_steady_with_the_seen_weight() {
    let Some(ctx) = common::gpu() else { return };
    let seen = ritschel_frames(&ctx, "sunsky", 8, |_| {});
    let plain = ritschel_frames(&ctx, "sunsky", 8, |ism| ism.first_set_seen_weight = 0.0);
    let ((mean, spread), (plain_mean, plain_spread)) = (mean_and_spread(&seen), mean_and_spread(&plain));
    eprintln!(
        "ism-ritschel sunsky frames seen-weighted {seen:.3?}: mean {mean:.3}, spread {:.1}%; by power {plain:.3?}: mean {plain_mean:.3}, spread {:.1}%",
        100.0 * spread,
        100.0 * plain_spread
    );
    assert!(
        spread < 0.7 * plain_spread,
        "spread {:.1}% seen-weighted vs {:.1}% by power",
        100.0 * spread,
        100.0 * plain_spread
    );
    assert!((0.9..=1.1).contains(&mean), "mean energy {mean:.3}");
}

/// `sshgi` finds the sky through its voxel columns (from the screen's texels and the panorama's
/// senders): in the courtyard open to the sky and in the window room lit only by the sky its
/// energy is within 10% of the path tracer's and its FLIP under half of `direct`'s; without sky
/// rays the window room gets none of it, and the GI panel says the sky is left out.
#[test]
fn sshgi_lights_with_the_sky_through_its_voxels() {
    let Some(ctx) = common::gpu() else { return };
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    let render = |r: &mut Renderer, project: &Project, settings: &RenderSettings, frames: usize, size: (u32, u32)| {
        for _ in 0..frames {
            r.render(&project.scene, settings, size).expect("render");
        }
        HdrImage { width: size.0, height: size.1, pixels: r.read_hdr().expect("hdr") }
    };
    for name in ["courtyard", "skylight"] {
        let scene = bouncelab::suite::scene(name).expect("suite scene");
        let project = scene.load(std::path::Path::new(".")).expect("loads");
        let reference = scene.reference(std::path::Path::new(".")).expect("reference");
        let size = (reference.width, reference.height);
        let ev = bouncelab::metrics::judging_exposure(&reference);
        let sshgi = RenderSettings { mode: GiMode::Sshgi, ..project.render.clone() };
        let mut dark = sshgi.clone();
        dark.sshgi.sky_rays = 0;
        let with_sky = render(&mut r, &project, &sshgi, 12, size);
        assert!(r.shortfalls(&project.scene, &sshgi).is_empty(), "{name}: the sky is lit");
        let sky = r.read_buffer("sshgi_sky").expect("the sky buffer");
        assert!(sky.pixels.iter().any(|p| p[2] > 0.0), "{name}: the sky buffer shows sky light");
        let without = render(&mut r, &project, &dark, 12, size);
        assert!(r.shortfalls(&project.scene, &dark).join(" ").contains("the sky"), "{name}: says the sky is left out");
        let direct = render(&mut r, &project, &RenderSettings { mode: GiMode::Direct, ..sshgi.clone() }, 1, size);
        let (s, w, d) = (
            bouncelab::metrics::compare(&with_sky, &reference, ev).expect("same size"),
            bouncelab::metrics::compare(&without, &reference, ev).expect("same size"),
            bouncelab::metrics::compare(&direct, &reference, ev).expect("same size"),
        );
        eprintln!(
            "{name}: sshgi energy {:.3} FLIP {:.4}; without sky rays {:.3}; direct FLIP {:.4}",
            s.luminance_ratio, s.flip, w.luminance_ratio, d.flip
        );
        assert!((0.9..=1.1).contains(&s.luminance_ratio), "{name}: sshgi energy {:.3}", s.luminance_ratio);
        assert!(s.flip < 0.5 * d.flip, "{name}: sshgi FLIP {:.4} against direct's {:.4}", s.flip, d.flip);
        if name == "skylight" {
            assert!(
                w.luminance_ratio < 0.5,
                "the sky alone lights the room: {:.3} without sky rays",
                w.luminance_ratio
            );
        }
    }
}

/// The mean over `frames` frames of the sum over the start level of sshgi's sky buffer (E / pi)
/// of `name`, from a renderer of its own (the same frame seeds each time).
fn sshgi_sky_sum(ctx: &bouncelab::render::GpuContext, name: &str, world_voxels: u32, frames: usize) -> f64 {
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    let scene = bouncelab::suite::scene(name).expect("suite scene");
    let project = scene.load(std::path::Path::new(".")).expect("loads");
    let mut settings = RenderSettings { mode: GiMode::Sshgi, ..project.render.clone() };
    settings.sshgi.world_voxels = world_voxels;
    let mut sum = 0.0;
    for _ in 0..frames {
        r.render(&project.scene, &settings, (128, 72)).expect("render");
        let sky = r.read_buffer("sshgi_sky").expect("the sky buffer");
        sum += sky.pixels.iter().map(|p| f64::from(p[0] + p[1] + p[2])).sum::<f64>();
    }
    sum / frames as f64
}

/// A sky ray that leaves the view in front of what its last column shows (or through the near
/// end) is unknown to the view's voxels; with the world grid it walks on through the scene's
/// surface voxels. Outdoors (the courtyard) that finds more sky than counting it blocked; in
/// the window room, where such rays meet the walls and the ceiling, the grid adds almost none
/// (a grid that leaked would light the room through its walls).
#[test]
fn sshgi_sky_rays_that_leave_the_view_find_the_sky_outdoors_and_the_walls_indoors() {
    let Some(ctx) = common::gpu() else { return };
    let gain = |name: &str| sshgi_sky_sum(&ctx, name, 512, 8) / sshgi_sky_sum(&ctx, name, 0, 8);
    let (outdoors, indoors) = (gain("courtyard"), gain("skylight"));
    eprintln!("sky light with the world grid over without: courtyard {outdoors:.4}, window room {indoors:.4}");
    assert!(outdoors > 1.02, "the courtyard's sky rays past the view found no sky: {outdoors:.4}");
    assert!((indoors - 1.0).abs() < 0.02, "the window room's sky changed with the grid: {indoors:.4}");
}
