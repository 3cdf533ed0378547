//! Which of a level's block texels stand for a world surface point: the CPU twin of the MRT
//! apply pass's choice (`mrt_apply.wgsl`: the block nearest to the point lifted 5 cm along its
//! normal, that block's side whose inward normal is closest to the point's, the orthographic
//! projection onto the side's canonical face, bilinear between texel centres). The DRT
//! operators use it to say whose light a ray that clutter blocks would have brought, so the
//! light they subtract is the light the runtime would have shown.

use glam::Vec3;

use crate::precompute::mrt::level::{Block, Level};
use crate::precompute::mrt::shape::{Face, Layout};

/// A level's block texels, block after block as `render::gi::mrt::pack` lays them out.
pub struct TexelMap {
    blocks: Vec<Block>,
    layouts: Vec<Layout>,
    first: Vec<usize>,
    total: usize,
}

/// Distance from `q` to the box `lo .. hi` (0 inside).
fn box_distance(lo: Vec3, hi: Vec3, q: Vec3) -> f32 {
    (lo - q).max(q - hi).max(Vec3::ZERO).length()
}

impl TexelMap {
    /// The map of `level` at `res` texels per face side.
    pub fn new(level: &Level, res: usize) -> Self {
        let layouts: Vec<Layout> = level.blocks.iter().map(|b| Layout::new(b.shape, res)).collect();
        let mut first = Vec::with_capacity(layouts.len());
        let mut total = 0;
        for l in &layouts {
            first.push(total);
            total += l.len();
        }
        Self { blocks: level.blocks.clone(), layouts, first, total }
    }

    /// Block texels in all.
    pub fn len(&self) -> usize {
        self.total
    }

    /// Whether the level has no texels.
    pub fn is_empty(&self) -> bool {
        self.total == 0
    }

    /// Block texel `i`'s block, face and in-plane texel (s, t).
    pub fn texel(&self, i: usize) -> Option<(usize, Face, usize, usize)> {
        let x = self.first.partition_point(|&f| f <= i).checked_sub(1)?;
        let layout = self.layouts.get(x)?;
        let j = i - self.first[x];
        (j < layout.len()).then(|| {
            let (face, (s, t), _, _) = layout.sample(j);
            (x, face, s, t)
        })
    }

    /// The global index of texel (s, t) of `face` of block `x`, if the face is present.
    pub fn index(&self, x: usize, face: Face, s: usize, t: usize) -> Option<usize> {
        let layout = self.layouts.get(x)?;
        let res = layout.res;
        (s < res && t < res).then_some(())?;
        Some(self.first[x] + layout.face_start(face)? + t * res + s)
    }

    /// The block whose box is nearest to `q` (the first of equals).
    fn nearest_block(&self, q: Vec3) -> Option<usize> {
        let mut best: Option<(usize, f32)> = None;
        for (i, b) in self.blocks.iter().enumerate() {
            let d = box_distance(b.origin, b.origin + b.size, q);
            if best.is_none_or(|(_, bd)| d < bd) {
                best = Some((i, d));
            }
        }
        best.map(|(i, _)| i)
    }

    /// The block and its texel range a point belongs to (tests, the inspector).
    pub fn block_of(&self, p: Vec3, n: Vec3) -> Option<(usize, std::ops::Range<usize>)> {
        let x = self.nearest_block(p + n * 0.05)?;
        Some((x, self.first[x]..self.first[x] + self.layouts[x].len()))
    }

    /// The block texels (global index, weight) the runtime reads for a surface at `p` with unit
    /// normal `n`; `None` where it reads no face texels (a side that is open, or partly open:
    /// its light comes from the side texels).
    pub fn taps(&self, p: Vec3, n: Vec3) -> Option<[(usize, f32); 4]> {
        let x = self.nearest_block(p + n * 0.05)?;
        let block = &self.blocks[x];
        let lp = block.local_point(p);
        let mut best = (Face::NegX, f32::MIN);
        for w in Face::ALL {
            let f = block.local_face(w);
            let along = lp[f.axis()];
            let plane = if f.positive() { 1.0 - along } else { along };
            let c = n.dot(w.inward_normal()) - 0.25 * plane.clamp(0.0, 1.0);
            if c > best.1 {
                best = (w, c);
            }
        }
        let face = block.local_face(best.0);
        let (a, b) = face.plane_axes();
        let taps = self.layouts[x].bilinear(face, lp[a], lp[b])?;
        Some(taps.map(|(i, w)| (self.first[x] + i, w)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::precompute::mrt::shape::Shape;

    #[test]
    fn a_floor_point_reads_the_floor_texel_under_it() {
        let block = Block { shape: Shape::Closed, origin: Vec3::ZERO, size: Vec3::new(4.0, 3.0, 4.0), turns: 0 };
        let level = Level::new(vec![block]);
        let map = TexelMap::new(&level, 16);
        let layout = Layout::new(block.shape, 16);
        // Floor (-y) texel (s, t) = (x, z) = (2, 13) has its centre at x = 2.5 / 16 * 4.
        let p = Vec3::new(2.5 / 16.0 * 4.0, 0.0, 13.5 / 16.0 * 4.0);
        let taps = map.taps(p, Vec3::Y).expect("the floor is present");
        let want = layout.face_start(Face::NegY).expect("floor") + 13 * 16 + 2;
        assert_eq!(taps[0].0, want);
        assert!((taps[0].1 - 1.0).abs() < 1e-4, "{taps:?}");
        // The same point seen as a wall's (normal +x) reads the -x wall.
        let taps = map.taps(Vec3::new(0.0, 1.5, 2.0), Vec3::X).expect("the wall is present");
        let start = layout.face_start(Face::NegX).expect("wall");
        assert!(taps.iter().all(|(i, _)| (start..start + 256).contains(i)), "{taps:?}");
    }
}
