//! `mrt` (Loos 2015's modular radiance transfer) through the GI seam with a small dictionary
//! (4x4 texels per face, cached like any other): the suite's window room, a bare glTF whose
//! blocks are fitted when the mode is chosen, against its cached path-traced reference (energy
//! and FLIP well ahead of `direct`); linearity in the light; the feedback's bounces converging
//! frame after frame; a block edit that rebuilds the level while a light edit does not; a
//! level it cannot fit that renders direct light with a message; every inspector buffer.

use crate::common;

use std::path::Path;

use bouncelab::image_io::HdrImage;
use bouncelab::metrics;
use bouncelab::precompute::mrt::dictionary::DictionaryParams;
use bouncelab::precompute::mrt::operators::InterfaceParams;
use bouncelab::project_file::Project;
use bouncelab::render::Renderer;
use bouncelab::scene::{MeshSource, ObjectRole};
use bouncelab::settings::{BlockOverride, GiMode, MrtSettings, RenderSettings};
use bouncelab::suite;

const SIZE: (u32, u32) = (128, 72);

/// A dictionary small enough to build in a debug test (seconds), large enough to carry light.
fn small() -> MrtSettings {
    let interfaces =
        InterfaceParams { positions: 4, directions: 8, supersample: 1, k_rlf: 48, k_r: 16, enrichment: 1, bands: 2 };
    let dictionary = DictionaryParams { res: 4, k_d: 32, k_b: 16, rays: 256, enrichment: 1, seed: 3, interfaces };
    MrtSettings { dictionary, ..MrtSettings::default() }
}

fn settings(project: &Project, mrt: MrtSettings) -> RenderSettings {
    RenderSettings { mode: GiMode::Mrt, mrt, ..project.render.clone() }
}

/// Renders until the technique is ready (its dictionary and level prepared off the frame), then
/// `frames` more; returns the last image.
fn render(r: &mut Renderer, project: &Project, settings: &RenderSettings, frames: usize) -> HdrImage {
    common::until_ready(r, &project.scene, settings, SIZE);
    for _ in 1..frames {
        r.render(&project.scene, settings, SIZE).expect("render");
    }
    HdrImage { width: SIZE.0, height: SIZE.1, pixels: r.read_hdr().expect("hdr") }
}

fn window() -> Project {
    suite::scene("window").expect("suite scene").load(Path::new(".")).expect("window")
}

fn counter(r: &Renderer, name: &str) -> u64 {
    r.technique_status().map_or(0, |s| s.counter(name))
}

#[test]
fn mrt_on_a_bare_window_room_fits_its_block_and_beats_direct_against_the_reference() {
    let Some(ctx) = common::gpu() else { return };
    let project = window();
    assert!(!project.scene.objects().iter().any(|o| o.role == ObjectRole::ProxyBlock), "a bare level");
    let reference = suite::scene("window").expect("suite scene").reference(Path::new(".")).expect("reference");
    let ev = bouncelab::metrics::judging_exposure(&reference);
    let big = (SIZE.0 * 2, SIZE.1 * 2);
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    let s = settings(&project, small());
    let mut image = |s: &RenderSettings, frames: usize| {
        common::until_ready(&mut r, &project.scene, s, big);
        for _ in 1..frames {
            r.render(&project.scene, s, big).expect("render");
        }
        let pixels = bouncelab::image_io::box_downsample(&r.read_hdr().expect("hdr"), big, 2);
        (HdrImage { width: SIZE.0, height: SIZE.1, pixels }, r.limitations(&project.scene, s))
    };
    let (mrt, notes) = image(&s, 16);
    let (direct, _) = image(&RenderSettings { mode: GiMode::Direct, ..s.clone() }, 1);
    assert!(notes.iter().any(|n| n.contains("fitted")), "a bare level says its blocks were fitted: {notes:?}");
    let (m, d) = (
        metrics::compare(&mrt, &reference, ev).expect("same size"),
        metrics::compare(&direct, &reference, ev).expect("same size"),
    );
    eprintln!(
        "window, 4x4-texel dictionary: mrt energy {:.3} FLIP {:.4}; direct energy {:.3} FLIP {:.4}",
        m.luminance_ratio, m.flip, d.luminance_ratio, d.flip
    );
    assert!((0.85..=1.15).contains(&m.luminance_ratio), "mrt energy {:.3} of the reference", m.luminance_ratio);
    assert!(m.flip < 0.5 * d.flip, "mrt FLIP {:.4} against direct's {:.4}", m.flip, d.flip);
}

#[test]
fn mrt_indirect_light_is_linear_in_the_light_and_its_feedback_converges() {
    let Some(ctx) = common::gpu() else { return };
    let project = window();
    let one_bounce = settings(&project, MrtSettings { feedback: 0.0, ..small() });
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    let mean = |r: &Renderer| metrics::mean_luminance(&r.read_buffer("indirect").expect("indirect"));
    render(&mut r, &project, &one_bounce, 2);
    let first = mean(&r);
    // Twice every light: twice the indirect light (the whole pipeline is linear in l_d).
    let mut brighter = project.clone();
    for l in &mut brighter.scene.desc_mut().lights {
        l.intensity *= 2.0;
    }
    render(&mut r, &brighter, &one_bounce, 2);
    let doubled = mean(&r);
    eprintln!("one bounce: indirect {first:.5}, with twice the light {doubled:.5}");
    assert!(first > 0.0 && (doubled / first - 2.0).abs() < 0.01, "{doubled} / {first}");
    // The feedback adds a bounce per frame: the indirect light grows, then settles.
    let feedback = settings(&project, small());
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    render(&mut r, &project, &feedback, 1);
    // An editor renders an unchanged view only while the technique says it refines: the first
    // frame of a level must say so, or the feedback never gets its bounces.
    let first_frame = r.technique_status().expect("status");
    assert!(first_frame.refining && first_frame.refine_target == 16, "{first_frame:?}");
    let mut means = vec![mean(&r)];
    for _ in 0..23 {
        r.render(&project.scene, &feedback, SIZE).expect("render");
        means.push(mean(&r));
    }
    eprintln!("feedback: indirect by frame {means:.5?}");
    assert!((means[0] - first).abs() < 1e-3 * first, "the first frame is one bounce: {} vs {first}", means[0]);
    assert!(means[4] > means[0] * 1.05, "bounces add light: {means:?}");
    assert!((means[23] - means[15]).abs() < 0.01 * means[23], "settled: {means:?}");
    let status = r.technique_status().expect("status");
    assert!(!status.refining && status.history_frames >= status.refine_target, "{status:?}");
}

#[test]
fn a_block_edit_rebuilds_the_level_and_a_light_edit_does_not() {
    let Some(ctx) = common::gpu() else { return };
    let mut project = window();
    let fitted = bouncelab::precompute::mrt::proxy::fitted_objects(&project.scene).expect("fits");
    project.scene.desc_mut().objects.extend(fitted);
    let s = settings(&project, small());
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    let before = render(&mut r, &project, &s, 4);
    let builds = counter(&r, "level builds");
    assert_eq!(builds, 1);
    assert!(!r.limitations(&project.scene, &s).iter().any(|n| n.contains("fitted")), "blocks of its own");
    // A light edit: l_d changes every frame, the level stays.
    project.scene.desc_mut().lights[0].intensity *= 0.5;
    render(&mut r, &project, &s, 2);
    assert_eq!(counter(&r, "level builds"), builds, "a light edit keeps the level");
    // A block edit: shrink the proxy to half its depth; the level is rebuilt off the frame and
    // the image changes once it is in.
    let index = project.scene.objects().iter().position(|o| o.role == ObjectRole::ProxyBlock).expect("block");
    if let MeshSource::Cuboid { size, .. } = &mut project.scene.desc_mut().objects[index].source {
        size.z *= 0.5;
    }
    let started = std::time::Instant::now();
    while counter(&r, "level builds") == builds {
        r.render(&project.scene, &s, SIZE).expect("render");
        // A hang guard, not a speed check: the rebuild runs on a worker, sleep to leave it the
        // cores.
        assert!(started.elapsed().as_secs() < 600, "the edit never rebuilt the level");
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    eprintln!("block edit to rebuilt level: {:.0} ms (debug build)", started.elapsed().as_secs_f64() * 1e3);
    let after = render(&mut r, &project, &s, 2);
    let diff: f64 = before.pixels.iter().zip(&after.pixels).map(|(a, b)| f64::from((a[0] - b[0]).abs())).sum();
    assert!(diff > 0.0, "the edited block changed the image");
}

#[test]
fn a_level_without_rooms_renders_direct_light_and_says_why() {
    let Some(ctx) = common::gpu() else { return };
    // The Cornell box's open planes enclose no room the fitter accepts.
    let project = suite::scene("cornell").expect("suite scene").load(Path::new(".")).expect("cornell");
    let s = settings(&project, small());
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    let mrt = render(&mut r, &project, &s, 2);
    // Said as a shortfall (the result is not what was asked for: `render` refuses to write it
    // without --allow-partial), not as a note.
    let problems = r.shortfalls(&project.scene, &s);
    assert!(problems.iter().any(|n| n.contains("no proxy blocks")), "{problems:?}");
    assert!(mrt.pixels.iter().all(|p| p.iter().all(|v| v.is_finite())));
    let mut d = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    let direct = render(&mut d, &project, &RenderSettings { mode: GiMode::Direct, ..s.clone() }, 1);
    assert_eq!(mrt.pixels, direct.pixels, "nothing added where nothing was fitted");
}

#[test]
fn every_mrt_inspector_buffer_reads_back_finite() {
    let Some(ctx) = common::gpu() else { return };
    let project = window();
    let s = settings(&project, small());
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    render(&mut r, &project, &s, 3);
    for b in bouncelab::render::gi::registry::buffers(GiMode::Mrt) {
        let img = r.read_buffer(b.name).unwrap_or_else(|e| panic!("{}: {e}", b.name));
        assert!(img.width > 0 && img.height > 0, "{}", b.name);
        assert!(img.pixels.iter().flatten().all(|v| v.is_finite()), "{} holds non-finite values", b.name);
    }
    let lightmap = r.read_buffer("mrt_lightmap").expect("lightmap");
    assert!(metrics::mean_luminance(&lightmap) > 0.0, "the lightmap holds light");
}

#[test]
fn mrt_lights_the_unlit_third_room_of_a_bare_multi_room_level() {
    let Some(ctx) = common::gpu() else { return };
    // The suite's rooms: a spot in the first room, the camera in the third, two doorways away;
    // `direct` shows black. Blocks fitted on the fly (one per room), light carried through the
    // doorway sides.
    let project = suite::scene("rooms").expect("suite scene").load(Path::new(".")).expect("rooms");
    let reference = suite::scene("rooms").expect("suite scene").reference(Path::new(".")).expect("reference");
    let ev = bouncelab::metrics::judging_exposure(&reference);
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    let mrt = render(&mut r, &project, &settings(&project, small()), 16);
    let notes = r.limitations(&project.scene, &settings(&project, small()));
    assert!(notes.iter().any(|n| n.contains("3 were fitted")), "{notes:?}");
    assert!(!notes.iter().any(|n| n.contains("no proxy block covers") || n.contains("not linked")), "{notes:?}");
    // The overlay draws the fitted blocks (12 edges each) and their four linked sides.
    let overlays = r.overlays();
    let blocks = overlays.iter().find(|o| o.name.starts_with("MRT blocks")).expect("the blocks' overlay");
    let (edges, links) =
        (blocks.lines.iter().filter(|l| l.tone < 0.5).count(), blocks.lines.iter().filter(|l| l.tone == 0.6).count());
    assert_eq!((edges, links), (36, 4), "{:?}", blocks.lines);
    let mut d = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    let direct = render(&mut d, &project, &RenderSettings { mode: GiMode::Direct, ..project.render.clone() }, 1);
    let (m, dc) = (
        metrics::compare(&mrt, &reference, ev).expect("same size"),
        metrics::compare(&direct, &reference, ev).expect("same size"),
    );
    eprintln!(
        "rooms, 4x4-texel dictionary: mrt energy {:.3} FLIP {:.4}; direct energy {:.3} FLIP {:.4}",
        m.luminance_ratio, m.flip, dc.luminance_ratio, dc.flip
    );
    assert!(dc.luminance_ratio < 0.01, "the view is unlit by direct light");
    assert!((0.5..=1.5).contains(&m.luminance_ratio), "mrt energy {:.3} of the reference", m.luminance_ratio);
    assert!(m.flip < 0.6 * dc.flip, "mrt FLIP {:.4} against direct's {:.4}", m.flip, dc.flip);
}

#[test]
fn padding_blends_two_blocks_that_split_one_room_so_their_seam_steps_less() {
    let Some(ctx) = common::gpu() else { return };
    // The window room covered by two hand-placed blocks, halves along x, open to each other over
    // their whole shared side: without padding each half reads its own edge texels and the
    // lightmap steps at the split plane.
    let mut project = window();
    let fitted = bouncelab::precompute::mrt::proxy::fitted_objects(&project.scene).expect("fits");
    let whole = fitted.first().expect("one block").clone();
    let MeshSource::Cuboid { size, .. } = whole.source else { panic!("a box") };
    let half = glam::Vec3::new(0.5 * size.x, size.y, size.z);
    for (k, dx) in [(0usize, -0.25), (1, 0.25)] {
        let mut o = whole.clone();
        let mut openings = [false; 6];
        // +X (index 0) on the west half, -X (index 1) on the east half.
        openings[k] = true;
        o.name = format!("half {k}");
        o.source = MeshSource::Cuboid { size: half, openings };
        o.transform.translation.x += dx * size.x;
        project.scene.desc_mut().objects.push(o);
    }
    let variation = |padding: bool| {
        let s = settings(&project, MrtSettings { padding, ..small() });
        let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
        render(&mut r, &project, &s, 4);
        let img = r.read_buffer("indirect").expect("indirect");
        let lum: Vec<f64> = img.pixels.iter().map(|p| f64::from(metrics::luminance(p))).collect();
        let w = img.width as usize;
        let mut tv = 0.0;
        for (i, v) in lum.iter().enumerate() {
            if i % w + 1 < w {
                tv += (lum[i + 1] - v).abs();
            }
        }
        tv
    };
    let (padded, unpadded) = (variation(true), variation(false));
    eprintln!("row variation of the indirect light: padded {padded:.4}, unpadded {unpadded:.4}");
    assert!(padded < unpadded, "padding smooths the seam: {padded} vs {unpadded}");
}

#[test]
fn an_objects_block_override_makes_its_surfaces_read_that_block_and_a_bad_name_is_reported() {
    let Some(ctx) = common::gpu() else { return };
    // The suite's rooms with their fitted blocks as objects ("proxy 1" .. "proxy 3"); the third
    // room's floor, seen by the camera, assigned to the first room's block.
    let mut project = suite::scene("rooms").expect("suite scene").load(Path::new(".")).expect("rooms");
    let fitted = bouncelab::precompute::mrt::proxy::fitted_objects(&project.scene).expect("fits");
    project.scene.desc_mut().objects.extend(fitted);
    let floor = project.scene.objects().iter().position(|o| o.name == "floor_2").expect("the third room's floor");
    let blocks_of_floor = |mrt: MrtSettings| {
        let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
        let s = settings(&project, mrt);
        render(&mut r, &project, &s, 1);
        let ids = r.read_buffer("object_id").expect("ids");
        let assignment = r.read_buffer("mrt_assignment").expect("assignment");
        let mut blocks: Vec<u32> = ids
            .pixels
            .iter()
            .zip(&assignment.pixels)
            .filter(|(id, _)| id[0] as usize == floor + 1)
            .map(|(_, a)| a[0] as u32)
            .collect();
        blocks.sort_unstable();
        blocks.dedup();
        (blocks, r.limitations(&project.scene, &s))
    };
    let (automatic, _) = blocks_of_floor(small());
    assert_eq!(automatic, vec![2], "the third room's floor reads the third block");
    let assigned = MrtSettings {
        block_overrides: vec![
            BlockOverride { object: "floor_2".into(), block: "proxy 1".into() },
            BlockOverride { object: "no such object".into(), block: "proxy 2".into() },
        ],
        ..small()
    };
    let (forced, notes) = blocks_of_floor(assigned);
    assert_eq!(forced, vec![0], "assigned to the first block");
    assert!(notes.iter().any(|n| n.contains("no object named \"no such object\"")), "{notes:?}");
}

#[test]
fn the_gpu_runtime_computes_what_the_cpu_reference_computes_in_the_reduced_spaces_side_texels_included() {
    use bouncelab::precompute::mrt::{cache, dictionary::Progress, geometry_image, level, proxy};
    use bouncelab::render::gi::mrt::technique::MrtTechnique;
    let Some(ctx) = common::gpu() else { return };
    // The suite's rooms with their blocks as objects: interfaces, transmissions and stretched
    // blocks all take part. One bounce, so the texels' indirect light is one pass of the
    // operators over this frame's l_d.
    let mut project = suite::scene("rooms").expect("suite scene").load(Path::new(".")).expect("rooms");
    let fitted = proxy::fitted_objects(&project.scene).expect("fits");
    project.scene.desc_mut().objects.extend(fitted);
    let mrt = MrtSettings { feedback: 0.0, ..small() };
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    render(&mut r, &project, &settings(&project, mrt.clone()), 2);
    let technique = r.technique_as::<MrtTechnique>().expect("mrt is active");
    let l_d = technique.texels(&ctx.device, &ctx.queue, "l_d").expect("a level").expect("readback");
    let gpu = technique.texels(&ctx.device, &ctx.queue, "indirect").expect("a level").expect("readback");
    let (_, packed) = technique.level().expect("a level");
    // The same level on the CPU: blocks, transmissions, dictionary, T_b->r.
    let (mut cpu_level, _) = proxy::level(&project.scene).expect("a level");
    let bvh = bouncelab::precompute::bvh::SceneBvh::build(&project.scene);
    let (d, _) =
        cache::load_or_build(&cache::default_dir(), &mrt.dictionary, &Progress::default()).expect("dictionary");
    for ((i, w), opening) in
        geometry_image::openings(&project.scene, &bvh, &cpu_level, d.interfaces.positions.positions)
    {
        cpu_level.set_opening(i, w, opening);
    }
    let ops = level::Operators { dictionary: &d, interfaces: &d.interfaces };
    let transfer = level::assemble(&cpu_level, &ops, mrt.depth as usize);
    let ranges: Vec<(usize, usize)> =
        packed.blocks.iter().map(|b| (b.texels[0] as usize, b.texels[1] as usize)).collect();
    let red: Vec<Vec<f64>> =
        ranges.iter().map(|(f, n)| l_d[*f..f + n].iter().map(|v| f64::from(v[0])).collect()).collect();
    let cpu = level::indirect(&cpu_level, &ops, &transfer, &red);
    let peak = cpu.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
    let mut worst = 0.0f64;
    for ((f, n), c) in ranges.iter().zip(&cpu) {
        for (g, c) in gpu[*f..f + n].iter().zip(c) {
            worst = worst.max((f64::from(g[0]) - c).abs());
        }
    }
    eprintln!("texel indirect, GPU against CPU: worst difference {worst:.3e} of a peak {peak:.3e}");
    assert!(peak > 0.0 && worst < 1e-3 * peak, "{worst} of {peak}");
    // The walls around the doorways (partly open sides) have their own texels (pass E): the
    // same light as the CPU's, side after side in (block, world side) order.
    let gpu_sides = technique.texels(&ctx.device, &ctx.queue, "sides").expect("a level").expect("readback");
    let mut cpu_sides = level::side_light(&cpu_level, &ops, &transfer, &red);
    cpu_sides.sort_by_key(|((x, w), _)| (*x, *w as usize));
    assert_eq!(cpu_sides.len(), 4, "both partitions, seen from either side");
    let cpu_flat: Vec<f64> = cpu_sides.into_iter().flat_map(|(_, v)| v).collect();
    assert_eq!(gpu_sides.len(), cpu_flat.len());
    let peak = cpu_flat.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let worst = gpu_sides.iter().zip(&cpu_flat).map(|(g, c)| (f64::from(g[0]) - c).abs()).fold(0.0, f64::max);
    eprintln!("side texels, GPU against CPU: worst difference {worst:.3e} of a peak {peak:.3e}");
    assert!(peak > 0.0 && worst < 1e-3 * peak, "{worst} of {peak}");
}

#[test]
fn a_level_the_fitter_covers_only_in_part_says_where_and_draws_the_gap() {
    let Some(ctx) = common::gpu() else { return };
    // Two storeys joined by a stairwell: blocks for each storey, the stairwell named and drawn.
    let dir = common::temp_dir("mrt", "partial");
    let path = dir.join("stacked.gltf");
    let level = bouncelab::precompute::mrt::fit::shapes::stacked();
    std::fs::write(&path, bouncelab::suite::shapes::gltf(&level).to_string_pretty()).expect("write");
    let project = Project::from_gltf(&path).expect("stacked");
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    let image = render(&mut r, &project, &settings(&project, small()), 2);
    assert!(image.pixels.iter().flatten().all(|v| v.is_finite()));
    let notes = r.limitations(&project.scene, &settings(&project, small()));
    let gap = notes.iter().find(|n| n.contains("between storeys")).unwrap_or_else(|| panic!("{notes:?}"));
    assert!(gap.contains("x 4.0..5.5") && gap.contains("z 0.5..3.0"), "{gap}");
    let overlays = r.overlays();
    let blocks = overlays.iter().find(|o| o.name.starts_with("MRT blocks")).expect("the blocks' overlay");
    assert!(blocks.lines.iter().any(|l| l.tone == 1.0), "the gap is drawn: {:?}", blocks.lines);
}

/// The window room lit only by the sky through its window (the texels of the hole let the sky
/// in) and the room lit only by emissive panels (the panels' texels emit, clutter's too), with
/// the small dictionary: energy within 15% of the path tracer and FLIP under half of `direct`'s,
/// where `direct` lights nothing; a sky edit rebuilds the level with the new sky.
#[test]
fn mrt_carries_the_sky_through_a_window_and_the_light_of_emissive_panels() {
    let Some(ctx) = common::gpu() else { return };
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    for name in ["skylight", "panels"] {
        let scene = suite::scene(name).expect("suite scene");
        let project = scene.load(Path::new(".")).expect("loads");
        let reference = scene.reference(Path::new(".")).expect("reference");
        let ev = bouncelab::metrics::judging_exposure(&reference);
        let s = settings(&project, small());
        let mrt = render(&mut r, &project, &s, 12);
        let direct = render(&mut r, &project, &RenderSettings { mode: GiMode::Direct, ..s.clone() }, 1);
        let (m, d) = (
            metrics::compare(&mrt, &reference, ev).expect("same size"),
            metrics::compare(&direct, &reference, ev).expect("same size"),
        );
        eprintln!(
            "{name}: mrt energy {:.3} FLIP {:.4}; direct energy {:.3} FLIP {:.4}",
            m.luminance_ratio, m.flip, d.luminance_ratio, d.flip
        );
        assert!((0.85..=1.15).contains(&m.luminance_ratio), "{name}: mrt energy {:.3}", m.luminance_ratio);
        assert!(m.flip < 0.5 * d.flip, "{name}: mrt FLIP {:.4} against direct's {:.4}", m.flip, d.flip);
        if name == "skylight" {
            let mut brighter = project.clone();
            let mut desc = brighter.scene.desc().clone();
            desc.environment.intensity *= 2.0;
            brighter.set_desc(desc).expect("sky");
            let again = render(&mut r, &brighter, &s, 12);
            let ratio = metrics::luminance_ratio(&again, &mrt).expect("ratio");
            eprintln!("skylight, sky x2: mrt image x{ratio:.3}");
            assert!((1.8..=2.2).contains(&ratio), "twice the sky gives x{ratio:.3}");
        }
    }
}
