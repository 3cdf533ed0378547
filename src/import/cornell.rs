//! The Cornell box shipped as the default scene (`assets/cornell_box.gltf`), generated here so
//! it is reproducible: a 2 m room open towards +Z, white floor, ceiling and back wall, red left
//! and green right wall, a short and a tall box (grouped under a parent node to exercise the
//! hierarchy), a point light under the ceiling and a camera looking in.

use glam::{Quat, Vec3};

use super::writer::{GltfWriter, NodeDesc};
use crate::scene::Mesh;

/// Classic Cornell box reflectances (approximate RGB of the measured spectra).
pub const WHITE: [f32; 3] = [0.73, 0.73, 0.73];
/// Left wall.
pub const RED: [f32; 3] = [0.63, 0.065, 0.05];
/// Right wall.
pub const GREEN: [f32; 3] = [0.14, 0.45, 0.091];
/// Point light intensity, W/sr per channel.
pub const LIGHT_INTENSITY: f32 = 2.5;
/// Point light position.
pub const LIGHT_POSITION: Vec3 = Vec3::new(0.0, 1.85, 0.0);

fn quad(w: &mut GltfWriter, name: &str, corners: [Vec3; 4], material: usize) -> usize {
    let n = (corners[1] - corners[0]).cross(corners[2] - corners[0]).normalize();
    let mesh = w.mesh(name, &corners, Some(&[n; 4]), &[0, 1, 2, 0, 2, 3], Some(material));
    w.node(NodeDesc { name: name.to_owned(), mesh: Some(mesh), ..NodeDesc::default() }, true)
}

fn cuboid_node(w: &mut GltfWriter, name: &str, size: Vec3, translation: Vec3, angle: f32, material: usize) -> usize {
    let m = Mesh::cuboid(name, size);
    let mesh = w.mesh(name, &m.positions, Some(&m.normals), &m.indices, Some(material));
    w.node(
        NodeDesc {
            name: name.to_owned(),
            mesh: Some(mesh),
            translation: Some(translation),
            rotation: Some(Quat::from_rotation_y(angle)),
            ..NodeDesc::default()
        },
        false,
    )
}

/// The Cornell box document.
pub fn cornell_box() -> GltfWriter {
    let mut w = GltfWriter::default();
    let white = w.material("white", [WHITE[0], WHITE[1], WHITE[2], 1.0]);
    let red = w.material("red", [RED[0], RED[1], RED[2], 1.0]);
    let green = w.material("green", [GREEN[0], GREEN[1], GREEN[2], 1.0]);
    let (x0, x1, y0, y1, z0, z1) = (-1.0, 1.0, 0.0, 2.0, -1.0, 1.0);
    let v = Vec3::new;
    // Each quad is counter-clockwise seen from inside the room.
    quad(&mut w, "floor", [v(x0, y0, z1), v(x1, y0, z1), v(x1, y0, z0), v(x0, y0, z0)], white);
    quad(&mut w, "ceiling", [v(x0, y1, z0), v(x1, y1, z0), v(x1, y1, z1), v(x0, y1, z1)], white);
    quad(&mut w, "back_wall", [v(x0, y0, z0), v(x1, y0, z0), v(x1, y1, z0), v(x0, y1, z0)], white);
    quad(&mut w, "left_wall", [v(x0, y0, z1), v(x0, y0, z0), v(x0, y1, z0), v(x0, y1, z1)], red);
    quad(&mut w, "right_wall", [v(x1, y0, z0), v(x1, y0, z1), v(x1, y1, z1), v(x1, y1, z0)], green);
    let short = cuboid_node(&mut w, "short_box", v(0.6, 0.6, 0.6), v(0.35, 0.3, 0.3), -0.29, white);
    let tall = cuboid_node(&mut w, "tall_box", v(0.6, 1.2, 0.6), v(-0.35, 0.6, -0.35), 0.29, white);
    w.node(NodeDesc { name: "boxes".into(), children: vec![short, tall], ..NodeDesc::default() }, true);
    let light = w.light("ceiling_light", "point", [1.0, 1.0, 1.0], LIGHT_INTENSITY, None);
    w.node(
        NodeDesc { name: "light".into(), translation: Some(LIGHT_POSITION), light: Some(light), ..NodeDesc::default() },
        true,
    );
    let cam = w.camera(0.6911, 0.05, Some(20.0));
    w.node(
        NodeDesc {
            name: "camera".into(),
            translation: Some(v(0.0, 1.0, 3.9)),
            camera: Some(cam),
            ..NodeDesc::default()
        },
        true,
    );
    w
}
