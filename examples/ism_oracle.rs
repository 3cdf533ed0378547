//! An oracle for ISM visibility: renders `ism` on a suite scene (or a `.gltf`) and checks its
//! imperfect shadow maps against rays through the scene's BVH, per bounce set:
//! - per atlas texel (every fourth VPL), the share of cosine-weighted directions whose stored
//!   depth is a false occluder (nearer than the first hit) or a hole (farther);
//! - per (receiver, VPL) pair, receivers spread over the surfaces by area, the lit share the
//!   ISM lookups give against the rays', with false shadow and false light (`CROSS=1` on the
//!   three rooms: only pairs in different rooms, i.e. light through doorways);
//! - the power the first set's VPLs hand to the second (bounce pass) against the power they
//!   reflect with exact visibility.
//!
//!
//! Diagnostics (environment): `GRID=x,z` and `PAIR=a,b` pick rooms, `SHOW=1` / `SHOW_SHADOW=1`
//! list false-light / false-shadow pairs (`NEIGHBOURS=1`: with the four neighbouring texels'
//! points; `SHOW_KIND=k`: false light of the k-th kind only, as the summary lists them), `DUMP=tile` writes that tile beside the rays' depths, `POINTS=tile[,box]` lists a
//! tile's chosen points with their splat radius and footprint (`TEXEL=x,y`: whether each covers
//! that texel as the splat pass decides it; `CLIPS=1`: with their clip lines).
//!
//! `cargo run --release --example ism_oracle -- clutter "(bounces: 3)"`
use bouncelab::precompute::bvh::SceneBvh;
use bouncelab::precompute::ism::atlas_word::{self, AtlasTexel};
use bouncelab::precompute::open_edges::CLIPS_PER_POINT;
use bouncelab::render::gi::ism::technique::IsmTechnique;
use bouncelab::render::gi::ism::vpl_pass::GpuVpl;
use bouncelab::render::{GpuContext, Renderer};
use bouncelab::settings::{GiMode, IsmSettings};
use bouncelab::suite;
use glam::Vec3;
use std::path::Path;

fn onb(n: Vec3) -> (Vec3, Vec3) {
    let s = if n.z >= 0.0 { 1.0 } else { -1.0 };
    let a = -1.0 / (s + n.z);
    let b = n.x * n.y * a;
    (Vec3::new(1.0 + s * n.x * n.x * a, s * b, -s * n.x), Vec3::new(b, s + n.y * n.y * a, -n.y))
}

/// Which (VPL, receiver) pairs the lookup oracle counts, from the environment (read once):
/// `GRID=x,z` splits the plan into rooms at x and z (room = [x >] + 2 [z >], otherwise the three
/// rooms' x / 5.2); `CROSS=1` keeps pairs in different rooms; `PAIR=a,b` VPLs in room a (any: -1) and
/// receivers in room b.
struct PairFilter {
    grid: Option<(f32, f32)>,
    cross: bool,
    pair: Option<(f32, f32)>,
}

impl PairFilter {
    fn from_env() -> Self {
        let two = |name: &str| {
            std::env::var(name)
                .ok()
                .and_then(|g| g.split_once(',').and_then(|(a, b)| Some((a.parse().ok()?, b.parse().ok()?))))
        };
        Self { grid: two("GRID"), cross: std::env::var_os("CROSS").is_some(), pair: two("PAIR") }
    }

    /// The room point `p` is in.
    fn room(&self, p: Vec3) -> f32 {
        match self.grid {
            Some((x, z)) => f32::from(u8::from(p.x > x)) + 2.0 * f32::from(u8::from(p.z > z)),
            None => (p.x / 5.2).floor(),
        }
    }

    /// Whether the pair of a VPL at `o` and a receiver at `p` counts.
    fn keeps(&self, o: Vec3, p: Vec3) -> bool {
        let (a, b) = (self.room(o), self.room(p));
        !(self.cross && a == b) && self.pair.is_none_or(|(pa, pb)| (pa < 0.0 || pa == a) && pb == b)
    }
}

/// Whether receiver `p` (normal `pn`) sees the VPL at `o` (normal `nn`): the ray between them,
/// each end lifted off its surface by 1 mm (a first-bounce VPL comes from the light's G-buffer
/// depth and may lie a fraction of a millimetre inside its surface, which a ray to the exact
/// position would count as shadowing every receiver).
fn sees(bvh: &SceneBvh, p: Vec3, pn: Vec3, o: Vec3, nn: Vec3) -> bool {
    let (a, b) = (p + pn * 1e-3, o + nn * 1e-3);
    let d = (b - a).length();
    d <= 0.0 || !bvh.occluded(a, (b - a) / d, d)
}

/// Whether the surface point `p` (normal `n`) lies inside solid geometry: the first surface
/// above it faces away (a floor's face running on under a wall).
fn buried(bvh: &SceneBvh, p: Vec3, n: Vec3) -> bool {
    bouncelab::precompute::facing::is_buried(bvh, p, n, 1e-4 * bvh.scale)
}

/// Every fourth live VPL of set `set`: its atlas tile, the VPL, its position and normal.
fn sampled_vpls(vpls: &[GpuVpl], set: usize, n: usize) -> impl Iterator<Item = (usize, GpuVpl, Vec3, Vec3)> + '_ {
    (0..n)
        .step_by(4)
        .map(move |k| (set * n + k, vpls[set * n + k]))
        .filter(|(_, v)| v.position[3] > 0.0)
        .map(|(tile, v)| (tile, v, Vec3::from_slice(&v.position[..3]), Vec3::from_slice(&v.normal[..3])))
}

/// The pool point (position, normal) an atlas word of tile `tile` names, if any.
fn word_point(word: u32, tile: usize, lookup: &atlas_word::IsmLookupData) -> Option<([f32; 4], [f32; 4])> {
    let j = *lookup.chosen_all.get(tile * lookup.per_ism as usize + atlas_word::slot(word)? as usize)? as usize;
    Some((*lookup.points.get(j)?, *lookup.normals.get(j)?))
}

/// What a false-light texel holds: the classes of [`fl_kind`].
const FL_KINDS: [&str; 6] = [
    "empty",
    "pull-push fill or depth only",
    "the receiver's own surface (a hole)",
    "a surface beyond the true occluder",
    "a nearer surface, receiver on its plane",
    "a nearer surface, ray past its clips",
];

/// Cosines of the VPL elevation bands (3, 10 and 30 degrees).
const FL_BANDS: [f32; 3] = [0.0523, 0.1736, 0.5];

/// Which of [`FL_KINDS`] a false-light lookup's texel word is: receiver `p` (normal `pn`) whose
/// ray from VPL `o` along `dir` first meets geometry at `wall`.
#[allow(clippy::too_many_arguments)]
fn fl_kind(
    word: u32,
    tile: usize,
    lookup: &atlas_word::IsmLookupData,
    p: Vec3,
    pn: Vec3,
    wall: f32,
    dir: Vec3,
    o: Vec3,
) -> usize {
    if word == u32::MAX {
        return 0;
    }
    let Some((sp, sn)) = word_point(word, tile, lookup).filter(|_| word & 1 == 0) else { return 1 };
    let (sp, sn) = (Vec3::from_slice(&sp[..3]), Vec3::from_slice(&sn[..3]));
    if sn.dot(pn) > 0.99 && (sp - p).dot(pn).abs() < 0.02 {
        return 2;
    }
    if (sp - o).length() > wall * 1.05 {
        return 3;
    }
    let den = dir.dot(sn);
    let t = if den.abs() > 1e-6 { (sp - o).dot(sn) / den } else { -1.0 };
    if t <= 0.0 || t >= (p - o).length() * 0.999 { 4 } else { 5 }
}

/// With NEIGHBOURS=1: the texel at atlas index `at` and its four neighbours, their depths and
/// points (one texel holds one surface; the lost one is often next door).
fn show_neighbours(words: &[u32], at: usize, side: usize, tile: usize, lookup: &atlas_word::IsmLookupData, d_max: f32) {
    if std::env::var_os("NEIGHBOURS").is_none() {
        return;
    }
    for (dx, dy) in [(0i64, 0i64), (-1, 0), (1, 0), (0, -1), (0, 1)] {
        let Some(&w) = words.get((at as i64 + dy * side as i64 + dx) as usize) else { continue };
        println!(
            "      ({dx},{dy}) depth {:.3} point {:.2?}",
            atlas_word::depth(w) * d_max,
            word_point(w, tile, lookup)
        );
    }
    let (x, y) = ((at % side) as u32, (at / side) as u32);
    let s = side as u32;
    for level in 1..=atlas_word::HOLE_LEVELS {
        let i = s * s
            + bouncelab::render::gi::ism::gather::level_base(s, level)
            + (y >> level) * (s >> level)
            + (x >> level);
        let Some(&w) = words.get(i as usize) else { continue };
        println!(
            "      level {level} depth {:.3} point {:.2?}",
            atlas_word::depth(w) * d_max,
            word_point(w, tile, lookup)
        );
    }
}

/// A VPL's paraboloid map frame: its position, tangents and normal (`paraboloid` in
/// `common/onb.wgsl`).
struct MapFrame {
    o: Vec3,
    t: Vec3,
    b: Vec3,
    n: Vec3,
}

impl MapFrame {
    fn new(o: Vec3, n: Vec3) -> Self {
        let (t, b) = onb(n);
        Self { o, t, b, n }
    }

    /// The map coordinates (0..1 across the tile) of the point `q`.
    fn uv(&self, q: Vec3) -> glam::Vec2 {
        let v = q - self.o;
        let l = Vec3::new(v.dot(self.t), v.dot(self.b), v.dot(self.n)) / v.length().max(1e-9);
        glam::Vec2::new(l.x, l.y) / (1.0 + l.z) * 0.5 + glam::Vec2::splat(0.5)
    }

    /// The direction of the centre of texel (x, y) of a map of side `res` in the frame's own
    /// coordinates (z along the normal), `None` past the rim.
    fn texel_local(x: f32, y: f32, res: f32) -> Option<Vec3> {
        let s = glam::Vec2::new(x + 0.5, y + 0.5) / res * 2.0 - glam::Vec2::ONE;
        let ss = s.dot(s);
        (ss <= 1.0).then(|| Vec3::new(2.0 * s.x, 2.0 * s.y, 1.0 - ss) / (1.0 + ss))
    }

    /// A direction in the frame's coordinates, in the world.
    fn world(&self, l: Vec3) -> Vec3 {
        (self.t * l.x + self.b * l.y + self.n * l.z).normalize()
    }
}

/// POINTS=tile[,x0,y0,z0,x1,y1,z1]: that tile's chosen points (inside the box), each with the
/// splat radius and footprint (centre, tangent images, texels) `ism_splat.wgsl` gives it;
/// TEXEL=x,y: whether each covers that texel as the splat pass decides it (footprint ellipse,
/// plane hit, clip lines; CLIPS=1 prints the lines). `chosen` (`IsmTechnique::read_chosen`)
/// holds the last set's areas only: a tile of an earlier set is listed without footprints.
fn list_points(
    spec: &str,
    chosen: Vec<(u32, f32)>,
    ism: &IsmSettings,
    lookup: &atlas_word::IsmLookupData,
    vpls: &[GpuVpl],
) {
    let v: Vec<f32> = spec.split(',').filter_map(|x| x.parse().ok()).collect();
    let tile = v.first().copied().unwrap_or(0.0) as usize;
    let inside = |p: [f32; 4]| v.len() < 7 || (0..3).all(|a| p[a] >= v[1 + a] && p[a] <= v[4 + a]);
    let (per, n_vpls) = (lookup.per_ism as usize, ism.vpl_count as usize);
    let Some(vpl) = vpls.get(tile) else { return println!("no tile {tile}") };
    let last_set = tile / n_vpls + 1 == ism.bounces.max(1) as usize;
    let texel: Option<(f32, f32)> = std::env::var("TEXEL")
        .ok()
        .and_then(|t| t.split_once(',').and_then(|(a, b)| Some((a.parse().ok()?, b.parse().ok()?))));
    let frame = MapFrame::new(Vec3::from_slice(&vpl.position[..3]), Vec3::from_slice(&vpl.normal[..3]));
    let fr = ism.ism_resolution as f32;
    println!(
        "tile {tile} vpl {:?} n {:?}{}",
        vpl.position,
        vpl.normal,
        if last_set { "" } else { " (not the last set: no areas)" }
    );
    for slot in 0..per {
        let j = lookup.chosen_all[tile * per + slot];
        if j == u32::MAX || !inside(lookup.points[j as usize]) {
            continue;
        }
        let (p, nn) = (lookup.points[j as usize], lookup.normals[j as usize]);
        print!(
            "  slot {slot} point {j} at [{:.3}, {:.3}, {:.3}] n [{:.2}, {:.2}, {:.2}]",
            p[0], p[1], p[2], nn[0], nn[1], nn[2]
        );
        let Some(area) = chosen.get(tile % n_vpls * per + slot).map(|c| c.1).filter(|_| last_set) else {
            println!();
            continue;
        };
        let radius = (ism.splat_radius.powi(2) / std::f32::consts::PI * area).sqrt();
        let (pp, pn) = (Vec3::new(p[0], p[1], p[2]), Vec3::new(nn[0], nn[1], nn[2]));
        let (a, b) = onb(pn);
        let centre = frame.uv(pp) * fr;
        let (ta, tb) = (frame.uv(pp + a * radius) * fr - centre, frame.uv(pp + b * radius) * fr - centre);
        print!(" r {radius:.3} centre {centre:.1} ta {ta:.1} tb {tb:.1}");
        let Some((x, y)) = texel else {
            println!();
            continue;
        };
        let Some(l) = MapFrame::texel_local(x, y, fr) else {
            println!("  texel: past the rim");
            continue;
        };
        let m00 = ta.x * ta.x + tb.x * tb.x + 0.25;
        let m01 = ta.x * ta.y + tb.x * tb.y;
        let m11 = ta.y * ta.y + tb.y * tb.y + 0.25;
        let q = glam::Vec2::new(x + 0.5, y + 0.5) - centre;
        let in_ellipse = m11 * q.x * q.x - 2.0 * m01 * q.x * q.y + m00 * q.y * q.y <= m00 * m11 - m01 * m01;
        let dir = frame.world(l);
        let den = dir.dot(pn);
        let hit = if den.abs() <= 1e-6 { 0.0 } else { (pp - frame.o).dot(pn) / den };
        let h = frame.o + dir * hit;
        let on = lookup.on_surface(j, h, 0.01 * radius);
        println!("  texel: inside {in_ellipse} hit {hit:.3} on surface {on}");
        if std::env::var_os("CLIPS").is_some() {
            let k = j as usize * CLIPS_PER_POINT;
            println!("    clips {:?} hit point {h:?}", &lookup.clips[k..k + CLIPS_PER_POINT]);
        }
    }
}

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().collect();
    let name = &args[1];
    let ism: IsmSettings = ron::from_str(&args[2])?;
    let ctx = GpuContext::new_headless()?;
    let mut project = if name.ends_with(".gltf") {
        bouncelab::project_file::Project::from_gltf(Path::new(name))?
    } else {
        suite::scene(name)?.load(Path::new("."))?
    };
    project.render.ism = ism.clone();
    project.render.mode = GiMode::Ism;
    let mut r = Renderer::new(&ctx.device, &ctx.queue)?;
    for _ in 0..2 {
        r.render(&project.scene, &project.render, (128, 72))?;
    }
    let t = r.technique_as::<IsmTechnique>().expect("ism");
    let (words, side) = t.read_atlas_words(r.device(), r.queue())?;
    let side = side as usize;
    let lookup = t.read_lookup_data(r.device(), r.queue())?;
    let vpls = t.read_all_vpls(r.device(), r.queue())?;
    let bvh = SceneBvh::build(&project.scene);
    let d_max = 2.0 * project.scene.bounds().map_or(1.0, |b| b.radius());
    if let Ok(spec) = std::env::var("POINTS") {
        list_points(&spec, t.read_chosen(r.device(), r.queue())?, &ism, &lookup, &vpls);
    }
    let res = ism.ism_resolution as usize;
    let c = side / res;
    let n = ism.vpl_count as usize;
    for set in 0..ism.bounces as usize {
        let (mut w_all, mut w_false, mut w_hole, mut w_near) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
        for (tile, _, o, nn) in sampled_vpls(&vpls, set, n) {
            let frame = MapFrame::new(o, nn);
            let (tx, ty) = ((tile % c) * res, (tile / c) * res);
            // DUMP=tile: that tile's stored depth (left) and the rays' (right) as a PNG.
            let dump = std::env::var("DUMP").ok().and_then(|v| v.parse::<usize>().ok()) == Some(tile);
            let mut png = vec![0u8; res * 2 * res * 4];
            for y in 0..res {
                for x in 0..res {
                    let Some(l) = MapFrame::texel_local(x as f32, y as f32, res as f32) else { continue };
                    let dir = frame.world(l);
                    let w = f64::from(l.z * (1.0 + l.z) * (1.0 + l.z));
                    let hit = bvh.intersect(o + nn * 2e-3, dir, 1e30);
                    let truth = hit.map_or(f32::INFINITY, |h| h.t);
                    let d = atlas_word::depth(words[(ty + y) * side + tx + x]);
                    let ism_t = if d >= 1.0 { f32::INFINITY } else { d * d_max };
                    if dump {
                        let shade = |t: f32| (255.0 * (1.0 - (t / (0.5 * d_max)).min(1.0))) as u8;
                        for (col, t) in [(x, ism_t), (x + res, truth)] {
                            let i = (y * 2 * res + col) * 4;
                            png[i..i + 4].copy_from_slice(&[shade(t), shade(t), shade(t), 255]);
                        }
                    }
                    w_all += w;
                    if ism_t < 0.8 * truth - 0.02 * d_max {
                        w_false += w;
                        if ism_t < 0.05 * d_max {
                            w_near += w;
                        }
                    } else if ism_t > 1.25 * truth + 0.02 * d_max {
                        w_hole += w;
                    }
                }
            }
            if dump {
                bouncelab::image_io::write_png(Path::new("/tmp/ism_tile.png"), 2 * res as u32, res as u32, png)?;
            }
        }
        println!(
            "{name} set {set}: false occluder {:.4} (near {:.4})  hole {:.4}",
            w_false / w_all,
            w_near / w_all,
            w_hole / w_all
        );
    }
    // Lookup oracle: receivers on the surfaces, set-0 VPLs, ISM visibility against BVH rays.
    let receivers = bouncelab::precompute::sample_points::distribute(&project.scene, 20000, 1, 9);
    let recv = receivers.world(&project.scene);
    let filter = PairFilter::from_env();
    if std::env::var_os("VPLS").is_some() {
        let n = ism.vpl_count as usize;
        for (set, chunk) in vpls.chunks(n).enumerate().take(ism.bounces as usize) {
            let mut by_room = std::collections::BTreeMap::<i32, (u32, f64)>::new();
            for v in chunk.iter().filter(|v| v.position[3] > 0.0) {
                let e = by_room.entry(filter.room(Vec3::from_slice(&v.position[..3])) as i32).or_default();
                e.0 += 1;
                e.1 += f64::from(0.2126 * v.power[0] + 0.7152 * v.power[1] + 0.0722 * v.power[2]);
            }
            println!("{name} set {set} VPLs by room (count, luminance power): {by_room:?}");
        }
    }
    // POWER=1: pairs weighted by the VPL's power too (what the screen sees).
    let power_weighted = std::env::var_os("POWER").is_some();
    // UNBURIED=1: only receivers on surfaces open to the air (not a floor under a wall).
    let unburied = std::env::var_os("UNBURIED").is_some();
    for set in 0..ism.bounces as usize {
        let (mut w_true, mut w_ism, mut w_fs, mut w_fl) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
        let mut w_fs_slab = 0.0f64;
        let mut shown = 0;
        let mut w_pairs = 0.0f64;
        let mut fl_classes = [[0.0f64; 4]; FL_KINDS.len()];
        for (tile, v, o, nn) in sampled_vpls(&vpls, set, n) {
            let sigma = v.normal[3];
            let frame = MapFrame::new(o, nn);
            let (tx, ty) = ((tile % c) * res, (tile / c) * res);
            for (p, pn) in &recv {
                let to_p = *p - o;
                let d = to_p.length();
                let dir = to_p / d;
                let cos_s = nn.dot(dir);
                let cos_r = pn.dot(-dir);
                if cos_s <= 0.0 || cos_r <= 0.0 || d < 1e-3 {
                    continue;
                }
                if !filter.keeps(o, *p) || (unburied && buried(&bvh, *p, *pn)) {
                    continue;
                }
                let mut w = f64::from(cos_s * cos_r / (d * d).max(0.01));
                if power_weighted {
                    w *= f64::from(0.2126 * v.power[0] + 0.7152 * v.power[1] + 0.0722 * v.power[2]);
                }
                let vis_true = sees(&bvh, *p, *pn, o, nn);
                let sin_r = (1.0 - cos_r * cos_r).max(0.0).sqrt();
                let delta = d * sigma * (ism.bias_constant + ism.bias_slope * sin_r);
                let q = *p + *pn * delta;
                let qq = q - o;
                let qd = qq.length();
                let uv = frame.uv(q);
                let t = ((uv * res as f32).floor().max(glam::Vec2::ZERO)).min(glam::Vec2::splat(res as f32 - 1.0));
                let at = (ty + t.y as usize) * side + tx + t.x as usize;
                let stored = atlas_word::depth(words[at]);
                // As `ism_lit`: the stored point's surface along q's own ray, then its neighbours'.
                let texel = AtlasTexel { words: &words, r: res as u32, c: c as u32, texel: (t.x as u32, t.y as u32) };
                let vis_ism = lookup.lit(texel, o, sigma, tile as u32, qq / qd, qd, qd / d_max, 8.0 / res as f32);
                w_pairs += w;
                if vis_true {
                    w_true += w;
                }
                if vis_ism {
                    w_ism += w;
                }
                if vis_true && !vis_ism {
                    w_fs += w;
                    // The share of false shadow the texel's own point's slab casts.
                    let own_j = atlas_word::slot(words[at])
                        .and_then(|s| lookup.chosen_all.get(tile * lookup.per_ism as usize + s as usize));
                    if own_j
                        .is_some_and(|&j| lookup.slab_blocks(j, o, qq / qd, qd, atlas_word::NEIGHBOUR_REACH * sigma))
                    {
                        w_fs_slab += w;
                    }
                    if std::env::var_os("SHOW_SHADOW").is_some()
                        && shown < 12
                        && cos_s > 0.2
                        && cos_r > 0.2
                        && set + 1 >= ism.bounces as usize
                    {
                        shown += 1;
                        let hit = bvh.intersect(o + nn * 2e-3, qq / qd, 1e30).map_or(f32::INFINITY, |h| h.t);
                        println!(
                            "  false shadow: tile {tile} vpl {o:.2} n {nn:.2}  recv {p:.2} n {pn:.2}  texel {t}  stored {:.3} m  slot {:?}  q at {qd:.3} m  first hit along q {hit:.3} m",
                            stored * d_max,
                            atlas_word::slot(words[at])
                        );
                        show_neighbours(&words, at, side, tile, &lookup, d_max);
                    }
                }
                if !vis_true && vis_ism {
                    w_fl += w;
                    let wall = bvh.intersect(o + nn * 2e-3, qq / qd, 1e30).map_or(f32::INFINITY, |h| h.t);
                    let kind = fl_kind(words[at], tile, &lookup, *p, *pn, wall, qq / qd, o);
                    let band = FL_BANDS.iter().position(|&b| cos_s < b).unwrap_or(FL_BANDS.len());
                    fl_classes[kind][band] += w * f64::from(v.power[0] + v.power[1] + v.power[2]);
                    let min_cos: f32 = std::env::var("SHOW_MIN_COS").ok().and_then(|v| v.parse().ok()).unwrap_or(0.0);
                    let kind_shown = std::env::var("SHOW_KIND").ok().and_then(|v| v.parse::<usize>().ok());
                    if std::env::var_os("SHOW").is_some()
                        && shown < 12
                        && cos_s >= min_cos
                        && kind_shown.is_none_or(|k| k == kind)
                    {
                        shown += 1;
                        let point = word_point(words[at], tile, &lookup);
                        println!(
                            "  false light: tile {tile} vpl {o:.2} n {nn:.2} sigma {sigma:.4}  recv {p:.2} n {pn:.2}  q {q:.2}  texel {t}  stored {:.3} m (mark {}) point {point:.2?}  q at {qd:.3} m  first hit along q {wall:.3} m",
                            stored * d_max,
                            words[at] & 1
                        );
                        show_neighbours(&words, at, side, tile, &lookup, d_max);
                    }
                }
            }
        }
        let fl_total: f64 = fl_classes.iter().flatten().sum();
        if fl_total > 0.0 {
            println!(
                "{name} set {set} false light by what the texel holds (share of its power; VPL elevation bands <3, 3-10, 10-30, >30 degrees):"
            );
            for (k, row) in FL_KINDS.iter().zip(&fl_classes) {
                println!("    {k:38} {:.3}  {:.3?}", row.iter().sum::<f64>() / fl_total, row.map(|x| x / fl_total));
            }
        }
        println!(
            "{name} set {set} lookups: ism/true {:.3}  false shadow {:.3} (own slab {:.3})  false light {:.3} (of true; of all pairs {:.4})  true {:.4e} ism {:.4e}",
            w_ism / w_true,
            w_fs / w_true,
            w_fs_slab / w_true,
            w_fl / w_true,
            w_fl / w_pairs,
            w_true,
            w_ism
        );
    }
    // Bounce oracle over FRAMES frames (default 1): power each set's VPLs reflect (true
    // visibility, receivers by area) against the power of the next set's VPLs they made.
    let frames: usize = std::env::var("FRAMES").ok().and_then(|v| v.parse().ok()).unwrap_or(1);
    // The last set carries the bounce tail's 1 / (1 - r) (`bounce_tail`), the later bounces'
    // power, not the power its sources reflect: it is compared only without the tail.
    let sets = ism.bounces.saturating_sub(1 + u32::from(ism.bounce_tail)) as usize;
    if ism.bounce_tail && ism.bounces > 1 {
        println!("{name}: the last set carries the bounce tail; `(bounce_tail: false)` compares it too");
    }
    let mut acc = vec![([0.0f64; 4], [0.0f64; 4]); sets];
    let mut vpls = vpls;
    for f in 0..frames {
        if f > 0 {
            r.render(&project.scene, &project.render, (128, 72))?;
            let t = r.technique_as::<IsmTechnique>().expect("ism");
            vpls = t.read_all_vpls(r.device(), r.queue())?;
        }
        for (src, a) in acc.iter_mut().enumerate() {
            let (g, t) = bounce_by_room(&project, &bvh, &receivers, &recv, &vpls, &ism, src, &filter);
            (0..4).for_each(|i| {
                a.0[i] += g[i];
                a.1[i] += t[i];
            });
        }
    }
    for (src, (g, t)) in acc.iter().enumerate() {
        println!("{name} bounce power set{}/true {:.3}", src + 1, g.iter().sum::<f64>() / t.iter().sum::<f64>());
        if std::env::var_os("CROSS").is_some() {
            println!("{name} bounce power by room, set{}/true: {:?}", src + 1, [0, 1, 2, 3].map(|i| g[i] / t[i]));
        }
    }
    Ok(())
}

/// Power set `src`'s VPLs hand to set `src + 1` (GPU) and the power they reflect with exact
/// visibility (receivers by area), each by room of the three rooms (x / 5.2).
#[allow(clippy::too_many_arguments)]
fn bounce_by_room(
    project: &bouncelab::project_file::Project,
    bvh: &SceneBvh,
    receivers: &bouncelab::precompute::sample_points::SamplePoints,
    recv: &[(Vec3, Vec3)],
    vpls: &[GpuVpl],
    ism: &IsmSettings,
    src: usize,
    filter: &PairFilter,
) -> ([f64; 4], [f64; 4]) {
    let n = ism.vpl_count as usize;
    let total_area: f64 = receivers.weighted_area.iter().sum();
    let a_recv = total_area / recv.len() as f64;
    let n2 = (ism.interleave * ism.interleave) as f64;
    let lum = |c: [f32; 4]| 0.2126 * f64::from(c[0]) + 0.7152 * f64::from(c[1]) + 0.0722 * f64::from(c[2]);
    let room = |p: Vec3| (filter.room(p).clamp(0.0, 3.0)) as usize;
    let (mut room_gpu, mut room_true) = ([0.0f64; 4], [0.0f64; 4]);
    for k in 0..n {
        let v = vpls[src * n + k];
        if v.position[3] <= 0.0 {
            continue;
        }
        let o = Vec3::from_slice(&v.position[..3]);
        let nn = Vec3::from_slice(&v.normal[..3]);
        for (ri, (p, pn)) in recv.iter().enumerate() {
            let to_p = *p - o;
            let d = to_p.length();
            let dir = to_p / d;
            let cos_s = nn.dot(dir);
            let cos_r = pn.dot(-dir);
            if cos_s <= 0.0 || cos_r <= 0.0 || d < 1e-3 || !sees(bvh, *p, *pn, o, nn) {
                continue;
            }
            let obj = &project.scene.objects()[receivers.points[ri].object as usize];
            let m = project.scene.materials().get(obj.material).cloned().unwrap_or_default();
            let alb = lum([m.base_color[0], m.base_color[1], m.base_color[2], 1.0]);
            // The bounce pass's form factor (`incident_power` in `ism_bounce.wgsl`): the receiving
            // patch as a disk of its area.
            let d2 = f64::from(d * d) + a_recv / std::f64::consts::PI;
            room_true[room(*p)] +=
                alb * lum(v.power) / n2 / std::f64::consts::PI * f64::from(cos_s * cos_r) / d2 * a_recv;
        }
        let next = vpls[(src + 1) * n + k];
        room_gpu[room(Vec3::from_slice(&next.position[..3]))] += lum(next.power) / n2;
    }
    (room_gpu, room_true)
}
