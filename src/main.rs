//! The `bouncelab` binary: argument parsing only; the work is in the library.

use std::path::PathBuf;
use std::process::ExitCode;

use bouncelab::cli;
use clap::{Parser, Subcommand};

/// Bounce Lab: design real-time global illumination.
#[derive(Parser)]
#[command(name = "bouncelab", version, about)]
struct Args {
    /// Project (.ron) or scene (.gltf/.glb) to open in the editor; the default project if omitted.
    project: Option<PathBuf>,
    #[command(flatten)]
    units: cli::SceneArgs,
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Subcommand)]
enum Command {
    /// Render a project or glTF scene headless to .exr (linear radiance) or .png (tonemapped).
    Render(cli::render::RenderArgs),
    /// Compare a candidate image with a reference: RMSE, relMSE, FLIP, luminance ratio.
    Compare {
        /// Candidate image (.exr linear or .png sRGB).
        candidate: PathBuf,
        /// Reference image.
        reference: PathBuf,
        /// Write the signed error heat map (red = too bright, blue = too dark).
        #[arg(long)]
        heatmap: Option<PathBuf>,
        /// Exposure in stops applied before FLIP (FLIP compares display images); negative
        /// stops are written as they are (`--exposure -1.5`).
        #[arg(long, default_value_t = 0.0, allow_negative_numbers = true, conflicts_with = "exposure_auto")]
        exposure: f32,
        /// Instead of --exposure: the exposure that puts the reference's mean luminance at 0.18,
        /// as docs/QUALITY.md judges every scene (printed as `exposure:`).
        #[arg(long)]
        exposure_auto: bool,
    },
    /// Time each mode per pass and write docs/BENCHMARKS.md; with --quality, render every mode
    /// on every scene of the suite against its reference and write docs/QUALITY.md.
    Bench {
        /// Fewer sizes and frames.
        #[arg(long)]
        quick: bool,
        /// The quality matrix (FLIP, relMSE, energy, frame time per mode and suite scene).
        #[arg(long)]
        quality: bool,
        /// Output markdown file (default docs/BENCHMARKS.md, or docs/QUALITY.md with --quality).
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Write the scene suite's glTF levels (assets/suite/) and, with --references, path-trace
    /// and cache their references (assets/suite/references/).
    Suite {
        /// Also render the references (minutes on two cores).
        #[arg(long)]
        references: bool,
        /// Only these scenes (comma-separated names); all if omitted.
        #[arg(long, value_delimiter = ',')]
        only: Vec<String>,
        /// Repository root.
        #[arg(long, default_value = ".")]
        root: PathBuf,
    },
    /// Build (or load from the cache) Modular Radiance Transfer's dictionary and print its
    /// modes, spectra and build time.
    MrtDictionary(cli::mrt::MrtArgs),
    /// The GPU profile: every mode on the suite's scenes at 720p, 1080p and 4K, each
    /// pass's GPU time, technique against direct, CPU record time; writes docs/gpu-profile.json
    /// and a Chrome trace per mode (`tools/gpu_bench.sh` packs it for the GPU machine).
    Profile(cli::profile::ProfileArgs),
    /// Export a project's scene with its authored lighting (lights, proxy blocks, sampling
    /// weights, clutter marks, settings) as glTF for the engine or DCC it came from.
    Export(cli::export::ExportArgs),
    /// Fit MRT proxy blocks to a level's geometry (rooms, and openings where they meet) and
    /// write the project with them.
    FitBlocks(cli::mrt::FitArgs),
    /// Tuning probe: render a technique and `direct` on suite scenes (or levels with their
    /// reference beside them) with overridden settings; print energy, indirect share and FLIP
    /// against the reference, judged as docs/QUALITY.md judges.
    Probe(cli::probe::ProbeArgs),
    /// Check MRT's reduced-space transfer on the CPU against a brute-force gather in the real
    /// geometry of a level: per block and per room, MRT's one-bounce light over the brute force's.
    ProbeMrt(cli::probe_mrt::ProbeMrtArgs),
    /// Check ISM's maps and lookups against rays through the scene, per bounce set: false
    /// occluders and holes, lit share, and the power each set hands the next.
    ProbeIsm(cli::probe_ism::ProbeIsmArgs),
    /// The share of each view's indirect light (path-traced) that leaves surfaces off screen or
    /// hidden: what a screen-space technique (`sshgi`) cannot send.
    UnseenLight(cli::unseen::UnseenArgs),
    /// Write the development levels of the shapes level designers build (rooms joined by
    /// corridors, L- and T-shaped rooms, ceiling steps, a wall-wide doorway, pillars, a 60 m
    /// hall, two storeys with a stairwell) as glTF files, to try the fitter and MRT on.
    DevLevels {
        /// The folder to write them to.
        out: PathBuf,
    },
    /// Regenerate assets/cornell_box.gltf and projects/default.ron from code.
    #[command(hide = true)]
    GenerateAssets {
        /// Repository root.
        #[arg(long, default_value = ".")]
        root: PathBuf,
    },
}

fn main() -> ExitCode {
    bouncelab::logging::init();
    let args = Args::parse();
    let result = match args.command {
        Some(Command::Render(args)) => cli::render::run(&args).map(|s| println!("wrote {s}")),
        Some(Command::Compare { candidate, reference, heatmap, exposure, exposure_auto }) => {
            let exposure = if exposure_auto {
                cli::compare::Exposure::MatchQuality
            } else {
                cli::compare::Exposure::Stops(exposure)
            };
            cli::compare::run(&candidate, &reference, heatmap.as_deref(), exposure).map(|s| println!("{s}"))
        }
        Some(Command::Bench { quick, quality: false, out }) => {
            cli::bench::run(&out.unwrap_or_else(|| "docs/BENCHMARKS.md".into()), quick).map(|md| println!("{md}"))
        }
        Some(Command::Bench { quality: true, out, .. }) => {
            cli::quality::run(std::path::Path::new("."), &out.unwrap_or_else(|| "docs/QUALITY.md".into()))
                .map(|md| println!("{md}"))
        }
        Some(Command::Suite { references, only, root }) => {
            cli::quality::suite(&root, references, &only).map(|s| println!("{s}"))
        }
        Some(Command::DevLevels { out }) => bouncelab::suite::shapes::write_all(&out)
            .map(|paths| paths.iter().for_each(|p| println!("wrote {}", p.display())))
            .map_err(|e| anyhow::anyhow!("{}: {e}", out.display())),
        Some(Command::GenerateAssets { root }) => cli::generate::generate(&root),
        Some(Command::MrtDictionary(args)) => cli::mrt::run(&args).map(|s| println!("{s}")),
        Some(Command::Profile(args)) => cli::profile::run(&args).map(|s| print!("{s}")),
        Some(Command::Export(args)) => cli::export::run(&args).map(|s| println!("wrote {s}")),
        Some(Command::FitBlocks(args)) => cli::mrt::fit(&args).map(|s| print!("{s}")),
        Some(Command::Probe(args)) => cli::probe::run(&args).map(|s| print!("{s}")),
        Some(Command::ProbeMrt(args)) => cli::probe_mrt::run(&args).map(|s| print!("{s}")),
        Some(Command::ProbeIsm(args)) => cli::probe_ism::run(&args).map(|s| print!("{s}")),
        Some(Command::UnseenLight(args)) => cli::unseen::run(&args).map(|s| print!("{s}")),
        None => bouncelab::app::run(args.project, args.units.options()),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {}", cli::error_report(&e));
            ExitCode::FAILURE
        }
    }
}
