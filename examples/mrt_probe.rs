//! A probe of MRT on a real level before its GPU runtime exists: fits proxy blocks to a suite
//! level (or uses its own), builds (or loads) the dictionary, lights every block texel with the
//! scene's lights through the real geometry (shadow rays on the scene BVH, the lit wall's albedo:
//! MRT's l_d), runs the reduced-space transfer on the CPU, and compares each block's one-bounce
//! light (a white receiver's outgoing radiance) with a brute-force gather at the same points in
//! the real geometry (cosine rays, the hit surface's shadowed direct light).
//!
//! `cargo run --release --example mrt_probe -- rooms 1024` (`MRT_CLOSED=1`: every block closed)
//!
//! Prints per block its mean direct and indirect light, MRT's over the brute force's, and the
//! texel rms error. The dictionary comes from the cache (`bouncelab mrt-dictionary`).

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
    let mut project = suite::scene(name)?.load(Path::new("."))?;
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
    // MRT_PLAIN_WARP=1: the dissertation's plain warp (no stretch correction);
    // MRT_FULL_SIDES=1: linked sides pass light over their whole area (no lintels).
    if std::env::var_os("MRT_PLAIN_WARP").is_some() {
        lvl = lvl.without_warp_correction();
    }
    let bvh = SceneBvh::build(scene);
    if std::env::var_os("MRT_FULL_SIDES").is_none() {
        for ((i, w), t) in geometry_image::transmissions(&bvh, &lvl) {
            lvl.set_transmission(i, w, t);
        }
    }
    let params = DictionaryParams::default();
    let (dictionary, source) = cache::load_or_build(&cache::default_dir(), &params, &Progress::default())?;
    println!("dictionary: {source:?}");
    let ops = Operators { dictionary: &dictionary, interfaces: &dictionary.interfaces };
    let transfer = level::assemble(&lvl, &ops, 6);
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
    let l_d: Vec<Vec<f64>> = texels
        .iter()
        .map(|t| t.iter().map(|s| s.map_or(0.0, |(q, n, a)| lum(direct(scene, &bvh, q, n, a)))).collect())
        .collect();
    let mrt = level::indirect(&lvl, &ops, &transfer, &l_d);
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
    // Brute force: cosine rays from the real surface point into the real scene.
    let truth: Vec<Vec<f64>> = texels
        .iter()
        .enumerate()
        .map(|(x, t)| {
            t.par_iter()
                .enumerate()
                .map(|(i, s)| {
                    let Some((q, n, _)) = *s else { return 0.0 };
                    let mut rng = Pcg32::new(5, (x * 100_000 + i) as u64, 0);
                    let (tt, bb) = n.any_orthonormal_pair();
                    let side = (rays as f64).sqrt() as usize;
                    let mut sum = 0.0;
                    for a in 0..side {
                        for c in 0..side {
                            let r1 = (a as f32 + rng.next_f32()) / side as f32;
                            let r2 = (c as f32 + rng.next_f32()) / side as f32;
                            let (r, phi) = (r1.sqrt(), std::f32::consts::TAU * r2);
                            let d =
                                (tt * r * phi.cos() + bb * r * phi.sin() + n * (1.0 - r1).max(0.0).sqrt()).normalize();
                            let origin = q + n * 1e-3 * bvh.scale;
                            let Some(hit) = bvh.intersect(origin, d, f32::INFINITY) else { continue };
                            let tri = &bvh.tris[hit.tri as usize];
                            let p = origin + d * hit.t;
                            let ng = if tri.ng.dot(d) < 0.0 { tri.ng } else { continue };
                            let albedo = geometry_image::albedo(scene, tri.material);
                            sum += lum(direct(scene, &bvh, p, ng, albedo));
                        }
                    }
                    sum / (side * side) as f64
                })
                .collect()
        })
        .collect();
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
