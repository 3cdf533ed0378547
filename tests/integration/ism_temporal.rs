//! Temporal behaviour of `ism` (Knecht 2009) against `ism-ritschel`: less flicker on a static
//! view while VPLs are resampled every frame and while a light and an object move, a bounded
//! afterglow after the light is switched off, and zero confidence where a moving object
//! uncovers the background, and a still view refining past c_base (`IsmSettings::still_frames`)
//! except while an edit's old history fades.

use crate::common;

use bouncelab::image_io::HdrImage;
use bouncelab::metrics;
use bouncelab::project_file::{Project, default_project_path};
use bouncelab::render::Renderer;
use bouncelab::settings::GiMode;

const SIZE: (u32, u32) = (64, 36);

fn frames(ctx: &bouncelab::render::GpuContext, project: &Project, mode: GiMode, n: usize) -> Vec<HdrImage> {
    let mut settings = project.render.clone();
    settings.mode = mode;
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    (0..n)
        .map(|_| {
            r.render(&project.scene, &settings, SIZE).expect("render");
            HdrImage { width: SIZE.0, height: SIZE.1, pixels: r.read_hdr().expect("hdr") }
        })
        .collect()
}

fn mean_lum(img: &HdrImage) -> f64 {
    metrics::mean_luminance(img)
}

#[test]
#[ignore = "heavy: 48 default-settings ism frames"]
fn temporal_reuse_flickers_less_than_ritschel() {
    let Some(ctx) = common::gpu() else { return };
    let project = Project::load(&default_project_path()).expect("default project");
    let warm = 12;
    let ism = frames(&ctx, &project, GiMode::Ism, warm + 12);
    let ritschel = frames(&ctx, &project, GiMode::IsmRitschel, warm + 12);
    let (fi, fr) = (
        metrics::mean_frame_change(&ism[warm..]).expect("frames"),
        metrics::mean_frame_change(&ritschel[warm..]).expect("frames"),
    );
    // The reference of a static scene does not change: its frame-to-frame change is 0.
    let static_ref = vec![ism[warm].clone(); 2];
    let (ti, tr) = (
        metrics::temporal_instability(&ism[warm..], &static_ref).expect("frames"),
        metrics::temporal_instability(&ritschel[warm..], &static_ref).expect("frames"),
    );
    eprintln!("mean frame-to-frame change: ism {fi:.5}, ism-ritschel {fr:.5} (instability {ti:.5} vs {tr:.5})");
    assert!(fi < 0.5 * fr, "temporal reuse must at least halve the flicker: {fi} vs {fr}");
    assert!(ti < 0.5 * tr, "temporal reuse must at least halve the temporal instability: {ti} vs {tr}");
    let (li, lr) = (mean_lum(&ism[ism.len() - 1]), mean_lum(&ritschel[ritschel.len() - 1]));
    assert!((li / lr - 1.0).abs() < 0.05, "same mean brightness: {li} vs {lr}");
}

#[test]
#[ignore = "heavy: up to 100 default-settings ism frames"]
fn afterglow_after_the_light_goes_off_is_bounded() {
    let Some(ctx) = common::gpu() else { return };
    let mut project = Project::load(&default_project_path()).expect("default project");
    let mut settings = project.render.clone();
    settings.mode = GiMode::Ism;
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    let indirect = |r: &Renderer| {
        let img = r.read_buffer("indirect").expect("indirect");
        metrics::mean_luminance(&img)
    };
    for _ in 0..20 {
        r.render(&project.scene, &settings, SIZE).expect("render");
    }
    let before = indirect(&r);
    project.scene.desc_mut().lights[0].intensity = 0.0;
    let mut frames_to_10 = None;
    for f in 1..=80 {
        r.render(&project.scene, &settings, SIZE).expect("render");
        if indirect(&r) < 0.1 * before {
            frames_to_10 = Some(f);
            break;
        }
    }
    eprintln!(
        "afterglow: indirect falls below 10% after {frames_to_10:?} frames (thesis EMA bound: ~22 at c_base 0.9)"
    );
    let f = frames_to_10.expect("the afterglow ends");
    assert!(f <= 30, "afterglow of {f} frames");
}

#[test]
fn confidence_is_zero_where_a_moving_object_uncovers_the_background() {
    let Some(ctx) = common::gpu() else { return };
    let mut project = Project::load(&default_project_path()).expect("default project");
    let mut settings = project.render.clone();
    settings.mode = GiMode::Ism;
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    for _ in 0..8 {
        r.render(&project.scene, &settings, SIZE).expect("render");
    }
    let box_index = project.scene.objects().iter().position(|o| o.name == "short_box").expect("short box");
    let ids_before = r.read_buffer("object_id").expect("ids");
    let static_conf = r.read_buffer("ism_confidence").expect("confidence");
    project.scene.desc_mut().objects[box_index].transform.translation.x -= 0.35;
    r.render(&project.scene, &settings, SIZE).expect("render");
    let ids_after = r.read_buffer("object_id").expect("ids");
    let conf = r.read_buffer("ism_confidence").expect("confidence");
    let id = (box_index + 1) as f32;
    let uncovered: Vec<f32> = ids_before
        .pixels
        .iter()
        .zip(&ids_after.pixels)
        .zip(&conf.pixels)
        .filter(|((b, a), _)| b[0] == id && a[0] != id && a[0] != 0.0)
        .map(|(_, c)| c[3])
        .collect();
    let zero = uncovered.iter().filter(|c| **c < 0.05).count();
    let static_mean = static_conf.pixels.iter().map(|c| c[3]).sum::<f32>() / static_conf.pixels.len() as f32;
    eprintln!(
        "uncovered pixels: {} ({} with confidence < 0.05); mean confidence of the static frame {static_mean:.3}",
        uncovered.len(),
        zero
    );
    assert!(uncovered.len() > 20, "the box uncovers background");
    assert!(zero as f32 >= 0.9 * uncovered.len() as f32, "confidence must drop to zero on disocclusion");
}

#[test]
#[ignore = "heavy: 48 default-settings ism frames and 16 references"]
fn moving_light_and_object_flicker_less_than_ritschel() {
    use bouncelab::settings::ReferenceSettings;
    let Some(ctx) = common::gpu() else { return };
    let project = Project::load(&default_project_path()).expect("default project");
    let tall = project.scene.objects().iter().position(|o| o.name == "tall_box").expect("tall box");
    let light0 = project.scene.lights()[0].position;
    let box0 = project.scene.objects()[tall].transform.translation;
    // The light drifts 2.5 cm and the tall box 1 cm per frame.
    let at = |f: usize| {
        let mut p = project.clone();
        p.scene.desc_mut().lights[0].position = light0 + glam::Vec3::new(0.025 * f as f32, 0.0, 0.0);
        p.scene.desc_mut().objects[tall].transform.translation = box0 + glam::Vec3::new(0.01 * f as f32, 0.0, 0.0);
        p
    };
    let (warm, n) = (8, 16);
    let run = |mode: GiMode| {
        let mut settings = project.render.clone();
        settings.mode = mode;
        let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
        let mut out = Vec::new();
        for f in 0..warm + n {
            r.render(&at(f).scene, &settings, SIZE).expect("render");
            if f >= warm {
                out.push(HdrImage { width: SIZE.0, height: SIZE.1, pixels: r.read_hdr().expect("hdr") });
            }
        }
        out
    };
    let (ism, ritschel) = (run(GiMode::Ism), run(GiMode::IsmRitschel));
    // The reference sequence: the path tracer with the same seed every frame, so its own noise
    // barely changes between frames and its frame-to-frame change is the scene's.
    let reference: Vec<HdrImage> = (warm..warm + n)
        .map(|f| {
            let p = at(f);
            common::reference(&p.scene, SIZE, ReferenceSettings { spp: 128, seed: 7, ..Default::default() })
        })
        .collect();
    let (ti, tr) = (
        metrics::temporal_instability(&ism, &reference).expect("frames"),
        metrics::temporal_instability(&ritschel, &reference).expect("frames"),
    );
    let change = metrics::mean_frame_change(&reference).expect("frames");
    eprintln!(
        "moving light and box: reference change {change:.5}; temporal instability ism {ti:.5}, ism-ritschel {tr:.5}"
    );
    assert!(ti < 0.7 * tr, "ism must flicker measurably less than ism-ritschel under motion: {ti} vs {tr}");
}

/// Channel `c` of the pixels that see geometry (the history's buffers are 0 elsewhere).
fn on_geometry(img: &HdrImage, ids: &HdrImage, c: usize) -> Vec<f32> {
    img.pixels.iter().zip(&ids.pixels).filter(|(_, id)| id[0] != 0.0).map(|(p, _)| p[c]).collect()
}

fn mean(values: &[f32]) -> f32 {
    values.iter().sum::<f32>() / values.len().max(1) as f32
}

#[test]
fn a_still_view_refines_past_c_base_and_a_light_edit_returns_to_it_until_the_old_history_fades() {
    let Some(ctx) = common::gpu() else { return };
    let mut project = Project::load(&default_project_path()).expect("default project");
    let mut settings = project.render.clone();
    settings.mode = GiMode::Ism;
    settings.ism.vpl_count = 64;
    settings.ism.bounces = 2;
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    let read = |r: &Renderer, name: &str| r.read_buffer(name).expect(name);
    r.render(&project.scene, &settings, SIZE).expect("render");
    let ids = read(&r, "object_id");
    let first = mean(&on_geometry(&read(&r, "ism_history_count"), &ids, 0));
    assert!((first - 1.0).abs() < 1e-4, "a new history is worth one frame: {first}");
    for _ in 1..12 {
        r.render(&project.scene, &settings, SIZE).expect("render");
    }
    let count = mean(&on_geometry(&read(&r, "ism_history_count"), &ids, 0));
    let on = on_geometry(&read(&r, "ism_confidence"), &ids, 3);
    let past_c_base = on.iter().filter(|c| **c > 0.905).count() as f32 / on.len().max(1) as f32;
    eprintln!("after 12 still frames: history worth {count:.2} frames, {past_c_base:.2} of the pixels past c_base");
    // The plain mean of its frames at first: worth 12 frames at most.
    assert!(count > 8.0 && count <= 12.0 + 1e-3, "history worth {count} frames");
    // The thesis's confidence never exceeds c_base (0.9); a still view's does wherever the
    // surface stands where it stood (the illumination term is off while still).
    assert!(past_c_base > 0.5, "a still view refines past c_base: {past_c_base} of the pixels");
    project.scene.desc_mut().lights[0].position.x += 0.01;
    let mut after_edit = Vec::new();
    for _ in 0..10 {
        r.render(&project.scene, &settings, SIZE).expect("render");
        let conf = read(&r, "ism_confidence");
        after_edit.push(conf.pixels.iter().map(|c| c[3]).fold(0.0f32, f32::max));
    }
    eprintln!("largest confidence in the 10 frames after a light edit: {after_edit:.3?}");
    assert!(
        after_edit.iter().all(|c| *c <= settings.ism.base_confidence + 1e-5),
        "after an edit the confidence keeps c_base while the old history fades: {after_edit:?}"
    );
}
