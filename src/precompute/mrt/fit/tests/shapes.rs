//! The shapes level designers build, carved on a lattice ([`super::super::carve`]): rooms joined
//! by corridors of any length (straight and turning), L- and T-shaped rooms, rooms of different
//! ceiling heights side by side, a doorway as wide as its wall, two storeys with a stairwell, a
//! room with pillars, a 60 m hall, a courtyard open to the sky. Each must give blocks covering
//! every enclosed room, linked through every doorway and corridor, or name what it leaves out.

use std::collections::VecDeque;

use super::super::carve::Carve;
use super::super::shapes::{self, ShapeLevel};
use super::*;

use super::super::shapes::Room;

/// The blocks holding the point `p`.
fn holding(blocks: &[FittedBlock], p: Vec3) -> Vec<usize> {
    (0..blocks.len()).filter(|&i| p.cmpge(blocks[i].min).all() && p.cmple(blocks[i].max).all()).collect()
}

/// Fits `carve`, and checks that nothing is reported left out, no open side leads nowhere, each
/// of `rooms` is at least 90% covered (points 0.25 m apart at half its height), and every room
/// is reached from the first through the links. Returns the blocks.
fn fits_whole(carve: &Carve, rooms: &[Room]) -> Vec<FittedBlock> {
    let report = fit_report(&carve.tris()).expect("fits");
    let blocks = report.blocks;
    let names = |i: usize| format!("proxy {}", i + 1);
    let gaps: Vec<String> = report.gaps.iter().map(|g| g.describe(&names)).collect();
    assert!(gaps.is_empty(), "{gaps:#?}\n{blocks:#?}");
    let level = level_of(&blocks);
    assert!(level.unlinked().is_empty(), "open sides lead nowhere: {:?}\n{blocks:#?}", level.unlinked());
    let mut reached = vec![false; blocks.len()];
    let mut queue = VecDeque::new();
    for (k, (lo, hi)) in rooms.iter().enumerate() {
        let (lo, hi) = (Vec3::from(*lo), Vec3::from(*hi));
        let y = 0.5 * (lo.y + hi.y);
        let (mut inside, mut all) = (0, 0);
        let mut x = lo.x + 0.125;
        while x < hi.x {
            let mut z = lo.z + 0.125;
            while z < hi.z {
                let held = holding(&blocks, Vec3::new(x, y, z));
                all += 1;
                if !held.is_empty() {
                    inside += 1;
                }
                if k == 0 {
                    for i in held {
                        if !reached[i] {
                            reached[i] = true;
                            queue.push_back(i);
                        }
                    }
                }
                z += 0.25;
            }
            x += 0.25;
        }
        assert!(
            inside as f32 >= 0.9 * all as f32,
            "room {k} {lo}..{hi}: {inside} of {all} points in blocks\n{blocks:#?}"
        );
    }
    while let Some(i) = queue.pop_front() {
        for w in crate::precompute::mrt::shape::Face::ALL {
            if let Some(j) = level.link(i, w)
                && !reached[j]
            {
                reached[j] = true;
                queue.push_back(j);
            }
        }
    }
    for (k, (lo, hi)) in rooms.iter().enumerate() {
        let centre = 0.5 * (Vec3::from(*lo) + Vec3::from(*hi));
        let held = holding(&blocks, centre);
        assert!(held.iter().any(|&i| reached[i]), "room {k} is not linked to the first: {blocks:#?}");
    }
    blocks
}

/// The shape named `name` of [`shapes::levels`].
fn shape(name: &str) -> ShapeLevel {
    shapes::levels().into_iter().find(|l| l.name == name).expect("a shape level")
}

#[test]
fn every_shape_is_covered_and_linked_through_its_doorways_and_corridors() {
    for level in shapes::levels() {
        let blocks = fits_whole(&level.carve, &level.rooms);
        eprintln!("{}: {} blocks", level.name, blocks.len());
    }
}

#[test]
fn rooms_of_different_ceiling_heights_side_by_side_get_blocks_of_their_own_heights() {
    for name in ["ceilings_doorway", "ceilings_open"] {
        let level = shape(name);
        let blocks = fit(&level.carve.tris()).expect("fits");
        for (room, height) in level.rooms.iter().zip([3.0, 4.5]) {
            let centre = 0.5 * (Vec3::from(room.0) + Vec3::from(room.1));
            for i in holding(&blocks, centre) {
                assert!((blocks[i].max.y - height).abs() < 0.05, "{name}: {:?} under a {height} m ceiling", blocks[i]);
            }
        }
    }
}

#[test]
fn pillars_do_not_cut_a_room_into_pieces_and_a_60_m_hall_is_cut_into_near_cubic_parts() {
    let blocks = fit(&shape("pillars").carve.tris()).expect("fits");
    assert!(blocks.len() <= 4, "{blocks:?}");
    let blocks = fit(&shape("hall_60m").carve.tris()).expect("fits");
    for b in &blocks {
        assert!((b.max - b.min).max_element() < 16.0, "near-cubic parts: {b:?}");
    }
}

#[test]
fn two_storeys_with_a_stairwell_are_fitted_each_and_the_stairwell_is_named() {
    let level = shapes::stacked();
    let report = fit_report(&level.carve.tris()).expect("fits");
    for room in &level.rooms {
        let centre = 0.5 * (Vec3::from(room.0) + Vec3::from(room.1));
        let held = holding(&report.blocks, centre);
        assert!(!held.is_empty(), "a block in each storey at {centre}: {:?}", report.blocks);
        for b in held.iter().map(|&i| &report.blocks[i]) {
            assert!((b.min.y - room.0[1]).abs() < 0.05 && (b.max.y - room.1[1]).abs() < 0.35, "{b:?}");
        }
    }
    let [gap] = report.gaps.as_slice() else { panic!("one gap: {:?}", report.gaps) };
    assert_eq!(gap.kind, GapKind::Stairwell);
    assert!((gap.min.x - 4.0).abs() < 0.3 && (gap.max.x - 5.5).abs() < 0.3, "{gap:?}");
    assert!((gap.min.z - 0.5).abs() < 0.3 && (gap.max.z - 3.0).abs() < 0.3, "{gap:?}");
    assert!((3.0..=3.4).contains(&gap.min.y), "{gap:?}");
    let text = gap.describe(&|i| format!("proxy {}", i + 1));
    assert!(text.contains("between storeys") && text.contains("x 4.0..5.5"), "{text}");
}

#[test]
fn a_courtyard_open_to_the_sky_is_no_enclosed_space_and_the_error_says_so() {
    // A 10 x 10 m yard: floor and 3 m walls, no roof.
    let (x, h, t) = (10.0, 3.0, 0.2);
    let mut tris = Vec::new();
    tris.extend(cuboid(Vec3::new(-t, -t, -t), Vec3::new(x + t, 0.0, x + t)));
    tris.extend(cuboid(Vec3::new(-t, 0.0, -t), Vec3::new(x + t, h, 0.0)));
    tris.extend(cuboid(Vec3::new(-t, 0.0, x), Vec3::new(x + t, h, x + t)));
    tris.extend(cuboid(Vec3::new(-t, 0.0, 0.0), Vec3::new(0.0, h, x)));
    tris.extend(cuboid(Vec3::new(x, 0.0, 0.0), Vec3::new(x + t, h, x)));
    let err = fit_report(&tris).expect_err("nothing enclosed");
    assert!(matches!(err, FitError::NoEnclosure { .. } | FitError::NoRoom), "{err}");
    assert!(err.to_string().contains("courtyard open to the sky"), "{err}");
}

#[test]
fn hand_placed_blocks_that_miss_a_room_or_a_link_are_named_with_where_and_what_to_do() {
    let (carve, rooms) = shapes::three_rooms_by_corridors(0.0);
    let tris = carve.tris();
    // Blocks over the first two rooms only, closed: the third room is uncovered and the doorway
    // between the first two joins blocks that are not linked.
    let boxes: Vec<(Vec3, Vec3)> = rooms[..2].iter().map(|(lo, hi)| (Vec3::from(*lo), Vec3::from(*hi))).collect();
    let gaps = coverage(&tris, &boxes, &[]).expect("checks");
    let names = |i: usize| format!("block {:?}", ["west", "middle"][i]);
    let text: Vec<String> = gaps.iter().map(|g| g.describe(&names)).collect();
    assert_eq!(gaps.len(), 2, "{text:#?}");
    let uncovered = gaps.iter().find(|g| matches!(g.kind, GapKind::Uncovered { .. })).expect("the third room");
    // The room and the doorway's air in the wall before it.
    assert!((uncovered.min.x - 10.4).abs() < 0.1 && (uncovered.max.x - rooms[2].1[0]).abs() < 0.1, "{uncovered:?}");
    assert!(text.iter().any(|t| t.contains("no proxy block covers the enclosed space at x 10.4..15.8")), "{text:#?}");
    let unlinked = gaps.iter().find(|g| matches!(g.kind, GapKind::Unlinked { a: 0, b: 1 })).expect("the doorway");
    assert!((4.9..=5.3).contains(&unlinked.min.x) && (1.0..=1.3).contains(&unlinked.min.z), "{unlinked:?}");
    assert!(
        text.iter().any(|t| t.contains("joins block \"west\" and block \"middle\", which are not linked")),
        "{text:#?}"
    );
    // Linked, and a block over the third room: nothing left out.
    let all: Vec<(Vec3, Vec3)> = rooms.iter().map(|(lo, hi)| (Vec3::from(*lo), Vec3::from(*hi))).collect();
    assert_eq!(coverage(&tris, &all, &[(0, 1), (1, 2)]).expect("checks"), Vec::new());
}
