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
    let roots: Vec<gltf::Node<'_>> = match doc.default_scene().or_else(|| doc.scenes().next()) {
        Some(scene) => scene.nodes().collect(),
        None => {
            // No scene (the spec allows a file of assets only): treat nodes that are nobody's
            // child as roots, and say so.
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
    };
    let mut visited = vec![false; doc.nodes().len()];
    let mut stack: Vec<(gltf::Node<'_>, Mat4)> = roots.into_iter().rev().map(|n| (n, Mat4::IDENTITY)).collect();
    let mut camera: Option<Camera> = None;
    let mut uses_default_material = false;
    let default_material = asset.materials.len();

    while let Some((node, parent)) = stack.pop() {
        let idx = node.index();
        let what = format!("node {idx} ({})", node.name().unwrap_or("unnamed"));
        if visited.get(idx).copied().unwrap_or(true) {
            return Err(node_err(what, "is reached twice (a cycle or several parents)".into()));
        }
        visited[idx] = true;
        if let gltf::scene::Transform::Decomposed { rotation, .. } = node.transform() {
            let len = Quat::from_array(rotation).length();
            if (len - 1.0).abs() > 1e-2 {
                return Err(node_err(
                    what,
                    format!("rotation {rotation:?} has length {len}; glTF requires a unit quaternion"),
                ));
            }
        }
        let local = Mat4::from_cols_array_2d(&node.transform().matrix());
        if !local.is_finite() {
            return Err(node_err(what, "transform has NaN or infinite values".into()));
        }
        let world = parent * local;
        if !world.is_finite() {
            return Err(node_err(what, "world transform overflows".into()));
        }
        let own = extras::read::<NodeExtras>(node.extras()).map_err(|m| node_err(what.clone(), m))?.unwrap_or_default();
        let exact = Transform::from_matrix_exact(&world);
        if let Some(mesh) = node.mesh() {
            for prim in mesh.primitives().filter(|p| super::primitive::is_triangles(p.mode())) {
                let material = prim.material().index().unwrap_or_else(|| {
                    uses_default_material = true;
                    default_material
                });
                let name = match (node.name(), mesh.primitives().len()) {
                    (Some(n), 1) => n.to_owned(),
                    (Some(n), _) => format!("{n}#{}", prim.index()),
                    (None, _) => format!("node {idx}#{}", prim.index()),
                };
                let from_file = MeshSource::Asset {
                    asset: 0,
                    mesh: mesh.index(),
                    primitive: prim.index(),
                    baked: if exact.is_some() { None } else { Some(world) },
                };
                // A mesh Bounce Lab generated comes back generated (where its node's transform
                // is a plain one; otherwise as the file's triangles).
                let source = generated_source(&own).filter(|_| exact.is_some()).unwrap_or(from_file);
                asset.scene.objects.push(Object {
                    name,
                    source,
                    mesh: 0,
                    material,
                    transform: exact.unwrap_or_default(),
                    sampling_weight: own.sampling_weight.unwrap_or(1.0),
                    role: own.role.unwrap_or(ObjectRole::Static),
                    visible: own.visible.unwrap_or(true),
                });
            }
        } else if let (Some(source), Some(transform)) = (generated_source(&own), exact) {
            // A proxy block: a node without a mesh, so other tools draw nothing over the level.
            let material = if asset.materials.is_empty() {
                uses_default_material = true;
                default_material
            } else {
                0
            };
            asset.scene.objects.push(Object {
                name: node.name().map_or_else(|| format!("node {idx}"), str::to_owned),
                source,
                mesh: 0,
                material,
                transform,
                sampling_weight: own.sampling_weight.unwrap_or(1.0),
                role: own.role.unwrap_or(ObjectRole::ProxyBlock),
                visible: own.visible.unwrap_or(true),
            });
        }
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
