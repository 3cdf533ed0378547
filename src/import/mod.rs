//! glTF 2.0 import (`.gltf` and `.glb`) into the scene model.
//!
//! Exists so that every technique sees a glTF file the same way an independent renderer does:
//! node hierarchy transforms, KHR_lights_punctual lights in the specification's candela and lux
//! (or in W/sr and W/m^2 where the file or the user says so: [`LightUnits`]), perspective
//! cameras, one-sided CCW triangles. Files are treated as hostile: every problem becomes an
//! [`ImportError`] naming the file, never a panic (docs/ARCHITECTURE.md, "Conventions").

mod accessor;
mod build;
pub mod extras;
mod guard;
mod images;
mod nodes;
mod primitive;
pub mod sky;
mod uri;

pub use accessor::AccessorError;
pub use uri::UriError;

use std::path::{Path, PathBuf};

use crate::scene::{Image, LightUnits, Material, Mesh, SceneDesc};

/// How to read a file.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ImportOptions {
    /// The units of the file's light intensities where the file does not record them
    /// (`extras.bouncelab.light_units` at the root, which Bounce Lab's own files carry).
    pub light_units: LightUnits,
}

/// Extensions we understand well enough to accept when a file marks them required.
pub const SUPPORTED_REQUIRED_EXTENSIONS: &[&str] = &["KHR_lights_punctual", "KHR_materials_emissive_strength"];

/// Why a glTF file could not be imported. Every variant names the file.
#[derive(Debug, thiserror::Error)]
pub enum ImportError {
    /// The file itself could not be read.
    #[error("{path}: cannot read file: {source}")]
    Io { path: PathBuf, source: std::io::Error },
    /// The JSON or GLB container is malformed or fails glTF validation.
    #[error("{path}: not a valid glTF file: {message}")]
    Parse { path: PathBuf, message: String },
    /// The file requires an extension we do not implement.
    #[error("{path}: requires unsupported extension {extension:?} (supported: {supported})")]
    UnsupportedExtension { path: PathBuf, extension: String, supported: String },
    /// A buffer could not be loaded.
    #[error("{path}: buffer {index}: {source}")]
    Buffer { path: PathBuf, index: usize, source: UriError },
    /// A buffer is shorter than its declared byteLength.
    #[error("{path}: buffer {index} has {actual} bytes but declares {declared}")]
    BufferTooShort { path: PathBuf, index: usize, actual: usize, declared: usize },
    /// A GLB buffer refers to a binary chunk that is absent.
    #[error("{path}: buffer {index} refers to the GLB binary chunk, which is missing")]
    MissingBinaryChunk { path: PathBuf, index: usize },
    /// An image could not be loaded or decoded.
    #[error("{path}: image {index}: {message}")]
    Image { path: PathBuf, index: usize, message: String },
    /// A mesh primitive is unusable.
    #[error("{path}: mesh {mesh} primitive {primitive}: {message}")]
    Primitive { path: PathBuf, mesh: usize, primitive: usize, message: String },
    /// A node, light or camera is unusable.
    #[error("{path}: {what}: {message}")]
    Node { path: PathBuf, what: String, message: String },
    /// The importer hit an internal failure on this file (a bug, reported instead of crashing).
    #[error("{path}: internal importer failure: {message}")]
    Internal { path: PathBuf, message: String },
}

/// Everything one glTF asset provides.
#[derive(Clone, Debug, Default)]
pub struct Asset {
    /// Meshes keyed by (glTF mesh index, primitive index), with the primitive's material index.
    pub primitives: Vec<((usize, usize), Mesh, Option<usize>)>,
    /// Decoded images, in glTF image order.
    pub images: Vec<Image>,
    /// Materials, in glTF material order (image indices local to this asset).
    pub materials: Vec<Material>,
    /// The default scene: objects (material index local; the default material is appended at
    /// `materials.len()` when used), lights, camera.
    pub scene: SceneDesc,
    /// The units the file's lights were read in (`scene.light_units`): the file's record, or
    /// [`ImportOptions::light_units`] where it has none.
    pub light_units: LightUnits,
    /// The units the file records, if it does.
    pub recorded_units: Option<LightUnits>,
    /// The render settings a Bounce Lab export carries (root `extras`).
    pub render: Option<crate::settings::RenderSettings>,
    /// Whether the file had a camera (otherwise `scene.camera` frames the bounds).
    pub has_camera: bool,
    /// Names of the materials that emit light.
    pub emissive: Vec<String>,
    /// The buffer and image files it read besides itself.
    pub files: Vec<PathBuf>,
}

impl Asset {
    /// The mesh of glTF mesh `mesh`, primitive `primitive`.
    pub fn primitive(&self, mesh: usize, primitive: usize) -> Option<&Mesh> {
        self.primitives.iter().find(|(k, _, _)| *k == (mesh, primitive)).map(|(_, m, _)| m)
    }
}

/// Imports a `.gltf` or `.glb` file with the default options (photometric lights unless the
/// file records other units).
pub fn import_gltf(path: &Path) -> Result<Asset, ImportError> {
    import_gltf_with(path, ImportOptions::default())
}

/// Imports a `.gltf` or `.glb` file.
pub fn import_gltf_with(path: &Path, options: ImportOptions) -> Result<Asset, ImportError> {
    let bytes = crate::input_file::read(path, crate::input_file::Kind::Scene)
        .map_err(|source| ImportError::Io { path: path.to_owned(), source })?;
    let base_dir = path.parent().unwrap_or_else(|| Path::new("."));
    import_slice_with(&bytes, base_dir, path, options)
}

/// Imports glTF or GLB bytes with the default options; `base_dir` resolves relative URIs,
/// `path` names the file in errors.
pub fn import_slice(bytes: &[u8], base_dir: &Path, path: &Path) -> Result<Asset, ImportError> {
    import_slice_with(bytes, base_dir, path, ImportOptions::default())
}

/// Imports glTF or GLB bytes.
pub fn import_slice_with(
    bytes: &[u8],
    base_dir: &Path,
    path: &Path,
    options: ImportOptions,
) -> Result<Asset, ImportError> {
    // Defence in depth: our own checks run before the gltf crate's readers, but a panic inside
    // the third-party parser must still become an error rather than take down the editor.
    guard::catch_quietly(|| build::build(bytes, base_dir, path, options))
        .unwrap_or_else(|message| Err(ImportError::Internal { path: path.to_owned(), message }))
}

pub use resolve::{ResolveError, framing_camera, resolve, scene_from_asset};
pub mod cornell;
mod resolve;
pub mod writer;
