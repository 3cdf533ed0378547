//! The ISM oracle (`bouncelab::render::gi::ism::oracle`, `bouncelab probe-ism`) holds the claim
//! docs/notes/ism-tuning.md makes from it ("What the oracle says now", measured with the power-
//! weighted pairs and unburied receivers: `probe-ism --power --unburied`): every set's lookups
//! read within 1% of the rays' light, and each set hands the next the power it reflects.

use crate::common;

use std::path::Path;

use bouncelab::project_file::Project;
use bouncelab::render::Renderer;
use bouncelab::render::gi::ism::oracle::{self, Capture, LookupOptions, Receivers};
use bouncelab::settings::{GiMode, IsmSettings};
use bouncelab::suite;

/// The most a set's lookups may read off the rays' lit share (|ism / true - 1|): the notes' 1%.
/// Measured on the three rooms (lavapipe, debug and release alike): 0.9962-0.9989 on the frame
/// checked, 0.9956-0.9995 over frames 2-9, so 0.56 points of margin.
const LOOKUP_TOLERANCE: f64 = 0.01;

/// Frames the bounce check sums (one frame scatters: see [`BOUNCE_TOLERANCE`]).
const BOUNCE_FRAMES: usize = 8;

/// The most the power a set hands the next, summed over [`BOUNCE_FRAMES`] frames, may be off the
/// power it reflects (|handed / reflected - 1|). The three rooms do not reach the notes' 1% on a
/// single frame: the frame checked reads 1.013, 1.006, 1.021 and 0.987 for sets 1-4, and single
/// frames scatter with a standard deviation of 1.5% (0.975-1.036 over 16 frames: the bounce pass
/// estimates each next VPL's power from a few VPLs). Summed over 8 frames they read 1.001, 1.008,
/// 1.002, 1.002, over 16 frames 0.999, 1.006, 1.008, 1.010: a bias up to 1% in the later sets.
/// 2.5% is that 1% plus about 2.7 standard deviations of an 8-frame sum (0.55%), so another
/// lavapipe's draw of the noise passes while a bounce pass off by 3% or more does not.
const BOUNCE_TOLERANCE: f64 = 0.025;

/// The three rooms with `ism` at its default settings, after the oracle's warm-up frames: the
/// project, its ISM settings and the renderer that holds the frame.
fn rooms_after_warm_up(ctx: &bouncelab::render::GpuContext) -> (Project, IsmSettings, Renderer) {
    let mut project = suite::scene("rooms").expect("suite scene").load(Path::new(".")).expect("rooms loads");
    project.render.mode = GiMode::Ism;
    project.render.ism = IsmSettings::default();
    let ism = project.render.ism.clone();
    let mut renderer = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    oracle::render_frames(&mut renderer, &project.scene, &project.render, oracle::WARM_UP_FRAMES).expect("renders");
    (project, ism, renderer)
}

/// `probe-ism rooms --power --unburied` through the library at the default ISM settings: per
/// set, the lookups' lit share over the rays' within [`LOOKUP_TOLERANCE`] of 1 and, per compared
/// set (all but the tail's), the power handed over the power reflected within
/// [`BOUNCE_TOLERANCE`] of 1. About 50 s in a debug build on two cores (each frame of the bounce
/// check renders a frame and traces 256 VPLs x 20000 receivers), hence the heavy tier.
#[test]
#[ignore = "heavy: about a minute in a debug build (the bounce check over eight frames)"]
fn ism_lookups_and_bounce_power_match_the_rays_on_the_three_rooms() {
    let Some(ctx) = common::gpu() else { return };
    let (project, ism, mut renderer) = rooms_after_warm_up(&ctx);
    let mut capture = Capture::read(&renderer, &project.scene, &ism).expect("reads the maps back");
    let receivers = Receivers::distribute(&capture, oracle::RECEIVERS);
    let options = LookupOptions { power_weighted: true, unburied: true, ..LookupOptions::default() };
    let lit: Vec<f64> =
        (0..ism.bounces as usize).map(|set| oracle::lookups(&capture, &receivers, &options, set).lit_ratio()).collect();
    let power: Vec<f64> = oracle::bounce_over_frames(
        &mut renderer,
        &project.render,
        &mut capture,
        &receivers,
        &options.filter,
        BOUNCE_FRAMES,
    )
    .expect("renders and reads the VPLs")
    .iter()
    .map(|r| r.ratio())
    .collect();
    eprintln!("rooms, default ISM settings: lookups ism/true per set {lit:.4?}; bounce power next/true {power:.4?}");
    assert_eq!((lit.len(), power.len()), (6, 4), "six sets, four compared (the last carries the tail)");
    for (set, r) in lit.iter().enumerate() {
        assert!((r - 1.0).abs() <= LOOKUP_TOLERANCE, "set {set}'s lookups read {r:.4} of the rays' light: {lit:.4?}");
    }
    for (source, r) in power.iter().enumerate() {
        assert!(
            (r - 1.0).abs() <= BOUNCE_TOLERANCE,
            "set {source} hands set {} {r:.4} of the power it reflects: {power:.4?}",
            source + 1
        );
    }
}

/// The most of the last set's chosen points that may lie behind their VPL (where the splat
/// drops them and no light of the VPL reaches). Measured on the three rooms (lavapipe, release):
/// 116,473 of 262,144 (44%) when `ism_select.wgsl` bounded a cluster's height above the VPL's
/// plane by its sphere, 40,195 (15%) with the clusters' planes; what remains lies in clusters that
/// mix two surfaces (a wall's foot and the floor).
const MOST_BEHIND: f64 = 0.25;

/// `probe-ism rooms --splat-lanes` through the library: the share of chosen points the splat
/// drops as lying behind their VPL stays below [`MOST_BEHIND`], so the points per ISM go to
/// surfaces that can shadow something.
#[test]
fn few_points_chosen_for_an_ism_lie_behind_its_vpl_on_the_three_rooms() {
    let Some(ctx) = common::gpu() else { return };
    let (project, ism, renderer) = rooms_after_warm_up(&ctx);
    let capture = Capture::read(&renderer, &project.scene, &ism).expect("reads the maps back");
    let lanes = oracle::splat_lanes(&capture, &renderer, &[32]).expect("reads the chosen points");
    let chosen = lanes.points + lanes.dropped.iter().sum::<usize>();
    let behind = lanes.dropped[1] as f64 / chosen.max(1) as f64;
    eprintln!("rooms: {} of {chosen} chosen points lie behind their VPL ({behind:.3})", lanes.dropped[1]);
    assert!(chosen > 100_000, "only {chosen} points were chosen");
    assert!(behind < MOST_BEHIND, "{behind:.3} of the chosen points lie behind their VPL");
}
