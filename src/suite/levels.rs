//! The suite's level-like glTF scenes, generated from code so they are reproducible: walls,
//! floors and ceilings are solid slabs with outward normals (as level geometry is modelled),
//! units and scales vary on purpose (a 20 cm diorama to a 60 m hall), and every light type
//! appears.

use glam::{Quat, Vec3};

use crate::import::writer::{GltfWriter, NodeDesc};
use crate::scene::{Mesh, rotation_looking};

/// Wall, floor and ceiling reflectances.
pub(super) const WALL: [f32; 4] = [0.7, 0.7, 0.68, 1.0];
pub(super) const FLOOR: [f32; 4] = [0.45, 0.4, 0.35, 1.0];
pub(super) const CEILING: [f32; 4] = [0.8, 0.8, 0.8, 1.0];

/// An axis-aligned slab from `min` to `max`.
pub(super) fn slab(w: &mut GltfWriter, name: &str, min: Vec3, max: Vec3, material: usize) {
    let m = Mesh::cuboid(name, max - min);
    let mesh = w.mesh(name, &m.positions, Some(&m.normals), &m.indices, Some(material));
    let desc = NodeDesc {
        name: name.to_owned(),
        mesh: Some(mesh),
        translation: Some(0.5 * (min + max)),
        ..Default::default()
    };
    w.node(desc, true);
}

/// A closed box room of slabs `t` thick around the inside `0..size`: floor, ceiling (named
/// `top`), then the front, back, left and right walls. `materials` = [wall, floor, ceiling].
fn closed_room(w: &mut GltfWriter, size: Vec3, t: f32, top: &str, materials: [usize; 3]) {
    let [wall, floor, ceiling] = materials;
    let (v, Vec3 { x: x1, y: h, z: z1 }) = (Vec3::new, size);
    slab(w, "floor", v(-t, -t, -t), v(x1 + t, 0.0, z1 + t), floor);
    slab(w, top, v(-t, h, -t), v(x1 + t, h + t, z1 + t), ceiling);
    slab(w, "front", v(0.0, 0.0, -t), v(x1, h, 0.0), wall);
    slab(w, "back", v(0.0, 0.0, z1), v(x1, h, z1 + t), wall);
    slab(w, "left", v(-t, 0.0, -t), v(0.0, h, z1 + t), wall);
    slab(w, "right", v(x1, 0.0, -t), v(x1 + t, h, z1 + t), wall);
}

/// A closed cylinder of `radius` and `height` standing on `base`, outward normals.
fn cylinder(w: &mut GltfWriter, name: &str, base: Vec3, radius: f32, height: f32, material: usize) {
    const SEGMENTS: u32 = 16;
    let (mut p, mut n, mut idx) = (Vec::new(), Vec::new(), Vec::new());
    for i in 0..=SEGMENTS {
        let a = i as f32 / SEGMENTS as f32 * std::f32::consts::TAU;
        let d = Vec3::new(a.cos(), 0.0, -a.sin());
        p.extend([d * radius, d * radius + Vec3::Y * height]);
        n.extend([d, d]);
    }
    for i in 0..SEGMENTS {
        let b = 2 * i;
        idx.extend([b, b + 2, b + 3, b, b + 3, b + 1]);
    }
    for (y, normal) in [(height, Vec3::Y), (0.0, Vec3::NEG_Y)] {
        let centre = p.len() as u32;
        p.push(Vec3::Y * y);
        n.push(normal);
        for i in 0..SEGMENTS {
            let a = i as f32 / SEGMENTS as f32 * std::f32::consts::TAU;
            p.push(Vec3::new(a.cos() * radius, y, -a.sin() * radius));
            n.push(normal);
        }
        for i in 0..SEGMENTS {
            let (a, b) = (centre + 1 + i, centre + 1 + (i + 1) % SEGMENTS);
            if normal.y > 0.0 { idx.extend([centre, a, b]) } else { idx.extend([centre, b, a]) }
        }
    }
    let mesh = w.mesh(name, &p, Some(&n), &idx, Some(material));
    w.node(NodeDesc { name: name.to_owned(), mesh: Some(mesh), translation: Some(base), ..Default::default() }, true);
}

/// A light node at `position` shining along `direction` (glTF lights shine along -Z).
pub(super) fn light(
    w: &mut GltfWriter,
    name: &str,
    kind: &str,
    intensity: f32,
    position: Vec3,
    direction: Vec3,
    cone: Option<(f32, f32)>,
) {
    let l = w.light(name, kind, [1.0, 0.95, 0.9], intensity, cone);
    let desc = NodeDesc {
        name: name.to_owned(),
        translation: Some(position),
        rotation: Some(rotation_looking(direction)),
        light: Some(l),
        ..Default::default()
    };
    w.node(desc, true);
}

pub(super) fn camera(w: &mut GltfWriter, eye: Vec3, target: Vec3, yfov: f32, znear: f32) {
    let cam = w.camera(yfov, znear, None);
    let rotation: Quat = rotation_looking(target - eye);
    let desc = NodeDesc {
        name: "camera".into(),
        translation: Some(eye),
        rotation: Some(rotation),
        camera: Some(cam),
        ..Default::default()
    };
    w.node(desc, true);
}

/// The three rooms' partition doorways (z ranges) and geometry constants.
pub mod rooms {
    /// Inner room size (x, y, z) in metres.
    pub const ROOM: [f32; 3] = [5.0, 3.0, 4.0];
    /// Slab thickness.
    pub const T: f32 = 0.2;
    /// Doorway height.
    pub const DOOR_HEIGHT: f32 = 2.1;
    /// Doorway z ranges in the two partitions: offset so that no straight line runs from the
    /// lit first room into the third.
    pub const DOORS: [[f32; 2]; 2] = [[0.4, 1.4], [2.6, 3.6]];

    /// The x where room `i` starts inside.
    pub fn start(i: usize) -> f32 {
        i as f32 * (ROOM[0] + T)
    }
}

/// Three 5 x 3 x 4 m rooms in a row joined by offset doorways, 0.2 m slabs, a spot light in the
/// first room; the camera stands in the third (unlit) room looking back through its doorway.
pub fn three_rooms() -> GltfWriter {
    use rooms::{DOOR_HEIGHT, DOORS, ROOM, T, start};
    let mut w = GltfWriter::default();
    let (wall, floor, ceiling) = (w.material("wall", WALL), w.material("floor", FLOOR), w.material("ceiling", CEILING));
    let v = Vec3::new;
    let (h, d) = (ROOM[1], ROOM[2]);
    for i in 0..3 {
        let (a, b) = (start(i), start(i) + ROOM[0]);
        slab(&mut w, &format!("floor_{i}"), v(a - T, -T, -T), v(b + T, 0.0, d + T), floor);
        slab(&mut w, &format!("ceiling_{i}"), v(a - T, h, -T), v(b + T, h + T, d + T), ceiling);
        slab(&mut w, &format!("front_{i}"), v(a, 0.0, -T), v(b, h, 0.0), wall);
        slab(&mut w, &format!("back_{i}"), v(a, 0.0, d), v(b, h, d + T), wall);
    }
    slab(&mut w, "end_0", v(-T, 0.0, -T), v(0.0, h, d + T), wall);
    slab(&mut w, "end_2", v(start(2) + ROOM[0], 0.0, -T), v(start(2) + ROOM[0] + T, h, d + T), wall);
    for (p, [z0, z1]) in DOORS.iter().enumerate() {
        let x = start(p) + ROOM[0];
        slab(&mut w, &format!("partition_{p}_a"), v(x, 0.0, -T), v(x + T, h, *z0), wall);
        slab(&mut w, &format!("partition_{p}_b"), v(x, 0.0, *z1), v(x + T, h, d + T), wall);
        slab(&mut w, &format!("partition_{p}_lintel"), v(x, DOOR_HEIGHT, *z0), v(x + T, h, *z1), wall);
    }
    light(&mut w, "spot", "spot", 40.0, v(1.2, 2.8, 2.0), v(0.5, -1.0, -0.15), Some((0.45, 0.7)));
    camera(&mut w, v(start(2) + 4.6, 1.7, 0.4), v(start(2) - 1.0, 1.0, 3.2), 1.2, 0.05);
    w
}

/// A 6 x 3 x 5 m room with a window in its front wall: a sun shining in through it, a lamp and
/// a spot light.
pub fn window_room() -> GltfWriter {
    let mut w = GltfWriter::default();
    let (wall, floor, ceiling) = (w.material("wall", WALL), w.material("floor", FLOOR), w.material("ceiling", CEILING));
    let (t, v) = (0.2, Vec3::new);
    let (x1, h, z1) = (6.0, 3.0, 5.0);
    slab(&mut w, "floor", v(-t, -t, -t), v(x1 + t, 0.0, z1 + t), floor);
    slab(&mut w, "ceiling", v(-t, h, -t), v(x1 + t, h + t, z1 + t), ceiling);
    slab(&mut w, "back", v(0.0, 0.0, z1), v(x1, h, z1 + t), wall);
    slab(&mut w, "left", v(-t, 0.0, -t), v(0.0, h, z1 + t), wall);
    slab(&mut w, "right", v(x1, 0.0, -t), v(x1 + t, h, z1 + t), wall);
    // The front wall around a 2 x 1.2 m window.
    let (wx0, wx1, wy0, wy1) = (2.0, 4.0, 1.0, 2.2);
    slab(&mut w, "front_left", v(0.0, 0.0, -t), v(wx0, h, 0.0), wall);
    slab(&mut w, "front_right", v(wx1, 0.0, -t), v(x1, h, 0.0), wall);
    slab(&mut w, "front_sill", v(wx0, 0.0, -t), v(wx1, wy0, 0.0), wall);
    slab(&mut w, "front_head", v(wx0, wy1, -t), v(wx1, h, 0.0), wall);
    light(&mut w, "sun", "directional", 4.0, v(3.0, 6.0, -4.0), v(0.2, -0.55, 1.0), None);
    light(&mut w, "lamp", "point", 2.0, v(1.0, 2.4, 4.2), Vec3::NEG_Y, None);
    light(&mut w, "spot", "spot", 12.0, v(5.5, 2.8, 4.5), v(-0.3, -1.0, -0.6), Some((0.35, 0.6)));
    camera(&mut w, v(5.6, 1.7, 4.7), v(2.5, 0.9, 0.3), 1.2, 0.05);
    w
}

/// An 8 x 3.5 x 6 m room with thirty small boxes and cylinders and a spot light.
pub fn cluttered_room() -> GltfWriter {
    let mut w = GltfWriter::default();
    let (wall, floor, ceiling) = (w.material("wall", WALL), w.material("floor", FLOOR), w.material("ceiling", CEILING));
    let colours = [[0.7, 0.2, 0.15, 1.0], [0.2, 0.5, 0.7, 1.0], [0.75, 0.7, 0.3, 1.0], [0.3, 0.6, 0.3, 1.0]];
    let stuff: Vec<usize> = colours.iter().enumerate().map(|(i, c)| w.material(&format!("clutter_{i}"), *c)).collect();
    let v = Vec3::new;
    let (x1, z1) = (8.0, 6.0);
    closed_room(&mut w, v(x1, 3.5, z1), 0.2, "ceiling", [wall, floor, ceiling]);
    // A fixed pseudo-random layout (LCG), the same on every run.
    let mut state = 12345u32;
    let mut next = || {
        state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
        (state >> 8) as f32 / (1 << 24) as f32
    };
    for i in 0..30 {
        let (x, z) = (0.6 + next() * (x1 - 1.2), 0.6 + next() * (z1 - 1.2));
        let size = 0.2 + 0.4 * next();
        let material = stuff[i % stuff.len()];
        if i % 3 == 2 {
            cylinder(&mut w, &format!("cylinder_{i}"), v(x, 0.0, z), 0.5 * size, 1.5 * size, material);
        } else {
            let height = size * (0.6 + next());
            slab(
                &mut w,
                &format!("box_{i}"),
                v(x - 0.5 * size, 0.0, z - 0.5 * size),
                v(x + 0.5 * size, height, z + 0.5 * size),
                material,
            );
        }
    }
    light(&mut w, "spot", "spot", 40.0, v(4.0, 3.3, 3.0), v(0.2, -1.0, 0.1), Some((0.6, 0.85)));
    camera(&mut w, v(0.5, 2.3, 5.6), v(5.0, 0.3, 2.0), 1.1, 0.05);
    w
}

/// A 60 x 12 x 20 m hall with two rows of pillars and three spot lights under the roof.
pub fn hall() -> GltfWriter {
    let mut w = GltfWriter::default();
    let (wall, floor, ceiling) = (w.material("wall", WALL), w.material("floor", FLOOR), w.material("ceiling", CEILING));
    let v = Vec3::new;
    let h = 12.0;
    closed_room(&mut w, v(60.0, h, 20.0), 0.5, "roof", [wall, floor, ceiling]);
    for k in 0..8 {
        let x = 5.0 + 7.0 * k as f32;
        for z in [6.0, 14.0] {
            slab(&mut w, &format!("pillar_{k}_{z}"), v(x - 0.5, 0.0, z - 0.5), v(x + 0.5, h, z + 0.5), wall);
        }
    }
    for (i, x) in [10.0, 30.0, 50.0].into_iter().enumerate() {
        light(&mut w, &format!("spot_{i}"), "spot", 600.0, v(x, 11.5, 10.0), v(0.1, -1.0, 0.0), Some((0.5, 0.75)));
    }
    camera(&mut w, v(2.0, 2.5, 10.0), v(40.0, 4.0, 9.0), 1.0, 0.1);
    w
}

/// A 20 cm diorama: an open box of 5 mm walls with two small blocks and a point light.
pub fn diorama() -> GltfWriter {
    let mut w = GltfWriter::default();
    let (white, red, green) = (
        w.material("white", WALL),
        w.material("red", [0.63, 0.065, 0.05, 1.0]),
        w.material("green", [0.14, 0.45, 0.09, 1.0]),
    );
    let (t, v) = (0.005, Vec3::new);
    let s = 0.1;
    slab(&mut w, "floor", v(-s - t, -t, -s - t), v(s + t, 0.0, s), white);
    slab(&mut w, "back", v(-s - t, 0.0, -s - t), v(s + t, 2.0 * s, -s), white);
    slab(&mut w, "ceiling", v(-s - t, 2.0 * s, -s - t), v(s + t, 2.0 * s + t, s), white);
    slab(&mut w, "left", v(-s - t, 0.0, -s), v(-s, 2.0 * s, s), red);
    slab(&mut w, "right", v(s, 0.0, -s), v(s + t, 2.0 * s, s), green);
    slab(&mut w, "block_a", v(-0.06, 0.0, -0.06), v(-0.01, 0.09, -0.01), white);
    slab(&mut w, "block_b", v(0.02, 0.0, 0.0), v(0.07, 0.04, 0.05), white);
    light(&mut w, "lamp", "point", 0.02, v(0.0, 0.18, 0.0), Vec3::NEG_Y, None);
    camera(&mut w, v(0.0, 0.1, 0.5), v(0.0, 0.09, 0.0), 0.6, 0.005);
    w
}
