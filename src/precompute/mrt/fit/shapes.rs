//! The shapes level designers build, as carved levels ([`super::carve`]) with the rooms each must
//! cover and a light in the first: rooms joined by corridors of any length (straight and
//! turning), L- and T-shaped rooms, rooms of different ceiling heights side by side, a doorway as
//! wide as its wall, a room with pillars, a 60 m hall with a side room, and two storeys joined
//! by a stairwell. The fitter's tests check each; `bouncelab dev-levels` writes them as glTF
//! development levels, and the MRT energy test lights them.

use super::carve::Carve;

/// A room's air: its minimum and maximum corners (m).
pub type Room = ([f32; 3], [f32; 3]);

/// A development level.
pub struct ShapeLevel {
    /// File-name-friendly name.
    pub name: &'static str,
    /// The level.
    pub carve: Carve,
    /// The spaces blocks must cover, the first lit, the others behind its doorways.
    pub rooms: Vec<Room>,
}

impl ShapeLevel {
    fn new(name: &'static str, carve: Carve, rooms: Vec<Room>) -> Self {
        Self { name, carve, rooms }
    }

    /// Where its light hangs: 0.4 m under the first room's ceiling, over its centre.
    pub fn light(&self) -> [f32; 3] {
        let (lo, hi) = self.rooms[0];
        [0.5 * (lo[0] + hi[0]), hi[1] - 0.4, 0.5 * (lo[2] + hi[2])]
    }
}

/// Three 5 x 3 x 4 m rooms along x, joined by 1.8 x 2.4 m passages `length` m long between
/// 0.2 m walls (0: a doorway through a 0.4 m wall; else a corridor of the doorway's section).
pub fn three_rooms_by_corridors(length: f32) -> (Carve, Vec<Room>) {
    let mut carve = Carve::default();
    let mut rooms = Vec::new();
    let mut x = 0.0;
    for k in 0..3 {
        let room = ([x, 0.0, 0.0], [x + 5.0, 3.0, 4.0]);
        carve = carve.air(room.0, room.1);
        rooms.push(room);
        x += 5.0;
        if k < 2 {
            let passage = 0.4 + length;
            carve = carve.air([x, 0.0, 1.1], [x + passage, 2.4, 2.9]);
            x += passage;
        }
    }
    (carve, rooms)
}

/// The corridor level: three 5 x 3 x 4 m rooms, a 0.6 m corridor as tall as the rooms
/// between each pair, 1.8 x 2.4 m doorways at either end.
fn tall_corridors() -> ShapeLevel {
    let mut carve = Carve::default();
    let mut rooms = Vec::new();
    for k in 0..3 {
        let x = k as f32 * 6.0;
        rooms.push(([x, 0.0, 0.0], [x + 5.0, 3.0, 4.0]));
        carve = carve.air([x, 0.0, 0.0], [x + 5.0, 3.0, 4.0]);
        if k < 2 {
            carve = carve
                .air([x + 5.0, 0.0, 1.1], [x + 5.2, 2.4, 2.9])
                .air([x + 5.2, 0.0, 1.1], [x + 5.8, 3.0, 2.9])
                .air([x + 5.8, 0.0, 1.1], [x + 6.0, 2.4, 2.9]);
        }
    }
    ShapeLevel::new("corridors_tall", carve, rooms)
}

/// Every single-storey shape, each with its rooms.
pub fn levels() -> Vec<ShapeLevel> {
    let mut out = Vec::new();
    for (name, length) in [("corridors_0m", 0.0), ("corridors_0.6m", 0.6), ("corridors_3m", 3.0)] {
        let (carve, rooms) = three_rooms_by_corridors(length);
        out.push(ShapeLevel::new(name, carve, rooms));
    }
    out.push(tall_corridors());
    // A corridor leaving room A's east wall and turning north after 2 m to room B.
    let (a, b) = (([0.0, 0.0, 0.0], [5.0, 3.0, 4.0]), ([4.0, 0.0, 9.2], [9.0, 3.0, 13.2]));
    let turning = Carve::default()
        .air(a.0, a.1)
        .air([5.0, 0.0, 1.1], [7.0, 2.5, 2.9])
        .air([5.2, 0.0, 2.9], [7.0, 2.5, 9.2])
        .air(b.0, b.1);
    out.push(ShapeLevel::new("corridor_turning", turning, vec![a, ([5.2, 0.0, 1.1], [7.0, 2.5, 9.0]), b]));
    let l_arms = [([0.0, 0.0, 0.0], [6.0, 3.0, 2.0]), ([0.0, 0.0, 2.0], [2.0, 3.0, 6.0])];
    out.push(ShapeLevel::new(
        "l_room",
        Carve::default().air(l_arms[0].0, l_arms[0].1).air(l_arms[1].0, l_arms[1].1),
        l_arms.to_vec(),
    ));
    let t_arms = [([0.0, 0.0, 0.0], [9.0, 3.0, 2.5]), ([3.5, 0.0, 2.5], [5.5, 3.0, 7.0])];
    out.push(ShapeLevel::new(
        "t_room",
        Carve::default().air(t_arms[0].0, t_arms[0].1).air(t_arms[1].0, t_arms[1].1),
        t_arms.to_vec(),
    ));
    let (low, high) = (([0.0, 0.0, 0.0], [5.0, 3.0, 4.0]), ([5.2, 0.0, 0.0], [9.2, 4.5, 4.0]));
    let door = Carve::default().air(low.0, low.1).air(high.0, high.1).air([5.0, 0.0, 1.5], [5.2, 2.1, 2.5]);
    out.push(ShapeLevel::new("ceilings_doorway", door, vec![low, high]));
    let open = Carve::default().air(low.0, low.1).air([5.0, 0.0, 0.0], [9.2, 4.5, 4.0]);
    out.push(ShapeLevel::new("ceilings_open", open, vec![low, high]));
    let (a, b) = (([0.0, 0.0, 0.0], [5.0, 3.0, 4.0]), ([5.2, 0.0, 0.0], [10.2, 3.0, 4.0]));
    let wide = Carve::default().air(a.0, a.1).air(b.0, b.1).air([5.0, 0.0, 0.0], [5.2, 2.4, 4.0]);
    out.push(ShapeLevel::new("wide_doorway", wide, vec![a, b]));
    out.push(pillars());
    let (hall, side) = (([0.0, 0.0, 0.0], [60.0, 6.0, 10.0]), ([20.0, 0.0, 10.2], [26.0, 3.0, 14.0]));
    let big = Carve::default().air(hall.0, hall.1).air(side.0, side.1).air([22.0, 0.0, 10.0], [23.2, 2.2, 10.2]);
    out.push(ShapeLevel::new("hall_60m", big, vec![hall, side]));
    out
}

/// A 12 x 4 x 8 m hall with two rows of three 0.5 m pillars; its halves as the rooms.
fn pillars() -> ShapeLevel {
    let mut carve = Carve::default().air([0.0, 0.0, 0.0], [12.0, 4.0, 8.0]);
    for x in [3.0, 6.0, 9.0] {
        for z in [2.5, 5.5] {
            carve = carve.rock([x - 0.25, 0.0, z - 0.25], [x + 0.25, 4.0, z + 0.25]);
        }
    }
    ShapeLevel::new("pillars", carve, vec![([0.0, 0.0, 0.0], [6.0, 4.0, 8.0]), ([6.0, 0.0, 0.0], [12.0, 4.0, 8.0])])
}

/// Two 6 x 3 x 5 m storeys, a 0.3 m slab between, a 1.5 x 2.5 m stairwell through it.
pub fn stacked() -> ShapeLevel {
    let (lower, upper) = (([0.0, 0.0, 0.0], [6.0, 3.0, 5.0]), ([0.0, 3.3, 0.0], [6.0, 6.3, 5.0]));
    let carve = Carve::default().air(lower.0, lower.1).air(upper.0, upper.1).air([4.0, 3.0, 0.5], [5.5, 3.3, 3.0]);
    ShapeLevel::new("stacked_stairwell", carve, vec![lower, upper])
}
