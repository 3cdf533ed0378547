//! The node graph of the default scene: world transforms, objects, lights and the camera.
//!
//! Walked with an explicit stack and a visited set: cycles, nodes with several parents and very
//! deep chains exist in the wild and must not hang or overflow.

use std::path::Path;

use glam::{Mat3, Mat4, Quat, Vec3};
use gltf::khr_lights_punctual::Kind;

use super::extras::{self, Generated, LightExtras, NodeExtras};
use super::{Asset, ImportError};
use crate::scene::{Camera, Light, LightKind, LightUnits, Material, MeshSource, Object, ObjectRole, Transform};

pub(super) fn build_scene(doc: &gltf::Document, asset: &mut Asset, path: &Path) -> Result<(), ImportError> {
    let node_err = |what: String, message: String| ImportError::Node { path: path.to_owned(), what, message };
    let mut visited = vec![false; doc.nodes().len()];
    let roots = scene_roots(doc, path);
    let mut stack: Vec<(gltf::Node<'_>, Mat4)> = roots.into_iter().rev().map(|n| (n, Mat4::IDENTITY)).collect();
    let mut camera: Option<Camera> = None;
    let mut uses_default_material = false;
    let default_material = DefaultMaterial { index: asset.materials.len(), only: asset.materials.is_empty() };

    while let Some((node, parent)) = stack.pop() {
        let idx = node.index();
        let what = format!("node {idx} ({})", node.name().unwrap_or("unnamed"));
        if visited.get(idx).copied().unwrap_or(true) {
            return Err(node_err(what, "is reached twice (a cycle or several parents)".into()));
        }
        visited[idx] = true;
        let world = world_transform(&node, parent).map_err(|m| node_err(what.clone(), m))?;
        let own = extras::read::<NodeExtras>(node.extras()).map_err(|m| node_err(what.clone(), m))?.unwrap_or_default();
        let (objects, used_default) = node_objects(&node, world, &own, default_material);
        uses_default_material |= used_default;
        asset.scene.objects.extend(objects);
        if let Some(light) = node.light() {
            let light =
                convert_light(&light, &world, node.name(), asset.light_units).map_err(|m| node_err(what.clone(), m))?;
            asset.scene.lights.push(light);
        }
        if let (Some(cam), None) = (node.camera(), camera) {
            camera = Some(convert_camera(&cam, &world).map_err(|m| node_err(what.clone(), m))?);
        }
        for child in node.children().collect::<Vec<_>>().into_iter().rev() {
            stack.push((child, world));
        }
    }

    asset.scene.light_units = asset.light_units;
    asset.scene.materials = asset.materials.clone();
    if uses_default_material {
        asset.scene.materials.push(Material::default());
    }
    asset.has_camera = camera.is_some();
    asset.scene.camera = camera.unwrap_or_default();
    Ok(())
}

/// The default scene's root nodes; without a scene (the spec allows a file of assets only),
/// every node that is nobody's child, and a warning.
fn scene_roots<'a>(doc: &'a gltf::Document, path: &Path) -> Vec<gltf::Node<'a>> {
    if let Some(scene) = doc.default_scene().or_else(|| doc.scenes().next()) {
        return scene.nodes().collect();
    }
    log::warn!("{}: the file has no scene; importing every root node", path.display());
    let mut is_child = vec![false; doc.nodes().len()];
    for n in doc.nodes() {
        for c in n.children() {
            if let Some(slot) = is_child.get_mut(c.index()) {
                *slot = true;
            }
        }
    }
    doc.nodes().filter(|n| !is_child.get(n.index()).copied().unwrap_or(true)).collect()
}

/// The node's world matrix under `parent`: its rotation a unit quaternion, every value finite.
fn world_transform(node: &gltf::Node<'_>, parent: Mat4) -> Result<Mat4, String> {
    if let gltf::scene::Transform::Decomposed { rotation, .. } = node.transform() {
        let len = Quat::from_array(rotation).length();
        if (len - 1.0).abs() > 1e-2 {
            return Err(format!("rotation {rotation:?} has length {len}; glTF requires a unit quaternion"));
        }
    }
    let local = Mat4::from_cols_array_2d(&node.transform().matrix());
    if !local.is_finite() {
        return Err("transform has NaN or infinite values".into());
    }
    let world = parent * local;
    if !world.is_finite() {
        return Err("world transform overflows".into());
    }
    Ok(world)
}

/// Where the default material will sit (after the file's) and whether the file has none.
#[derive(Clone, Copy)]
struct DefaultMaterial {
    index: usize,
    only: bool,
}

/// The objects of one node: one per triangle primitive of its mesh, or for a mesh-less node
/// that Bounce Lab's extras name a generated mesh (a proxy block), that object. Also whether
/// one of them uses the default material.
fn node_objects(node: &gltf::Node<'_>, world: Mat4, own: &NodeExtras, default: DefaultMaterial) -> (Vec<Object>, bool) {
    let exact = Transform::from_matrix_exact(&world);
    let object = |name: String, source: MeshSource, material: usize, role: ObjectRole| Object {
        name,
        source,
        mesh: 0,
        material,
        transform: exact.unwrap_or_default(),
        sampling_weight: own.sampling_weight.unwrap_or(1.0),
        role: own.role.unwrap_or(role),
        visible: own.visible.unwrap_or(true),
    };
    let Some(mesh) = node.mesh() else {
        // A proxy block: a node without a mesh, so other tools draw nothing over the level.
        return match (generated_source(own), exact) {
            (Some(source), Some(_)) => {
                let material = if default.only { default.index } else { 0 };
                let name = node.name().map_or_else(|| format!("node {}", node.index()), str::to_owned);
                (vec![object(name, source, material, ObjectRole::ProxyBlock)], default.only)
            }
            _ => (Vec::new(), false),
        };
    };
    let mut uses_default = false;
    let objects = mesh
        .primitives()
        .filter(|p| super::primitive::is_triangles(p.mode()))
        .map(|prim| {
            let material = prim.material().index().unwrap_or_else(|| {
                uses_default = true;
                default.index
            });
            let name = match (node.name(), mesh.primitives().len()) {
                (Some(n), 1) => n.to_owned(),
                (Some(n), _) => format!("{n}#{}", prim.index()),
                (None, _) => format!("node {}#{}", node.index(), prim.index()),
            };
            let from_file = MeshSource::Asset {
                asset: 0,
                mesh: mesh.index(),
                primitive: prim.index(),
                baked: if exact.is_some() { None } else { Some(world) },
            };
            // A mesh Bounce Lab generated comes back generated (where its node's transform is
            // a plain one; otherwise as the file's triangles).
            let source = generated_source(own).filter(|_| exact.is_some()).unwrap_or(from_file);
            object(name, source, material, ObjectRole::Static)
        })
        .collect();
    (objects, uses_default)
}

fn convert_light(
    light: &gltf::khr_lights_punctual::Light<'_>,
    world: &Mat4,
    node_name: Option<&str>,
    units: LightUnits,
) -> Result<Light, String> {
    let kind = match light.kind() {
        Kind::Point => LightKind::Point,
        Kind::Directional => LightKind::Directional,
        Kind::Spot { inner_cone_angle, outer_cone_angle } => LightKind::Spot { inner_cone_angle, outer_cone_angle },
    };
    let direction =
        world.transform_vector3(Vec3::NEG_Z).try_normalize().ok_or("light direction is degenerate (zero scale)")?;
    let own = extras::read::<LightExtras>(light.extras())?.unwrap_or_default();
    let out = Light {
        name: light.name().or(node_name).unwrap_or("light").to_owned(),
        kind,
        color: light.color(),
        // The scene model is radiometric: candela and lux become W/sr and W/m^2.
        intensity: units.to_radiometric(light.intensity()),
        range: light.range(),
        position: world.transform_point3(Vec3::ZERO),
        direction,
        cast_shadows: own.cast_shadows.unwrap_or(true),
    };
    out.validate().map_err(|e| e.to_string())?;
    Ok(out)
}

fn convert_camera(cam: &gltf::Camera<'_>, world: &Mat4) -> Result<Camera, String> {
    let gltf::camera::Projection::Perspective(p) = cam.projection() else {
        return Err("orthographic cameras are not supported".into());
    };
    let m = Mat3::from_mat4(*world);
    let cols = [m.x_axis.try_normalize(), m.y_axis.try_normalize(), m.z_axis.try_normalize()];
    let [Some(x), Some(y), Some(z)] = cols else {
        return Err("camera transform has a zero scale".into());
    };
    let out = Camera {
        position: world.transform_point3(Vec3::ZERO),
        rotation: Quat::from_mat3(&Mat3::from_cols(x, y, z)).normalize(),
        yfov: p.yfov(),
        znear: p.znear(),
        zfar: p.zfar(),
    };
    out.validate().map_err(|e| e.to_string())?;
    Ok(out)
}

/// The mesh source a node's extras name, if it names a generated mesh.
fn generated_source(own: &NodeExtras) -> Option<MeshSource> {
    match own.generated.as_ref()? {
        Generated::Cuboid { size, openings } => {
            Some(MeshSource::Cuboid { size: Vec3::from(*size), openings: *openings })
        }
        Generated::Plane { size } => Some(MeshSource::Plane { size: *size }),
    }
}
