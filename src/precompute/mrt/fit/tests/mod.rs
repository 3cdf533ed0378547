//! The fitter on built levels: rooms, doorways, corridors, solids, and the levels it refuses.
use super::voxels::inside_solid;
use super::*;
use crate::precompute::mrt::level::{Block, Level};
use crate::precompute::mrt::proxy::{open_faces, shape_for};

/// The 12 triangles of a box, facing out.
fn cuboid(lo: Vec3, hi: Vec3) -> Vec<[Vec3; 3]> {
    let c = |i: usize| {
        Vec3::new(
            if i & 1 == 0 { lo.x } else { hi.x },
            if i & 2 == 0 { lo.y } else { hi.y },
            if i & 4 == 0 { lo.z } else { hi.z },
        )
    };
    let quads = [[0, 2, 6, 4], [1, 5, 7, 3], [0, 4, 5, 1], [2, 3, 7, 6], [0, 1, 3, 2], [4, 6, 7, 5]];
    // Counter-clockwise seen from outside: the normals face out, as level geometry's do.
    quads.iter().flat_map(|q| [[c(q[0]), c(q[2]), c(q[1])], [c(q[0]), c(q[3]), c(q[2])]]).collect()
}

/// The slabs (thickness `t`) enclosing the space x in [0, `x`], y in [0, `h`], z in [0, `z`]:
/// floor, ceiling and four walls.
fn shell(x: f32, z: f32, h: f32, t: f32) -> Vec<[Vec3; 3]> {
    let mut tris = Vec::new();
    tris.extend(cuboid(Vec3::new(-t, -t, -t), Vec3::new(x + t, 0.0, z + t)));
    tris.extend(cuboid(Vec3::new(-t, h, -t), Vec3::new(x + t, h + t, z + t)));
    tris.extend(cuboid(Vec3::new(-t, 0.0, -t), Vec3::new(x + t, h, 0.0)));
    tris.extend(cuboid(Vec3::new(-t, 0.0, z), Vec3::new(x + t, h, z + t)));
    tris.extend(cuboid(Vec3::new(-t, 0.0, 0.0), Vec3::new(0.0, h, z)));
    tris.extend(cuboid(Vec3::new(x, 0.0, 0.0), Vec3::new(x + t, h, z)));
    tris
}

/// Three 5 x 3 x 4 m rooms along +x, 0.2 m slabs, a 1 x 2.1 m doorway in each partition
/// (the offset doorways of the suite's multi-room level).
fn three_rooms() -> Vec<[Vec3; 3]> {
    let (w, h, d, t) = (5.0, 3.0, 4.0, 0.2);
    let length = 3.0 * w + 2.0 * t;
    let mut tris = Vec::new();
    tris.extend(shell(length, d, h, t));
    for (k, door_z) in [(1.0, 0.5), (2.0, 2.5)] {
        let x = k * w + (k - 1.0) * t;
        // The partition with a doorway from door_z to door_z + 1, 2.1 m high.
        tris.extend(cuboid(Vec3::new(x, 0.0, 0.0), Vec3::new(x + t, h, door_z)));
        tris.extend(cuboid(Vec3::new(x, 0.0, door_z + 1.0), Vec3::new(x + t, h, d)));
        tris.extend(cuboid(Vec3::new(x, 2.1, door_z), Vec3::new(x + t, h, door_z + 1.0)));
    }
    tris
}

/// As proxy boxes: the level of `blocks`.
fn level_of(blocks: &[FittedBlock]) -> Level {
    Level::new(
        blocks
            .iter()
            .map(|b| {
                let (shape, turns) = shape_for(&open_faces(&b.openings, 0)).expect("a dictionary shape");
                Block { shape, origin: b.min, size: b.max - b.min, turns }
            })
            .collect(),
    )
}

#[test]
fn three_rooms_joined_by_doorways_stay_whole_blocks_linked_through_their_doorway_sides() {
    let blocks = fit(&three_rooms()).expect("fits");
    assert_eq!(blocks.len(), 3, "one doorway per side: whole rooms {blocks:?}");
    let (a, b, c) = (&blocks[0], &blocks[1], &blocks[2]);
    // Open towards each other (+x is openings[0], -x openings[1]), meeting at the
    // partitions' mid-planes; every other side closed.
    assert_eq!(a.openings, [true, false, false, false, false, false]);
    assert_eq!(b.openings, [true, true, false, false, false, false]);
    assert_eq!(c.openings, [false, true, false, false, false, false]);
    assert!((a.max.x - 5.1).abs() < 0.05 && (b.min.x - 5.1).abs() < 0.05, "{a:?} {b:?}");
    assert!((b.max.x - 10.3).abs() < 0.05 && (c.min.x - 10.3).abs() < 0.05, "{b:?} {c:?}");
    for room in &blocks {
        let size = room.max - room.min;
        assert!((size.y - 3.0).abs() < 0.25 && (size.z - 4.0).abs() < 0.25, "{size}");
    }
    let level = level_of(&blocks);
    assert_eq!(level.link_count(), 4, "two doorways, linked both ways");
    assert!(level.unlinked().is_empty(), "{:?}", level.unlinked());
}

#[test]
fn a_side_with_doorways_to_two_rooms_splits_its_room_into_strips_one_per_doorway() {
    // A 5 x 3 x 8 m room whose east wall has a doorway into each of two 4.8 x 3 x 3.9 m rooms
    // (split by a wall at z 3.9 .. 4.1): doorways at z 1 .. 2 and 5.5 .. 6.5.
    let (h, t) = (3.0, 0.2);
    let (x0, x1, x2, d) = (5.0, 5.2, 10.0, 8.0);
    let mut tris = Vec::new();
    tris.extend(shell(x2, d, h, t));
    tris.extend(cuboid(Vec3::new(x1, 0.0, 3.9), Vec3::new(x2, h, 4.1)));
    for (z0, z1) in [(0.0, 1.0), (2.0, 5.5), (6.5, d)] {
        tris.extend(cuboid(Vec3::new(x0, 0.0, z0), Vec3::new(x1, h, z1)));
    }
    for z in [1.0, 5.5] {
        tris.extend(cuboid(Vec3::new(x0, 2.1, z), Vec3::new(x1, h, z + 1.0)));
    }
    let blocks = fit(&tris).expect("fits");
    // The west room cut at the four jambs: 5 strips along z; the east rooms whole.
    let west: Vec<&FittedBlock> = blocks.iter().filter(|b| 0.5 * (b.min.x + b.max.x) < x0).collect();
    assert_eq!((west.len(), blocks.len() - west.len()), (5, 2), "{blocks:?}");
    // Its doorway strips open east and span their doorways.
    let doors: Vec<&&FittedBlock> = west.iter().filter(|b| b.openings[0]).collect();
    assert_eq!(doors.len(), 2, "{blocks:?}");
    for (door, z) in doors.iter().zip([1.0, 5.5]) {
        assert!((door.min.z - z).abs() < 0.15 && (door.max.z - z - 1.0).abs() < 0.15, "{door:?}");
    }
    // Strips open to each other (4 sides) and the two doorways: 6 sides, linked both ways.
    let level = level_of(&blocks);
    assert_eq!(level.link_count(), 12);
    assert!(level.unlinked().is_empty(), "{:?}", level.unlinked());
}

#[test]
fn a_long_room_is_cut_into_near_cubic_parts_along_its_length_and_its_doorway_stays_whole() {
    // A 9 x 3 x 3 m hall whose east end has a doorway into a 3 x 3 x 3 m room.
    let (h, t, d) = (3.0, 0.2, 3.0);
    let (x0, x1, x2) = (9.0, 9.2, 12.2);
    let mut tris = Vec::new();
    tris.extend(shell(x2, d, h, t));
    tris.extend(cuboid(Vec3::new(x0, 0.0, 0.0), Vec3::new(x1, h, 1.0)));
    tris.extend(cuboid(Vec3::new(x0, 0.0, 2.0), Vec3::new(x1, h, d)));
    tris.extend(cuboid(Vec3::new(x0, 2.1, 1.0), Vec3::new(x1, h, 2.0)));
    let blocks = fit(&tris).expect("fits");
    // The hall in three parts of about 3 m (the mean of its width and height), the room whole.
    let hall: Vec<&FittedBlock> = blocks.iter().filter(|b| 0.5 * (b.min.x + b.max.x) < x0).collect();
    assert_eq!((hall.len(), blocks.len() - hall.len()), (3, 1), "{blocks:?}");
    for b in &hall {
        let length = b.max.x - b.min.x;
        assert!((2.6..3.4).contains(&length), "{b:?}");
        assert!(b.max.z - b.min.z > 2.5, "cut across its length only: {b:?}");
    }
    // Parts open to each other (2 sides) and the doorway: 3 sides, linked both ways.
    let level = level_of(&blocks);
    assert_eq!(level.link_count(), 6);
    assert!(level.unlinked().is_empty(), "{:?}", level.unlinked());
}

#[test]
fn solids_are_not_rooms_and_a_closed_room_is_one_closed_block() {
    // One closed 4 x 3 x 4 m room of 0.2 m slabs with a 1.5 m solid cube standing in it.
    let (w, h, t) = (4.0, 3.0, 0.2);
    let mut tris = Vec::new();
    tris.extend(shell(w, w, h, t));
    tris.extend(cuboid(Vec3::new(1.0, 0.0, 1.0), Vec3::new(2.5, 1.5, 2.5)));
    let blocks = fit(&tris).expect("fits");
    assert_eq!(blocks.len(), 1, "{blocks:?}");
    assert_eq!(blocks[0].openings, [false; 6]);
    assert!((blocks[0].max - blocks[0].min - Vec3::new(w, h, w)).abs().max_element() < 0.25);
    // A lone solid crate encloses nothing to light: its inside faces away from it.
    let crate_only = cuboid(Vec3::ZERO, Vec3::splat(3.0));
    assert!(matches!(fit(&crate_only), Err(FitError::NoEnclosure { .. })), "{:?}", fit(&crate_only));
    // The validity test itself: inside a closed box its backs face the point.
    assert!(inside_solid(&cuboid(Vec3::ZERO, Vec3::ONE), Vec3::splat(0.5)));
    assert!(!inside_solid(&cuboid(Vec3::ZERO, Vec3::ONE), Vec3::splat(1.5)));
}

#[test]
fn levels_it_cannot_fit_get_a_clear_error() {
    // An open field: one big plane.
    let field = vec![
        [Vec3::new(-50.0, 0.0, -50.0), Vec3::new(50.0, 0.0, -50.0), Vec3::new(50.0, 0.0, 50.0)],
        [Vec3::new(-50.0, 0.0, -50.0), Vec3::new(50.0, 0.0, 50.0), Vec3::new(-50.0, 0.0, 50.0)],
    ];
    assert!(matches!(fit(&field), Err(FitError::NoEnclosure { .. })));
    let lone = vec![[Vec3::ZERO, Vec3::X, Vec3::Z]];
    assert!(matches!(fit(&lone), Err(FitError::NoEnclosure { .. })));
    assert_eq!(fit(&[]), Err(FitError::Empty));
    // A sphere: closed, but its walls face every direction.
    let (rings, segments) = (12, 24);
    let p = |i: usize, j: usize| {
        let (th, ph) =
            (std::f32::consts::PI * i as f32 / rings as f32, std::f32::consts::TAU * j as f32 / segments as f32);
        Vec3::new(th.sin() * ph.cos(), th.cos(), th.sin() * ph.sin()) * 3.0
    };
    let mut sphere = Vec::new();
    for i in 0..rings {
        for j in 0..segments {
            sphere.push([p(i, j), p(i + 1, j), p(i + 1, j + 1)]);
            sphere.push([p(i, j), p(i + 1, j + 1), p(i, j + 1)]);
        }
    }
    let err = fit(&sphere).expect_err("a sphere");
    assert!(matches!(err, FitError::NonRectilinear { .. }), "{err}");
    assert!(err.to_string().contains("not rectilinear"));
    // A closed box turned 45 degrees about up: rectilinear in itself, but off the grid.
    let turn = glam::Quat::from_rotation_y(std::f32::consts::FRAC_PI_4);
    let turned: Vec<[Vec3; 3]> =
        cuboid(Vec3::splat(-2.0), Vec3::splat(2.0)).iter().map(|t| t.map(|p| turn * p)).collect();
    assert!(matches!(fit(&turned), Err(FitError::NonRectilinear { .. })), "{:?}", fit(&turned));
}

mod shapes;
