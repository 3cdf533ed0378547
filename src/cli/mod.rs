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
use crate::project_file::Project;
use crate::scene::{LightUnits, Sky};

/// How to read the scene, on every command that opens one: `--light-units` for a glTF file's
/// lights and emission, and the sky (glTF has none) with `--sky`, `--sky-intensity` and
/// `--sky-rotation`, which replace a project's own.
#[derive(Clone, Debug, Default, clap::Args)]
pub struct SceneArgs {
    /// The units of a glTF file's light intensities and emission where the file does not record
    /// them: `photometric` (the glTF specification's candela and lux, and cd/m² for emission, as
    /// Blender, Godot and Bevy write and read them; the default) or `radiometric` (W/sr, W/m²
    /// and W/(sr m²)). A project file carries its own choice, which this replaces.
    #[arg(long = "light-units", value_parser = parse_light_units)]
    pub light_units: Option<LightUnits>,
    /// The sky: `R,G,B` (a constant sky of that radiance in the scene's light units: W/(sr m²)
    /// when radiometric, cd/m² when photometric), `FILE.hdr` or `FILE.exr` (an equirectangular
    /// image, its texels radiance in the same units), `preetham` or `preetham:T` (Preetham et
    /// al.'s clear sky of turbidity T, default 3, in physical units, driven by the scene's sun),
    /// or `none`.
    #[arg(long, value_parser = parse_sky)]
    pub sky: Option<Sky>,
    /// A scale on the sky's radiance (default 1).
    #[arg(long)]
    pub sky_intensity: Option<f32>,
    /// The sky's rotation about +Y in degrees.
    #[arg(long, allow_negative_numbers = true)]
    pub sky_rotation: Option<f32>,
}

impl SceneArgs {
    /// The import options the flag asks for, if it was given.
    pub fn options(&self) -> Option<ImportOptions> {
        self.light_units.map(|light_units| ImportOptions { light_units })
    }

    /// Opens a project or glTF file as these flags say.
    pub fn open(&self, path: &std::path::Path) -> anyhow::Result<Project> {
        let mut project = Project::open_with(path, self.options())?;
        self.apply_sky(&mut project)?;
        Ok(project)
    }

    /// Gives `project` the sky these flags ask for (a constant sky's colour read in the scene's
    /// light units) and loads its image.
    pub fn apply_sky(&self, project: &mut Project) -> anyhow::Result<()> {
        if self.sky.is_none() && self.sky_intensity.is_none() && self.sky_rotation.is_none() {
            return Ok(());
        }
        let mut desc = project.scene.desc().clone();
        let units = desc.light_units;
        let env = &mut desc.environment;
        if let Some(sky) = &self.sky {
            env.sky = match sky {
                Sky::Constant(c) => Sky::Constant(c.map(|v| units.to_radiometric(v))),
                other => other.clone(),
            };
        }
        // The flag's intensity is a plain scale. An image's texels are read in the scene's light
        // units, so its conversion rides on the intensity; a constant colour was converted above,
        // and the analytic sky is physical.
        let scale = self.sky_intensity.or(self.sky.as_ref().map(|_| 1.0));
        if let Some(i) = scale {
            env.intensity = if matches!(env.sky, Sky::Image(_)) { units.to_radiometric(i) } else { i };
        }
        if let Some(r) = self.sky_rotation {
            env.rotation_degrees = r;
        }
        project.set_desc(desc)?;
        Ok(())
    }
}

fn parse_sky(text: &str) -> Result<Sky, String> {
    if text == "none" {
        return Ok(Sky::None);
    }
    if let Some(rest) = text.strip_prefix("preetham") {
        let turbidity = match rest.strip_prefix(':') {
            Some(t) => t.parse::<f32>().map_err(|_| format!("--sky {text:?}: the turbidity is a number"))?,
            None if rest.is_empty() => 3.0,
            None => return Err(format!("--sky {text:?}: expected preetham or preetham:T")),
        };
        let (lo, hi) = crate::scene::preetham::TURBIDITY_RANGE;
        if !(lo..=hi).contains(&turbidity) {
            return Err(format!("--sky {text:?}: turbidity {turbidity} is outside {lo}..={hi}"));
        }
        return Ok(Sky::Preetham { turbidity });
    }
    let parts: Vec<&str> = text.split(',').collect();
    if parts.len() == 3 {
        let rgb: Result<Vec<f32>, _> = parts.iter().map(|p| p.trim().parse::<f32>()).collect();
        return match rgb {
            Ok(v) if v.iter().all(|c| c.is_finite() && *c >= 0.0) => Ok(Sky::Constant([v[0], v[1], v[2]])),
            _ => Err(format!("--sky {text:?}: a colour is three numbers >= 0, R,G,B")),
        };
    }
    let lower = text.to_ascii_lowercase();
    if lower.ends_with(".hdr") || lower.ends_with(".exr") {
        return Ok(Sky::Image(text.to_owned()));
    }
    Err(format!("--sky {text:?}: expected R,G,B, an .hdr or .exr file, preetham[:T], or none"))
}

fn parse_light_units(text: &str) -> Result<LightUnits, String> {
    LightUnits::parse(text).ok_or_else(|| format!("unknown light units {text:?}: photometric or radiometric"))
}
