//! `bouncelab bench` rows for MRT's precompute (Loos 2015) on these cores: the dictionary with
//! its interface operators (what `mrt-dictionary` builds and caches), and, for random mazes of
//! 11 and 41 unit blocks (the sizes of the dissertation's Table 3.3), the level assembly of
//! T_{b->r} (what a block edit rebuilds) and one frame's indirect light in the reduced spaces
//! on the CPU; then the GPU runtime's per-stage cost on the suite's multi-room level, alone and
//! with those mazes as its proxy blocks, as ratios to `direct` on the same view.

use std::collections::HashMap;
use std::fmt::Write as _;
use std::time::Instant;

use crate::precompute::mrt::dictionary::{self, Dictionary, DictionaryParams, Progress};
use crate::precompute::mrt::level::{self, Block, Level, Operators};
use crate::precompute::mrt::operators::InterfaceParams;
use crate::precompute::mrt::proxy::shape_for;
use crate::precompute::mrt::shape::Face;
use crate::precompute::rng::Pcg32;

/// A random maze of `count` unit blocks: a spanning tree grown from one cell, each block open
/// towards its tree neighbours.
pub fn maze(count: usize, seed: u64) -> Level {
    let sides = [Face::PosX, Face::NegX, Face::PosZ, Face::NegZ];
    let step = |f: Face| match f {
        Face::PosX => (1, 0),
        Face::NegX => (-1, 0),
        Face::PosZ => (0, 1),
        _ => (0, -1),
    };
    let mut rng = Pcg32::new(seed, 0, 0);
    let mut cells: Vec<(i32, i32)> = vec![(0, 0)];
    let mut open: HashMap<(i32, i32), Vec<Face>> = HashMap::from([((0, 0), Vec::new())]);
    while cells.len() < count {
        let at = cells[(rng.next_u32() as usize) % cells.len()];
        let side = sides[(rng.next_u32() % 4) as usize];
        let (dx, dz) = step(side);
        let next = (at.0 + dx, at.1 + dz);
        if open.contains_key(&next) {
            continue;
        }
        open.entry(at).or_default().push(side);
        open.insert(next, vec![side.opposite()]);
        cells.push(next);
    }
    let blocks = cells
        .iter()
        .filter_map(|c| {
            let (shape, turns) = shape_for(&open[c])?;
            Some(Block::unit(shape, [c.0, 0, c.1], turns))
        })
        .collect();
    Level::new(blocks)
}

/// Appends the MRT precompute section.
pub fn mrt_rows(md: &mut String, quick: bool) -> anyhow::Result<()> {
    let params = if quick {
        let interfaces = InterfaceParams {
            positions: 6,
            directions: 12,
            supersample: 3,
            k_rlf: 128,
            k_r: 32,
            enrichment: 1,
            bands: 4,
        };
        DictionaryParams { res: 8, rays: 1024, interfaces, ..DictionaryParams::default() }
    } else {
        DictionaryParams::default()
    };
    let t = Instant::now();
    let d: Dictionary = dictionary::build(&params, &Progress::default())?;
    let build_s = t.elapsed().as_secs_f64();
    let i = &params.interfaces;
    let _ = writeln!(md, "\n## MRT precompute (Loos 2015, CPU)\n");
    let _ = writeln!(
        md,
        "{} threads. Dictionary of the six cube shapes at {}² texels per face, {} gather rays per texel, k_d {}, k_b {}, with the interface operators ({}² positions x {}² directions x {}² supersamples, k_rlf {}, k_r {}, {} enrichment passes): built in {build_s:.1} s (the dissertation: 119 s + 260 s on 12 cores at 16K rays); {:.2} MB of runtime operators. `bouncelab mrt-dictionary` caches it.\n",
        rayon::current_num_threads(),
        params.res,
        params.rays,
        params.k_d,
        params.k_b,
        i.positions,
        i.directions,
        i.supersample,
        d.interfaces.k_rlf,
        d.interfaces.response.k_r,
        i.enrichment,
        d.runtime_bytes() as f64 / 1e6
    );
    let _ = writeln!(
        md,
        "| maze | blocks | links | T_b->r blocks (depth 6) | assembly ms | T_b->r MB | one frame's reduced-space indirect, CPU ms |"
    );
    let _ = writeln!(md, "|---|---|---|---|---|---|---|");
    let ops = Operators { dictionary: &d, interfaces: &d.interfaces };
    for count in [11usize, 41] {
        let level = maze(count, 7);
        let t = Instant::now();
        let transfer = level::assemble(&level, &ops, 6);
        let assembly_ms = t.elapsed().as_secs_f64() * 1e3;
        let bytes: usize = transfer.blocks.values().map(|b| 4 * b.len()).sum();
        let l_d: Vec<Vec<f64>> = level
            .blocks
            .iter()
            .map(|b| d.element(b.shape).map_or(Vec::new(), |e| (0..e.n).map(|i| ((i % 7) as f64) * 0.1).collect()))
            .collect();
        let t = Instant::now();
        let _ = level::indirect(&level, &ops, &transfer, &l_d);
        let frame_ms = t.elapsed().as_secs_f64() * 1e3;
        let _ = writeln!(
            md,
            "| random tree | {} | {} | {} | {assembly_ms:.1} | {:.2} | {frame_ms:.1} |",
            level.blocks.len(),
            level.link_count(),
            transfer.blocks.len(),
            bytes as f64 / 1e6
        );
    }
    Ok(())
}

/// The proxy objects of `level`'s blocks (unrotated boxes with their world sides open).
fn proxies(level: &Level) -> Vec<crate::scene::Object> {
    use crate::precompute::mrt::proxy::{OPENING_ORDER, block_object};
    level
        .blocks
        .iter()
        .enumerate()
        .map(|(i, b)| {
            let mut openings = [false; 6];
            for f in b.shape.open_faces() {
                if let Some(k) = OPENING_ORDER.iter().position(|o| *o == b.world_face(*f)) {
                    openings[k] = true;
                }
            }
            block_object(&format!("maze {}", i + 1), b.origin, b.origin + b.size, openings)
        })
        .collect()
}

/// Appends MRT's per-frame GPU cost per stage on the suite's rooms (blocks fitted on the fly),
/// and with 11- and 41-block mazes as its proxy blocks (the stages scale with blocks and texels,
/// the apply pass with pixels x blocks), as ratios to `direct` on the same view.
pub fn mrt_runtime_rows(md: &mut String, ctx: &crate::render::GpuContext, quick: bool) -> anyhow::Result<()> {
    use crate::settings::GiMode;
    let rooms = crate::suite::scene("rooms")?.load(std::path::Path::new("."))?;
    let size = (640, 360);
    let frames = if quick { 5 } else { 20 };
    let direct = super::bench::measure(ctx, &rooms, GiMode::Direct, size, frames)?;
    let mut levels = vec![("the suite's rooms, 3 fitted blocks".to_owned(), rooms.clone())];
    for count in [11usize, 41] {
        let mut p = rooms.clone();
        p.scene.desc_mut().objects.extend(proxies(&maze(count, 7)));
        levels.push((format!("the rooms' view, a {count}-block maze as proxies"), p));
    }
    let _ = writeln!(md, "\n## MRT per frame (GPU runtime)\n");
    let _ = writeln!(
        md,
        "640x360, default settings (16² texels per face, k_b 32, k_r 32, depth 6, feedback on). `direct` on the same view: {:.2} ms per frame. Pass times are GPU timestamps (median of {frames} frames).\n",
        direct.frame_ms
    );
    let _ = writeln!(md, "| level | frame ms | frame / direct | MRT passes, GPU ms (/ direct) |");
    let _ = writeln!(md, "|---|---|---|---|");
    for (name, project) in &levels {
        let row = super::bench::measure(ctx, project, GiMode::Mrt, size, frames)?;
        stage_row(md, name, &row, direct.frame_ms, &["mrt"]);
    }
    Ok(())
}

/// One table row: `name`, the frame time and its ratio to `direct_ms`, and the GPU time of each
/// pass whose name starts with one of `prefixes` (with its ratio to `direct_ms`).
pub(super) fn stage_row(md: &mut String, name: &str, row: &super::bench::Row, direct_ms: f64, prefixes: &[&str]) {
    let direct_ms = direct_ms.max(1e-9);
    let stages: Vec<String> = row
        .passes
        .iter()
        .filter(|p| prefixes.iter().any(|x| p.name.starts_with(x)))
        .map(|p| format!("{} {:.2} ({:.2})", p.name, p.ms, p.ms / direct_ms))
        .collect();
    let stages = if stages.is_empty() { "none (or no timestamp queries)".to_owned() } else { stages.join(", ") };
    let _ = writeln!(md, "| {name} | {:.2} | {:.2} | {stages} |", row.frame_ms, row.frame_ms / direct_ms);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_maze_is_a_tree_of_linked_blocks() {
        let level = maze(11, 3);
        assert_eq!(level.blocks.len(), 11);
        assert_eq!(level.link_count(), 2 * 10, "a spanning tree has n - 1 openings, linked both ways");
        assert!(level.unlinked().is_empty());
    }
}
