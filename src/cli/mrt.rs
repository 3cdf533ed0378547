//! `bouncelab mrt-dictionary`: builds (or loads from the cache) MRT's dictionary with progress
//! and the time left on stderr, and prints what it holds: per shape the samples, the modes kept,
//! the singular-value energy of the direct-light prior and of the indirect operator M (the
//! dissertation's Table 3.2), the uniform-light check, and the build time and sizes.

use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::Instant;

use crate::precompute::mrt::basis::Element;
use crate::precompute::mrt::cache::{self, Source};
use crate::precompute::mrt::dictionary::{DictionaryParams, Progress};
use crate::precompute::mrt::operators::InterfaceParams;

/// Arguments of `bouncelab mrt-dictionary`.
#[derive(clap::Args, Debug)]
pub struct MrtArgs {
    /// Texels per face side.
    #[arg(long, default_value_t = DictionaryParams::default().res)]
    pub res: usize,
    /// Gather rays per texel (16384 is the dissertation's final quality).
    #[arg(long, default_value_t = DictionaryParams::default().rays)]
    pub rays: usize,
    /// Indirect modes kept.
    #[arg(long, default_value_t = DictionaryParams::default().k_b)]
    pub modes: usize,
    /// Enrichment passes.
    #[arg(long, default_value_t = DictionaryParams::default().enrichment)]
    pub enrichment: usize,
    /// Light-field positions per side of an opening.
    #[arg(long, default_value_t = InterfaceParams::default().positions)]
    pub lf_positions: usize,
    /// Light-field direction cells per side.
    #[arg(long, default_value_t = InterfaceParams::default().directions)]
    pub lf_directions: usize,
    /// Light-field supersamples per side of a direction cell.
    #[arg(long, default_value_t = InterfaceParams::default().supersample)]
    pub lf_supersample: usize,
    /// Enrichment passes of the light-field basis.
    #[arg(long, default_value_t = InterfaceParams::default().enrichment)]
    pub lf_enrichment: usize,
    /// Position bands across an opening whose masked copies enrich the light-field basis (at
    /// most the positions; more is taken as the positions).
    #[arg(long, default_value_t = InterfaceParams::default().bands)]
    pub lf_bands: usize,
    /// Build even when a cached file exists (and replace it).
    #[arg(long)]
    pub rebuild: bool,
    /// Cache folder (default: the user's cache folder, `bouncelab/`).
    #[arg(long)]
    pub cache: Option<PathBuf>,
}

/// Arguments of `bouncelab fit-blocks`.
#[derive(clap::Args, Debug)]
pub struct FitArgs {
    /// The level: a glTF file or a project file.
    pub input: PathBuf,
    /// The project file to write (`.ron`; the level with the fitted proxy blocks). Never one of
    /// the inputs: the level keeps its geometry.
    #[arg(long)]
    pub out: PathBuf,
    #[command(flatten)]
    pub units: super::SceneArgs,
}

/// Fits proxy blocks to a level and writes the project with them; returns the report. Blocks
/// the project already has are replaced (and the report says so), never stacked: two sets made
/// `mrt` render twice the light.
pub fn fit(args: &FitArgs) -> anyhow::Result<String> {
    use crate::output_path;
    use crate::scene::ObjectRole;
    output_path::check(&args.out, output_path::PROJECT, &[&args.input])?;
    let mut project = args.units.open(&args.input)?;
    let inputs = project.files();
    output_path::check(&args.out, output_path::PROJECT, &inputs.iter().map(PathBuf::as_path).collect::<Vec<_>>())?;
    let objects = &mut project.scene.desc_mut().objects;
    let before = objects.len();
    objects.retain(|o| o.role != ObjectRole::ProxyBlock);
    let replaced = before - objects.len();
    let bvh = crate::precompute::bvh::SceneBvh::build(&project.scene);
    let crate::precompute::mrt::proxy::Fitted { objects: fitted, gaps } =
        crate::precompute::mrt::proxy::fit_scene(&project.scene, &bvh)
            .map_err(|e| anyhow::anyhow!("{}: cannot fit proxy blocks: {e}", args.input.display()))?;
    let mut out = format!("{}: {} proxy blocks\n", args.input.display(), fitted.len());
    if replaced > 0 {
        let _ = writeln!(out, "note: replaced the {replaced} proxy blocks the project had (blocks are never stacked)");
    }
    let sides = ["+X", "-X", "+Y", "-Y", "+Z", "-Z"];
    for o in &fitted {
        if let crate::scene::MeshSource::Cuboid { size, openings } = &o.source {
            let open: Vec<&str> = sides.iter().zip(openings).filter(|(_, o)| **o).map(|(s, _)| *s).collect();
            let t = o.transform.translation;
            let _ = writeln!(
                out,
                "  {}: centre ({:.2}, {:.2}, {:.2}), size {:.2} x {:.2} x {:.2} m, open {}",
                o.name,
                t.x,
                t.y,
                t.z,
                size.x,
                size.y,
                size.z,
                if open.is_empty() { "none".to_owned() } else { open.join(" ") }
            );
        }
    }
    if gaps.is_empty() {
        let _ = writeln!(out, "the blocks cover every enclosed space, linked through every opening between them");
    } else {
        let plural = if gaps.len() == 1 { "" } else { "s" };
        let _ = writeln!(out, "warning: the fit is partial ({} gap{plural}):", gaps.len());
        for g in &gaps {
            let _ = writeln!(out, "  - {}", g.text);
        }
    }
    project.scene.desc_mut().objects.extend(fitted);
    project.save(&args.out)?;
    let _ = writeln!(out, "wrote {}", args.out.display());
    Ok(out)
}

/// Modes needed for `share` of the energy (sum of squares) of the spectrum `s`.
fn modes_for(s: &[f64], share: f64) -> usize {
    let total: f64 = s.iter().map(|x| x * x).sum();
    let mut acc = 0.0;
    for (i, x) in s.iter().enumerate() {
        acc += x * x;
        if acc >= share * total {
            return i + 1;
        }
    }
    s.len()
}

/// The worst deviation from 1 of the reconstructed bounce of uniform light on every present
/// face, on the closed shape only (where the exact bounce is 1).
fn furnace(e: &Element) -> Option<f64> {
    (e.shape == crate::precompute::mrt::shape::Shape::Closed).then(|| {
        let ind = e.reconstruct(&e.project(&vec![1.0; e.n]));
        ind.iter().map(|v| (v - 1.0).abs()).fold(0.0, f64::max)
    })
}

/// Runs the command; returns the report.
pub fn run(args: &MrtArgs) -> anyhow::Result<String> {
    let params = DictionaryParams {
        res: args.res,
        rays: args.rays,
        k_b: args.modes,
        enrichment: args.enrichment,
        interfaces: InterfaceParams {
            positions: args.lf_positions,
            directions: args.lf_directions,
            supersample: args.lf_supersample,
            enrichment: args.lf_enrichment,
            bands: args.lf_bands.min(args.lf_positions),
            ..InterfaceParams::default()
        },
        ..DictionaryParams::default()
    };
    params.validate()?;
    let dir = args.cache.clone().unwrap_or_else(cache::default_dir);
    if args.rebuild {
        let path = cache::path_for(&dir, &params);
        if path.exists() {
            std::fs::remove_file(&path).map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
        }
    }
    let progress = Progress::default();
    let started = Instant::now();
    let done = std::sync::atomic::AtomicBool::new(false);
    let (dictionary, source) = std::thread::scope(|scope| {
        scope.spawn(|| {
            // A line rewritten in place on a terminal, a plain line every 5 s in logs.
            let tty = std::io::IsTerminal::is_terminal(&std::io::stderr());
            let every = std::time::Duration::from_millis(if tty { 200 } else { 5000 });
            let mut shown = Instant::now();
            while !done.load(std::sync::atomic::Ordering::Relaxed) {
                std::thread::sleep(std::time::Duration::from_millis(50));
                let (f, left) = progress.fraction_and_left();
                if f > 0.0 && f < 1.0 && shown.elapsed() >= every {
                    shown = Instant::now();
                    let left = left.map_or(String::from("?"), |s| format!("{s:.0}"));
                    let line = format!("mrt dictionary: {:5.1}% ({left} s left)", 100.0 * f);
                    if tty { eprint!("\r{line}   ") } else { eprintln!("{line}") }
                }
            }
        });
        let result = cache::load_or_build(&dir, &params, &progress);
        done.store(true, std::sync::atomic::Ordering::Relaxed);
        result
    })?;
    if std::io::IsTerminal::is_terminal(&std::io::stderr()) {
        eprintln!();
    }
    let seconds = started.elapsed().as_secs_f64();
    let mut out = String::new();
    match &source {
        Source::Loaded(path) => writeln!(out, "loaded {} in {seconds:.2} s", path.display())?,
        Source::Built { path, why, not_cached: None } => {
            writeln!(out, "built in {seconds:.1} s ({why}); wrote {}", path.display())?;
        }
        built @ Source::Built { .. } => writeln!(out, "{} ({seconds:.1} s)", built.describe())?,
    }
    let _ = writeln!(
        out,
        "cache folder: {} (keeps the dictionary in use and the {} most recently used others)",
        dir.display(),
        cache::KEEP_OTHERS
    );
    writeln!(
        out,
        "{} texels per face, {} rays per texel, k_d {}, k_b {}, enrichment {}; runtime operators {:.2} MB (f32)",
        params.res,
        params.rays,
        params.k_d,
        params.k_b,
        params.enrichment,
        dictionary.runtime_bytes() as f64 / 1e6
    )?;
    writeln!(
        out,
        "| shape | n | k_d | k_b | L_d modes for 80/90/95% | M modes for 80/90/95% | uniform light, worst error |"
    )?;
    writeln!(out, "|---|---|---|---|---|---|---|")?;
    for e in &dictionary.elements {
        let modes = |s: &[f64]| format!("{} / {} / {}", modes_for(s, 0.8), modes_for(s, 0.9), modes_for(s, 0.95));
        writeln!(
            out,
            "| {} | {} | {} | {} | {} | {} | {} |",
            e.shape.name(),
            e.n,
            e.k_d,
            e.k_b,
            modes(&e.data_sigma),
            modes(&e.m_sigma),
            furnace(e).map_or("-".into(), |w| format!("{w:.2e}"))
        )?;
    }
    interfaces(&dictionary, &mut out)?;
    Ok(out)
}

/// Reports the interface operators.
fn interfaces(dictionary: &crate::precompute::mrt::dictionary::Dictionary, out: &mut String) -> anyhow::Result<()> {
    let (ops, params) = (&dictionary.interfaces, &dictionary.params.interfaces);
    let r = &ops.response;
    writeln!(
        out,
        "interfaces: light fields of {}x{} positions, {}x{} directions, {}x{} supersampled; k_rlf {} (light-field modes for 80/90/95%: {} / {} / {}) after {} enrichment passes; k_r {} (G modes for 80/90/95%: {} / {} / {})",
        params.positions,
        params.positions,
        params.directions,
        params.directions,
        params.supersample,
        params.supersample,
        ops.k_rlf,
        modes_for(&ops.sigma, 0.8),
        modes_for(&ops.sigma, 0.9),
        modes_for(&ops.sigma, 0.95),
        params.enrichment,
        r.k_r,
        modes_for(&r.sigma, 0.8),
        modes_for(&r.sigma, 0.9),
        modes_for(&r.sigma, 0.95),
    )?;
    for (turn, m) in &ops.turns {
        // The largest singular value of R: about 1 or below (a reprojection adds no light,
        // though resampling may gather several samples onto one).
        let k = ops.k_rlf;
        let top = faer::Mat::<f64>::from_fn(k, k, |i, j| m[i * k + j])
            .singular_values()
            .ok()
            .and_then(|s| s.first().copied())
            .unwrap_or(f64::NAN);
        writeln!(out, "R {turn:?}: largest singular value {top:.3}")?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn modes_for_counts_the_leading_energy() {
        assert_eq!(modes_for(&[3.0, 1.0, 1.0], 0.8), 1, "9 of 11");
        assert_eq!(modes_for(&[3.0, 1.0, 1.0], 0.9), 2);
        assert_eq!(modes_for(&[1.0, 1.0], 1.0), 2);
    }
}
