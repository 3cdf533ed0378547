//! `bouncelab probe-mrt`: MRT's reduced-space transfer on the CPU against a brute-force gather
//! on a real level, to tell how far MRT's light is from the light the level really gets, and
//! where (per block, per room, per face, around doorways), with every stage open to print (the
//! GPU runtime computes the same transfer, `tests/integration/mrt.rs`). It fits proxy blocks to
//! a suite level (or uses its own), builds (or loads) the dictionary, lights every block texel
//! with the scene's lights through the real geometry (shadow rays on the scene BVH, the lit
//! wall's albedo: MRT's l_d), runs the reduced-space transfer on the CPU, and compares each
//! block's one-bounce light (a white receiver's outgoing radiance) with a brute-force gather at
//! the same points in the real geometry (cosine rays, the hit surface's shadowed direct light).
//!
//! `cargo run --release -- probe-mrt rooms --rays 1024` (`--closed`: every block closed)
//!
//! Prints per room and per block its mean direct and indirect light, MRT's over the brute
//! force's, and (per block) the texel rms error; the other flags add reports or variants, each
//! documented on its flag. The dictionary comes from the cache (`bouncelab mrt-dictionary`). A
//! level name ending in `.gltf` is read from that file (`tools/dev_levels.py` writes
//! development levels).

mod brute;
mod rooms;

use brute::Brute;
use rooms::rooms_report;
pub use rooms::{RoomLight, room_light};
use std::f64::consts::PI;
use std::fmt::{self, Write as _};
use std::path::Path;

use glam::Vec3;
use rayon::prelude::*;

use crate::precompute::bvh::SceneBvh;
use crate::precompute::mrt::basis::Element;
use crate::precompute::mrt::cache;
use crate::precompute::mrt::dictionary::{Dictionary, DictionaryParams, Progress};
use crate::precompute::mrt::geometry_image;
use crate::precompute::mrt::level::{self, Block, Level, Operators, Transfer};
use crate::precompute::mrt::lightfield::{self, LightFieldRes};
use crate::precompute::mrt::opening::{Opening, PositionOps};
use crate::precompute::mrt::proxy;
use crate::precompute::mrt::shape::{Face, Layout};
use crate::precompute::rng::Pcg32;
use crate::project_file::Project;
use crate::scene::{LightKind, MeshSource, ObjectRole, Scene};
use crate::suite;

/// `bouncelab probe-mrt`'s arguments.
#[derive(clap::Args, Clone, Debug)]
pub struct ProbeMrtArgs {
    /// A suite scene's name, a `.gltf` level outside the suite (e.g. `tools/dev_levels.py`'s), or
    /// `shape:NAME`, one of `bouncelab dev-levels`' shapes (its rooms are the report's rooms).
    #[arg(default_value = "rooms")]
    pub level: String,
    /// The brute force's cosine rays per texel (stratified: the largest square grid within).
    #[arg(long, default_value_t = 1024)]
    pub rays: usize,
    /// The dictionary's parameters as RON, e.g. "(res: 4, rays: 256)" (fields left out keep
    /// their defaults; --bands and --kb apply on top). Small ones build in seconds.
    #[arg(long, value_name = "RON", value_parser = parse_dictionary)]
    pub dictionary: Option<DictionaryParams>,
    /// Close every block (each room alone: MRT's in-block transfer without the interfaces,
    /// against the brute force in the real, connected level).
    #[arg(long)]
    pub closed: bool,
    /// Print each block's box (its lower and upper corners).
    #[arg(long)]
    pub boxes: bool,
    /// The dissertation's plain warp (no stretch correction).
    #[arg(long)]
    pub plain_warp: bool,
    /// Linked sides pass light over their whole area (no lintels).
    #[arg(long)]
    pub full_sides: bool,
    /// The light-field basis' position bands (the dictionary's default otherwise).
    #[arg(long, value_name = "N")]
    pub bands: Option<usize>,
    /// The blocks' indirect modes k_b.
    #[arg(long, value_name = "N")]
    pub kb: Option<usize>,
    /// Each linked side passes its open share everywhere and reflects nothing (the scalar
    /// transmission before per-position openings).
    #[arg(long)]
    pub share_only: bool,
    /// Linked sides masked by position, reflecting nothing.
    #[arg(long)]
    pub no_reflect: bool,
    /// Per partly open side, the flux of the light field that uniform walls send out through
    /// it: all of it, over the open positions, what the mask passes, the closed share times
    /// albedo, and what the reflection sends back.
    #[arg(long)]
    pub flux: bool,
    /// Print each block's warp (its stretch's flux corrections): the walls' and, per side
    /// light enters through, the faces'.
    #[arg(long)]
    pub warps: bool,
    /// Only block K's direct light (and, in the brute force, only light from points inside
    /// block K's box, grown by 0.15 m up to its linked sides) takes part: one bounce's sources
    /// one by one.
    #[arg(long, value_name = "K")]
    pub source: Option<usize>,
    /// Every texel (and every real surface but those of linked sides in the brute force) emits
    /// 1 in place of the direct light.
    #[arg(long)]
    pub uniform: bool,
    /// Per partly open side, the light leaving through its open positions (the doorway) from
    /// the block's direct light: traced from the exact texels (in the unit cube) against MRT's
    /// R_{b->rlf} b, and over the whole side.
    #[arg(long)]
    pub exit: bool,
    /// N bounces on both sides (MRT's feedback iterated N times: albedo x the last indirect
    /// added to the direct texels; the brute force a path of N diffuse bounces).
    #[arg(long, value_name = "N", default_value_t = 1)]
    pub multi: usize,
    /// The feedback's N bounces (albedo x indirect fed back), each's total light and its ratio
    /// to the previous one (the loop gain; above 1 the feedback diverges).
    #[arg(long, value_name = "N")]
    pub bounces: Option<usize>,
    /// The brute force treats the surfaces of linked sides (within 0.15 m of the side, facing
    /// across it) as MRT does: they get no direct light and reflecting there does not count as
    /// a bounce (MRT's reflection happens within the transfer).
    #[arg(long)]
    pub mimic: bool,
    /// The light on the closed part of each partly open side (the wall around a doorway, which
    /// has no texels): MRT's against the brute force at the real surface behind each closed
    /// opening position.
    #[arg(long)]
    pub sides: bool,
    /// Group the blocks into rooms by their centres along x at these cuts (e.g. "5.1,10.3"):
    /// the area-weighted light per room.
    #[arg(long, value_name = "X,...", value_delimiter = ',', allow_negative_numbers = true)]
    pub rooms_x: Vec<f32>,
    /// Each block's faces (world side): mean brute-force and MRT light.
    #[arg(long)]
    pub faces: bool,
    #[command(flatten)]
    pub units: crate::cli::SceneArgs,
}

fn parse_dictionary(text: &str) -> Result<DictionaryParams, String> {
    ron::from_str(text).map_err(|e| format!("dictionary parameters {text:?}: {e}"))
}

/// A block texel's real surface: point, normal, albedo (`None` where none was found).
type Texel = Option<(Vec3, Vec3, Vec3)>;

/// Light per block, per texel.
type Light = Vec<Vec<f64>>;

/// Runs the probe and returns its report.
pub fn run(args: &ProbeMrtArgs) -> anyhow::Result<String> {
    let mut out = String::new();
    let Setup { project, mut lvl, bvh, params, dictionary } = setup(args, &mut out)?;
    let scene = &project.scene;
    if !args.full_sides {
        set_openings(scene, &bvh, &mut lvl, &dictionary, args);
    }
    let ops = Operators { dictionary: &dictionary, interfaces: &dictionary.interfaces };
    let transfer = level::assemble(&lvl, &ops, 6);
    let probe = Probe { args, scene, bvh: &bvh, lvl: &lvl, dictionary: &dictionary, params, ops, transfer };
    if args.flux {
        flux_report(&probe, &mut out)?;
    }
    if args.warps {
        warps_report(&lvl, &mut out)?;
    }
    let lit = Lit::new(&probe);
    if args.exit {
        exit_report(&probe, &lit.l_d, &mut out)?;
    }
    let (mrt, last_input) = mrt_bounces(&probe, &lit);
    if let Some(n) = args.bounces {
        gain_report(&probe, &lit, n, &mut out)?;
    }
    let brute = Brute::new(&probe);
    let truth = brute.texels(&lit.texels);
    if args.sides {
        sides_report(&probe, &brute, &last_input, &mut out)?;
    }
    rooms_report(&probe, &lit, &truth, &mrt, &mut out)?;
    if args.faces {
        faces_report(&probe, &truth, &mrt, &mut out)?;
    }
    block_table(&lvl, &lit, &truth, &mrt, &mut out)?;
    Ok(out)
}

/// What every run needs: the level with its blocks, its BVH and the dictionary.
struct Setup {
    project: Project,
    lvl: Level,
    bvh: SceneBvh,
    params: DictionaryParams,
    dictionary: Dictionary,
}

fn setup(args: &ProbeMrtArgs, out: &mut String) -> anyhow::Result<Setup> {
    let project = load_level(args, out)?;
    let lvl = proxy_level(&project.scene, args, out)?;
    let bvh = SceneBvh::build(&project.scene);
    let params = dictionary_params(args);
    let (dictionary, source) = cache::load_or_build(&cache::default_dir(), &params, &Progress::default())?;
    writeln!(out, "dictionary: {source:?}")?;
    Ok(Setup { project, lvl, bvh, params, dictionary })
}

/// The level, with fitted proxy blocks where it has none (and every block closed with
/// `--closed`).
fn load_level(args: &ProbeMrtArgs, out: &mut String) -> anyhow::Result<Project> {
    let name = args.level.as_str();
    let mut project = if let Some(shape) = name.strip_prefix("shape:") {
        let path = std::env::temp_dir().join(format!("bouncelab-{}-{shape}.gltf", std::process::id()));
        let text = suite::shapes::gltf(&shape_level(shape)?).to_string_pretty();
        crate::atomic_file::write(&path, text.as_bytes())?;
        let project = Project::from_gltf(&path);
        let _ = std::fs::remove_file(&path);
        project?
    } else if name.ends_with(".gltf") {
        Project::from_gltf_with(Path::new(name), args.units.options().unwrap_or_default())?
    } else {
        suite::scene(name)?.load(Path::new("."))?
    };
    args.units.apply_sky(&mut project)?;
    if !project.scene.objects().iter().any(|o| o.role == ObjectRole::ProxyBlock) {
        let fitted = proxy::fitted_objects(&project.scene)?;
        writeln!(out, "{name}: fitted {} proxy blocks", fitted.len())?;
        project.scene.desc_mut().objects.extend(fitted);
    }
    if args.closed {
        for o in &mut project.scene.desc_mut().objects {
            if let MeshSource::Cuboid { openings, .. } = &mut o.source
                && o.role == ObjectRole::ProxyBlock
            {
                *openings = [false; 6];
            }
        }
    }
    Ok(project)
}

/// The shape level `name` of `bouncelab dev-levels`.
fn shape_level(name: &str) -> anyhow::Result<crate::precompute::mrt::fit::shapes::ShapeLevel> {
    suite::shapes::levels().into_iter().find(|l| l.name == name).ok_or_else(|| {
        let names: Vec<&str> = suite::shapes::levels().iter().map(|l| l.name).collect();
        anyhow::anyhow!("no shape level {name:?}; the shapes are {}", names.join(", "))
    })
}

/// MRT's level of the scene's proxy blocks (printing their boxes with `--boxes`).
fn proxy_level(scene: &Scene, args: &ProbeMrtArgs, out: &mut String) -> anyhow::Result<Level> {
    let (mut lvl, _) = proxy::level(scene)?;
    if args.boxes {
        for b in &lvl.blocks {
            writeln!(out, "box {:.2?} .. {:.2?}", b.origin, b.origin + b.size)?;
        }
    }
    if args.plain_warp {
        lvl = lvl.without_warp_correction();
    }
    Ok(lvl)
}

/// The dictionary's parameters: `--dictionary` (or the defaults), then `--bands` and `--kb`.
fn dictionary_params(args: &ProbeMrtArgs) -> DictionaryParams {
    let mut params = args.dictionary.unwrap_or_default();
    if let Some(b) = args.bands {
        params.interfaces.bands = b;
    }
    if let Some(k) = args.kb {
        params.k_b = k;
    }
    params
}

/// What the real level leaves open of each linked side, per position (`--share-only` and
/// `--no-reflect` change what the closed part does).
fn set_openings(scene: &Scene, bvh: &SceneBvh, lvl: &mut Level, dictionary: &Dictionary, args: &ProbeMrtArgs) {
    let positions = dictionary.interfaces.positions.positions;
    for ((i, w), o) in geometry_image::openings(scene, bvh, lvl, positions) {
        let o = if args.share_only {
            Opening::uniform(positions, o.share(), 0.0)
        } else if args.no_reflect {
            Opening { albedo: vec![0.0; o.open.len()], ..o }
        } else {
            o
        };
        lvl.set_opening(i, w, o);
    }
}

/// What every stage shares: the level, its BVH, the dictionary and MRT's transfer.
struct Probe<'a> {
    args: &'a ProbeMrtArgs,
    scene: &'a Scene,
    bvh: &'a SceneBvh,
    lvl: &'a Level,
    dictionary: &'a Dictionary,
    params: DictionaryParams,
    ops: Operators<'a>,
    transfer: Transfer,
}

impl Probe<'_> {
    /// MRT's indirect light from per-texel light `l`.
    fn indirect(&self, l: &[Vec<f64>]) -> Light {
        level::indirect(self.lvl, &self.ops, &self.transfer, l)
    }

    /// The light-field coefficients that block `b`'s walls, lit with `l`, send out through its
    /// world side `w` (MRT's R_{b->rlf} b); `None` where the dictionary lacks the shape or exit.
    fn exit_field(&self, b: &Block, w: Face, l: &[f64]) -> Option<Vec<f64>> {
        let e = self.dictionary.element(b.shape)?;
        let exit = self.dictionary.interfaces.exit(b.shape, b.local_face(w))?;
        Some(exit_coefficients(self.dictionary.interfaces.positions.k, e, &exit.r_b_rlf, &e.project(l)))
    }
}

/// R_{b->rlf} b: `k` light-field coefficients of element `e`'s block coefficients `bb`.
fn exit_coefficients(k: usize, e: &Element, r_b_rlf: &[f64], bb: &[f64]) -> Vec<f64> {
    (0..k).map(|i| (0..e.k_b).map(|j| r_b_rlf[i * e.k_b + j] * bb[j]).sum()).collect()
}

/// A luminance-like mean of rgb.
fn lum(v: Vec3) -> f64 {
    f64::from((v.x + v.y + v.z) / 3.0)
}

/// The area of a box of `size`'s face across `axis`.
fn face_area(size: Vec3, axis: usize) -> f32 {
    match axis {
        0 => size.y * size.z,
        1 => size.x * size.z,
        _ => size.x * size.y,
    }
}

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

/// The flux (irradiance summed over the opening positions, each weighted) of light-field
/// coefficients `q`.
fn flux(pos: &PositionOps, q: &[f64], weights: impl Fn(usize) -> f64) -> f64 {
    let k = pos.k;
    (0..pos.positions * pos.positions)
        .map(|p| weights(p) * pos.irradiance[p * k..(p + 1) * k].iter().zip(q).map(|(e, x)| e * x).sum::<f64>())
        .sum()
}

/// The k x k matrix `m` (row-major) times `q`.
fn apply(k: usize, m: &[f64], q: &[f64]) -> Vec<f64> {
    (0..k).map(|i| (0..k).map(|j| m[i * k + j] * q[j]).sum()).collect()
}

/// `--flux`: per partly open side, the flux of uniform walls' light field through it, its
/// profile along u, and where the passed light lands in the next block.
fn flux_report(probe: &Probe, out: &mut String) -> fmt::Result {
    let (lvl, pos) = (probe.lvl, &probe.dictionary.interfaces.positions);
    let k = pos.k;
    for (x, w) in lvl.linked_sides() {
        let Some(o) = lvl.opening(x, w) else { continue };
        let b = lvl.blocks[x];
        let l = vec![1.0; Layout::new(b.shape, probe.params.res).len()];
        let Some(q) = probe.exit_field(&b, w, &l) else { continue };
        let all = flux(pos, &q, |_| 1.0);
        let open = flux(pos, &q, |p| o.open[p]);
        let closed = flux(pos, &q, |p| o.albedo[p] * (1.0 - o.open[p]));
        let passed = pos.mask(&o.open).map_or(all, |m| flux(pos, &apply(k, &m, &q), |_| 1.0));
        let back = pos.reflection(&o.open, &o.albedo).map_or(0.0, |m| flux(pos, &apply(k, &m, &q), |_| 1.0));
        writeln!(
            out,
            "block {x} side {w:?}: share {:.3}, flux {all:.3}, over open {open:.3}, passed {passed:.3}, albedo x closed {closed:.3}, reflected {back:.3}",
            o.share()
        )?;
        flux_profile(pos, o, &q, out)?;
        if let Some(y) = lvl.link(x, w) {
            flux_landing(probe, (x, w, y), o, &q, out)?;
        }
    }
    Ok(())
}

/// The passed light's irradiance profile along u (summed over v): masked exactly, and through
/// the reduced mask.
fn flux_profile(pos: &PositionOps, o: &Opening, q: &[f64], out: &mut String) -> fmt::Result {
    let (k, np) = (pos.k, pos.positions);
    let Some(m) = pos.mask(&o.open) else { return Ok(()) };
    let mq = apply(k, &m, q);
    let at = |v: &[f64], p: usize| pos.irradiance[p * k..(p + 1) * k].iter().zip(v).map(|(e, x)| e * x).sum::<f64>();
    let exact: Vec<String> = (0..np)
        .map(|i| format!("{:5.1}", (0..np).map(|j| o.open[j * np + i] * at(q, j * np + i)).sum::<f64>()))
        .collect();
    let reduced: Vec<String> =
        (0..np).map(|i| format!("{:5.1}", (0..np).map(|j| at(&mq, j * np + i)).sum::<f64>())).collect();
    writeln!(out, "  exact   {}\n  reduced {}", exact.join(" "), reduced.join(" "))
}

/// Where the light passed through block x's side w lands: block y's walls (response rows and
/// their stretch corrections, area-weighted, E = pi x the white receiver's light) against the
/// flux entering (irradiance x the side's area / P^2).
fn flux_landing(
    probe: &Probe,
    (x, w, y): (usize, Face, usize),
    o: &Opening,
    q: &[f64],
    out: &mut String,
) -> fmt::Result {
    let (lvl, res) = (probe.lvl, probe.params.res);
    let pos = &probe.dictionary.interfaces.positions;
    let np = pos.positions;
    let passed_q = pos.mask(&o.open).map_or(q.to_vec(), |m| apply(pos.k, &m, q));
    let walls = probe.dictionary.interfaces.response.walls(&passed_q);
    let by = lvl.blocks[y];
    let rows = level::response_rows(&by, w.opposite(), res);
    let scales = level::response_scales(lvl, y, w.opposite(), res);
    let layout = Layout::new(by.shape, res);
    let per = (res * res) as f64;
    let mut landed = 0.0;
    for (i, (row, sc)) in rows.iter().zip(&scales).enumerate() {
        let Some(row) = row else { continue };
        let face = by.world_face(layout.sample(i).0);
        let area = f64::from(face_area(by.size, face.axis())) / per;
        landed += area * PI * sc * walls[*row];
    }
    let b = lvl.blocks[x];
    let side_area = f64::from(if w.axis() == 0 { b.size.y * b.size.z } else { b.size.x * b.size.y });
    let entering = flux(pos, &passed_q, |_| 1.0) * side_area / (np * np) as f64;
    let canonical_in = flux(pos, &passed_q, |_| 1.0) / (np * np) as f64;
    let canonical_out: f64 = rows.iter().flatten().map(|row| PI * walls[*row] / per).sum::<f64>();
    writeln!(
        out,
        "  into block {y}: flux entering {entering:.3}, landing on its walls {landed:.3}; unit cube {canonical_in:.4} -> {canonical_out:.4}"
    )
}

/// `--warps`: each block's size and its warp's corrections.
fn warps_report(lvl: &Level, out: &mut String) -> fmt::Result {
    for (x, w) in lvl.warps.iter().enumerate() {
        let through: Vec<String> = w.through.iter().map(|r| format!("{:.2?}", r)).collect();
        writeln!(
            out,
            "block {x} {:?} walls {:.2?}\n  through {}",
            lvl.blocks[x].size,
            w.walls,
            through.join("\n          ")
        )?;
    }
    Ok(())
}

/// Every texel's real surface (the runtime's geometry images) and MRT's direct light there.
struct Lit {
    /// Per block, per texel.
    texels: Vec<Vec<Texel>>,
    /// MRT's l_d: the direct light (or 1 with `--uniform`), only block K's with `--source K`.
    l_d: Light,
}

impl Lit {
    fn new(probe: &Probe) -> Self {
        let (scene, bvh) = (probe.scene, probe.bvh);
        let sky = scene.sky_texels();
        let texels: Vec<Vec<Texel>> = probe
            .lvl
            .blocks
            .iter()
            .map(|b| {
                geometry_image::geometry_image(scene, sky.as_deref(), bvh, b, probe.params.res)
                    .into_iter()
                    .map(|s| s.found.then_some((s.position, s.normal, s.albedo)))
                    .collect()
            })
            .collect();
        let (source, uniform) = (probe.args.source, probe.args.uniform);
        let l_d = texels
            .iter()
            .enumerate()
            .map(|(x, t)| {
                t.iter()
                    .map(|s| match s {
                        Some(_) if uniform && source.is_none_or(|k| k == x) => 1.0,
                        Some((q, n, a)) if source.is_none_or(|k| k == x) => lum(direct(scene, bvh, *q, *n, *a)),
                        _ => 0.0,
                    })
                    .collect()
            })
            .collect();
        Self { texels, l_d }
    }
}

/// `--exit`: per partly open side, the light leaving the block through it from its direct
/// light, exact (traced from the texels) and MRT's, through the doorway and the whole side.
fn exit_report(probe: &Probe, l_d: &[Vec<f64>], out: &mut String) -> fmt::Result {
    let (lvl, pos) = (probe.lvl, &probe.dictionary.interfaces.positions);
    let lf = probe.params.interfaces.light_field();
    let np = lf.positions;
    let cos = cell_weights(&lf);
    let sum = |v: &[f64], f: &dyn Fn(usize) -> f64| (0..np * np).map(|p| f(p) * v[p]).sum::<f64>();
    for (x, w) in lvl.linked_sides() {
        let Some(o) = lvl.opening(x, w) else { continue };
        let b = lvl.blocks[x];
        let Some(q) = probe.exit_field(&b, w, &l_d[x]) else { continue };
        let layout = Layout::new(b.shape, probe.params.res);
        let exact = lightfield::trace(&layout, b.local_face(w), &l_d[x], 1, &lf);
        let exact_e = exact_irradiance(&lf, &exact, &cos);
        let k = pos.k;
        let red_e: Vec<f64> =
            (0..np * np).map(|p| pos.irradiance[p * k..(p + 1) * k].iter().zip(&q).map(|(a, c)| a * c).sum()).collect();
        writeln!(
            out,
            "exit {x} {w:?}: whole side exact {:.4} / MRT {:.4}; doorway exact {:.4} / MRT {:.4}",
            sum(&exact_e, &|_| 1.0),
            sum(&red_e, &|_| 1.0),
            sum(&exact_e, &|p| o.open[p]),
            sum(&red_e, &|p| o.open[p])
        )?;
    }
    Ok(())
}

/// Each direction cell's cosine to the opening's normal times its solid angle (the cell
/// cosines of `PositionOps::build`).
fn cell_weights(lf: &LightFieldRes) -> Vec<f64> {
    let dirs = lf.directions * lf.directions;
    (0..dirs)
        .map(|c| {
            let (a, bb) = (c % lf.directions, c / lf.directions);
            let sq = glam::Vec2::new(
                (a as f32 + 0.5) / lf.directions as f32 * 2.0 - 1.0,
                (bb as f32 + 0.5) / lf.directions as f32 * 2.0 - 1.0,
            );
            f64::from(lightfield::square_to_hemisphere(sq).z) * std::f64::consts::TAU / dirs as f64
        })
        .collect()
}

/// The irradiance per opening position of the exact light field `exact`.
fn exact_irradiance(lf: &LightFieldRes, exact: &[f64], cos: &[f64]) -> Vec<f64> {
    let np = lf.positions;
    let dirs = lf.directions * lf.directions;
    (0..np * np)
        .map(|p| {
            let (i, j) = (p % np, p / np);
            (0..dirs)
                .map(|c| exact[lightfield::index(lf, (i, j), (c % lf.directions, c / lf.directions))] * cos[c])
                .sum()
        })
        .collect()
}

/// MRT's indirect light after `--multi` bounces (the feedback: albedo x the last indirect added
/// to the direct texels), and the light that last bounce started from.
fn mrt_bounces(probe: &Probe, lit: &Lit) -> (Light, Light) {
    let bounces = probe.args.multi.max(1);
    let mut mrt = probe.indirect(&lit.l_d);
    let mut last_input = lit.l_d.clone();
    for _ in 1..bounces {
        let fed: Light = lit
            .l_d
            .iter()
            .zip(&mrt)
            .zip(&lit.texels)
            .map(|((d, m), t)| {
                d.iter().zip(m).zip(t).map(|((d, m), s)| d + m.max(0.0) * s.map_or(0.0, |(_, _, a)| lum(a))).collect()
            })
            .collect();
        mrt = probe.indirect(&fed);
        last_input = fed;
    }
    (mrt, last_input)
}

/// `--bounces N`: the feedback's first `n` bounces, each's total light and its ratio to the
/// previous one.
fn gain_report(probe: &Probe, lit: &Lit, n: usize, out: &mut String) -> fmt::Result {
    let total = |v: &[Vec<f64>]| v.iter().flatten().map(|x| x.abs()).sum::<f64>();
    let mut bounce = lit.l_d.clone();
    let mut last = total(&bounce);
    for k in 1..=n {
        let ind = probe.indirect(&bounce);
        bounce = ind
            .iter()
            .zip(&lit.texels)
            .map(|(b, t)| b.iter().zip(t).map(|(v, s)| v.max(0.0) * s.map_or(0.0, |(_, _, a)| lum(a))).collect())
            .collect();
        let now = total(&bounce);
        writeln!(out, "bounce {k}: {now:.4} ({:.3} of the previous)", now / last.max(1e-30))?;
        last = now;
    }
    Ok(())
}

/// `--sides`: the light on the closed part of each partly open side, MRT's (from the last
/// bounce's input `last_input`) against the brute force's.
fn sides_report(probe: &Probe, brute: &Brute, last_input: &[Vec<f64>], out: &mut String) -> fmt::Result {
    let (lvl, scene, bvh) = (probe.lvl, probe.scene, probe.bvh);
    let np = probe.dictionary.interfaces.positions.positions;
    for ((x, w), v) in level::side_light(lvl, &probe.ops, &probe.transfer, last_input) {
        let (Some(o), Some(frame)) = (lvl.opening(x, w), geometry_image::SideFrame::new(lvl, x, w)) else {
            continue;
        };
        let cells: Vec<usize> = (0..np * np).filter(|p| o.open[*p] < 0.5).collect();
        let reach = geometry_image::SEARCH.min(0.45 * lvl.blocks[x].size[w.axis()]);
        let truth: Vec<f64> = cells
            .par_iter()
            .map(|&p| {
                let at = frame.point(((p % np) as f32 + 0.5) / np as f32, ((p / np) as f32 + 0.5) / np as f32);
                let s = geometry_image::surface(scene, bvh, at, -frame.n, reach);
                if s.found { brute.gather(s.position, s.normal, 900_000 + (x * 1000 + p) as u64) } else { 0.0 }
            })
            .collect();
        let t = truth.iter().sum::<f64>() / cells.len().max(1) as f64;
        let m = cells.iter().map(|p| v[*p]).sum::<f64>() / cells.len().max(1) as f64;
        writeln!(
            out,
            "side {x} {w:?}: {} closed positions, brute force {t:.4}, MRT {m:.4}: {:.3}",
            cells.len(),
            m / t.max(1e-12)
        )?;
    }
    Ok(())
}

/// `--faces`: each block's faces (world side), mean brute-force and MRT light.
fn faces_report(probe: &Probe, truth: &[Vec<f64>], mrt: &[Vec<f64>], out: &mut String) -> fmt::Result {
    let res = probe.params.res;
    for (x, b) in probe.lvl.blocks.iter().enumerate() {
        let layout = Layout::new(b.shape, res);
        let per = res * res;
        let line: Vec<String> = (0..layout.len() / per)
            .map(|g| {
                let face = b.world_face(layout.sample(g * per).0);
                let t: f64 = truth[x][g * per..(g + 1) * per].iter().sum::<f64>() / per as f64;
                let m: f64 = mrt[x][g * per..(g + 1) * per].iter().sum::<f64>() / per as f64;
                format!("{face:?} {t:.4}/{m:.4}")
            })
            .collect();
        writeln!(out, "block {x}: {}", line.join(", "))?;
    }
    Ok(())
}

/// The per-block table: mean direct and indirect light, MRT's over the brute force's, and the
/// texel rms error over the brute force's mean.
fn block_table(lvl: &Level, lit: &Lit, truth: &[Vec<f64>], mrt: &[Vec<f64>], out: &mut String) -> fmt::Result {
    writeln!(
        out,
        "| block | shape | size (m) | direct | brute-force bounce | MRT bounce | MRT / brute force | texel rms / mean |"
    )?;
    writeln!(out, "|---|---|---|---|---|---|---|---|")?;
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len().max(1) as f64;
    for (x, b) in lvl.blocks.iter().enumerate() {
        let (d, t, m) = (mean(&lit.l_d[x]), mean(&truth[x]), mean(&mrt[x]));
        let rms =
            (mrt[x].iter().zip(&truth[x]).map(|(a, b)| (a - b).powi(2)).sum::<f64>() / truth[x].len() as f64).sqrt();
        writeln!(
            out,
            "| {x} | {} | {:.1} x {:.1} x {:.1} | {d:.4} | {t:.4} | {m:.4} | {:.3} | {:.3} |",
            b.shape.name(),
            b.size.x,
            b.size.y,
            b.size.z,
            m / t.max(1e-12),
            rms / t.max(1e-12)
        )?;
    }
    Ok(())
}
