//! `probe-mrt`'s light per room: the blocks' bounce light summed into rooms (by cuts along x, by
//! a shape level's rooms, or by boxes the caller names), MRT's against the brute force's.

use super::*;

/// One room's light, summed over the blocks whose centres lie in it (each texel weighted by its
/// face's area / res²).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RoomLight {
    /// The brute force's bounce light.
    pub brute: f64,
    /// MRT's bounce light.
    pub mrt: f64,
    /// The direct light (MRT's l_d).
    pub direct: f64,
    /// Blocks counted.
    pub blocks: usize,
}

/// Per room box of `rooms` (world min, max), MRT's and the brute force's bounce light over the
/// blocks whose centres lie in it: how much light reaches the rooms behind the doorways.
pub fn room_light(args: &ProbeMrtArgs, rooms: &[(Vec3, Vec3)]) -> anyhow::Result<Vec<RoomLight>> {
    let Setup { project, mut lvl, bvh, params, dictionary } = setup(args, &mut String::new())?;
    let scene = &project.scene;
    set_openings(scene, &bvh, &mut lvl, &dictionary, args);
    let ops = Operators { dictionary: &dictionary, interfaces: &dictionary.interfaces };
    let transfer = level::assemble(&lvl, &ops, 6);
    let probe = Probe { args, scene, bvh: &bvh, lvl: &lvl, dictionary: &dictionary, params, ops, transfer };
    let lit = Lit::new(&probe);
    let (mrt, _) = mrt_bounces(&probe, &lit);
    let truth = Brute::new(&probe).texels(&lit.texels);
    let room_of = |c: Vec3| rooms.iter().position(|(lo, hi)| c.cmpge(*lo).all() && c.cmple(*hi).all());
    Ok(room_sums(&probe, &lit, &truth, &mrt, &room_of, rooms.len()))
}

/// Area-weighted light per room (a texel stands for its face's area / res^2), the blocks
/// grouped by their centres along x at `--rooms-x`.
pub(super) fn rooms_report(
    probe: &Probe,
    lit: &Lit,
    truth: &[Vec<f64>],
    mrt: &[Vec<f64>],
    out: &mut String,
) -> fmt::Result {
    let cuts = &probe.args.rooms_x;
    let shape = probe.args.level.strip_prefix("shape:").and_then(|n| shape_level(n).ok()).filter(|_| cuts.is_empty());
    let boxes: Vec<(Vec3, Vec3)> =
        shape.map_or(Vec::new(), |l| l.rooms.iter().map(|(lo, hi)| (Vec3::from(*lo), Vec3::from(*hi))).collect());
    let sums = if boxes.is_empty() {
        let room_of = |c: Vec3| Some(cuts.iter().filter(|x| c.x > **x).count());
        room_sums(probe, lit, truth, mrt, &room_of, cuts.len() + 1)
    } else {
        let room_of = |c: Vec3| boxes.iter().position(|(lo, hi)| c.cmpge(*lo).all() && c.cmple(*hi).all());
        room_sums(probe, lit, truth, mrt, &room_of, boxes.len())
    };
    for (k, r) in sums.iter().enumerate() {
        let ratio = r.mrt / r.brute.max(1e-12);
        writeln!(
            out,
            "room {k}: direct {:.4}, brute-force bounce {:.4}, MRT bounce {:.4}: MRT / brute force {ratio:.3}",
            r.direct, r.brute, r.mrt
        )?;
    }
    Ok(())
}

/// The light of each block summed into the room `room_of` its centre (of `n` rooms).
fn room_sums(
    probe: &Probe,
    lit: &Lit,
    truth: &[Vec<f64>],
    mrt: &[Vec<f64>],
    room_of: &dyn Fn(Vec3) -> Option<usize>,
    n: usize,
) -> Vec<RoomLight> {
    let res = probe.params.res;
    let mut rooms = vec![RoomLight::default(); n];
    for (x, b) in probe.lvl.blocks.iter().enumerate() {
        let Some(r) = room_of(b.origin + 0.5 * b.size).and_then(|k| rooms.get_mut(k)) else { continue };
        r.blocks += 1;
        let layout = Layout::new(b.shape, res);
        let per = (res * res) as f64;
        for i in 0..layout.len() {
            let (face, _, _, _) = layout.sample(i);
            let area = f64::from(face_area(b.size, b.world_face(face).axis())) / per;
            r.brute += area * truth[x][i];
            r.mrt += area * mrt[x][i];
            r.direct += area * lit.l_d[x][i];
        }
    }
    rooms
}
