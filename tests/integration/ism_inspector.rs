//! The ISM inspector buffers: the split G-buffer is an exact permutation of the G-buffer into
//! n x n tiles (Knecht 2009 Fig. 3.2), the atlas as splatted (a copy taken before hole
//! filling, a different buffer) has holes that the filled atlas covers; a splat changes only
//! when the push replaces it by a nearer surface seen through a hole (deeper than the coarse
//! depth by more than the threshold), the push marks exactly what it wrote, and every ISM
//! buffer reads back finite.

use crate::common;

use bouncelab::project_file::{Project, default_project_path};
use bouncelab::render::Renderer;
use bouncelab::settings::GiMode;

#[test]
fn split_gbuffer_and_atlas_views_are_consistent() {
    let Some(ctx) = common::gpu() else { return };
    let project = Project::load(&default_project_path()).expect("default project");
    let mut settings = project.render.clone();
    settings.mode = GiMode::Ism;
    settings.ism.bounces = 1;
    let n = settings.ism.interleave;
    // Not divisible by n: the split layout pads each block.
    let size = (70u32, 45u32);
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    // Showing the splats makes the technique copy each set's atlas rows before pull-push.
    r.set_inspected(Some("ism_atlas_splats"));
    r.render(&project.scene, &settings, size).expect("render");
    let normal = r.read_buffer("normal").expect("normal");
    let split = r.read_buffer("ism_split_normal").expect("split normals");
    let block = (size.0.div_ceil(n), size.1.div_ceil(n));
    assert_eq!((split.width, split.height), (block.0 * n, block.1 * n));
    let raw = r.read_buffer("ism_raw").expect("split accumulation");
    assert_eq!((raw.width, raw.height), (split.width, split.height));
    for y in 0..size.1 {
        for x in 0..size.0 {
            let (sx, sy) = ((x % n) * block.0 + x / n, (y % n) * block.1 + y / n);
            let a = normal.pixels[(y * size.0 + x) as usize];
            let b = split.pixels[(sy * split.width + sx) as usize];
            assert_eq!(a, b, "pixel ({x}, {y}) -> split ({sx}, {sy})");
        }
    }
    let after = r.read_buffer("ism_atlas").expect("atlas");
    let before = r.read_buffer("ism_atlas_splats").expect("atlas splats");
    assert_eq!((before.width, before.height), (after.width, after.height));
    let empty = |img: &bouncelab::image_io::HdrImage| img.pixels.iter().filter(|p| p[0] >= 1.0).count();
    let (mut splats, mut kept, mut farther, mut filled, mut unmarked_mismatch) = (0, 0, 0, 0, 0);
    for (b, a) in before.pixels.iter().zip(&after.pixels) {
        if b[0] < 1.0 {
            splats += 1;
            if a[0] == b[0] {
                kept += 1;
            } else if a[0] > b[0] {
                farther += 1;
            }
        } else if a[0] < 1.0 {
            filled += 1;
        }
        // The push marks what it fills with the lowest mantissa bit: unmarked texels of the
        // filled atlas are exactly the splat copy's.
        if a[0].to_bits() & 1 == 0 && a[0] != b[0] {
            unmarked_mismatch += 1;
        }
    }
    let (holes_before, holes_after) = (empty(&before), empty(&after));
    eprintln!(
        "atlas {}^2: {splats} splatted texels ({kept} unchanged after pull-push), {filled} holes filled; \
         empty before {holes_before}, after {holes_after}",
        after.width
    );
    assert!(splats > 1000, "the splat copy holds the splats: {splats}");
    assert!(filled > 0 && holes_after < holes_before, "pull-push filled nothing");
    assert!(kept as f64 > 0.8 * splats as f64, "pull-push replaced most splats: {kept} of {splats} kept");
    assert_eq!(farther, 0, "pull-push may only bring nearer surfaces forward, never push a splat back");
    assert_eq!(unmarked_mismatch, 0, "texels the push did not mark must equal the splat copy");
    for name in ["ism_confidence", "ism_history", "ism_light_power", "ism_importance", "indirect"] {
        let img = r.read_buffer(name).expect(name);
        assert!(img.pixels.iter().all(|p| p.iter().all(|v| v.is_finite())), "{name} is not finite");
    }
}
