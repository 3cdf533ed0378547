//! The GI technique seam: switching modes releases the previous technique's GPU memory
//! (measured by wgpu's allocator report and the techniques' own accounting), each edit resets
//! exactly the history it should, and the frame's shared depth/normal pyramid picks real
//! surfaces at every level.

use crate::common;

use bouncelab::project_file::{Project, default_project_path};
use bouncelab::render::Renderer;
use bouncelab::render::gi::ResetReason;
use bouncelab::settings::{GiMode, IsmSettings, RenderSettings};
use glam::Vec3;

const SIZE: (u32, u32) = (48, 27);

fn light_ism(project: &Project) -> RenderSettings {
    RenderSettings {
        mode: GiMode::Ism,
        ism: IsmSettings { vpl_count: 64, bounces: 2, total_points: 8192, ..IsmSettings::default() },
        ..project.render.clone()
    }
}

/// Bytes the allocator holds in allocations whose label contains `label` (except the small
/// parameter blocks that live with the pipelines), and in all.
fn allocated(device: &wgpu::Device, label: &str) -> Option<(u64, u64)> {
    let report = device.generate_allocator_report()?;
    let matching = report
        .allocations
        .iter()
        .filter(|a| a.name.contains(label) && !a.name.contains("params"))
        .map(|a| a.size)
        .sum();
    Some((matching, report.total_allocated_bytes))
}

#[test]
fn switching_from_ism_to_direct_frees_the_ism_gpu_memory() {
    let Some(ctx) = common::gpu() else { return };
    let project = Project::load(&default_project_path()).expect("default project");
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    let direct = RenderSettings { mode: GiMode::Direct, ..project.render.clone() };
    r.render(&project.scene, &direct, SIZE).expect("direct");
    let _ = ctx.device.poll(wgpu::PollType::wait_indefinitely());
    let base = allocated(&ctx.device, "ism");
    let settings = RenderSettings { mode: GiMode::Ism, ..project.render.clone() };
    for _ in 0..2 {
        r.render(&project.scene, &settings, SIZE).expect("ism");
    }
    let _ = ctx.device.poll(wgpu::PollType::wait_indefinitely());
    let held = r.technique_gpu_bytes();
    let ism_bytes = held.iter().find(|(m, _)| *m == GiMode::Ism).map_or(0, |(_, b)| *b);
    let during = allocated(&ctx.device, "ism");
    r.render(&project.scene, &direct, SIZE).expect("direct again");
    let _ = ctx.device.poll(wgpu::PollType::wait_indefinitely());
    let after = allocated(&ctx.device, "ism");
    let released = r.technique_gpu_bytes();
    eprintln!(
        "GPU memory: ism accounts {:.1} MiB while active; per technique after the switch {released:?}; \
         allocator (ism-labelled, total) before {base:?}, during {during:?}, after {after:?}",
        ism_bytes as f64 / 1048576.0
    );
    // 6 bounces x 256 VPLs at 128^2: the atlas alone is 5120^2 x 4 bytes = 100 MiB.
    assert!(ism_bytes > 100 << 20, "ism holds its atlas while active: {ism_bytes} bytes");
    assert!(released.iter().all(|(_, b)| *b == 0), "no technique holds memory in direct mode: {released:?}");
    // Where the adapter's allocator reports (Vulkan), the labelled allocations are gone too.
    if let (Some((ism_during, total_during)), Some((ism_after, total_after))) = (during, after) {
        assert!(ism_during > 100 << 20, "the allocator sees the ism buffers: {ism_during}");
        assert_eq!(ism_after, 0, "ism allocations left after switching to direct");
        assert!(total_during - total_after >= ism_during * 9 / 10, "{total_during} -> {total_after}");
    }
}

/// Renders `frames` ISM frames of `project` with `settings` and returns the status after.
fn status_after(
    r: &mut Renderer,
    project: &Project,
    settings: &RenderSettings,
    frames: usize,
) -> bouncelab::render::gi::TechniqueStatus {
    for _ in 0..frames {
        r.render(&project.scene, settings, SIZE).expect("render");
    }
    r.technique_status().expect("an active technique")
}

/// Warms ISM up for four frames and returns the renderer, the project and the status.
fn warmed() -> Option<(Renderer, Project, RenderSettings, bouncelab::render::gi::TechniqueStatus)> {
    let ctx = common::gpu()?;
    let project = Project::load(&default_project_path()).expect("default project");
    let settings = light_ism(&project);
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    let s = status_after(&mut r, &project, &settings, 4);
    assert_eq!(s.resets, [ResetReason::ModeEntered], "entering ism resets once");
    assert_eq!(s.history_frames, 4);
    Some((r, project, settings, s))
}

#[test]
fn moving_a_light_keeps_the_ism_history_and_the_point_data() {
    let Some((mut r, mut project, settings, before)) = warmed() else { return };
    project.scene.desc_mut().lights[0].position += Vec3::new(0.1, 0.0, 0.0);
    let after = status_after(&mut r, &project, &settings, 1);
    assert_eq!(after.last_reset, Some(ResetReason::LightEdited));
    assert_eq!(after.history_frames, before.history_frames + 1, "the confidence handles moving lights");
    assert_eq!(after.counter("point uploads"), before.counter("point uploads"), "lights do not move points");
    assert_eq!(after.counter("point rebuilds"), before.counter("point rebuilds"));
}

#[test]
fn moving_an_object_reuploads_its_points_and_keeps_the_history() {
    let Some((mut r, mut project, settings, before)) = warmed() else { return };
    project.scene.desc_mut().objects[5].transform.translation.x += 0.05;
    let after = status_after(&mut r, &project, &settings, 1);
    assert_eq!(after.last_reset, Some(ResetReason::SceneEdited));
    assert_eq!(after.history_frames, before.history_frames + 1, "the confidence handles moving objects");
    assert_eq!(after.counter("point uploads"), before.counter("point uploads") + 1, "moved points re-uploaded");
    assert_eq!(after.counter("point rebuilds"), before.counter("point rebuilds"), "same distribution");
    // Scaling changes the areas: the points are redistributed.
    project.scene.desc_mut().objects[5].transform.scale *= 1.1;
    let scaled = status_after(&mut r, &project, &settings, 1);
    assert_eq!(scaled.counter("point rebuilds"), before.counter("point rebuilds") + 1);
}

#[test]
fn a_camera_cut_drops_the_history_but_a_small_step_does_not() {
    let Some((mut r, mut project, settings, before)) = warmed() else { return };
    let mut cam = *project.scene.camera();
    cam.position += Vec3::new(0.02, 0.0, 0.0);
    project.scene.set_camera(cam);
    let step = status_after(&mut r, &project, &settings, 1);
    assert_eq!(step.history_frames, before.history_frames + 1, "a small step is reprojected");
    assert_eq!(step.resets.len(), before.resets.len(), "no reset for a small step");
    cam.position += Vec3::new(1.5, 0.0, -1.0);
    project.scene.set_camera(cam);
    let cut = status_after(&mut r, &project, &settings, 1);
    assert_eq!(cut.last_reset, Some(ResetReason::CameraCut));
    assert_eq!(cut.history_frames, 1, "the history restarts at the cut");
}

#[test]
fn changing_a_setting_drops_the_history() {
    let Some((mut r, project, mut settings, _)) = warmed() else { return };
    settings.ism.w_illumination *= 2.0;
    let changed = status_after(&mut r, &project, &settings, 1);
    assert_eq!(changed.last_reset, Some(ResetReason::SettingsChanged));
    assert_eq!(changed.history_frames, 1);
    // Exposure is display only.
    settings.view.exposure_ev += 1.0;
    let exposed = status_after(&mut r, &project, &settings, 1);
    assert_eq!(exposed.resets.len(), changed.resets.len());
    assert_eq!(exposed.history_frames, 2);
}

#[test]
fn entering_a_mode_resets_and_ism_ritschel_keeps_no_history() {
    let Some((mut r, project, mut settings, before)) = warmed() else { return };
    settings.mode = GiMode::IsmRitschel;
    let ritschel = status_after(&mut r, &project, &settings, 2);
    assert_eq!(ritschel.last_reset, Some(ResetReason::ModeEntered));
    assert_eq!(ritschel.resets.len(), before.resets.len() + 1);
    assert_eq!(ritschel.history_frames, 1, "ism-ritschel uses each frame alone");
    settings.mode = GiMode::Ism;
    let back = status_after(&mut r, &project, &settings, 3);
    assert_eq!(back.last_reset, Some(ResetReason::ModeEntered));
    assert_eq!(back.history_frames, 3);
    let resized = {
        r.render(&project.scene, &settings, (SIZE.0 + 8, SIZE.1)).expect("resize");
        r.technique_status().expect("status")
    };
    assert_eq!(resized.last_reset, Some(ResetReason::Resized));
    assert_eq!(resized.history_frames, 1);
}

#[test]
fn pyramid_levels_hold_one_of_their_children_never_an_average() {
    let Some(ctx) = common::gpu() else { return };
    let project = Project::load(&default_project_path()).expect("default project");
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    r.set_inspected(Some("pyramid_2"));
    r.render(&project.scene, &project.render, (64, 36)).expect("render");
    let levels: Vec<_> = (0..4).map(|l| r.read_buffer(&format!("pyramid_{l}")).expect("level")).collect();
    let depth = r.read_buffer("depth").expect("depth");
    let geometry = depth.pixels.iter().filter(|p| p[0] > 0.0).count();
    let seeded = levels[0].pixels.iter().filter(|p| p[3] > 0.5).count();
    assert_eq!(seeded, geometry, "level 0 marks exactly the pixels with geometry");
    for l in 1..levels.len() {
        let (fine, coarse) = (&levels[l - 1], &levels[l]);
        assert_eq!((coarse.width, coarse.height), ((fine.width / 2).max(1), (fine.height / 2).max(1)));
        for y in 0..coarse.height {
            for x in 0..coarse.width {
                let c = coarse.pixels[(y * coarse.width + x) as usize];
                let children: Vec<[f32; 4]> = (0..4)
                    .map(|k| {
                        let (fx, fy) = ((2 * x + (k & 1)).min(fine.width - 1), (2 * y + (k >> 1)).min(fine.height - 1));
                        fine.pixels[(fy * fine.width + fx) as usize]
                    })
                    .collect();
                if children.iter().all(|p| p[3] < 0.5) {
                    assert!(c[3] < 0.5, "level {l} ({x}, {y}) invents geometry");
                } else {
                    assert!(children.contains(&c), "level {l} ({x}, {y}) = {c:?} is none of {children:?}");
                }
            }
        }
    }
}
