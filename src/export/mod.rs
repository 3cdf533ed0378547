//! Export of a project's scene as glTF 2.0 (`.gltf` with an embedded buffer, or `.glb`), so
//! the lighting authored in Bounce Lab goes back to the engine or DCC the level came from: the
//! lights as KHR_lights_punctual in the scene's light units (with range and cone angles), the
//! camera, the materials with their textures (PNG), every object's mesh under a node of its
//! name, and Bounce Lab's own data in `extras` (sampling weights, roles, proxy blocks and their
//! openings, clutter marks, the render settings; [`crate::import::extras`]), so that importing
//! the export gives the same project. Proxy blocks are nodes without a mesh: other tools would
//! draw them as solid boxes over the level. The file is written atomically.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use glam::{Quat, Vec3};
use serde_json::{Value, json};

use crate::import::extras::{self, Generated, LightExtras, MaterialExtras, NodeExtras, RootExtras};
use crate::import::writer::{GltfWriter, MeshAttributes, NodeDesc};
use crate::project_file::Project;
use crate::scene::{Image, Light, LightKind, LightUnits, Material, MeshSource, Object, ObjectRole, Scene};

/// Why an export failed. Every variant names the file.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    /// The output is neither `.gltf` nor `.glb`.
    #[error("{path}: exports are .gltf or .glb files")]
    Extension { path: PathBuf },
    /// An image could not be encoded.
    #[error("{path}: image {index}: {message}")]
    Image { path: PathBuf, index: usize, message: String },
    /// Writing failed (the previous file, if any, is untouched).
    #[error("{path}: {source}")]
    Io { path: PathBuf, source: std::io::Error },
}

/// What an export wrote.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ExportSummary {
    pub objects: usize,
    pub proxy_blocks: usize,
    pub lights: usize,
    pub materials: usize,
    pub images: usize,
    pub bytes: usize,
    pub light_units: LightUnits,
}

impl std::fmt::Display for ExportSummary {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} objects ({} proxy blocks), {} lights in {} units, {} materials, {} images, {} bytes",
            self.objects, self.proxy_blocks, self.lights, self.light_units, self.materials, self.images, self.bytes
        )
    }
}

/// Writes `project`'s scene to `path` (`.gltf` or `.glb`) in the scene's light units.
pub fn export(project: &Project, path: &Path) -> Result<ExportSummary, ExportError> {
    let glb = match path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).as_deref() {
        Some("glb") => true,
        Some("gltf") => false,
        _ => return Err(ExportError::Extension { path: path.to_owned() }),
    };
    let (writer, summary) = document(project, path)?;
    let bytes = if glb { writer.to_glb() } else { writer.to_string_pretty().into_bytes() };
    crate::atomic_file::write(path, &bytes).map_err(|source| ExportError::Io { path: path.to_owned(), source })?;
    Ok(ExportSummary { bytes: bytes.len(), ..summary })
}

/// The glTF document of `project` (`path` names the file in errors).
pub fn document(project: &Project, path: &Path) -> Result<(GltfWriter, ExportSummary), ExportError> {
    let scene = &project.scene;
    let units = scene.desc().light_units;
    let mut w = GltfWriter::default();
    w.set_light_units(units);
    let environment = exported_environment(scene.environment(), path);
    w.set_extras(extras::wrap(&RootExtras { light_units: None, render: Some(project.render.clone()), environment }));
    let textures = images(&mut w, &scene.resources().images, path)?;
    for m in scene.materials() {
        w.material_json(material(m, &textures, units));
    }
    let mut meshes = HashMap::new();
    let mut proxy_blocks = 0;
    for object in scene.objects() {
        proxy_blocks += usize::from(object.role == ObjectRole::ProxyBlock);
        object_node(&mut w, scene, object, &mut meshes);
    }
    for light in scene.lights() {
        light_node(&mut w, light, units);
    }
    let camera = scene.camera();
    let c = w.camera(camera.yfov, camera.znear, camera.zfar);
    w.node(
        NodeDesc {
            name: "camera".into(),
            translation: Some(camera.position),
            rotation: Some(camera.rotation.normalize()),
            camera: Some(c),
            ..NodeDesc::default()
        },
        true,
    );
    let summary = ExportSummary {
        objects: scene.objects().len(),
        proxy_blocks,
        lights: scene.lights().len(),
        materials: scene.materials().len(),
        images: scene.resources().images.len(),
        bytes: 0,
        light_units: units,
    };
    Ok((w, summary))
}

/// Every image as a PNG texture, in order (texture i samples image i).
fn images(w: &mut GltfWriter, images: &[Image], path: &Path) -> Result<Vec<usize>, ExportError> {
    images
        .iter()
        .enumerate()
        .map(|(index, img)| {
            let err = |message: String| ExportError::Image { path: path.to_owned(), index, message };
            let rgba = image::RgbaImage::from_raw(img.width, img.height, img.rgba8.clone())
                .ok_or_else(|| err(format!("{} bytes for {}x{} texels", img.rgba8.len(), img.width, img.height)))?;
            let mut png = std::io::Cursor::new(Vec::new());
            rgba.write_to(&mut png, image::ImageFormat::Png).map_err(|e| err(e.to_string()))?;
            Ok(w.png_texture(png.get_ref()))
        })
        .collect()
}

/// The environment as the root `extras` carry it (none without a sky; an image's path relative
/// to the exported file's folder).
fn exported_environment(env: &crate::scene::Environment, path: &Path) -> Option<crate::scene::Environment> {
    let mut env = env.clone();
    match &mut env.sky {
        crate::scene::Sky::None => return None,
        crate::scene::Sky::Image(name) => {
            let dir = path.parent().unwrap_or_else(|| Path::new("."));
            *name = crate::project_file::relative_path(Path::new(name.as_str()), dir);
        }
        crate::scene::Sky::Constant(_) | crate::scene::Sky::Preetham { .. } => {}
    }
    Some(env)
}

/// A material as glTF's metallic-roughness (metallic 0: the scene model's materials are
/// dielectric), its specular lobe in `extras`, its emission as `emissiveFactor` and
/// `KHR_materials_emissive_strength` in the file's light units (`units`).
fn material(m: &Material, textures: &[usize], units: LightUnits) -> Value {
    let mut pbr = json!({"baseColorFactor": m.base_color, "metallicFactor": 0.0, "roughnessFactor": m.roughness});
    if let Some(t) = m.base_color_texture.as_ref().and_then(|t| textures.get(t.image).map(|i| (i, t.tex_coord))) {
        pbr["baseColorTexture"] = json!({"index": t.0, "texCoord": t.1});
    }
    let mut out = json!({"name": m.name, "pbrMetallicRoughness": pbr});
    if let Some(t) = m.normal_texture.as_ref().and_then(|t| textures.get(t.image).map(|i| (i, t.tex_coord))) {
        out["normalTexture"] = json!({"index": t.0, "texCoord": t.1, "scale": m.normal_scale});
    }
    if m.specular != [0.0; 3] {
        out["extras"] = extras::wrap(&MaterialExtras { specular: Some(m.specular) });
    }
    if m.emits() {
        // glTF keeps each factor in [0, 1]: a brighter colour moves into the strength.
        let peak = m.emissive_color.iter().copied().fold(0.0f32, f32::max).max(1.0);
        out["emissiveFactor"] = json!(m.emissive_color.map(|c| c / peak));
        let strength = units.from_radiometric(m.emissive_strength * peak);
        if strength != 1.0 {
            out["extensions"] = json!({"KHR_materials_emissive_strength": {"emissiveStrength": strength}});
        }
    }
    if let Some(t) = m.emissive_texture.as_ref().and_then(|t| textures.get(t.image).map(|i| (i, t.tex_coord))) {
        out["emissiveTexture"] = json!({"index": t.0, "texCoord": t.1});
    }
    out
}

/// An object's node: its mesh (shared by objects of the same mesh and material), or for a
/// proxy block none, and its data in `extras`.
fn object_node(w: &mut GltfWriter, scene: &Scene, object: &Object, meshes: &mut HashMap<(usize, usize), usize>) {
    let generated = match &object.source {
        MeshSource::Cuboid { size, openings } => Some(Generated::Cuboid { size: size.to_array(), openings: *openings }),
        MeshSource::Plane { size } => Some(Generated::Plane { size: *size }),
        MeshSource::Asset { .. } => None,
    };
    let own = NodeExtras {
        role: Some(object.role),
        sampling_weight: Some(object.sampling_weight),
        visible: Some(object.visible),
        generated,
    };
    let mesh = (object.role != ObjectRole::ProxyBlock).then(|| mesh_index(w, scene, object, meshes)).flatten();
    let t = &object.transform;
    w.node(
        NodeDesc {
            name: object.name.clone(),
            translation: Some(t.translation),
            rotation: Some(t.rotation.normalize()),
            scale: Some(t.scale),
            mesh,
            extras: Some(extras::wrap(&own)),
            ..NodeDesc::default()
        },
        true,
    );
}

/// The glTF mesh of `object` (written on first use).
fn mesh_index(
    w: &mut GltfWriter,
    scene: &Scene,
    object: &Object,
    meshes: &mut HashMap<(usize, usize), usize>,
) -> Option<usize> {
    if let Some(&i) = meshes.get(&(object.mesh, object.material)) {
        return Some(i);
    }
    let mesh = scene.resources().meshes.get(object.mesh)?;
    if mesh.indices.is_empty() {
        return None;
    }
    let textured = mesh.uvs.len() == mesh.positions.len() && mesh.uvs.iter().any(|uv| *uv != glam::Vec2::ZERO);
    let tangents = mesh.tangents.len() == mesh.positions.len() && mesh.tangents.iter().all(|t| t.w.abs() == 1.0);
    let attributes = MeshAttributes {
        positions: &mesh.positions,
        normals: &mesh.normals,
        uvs: textured.then_some(&mesh.uvs[..]),
        tangents: tangents.then_some(&mesh.tangents[..]),
        indices: &mesh.indices,
    };
    let i = w.mesh_with(&mesh.name, attributes, Some(object.material));
    meshes.insert((object.mesh, object.material), i);
    Some(i)
}

/// A light's node: KHR_lights_punctual in `units`, pointing along the node's -Z.
fn light_node(w: &mut GltfWriter, light: &Light, units: LightUnits) {
    let kind = match light.kind {
        LightKind::Point => "point",
        LightKind::Spot { .. } => "spot",
        LightKind::Directional => "directional",
    };
    let mut l = json!({
        "name": light.name,
        "type": kind,
        "color": light.color,
        "intensity": units.from_radiometric(light.intensity),
    });
    if let LightKind::Spot { inner_cone_angle, outer_cone_angle } = light.kind {
        l["spot"] = json!({"innerConeAngle": inner_cone_angle, "outerConeAngle": outer_cone_angle});
    }
    if let (Some(range), false) = (light.range, light.kind == LightKind::Directional) {
        l["range"] = json!(range);
    }
    if !light.cast_shadows {
        l["extras"] = extras::wrap(&LightExtras { cast_shadows: Some(false) });
    }
    let index = w.light_json(l);
    let rotation = Quat::from_rotation_arc(Vec3::NEG_Z, light.direction.normalize_or(Vec3::NEG_Y));
    w.node(
        NodeDesc {
            name: light.name.clone(),
            translation: (light.kind != LightKind::Directional).then_some(light.position),
            rotation: (light.kind != LightKind::Point).then_some(rotation),
            light: Some(index),
            ..NodeDesc::default()
        },
        true,
    );
}
