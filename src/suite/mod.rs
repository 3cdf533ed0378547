//! The scene suite that keeps every technique honest beyond the Cornell box: level-like scenes
//! generated from code (`levels`), the Cornell box with glossy and normal-mapped variants, and
//! a cached path-traced reference of each (`assets/suite/references/`), keyed by a hash of the
//! scene file, this module's version and the tracer's, so a stale reference is found, never
//! trusted. `bouncelab suite --references` regenerates them; `bouncelab bench --quality`
//! renders every mode on every scene against them and writes `docs/QUALITY.md`.
//!
//! Pure CPU code (no wgpu): the GPU renders happen in the CLI and the tests.

pub mod levels;
pub mod lit_levels;
pub mod shapes;

use std::path::{Path, PathBuf};

use crate::image_io::HdrImage;
use crate::import::writer::GltfWriter;
use crate::precompute::pathtracer::PathTracer;
use crate::project_file::Project;
use crate::scene::{Image, LightUnits, Material, MeshSource, Object, ObjectRole, TextureRef, Transform};
use crate::settings::ReferenceSettings;

/// Bump when a scene's construction in code changes (the references then read as stale).
pub const SUITE_VERSION: u32 = 1;
/// The references' size in pixels (tests compare at half of it, box-filtered).
pub const REFERENCE_SIZE: (u32, u32) = (128, 72);
/// The references' samples per pixel (scenes lit mostly indirectly in view get more, see
/// [`SuiteScene::spp`]).
pub const REFERENCE_SPP: u32 = 2048;

/// Why a suite scene or reference cannot be used.
#[derive(Debug, thiserror::Error)]
pub enum SuiteError {
    /// No scene of that name.
    #[error("unknown suite scene {0:?}; the suite has: {1}")]
    Unknown(String, String),
    /// The scene's file could not be loaded.
    #[error("suite scene {name:?}: {source}")]
    Load { name: String, source: crate::project_file::ProjectError },
    /// A file could not be read or written.
    #[error("{path}: {source}")]
    Io { path: PathBuf, source: std::io::Error },
    /// The cached reference is missing or was made from another scene or tracer.
    #[error("the reference of {name:?} ({path}) is {why}; regenerate it with `bouncelab suite --references`")]
    Stale { name: String, path: PathBuf, why: &'static str },
    /// The reference image could not be read or written.
    #[error(transparent)]
    Image(#[from] crate::image_io::ImageIoError),
}

/// How a scene is made.
#[derive(Clone, Copy)]
enum Source {
    /// A generated glTF level.
    Level(fn() -> GltfWriter),
    /// The shipped Cornell box with an edit applied after import.
    Cornell(fn(&mut Project)),
}

/// One scene of the suite.
#[derive(Clone, Copy)]
pub struct SuiteScene {
    /// File stem and name in tables.
    pub name: &'static str,
    /// What it tests.
    pub description: &'static str,
    source: Source,
}

fn unchanged(_: &mut Project) {}

/// Every scene, in table order.
pub const SCENES: &[SuiteScene] = &[
    SuiteScene {
        name: "cornell",
        description: "2 m Cornell box, point light (planes, no slabs)",
        source: Source::Cornell(unchanged),
    },
    SuiteScene {
        name: "rooms",
        description: "three 5x3x4 m rooms, 0.2 m slabs, offset doorways, spot in the first; seen from the unlit third",
        source: Source::Level(levels::three_rooms),
    },
    SuiteScene {
        name: "window",
        description: "6x3x5 m room, sun through a window, a lamp and a spot",
        source: Source::Level(levels::window_room),
    },
    SuiteScene {
        name: "clutter",
        description: "8x3.5x6 m room with 30 boxes and cylinders, a spot",
        source: Source::Level(levels::cluttered_room),
    },
    SuiteScene {
        name: "hall",
        description: "60x12x20 m hall, 16 pillars, three spots under the roof",
        source: Source::Level(levels::hall),
    },
    SuiteScene {
        name: "diorama",
        description: "20 cm open box with 5 mm walls and a point light",
        source: Source::Level(levels::diorama),
    },
    SuiteScene {
        name: "glossy",
        description: "Cornell box with a glossy floor (specular 0.5, roughness 0.3)",
        source: Source::Cornell(glossy_floor),
    },
    SuiteScene {
        name: "bumpy",
        description: "Cornell box with a normal-mapped floor (grooves at +-35 degrees)",
        source: Source::Cornell(bumpy_floor),
    },
    SuiteScene {
        name: "skylight",
        description: "the 6x3x5 m window room lit only by a constant blue sky through its window",
        source: Source::Level(lit_levels::skylight),
    },
    SuiteScene {
        name: "sunsky",
        description: "the window room under the sun and an image sky (128x64 EXR)",
        source: Source::Level(lit_levels::sunsky),
    },
    SuiteScene {
        name: "panels",
        description: "closed 5x3x4 m room lit only by two emissive ceiling panels and a wall screen",
        source: Source::Level(lit_levels::panels),
    },
    SuiteScene {
        name: "courtyard",
        description: "12x12 m courtyard open to the sky, 4 m walls, low sun and a constant sky",
        source: Source::Level(lit_levels::courtyard),
    },
];

fn glossy_floor(project: &mut Project) {
    let desc = project.scene.desc_mut();
    let floor = desc.objects.iter().find(|o| o.name == "floor").map(|o| o.material);
    let mut glossy = floor.and_then(|m| desc.materials.get(m).cloned()).unwrap_or_default();
    glossy.name = "glossy floor".into();
    glossy.specular = [0.5; 3];
    glossy.roughness = 0.3;
    desc.materials.push(glossy);
    let m = desc.materials.len() - 1;
    if let Some(o) = desc.objects.iter_mut().find(|o| o.name == "floor") {
        o.material = m;
    }
}

/// A 2 m floor overlay whose normal map has grooves two texels wide (normals tilted +-35
/// degrees about z), 64 texels across.
fn bumpy_floor(project: &mut Project) {
    let (w, h) = (64u32, 64u32);
    let (s, c) = (35f32.to_radians().sin(), 35f32.to_radians().cos());
    let enc = |v: f32| ((v * 0.5 + 0.5) * 255.0).round() as u8;
    let rgba8 = (0..w * h)
        .flat_map(|i| {
            let x = if (i % w / 2) % 2 == 0 { s } else { -s };
            [enc(x), 128, enc(c), 255]
        })
        .collect();
    // The normal map arrives as an extra asset holding only that image.
    let Some(mut extra) = project.imported.first().cloned() else { return };
    extra.primitives.clear();
    extra.materials.clear();
    extra.images = vec![Image { width: w, height: h, rgba8 }];
    let image: usize = project.imported.iter().map(|a| a.images.len()).sum();
    project.imported.push(extra);
    let mut desc = project.scene.desc().clone();
    let mut material = Material::diffuse("bumpy", [0.7; 3]);
    material.normal_texture = Some(TextureRef { image, tex_coord: 0 });
    desc.materials.push(material);
    desc.objects.push(Object {
        name: "bumpy floor".into(),
        source: MeshSource::Plane { size: 1.99 },
        mesh: 0,
        material: desc.materials.len() - 1,
        transform: Transform { translation: glam::Vec3::new(0.0, 0.002, 0.0), ..Transform::default() },
        sampling_weight: 1.0,
        role: ObjectRole::Static,
        visible: true,
    });
    if let Ok(scene) = crate::import::resolve(desc, &project.imported) {
        project.scene = scene;
    }
}

/// The scene named `name`.
pub fn scene(name: &str) -> Result<&'static SuiteScene, SuiteError> {
    SCENES.iter().find(|s| s.name == name).ok_or_else(|| {
        SuiteError::Unknown(name.to_owned(), SCENES.iter().map(|s| s.name).collect::<Vec<_>>().join(", "))
    })
}

impl SuiteScene {
    /// The glTF file the scene is imported from, under the repository `root`.
    pub fn gltf_path(&self, root: &Path) -> PathBuf {
        match self.source {
            Source::Level(_) => root.join("assets/suite").join(format!("{}.gltf", self.name)),
            Source::Cornell(_) => root.join("assets/cornell_box.gltf"),
        }
    }

    /// The glTF text of a generated level (`None` for the Cornell variants, which use the
    /// shipped box).
    pub fn gltf_text(&self) -> Option<String> {
        match self.source {
            Source::Level(build) => Some(build().to_string_pretty()),
            Source::Cornell(_) => None,
        }
    }

    /// The scene as a project (imported like a bare glTF, then edited in code).
    pub fn load(&self, root: &Path) -> Result<Project, SuiteError> {
        let path = self.gltf_path(root);
        let mut project =
            Project::from_gltf(&path).map_err(|source| SuiteError::Load { name: self.name.to_owned(), source })?;
        if let Source::Cornell(edit) = self.source {
            edit(&mut project);
        }
        Ok(project)
    }

    /// Samples per pixel of this scene's reference: the rooms are seen from the unlit room,
    /// where every path needs several bounces, so they get 16x more; the room lit by a
    /// constant sky through its window (which only BRDF sampling finds) 4x more.
    pub fn spp(&self) -> u32 {
        match self.name {
            "rooms" => 16 * REFERENCE_SPP,
            "skylight" => 4 * REFERENCE_SPP,
            _ => REFERENCE_SPP,
        }
    }

    /// Where the cached reference lives.
    pub fn reference_path(&self, root: &Path) -> PathBuf {
        root.join("assets/suite/references").join(format!("{}.exr", self.name))
    }

    fn key_path(&self, root: &Path) -> PathBuf {
        root.join("assets/suite/references").join(format!("{}.key", self.name))
    }

    /// What the reference depends on: the scene file's bytes (less its root `extras`, the
    /// record of its light units, which enters by name unless it is the radiometric units every
    /// suite file was read in before files recorded them), the suite and tracer versions, the
    /// size and the sample count (FNV-1a, stable across builds).
    pub fn reference_key(&self, root: &Path) -> Result<String, SuiteError> {
        let path = self.gltf_path(root);
        let bytes = std::fs::read(&path).map_err(|source| SuiteError::Io { path: path.clone(), source })?;
        let (bytes, units) = without_unit_record(bytes);
        let units = units.filter(|u| *u != LightUnits::Radiometric).map(|u| format!("|{u}")).unwrap_or_default();
        let mut h = 0xcbf2_9ce4_8422_2325u64;
        let extra = format!(
            "{}|{}|{}|{:?}|{}{units}",
            self.name,
            SUITE_VERSION,
            crate::precompute::pathtracer::TRACER_VERSION,
            REFERENCE_SIZE,
            self.spp()
        );
        // The sky travels in the root extras the unit record's cut removes, and an image sky in
        // its own file: both enter by their bytes.
        let sky = self.sky_bytes(root)?;
        for b in bytes.iter().chain(extra.as_bytes()).chain(&sky) {
            h = (h ^ u64::from(*b)).wrapping_mul(0x0100_0000_01b3);
        }
        Ok(format!("{h:016x}"))
    }

    /// The environment of a generated level as JSON text, and its sky image's bytes (empty for
    /// the levels without a sky, whose keys stay as they were).
    fn sky_bytes(&self, root: &Path) -> Result<Vec<u8>, SuiteError> {
        let Source::Level(build) = self.source else { return Ok(Vec::new()) };
        let doc = build().to_json();
        let Some(env) = doc.pointer("/extras/bouncelab/environment") else { return Ok(Vec::new()) };
        let mut out = env.to_string().into_bytes();
        if let Some(name) = env.pointer("/sky/Image").and_then(|n| n.as_str()) {
            let path = root.join("assets/suite").join(name);
            out.extend(std::fs::read(&path).map_err(|source| SuiteError::Io { path, source })?);
        }
        Ok(out)
    }

    /// The cached reference, if it is current.
    pub fn reference(&self, root: &Path) -> Result<HdrImage, SuiteError> {
        let path = self.reference_path(root);
        let stale = |why| SuiteError::Stale { name: self.name.to_owned(), path: path.clone(), why };
        let key = std::fs::read_to_string(self.key_path(root)).map_err(|_| stale("missing"))?;
        if key.trim() != self.reference_key(root)? {
            return Err(stale("stale (the scene, the suite or the tracer changed)"));
        }
        let img = crate::image_io::read_linear(&path)?;
        if (img.width, img.height) != REFERENCE_SIZE {
            return Err(stale("of the wrong size"));
        }
        Ok(img)
    }

    /// Path-traces the reference and caches it (atomically: image first, then its key).
    pub fn render_reference(&self, root: &Path) -> Result<HdrImage, SuiteError> {
        let project = self.load(root)?;
        let settings = ReferenceSettings { spp: self.spp(), ..ReferenceSettings::default() };
        let mut tracer = PathTracer::new(&project.scene, REFERENCE_SIZE, settings);
        tracer.render(self.spp(), &std::sync::atomic::AtomicBool::new(false), |_| {});
        let img = HdrImage { width: REFERENCE_SIZE.0, height: REFERENCE_SIZE.1, pixels: tracer.image() };
        let dir = root.join("assets/suite/references");
        std::fs::create_dir_all(&dir).map_err(|source| SuiteError::Io { path: dir.clone(), source })?;
        crate::image_io::write_exr(&self.reference_path(root), &img)?;
        let key_path = self.key_path(root);
        crate::atomic_file::write(&key_path, format!("{}\n", self.reference_key(root)?).as_bytes())
            .map_err(|source| SuiteError::Io { path: key_path, source })?;
        Ok(img)
    }
}

/// Writes every generated level's glTF under `root` (`assets/suite/`), and the image sky.
pub fn write_levels(root: &Path) -> Result<Vec<PathBuf>, SuiteError> {
    let dir = root.join("assets/suite");
    std::fs::create_dir_all(&dir).map_err(|source| SuiteError::Io { path: dir.clone(), source })?;
    let sky = lit_levels::sky_image();
    let pixels = sky.texels.iter().map(|t| [t[0], t[1], t[2], 1.0]).collect();
    let sky_path = dir.join(lit_levels::SKY_IMAGE);
    crate::image_io::write_exr(&sky_path, &HdrImage { width: sky.width, height: sky.height, pixels })?;
    let mut written = vec![sky_path];
    for s in SCENES {
        if let Some(text) = s.gltf_text() {
            let path = s.gltf_path(root);
            crate::atomic_file::write(&path, text.as_bytes())
                .map_err(|source| SuiteError::Io { path: path.clone(), source })?;
            written.push(path);
        }
    }
    Ok(written)
}

/// Box-filters `img` down by `k` per axis (the tests compare at half the reference size).
pub fn downsample(img: &HdrImage, k: u32) -> HdrImage {
    let pixels = crate::image_io::box_downsample(&img.pixels, (img.width, img.height), k);
    HdrImage { width: img.width / k, height: img.height / k, pixels }
}

/// A glTF text's bytes without its root `extras` member as [`crate::import::writer::GltfWriter`]
/// prints it (the lines from `  "extras": {` to `  },`, cut as text: parsing and printing the
/// JSON again would move the last digit of some floats), and the light units that record names.
/// Any other text is returned whole.
fn without_unit_record(bytes: Vec<u8>) -> (Vec<u8>, Option<LightUnits>) {
    const OPEN: &str = "\n  \"extras\": {\n";
    const CLOSE: &str = "\n  },\n";
    let Ok(text) = std::str::from_utf8(&bytes) else { return (bytes, None) };
    let Some(start) = text.find(OPEN).map(|i| i + 1) else { return (bytes, None) };
    let Some(end) = text[start..].find(CLOSE).map(|i| start + i + CLOSE.len()) else { return (bytes, None) };
    let member = format!("{{{}}}", &text[start..end - 2]);
    let units = serde_json::from_str::<serde_json::Value>(&member)
        .ok()
        .and_then(|v| v.pointer("/extras/bouncelab/light_units").and_then(|u| u.as_str()).and_then(LightUnits::parse));
    let cut = format!("{}{}", &text[..start], &text[end..]);
    (cut.into_bytes(), units)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The suite's levels key their references as they did before files recorded their units:
    /// cutting the radiometric record gives back the bytes of the file without it; a record of
    /// other units changes the key.
    #[test]
    fn a_radiometric_unit_record_leaves_the_reference_key_as_it_was() {
        let mut w = crate::import::cornell::cornell_box();
        let with = w.to_string_pretty();
        let mut doc = w.to_json();
        doc.as_object_mut().expect("object").remove("extras");
        let mut without = serde_json::to_string_pretty(&doc).expect("json");
        without.push('\n');
        let (cut, units) = without_unit_record(with.clone().into_bytes());
        assert_eq!(units, Some(LightUnits::Radiometric));
        assert!(cut == without.as_bytes(), "the record's lines are cut and nothing else");
        w.set_light_units(LightUnits::Photometric);
        assert_eq!(without_unit_record(w.to_string_pretty().into_bytes()).1, Some(LightUnits::Photometric));
        assert_eq!(without_unit_record(b"{}".to_vec()), (b"{}".to_vec(), None));
    }
}
