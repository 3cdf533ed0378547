//! Scenes built from box slabs for the precompute tests: the walls, floors and ceilings of the
//! levels the ISM passes must handle, without a glTF file.

use glam::Vec3;

use crate::scene::{Material, Mesh, MeshSource, Object, ObjectRole, Resources, Scene, SceneDesc, Transform};

/// A static box slab of `size` centred at `centre`, drawn with mesh `mesh` and material 0.
pub fn slab(name: &str, centre: Vec3, size: Vec3, mesh: usize) -> Object {
    Object {
        name: name.into(),
        source: MeshSource::Cuboid { size, openings: [false; 6] },
        mesh,
        material: 0,
        transform: Transform { translation: centre, ..Transform::default() },
        sampling_weight: 1.0,
        role: ObjectRole::Static,
        visible: true,
    }
}

/// The slabs `(name, centre, size)` and any further objects with their meshes, as a scene with
/// one default material.
pub fn scene_of_slabs(parts: &[(&str, Vec3, Vec3)], more: Vec<(Object, Mesh)>) -> Scene {
    let mut objects: Vec<Object> = parts.iter().enumerate().map(|(i, (n, c, s))| slab(n, *c, *s, i)).collect();
    let mut meshes: Vec<Mesh> = parts.iter().map(|(n, _, s)| Mesh::cuboid(n, *s)).collect();
    for (mut object, mesh) in more {
        object.mesh = meshes.len();
        objects.push(object);
        meshes.push(mesh);
    }
    let desc = SceneDesc { materials: vec![Material::default()], objects, ..SceneDesc::default() };
    Scene::new(desc, Resources { meshes, images: vec![], sky: None }).expect("scene")
}
