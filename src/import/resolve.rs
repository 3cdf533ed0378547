//! Builds a renderable [`Scene`] from a [`SceneDesc`] and the assets it refers to: the one
//! path shared by "open a glTF" and "open a project".

use std::collections::HashMap;

use glam::Vec3;

use super::Asset;
use crate::scene::{Camera, Mesh, MeshSource, Resources, Scene, SceneDesc, SceneError};

/// Why a description could not be resolved against its assets.
#[derive(Debug, thiserror::Error)]
pub enum ResolveError {
    /// An object refers to an asset or primitive that does not exist.
    #[error("object {object:?}: {message}")]
    MissingSource { object: String, message: String },
    /// The resolved scene is inconsistent.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// The environment's sky image could not be loaded.
    #[error(transparent)]
    Sky(#[from] super::sky::SkyError),
}

/// What makes two objects' meshes the same: objects with equal keys share one [`Mesh`] (on the
/// CPU and on the GPU), so a level of 100,000 copies of a few props holds a few meshes.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
enum MeshKey {
    Asset { asset: usize, mesh: usize, primitive: usize, baked: Option<[u32; 16]> },
    Cuboid([u32; 3]),
    Plane(u32),
}

impl MeshKey {
    fn of(source: &MeshSource) -> Self {
        match source {
            MeshSource::Asset { asset, mesh, primitive, baked } => Self::Asset {
                asset: *asset,
                mesh: *mesh,
                primitive: *primitive,
                baked: baked.map(|m| m.to_cols_array().map(f32::to_bits)),
            },
            MeshSource::Cuboid { size, .. } => Self::Cuboid(size.to_array().map(f32::to_bits)),
            MeshSource::Plane { size } => Self::Plane(size.to_bits()),
        }
    }
}

/// Resolves every object's [`MeshSource`] and concatenates the assets' images in order
/// (material [`crate::scene::TextureRef::image`] indices are into that concatenation). Objects
/// with the same source share one mesh.
pub fn resolve(mut desc: SceneDesc, assets: &[Asset]) -> Result<Scene, ResolveError> {
    let mut resources = Resources::default();
    for asset in assets {
        resources.images.extend(asset.images.iter().cloned());
    }
    let mut shared: HashMap<MeshKey, usize> = HashMap::new();
    for object in &mut desc.objects {
        let key = MeshKey::of(&object.source);
        if let Some(&index) = shared.get(&key) {
            object.mesh = index;
            continue;
        }
        let missing = |message: String| ResolveError::MissingSource { object: object.name.clone(), message };
        let mesh = match &object.source {
            MeshSource::Asset { asset, mesh, primitive, baked } => {
                let a = assets.get(*asset).ok_or_else(|| missing(format!("asset {asset} does not exist")))?;
                let mut m = a
                    .primitive(*mesh, *primitive)
                    .cloned()
                    .ok_or_else(|| missing(format!("asset {asset} has no mesh {mesh} primitive {primitive}")))?;
                if let Some(matrix) = baked {
                    if !matrix.is_finite() {
                        return Err(missing("baked matrix is not finite".into()));
                    }
                    m.bake_transform(matrix);
                }
                m
            }
            MeshSource::Cuboid { size, .. } => Mesh::cuboid(&object.name, *size),
            MeshSource::Plane { size } => Mesh::plane(&object.name, *size),
        };
        object.mesh = resources.meshes.len();
        shared.insert(key, object.mesh);
        resources.meshes.push(mesh);
    }
    Ok(Scene::new(desc, resources)?)
}

/// Imports one glTF file as a scene; without a camera in the file the view frames the bounds.
pub fn scene_from_asset(asset: &Asset) -> Result<Scene, ResolveError> {
    let mut scene = resolve(asset.scene.clone(), std::slice::from_ref(asset))?;
    if !asset.has_camera {
        let camera = framing_camera(&scene);
        scene.set_camera(camera);
    }
    Ok(scene)
}

/// A camera looking at the scene bounds from +Z (slightly above), far enough to see them all.
pub fn framing_camera(scene: &Scene) -> Camera {
    let yfov = 0.8f32;
    let Some(b) = scene.bounds() else {
        return Camera::default();
    };
    let r = b.radius().max(0.01);
    let dist = r / (0.5 * yfov).sin();
    let dir = Vec3::new(0.0, 0.25, 1.0).normalize();
    Camera { znear: (dist - r).max(0.01 * r).min(0.1), ..Camera::look_at(b.center() + dir * dist, b.center(), yfov) }
}
