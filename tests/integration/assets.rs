//! The shipped assets are exactly what the generator makes (so they are reproducible), and the
//! default project renders on the software adapter.

use crate::common;

use std::path::Path;

use bouncelab::cli::generate;
use bouncelab::project_file::{Project, default_project_path};

#[test]
fn shipped_assets_are_current() {
    let gltf = Path::new("assets/cornell_box.gltf");
    assert_eq!(
        std::fs::read_to_string(gltf).expect("asset"),
        generate::cornell_gltf_text(),
        "run `bouncelab generate-assets`"
    );
    let project = default_project_path();
    let want = generate::default_project_text(gltf, &project).expect("project text");
    assert_eq!(std::fs::read_to_string(&project).expect("project"), want, "run `bouncelab generate-assets`");
}

#[test]
fn default_project_renders_plausibly() {
    let Some(ctx) = common::gpu() else { return };
    let project = Project::load(&default_project_path()).expect("loads");
    let size = (64, 36);
    // Direct light alone: the default project's own mode adds the walls' colour bleeding.
    let direct =
        bouncelab::settings::RenderSettings { mode: bouncelab::settings::GiMode::Direct, ..project.render.clone() };
    let px = common::render(&ctx, &project.scene, &direct, size);
    assert!(px.iter().all(|p| p.iter().all(|c| c.is_finite() && *c >= 0.0)), "finite, non-negative radiance");
    // Centre of the back wall: lit by the point light, white.
    let c = px[(18 * 64 + 32) as usize];
    assert!(c[0] > 0.01 && (c[0] - c[1]).abs() < 1e-3 * c[0].max(1.0) + 1e-4, "back wall is lit and grey: {c:?}");
}

/// The first run shows what the tool is for: on the default project every GI mode adds
/// indirect light to `direct` (the walls' bleeding onto the boxes and the ceiling), `mrt`
/// included, through the Cornell room's proxy block.
#[test]
fn every_gi_mode_shows_indirect_light_on_the_default_project() {
    let Some(ctx) = common::gpu() else { return };
    use bouncelab::render::{Renderer, harness};
    use bouncelab::settings::{GiMode, RenderSettings};
    let project = Project::load(&default_project_path()).expect("loads");
    let size = (48, 27);
    let mean = |mode: GiMode| {
        let settings = RenderSettings { mode, ..project.render.clone() };
        let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
        harness::until_ready(&mut r, &project.scene, &settings, size, |_| {}).expect("ready");
        let frames = harness::converge(&mut r, &project.scene, &settings, size, 64).expect("converges");
        let img = bouncelab::image_io::HdrImage { width: size.0, height: size.1, pixels: r.read_hdr().expect("hdr") };
        (bouncelab::metrics::mean_luminance(&img), frames)
    };
    let (direct, _) = mean(GiMode::Direct);
    for row in bouncelab::render::gi::registry::modes() {
        if matches!(row.mode, GiMode::Direct | GiMode::Reference) {
            continue;
        }
        let (gi, frames) = mean(row.mode);
        eprintln!("{}: {:.3} x direct after {frames} frames", row.mode.name(), gi / direct);
        assert!(
            gi > 1.1 * direct,
            "{} adds no indirect light to the default project: {gi} against direct's {direct}",
            row.mode.name()
        );
    }
}
