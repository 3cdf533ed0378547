//! Test levels carved out of solid rock on a 0.1 m lattice: air boxes (rooms, corridors, doorways,
//! stairwells) less solid boxes (pillars), the boundary between air and rock as merged quads
//! facing the air. Any shape a level designer builds is a few boxes; walls between rooms are as
//! thick as the rock left between their air.

use glam::{IVec3, Vec3};

/// The lattice step (m).
const STEP: f32 = 0.1;

/// A level under construction.
#[derive(Default)]
pub struct Carve {
    /// Boxes of air (lattice min, max) and whether each is air (true) or rock put back (false).
    boxes: Vec<(IVec3, IVec3, bool)>,
}

fn lattice(p: Vec3) -> IVec3 {
    (p / STEP).round().as_ivec3()
}

impl Carve {
    /// Carves air out of `lo .. hi` (m).
    pub fn air(mut self, lo: [f32; 3], hi: [f32; 3]) -> Self {
        self.boxes.push((lattice(Vec3::from(lo)), lattice(Vec3::from(hi)), true));
        self
    }

    /// Puts rock back in `lo .. hi` (m): a pillar.
    pub fn rock(mut self, lo: [f32; 3], hi: [f32; 3]) -> Self {
        self.boxes.push((lattice(Vec3::from(lo)), lattice(Vec3::from(hi)), false));
        self
    }

    /// The air/rock boundary as triangles facing the air, coplanar faces merged into rectangles.
    pub fn tris(&self) -> Vec<[Vec3; 3]> {
        let lo = self.boxes.iter().fold(IVec3::MAX, |a, b| a.min(b.0)) - IVec3::ONE;
        let hi = self.boxes.iter().fold(IVec3::MIN, |a, b| a.max(b.1)) + IVec3::ONE;
        let dims = hi - lo;
        let index = |c: IVec3| ((c.y * dims.z + c.z) * dims.x + c.x) as usize;
        let mut air = vec![false; (dims.x * dims.y * dims.z) as usize];
        for (a, b, is_air) in &self.boxes {
            for y in a.y..b.y {
                for z in a.z..b.z {
                    for x in a.x..b.x {
                        air[index(IVec3::new(x, y, z) - lo)] = *is_air;
                    }
                }
            }
        }
        let at = |c: IVec3| c.cmpge(IVec3::ZERO).all() && c.cmplt(dims).all() && air[index(c)];
        let mut tris = Vec::new();
        for axis in 0..3 {
            let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
            for p in 0..=dims[axis] {
                for facing_pos in [false, true] {
                    // The face on plane p whose air lies at p (normal +axis) or at p - 1 (-axis).
                    let mut mask = vec![false; (dims[u] * dims[v]) as usize];
                    for j in 0..dims[v] {
                        for i in 0..dims[u] {
                            let mut c = IVec3::ZERO;
                            (c[axis], c[u], c[v]) = (p, i, j);
                            let mut below = c;
                            below[axis] -= 1;
                            let (front, back) = if facing_pos { (c, below) } else { (below, c) };
                            mask[(j * dims[u] + i) as usize] = at(front) && !at(back);
                        }
                    }
                    for (i0, j0, i1, j1) in rectangles(&mut mask, dims[u], dims[v]) {
                        let corner = |i: i32, j: i32| {
                            let mut c = Vec3::ZERO;
                            (c[axis], c[u], c[v]) = (p as f32, i as f32, j as f32);
                            (c + lo.as_vec3()) * STEP
                        };
                        let (a, b, c, d) = (corner(i0, j0), corner(i1, j0), corner(i1, j1), corner(i0, j1));
                        // (u x v) is +axis: counter-clockwise a b c faces +axis.
                        if facing_pos {
                            tris.extend([[a, b, c], [a, c, d]]);
                        } else {
                            tris.extend([[a, c, b], [a, d, c]]);
                        }
                    }
                }
            }
        }
        tris
    }
}

/// Greedy maximal rectangles covering `mask` (w x h, row-major), cleared as they are taken.
fn rectangles(mask: &mut [bool], w: i32, h: i32) -> Vec<(i32, i32, i32, i32)> {
    let mut out = Vec::new();
    for j in 0..h {
        for i in 0..w {
            if !mask[(j * w + i) as usize] {
                continue;
            }
            let mut i1 = i;
            while i1 < w && mask[(j * w + i1) as usize] {
                i1 += 1;
            }
            let mut j1 = j + 1;
            while j1 < h && (i..i1).all(|k| mask[(j1 * w + k) as usize]) {
                j1 += 1;
            }
            for jj in j..j1 {
                for k in i..i1 {
                    mask[(jj * w + k) as usize] = false;
                }
            }
            out.push((i, j, i1, j1));
        }
    }
    out
}
