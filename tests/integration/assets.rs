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
    let px = common::render(&ctx, &project.scene, &project.render, size);
    assert!(px.iter().all(|p| p.iter().all(|c| c.is_finite() && *c >= 0.0)), "finite, non-negative radiance");
    // Centre of the back wall: lit by the point light, white.
    let c = px[(18 * 64 + 32) as usize];
    assert!(c[0] > 0.01 && (c[0] - c[1]).abs() < 1e-3 * c[0].max(1.0) + 1e-4, "back wall is lit and grey: {c:?}");
}
