//! Command-line entry points (docs/ARCHITECTURE.md, "Command line"): `render`, `bench` (and its quality
//! matrix), the scene suite and asset generation.
//! The binary's `main.rs` only parses arguments and calls these.

pub mod bench;
pub mod bench_drt;
pub mod bench_mrt;
pub mod bench_rcs;
pub mod bench_sshgi;
pub mod budget;
pub mod compare;
pub mod export;
pub mod generate;
pub mod mrt;
pub mod probe;
pub mod probe_ism;
pub mod probe_mrt;
pub mod profile;
pub mod progress;
pub mod quality;
pub mod render;
pub mod report;
pub mod sheet;
pub mod unseen;

pub use report::error_report;

use crate::import::ImportOptions;
use crate::scene::LightUnits;

/// `--light-units`, on every command that opens a glTF file.
#[derive(Clone, Copy, Debug, Default, clap::Args)]
pub struct LightUnitsArg {
    /// The units of a glTF file's light intensities where the file does not record them:
    /// `photometric` (the glTF specification's candela and lux, as Blender, Godot and Bevy
    /// write and read them; the default) or `radiometric` (W/sr and W/m²). A project file
    /// carries its own choice, which this replaces.
    #[arg(long = "light-units", value_parser = parse_light_units)]
    pub light_units: Option<LightUnits>,
}

impl LightUnitsArg {
    /// The import options the flag asks for, if it was given.
    pub fn options(&self) -> Option<ImportOptions> {
        self.light_units.map(|light_units| ImportOptions { light_units })
    }
}

fn parse_light_units(text: &str) -> Result<LightUnits, String> {
    LightUnits::parse(text).ok_or_else(|| format!("unknown light units {text:?}: photometric or radiometric"))
}
