//! MRT's light prior training set (Loos 2015 §3.3 / §4.1.1): the direct light that sphere lights of
//! equal power put on a shape's samples, one column per light. Lights sit on a 6x6x6 grid of cell
//! centres inside the cube, three cell layers out through every open side (108 each) and, for each
//! pair of adjacent open sides, 3x3 diagonal columns of 6 (54). A light outside the block lights a
//! sample only through an opening. The direct light is the outgoing radiance of a white diffuse
//! wall up to a constant, cos(theta) / d^2 with d clamped at the sphere's radius
//! ([`LIGHT_RADIUS`]); the SVD that follows is blind to that constant.

use glam::Vec3;

use super::shape::{Face, Layout, exit};

/// Grid cells per cube side (the dissertation's 6).
pub const GRID: usize = 6;

/// The sphere lights' radius, the distance below which their 1/d^2 is clamped: one grid spacing.
/// The dissertation leaves it open (half a spacing is the obvious guess). Measured on the closed
/// cube (`bouncelab mrt-dictionary`, 16x16 texels): half a spacing needs 74 / 104 / 125 prior modes
/// for 80 / 90 / 95% of the training set's energy, one spacing 21 / 40 / 61 and one and a half
/// 8 / 17 / 29; the dissertation's Table 3.2 has 22 / 41 / 62, so one spacing is what it used in
/// effect.
pub const LIGHT_RADIUS: f32 = 1.0 / GRID as f32;

/// The training lights of `layout`'s shape.
pub fn light_positions(layout: &Layout) -> Vec<Vec3> {
    let cell = |i: usize| (i as f32 + 0.5) / GRID as f32;
    let mut lights = Vec::new();
    for (x, y, z) in grid3(GRID, GRID, GRID) {
        lights.push(Vec3::new(cell(x), cell(y), cell(z)));
    }
    // Three layers beyond each open side, over its 6x6 cells.
    for &face in layout.shape.open_faces() {
        let (a, b) = face.plane_axes();
        for (layer, i, j) in grid3(3, GRID, GRID) {
            let mut p = Vec3::ZERO;
            let out = cell(layer);
            p[face.axis()] = if face.positive() { 1.0 + out } else { -out };
            p[a] = cell(i);
            p[b] = cell(j);
            lights.push(p);
        }
    }
    // Diagonal ("kitty-corner") columns beyond each pair of adjacent open sides.
    for (f, g) in layout.shape.adjacent_open_pairs() {
        for (i, j, y) in grid3(3, 3, GRID) {
            let mut p = Vec3::new(0.0, cell(y), 0.0);
            p[f.axis()] = if f.positive() { 1.0 + cell(i) } else { -cell(i) };
            p[g.axis()] = if g.positive() { 1.0 + cell(j) } else { -cell(j) };
            lights.push(p);
        }
    }
    lights
}

fn grid3(a: usize, b: usize, c: usize) -> impl Iterator<Item = (usize, usize, usize)> {
    (0..a).flat_map(move |i| (0..b).flat_map(move |j| (0..c).map(move |k| (i, j, k))))
}

/// Whether a light at `light` outside the unit cube reaches the point `p` of a present face:
/// the segment leaves the cube through an open side.
fn through_opening(layout: &Layout, p: Vec3, light: Vec3) -> bool {
    let inside = light.cmpge(Vec3::ZERO).all() && light.cmple(Vec3::ONE).all();
    if inside {
        return true;
    }
    let d = (light - p).normalize_or_zero();
    let (face, _, _, _): (Face, f32, f32, f32) = exit(p + d * 1e-5, d);
    layout.shape.is_open(face)
}

/// The direct light of a light at `light` on sample `i`: cos(theta) / max(d, radius)^2, zero
/// behind the face or where a wall stands between.
pub fn direct(layout: &Layout, i: usize, light: Vec3) -> f32 {
    let (_, _, p, n) = layout.sample(i);
    let v = light - p;
    let d = v.length();
    let cos = n.dot(v) / d.max(1e-9);
    if cos <= 0.0 || !through_opening(layout, p, light) {
        return 0.0;
    }
    cos / d.max(LIGHT_RADIUS).powi(2)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::precompute::mrt::shape::Shape;

    #[test]
    fn the_training_set_has_the_dissertations_counts() {
        let count = |s| light_positions(&Layout::new(s, 2)).len();
        assert_eq!(count(Shape::Closed), 216);
        assert_eq!(count(Shape::DeadEnd), 216 + 108);
        assert_eq!(count(Shape::Corridor), 216 + 2 * 108);
        assert_eq!(count(Shape::Corner), 216 + 2 * 108 + 54);
        assert_eq!(count(Shape::Crossroads), 216 + 4 * 108 + 4 * 54);
    }

    #[test]
    fn a_light_outside_lights_only_what_it_sees_through_the_opening() {
        let layout = Layout::new(Shape::DeadEnd, 4);
        // A light 0.25 beyond the open +z side, at mid height.
        let light = Vec3::new(0.5, 0.5, 1.25);
        let back = layout.face_start(Face::NegZ).expect("back wall");
        assert!(direct(&layout, back + 2 * 4 + 2, light) > 0.0, "the back wall faces the opening");
        // Beyond the closed -x wall it lights nothing.
        let behind = Vec3::new(-0.25, 0.5, 0.5);
        assert!((0..layout.len()).all(|i| direct(&layout, i, behind) == 0.0), "a closed wall blocks it");
    }
}
