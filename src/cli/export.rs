//! `bouncelab export`: a project's scene with its authored lighting as glTF ([`crate::export`]).

use std::path::{Path, PathBuf};

use crate::output_path;

/// Arguments of `bouncelab export`.
#[derive(clap::Args, Debug)]
pub struct ExportArgs {
    /// The project (.ron) or scene (.gltf/.glb) to export.
    pub input: PathBuf,
    /// The file to write: `.gltf` (one file, embedded buffer) or `.glb` (binary). Never one of
    /// the inputs.
    #[arg(long)]
    pub out: PathBuf,
    /// Units the lights are written in (default: the project's own choice, photometric for a
    /// glTF opened without a record of its units); a glTF input is read in them too.
    #[command(flatten)]
    pub units: super::SceneArgs,
}

/// Exports and returns a one-line summary.
pub fn run(args: &ExportArgs) -> anyhow::Result<String> {
    output_path::check(&args.out, output_path::GLTF, &[&args.input])?;
    let project = args.units.open(&args.input)?;
    let inputs = project.files();
    output_path::check(&args.out, output_path::GLTF, &inputs.iter().map(PathBuf::as_path).collect::<Vec<&Path>>())?;
    let summary = crate::export::export(&project, &args.out)?;
    Ok(format!("{}: {summary}", args.out.display()))
}
