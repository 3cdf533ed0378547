//! The `bouncelab` binary: argument parsing only; the work is in the library.

use std::path::PathBuf;
use std::process::ExitCode;

use bouncelab::cli;
use bouncelab::settings::GiMode;
use clap::{Parser, Subcommand};

/// Bounce Lab: design real-time global illumination.
#[derive(Parser)]
#[command(name = "bouncelab", version, about)]
struct Args {
    /// Project (.ron) or scene (.gltf/.glb) to open in the editor; the default project if omitted.
    project: Option<PathBuf>,
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Subcommand)]
enum Command {
    /// Render a project or glTF scene headless to .exr (linear radiance) or .png (tonemapped).
    Render {
        /// Project (.ron) or scene (.gltf/.glb).
        input: PathBuf,
        /// GI mode (default: the project's).
        #[arg(long, value_enum)]
        mode: Option<GiMode>,
        /// Output file (.exr or .png).
        #[arg(long)]
        out: PathBuf,
        /// Width in pixels.
        #[arg(long, default_value_t = 640)]
        width: u32,
        /// Height in pixels.
        #[arg(long, default_value_t = 360)]
        height: u32,
        /// Frames to render; the last one is written.
        #[arg(long, default_value_t = 1)]
        frames: u32,
        /// Exposure in stops for the PNG view.
        #[arg(long)]
        exposure: Option<f32>,
        /// Samples per pixel (reference mode).
        #[arg(long)]
        spp: Option<u32>,
        /// Longest path in bounces, 1 = direct light only (reference mode).
        #[arg(long)]
        max_bounces: Option<u32>,
        /// Random seed (reference mode).
        #[arg(long)]
        seed: Option<u64>,
        /// Bounce from which Russian roulette may end paths (reference mode).
        #[arg(long)]
        rr_start: Option<u32>,
        /// Write an intermediate buffer instead of the final image (albedo, normal, material,
        /// motion, object_id, depth, indirect, hdr, ldr, shadow_map).
        #[arg(long)]
        buffer: Option<String>,
        /// Supersampling per axis for raster modes: renders at N times the size and box-filters
        /// down, as a path tracer's pixel filter does (1 = one sample at each pixel centre).
        #[arg(long, default_value_t = 3)]
        ssaa: u32,
    },
    /// Compare a candidate image with a reference: RMSE, relMSE, FLIP, luminance ratio.
    Compare {
        /// Candidate image (.exr linear or .png sRGB).
        candidate: PathBuf,
        /// Reference image.
        reference: PathBuf,
        /// Write the signed error heat map (red = too bright, blue = too dark).
        #[arg(long)]
        heatmap: Option<PathBuf>,
        /// Exposure in stops applied before FLIP (FLIP compares display images).
        #[arg(long, default_value_t = 0.0)]
        exposure: f32,
    },
    /// Time each mode per pass and write docs/BENCHMARKS.md.
    Bench {
        /// Fewer sizes and frames.
        #[arg(long)]
        quick: bool,
        /// Output markdown file.
        #[arg(long, default_value = "docs/BENCHMARKS.md")]
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
        Some(Command::Render {
            input,
            mode,
            out,
            width,
            height,
            frames,
            exposure,
            spp,
            max_bounces,
            seed,
            rr_start,
            buffer,
            ssaa,
        }) => {
            let args = cli::render::RenderArgs {
                input,
                mode,
                out,
                width,
                height,
                frames,
                exposure,
                spp,
                max_bounces,
                seed,
                rr_start,
                buffer,
                ssaa,
            };
            cli::render::run(&args).map(|s| println!("wrote {s}"))
        }
        Some(Command::Compare { candidate, reference, heatmap, exposure }) => {
            cli::compare::run(&candidate, &reference, heatmap.as_deref(), exposure).map(|s| println!("{s}"))
        }
        Some(Command::Bench { quick, out }) => cli::bench::run(&out, quick).map(|md| println!("{md}")),
        Some(Command::GenerateAssets { root }) => cli::generate::generate(&root),
        None => bouncelab::app::run(args.project),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}
