//! The scene model: pure data that every other layer reads.
//!
//! It exists so that the importer, the project file, the renderer, the reference path tracer and
//! the editor all agree on one description of the world, with the conventions of
//! docs/ARCHITECTURE.md, "Conventions" (metres, +Y up, radiometric lights in W/sr, one-sided
//! surfaces). It never imports wgpu or egui.
//!
//! Every mutable access goes through a method that bumps [`Scene::revision`], so caches (GPU
//! buffers, sample points, path-tracer accumulation) can tell when they are stale.

pub mod basis;
mod camera;
mod environment;
mod light;
pub mod limits;
mod material;
mod mesh;
mod object;
pub mod preetham;
mod units;

pub use camera::{Camera, rotation_looking};
pub use environment::{Environment, Sky, SkyImage, equirect_direction, equirect_uv};
pub use light::{Light, LightKind, spot_attenuation};
pub use material::{Material, TextureRef};
pub use mesh::{Aabb, Mesh, MeshError};
pub use object::{MeshSource, Object, ObjectRole, Transform};
pub use units::{LUMENS_PER_WATT, LightUnits};

use serde::{Deserialize, Serialize};

/// The size the analytic sky is baked at for every consumer (texels; 0.7 degrees each).
pub const PREETHAM_SIZE: (u32, u32) = (512, 256);

/// An RGBA8 image decoded from an asset (base colour or normal map).
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Tightly packed RGBA8 texels, row-major from the top-left.
    pub rgba8: Vec<u8>,
}

/// Runtime geometry and images loaded from the scene's assets (not saved in project files; the
/// project file refers to them by [`MeshSource`] and [`TextureRef`]).
#[derive(Clone, Debug, Default)]
pub struct Resources {
    /// Meshes, indexed by [`Object::mesh`].
    pub meshes: Vec<Mesh>,
    /// Images, indexed by [`TextureRef::image`].
    pub images: Vec<Image>,
    /// The decoded [`Sky::Image`] of the environment, if it has one.
    pub sky: Option<std::sync::Arc<SkyImage>>,
}

/// The authored description of a scene: what the project file stores.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneDesc {
    /// Materials, indexed by [`Object::material`].
    pub materials: Vec<Material>,
    /// Objects (static geometry, proxy blocks, clutter).
    pub objects: Vec<Object>,
    /// The units the scene's glTF files give their lights in, which an export writes and the
    /// editor shows first ([`LightUnits`]). The lights below are always radiometric. A project
    /// file without the field was written before the choice existed and meant radiometric.
    #[serde(default = "LightUnits::legacy")]
    pub light_units: LightUnits,
    /// Punctual lights (radiometric: W/sr, or W/m^2 for directional ones).
    pub lights: Vec<Light>,
    /// The sky (radiometric radiance, W/(sr m²)); a file without the field has none, and one
    /// without a sky is saved without it.
    #[serde(default, skip_serializing_if = "Environment::is_default")]
    pub environment: Environment,
    /// The view camera.
    pub camera: Camera,
}

/// A scene ready to render: the authored description plus its loaded resources.
#[derive(Clone, Debug)]
pub struct Scene {
    desc: SceneDesc,
    resources: Resources,
    revision: u64,
    resources_revision: u64,
}

/// A problem that makes a scene unusable (found by [`Scene::validate`]).
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum SceneError {
    /// An object names a mesh that does not exist.
    #[error("object {object:?} refers to mesh {mesh}, but the scene has {count} meshes")]
    MissingMesh { object: String, mesh: usize, count: usize },
    /// An object names a material that does not exist.
    #[error("object {object:?} refers to material {material}, but the scene has {count} materials")]
    MissingMaterial { object: String, material: usize, count: usize },
    /// A material names an image that does not exist.
    #[error("material {material:?} refers to image {image}, but the scene has {count} images")]
    MissingImage { material: String, image: usize, count: usize },
    /// A value is NaN, infinite or out of its range.
    #[error("{what} is invalid: {why}")]
    BadValue { what: String, why: String },
}

/// The source of every scene's revisions: one counter for all scenes, so that a scene built
/// anew (a structural edit, a reloaded asset) never shows a cache the revision of the scene it
/// replaced.
static REVISIONS: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(1);

fn next_revision() -> u64 {
    REVISIONS.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1
}

impl Scene {
    /// Builds a scene and checks that every reference resolves and every number is finite.
    pub fn new(desc: SceneDesc, resources: Resources) -> Result<Self, SceneError> {
        let revision = next_revision();
        let scene = Self { desc, resources, revision, resources_revision: revision };
        scene.validate()?;
        Ok(scene)
    }

    /// The authored description.
    pub fn desc(&self) -> &SceneDesc {
        &self.desc
    }

    /// Mutable access to the description; bumps the revision.
    pub fn desc_mut(&mut self) -> &mut SceneDesc {
        self.revision = next_revision();
        &mut self.desc
    }

    /// Loaded meshes and images.
    pub fn resources(&self) -> &Resources {
        &self.resources
    }

    /// Mutable access to the resources; bumps the revision.
    pub fn resources_mut(&mut self) -> &mut Resources {
        self.revision = next_revision();
        self.resources_revision = self.revision;
        &mut self.resources
    }

    /// A counter that changes on every edit (every mutable access); no two scenes' states share
    /// a value.
    pub fn revision(&self) -> u64 {
        self.revision
    }

    /// A counter that changes whenever meshes or images change (GPU geometry caches key on it).
    pub fn resources_revision(&self) -> u64 {
        self.resources_revision
    }

    /// Objects.
    pub fn objects(&self) -> &[Object] {
        &self.desc.objects
    }

    /// Lights.
    pub fn lights(&self) -> &[Light] {
        &self.desc.lights
    }

    /// Materials.
    pub fn materials(&self) -> &[Material] {
        &self.desc.materials
    }

    /// The environment.
    pub fn environment(&self) -> &Environment {
        &self.desc.environment
    }

    /// The decoded sky image, if the environment is an image and it is loaded.
    pub fn sky_image(&self) -> Option<&SkyImage> {
        self.resources.sky.as_deref()
    }

    /// The texels every consumer reads the sky from (in the sky's own frame): the decoded
    /// image, or the analytic sky baked at [`PREETHAM_SIZE`] for the current sun (computed on
    /// each call: call once per build); `None` for a constant sky or none.
    pub fn sky_texels(&self) -> Option<std::sync::Arc<SkyImage>> {
        match &self.desc.environment.sky {
            Sky::Image(_) => self.resources.sky.clone(),
            Sky::Preetham { turbidity } => {
                let sun = self.desc.environment.to_sky(self.sun_direction());
                let baked = preetham::Preetham::new(sun, *turbidity).image(PREETHAM_SIZE.0, PREETHAM_SIZE.1);
                Some(std::sync::Arc::new(baked))
            }
            _ => None,
        }
    }

    /// The unit direction towards the sun: against the first directional light with light,
    /// else 45 degrees up from +Z.
    pub fn sun_direction(&self) -> glam::Vec3 {
        self.desc
            .lights
            .iter()
            .find(|l| l.kind == LightKind::Directional && l.intensity > 0.0)
            .map_or(glam::Vec3::new(0.0, 1.0, 1.0).normalize(), |l| -l.direction)
    }

    /// Whether any light comes from the sky.
    pub fn has_sky(&self) -> bool {
        match self.desc.environment.sky {
            Sky::Preetham { .. } => self.desc.environment.intensity > 0.0,
            _ => self.desc.environment.emits(self.sky_image()),
        }
    }

    /// The view camera.
    pub fn camera(&self) -> &Camera {
        &self.desc.camera
    }

    /// Sets the view camera; bumps the revision.
    pub fn set_camera(&mut self, camera: Camera) {
        self.desc_mut().camera = camera;
    }

    /// The world-space bounds of every object, or `None` for an empty scene.
    pub fn bounds(&self) -> Option<Aabb> {
        let mut out: Option<Aabb> = None;
        for object in self.desc.objects.iter().filter(|o| o.is_rendered()) {
            let Some(mesh) = self.resources.meshes.get(object.mesh) else {
                continue;
            };
            let Some(local) = mesh.bounds() else { continue };
            let world = local.transformed(&object.transform.matrix());
            out = Some(match out {
                Some(b) => b.union(&world),
                None => world,
            });
        }
        out
    }

    /// Checks references and numbers.
    pub fn validate(&self) -> Result<(), SceneError> {
        let meshes = self.resources.meshes.len();
        let materials = self.desc.materials.len();
        let images = self.resources.images.len();
        for object in &self.desc.objects {
            if object.mesh >= meshes {
                return Err(SceneError::MissingMesh { object: object.name.clone(), mesh: object.mesh, count: meshes });
            }
            if object.material >= materials {
                return Err(SceneError::MissingMaterial {
                    object: object.name.clone(),
                    material: object.material,
                    count: materials,
                });
            }
            object.validate()?;
        }
        for material in &self.desc.materials {
            let textures = [&material.base_color_texture, &material.normal_texture, &material.emissive_texture];
            for tex in textures.into_iter().flatten() {
                if tex.image >= images {
                    return Err(SceneError::MissingImage {
                        material: material.name.clone(),
                        image: tex.image,
                        count: images,
                    });
                }
            }
            material.validate()?;
        }
        for light in &self.desc.lights {
            light.validate()?;
        }
        self.desc.environment.validate()?;
        if let Some(sky) = &self.resources.sky {
            sky.validate()?;
        }
        self.desc.camera.validate()?;
        Ok(())
    }
}

/// Returns an error unless every value is finite.
pub(crate) fn check_finite(what: &str, values: &[f32]) -> Result<(), SceneError> {
    if values.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(SceneError::BadValue { what: what.to_owned(), why: "not a finite number".to_owned() })
    }
}
