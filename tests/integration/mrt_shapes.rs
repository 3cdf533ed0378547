//! MRT on the fitter's shape levels (`bouncelab dev-levels`): the light that reaches each room
//! behind the lit room's doorways and corridors, MRT's reduced-space transfer on the CPU (the
//! GPU runtime computes the same, `mrt.rs`) against a brute-force path of three diffuse bounces
//! in the real geometry (`probe-mrt`). With the tests' small dictionary (4x4 texels a face, 4x4
//! opening positions) MRT lands within a factor of about two of the brute force in every room;
//! the default dictionary's figures (within 15% on most shapes, not all) are in
//! `docs/notes/mrt.md`. A fit that missed a room or a link leaves that room dark and fails.

use clap::Parser as _;

use bouncelab::cli::probe_mrt::{ProbeMrtArgs, room_light};
use bouncelab::precompute::mrt::fit::shapes;
use glam::Vec3;

#[derive(clap::Parser)]
struct Args {
    #[command(flatten)]
    probe: ProbeMrtArgs,
}

/// The MRT tests' small dictionary.
const DICTIONARY: &str = "(res: 4, k_d: 32, k_b: 16, rays: 256, enrichment: 1, seed: 3, interfaces: (positions: 4, \
                          directions: 8, supersample: 1, k_rlf: 48, k_r: 16, enrichment: 1, bands: 2))";

#[test]
fn light_reaches_every_room_behind_the_doorways_and_corridors_of_every_shape() {
    let mut failures = Vec::new();
    for level in shapes::levels() {
        let name = format!("shape:{}", level.name);
        let args =
            Args::parse_from(["probe-mrt", &name, "--rays", "64", "--multi", "3", "--dictionary", DICTIONARY]).probe;
        let boxes: Vec<(Vec3, Vec3)> = level.rooms.iter().map(|(lo, hi)| (Vec3::from(*lo), Vec3::from(*hi))).collect();
        let rooms = room_light(&args, &boxes).expect("probes");
        for (k, r) in rooms.iter().enumerate() {
            let ratio = r.mrt / r.brute.max(1e-12);
            eprintln!("{} room {k}: {} blocks, MRT / brute force {ratio:.3}", level.name, r.blocks);
            if r.blocks == 0 || r.brute <= 0.0 || !(0.4..=1.6).contains(&ratio) {
                failures.push(format!("{} room {k}: {} blocks, MRT / brute force {ratio:.3}", level.name, r.blocks));
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}
