//! `bouncelab probe-ism`: ISM's imperfect shadow maps and lookups against rays through the
//! scene, per bounce set (`render::gi::ism::oracle`). Renders `ism` on a suite level (or a
//! `.gltf` level, e.g. one of `tools/unseen_levels.py`'s) at 128x72, two frames, then prints per
//! set:
//!
//! - `<level> set <s>: false occluder F (near N)  hole H`: the share of cosine-weighted
//!   directions of every fourth VPL's map whose stored depth is nearer than the rays' first hit
//!   (near: within 5% of the scene's span) or farther;
//! - `<level> set <s> lookups: ism/true R  false shadow ...  false light ...`: the lit share the
//!   ISM lookups give (pairs of every fourth VPL and receivers spread over the surfaces by area,
//!   weighted by their form factor) over the rays', preceded by the false light split by what its
//!   texel holds and the VPL's elevation;
//! - `<level> bounce power set<s+1>/true R`: the power set s's VPLs hand set s + 1 over the power
//!   they reflect with exact visibility (with the bounce tail on, the last set is not compared:
//!   `--settings "(bounce_tail: false)"` compares it too).
//!
//! `cargo run --release -- probe-ism rooms --power --unburied` (what the development notes'
//! claims are measured with: docs/notes/ism-tuning.md); the other flags pick rooms and list
//! wrongly lit pairs, a tile's points or its depths, each documented on its flag.

use std::fmt::Write as _;
use std::path::Path;

use crate::project_file::Project;
use crate::render::gi::ism::oracle::{
    self, BounceReport, Capture, ExampleKind, FALSE_LIGHT_KINDS, LookupOptions, LookupReport, MapReport, NeighbourAt,
    PairExample, PairFilter, PointsQuery, PointsReport, Receivers, ShowOptions, TexelCover,
};
use crate::render::{GpuContext, Renderer};
use crate::settings::{GiMode, IsmSettings};
use crate::suite;

/// `bouncelab probe-ism`'s arguments.
#[derive(clap::Args, Clone, Debug)]
pub struct ProbeIsmArgs {
    /// A suite scene's name, or a `.gltf` level outside the suite (e.g. `tools/unseen_levels.py`'s).
    #[arg(default_value = "rooms")]
    pub level: String,
    /// The ISM settings as RON, e.g. "(bounces: 3)" (fields left out keep their defaults; the
    /// level's own settings are replaced).
    #[arg(long, value_name = "RON", default_value = "()", value_parser = parse_settings)]
    pub settings: IsmSettings,
    /// Split the plan into rooms at x = X and z = Z (room = [x > X] + 2 [z > Z]) instead of the
    /// suite's three rooms (x / 5.2), for --pair, --cross and --vpls.
    #[arg(long, value_name = "X,Z", allow_hyphen_values = true, value_parser = parse_pair)]
    pub grid: Option<(f32, f32)>,
    /// Only pairs of VPLs in room A (any room: -1) and receivers in room B.
    #[arg(long, value_name = "A,B", allow_hyphen_values = true, value_parser = parse_pair)]
    pub pair: Option<(f32, f32)>,
    /// Only pairs in different rooms (on the three rooms: light through doorways); also prints
    /// each set's bounce power per room.
    #[arg(long)]
    pub cross: bool,
    /// List up to 12 wrongly lit pairs (false light) per set: the VPL, the receiver, the texel,
    /// its stored depth and point, and the rays' first hit.
    #[arg(long)]
    pub show: bool,
    /// List up to 12 wrongly shadowed pairs (false shadow) of the last set, both cosines above
    /// 0.2: the texel's stored depth and slot, and the rays' first hit.
    #[arg(long)]
    pub show_shadow: bool,
    /// With --show or --show-shadow: each listed pair's texel with its four neighbours and its
    /// coarse levels, their depths and points (a texel holds one surface; the lost one is often
    /// next door).
    #[arg(long)]
    pub neighbours: bool,
    /// With --show: false light of the K-th kind only, as the summary lists them (0 empty, 1
    /// pull-push fill or depth only, 2 the receiver's own surface, 3 a surface beyond the true
    /// occluder, 4 a nearer surface with the receiver on its plane, 5 a nearer surface whose
    /// clip lines the ray passes).
    #[arg(long, value_name = "K", value_parser = parse_kind)]
    pub show_kind: Option<usize>,
    /// With --show: only pairs whose VPL sees the receiver above this cosine of elevation.
    #[arg(long, value_name = "C", default_value_t = 0.0, allow_negative_numbers = true)]
    pub show_min_cos: f32,
    /// Write tile TILE's stored depths (left) beside the rays' (right) as `ism_tile.png` in the
    /// temporary folder (white near, black from half the scene's span on).
    #[arg(long, value_name = "TILE")]
    pub dump: Option<usize>,
    /// List tile TILE's chosen points (only those inside the box X0,Y0,Z0,X1,Y1,Z1 if given),
    /// each with the splat radius and footprint (centre, tangent images, in texels) that
    /// `ism_splat.wgsl` gives it; only the last set's tiles have footprints (the areas kept).
    #[arg(long, value_name = "TILE[,BOX]", allow_hyphen_values = true, value_parser = parse_points)]
    pub points: Option<(usize, Option<[f32; 6]>)>,
    /// With --points: whether each point's splat covers map texel X,Y as the splat pass decides
    /// it (footprint ellipse, plane hit, clip lines).
    #[arg(long, value_name = "X,Y", requires = "points", value_parser = parse_pair)]
    pub texel: Option<(f32, f32)>,
    /// With --texel: print each point's clip lines and the texel's hit on its plane.
    #[arg(long, requires = "texel")]
    pub clips: bool,
    /// Print how evenly the splat pass's lanes share the last set's footprints (lock-step
    /// groups of 32 lanes, a GPU's warp, and 8, lavapipe's SIMD): a thread per point against
    /// each workgroup's rows, or its texels (what `ism_splat.wgsl` does), dealt out in equal runs.
    #[arg(long)]
    pub splat_lanes: bool,
    /// Print each set's VPL count and luminance power per room.
    #[arg(long)]
    pub vpls: bool,
    /// Weight the lookup pairs by the VPL's luminance power too (what the screen sees).
    #[arg(long)]
    pub power: bool,
    /// Only receivers on surfaces open to the air in the lookup check (not a floor's face
    /// running on under a wall).
    #[arg(long)]
    pub unburied: bool,
    /// Sum the bounce check over N frames (the maps and lookups are the first frame's).
    #[arg(long, value_name = "N", default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..))]
    pub frames: u32,
    /// Receivers spread over the surfaces by area (fewer: faster and noisier).
    #[arg(long, value_name = "N", default_value_t = oracle::RECEIVERS, value_parser = parse_receivers)]
    pub receivers: usize,
    #[command(flatten)]
    pub units: super::SceneArgs,
}

fn parse_settings(text: &str) -> Result<IsmSettings, String> {
    let settings: IsmSettings = ron::from_str(text).map_err(|e| format!("ISM settings {text:?}: {e}"))?;
    settings.validate().map_err(|e| format!("ISM settings {text:?}: {e}"))?;
    Ok(settings)
}

fn parse_pair(text: &str) -> Result<(f32, f32), String> {
    let number = |s: &str| s.trim().parse::<f32>().ok().filter(|v| v.is_finite());
    text.split_once(',')
        .and_then(|(a, b)| Some((number(a)?, number(b)?)))
        .ok_or_else(|| format!("{text:?} is not two comma-separated numbers (e.g. 4.6,3.6)"))
}

fn parse_kind(text: &str) -> Result<usize, String> {
    text.parse::<usize>()
        .ok()
        .filter(|&k| k < FALSE_LIGHT_KINDS.len())
        .ok_or_else(|| format!("{text:?} is not a kind of false light, 0 to {}", FALSE_LIGHT_KINDS.len() - 1))
}

fn parse_receivers(text: &str) -> Result<usize, String> {
    text.parse::<usize>().ok().filter(|&n| n > 0).ok_or_else(|| format!("{text:?} is not a positive count"))
}

fn parse_points(text: &str) -> Result<(usize, Option<[f32; 6]>), String> {
    let (tile, rest) = text.split_once(',').map_or((text, None), |(t, r)| (t, Some(r)));
    let tile = tile.trim().parse::<usize>().map_err(|_| format!("{text:?}: the tile {tile:?} is not a tile index"))?;
    let Some(rest) = rest else { return Ok((tile, None)) };
    let corners: Vec<f32> = rest.split(',').filter_map(|v| v.trim().parse().ok()).collect();
    let bbox: [f32; 6] =
        corners.try_into().map_err(|_| format!("{text:?}: the box is six numbers X0,Y0,Z0,X1,Y1,Z1 after the tile"))?;
    Ok((tile, Some(bbox)))
}

/// Runs the probe and returns its report.
pub fn run(args: &ProbeIsmArgs) -> anyhow::Result<String> {
    if args.neighbours && !(args.show || args.show_shadow) {
        anyhow::bail!("--neighbours adds to the pairs --show or --show-shadow list: name one of them");
    }
    if (args.show_kind.is_some() || args.show_min_cos != 0.0) && !args.show {
        anyhow::bail!("--show-kind and --show-min-cos pick among the pairs --show lists: add --show");
    }
    let name = args.level.as_str();
    let mut project = load_level(name, &args.units)?;
    project.render.ism = args.settings.clone();
    project.render.mode = GiMode::Ism;
    let ctx = GpuContext::new_headless()?;
    let mut renderer = Renderer::new(&ctx.device, &ctx.queue)?;
    oracle::render_frames(&mut renderer, &project.scene, &project.render, oracle::WARM_UP_FRAMES)?;
    let mut capture = Capture::read(&renderer, &project.scene, &args.settings)?;
    let mut out = String::new();
    if let Some((tile, bbox)) = args.points {
        let query = PointsQuery { tile, bbox, texel: args.texel, clips: args.clips };
        write_points(&mut out, &oracle::list_points(&capture, &renderer, &query)?)?;
    }
    if args.splat_lanes {
        let l = oracle::splat_lanes(&capture, &renderer, &[32, 8])?;
        writeln!(
            out,
            "{name} splat lanes (last set): {} points, {} rows, {} texels walked, the largest footprint {} rows and {} texels; chosen points the splat drops: {} of dead VPLs, {} behind their VPL, {} seen edge-on",
            l.points, l.rows, l.texels, l.largest.0, l.largest.1, l.dropped[0], l.dropped[1], l.dropped[2]
        )?;
        for (width, [per_point, rows, texels]) in &l.busy {
            writeln!(
                out,
                "{name} splat lanes, groups of {width}: busy {:.1}% with a thread per point, {:.1}% with the rows dealt out, {:.1}% with the texels dealt out",
                100.0 * per_point,
                100.0 * rows,
                100.0 * texels
            )?;
        }
    }
    let sets = args.settings.bounces as usize;
    for set in 0..sets {
        write_maps(&mut out, name, &oracle::map_errors(&capture, set))?;
    }
    if let Some(tile) = args.dump {
        let image = oracle::tile_depths(&capture, tile)?;
        let path = std::env::temp_dir().join("ism_tile.png");
        crate::image_io::write_png(&path, image.width, image.height, image.pixels)?;
        writeln!(out, "{name}: tile {tile}'s depths (stored | rays) in {}", path.display())?;
    }
    let receivers = Receivers::distribute(&capture, args.receivers);
    let options = lookup_options(args);
    if args.vpls {
        for set in 0..sets {
            let rooms = oracle::vpls_by_room(&capture, &options.filter, set);
            writeln!(out, "{name} set {set} VPLs by room (count, luminance power): {rooms:?}")?;
        }
    }
    for set in 0..sets {
        write_lookups(&mut out, name, &oracle::lookups(&capture, &receivers, &options, set))?;
    }
    let frames = args.frames as usize;
    let bounces =
        oracle::bounce_over_frames(&mut renderer, &project.render, &mut capture, &receivers, &options.filter, frames)?;
    write_bounces(&mut out, name, &args.settings, &bounces, args.cross)?;
    Ok(out)
}

/// The level: a suite scene, or a `.gltf` file.
fn load_level(name: &str, units: &super::SceneArgs) -> anyhow::Result<Project> {
    let mut project = if name.ends_with(".gltf") {
        Project::from_gltf_with(Path::new(name), units.options().unwrap_or_default())?
    } else {
        suite::scene(name)?.load(Path::new("."))?
    };
    units.apply_sky(&mut project)?;
    Ok(project)
}

/// Which pairs the lookup check counts and lists, from the flags.
fn lookup_options(args: &ProbeIsmArgs) -> LookupOptions {
    LookupOptions {
        filter: PairFilter { grid: args.grid, cross: args.cross, pair: args.pair },
        power_weighted: args.power,
        unburied: args.unburied,
        show: ShowOptions {
            false_light: args.show,
            false_shadow: args.show_shadow,
            neighbours: args.neighbours,
            kind: args.show_kind,
            min_cos: args.show_min_cos,
        },
    }
}

/// The map check's line of one set.
fn write_maps(out: &mut String, name: &str, m: &MapReport) -> std::fmt::Result {
    writeln!(
        out,
        "{name} set {}: false occluder {:.4} (near {:.4})  hole {:.4}",
        m.set, m.false_occluder, m.near, m.hole
    )
}

/// The lookup check of one set: its listed pairs, the false light by kind, the summary line.
fn write_lookups(out: &mut String, name: &str, r: &LookupReport) -> std::fmt::Result {
    for example in &r.examples {
        write_example(out, example)?;
    }
    let total: f64 = r.false_light_kinds.iter().flatten().sum();
    if total > 0.0 {
        writeln!(
            out,
            "{name} set {} false light by what the texel holds (share of its power; VPL elevation bands <3, 3-10, 10-30, >30 degrees):",
            r.set
        )?;
        for (kind, row) in FALSE_LIGHT_KINDS.iter().zip(&r.false_light_kinds) {
            writeln!(out, "    {kind:38} {:.3}  {:.3?}", row.iter().sum::<f64>() / total, row.map(|x| x / total))?;
        }
    }
    writeln!(
        out,
        "{name} set {} lookups: ism/true {:.3}  false shadow {:.3} (own slab {:.3})  false light {:.3} (of true; of all pairs {:.4})  true {:.4e} ism {:.4e}",
        r.set,
        r.lit_ratio(),
        r.false_shadow / r.rays,
        r.own_slab / r.rays,
        r.false_light / r.rays,
        r.false_light / r.pairs,
        r.rays,
        r.ism
    )
}

/// One listed pair, with its texel's neighbours when they were asked for.
fn write_example(out: &mut String, e: &PairExample) -> std::fmt::Result {
    let (tile, (o, nn), (p, pn), t) = (e.tile, e.vpl, e.receiver, e.texel);
    let (qd, hit, stored) = (e.q_distance, e.first_hit, e.stored);
    match &e.what {
        ExampleKind::FalseShadow { slot } => writeln!(
            out,
            "  false shadow: tile {tile} vpl {o:.2} n {nn:.2}  recv {p:.2} n {pn:.2}  texel {t}  stored {stored:.3} m  slot {slot:?}  q at {qd:.3} m  first hit along q {hit:.3} m"
        )?,
        ExampleKind::FalseLight { sigma, q, mark, point } => writeln!(
            out,
            "  false light: tile {tile} vpl {o:.2} n {nn:.2} sigma {sigma:.4}  recv {p:.2} n {pn:.2}  q {q:.2}  texel {t}  stored {stored:.3} m (mark {mark}) point {point:.2?}  q at {qd:.3} m  first hit along q {hit:.3} m"
        )?,
    }
    for w in &e.neighbours {
        match w.at {
            NeighbourAt::Offset(dx, dy) => {
                writeln!(out, "      ({dx},{dy}) depth {:.3} point {:.2?}", w.depth, w.point)?
            }
            NeighbourAt::Level(level) => {
                writeln!(out, "      level {level} depth {:.3} point {:.2?}", w.depth, w.point)?;
            }
        }
    }
    Ok(())
}

/// A tile's chosen points, with their footprints and texel cover where known.
fn write_points(out: &mut String, r: &PointsReport) -> std::fmt::Result {
    let note = if r.last_set { "" } else { " (not the last set: no areas)" };
    writeln!(out, "tile {} vpl {:?} n {:?}{note}", r.tile, r.position, r.normal)?;
    for pt in &r.points {
        let (p, n) = (pt.position, pt.normal);
        write!(
            out,
            "  slot {} point {} at [{:.3}, {:.3}, {:.3}] n [{:.2}, {:.2}, {:.2}]",
            pt.slot, pt.index, p[0], p[1], p[2], n[0], n[1], n[2]
        )?;
        let Some(fp) = &pt.footprint else {
            writeln!(out)?;
            continue;
        };
        write!(out, " r {:.3} centre {:.1} ta {:.1} tb {:.1}", fp.radius, fp.centre, fp.ta, fp.tb)?;
        match &fp.texel {
            None => writeln!(out)?,
            Some(TexelCover::PastRim) => writeln!(out, "  texel: past the rim")?,
            Some(TexelCover::Decided { inside, hit, on_surface, clips }) => {
                writeln!(out, "  texel: inside {inside} hit {hit:.3} on surface {on_surface}")?;
                if let Some((lines, h)) = clips {
                    writeln!(out, "    clips {lines:?} hit point {h:?}")?;
                }
            }
        }
    }
    Ok(())
}

/// The bounce check's lines: per compared set, the power handed over the power reflected (and
/// per room with --cross).
fn write_bounces(
    out: &mut String,
    name: &str,
    ism: &IsmSettings,
    reports: &[BounceReport],
    cross: bool,
) -> std::fmt::Result {
    if ism.bounce_tail && ism.bounces > 1 {
        writeln!(out, "{name}: the last set carries the bounce tail; `(bounce_tail: false)` compares it too")?;
    }
    for r in reports {
        writeln!(out, "{name} bounce power set{}/true {:.3}", r.source + 1, r.ratio())?;
        if cross {
            writeln!(out, "{name} bounce power by room, set{}/true: {:?}", r.source + 1, r.room_ratios())?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flag_values_parse_or_say_why() {
        assert_eq!(parse_pair("-1,3"), Ok((-1.0, 3.0)));
        assert!(parse_pair("1").is_err() && parse_pair("a,b").is_err());
        assert_eq!(parse_points("12"), Ok((12, None)));
        assert_eq!(parse_points("3,0,0,0,1,2,3"), Ok((3, Some([0.0, 0.0, 0.0, 1.0, 2.0, 3.0]))));
        assert!(parse_points("3,0,0").is_err_and(|e| e.contains("six numbers")));
        assert!(parse_points("x").is_err());
        assert_eq!(parse_kind("5"), Ok(5));
        assert!(parse_kind("6").is_err());
        assert!(parse_settings("(vpl_count: 0)").is_err());
        assert!(parse_settings("(nope: 1)").is_err());
        assert_eq!(parse_settings("()"), Ok(IsmSettings::default()));
    }
}
