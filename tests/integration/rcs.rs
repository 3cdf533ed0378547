//! `rcs` (radiance cache splatting, Gautron et al.) at CI sizes: records read E = pi in a white
//! furnace (the plane's border compensation and the integration weights); on the Cornell box it
//! is closer to the path tracer than `direct` with energy within 10%, and its gradients bring the
//! interpolation closer to the reference than flat records; a small camera move reuses most
//! records; moving one light renews only the records whose hemispheres it changes, and moving
//! an object drops the records on it and keeps the far ones.

use crate::common;

use bouncelab::image_io::HdrImage;
use bouncelab::metrics;
use bouncelab::project_file::Project;
use bouncelab::render::Renderer;
use bouncelab::render::gi::rcs::technique::RcsTechnique;
use bouncelab::settings::{GiMode, RcsSettings, RenderSettings};
use bouncelab::suite;
use glam::Vec3;
use std::path::Path;

const SIZE: (u32, u32) = (128, 72);

fn cornell() -> (Project, HdrImage) {
    let scene = suite::scene("cornell").expect("suite scene");
    (scene.load(Path::new(".")).expect("cornell"), scene.reference(Path::new(".")).expect("cached reference"))
}

fn with(project: &Project, mode: GiMode, rcs: RcsSettings) -> RenderSettings {
    RenderSettings { mode, rcs, ..project.render.clone() }
}

/// Renders until the cache has stopped refining (at most `limit` frames); the last frame.
fn converge(r: &mut Renderer, project: &Project, settings: &RenderSettings, size: (u32, u32), limit: usize) -> usize {
    bouncelab::render::harness::converge(r, &project.scene, settings, size, limit).expect("render")
}

/// The final image at twice [`SIZE`], box-filtered to the reference's pixels.
fn image(r: &Renderer) -> HdrImage {
    let big = (SIZE.0 * 2, SIZE.1 * 2);
    HdrImage {
        width: SIZE.0,
        height: SIZE.1,
        pixels: bouncelab::image_io::box_downsample(&r.read_hdr().expect("hdr"), big, 2),
    }
}

fn counter(r: &Renderer, name: &str) -> u64 {
    r.technique_status().expect("status").counter(name)
}

#[test]
fn records_in_a_white_furnace_read_pi() {
    let Some(ctx) = common::gpu() else { return };
    let (project, _) = cornell();
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    let rcs = RcsSettings { furnace: true, bounces: 1, ..RcsSettings::default() };
    let frames = converge(&mut r, &project, &with(&project, GiMode::Rcs, rcs), (64, 36), 8);
    let technique = r.technique_as::<RcsTechnique>().expect("rcs");
    let records = technique.read_records(&ctx.device, &ctx.queue).expect("records");
    let live: Vec<_> = records.iter().filter(|r| r.position[3] > 0.0).collect();
    assert!(live.len() > 20, "{} records after {frames} frames", live.len());
    let worst = live
        .iter()
        .flat_map(|r| r.irradiance[..3].iter().map(|e| (e / std::f32::consts::PI - 1.0).abs()))
        .fold(0.0f32, f32::max);
    eprintln!("{} records, worst |E / pi - 1| = {worst:.5}", live.len());
    assert!(worst < 1e-3, "a furnace record reads E / pi off by {worst}");
}

#[test]
fn rcs_on_the_cornell_box_beats_directs_flip_with_energy_within_ten_percent() {
    let Some(ctx) = common::gpu() else { return };
    let (project, reference) = cornell();
    let big = (SIZE.0 * 2, SIZE.1 * 2);
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    r.render(&project.scene, &with(&project, GiMode::Direct, RcsSettings::default()), big).expect("render");
    let direct = image(&r);
    let frames = converge(&mut r, &project, &with(&project, GiMode::Rcs, RcsSettings::default()), big, 12);
    let rcs = image(&r);
    let ev = bouncelab::metrics::judging_exposure(&reference);
    let fd = metrics::flip(&direct, &reference, ev).expect("flip").0;
    let fr = metrics::flip(&rcs, &reference, ev).expect("flip").0;
    let energy = metrics::luminance_ratio(&rcs, &reference).expect("ratio");
    eprintln!(
        "rcs FLIP {fr:.4} vs direct {fd:.4} ({:.2}); energy {energy:.3}; {} records after {frames} frames",
        fr / fd,
        counter(&r, "records")
    );
    assert!(fr < 0.5 * fd, "rcs FLIP {fr:.4} is not below half of direct's {fd:.4}");
    assert!((0.9..=1.1).contains(&energy), "rcs energy {energy:.3} of the reference");
}

#[test]
fn gradients_bring_sparse_records_closer_to_the_reference() {
    let Some(ctx) = common::gpu() else { return };
    let (project, reference) = cornell();
    let big = (SIZE.0 * 2, SIZE.1 * 2);
    // Sparse records (a large a, large zones) make the interpolation error visible.
    let sparse = RcsSettings { accuracy: 0.8, min_zone_pixels: 24.0, ..RcsSettings::default() };
    let ev = bouncelab::metrics::judging_exposure(&reference);
    let mut errors = Vec::new();
    for gradients in [false, true] {
        let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
        converge(&mut r, &project, &with(&project, GiMode::Rcs, RcsSettings { gradients, ..sparse.clone() }), big, 12);
        let img = image(&r);
        let rel = metrics::compare(&img, &reference, ev).expect("compare");
        errors.push((rel.relmse, rel.flip));
    }
    eprintln!(
        "without gradients relMSE {:.5} FLIP {:.4}; with {:.5} {:.4}",
        errors[0].0, errors[0].1, errors[1].0, errors[1].1
    );
    assert!(errors[1].0 < errors[0].0, "gradients: relMSE {:.5} not below {:.5}", errors[1].0, errors[0].0);
    assert!(errors[1].1 < errors[0].1, "gradients: FLIP {:.4} not below {:.4}", errors[1].1, errors[0].1);
}

/// Moves the camera 8.5 cm (a small move: some surface is uncovered at the view's edge).
fn nudge_camera(project: &mut Project) {
    let mut camera = *project.scene.camera();
    camera.position += Vec3::new(0.08, 0.03, 0.0);
    project.scene.set_camera(camera);
}

/// Renders one frame, then waits for the GPU outside it (as the editor starts a frame once the
/// last has finished, so the frame's readback lands for the next).
fn frame(r: &mut Renderer, project: &Project, settings: &RenderSettings) {
    r.render(&project.scene, settings, SIZE).expect("render");
    r.wait_for_gpu().expect("gpu");
}

#[test]
fn a_small_camera_move_reuses_most_records() {
    let Some(ctx) = common::gpu() else { return };
    let (mut project, _) = cornell();
    let settings = with(&project, GiMode::Rcs, RcsSettings::default());
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    converge(&mut r, &project, &settings, SIZE, 12);
    let before = counter(&r, "records");
    nudge_camera(&mut project);
    // The first frame finds the uncovered pixels, the second makes their records.
    frame(&mut r, &project, &settings);
    frame(&mut r, &project, &settings);
    let made = counter(&r, "records made last frame");
    let reused = counter(&r, "records reused last frame");
    eprintln!("{before} records; after the move {made} made, {reused} reused");
    assert_eq!(reused, before, "every record survives the move");
    assert!(made > 0, "the move uncovers some surface");
    assert!((made as f64) < 0.15 * before as f64, "{made} new records of {before}: the cache was not reused");
}

#[test]
fn no_frame_waits_for_the_gpu_and_a_camera_move_gets_its_records_the_next_frame() {
    let Some(ctx) = common::gpu() else { return };
    let (mut project, _) = cornell();
    let settings = with(&project, GiMode::Rcs, RcsSettings::default());
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    let frames = converge(&mut r, &project, &settings, SIZE, 24);
    assert!(frames < 24, "the cache did not converge in {frames} frames");
    // Converged: the readbacks found nothing to do, so still frames read nothing back and
    // show the same image.
    frame(&mut r, &project, &settings);
    let seen = r.read_hdr().expect("hdr");
    for still in 0..2 {
        frame(&mut r, &project, &settings);
        assert_eq!(counter(&r, "GPU waits last frame"), 0, "still frame {still} waited for the GPU");
        assert_eq!(counter(&r, "uncovered tiles"), 0);
        assert!(r.read_hdr().expect("hdr") == seen, "still frame {still} differs from the frame before");
    }
    nudge_camera(&mut project);
    let mut made = Vec::new();
    for _ in 0..2 {
        // `frame` waits after `render`, outside it; the counter is the waits inside the frame.
        // (`readback::blocking_waits` counts the whole process: `cargo test` runs tests beside
        // this one in threads.)
        frame(&mut r, &project, &settings);
        made.push(counter(&r, "records made last frame"));
        assert_eq!(counter(&r, "GPU waits last frame"), 0, "a frame after the move waited for the GPU");
    }
    eprintln!("records made in the two frames after the move: {made:?}");
    assert_eq!(made[0], 0, "the first frame after the move has no readback of the new view yet");
    assert!(made[1] > 0, "the uncovered surface got no records in the frame after");
    // Another mode and back drops the cache: the frames after it place records again, however
    // quiet the view was before.
    frame(&mut r, &project, &with(&project, GiMode::Direct, RcsSettings::default()));
    frame(&mut r, &project, &settings);
    frame(&mut r, &project, &settings);
    assert!(counter(&r, "records made last frame") > 0, "back in rcs, the second frame placed no record");
}

/// Two 4 x 4 m halves of a floor split by a closed 0.3 m wall 2 m high, a point light 1.5 m up
/// in each half (below the wall's top, so neither lights the other half), a 0.6 m box in the
/// west half; the camera looks down on both.
fn two_rooms() -> Project {
    use bouncelab::scene::{Camera, Light, Material, MeshSource, Transform};
    let cuboid = |size: Vec3| MeshSource::Cuboid { size, openings: [false; 6] };
    let at = |p: Vec3| Transform { translation: p, ..Default::default() };
    let objects = vec![
        common::object("floor", cuboid(Vec3::new(8.6, 0.2, 4.0)), 0, at(Vec3::new(0.0, -0.1, 0.0))),
        common::object("wall", cuboid(Vec3::new(0.3, 2.0, 4.0)), 0, at(Vec3::new(0.0, 1.0, 0.0))),
        common::object("box", cuboid(Vec3::splat(0.6)), 1, at(Vec3::new(-2.2, 0.3, 0.5))),
    ];
    let lights = vec![
        Light::point("west lamp", Vec3::new(-2.0, 1.5, -0.8), 15.0),
        Light::point("east lamp", Vec3::new(2.0, 1.5, 0.0), 15.0),
    ];
    let camera = Camera::look_at(Vec3::new(0.0, 7.5, 5.0), Vec3::new(0.0, 0.0, 0.0), 1.0);
    let materials = vec![Material::diffuse("grey", [0.7; 3]), Material::diffuse("red", [0.8, 0.2, 0.1])];
    let scene = common::scene(objects, materials, lights, camera);
    Project { assets: Vec::new(), scene, render: RenderSettings::default(), imported: Vec::new() }
}

/// Times each record was computed, by slot (0: free).
fn computed(r: &Renderer) -> Vec<(Vec3, u32)> {
    let t = r.technique_as::<RcsTechnique>().expect("rcs");
    let records = t.read_records(r.device(), r.queue()).expect("records");
    records
        .iter()
        .map(|x| {
            (
                Vec3::new(x.position[0], x.position[1], x.position[2]),
                if x.position[3] > 0.0 { x.normal[3] as u32 } else { 0 },
            )
        })
        .collect()
}

/// The two rooms with a converged cache: the project, its settings, the renderer and each
/// slot's record before an edit.
fn warm_two_rooms(ctx: &bouncelab::render::GpuContext) -> (Project, RenderSettings, Renderer, Vec<(Vec3, u32)>) {
    let project = two_rooms();
    let settings = with(&project, GiMode::Rcs, RcsSettings::default());
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    converge(&mut r, &project, &settings, SIZE, 16);
    let before = computed(&r);
    (project, settings, r, before)
}

#[test]
fn moving_one_light_renews_only_the_records_it_changes() {
    let Some(ctx) = common::gpu() else { return };
    let (mut project, settings, mut r, before) = warm_two_rooms(&ctx);
    project.scene.desc_mut().lights[0].position += Vec3::new(0.4, 0.0, 0.3);
    converge(&mut r, &project, &settings, SIZE, 16);
    let after = computed(&r);
    let renewals = counter(&r, "light check renewals");
    let (mut renewed_west, mut renewed_east, mut east) = (0, 0, 0);
    for ((p, a), (_, b)) in before.iter().zip(&after) {
        if *a == 0 {
            continue;
        }
        let renewed = b > a;
        if p.x > 0.2 {
            east += 1;
            renewed_east += usize::from(renewed);
        } else {
            renewed_west += usize::from(renewed);
        }
    }
    let live = before.iter().filter(|x| x.1 > 0).count();
    eprintln!("{live} records; the light check renewed {renewals}: {renewed_west} west, {renewed_east} of {east} east");
    assert!(renewed_west > 0 && renewals > 0, "moving the west lamp renewed nothing");
    assert!(east > live / 4, "{east} of {live} records in the east half");
    assert_eq!(renewed_east, 0, "records in the east half, which the west lamp cannot reach, were renewed");
    assert!((renewals as usize) < live, "every record was renewed");
    // What stayed is right: the image matches a cache built from scratch for the moved lamp.
    let incremental = r.read_hdr().expect("hdr");
    let mut fresh = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    converge(&mut fresh, &project, &settings, SIZE, 16);
    let scratch = fresh.read_hdr().expect("hdr");
    let (a, b) = (
        HdrImage { width: SIZE.0, height: SIZE.1, pixels: incremental },
        HdrImage { width: SIZE.0, height: SIZE.1, pixels: scratch },
    );
    let ratio = metrics::luminance_ratio(&a, &b).expect("ratio");
    eprintln!("incremental / from scratch energy {ratio:.4}");
    assert!((ratio - 1.0).abs() < 0.01, "the renewed cache reads {ratio:.4} of one built from scratch");
}

#[test]
fn moving_an_object_drops_its_records_and_keeps_the_far_half() {
    let Some(ctx) = common::gpu() else { return };
    let (mut project, settings, mut r, before) = warm_two_rooms(&ctx);
    let on_box = before
        .iter()
        .filter(|(p, c)| *c > 0 && p.x < -1.85 && p.x > -2.55 && p.z > 0.15 && p.z < 0.85 && p.y > 0.01)
        .count();
    project.scene.desc_mut().objects[2].transform.translation += Vec3::new(0.0, 0.0, -0.8);
    let renewed_before = counter(&r, "records renewed");
    // The edit's frame drops the records and finds what to redo; the next renews them.
    frame(&mut r, &project, &settings);
    frame(&mut r, &project, &settings);
    let after = computed(&r);
    let dropped = counter(&r, "records dropped");
    let renewed_east = before.iter().zip(&after).filter(|((p, a), (_, b))| *a > 0 && p.x > 0.2 && b != a).count();
    let renewed = counter(&r, "records renewed") - renewed_before;
    eprintln!("{on_box} records on the box; dropped {dropped}; renewed {renewed}; east changed {renewed_east}");
    assert!(on_box > 0 && dropped as usize >= on_box, "records on the moved box were not dropped");
    assert!(renewed > 0, "no neighbour of the box was renewed");
    assert_eq!(renewed_east, 0, "records beyond the wall changed");
}

#[test]
fn the_inspector_buffers_show_the_fill_and_a_covered_converged_cache() {
    let Some(ctx) = common::gpu() else { return };
    let (project, _) = cornell();
    let settings = with(&project, GiMode::Rcs, RcsSettings::default());
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    r.render(&project.scene, &settings, SIZE).expect("render");
    let added = |r: &Renderer| {
        let img = r.read_buffer("rcs_records_added").expect("records added");
        img.pixels.iter().filter(|p| p[0] > 0.0).count()
    };
    let first = added(&r);
    converge(&mut r, &project, &settings, SIZE, 16);
    r.render(&project.scene, &settings, SIZE).expect("render");
    let coverage = r.read_buffer("rcs_coverage").expect("coverage");
    let geometry = coverage.pixels.iter().filter(|p| p[2] > 0.5).count();
    let uncovered = coverage.pixels.iter().filter(|p| p[0] > 0.5).count();
    let weight = r.read_buffer("rcs_weight").expect("weight");
    let weighted = weight.pixels.iter().zip(&coverage.pixels).filter(|(w, c)| c[2] > 0.5 && w[0] > 0.0).count();
    let count = r.read_buffer("rcs_record_count").expect("count");
    let most = count.pixels.iter().map(|p| p[0]).fold(0.0f32, f32::max);
    let with = r.read_buffer("rcs_irradiance").expect("irradiance");
    let plain = r.read_buffer("rcs_irradiance_plain").expect("plain");
    let difference = r.read_buffer("rcs_gradient_difference").expect("difference");
    let mut worst = 0.0f32;
    for ((a, b), d) in with.pixels.iter().zip(&plain.pixels).zip(&difference.pixels) {
        worst = worst.max((a[0] - b[0] - d[0]).abs());
    }
    let planes = r.read_buffer("rcs_hemispheres").expect("planes");
    eprintln!(
        "first frame added records at {first} pixels, after convergence {}; {geometry} geometry pixels, {uncovered} uncovered, {weighted} weighted, up to {most} records a pixel; planes {}x{}",
        added(&r),
        planes.width,
        planes.height
    );
    assert!(first > 50, "the first frame placed records at {first} pixels");
    assert_eq!(added(&r), 0, "a converged cache of an unchanged view adds no record");
    assert!(geometry > (SIZE.0 * SIZE.1 / 2) as usize);
    assert_eq!(uncovered, 0, "pixels uncovered after the cache filled");
    assert_eq!(weighted, geometry, "every geometry pixel has some weight");
    assert!(most >= 2.0, "zones overlap: at most {most} records reach a pixel");
    assert!(worst < 1e-4, "the gradient difference is not with minus without ({worst})");
}

#[test]
fn a_cache_or_view_larger_than_the_adapter_allows_is_refused_with_what_to_change() {
    use bouncelab::render::gi::SupportQuery;
    // WebGPU's default 128 MiB storage binding holds 131072 records' check strata.
    let limits = wgpu::Limits::default();
    let query = |max_records| {
        let settings = RenderSettings {
            mode: GiMode::Rcs,
            rcs: RcsSettings { max_records, ..RcsSettings::default() },
            ..RenderSettings::default()
        };
        RcsTechnique::support(&SupportQuery {
            limits: &limits,
            features: wgpu::Features::empty(),
            size: SIZE,
            settings: &settings,
        })
    };
    assert_eq!(query(16384), Ok(()));
    let e = query(262_144).expect_err("256 MiB of strata");
    assert!(e.contains("rcs.max_records") && e.contains("131072"), "{e}");
    // The splat sums take 16 bytes a pixel in one binding: 4K fits 128 MiB, 4096 x 2160 not.
    let view = |size| {
        let settings = RenderSettings { mode: GiMode::Rcs, ..RenderSettings::default() };
        RcsTechnique::support(&SupportQuery {
            limits: &limits,
            features: wgpu::Features::empty(),
            size,
            settings: &settings,
        })
    };
    assert_eq!(view((3840, 2160)), Ok(()));
    let e = view((4096, 2160)).expect_err("135 MiB of sums");
    assert!(e.contains("4096x2160") && e.contains("render smaller"), "{e}");
}

/// The Cornell box lit by its short box glowing (3 W/(sr m²)) and a constant sky through its
/// open front, with its lamp off.
fn glowing_cornell_under_a_sky(sky: f32) -> Project {
    let (mut project, _) = cornell();
    let mut desc = project.scene.desc().clone();
    for light in &mut desc.lights {
        light.intensity = 0.0;
    }
    let mut glow = bouncelab::scene::Material::diffuse("glow", [0.2; 3]);
    glow.emissive_color = [1.0, 0.8, 0.5];
    glow.emissive_strength = 3.0;
    desc.materials.push(glow);
    let m = desc.materials.len() - 1;
    if let Some(o) = desc.objects.iter_mut().find(|o| o.name == "short_box") {
        o.material = m;
    }
    desc.environment.sky = bouncelab::scene::Sky::Constant([0.4, 0.6, 1.0]);
    desc.environment.intensity = sky;
    project.set_desc(desc).expect("scene");
    project
}

#[test]
fn rcs_records_see_emissive_surfaces_and_the_sky_and_renew_when_the_sky_changes() {
    let Some(ctx) = common::gpu() else { return };
    let size = (64, 36);
    let big = (size.0 * 2, size.1 * 2);
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    for sky in [1.0f32, 3.0] {
        let project = glowing_cornell_under_a_sky(sky);
        let reference = common::reference(
            &project.scene,
            size,
            bouncelab::settings::ReferenceSettings { spp: 128, ..Default::default() },
        );
        r.render(&project.scene, &with(&project, GiMode::Direct, RcsSettings::default()), big).expect("render");
        let shrink = |r: &Renderer| HdrImage {
            width: size.0,
            height: size.1,
            pixels: bouncelab::image_io::box_downsample(&r.read_hdr().expect("hdr"), big, 2),
        };
        let direct = shrink(&r);
        converge(&mut r, &project, &with(&project, GiMode::Rcs, RcsSettings::default()), big, 16);
        let rcs = shrink(&r);
        let ev = bouncelab::metrics::judging_exposure(&reference);
        let fd = metrics::flip(&direct, &reference, ev).expect("flip").0;
        let fr = metrics::flip(&rcs, &reference, ev).expect("flip").0;
        let energy = metrics::luminance_ratio(&rcs, &reference).expect("ratio");
        eprintln!("sky x{sky}: rcs energy {energy:.3}, FLIP {fr:.4} vs direct {fd:.4}");
        assert!((0.9..=1.1).contains(&energy), "sky x{sky}: rcs energy {energy:.3} of the reference");
        assert!(fr < 0.5 * fd, "sky x{sky}: rcs FLIP {fr:.4} is not below half of direct's {fd:.4}");
    }
}

/// A spot grazes a dark glossy floor (`common::glossy_cornell`): most of the floor's first-bounce
/// light leaves it in its lobe, and the records' hemisphere renders must send it (as a diffuse
/// sender: the lobe's directional albedo per light). One bounce finds 0.98 of the one-bounce
/// reference's indirect light; with the floor sending its albedo alone it found 0.66.
#[test]
fn records_gather_the_light_a_glossy_floor_sends_in_its_lobe() {
    let Some(ctx) = common::gpu() else { return };
    let project = common::glossy_cornell();
    let size = (64, 36);
    let one_bounce = common::reference(
        &project.scene,
        size,
        bouncelab::settings::ReferenceSettings { spp: 256, max_bounces: 2, ..Default::default() },
    );
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    r.render(&project.scene, &with(&project, GiMode::Direct, RcsSettings::default()), size).expect("render");
    let hdr = |r: &Renderer| HdrImage { width: size.0, height: size.1, pixels: r.read_hdr().expect("hdr") };
    let direct = metrics::mean_luminance(&hdr(&r));
    let rcs = RcsSettings { bounces: 1, ..RcsSettings::default() };
    let frames = converge(&mut r, &project, &with(&project, GiMode::Rcs, rcs), size, 16);
    let lit = metrics::mean_luminance(&hdr(&r));
    let found = (lit - direct) / (metrics::mean_luminance(&one_bounce) - direct);
    eprintln!("glossy floor: rcs finds {found:.3} of the one-bounce reference's indirect light after {frames} frames");
    assert!((0.85..=1.15).contains(&found), "rcs finds {found:.3} of the reference's indirect light");
}

/// The splat keeps a record for a 16 x 16 tile only where its zone meets the box of the tile's
/// pixels that face its way; the test must drop no record that reaches a pixel. A cache filled
/// with the test and one filled with every record splatted at every pixel give the same image
/// (and so the same coverage, records and bounces at every step).
#[test]
fn the_splats_tile_test_drops_no_record_that_reaches_a_pixel() {
    use bouncelab::render::gi::rcs::splat::keep_every_record_in_every_tile;
    let Some(ctx) = common::gpu() else { return };
    let mut project = two_rooms();
    let settings = with(&project, GiMode::Rcs, RcsSettings::default());
    let run = |project: &Project, every: bool| {
        keep_every_record_in_every_tile(every);
        let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
        converge(&mut r, project, &settings, SIZE, 16);
        let records = counter(&r, "records");
        (r.read_hdr().expect("hdr"), records)
    };
    // A view from the side as well: tiles whose pixels face several ways and lie far apart.
    for view in 0..2 {
        let (tested, records) = run(&project, false);
        let (every, records_every) = run(&project, true);
        keep_every_record_in_every_tile(false);
        assert_eq!(records, records_every, "view {view}: the fills differ");
        assert!(records > 20, "view {view}: {records} records: no cache to splat");
        let worst =
            tested.iter().zip(&every).map(|(a, b)| (a[0] - b[0]).abs().max((a[1] - b[1]).abs())).fold(0.0f32, f32::max);
        assert!(worst <= 1e-6, "view {view}: the tile test changed a pixel by {worst}");
        let side = bouncelab::scene::Camera::look_at(Vec3::new(-3.5, 1.2, 3.5), Vec3::new(0.5, 0.3, -0.5), 1.0);
        project.scene.set_camera(side);
    }
}
