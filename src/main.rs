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
    env_logger::Builder::from_env(
        env_logger::Env::default().default_filter_or("info,wgpu_core=warn,wgpu_hal=warn,naga=warn"),
    )
    .init();
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
        }) => cli::render::run(&cli::render::RenderArgs {
            input,
            mode,
            out,
            width,
            height,
            frames,
            exposure,
        })
        .map(|s| println!("wrote {s}")),
        Some(Command::Bench { quick, out }) => {
            cli::bench::run(&out, quick).map(|md| println!("{md}"))
        }
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
