//! The fitter's shape levels ([`crate::precompute::mrt::fit::shapes`]) as glTF development
//! levels: the carved surfaces in three materials (floors, ceilings, walls by their normals), a
//! point light in the first room, the camera in the last looking back. `bouncelab dev-levels`
//! writes them; MRT's energy test reads them back like any level a user brings.

use std::path::{Path, PathBuf};

use glam::Vec3;

use crate::import::writer::{GltfWriter, NodeDesc};
use crate::precompute::mrt::fit::shapes::{self, ShapeLevel};
use crate::scene::{LightUnits, rotation_looking};

/// Wall, floor and ceiling reflectances (as the suite's levels).
const WALL: [f32; 4] = [0.7, 0.7, 0.68, 1.0];
const FLOOR: [f32; 4] = [0.45, 0.4, 0.35, 1.0];
const CEILING: [f32; 4] = [0.8, 0.8, 0.8, 1.0];

/// The point light's intensity (W/sr).
const LIGHT: f32 = 20.0;

/// `level` as a glTF document (radiometric light units, recorded in the file).
pub fn gltf(level: &ShapeLevel) -> GltfWriter {
    let mut w = GltfWriter::default();
    w.set_light_units(LightUnits::Radiometric);
    let tris = level.carve.tris();
    // Each surface's material by the way it faces: floors up, ceilings down, walls sideways.
    let parts = [("floor", FLOOR, 1.0f32), ("ceiling", CEILING, -1.0), ("wall", WALL, 0.0)];
    for (name, colour, keep) in parts {
        let (mut positions, mut normals) = (Vec::new(), Vec::new());
        for t in &tris {
            let n = (t[1] - t[0]).cross(t[2] - t[0]).normalize_or_zero();
            let facing = if n.y > 0.5 {
                1.0
            } else if n.y < -0.5 {
                -1.0
            } else {
                0.0
            };
            if facing == keep {
                positions.extend(t);
                normals.extend([n; 3]);
            }
        }
        let indices: Vec<u32> = (0..positions.len() as u32).collect();
        let material = w.material(name, colour);
        let mesh = w.mesh(name, &positions, Some(&normals), &indices, Some(material));
        w.node(NodeDesc { name: name.to_owned(), mesh: Some(mesh), ..Default::default() }, true);
    }
    let light = w.light("lamp", "point", [1.0, 1.0, 1.0], LIGHT, None);
    let at = Vec3::from(level.light());
    w.node(NodeDesc { name: "lamp".into(), translation: Some(at), light: Some(light), ..Default::default() }, true);
    let (lo, hi) = level.rooms[level.rooms.len() - 1];
    let (lo, hi) = (Vec3::from(lo), Vec3::from(hi));
    let eye = Vec3::new(lo.x + 0.8 * (hi.x - lo.x), lo.y + 1.6, lo.z + 0.8 * (hi.z - lo.z));
    let target = Vec3::from(level.rooms[0].0).lerp(Vec3::from(level.rooms[0].1), 0.5).with_y(lo.y + 1.0);
    let camera = w.camera(1.2, 0.05, None);
    let desc = NodeDesc {
        name: "camera".into(),
        translation: Some(eye),
        rotation: Some(rotation_looking(target - eye)),
        camera: Some(camera),
        ..Default::default()
    };
    w.node(desc, true);
    w
}

/// Every shape level, the stacked storeys last.
pub fn levels() -> Vec<ShapeLevel> {
    let mut out = shapes::levels();
    out.push(shapes::stacked());
    out
}

/// Writes every shape level as `DIR/<name>.gltf`; returns the paths.
pub fn write_all(dir: &Path) -> std::io::Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dir)?;
    let mut out = Vec::new();
    for level in levels() {
        let path = dir.join(format!("{}.gltf", level.name));
        crate::atomic_file::write(&path, gltf(&level).to_string_pretty().as_bytes())?;
        out.push(path);
    }
    Ok(out)
}
