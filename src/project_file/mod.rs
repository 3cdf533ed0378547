//! Project files: versioned RON with the scene, its assets, the camera and the render settings.
//!
//! Contracts (docs/ARCHITECTURE.md, "Project files"): `format_version` first; older versions
//! migrate with `From`; unknown fields are errors with line and column; saves are atomic and
//! deterministic; assets are referenced relative to the project file.

use crate::atomic_file as atomic;
mod paths;
mod reload;
pub use paths::relative_to as relative_path;
pub use reload::ReloadReport;

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::import::{self, ImportError, ImportOptions, ResolveError};
use crate::scene::{Scene, SceneDesc, Sky};
use crate::settings::{RenderSettings, SettingsError};

/// The version this build writes. Version 2 added the scene's `light_units`; a version 1 file
/// reads as radiometric, which is what it meant ([`crate::scene::LightUnits::legacy`]).
pub const FORMAT_VERSION: u32 = 2;

/// Why a project could not be loaded or saved. Every variant names the file.
#[derive(Debug, thiserror::Error)]
pub enum ProjectError {
    /// Reading or writing failed.
    #[error("{path}: {source}")]
    Io { path: PathBuf, source: std::io::Error },
    /// The RON text is malformed or has unknown or missing fields.
    #[error("{path}:{line}:{column}: {message}")]
    Parse { path: PathBuf, line: usize, column: usize, message: String },
    /// `format_version` 0: no Bounce Lab ever wrote it (1 is the first).
    #[error("{path}: format_version 0 is not a version (the first is 1)")]
    NoVersion { path: PathBuf },
    /// Written by a newer Bounce Lab.
    #[error("{path}: format_version {found} is newer than this build understands ({FORMAT_VERSION})")]
    TooNew { path: PathBuf, found: u32 },
    /// A glTF opened on its own failed to import (its error names the file).
    #[error(transparent)]
    Import(Box<ImportError>),
    /// A referenced asset failed to import.
    #[error("{project}: asset {index}: {source}")]
    Asset { project: PathBuf, index: usize, source: Box<ImportError> },
    /// The scene does not resolve against its assets.
    #[error("{path}: {source}")]
    Resolve { path: PathBuf, source: ResolveError },
    /// A setting is out of range.
    #[error("{path}: {source}")]
    Settings { path: PathBuf, source: SettingsError },
    /// Serialising failed (a bug).
    #[error("{path}: cannot serialise project: {message}")]
    Serialize { path: PathBuf, message: String },
}

/// The on-disk schema, version 1.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ProjectFileV1 {
    /// Always first: the schema version.
    pub format_version: u32,
    /// glTF assets, relative to the project file, with forward slashes.
    pub assets: Vec<String>,
    /// Objects, materials, lights and camera.
    pub scene: SceneDesc,
    /// GI mode and render settings.
    pub render: RenderSettings,
}

#[derive(Deserialize)]
struct Header {
    format_version: u32,
}

/// A loaded project: the scene plus what it was made from.
#[derive(Clone, Debug)]
pub struct Project {
    /// Absolute (or as given) paths of the glTF assets.
    pub assets: Vec<PathBuf>,
    /// The renderable scene.
    pub scene: Scene,
    /// GI mode and render settings.
    pub render: RenderSettings,
    /// The imported assets, kept so edits (undo, added objects) can rebuild meshes.
    pub imported: Vec<import::Asset>,
}

impl Project {
    /// A project made of a single glTF file with default settings (its lights photometric
    /// unless the file records other units).
    pub fn from_gltf(path: &Path) -> Result<Self, ProjectError> {
        Self::from_gltf_with(path, ImportOptions::default())
    }

    /// A project made of a single glTF file read with `options`, with default settings.
    pub fn from_gltf_with(path: &Path, options: ImportOptions) -> Result<Self, ProjectError> {
        let asset = import::import_gltf_with(path, options).map_err(|e| ProjectError::Import(Box::new(e)))?;
        let mut scene = import::scene_from_asset(&asset)
            .map_err(|source| ProjectError::Resolve { path: path.to_owned(), source })?;
        attach_sky(&mut scene).map_err(|source| ProjectError::Resolve { path: path.to_owned(), source })?;
        // A Bounce Lab export carries the settings of the project it came from.
        let render = asset.render.clone().unwrap_or_default();
        Ok(Self { assets: vec![path.to_owned()], scene, render, imported: vec![asset] })
    }

    /// Opens a `.ron` project, or a `.gltf` / `.glb` scene as a new project.
    pub fn open(path: &Path) -> Result<Self, ProjectError> {
        Self::open_with(path, None)
    }

    /// [`Self::open`], a glTF read with `options` where given; a project reads its assets in
    /// its own units, unless `options` says otherwise.
    pub fn open_with(path: &Path, options: Option<ImportOptions>) -> Result<Self, ProjectError> {
        match path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).as_deref() {
            Some("gltf" | "glb") => Self::from_gltf_with(path, options.unwrap_or_default()),
            _ => {
                let mut project = Self::load(path)?;
                if let Some(o) = options {
                    project.scene.desc_mut().light_units = o.light_units;
                }
                Ok(project)
            }
        }
    }

    /// Loads a project file and the assets it refers to.
    pub fn load(path: &Path) -> Result<Self, ProjectError> {
        let text = crate::input_file::read_text(path, crate::input_file::Kind::Project)
            .map_err(|source| ProjectError::Io { path: path.to_owned(), source })?;
        let mut file = parse(&text, path)?;
        let dir = path.parent().unwrap_or_else(|| Path::new("."));
        let assets: Vec<PathBuf> = file.assets.iter().map(|a| dir.join(a)).collect();
        if let Sky::Image(name) = &mut file.scene.environment.sky {
            *name = dir.join(&*name).to_string_lossy().into_owned();
        }
        Self::from_parts(path, assets, file.scene, file.render)
    }

    /// A project from its parts: `assets` are imported and `scene` resolved against them;
    /// `path` names the file the parts came from in errors (a project or a recovery file).
    pub fn from_parts(
        path: &Path,
        assets: Vec<PathBuf>,
        scene: SceneDesc,
        render: RenderSettings,
    ) -> Result<Self, ProjectError> {
        let options = ImportOptions { light_units: scene.light_units };
        let imported = assets
            .iter()
            .enumerate()
            .map(|(index, a)| {
                import::import_gltf_with(a, options).map_err(|e| ProjectError::Asset {
                    project: path.to_owned(),
                    index,
                    source: Box::new(e),
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        let mut scene = import::resolve(scene, &imported)
            .map_err(|source| ProjectError::Resolve { path: path.to_owned(), source })?;
        attach_sky(&mut scene).map_err(|source| ProjectError::Resolve { path: path.to_owned(), source })?;
        render.validate().map_err(|source| ProjectError::Settings { path: path.to_owned(), source })?;
        Ok(Self { assets, scene, render, imported })
    }

    /// Replaces the scene description (undo, redo, structural edits), rebuilding meshes from the
    /// loaded assets when the objects' mesh sources changed.
    pub fn set_desc(&mut self, desc: SceneDesc) -> Result<(), ResolveError> {
        let same_sources = desc.objects.len() == self.scene.objects().len()
            && desc.objects.iter().zip(self.scene.objects()).all(|(a, b)| a.source == b.source);
        if same_sources {
            let mut desc = desc;
            for (new, old) in desc.objects.iter_mut().zip(self.scene.objects()) {
                new.mesh = old.mesh;
            }
            // A new sky image loads before anything changes: a failure leaves the scene as it was.
            let sky = if desc.environment.sky != self.scene.environment().sky {
                Some(import::sky::load_sky(&desc.environment, Path::new(""))?)
            } else {
                None
            };
            desc_validate(&desc, &self.scene)?;
            *self.scene.desc_mut() = desc;
            if let Some(sky) = sky {
                self.scene.resources_mut().sky = sky;
            }
        } else {
            let mut scene = import::resolve(desc, &self.imported)?;
            attach_sky(&mut scene)?;
            self.scene = scene;
        }
        Ok(())
    }

    /// Reads the lights of the glTF assets that do not record their units again as `units`
    /// (the file's numbers were candela and the user says they were W/sr, or the reverse): each
    /// light of the scene that still has the name and intensity it was imported with takes the
    /// file's number in `units`; lights edited since keep their values. The scene's choice
    /// becomes `units`. Returns how many lights changed.
    pub fn reread_file_lights(&mut self, units: crate::scene::LightUnits) -> usize {
        let mut changed = 0;
        let mut desc = self.scene.desc().clone();
        for asset in self.imported.iter_mut().filter(|a| a.recorded_units.is_none()) {
            for imported in &asset.scene.lights {
                let written = asset.light_units.from_radiometric(imported.intensity);
                let now = units.to_radiometric(written);
                for light in
                    desc.lights.iter_mut().filter(|l| l.name == imported.name && l.intensity == imported.intensity)
                {
                    light.intensity = now;
                    changed += 1;
                }
            }
            for light in &mut asset.scene.lights {
                light.intensity = units.to_radiometric(asset.light_units.from_radiometric(light.intensity));
            }
            asset.light_units = units;
            asset.scene.light_units = units;
        }
        desc.light_units = units;
        *self.scene.desc_mut() = desc;
        changed
    }

    /// Whether a glTF asset of the project gives its lights without recording their units (so
    /// the light units say how its numbers are read).
    pub fn has_unrecorded_lights(&self) -> bool {
        self.imported.iter().any(|a| a.recorded_units.is_none() && !a.scene.lights.is_empty())
    }

    /// Replaces the description and the imported assets together (undoing a live reload):
    /// the scene is resolved against `imported`.
    pub fn set_desc_and_assets(&mut self, desc: SceneDesc, imported: Vec<import::Asset>) -> Result<(), ResolveError> {
        let mut scene = import::resolve(desc, &imported)?;
        attach_sky(&mut scene)?;
        self.imported = imported;
        self.scene = scene;
        Ok(())
    }

    /// Every file the project was read from: its glTF assets and the buffers and images they
    /// name (an output must never replace one of them).
    pub fn files(&self) -> Vec<PathBuf> {
        self.file_paths().map(Path::to_owned).collect()
    }

    /// [`Self::files`] without copying them.
    pub fn file_paths(&self) -> impl Iterator<Item = &Path> + Clone {
        let referenced = self.imported.iter().flat_map(|a| a.files.iter().map(PathBuf::as_path));
        let sky = match &self.scene.environment().sky {
            Sky::Image(name) => Some(Path::new(name.as_str())),
            _ => None,
        };
        self.assets.iter().map(PathBuf::as_path).chain(referenced).chain(sky)
    }

    /// What makes any render of this project other than what the user asked for, as sentences:
    /// no light at all (no punctual light, no sky, no emissive surface).
    pub fn shortfalls(&self) -> Vec<String> {
        let punctual = self.scene.lights().iter().any(|l| l.intensity > 0.0 && l.color.iter().any(|c| *c > 0.0));
        let emissive = self.scene.materials().iter().any(crate::scene::Material::emits);
        if punctual || emissive || self.scene.has_sky() {
            return Vec::new();
        }
        vec!["the scene has no light (no light with a positive intensity, no sky, no emissive surface): every mode renders it black".to_owned()]
    }

    /// The RON text this project saves as, with asset paths relative to `project_path`'s folder.
    pub fn to_ron(&self, project_path: &Path) -> Result<String, ProjectError> {
        let dir = project_path.parent().unwrap_or_else(|| Path::new("."));
        let mut scene = self.scene.desc().clone();
        if let Sky::Image(name) = &mut scene.environment.sky {
            *name = paths::relative_to(Path::new(name.as_str()), dir);
        }
        let file = ProjectFileV1 {
            format_version: FORMAT_VERSION,
            assets: self.assets.iter().map(|a| paths::relative_to(a, dir)).collect(),
            scene,
            render: self.render.clone(),
        };
        let config = ron::ser::PrettyConfig::new().indentor("  ").struct_names(false).separate_tuple_members(false);
        let mut text = ron::ser::to_string_pretty(&file, config)
            .map_err(|e| ProjectError::Serialize { path: project_path.to_owned(), message: e.to_string() })?;
        text.push('\n');
        Ok(text)
    }

    /// Saves atomically to `path` (temp file, fsync, rename): the previous file survives any
    /// failure.
    pub fn save(&self, path: &Path) -> Result<(), ProjectError> {
        self.render.validate().map_err(|source| ProjectError::Settings { path: path.to_owned(), source })?;
        let text = self.to_ron(path)?;
        atomic::write(path, text.as_bytes()).map_err(|source| ProjectError::Io { path: path.to_owned(), source })
    }
}

/// Parses project text of any known version into the current schema.
pub fn parse(text: &str, path: &Path) -> Result<ProjectFileV1, ProjectError> {
    // Editors on Windows save UTF-8 with a byte-order mark; RON would call it a syntax error.
    let text = match text.strip_prefix('\u{feff}') {
        Some(rest) => {
            log::warn!("{}: ignoring the UTF-8 byte-order mark", path.display());
            rest
        }
        None => text,
    };
    let spanned = |e: ron::error::SpannedError| ProjectError::Parse {
        path: path.to_owned(),
        line: e.span.start.line,
        column: e.span.start.col,
        message: e.code.to_string(),
    };
    let header: Header = ron::from_str(text).map_err(spanned)?;
    match header.format_version {
        v if v > FORMAT_VERSION => Err(ProjectError::TooNew { path: path.to_owned(), found: v }),
        0 => Err(ProjectError::NoVersion { path: path.to_owned() }),
        // Version 2 added `scene.light_units`, which a version 1 file lacks and serde fills
        // in as radiometric (`LightUnits::legacy`); the schema is otherwise the same.
        _ => ron::from_str::<ProjectFileV1>(text).map_err(spanned),
    }
}

/// The default project shipped in `projects/` (the generated Cornell box).
pub fn default_project_path() -> PathBuf {
    let local = PathBuf::from("projects/default.ron");
    if local.exists() { local } else { Path::new(env!("CARGO_MANIFEST_DIR")).join("projects/default.ron") }
}

/// Whether `path` is the shipped default project (compared canonically): the editor opens it
/// read-only-safe, so Save asks for a new path instead of writing into the install.
pub fn is_default_project(path: &Path) -> bool {
    match (std::fs::canonicalize(path), std::fs::canonicalize(default_project_path())) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    }
}

/// Loads (or drops) the sky image `scene`'s environment names (its path as the project holds it:
/// joined to the project's folder on load).
pub fn attach_sky(scene: &mut Scene) -> Result<(), ResolveError> {
    let sky = import::sky::load_sky(scene.environment(), Path::new(""))?;
    if sky != scene.resources().sky {
        scene.resources_mut().sky = sky;
    }
    Ok(())
}

/// Validates `desc` against `scene`'s loaded resources without replacing anything.
fn desc_validate(desc: &SceneDesc, scene: &Scene) -> Result<(), ResolveError> {
    Scene::new(desc.clone(), scene.resources().clone())?;
    Ok(())
}
