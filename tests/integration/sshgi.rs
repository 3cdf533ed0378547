//! `sshgi` (Soler et al. 2010) against the reference path tracer on the Cornell box, at 128x72
//! with a 64x36 start level (the suite's quality matrix renders 256x144 with the default quarter
//! start, the same start level): the first bounce's units (Eq. 4's form factor and the levels'
//! 2^(2k) energy scale applied once), bounces that add energy without creating any, and the
//! issue's bars for the whole technique (less than 0.6x the FLIP of `direct`, mean luminance
//! within 10%: it reads 0.905); a visibility difference buffer equal to an unshadowed render's,
//! and a voxel slice viewer that ORs its slice range; a closed wall that stops the
//! light with visibility and leaks it without; the temporal filter on a moving camera; voting
//! that drops a one-pixel pole from the coarse levels instead of letting it flicker; a start level
//! over its texel cap that starts coarser, exactly as the level it lands on.

use crate::common;

use bouncelab::image_io::HdrImage;
use bouncelab::metrics;
use bouncelab::project_file::Project;
use bouncelab::render::{GpuContext, Renderer};
use bouncelab::settings::{GiMode, ReferenceSettings, RenderSettings, SshgiSettings};
use bouncelab::suite;
use std::path::Path;

const SIZE: (u32, u32) = (128, 72);

/// Half resolution: a 64x36 start level at [`SIZE`].
const START: u32 = 1;

/// The mean of `frames` frames (each frame rotates the sample pattern; sshgi has no temporal
/// filter yet, so the test averages what a temporal filter would).
fn render(ctx: &GpuContext, project: &Project, settings: &RenderSettings, frames: usize) -> HdrImage {
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    let mut sum = vec![[0.0f32; 4]; (SIZE.0 * SIZE.1) as usize];
    for _ in 0..frames {
        r.render(&project.scene, settings, SIZE).expect("render");
        for (s, p) in sum.iter_mut().zip(r.read_hdr().expect("hdr")) {
            (0..4).for_each(|c| s[c] += p[c] / frames as f32);
        }
    }
    HdrImage { width: SIZE.0, height: SIZE.1, pixels: sum }
}

fn with(project: &Project, mode: GiMode, sshgi: SshgiSettings) -> RenderSettings {
    RenderSettings { mode, sshgi, ..project.render.clone() }
}

#[test]
fn sshgi_on_the_cornell_box_has_the_first_bounces_units_and_bounces_add_energy_without_creating_it() {
    let Some(ctx) = common::gpu() else { return };
    let project = suite::scene("cornell").expect("suite scene").load(Path::new(".")).expect("cornell");
    let direct = render(&ctx, &project, &with(&project, GiMode::Direct, SshgiSettings::default()), 1);
    let one_bounce =
        common::reference(&project.scene, SIZE, ReferenceSettings { spp: 128, max_bounces: 2, ..Default::default() });
    let full = suite::scene("cornell").expect("suite scene").reference(Path::new(".")).expect("cached reference");
    let mean = metrics::mean_luminance;
    let lum: Vec<f64> = (1..=3)
        .map(|bounces| {
            let settings = with(
                &project,
                GiMode::Sshgi,
                SshgiSettings { bounces, start_level: START, bounce_tail: false, ..Default::default() },
            );
            mean(&render(&ctx, &project, &settings, 4))
        })
        .collect();
    let (d, r1, rf) = (mean(&direct), mean(&one_bounce), mean(&full));
    // One bounce: the share of the one-bounce reference's indirect light it finds. Off-screen
    // and hidden senders are missing, so below 1; a wrong pi or a doubled 4^k scale is far off.
    let first = (lum[0] - d) / (r1 - d);
    eprintln!(
        "indirect of one bounce vs the one-bounce reference {first:.3}; luminance by bounces {lum:?}, reference {rf:.4}"
    );
    assert!((0.7..=1.1).contains(&first), "first bounce finds {first:.3} of the one-bounce reference's indirect light");
    assert!(lum[0] < lum[1] && lum[1] < lum[2], "each bounce adds light: {lum:?}");
    assert!(lum[2] <= rf * 1.02, "three bounces {:.4} exceed the all-bounce reference {rf:.4}", lum[2]);
}

#[test]
fn the_bounce_tail_stands_for_the_bounces_after_the_last_and_stays_under_the_reference() {
    let Some(ctx) = common::gpu() else { return };
    let project = suite::scene("cornell").expect("suite scene").load(Path::new(".")).expect("cornell");
    let full = suite::scene("cornell").expect("suite scene").reference(Path::new(".")).expect("cached reference");
    let lum = |bounces, bounce_tail| {
        let sshgi = SshgiSettings { bounces, bounce_tail, start_level: START, ..Default::default() };
        metrics::mean_luminance(&render(&ctx, &project, &with(&project, GiMode::Sshgi, sshgi), 4))
    };
    let (two, four) = (lum(2, false), lum(4, false));
    let (two_tail, four_tail) = (lum(2, true), lum(4, true));
    let rf = metrics::mean_luminance(&full);
    eprintln!(
        "two bounces {two:.4}, with the tail {two_tail:.4}; four {four:.4}, with the tail {four_tail:.4}; reference {rf:.4}"
    );
    // The tail adds what the bounces after the last would: two bounces with it come near four,
    // and four with it add less than two did (the series converges).
    assert!(
        two_tail > two && four_tail > four,
        "the tail adds light: {two:.4} -> {two_tail:.4}, {four:.4} -> {four_tail:.4}"
    );
    assert!(two_tail >= 0.5 * (two + four), "two bounces and the tail {two_tail:.4} stay far below four {four:.4}");
    assert!(four_tail - four < two_tail - two, "the tail after four bounces adds more than after two");
    assert!(four_tail <= rf * 1.05, "four bounces and the tail {four_tail:.4} exceed the reference {rf:.4}");
}

#[test]
fn sshgi_on_the_cornell_box_has_under_six_tenths_of_directs_flip_and_energy_within_ten_percent() {
    let Some(ctx) = common::gpu() else { return };
    // As the quality matrix renders it: default settings at 256x144, box-filtered to the cached
    // reference's 128x72 pixels.
    let project = suite::scene("cornell").expect("suite scene").load(Path::new(".")).expect("cornell");
    let reference = suite::scene("cornell").expect("suite scene").reference(Path::new(".")).expect("cached reference");
    let big = (SIZE.0 * 2, SIZE.1 * 2);
    let render_big = |settings: &RenderSettings, frames: usize| {
        let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
        let mut sum = vec![[0.0f32; 4]; (big.0 * big.1) as usize];
        for _ in 0..frames {
            r.render(&project.scene, settings, big).expect("render");
            for (s, p) in sum.iter_mut().zip(r.read_hdr().expect("hdr")) {
                (0..4).for_each(|c| s[c] += p[c] / frames as f32);
            }
        }
        HdrImage { width: SIZE.0, height: SIZE.1, pixels: bouncelab::image_io::box_downsample(&sum, big, 2) }
    };
    let direct = render_big(&with(&project, GiMode::Direct, SshgiSettings::default()), 1);
    let sshgi = render_big(&with(&project, GiMode::Sshgi, SshgiSettings::default()), 8);
    let ev = bouncelab::metrics::judging_exposure(&reference);
    let fd = metrics::flip(&direct, &reference, ev).expect("flip").0;
    let fs = metrics::flip(&sshgi, &reference, ev).expect("flip").0;
    let energy = metrics::luminance_ratio(&sshgi, &reference).expect("ratio");
    eprintln!("sshgi FLIP {fs:.4} vs direct {fd:.4} ({:.2}); energy {energy:.3}", fs / fd);
    assert!(fs < 0.6 * fd, "sshgi FLIP {fs:.4} is not below 0.6 x direct's {fd:.4}");
    // The 10%: the defaults read 0.905 (off-screen and hidden senders send nothing, and
    // Eq. 4's bound loses 2% at 64 samples against 256). Before the march ran between the voted
    // points' own pixels over half-size columns it read 0.881.
    assert!((0.9..=1.1).contains(&energy), "sshgi energy {energy:.3} of the reference");
}

#[test]
fn a_start_level_over_the_texel_cap_starts_where_the_cap_allows_and_renders_as_that_level() {
    let Some(ctx) = common::gpu() else { return };
    let project = suite::scene("cornell").expect("suite scene").load(Path::new(".")).expect("cornell");
    let big = (SIZE.0 * 2, SIZE.1 * 2);
    // One frame: the start level's gather size, the image, and whether the GI panel's notes
    // name the capped start (64x36 in place of 128x72).
    let frame = |sshgi: SshgiSettings| {
        let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
        let settings = with(&project, GiMode::Sshgi, sshgi);
        r.render(&project.scene, &settings, big).expect("render");
        let gather = r.read_buffer("sshgi_gather_0").expect("start level gather");
        let notes = r.limitations(&project.scene, &settings);
        assert_eq!(
            notes.iter().any(|n| n.contains("starts its gathers at 64x36 texels, not 128x72")),
            settings.sshgi.max_start_texels > 0,
            "the notes name the capped start exactly when the cap acts: {notes:?}"
        );
        ((gather.width, gather.height), r.read_hdr().expect("hdr"))
    };
    let half = SshgiSettings { start_level: 1, temporal_weight: 0.0, ..Default::default() };
    // 256x144 halves to 128x72 (9,216 texels), over a cap of 64x36: one more halving.
    let (capped_size, capped) = frame(SshgiSettings { max_start_texels: 64 * 36, ..half.clone() });
    let (uncapped_size, _) = frame(SshgiSettings { max_start_texels: 0, ..half.clone() });
    let (quarter_size, quarter) = frame(SshgiSettings { start_level: 2, max_start_texels: 0, ..half });
    assert_eq!(uncapped_size, (128, 72), "without a cap the start level is the one set");
    assert_eq!(capped_size, (64, 36), "the capped start level holds at most the cap's texels");
    assert_eq!(quarter_size, (64, 36));
    // Every pass the Cornell box runs (voxel level, ring radius, energy scale, the panorama's
    // gather and receive per start texel) takes the start the cap chose: the image equals that of
    // the level set directly.
    let worst =
        capped.iter().zip(&quarter).flat_map(|(a, b)| (0..3).map(move |c| (a[c] - b[c]).abs())).fold(0.0f32, f32::max);
    assert!(worst <= 1e-6, "the capped start renders unlike the quarter start it chose: worst difference {worst}");
}

/// A floor with a spot-lit patch on its left, a closed 0.3 m wall standing across it, and a
/// receiver block on the right whose -X face looks at the patch over the wall: every path from
/// the patch to that face passes through the wall.
fn walled_scene() -> bouncelab::scene::Scene {
    use bouncelab::scene::{Camera, Light, Material, MeshSource, Transform};
    use glam::Vec3;
    let cuboid = |size: Vec3| MeshSource::Cuboid { size, openings: [false; 6] };
    let at = |p: Vec3| Transform { translation: p, ..Default::default() };
    let objects = vec![
        common::object("floor", MeshSource::Plane { size: 8.0 }, 0, Transform::default()),
        common::object("wall", cuboid(Vec3::new(0.3, 1.5, 3.0)), 0, at(Vec3::new(0.0, 0.75, 0.0))),
        common::object("receiver", cuboid(Vec3::new(0.3, 1.5, 3.0)), 0, at(Vec3::new(1.3, 0.75, 0.0))),
    ];
    let spot = Light::spot("spot", Vec3::new(-1.6, 3.0, 0.0), Vec3::NEG_Y, 30.0, 0.25, 0.35);
    let camera = Camera::look_at(Vec3::new(-0.6, 4.0, 5.0), Vec3::new(0.2, 0.3, 0.0), 0.9);
    common::scene(objects, vec![Material::diffuse("grey", [0.8; 3])], vec![spot], camera)
}

#[test]
fn sshgi_visibility_stops_the_light_a_closed_wall_blocks_which_leaks_without_it() {
    let Some(ctx) = common::gpu() else { return };
    let mut project = Project::load(&bouncelab::project_file::default_project_path()).expect("project");
    project.scene = walled_scene();
    let receiver_light = |visibility: bool| {
        let sshgi =
            SshgiSettings { start_level: START, bounces: 1, visibility, temporal_weight: 0.0, ..Default::default() };
        let settings = with(&project, GiMode::Sshgi, sshgi);
        let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
        r.render(&project.scene, &settings, SIZE).expect("render");
        let indirect = r.read_buffer("indirect").expect("indirect");
        let ids = r.read_buffer("object_id").expect("ids");
        let receiver = 3.0;
        let values: Vec<f64> = ids
            .pixels
            .iter()
            .zip(&indirect.pixels)
            .filter(|(id, _)| id[0] == receiver)
            .map(|(_, p)| f64::from(0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]))
            .collect();
        assert!(values.len() > 100, "the receiver covers {} pixels", values.len());
        values.iter().sum::<f64>() / values.len() as f64
    };
    let (with_vis, without) = (receiver_light(true), receiver_light(false));
    eprintln!("receiver E/pi: visibility on {with_vis:.5}, off {without:.5}");
    assert!(without > 1e-3, "without visibility the patch's light leaks onto the receiver: {without:.5}");
    assert!(with_vis < 0.2 * without, "visibility leaves {with_vis:.5} of the leak's {without:.5}");
}

#[test]
fn sshgi_inspector_difference_is_the_light_visibility_removes_and_the_slice_viewer_ors_its_range() {
    let Some(ctx) = common::gpu() else { return };
    let mut project = Project::load(&bouncelab::project_file::default_project_path()).expect("project");
    project.scene = walled_scene();
    let settings = |visibility: bool| {
        let sshgi =
            SshgiSettings { start_level: START, bounces: 1, visibility, temporal_weight: 0.0, ..Default::default() };
        with(&project, GiMode::Sshgi, sshgi)
    };
    // The first frame of a fresh renderer has the same sample pattern in both runs.
    let mut open = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    open.render(&project.scene, &settings(false), SIZE).expect("render");
    let unshadowed = open.read_buffer("sshgi_bounce_1").expect("bounce 1");
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    r.set_inspected(Some("sshgi_visibility_difference"));
    r.render(&project.scene, &settings(true), SIZE).expect("render");
    let shadowed = r.read_buffer("sshgi_bounce_1").expect("bounce 1");
    let difference = r.read_buffer("sshgi_visibility_difference").expect("difference");
    assert_eq!((difference.width, difference.height), (shadowed.width, shadowed.height));
    let (mut blocked, mut worst) = (0.0f64, 0.0f32);
    for ((d, o), s) in difference.pixels.iter().zip(&unshadowed.pixels).zip(&shadowed.pixels) {
        blocked += f64::from(d[1]);
        worst = worst.max((d[1] - (o[1] - s[1])).abs());
    }
    eprintln!(
        "visibility removes {:.5} E/pi per texel; worst mismatch {worst:.2e}",
        blocked / difference.pixels.len() as f64
    );
    assert!(blocked > 0.0, "the wall blocks light: the difference sums to {blocked}");
    assert!(worst < 1e-4, "the difference differs from an unshadowed render's by {worst}");

    // The slice viewer: the OR over every slice is the view's solid columns; the slices in
    // front of the nearest voxel hold nothing.
    let columns = r.read_buffer("sshgi_voxels").expect("voxels");
    let all = r.read_buffer("sshgi_voxel_slices@0,0,127").expect("all slices");
    assert_eq!((all.width, all.height), (columns.width, columns.height));
    let solid: Vec<bool> = columns.pixels.iter().map(|p| p[0] > 0.0).collect();
    assert!(solid.iter().any(|&s| s), "the wall voxelises");
    assert!(all.pixels.iter().zip(&solid).all(|(p, &s)| (p[0] == 1.0) == s), "OR of all slices = solid columns");
    let nearest = columns.pixels.iter().filter(|p| p[0] > 0.0).map(|p| (p[1] * 128.0) as u32).min().expect("solid");
    if nearest > 0 {
        let front = r.read_buffer(&format!("sshgi_voxel_slices@0,0,{}", nearest - 1)).expect("front");
        assert!(front.pixels.iter().all(|p| p[0] == 0.0), "nothing before slice {nearest}");
    }
    let one = r.read_buffer(&format!("sshgi_voxel_slices@0,{nearest},{nearest}")).expect("one slice");
    assert!(one.pixels.iter().any(|p| p[0] == 1.0), "slice {nearest} holds the nearest voxel");
    assert!(r.read_buffer("sshgi_voxel_slices@0,9,3").is_err(), "a reversed range is an error");
}

#[test]
fn sshgi_temporal_filter_steadies_a_moving_camera() {
    let Some(ctx) = common::gpu() else { return };
    let mut project = suite::scene("cornell").expect("suite scene").load(Path::new(".")).expect("cornell");
    let start = project.scene.desc().camera.position;
    let change = |temporal_weight: f32, temporal_two_tap: bool, project: &mut Project| {
        let sshgi = SshgiSettings { start_level: START, temporal_weight, temporal_two_tap, ..Default::default() };
        let settings = with(project, GiMode::Sshgi, sshgi);
        let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
        let frames: Vec<HdrImage> = (0..16)
            .map(|i| {
                project.scene.desc_mut().camera.position = start + glam::Vec3::new(0.004 * i as f32, 0.0, 0.0);
                r.render(&project.scene, &settings, SIZE).expect("render");
                HdrImage { width: SIZE.0, height: SIZE.1, pixels: r.read_hdr().expect("hdr") }
            })
            .collect();
        metrics::mean_frame_change(&frames[6..]).expect("frames")
    };
    let raw = change(0.0, false, &mut project);
    let (filtered, light) = (change(0.85, false, &mut project), change(0.5, false, &mut project));
    let two_tap = change(0.5, true, &mut project);
    eprintln!(
        "mean frame change on a moving camera: recursive a=0.85 {filtered:.5}, a=0.5 {light:.5}, 2-tap a=0.5 {two_tap:.5}, none {raw:.5}"
    );
    assert!(filtered < 0.7 * raw, "the temporal filter leaves {filtered:.5} of {raw:.5}");
    assert!(filtered < light, "a larger history weight steadies more: {filtered:.5} vs {light:.5}");
    // The paper's 2-tap blend of two raw frames halves the noise of their difference at best:
    // steadier than none, less steady than the recursive history of the same weight.
    assert!(two_tap < 0.8 * raw && two_tap > light, "2-tap {two_tap:.5}, recursive {light:.5}, none {raw:.5}");
}

#[test]
fn voting_drops_a_one_pixel_pole_from_coarse_levels_in_every_frame_of_a_slow_pan() {
    use bouncelab::scene::{Camera, Light, Material, MeshSource, Transform};
    use glam::Vec3;
    let Some(ctx) = common::gpu() else { return };
    // A 6 cm pole 4 m away in a 64x36 view (8.7 cm per pixel) in front of a wall 2 m behind it.
    let size = (64, 36);
    let cuboid = |size: Vec3| MeshSource::Cuboid { size, openings: [false; 6] };
    let at = |p: Vec3| Transform { translation: p, ..Default::default() };
    let objects = vec![
        common::object("wall", cuboid(Vec3::new(12.0, 6.0, 0.2)), 0, at(Vec3::new(0.0, 1.0, -2.1))),
        common::object("pole", cuboid(Vec3::new(0.06, 4.0, 0.06)), 0, at(Vec3::new(0.0, 1.0, 0.0))),
    ];
    let light = Light::point("lamp", Vec3::new(0.0, 2.0, 3.0), 20.0);
    let mut project = Project::load(&bouncelab::project_file::default_project_path()).expect("project");
    let settings = with(&project, GiMode::Sshgi, SshgiSettings::default());
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    let (mut frames_with_pole, mut coarse_hits) = (0, Vec::new());
    for i in 0..8 {
        // A quarter of a pixel per frame.
        let x = 0.022 * i as f32;
        let camera = Camera::look_at(Vec3::new(x, 1.0, 4.0), Vec3::new(x, 1.0, 0.0), 0.8);
        let materials = vec![Material::diffuse("grey", [0.7; 3])];
        project.scene = common::scene(objects.clone(), materials, vec![light.clone()], camera);
        r.render(&project.scene, &settings, size).expect("render");
        // Pyramid texels nearer than the wall (6 m) are the pole's.
        let pole = |img: &HdrImage| img.pixels.iter().filter(|p| p[3] > 0.5 && p[0] < 5.0).count();
        let fine = pole(&r.read_buffer("pyramid_0").expect("level 0"));
        frames_with_pole += usize::from(fine > 0);
        coarse_hits.push((1..3).map(|l| pole(&r.read_buffer(&format!("pyramid_{l}")).expect("level"))).sum::<usize>());
    }
    assert!(frames_with_pole >= 4, "the pole is on screen in {frames_with_pole} of 8 frames");
    assert!(coarse_hits.iter().all(|&n| n == 0), "pole texels on levels 1-2 per frame: {coarse_hits:?}");
}

/// The claim of docs/notes/sshgi.md: on the Cornell box at the default settings, sshgi's first
/// bounce matches the exact screen-space gather it approximates (every start-level texel's light
/// with the paper's bounded form factor and ray-cast visibility) to 0.1% (`examples/
/// sshgi_oracle.rs`, release build). Held here within 1% over 16 frames; and visibility takes
/// light away (the boxes shadow the floor and walls), so the exact gather with it is below the
/// one without.
#[test]
fn sshgi_first_bounce_matches_the_exact_screen_space_gather_on_the_cornell_box() {
    let Some(ctx) = common::gpu() else { return };
    let project = suite::scene("cornell").expect("scene").load(Path::new(".")).expect("loads");
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    let report =
        bouncelab::render::gi::sshgi::oracle::first_bounce(&mut r, &project, &SshgiSettings::default(), (256, 144), 16)
            .expect("oracle");
    let ratio = report.sshgi / report.visible;
    eprintln!(
        "cornell: sshgi {:.5}, exact gather {:.5} ({ratio:.4}), without visibility {:.5}",
        report.sshgi, report.visible, report.unoccluded
    );
    assert!((ratio - 1.0).abs() < 0.01, "sshgi's first bounce is {ratio} of the exact gather");
    assert!(report.visible < 0.99 * report.unoccluded, "visibility removes light: {report:?}");
}
