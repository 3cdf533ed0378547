//! A probe of MRT on a real level on the CPU (the GPU runtime computes the same, `tests/integration/mrt.rs`): fits proxy blocks to a suite
//! level (or uses its own), builds (or loads) the dictionary, lights every block texel with the
//! scene's lights through the real geometry (shadow rays on the scene BVH, the lit wall's albedo:
//! MRT's l_d), runs the reduced-space transfer on the CPU, and compares each block's one-bounce
//! light (a white receiver's outgoing radiance) with a brute-force gather at the same points in
//! the real geometry (cosine rays, the hit surface's shadowed direct light).
//!
//! `cargo run --release --example mrt_probe -- rooms 1024` (`MRT_CLOSED=1`: every block closed)
//!
//! Prints per block its mean direct and indirect light, MRT's over the brute force's, and the
//! texel rms error. The dictionary comes from the cache (`bouncelab mrt-dictionary`). A level
//! name ending in `.gltf` is read from that file (`tools/dev_levels.py` writes development
//! levels). Environment switches, each documented where it is read: MRT_MULTI (n bounces),
//! MRT_MIMIC (the brute force treats doorway walls as MRT does), MRT_SOURCE / MRT_UNIFORM (one
//! block's light, or uniform emission), MRT_FACES / MRT_SIDES (per face, the walls around
//! doorways), MRT_FLUX / MRT_EXIT (flux through partly open sides), MRT_SHARE_ONLY /
//! MRT_NO_REFLECT / MRT_BANDS / MRT_KB (variants), MRT_ROOMS_X (rooms by x).

use std::path::Path;

use bouncelab::precompute::bvh::SceneBvh;
use bouncelab::precompute::mrt::cache;
use bouncelab::precompute::mrt::dictionary::{DictionaryParams, Progress};
use bouncelab::precompute::mrt::geometry_image;
use bouncelab::precompute::mrt::level::{self, Operators};
use bouncelab::precompute::mrt::proxy;
use bouncelab::precompute::mrt::shape::Layout;
use bouncelab::precompute::rng::Pcg32;
use bouncelab::scene::{LightKind, ObjectRole, Scene};
use bouncelab::suite;
use glam::Vec3;
use rayon::prelude::*;

/// The outgoing radiance (white-normalised: albedo x E / pi) of direct light at `p` with normal
/// `n` and albedo `albedo`.
fn direct(scene: &Scene, bvh: &SceneBvh, p: Vec3, n: Vec3, albedo: Vec3) -> Vec3 {
    let eps = 1e-3 * bvh.scale;
    let lifted = p + n * eps;
    let mut e = Vec3::ZERO;
    for light in scene.lights() {
        let (l, irradiance) = light.incident(p);
        let cos = n.dot(l);
        if cos <= 0.0 {
            continue;
        }
        let dist = match light.kind {
            LightKind::Directional => f32::INFINITY,
            _ => (light.position - lifted).length(),
        };
        if !bvh.occluded(lifted, l, dist) {
            e += irradiance * cos;
        }
    }
    albedo * e / std::f32::consts::PI
}

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().collect();
    let name = args.get(1).map_or("rooms", String::as_str);
    let rays: usize = args.get(2).map_or(Ok(1024), |s| s.parse())?;
    // A name ending in .gltf is a level outside the suite (e.g. `tools/dev_levels.py`'s).
    let mut project = if name.ends_with(".gltf") {
        bouncelab::project_file::Project::from_gltf(Path::new(name))?
    } else {
        suite::scene(name)?.load(Path::new("."))?
    };
    if !project.scene.objects().iter().any(|o| o.role == ObjectRole::ProxyBlock) {
        let fitted = proxy::fitted_objects(&project.scene)?;
        println!("{name}: fitted {} proxy blocks", fitted.len());
        project.scene.desc_mut().objects.extend(fitted);
    }
    // MRT_CLOSED=1: close every block (each room alone: MRT's in-block transfer without the
    // interfaces, against the brute force in the real, connected level).
    if std::env::var_os("MRT_CLOSED").is_some() {
        for o in &mut project.scene.desc_mut().objects {
            if let bouncelab::scene::MeshSource::Cuboid { openings, .. } = &mut o.source
                && o.role == ObjectRole::ProxyBlock
            {
                *openings = [false; 6];
            }
        }
    }
    let scene = &project.scene;
    let (mut lvl, _) = proxy::level(scene)?;
    if std::env::var_os("MRT_BOXES").is_some() {
        for b in &lvl.blocks {
            println!("box {:.2?} .. {:.2?}", b.origin, b.origin + b.size);
        }
    }
    // MRT_PLAIN_WARP=1: the dissertation's plain warp (no stretch correction);
    // MRT_FULL_SIDES=1: linked sides pass light over their whole area (no lintels).
    if std::env::var_os("MRT_PLAIN_WARP").is_some() {
        lvl = lvl.without_warp_correction();
    }
    let bvh = SceneBvh::build(scene);
    // MRT_BANDS=n: the light-field basis' position bands (the dictionary's default otherwise).
    let mut params = DictionaryParams::default();
    if let Some(b) = std::env::var("MRT_BANDS").ok().and_then(|v| v.parse().ok()) {
        params.interfaces.bands = b;
    }
    // MRT_KB=n: the blocks' indirect modes k_b.
    if let Some(k) = std::env::var("MRT_KB").ok().and_then(|v| v.parse().ok()) {
        params.k_b = k;
    }
    let (dictionary, source) = cache::load_or_build(&cache::default_dir(), &params, &Progress::default())?;
    // MRT_SHARE_ONLY=1: each linked side passes its open share everywhere and reflects nothing
    // (the scalar transmission before per-position openings); MRT_NO_REFLECT=1: masked by
    // position, reflecting nothing.
    if std::env::var_os("MRT_FULL_SIDES").is_none() {
        let positions = dictionary.interfaces.positions.positions;
        for ((i, w), o) in geometry_image::openings(scene, &bvh, &lvl, positions) {
            let o = if std::env::var_os("MRT_SHARE_ONLY").is_some() {
                bouncelab::precompute::mrt::opening::Opening::uniform(positions, o.share(), 0.0)
            } else if std::env::var_os("MRT_NO_REFLECT").is_some() {
                bouncelab::precompute::mrt::opening::Opening { albedo: vec![0.0; o.open.len()], ..o }
            } else {
                o
            };
            lvl.set_opening(i, w, o);
        }
    }
    println!("dictionary: {source:?}");
    let ops = Operators { dictionary: &dictionary, interfaces: &dictionary.interfaces };
    let transfer = level::assemble(&lvl, &ops, 6);
    // MRT_FLUX=1: per partly open side, the flux of the light field that uniform walls send out
    // through it: all of it, over the open positions, what the mask passes, the closed share
    // times albedo, and what the reflection sends back.
    if std::env::var_os("MRT_FLUX").is_some() {
        let pos = &dictionary.interfaces.positions;
        let k = pos.k;
        let flux = |q: &[f64], weights: &dyn Fn(usize) -> f64| -> f64 {
            (0..pos.positions * pos.positions)
                .map(|p| weights(p) * pos.irradiance[p * k..(p + 1) * k].iter().zip(q).map(|(e, x)| e * x).sum::<f64>())
                .sum()
        };
        let apply =
            |m: &[f64], q: &[f64]| -> Vec<f64> { (0..k).map(|i| (0..k).map(|j| m[i * k + j] * q[j]).sum()).collect() };
        for (x, w) in lvl.linked_sides() {
            let Some(o) = lvl.opening(x, w) else { continue };
            let b = lvl.blocks[x];
            let Some(e) = dictionary.element(b.shape) else { continue };
            let Some(exit) = dictionary.interfaces.exit(b.shape, b.local_face(w)) else { continue };
            let l = vec![1.0; Layout::new(b.shape, params.res).len()];
            let bb = e.project(&l);
            let q: Vec<f64> = (0..k).map(|i| (0..e.k_b).map(|j| exit.r_b_rlf[i * e.k_b + j] * bb[j]).sum()).collect();
            let all = flux(&q, &|_| 1.0);
            let open = flux(&q, &|p| o.open[p]);
            let closed = flux(&q, &|p| o.albedo[p] * (1.0 - o.open[p]));
            let passed = pos.mask(&o.open).map_or(all, |m| flux(&apply(&m, &q), &|_| 1.0));
            let back = pos.reflection(&o.open, &o.albedo).map_or(0.0, |m| flux(&apply(&m, &q), &|_| 1.0));
            println!(
                "block {x} side {w:?}: share {:.3}, flux {all:.3}, over open {open:.3}, passed {passed:.3}, albedo x closed {closed:.3}, reflected {back:.3}",
                o.share()
            );
            // The passed light's irradiance profile along u (summed over v): masked exactly,
            // and through the reduced mask.
            let np = pos.positions;
            if let Some(m) = pos.mask(&o.open) {
                let mq = apply(&m, &q);
                let at = |v: &[f64], p: usize| {
                    pos.irradiance[p * k..(p + 1) * k].iter().zip(v).map(|(e, x)| e * x).sum::<f64>()
                };
                let exact: Vec<String> = (0..np)
                    .map(|i| format!("{:5.1}", (0..np).map(|j| o.open[j * np + i] * at(&q, j * np + i)).sum::<f64>()))
                    .collect();
                let reduced: Vec<String> =
                    (0..np).map(|i| format!("{:5.1}", (0..np).map(|j| at(&mq, j * np + i)).sum::<f64>())).collect();
                println!("  exact   {}\n  reduced {}", exact.join(" "), reduced.join(" "));
            }
            // Where the passed light lands: the receiving block's walls (response rows and their
            // stretch corrections, area-weighted, E = pi x the white receiver's light) against
            // the flux entering (irradiance x the side's area / P^2).
            if let Some(y) = lvl.link(x, w) {
                let passed_q = pos.mask(&o.open).map_or(q.clone(), |m| apply(&m, &q));
                let resp = &dictionary.interfaces.response;
                let walls = resp.walls(&passed_q);
                let by = lvl.blocks[y];
                let rows = level::response_rows(&by, w.opposite(), params.res);
                let scales = level::response_scales(&lvl, y, w.opposite(), params.res);
                let layout = Layout::new(by.shape, params.res);
                let per = (params.res * params.res) as f64;
                let mut landed = 0.0;
                for (i, (row, sc)) in rows.iter().zip(&scales).enumerate() {
                    let Some(row) = row else { continue };
                    let face = by.world_face(layout.sample(i).0);
                    let sz = by.size;
                    let area = f64::from(match face.axis() {
                        0 => sz.y * sz.z,
                        1 => sz.x * sz.z,
                        _ => sz.x * sz.y,
                    }) / per;
                    landed += area * std::f64::consts::PI * sc * walls[*row];
                }
                let b = lvl.blocks[x];
                let side_area = f64::from(if w.axis() == 0 { b.size.y * b.size.z } else { b.size.x * b.size.y });
                let entering = flux(&passed_q, &|_| 1.0) * side_area / (np * np) as f64;
                let canonical_in = flux(&passed_q, &|_| 1.0) / (np * np) as f64;
                let canonical_out: f64 =
                    rows.iter().flatten().map(|row| std::f64::consts::PI * walls[*row] / per).sum::<f64>();
                println!(
                    "  into block {y}: flux entering {entering:.3}, landing on its walls {landed:.3}; unit cube {canonical_in:.4} -> {canonical_out:.4}"
                );
            }
        }
    }
    if std::env::var_os("MRT_WARPS").is_some() {
        for (x, w) in lvl.warps.iter().enumerate() {
            let through: Vec<String> = w.through.iter().map(|r| format!("{:.2?}", r)).collect();
            println!(
                "block {x} {:?} walls {:.2?}\n  through {}",
                lvl.blocks[x].size,
                w.walls,
                through.join("\n          ")
            );
        }
    }
    // Every texel's real surface (point, normal, albedo), per block: the runtime's geometry images.
    let texels: Vec<Vec<Option<(Vec3, Vec3, Vec3)>>> = lvl
        .blocks
        .iter()
        .map(|b| {
            geometry_image::geometry_image(scene, &bvh, b, params.res)
                .into_iter()
                .map(|s| s.found.then_some((s.position, s.normal, s.albedo)))
                .collect()
        })
        .collect();
    // MRT's direct light (luminance-like mean of rgb) and its transfer.
    let lum = |v: Vec3| f64::from((v.x + v.y + v.z) / 3.0);
    // MRT_SOURCE=k: only block k's direct light (and, in the brute force, only light from
    // points inside block k's box, grown by 0.15 m up to its linked sides) takes part: one bounce's sources one by one.
    let source: Option<usize> = std::env::var("MRT_SOURCE").ok().and_then(|v| v.parse().ok());
    // MRT_UNIFORM=1: every texel (and every real surface but those of linked sides in the brute
    // force) emits 1 in place of the direct light.
    let uniform = std::env::var_os("MRT_UNIFORM").is_some();
    // The source's linked sides (world side, plane), once.
    let source_sides: Vec<(bouncelab::precompute::mrt::shape::Face, f32)> = source.map_or(Vec::new(), |k| {
        lvl.linked_sides().into_iter().filter(|(i, _)| *i == k).map(|(_, w)| (w, lvl.side_rect(k, w).0)).collect()
    });
    let inside = |p: Vec3| {
        source.is_none_or(|k| {
            let b = &lvl.blocks[k];
            // Grown by 0.15 m (fitted boxes stop short of the outer walls), but never past a
            // linked side (the rooms beyond start there).
            (p - b.origin).cmpge(Vec3::splat(-0.15)).all()
                && (b.origin + b.size - p).cmpge(Vec3::splat(-0.15)).all()
                && source_sides
                    .iter()
                    .all(|(w, plane)| if w.positive() { p[w.axis()] <= *plane } else { p[w.axis()] >= *plane })
        })
    };
    let l_d: Vec<Vec<f64>> = texels
        .iter()
        .enumerate()
        .map(|(x, t)| {
            t.iter()
                .map(|s| match s {
                    Some(_) if uniform && source.is_none_or(|k| k == x) => 1.0,
                    Some((q, n, a)) if source.is_none_or(|k| k == x) => lum(direct(scene, &bvh, *q, *n, *a)),
                    _ => 0.0,
                })
                .collect()
        })
        .collect();
    // MRT_EXIT=1: per partly open side, the light leaving through its open positions (the
    // doorway) from the block's direct light: traced from the exact texels (in the unit cube)
    // against MRT's R_{b->rlf} b, and over the whole side.
    if std::env::var_os("MRT_EXIT").is_some() {
        let pos = &dictionary.interfaces.positions;
        let k = pos.k;
        let lf = params.interfaces.light_field();
        let np = lf.positions;
        let dirs = lf.directions * lf.directions;
        for (x, w) in lvl.linked_sides() {
            let Some(o) = lvl.opening(x, w) else { continue };
            let b = lvl.blocks[x];
            let (Some(e), Some(exit)) =
                (dictionary.element(b.shape), dictionary.interfaces.exit(b.shape, b.local_face(w)))
            else {
                continue;
            };
            let layout = Layout::new(b.shape, params.res);
            let exact = bouncelab::precompute::mrt::lightfield::trace(&layout, b.local_face(w), &l_d[x], 1, &lf);
            // Irradiance per position of the exact field (cell cosines as PositionOps::build).
            let cos: Vec<f64> = (0..dirs)
                .map(|c| {
                    let (a, bb) = (c % lf.directions, c / lf.directions);
                    let sq = glam::Vec2::new(
                        (a as f32 + 0.5) / lf.directions as f32 * 2.0 - 1.0,
                        (bb as f32 + 0.5) / lf.directions as f32 * 2.0 - 1.0,
                    );
                    f64::from(bouncelab::precompute::mrt::lightfield::square_to_hemisphere(sq).z)
                        * std::f64::consts::TAU
                        / dirs as f64
                })
                .collect();
            let exact_e: Vec<f64> = (0..np * np)
                .map(|p| {
                    let (i, j) = (p % np, p / np);
                    (0..dirs)
                        .map(|c| {
                            let at = bouncelab::precompute::mrt::lightfield::index(
                                &lf,
                                (i, j),
                                (c % lf.directions, c / lf.directions),
                            );
                            exact[at] * cos[c]
                        })
                        .sum()
                })
                .collect();
            let bb = e.project(&l_d[x]);
            let q: Vec<f64> = (0..k).map(|i| (0..e.k_b).map(|j| exit.r_b_rlf[i * e.k_b + j] * bb[j]).sum()).collect();
            let red_e: Vec<f64> = (0..np * np)
                .map(|p| pos.irradiance[p * k..(p + 1) * k].iter().zip(&q).map(|(a, c)| a * c).sum())
                .collect();
            let sum = |v: &[f64], f: &dyn Fn(usize) -> f64| (0..np * np).map(|p| f(p) * v[p]).sum::<f64>();
            println!(
                "exit {x} {w:?}: whole side exact {:.4} / MRT {:.4}; doorway exact {:.4} / MRT {:.4}",
                sum(&exact_e, &|_| 1.0),
                sum(&red_e, &|_| 1.0),
                sum(&exact_e, &|p| o.open[p]),
                sum(&red_e, &|p| o.open[p])
            );
        }
    }
    // MRT_MULTI=n: n bounces on both sides (MRT's feedback iterated n times: albedo x the last
    // indirect added to the direct texels; the brute force a path of n diffuse bounces).
    let bounces: usize = std::env::var("MRT_MULTI").ok().and_then(|v| v.parse().ok()).unwrap_or(1).max(1);
    let run = |l: &[Vec<f64>]| level::indirect(&lvl, &ops, &transfer, l);
    let mut mrt = run(&l_d);
    let mut last_input = l_d.clone();
    for _ in 1..bounces {
        let fed: Vec<Vec<f64>> = l_d
            .iter()
            .zip(&mrt)
            .zip(&texels)
            .map(|((d, m), t)| {
                d.iter().zip(m).zip(t).map(|((d, m), s)| d + m.max(0.0) * s.map_or(0.0, |(_, _, a)| lum(a))).collect()
            })
            .collect();
        mrt = run(&fed);
        last_input = fed;
    }
    // MRT_BOUNCES=n: the feedback's bounces (albedo x indirect fed back), each's total light and
    // its ratio to the previous one (the loop gain; above 1 the feedback diverges).
    if let Some(n) = std::env::var("MRT_BOUNCES").ok().and_then(|v| v.parse::<usize>().ok()) {
        let total = |v: &[Vec<f64>]| v.iter().flatten().map(|x| x.abs()).sum::<f64>();
        let mut bounce = l_d.clone();
        let mut last = total(&bounce);
        for k in 1..=n {
            let ind = level::indirect(&lvl, &ops, &transfer, &bounce);
            bounce = ind
                .iter()
                .zip(&texels)
                .map(|(b, t)| b.iter().zip(t).map(|(v, s)| v.max(0.0) * s.map_or(0.0, |(_, _, a)| lum(a))).collect())
                .collect();
            let now = total(&bounce);
            println!("bounce {k}: {now:.4} ({:.3} of the previous)", now / last.max(1e-30));
            last = now;
        }
    }
    // MRT_MIMIC=1: the brute force treats the surfaces of linked sides (within 0.15 m of the
    // side, facing across it) as MRT does: they get no direct light and reflecting there
    // does not count as a bounce (MRT's reflection happens within the transfer).
    let mimic = std::env::var_os("MRT_MIMIC").is_some();
    let linked: Vec<(usize, f32, Vec3, Vec3)> = lvl
        .linked_sides()
        .into_iter()
        .map(|(i, w)| {
            let (plane, lo, hi) = lvl.side_rect(i, w);
            (w.axis(), plane, lo, hi)
        })
        .collect();
    let on_side = |p: Vec3, ng: Vec3| {
        linked.iter().any(|(axis, plane, lo, hi)| {
            ng[*axis].abs() > 0.5
                && (p[*axis] - plane).abs() < 0.15
                && (0..3).filter(|a| a != axis).all(|a| p[a] >= lo[a] - 0.01 && p[a] <= hi[a] + 0.01)
        })
    };
    // Brute force: cosine rays from the real surface point into the real scene.
    let gather = |q: Vec3, n: Vec3, seed: u64| -> f64 {
        let mut rng = Pcg32::new(5, seed, 0);
        let (tt, bb) = n.any_orthonormal_pair();
        let side = (rays as f64).sqrt() as usize;
        let mut sum = 0.0;
        for a in 0..side {
            for c in 0..side {
                let r1 = (a as f32 + rng.next_f32()) / side as f32;
                let r2 = (c as f32 + rng.next_f32()) / side as f32;
                let (r, phi) = (r1.sqrt(), std::f32::consts::TAU * r2);
                let mut d = (tt * r * phi.cos() + bb * r * phi.sin() + n * (1.0 - r1).max(0.0).sqrt()).normalize();
                let mut origin = q + n * 1e-3 * bvh.scale;
                let mut throughput = 1.0;
                let mut k = 0;
                let mut steps = 0;
                while k < bounces && steps < 64 {
                    steps += 1;
                    let Some(hit) = bvh.intersect(origin, d, f32::INFINITY) else { break };
                    let tri = &bvh.tris[hit.tri as usize];
                    let p = origin + d * hit.t;
                    let ng = if tri.ng.dot(d) < 0.0 { tri.ng } else { break };
                    let albedo = geometry_image::albedo(scene, tri.material);
                    if mimic && on_side(p, ng) {
                        // MRT's closed part of a linked side: no direct light, a
                        // reflection within the same bounce.
                    } else if uniform {
                        if inside(p) && !on_side(p, ng) {
                            sum += throughput;
                        }
                    } else if inside(p) {
                        sum += throughput * lum(direct(scene, &bvh, p, ng, albedo));
                    }
                    if !(mimic && on_side(p, ng)) {
                        k += 1;
                        if k == bounces {
                            break;
                        }
                    }
                    throughput *= lum(albedo);
                    let (t2, b2) = ng.any_orthonormal_pair();
                    let (u1, u2) = (rng.next_f32(), rng.next_f32());
                    let (r, phi) = (u1.sqrt(), std::f32::consts::TAU * u2);
                    d = (t2 * r * phi.cos() + b2 * r * phi.sin() + ng * (1.0 - u1).max(0.0).sqrt()).normalize();
                    origin = p + ng * 1e-3 * bvh.scale;
                }
            }
        }
        sum / (side * side) as f64
    };
    let truth: Vec<Vec<f64>> = texels
        .iter()
        .enumerate()
        .map(|(x, t)| {
            t.par_iter()
                .enumerate()
                .map(|(i, s)| s.map_or(0.0, |(q, n, _)| gather(q, n, (x * 100_000 + i) as u64)))
                .collect()
        })
        .collect();
    // MRT_SIDES=1: the light on the closed part of each partly open side (the wall around a
    // doorway, which has no texels): MRT's against the brute force at the real surface behind
    // each closed opening position.
    if std::env::var_os("MRT_SIDES").is_some() {
        let np = dictionary.interfaces.positions.positions;
        for ((x, w), v) in level::side_light(&lvl, &ops, &transfer, &last_input) {
            let (Some(o), Some(frame)) = (lvl.opening(x, w), geometry_image::SideFrame::new(&lvl, x, w)) else {
                continue;
            };
            let cells: Vec<usize> = (0..np * np).filter(|p| o.open[*p] < 0.5).collect();
            let reach = geometry_image::SEARCH.min(0.45 * lvl.blocks[x].size[w.axis()]);
            let brute: Vec<f64> = cells
                .par_iter()
                .map(|&p| {
                    let at = frame.point(((p % np) as f32 + 0.5) / np as f32, ((p / np) as f32 + 0.5) / np as f32);
                    let s = geometry_image::surface(scene, &bvh, at, -frame.n, reach);
                    if s.found { gather(s.position, s.normal, 900_000 + (x * 1000 + p) as u64) } else { 0.0 }
                })
                .collect();
            let t = brute.iter().sum::<f64>() / cells.len().max(1) as f64;
            let m = cells.iter().map(|p| v[*p]).sum::<f64>() / cells.len().max(1) as f64;
            println!(
                "side {x} {w:?}: {} closed positions, brute force {t:.4}, MRT {m:.4}: {:.3}",
                cells.len(),
                m / t.max(1e-12)
            );
        }
    }
    // Area-weighted light per room (a texel stands for its face's area / res^2), the blocks
    // grouped by their centres along x at `MRT_ROOMS_X` (e.g. "5.1,10.3").
    let cuts: Vec<f32> = std::env::var("MRT_ROOMS_X")
        .ok()
        .map(|v| v.split(',').filter_map(|x| x.trim().parse().ok()).collect())
        .unwrap_or_default();
    let mut rooms: Vec<(f64, f64, f64)> = vec![(0.0, 0.0, 0.0); cuts.len() + 1];
    for (x, b) in lvl.blocks.iter().enumerate() {
        let layout = Layout::new(b.shape, params.res);
        let per = (params.res * params.res) as f64;
        let centre = b.origin.x + 0.5 * b.size.x;
        let room = cuts.iter().filter(|c| centre > **c).count();
        for i in 0..layout.len() {
            let (face, _, _, _) = layout.sample(i);
            let s = b.size;
            let area = match b.world_face(face).axis() {
                0 => s.y * s.z,
                1 => s.x * s.z,
                _ => s.x * s.y,
            };
            let area = f64::from(area) / per;
            let r = &mut rooms[room];
            r.0 += area * truth[x][i];
            r.1 += area * mrt[x][i];
            r.2 += area * l_d[x][i];
        }
    }
    for (k, (t, m, d)) in rooms.iter().enumerate() {
        let ratio = m / t.max(1e-12);
        println!("room {k}: direct {d:.4}, brute-force bounce {t:.4}, MRT bounce {m:.4}: MRT / brute force {ratio:.3}");
    }
    // MRT_FACES=1: each block's faces (world side): mean brute-force and MRT light.
    if std::env::var_os("MRT_FACES").is_some() {
        for (x, b) in lvl.blocks.iter().enumerate() {
            let layout = Layout::new(b.shape, params.res);
            let per = params.res * params.res;
            let line: Vec<String> = (0..layout.len() / per)
                .map(|g| {
                    let face = b.world_face(layout.sample(g * per).0);
                    let t: f64 = truth[x][g * per..(g + 1) * per].iter().sum::<f64>() / per as f64;
                    let m: f64 = mrt[x][g * per..(g + 1) * per].iter().sum::<f64>() / per as f64;
                    format!("{face:?} {t:.4}/{m:.4}")
                })
                .collect();
            println!("block {x}: {}", line.join(", "));
        }
    }
    println!(
        "| block | shape | size (m) | direct | brute-force bounce | MRT bounce | MRT / brute force | texel rms / mean |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    for (x, b) in lvl.blocks.iter().enumerate() {
        let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len().max(1) as f64;
        let (d, t, m) = (mean(&l_d[x]), mean(&truth[x]), mean(&mrt[x]));
        let rms =
            (mrt[x].iter().zip(&truth[x]).map(|(a, b)| (a - b).powi(2)).sum::<f64>() / truth[x].len() as f64).sqrt();
        println!(
            "| {x} | {} | {:.1} x {:.1} x {:.1} | {d:.4} | {t:.4} | {m:.4} | {:.3} | {:.3} |",
            b.shape.name(),
            b.size.x,
            b.size.y,
            b.size.z,
            m / t.max(1e-12),
            rms / t.max(1e-12)
        );
    }
    Ok(())
}
