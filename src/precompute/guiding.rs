//! Path guiding for the reference tracer: where the light a path meets came from in earlier
//! passes, learnt per region of space, and bounce directions drawn towards it.
//!
//! A level lit by one spot in one room and seen from another is lit almost wholly by paths that
//! find the lit room through a doorway; BRDF sampling finds it by chance, so such views stay
//! noisy for hundreds of samples. Following Müller, Gross & Novák (2017, "Practical Path Guiding
//! for Efficient Light-Transport Simulation"), the tracer learns the incident radiance while it
//! renders: a binary tree over space (split in the middle of a cell's longest side wherever a
//! training iteration left more than `c sqrt(passes)` path vertices in it), and in each cell a
//! histogram of incident radiance over the sphere of directions per side a surface faces
//! (cylindrical equal-area bins, in place of their adaptive quadtree). Training runs in
//! iterations of 1, 2, 4, ..., 32 passes; each iteration's vertices fill fresh histograms that
//! the next iteration samples from, so a guide only ever reflects earlier passes and every pass
//! stays an unbiased estimate. Only one path in four trains (the tracer's `TRAINING_STRIDE`), so
//! `c` is a quarter of their 12,000.
//! Bounce directions come from the one-sample mixture of the BRDF and the guide, half each
//! (their `alpha` = 0.5), weighted by the mixture's density; a cell without data falls back to the
//! BRDF alone. A guide keeps a tenth of uniform density, so one bright record cannot make it
//! blind elsewhere.

use glam::Vec3;

/// Histogram columns (azimuth) and rows (cosine of the polar angle), world space.
const PHI_BINS: usize = 32;
const Z_BINS: usize = 16;
/// Bins of a cell's histogram.
pub const BINS: usize = PHI_BINS * Z_BINS;
/// Solid angle of one bin (the mapping is equal-area).
const BIN_SOLID_ANGLE: f32 = 4.0 * std::f32::consts::PI / BINS as f32;
/// Share of a guide's density spread uniformly over the sphere.
const UNIFORM_SHARE: f32 = 0.1;
/// Share of bounces drawn from the guide where a cell has one (Müller et al.'s alpha).
pub const GUIDE_SHARE: f32 = 0.5;
/// Vertices per cell (times the square root of the iteration's passes) above which a cell is
/// split for the next iteration: Müller et al.'s c (12,000) over the four paths per training
/// path.
const SPLIT_THRESHOLD: f64 = 3_000.0;
/// Deepest a cell may lie in the tree.
const MAX_DEPTH: u32 = 24;
/// Passes after which training stops (iterations of 1, 2, ..., 32 passes).
pub const TRAINING_PASSES: u32 = 63;

/// The azimuths where columns begin, as unit vectors (`-pi + k 2 pi / PHI_BINS`).
static COLUMN_STARTS: std::sync::LazyLock<[(f32, f32); PHI_BINS]> = std::sync::LazyLock::new(|| {
    std::array::from_fn(|k| {
        let phi = (k as f32 / PHI_BINS as f32 - 0.5) * 2.0 * std::f32::consts::PI;
        (phi.cos(), phi.sin())
    })
});

/// The histogram bin of world direction `d` (unit). The column comes from four half-plane
/// tests against the columns' starting azimuths (no arc tangent: this runs at every bounce).
pub fn bin_of(d: Vec3) -> usize {
    let z = ((d.z + 1.0) * 0.5 * Z_BINS as f32) as usize;
    let starts = &*COLUMN_STARTS;
    // Azimuths below 0 (y < 0) take the first half of the columns; within a half, a direction
    // lies past a column's start when it is counter-clockwise of it.
    let (mut lo, mut hi) = if d.y < 0.0 { (0, PHI_BINS / 2) } else { (PHI_BINS / 2, PHI_BINS) };
    while hi - lo > 1 {
        let mid = (lo + hi) / 2;
        let (c, s) = starts[mid];
        if c * d.y - s * d.x >= 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    z.min(Z_BINS - 1) * PHI_BINS + lo
}

/// Which way a surface faces, as one of six classes (the axis of its normal's largest
/// component, and its sign): each cell learns a histogram per class, so the two sides of a wall
/// that share a cell do not mix their light (levels are mostly axis-aligned).
pub const SIDES: usize = 6;
pub fn side_of(n: Vec3) -> usize {
    let axis = n.abs().max_position();
    2 * axis + usize::from(n[axis] < 0.0)
}

/// The direction at `(u, v)` in [0, 1)^2 inside bin `bin`.
fn direction_in(bin: usize, u: f32, v: f32) -> Vec3 {
    let (row, col) = (bin / PHI_BINS, bin % PHI_BINS);
    let z = ((row as f32 + u) / Z_BINS as f32) * 2.0 - 1.0;
    let phi = ((col as f32 + v) / PHI_BINS as f32 - 0.5) * 2.0 * std::f32::consts::PI;
    let r = (1.0 - z * z).max(0.0).sqrt();
    Vec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// A node of the spatial tree: an inner node splits `axis` at `split` into the nodes at
/// `child` and `child + 1`; a leaf (`axis` = 3) is cell `child`.
#[derive(Clone, Copy, Debug)]
struct Node {
    axis: u32,
    split: f32,
    child: u32,
}

const LEAF: u32 = 3;

/// The spatial binary tree and each cell's box.
#[derive(Clone, Debug)]
struct Tree {
    nodes: Vec<Node>,
    boxes: Vec<(Vec3, Vec3)>,
    root: (Vec3, Vec3),
    /// A grid over the root box: per voxel, the deepest node whose region holds the whole
    /// voxel, where lookups start (a descent from the root is a dozen dependent loads, and
    /// every bounce looks its cell up).
    starts: Vec<u32>,
    dims: [usize; 3],
    voxels_per_unit: Vec3,
}

/// Voxels of the lookup grid along the root box's longest side.
const GRID: usize = 32;

impl Tree {
    fn single(lo: Vec3, hi: Vec3) -> Self {
        let nodes = vec![Node { axis: LEAF, split: 0.0, child: 0 }];
        Self::with_grid(nodes, vec![(lo, hi)], (lo, hi))
    }

    /// The tree over `nodes` and its cells' `boxes`, with its lookup grid over `root`.
    fn with_grid(nodes: Vec<Node>, boxes: Vec<(Vec3, Vec3)>, root: (Vec3, Vec3)) -> Self {
        let extent = (root.1 - root.0).max(Vec3::splat(1e-6));
        let voxel = extent.max_element() / GRID as f32;
        let dims = (extent / voxel).ceil().as_uvec3().to_array().map(|d| (d as usize).clamp(1, GRID));
        let voxels_per_unit = Vec3::new(dims[0] as f32, dims[1] as f32, dims[2] as f32) / extent;
        let mut tree = Self { nodes, boxes, root, starts: Vec::new(), dims, voxels_per_unit };
        let size = extent / Vec3::new(dims[0] as f32, dims[1] as f32, dims[2] as f32);
        let mut starts = Vec::with_capacity(dims[0] * dims[1] * dims[2]);
        for z in 0..dims[2] {
            for y in 0..dims[1] {
                for x in 0..dims[0] {
                    let lo = root.0 + Vec3::new(x as f32, y as f32, z as f32) * size;
                    starts.push(tree.start(lo - size * 1e-3, lo + size * 1.001));
                }
            }
        }
        tree.starts = starts;
        tree
    }

    /// The deepest node whose every point of the box `lo`-`hi` descends through.
    fn start(&self, lo: Vec3, hi: Vec3) -> u32 {
        let mut at = 0;
        loop {
            let n = self.nodes[at as usize];
            if n.axis == LEAF {
                return at;
            }
            let axis = n.axis as usize;
            if hi[axis] < n.split {
                at = n.child;
            } else if lo[axis] >= n.split {
                at = n.child + 1;
            } else {
                return at;
            }
        }
    }

    /// The cell holding `p` (points outside the root box go to the nearest cell).
    fn cell(&self, p: Vec3) -> usize {
        let v = ((p - self.root.0) * self.voxels_per_unit).max(Vec3::ZERO);
        let [x, y, z] = [0, 1, 2].map(|a| (v[a] as usize).min(self.dims[a] - 1));
        let mut n = self.nodes[self.starts[(z * self.dims[1] + y) * self.dims[0] + x] as usize];
        while n.axis != LEAF {
            let right = p[n.axis as usize] >= n.split;
            n = self.nodes[n.child as usize + usize::from(right)];
        }
        n.child as usize
    }

    /// A copy in which every cell that held more than `threshold` vertices (`counts`) is split
    /// in the middle of its longest side, recursively, each half assumed to hold half.
    fn refined(&self, counts: &[u64], threshold: f64) -> Self {
        let mut out = Self {
            nodes: vec![Node { axis: LEAF, split: 0.0, child: 0 }],
            boxes: Vec::new(),
            root: self.root,
            starts: Vec::new(),
            dims: self.dims,
            voxels_per_unit: self.voxels_per_unit,
        };
        self.copy_into(&mut out, 0, 0, counts, threshold, 0);
        Self::with_grid(out.nodes, out.boxes, self.root)
    }

    fn copy_into(&self, out: &mut Self, from: usize, to: usize, counts: &[u64], threshold: f64, depth: u32) {
        let n = self.nodes[from];
        if n.axis != LEAF {
            let child = out.nodes.len();
            out.nodes.extend([Node { axis: LEAF, split: 0.0, child: 0 }; 2]);
            out.nodes[to] = Node { axis: n.axis, split: n.split, child: child as u32 };
            self.copy_into(out, n.child as usize, child, counts, threshold, depth + 1);
            self.copy_into(out, n.child as usize + 1, child + 1, counts, threshold, depth + 1);
            return;
        }
        let cell = n.child as usize;
        split_cell(out, to, self.boxes[cell], counts[cell] as f64, threshold, depth);
    }
}

/// Makes node `to` of `out` a cell over `bounds`, or splits it while `count` exceeds `threshold`.
fn split_cell(out: &mut Tree, to: usize, bounds: (Vec3, Vec3), count: f64, threshold: f64, depth: u32) {
    let (lo, hi) = bounds;
    if count <= threshold || depth >= MAX_DEPTH {
        out.nodes[to] = Node { axis: LEAF, split: 0.0, child: out.boxes.len() as u32 };
        out.boxes.push(bounds);
        return;
    }
    let axis = (hi - lo).max_position();
    let split = 0.5 * (lo[axis] + hi[axis]);
    let child = out.nodes.len();
    out.nodes.extend([Node { axis: LEAF, split: 0.0, child: 0 }; 2]);
    out.nodes[to] = Node { axis: axis as u32, split, child: child as u32 };
    let (mut left_hi, mut right_lo) = (hi, lo);
    left_hi[axis] = split;
    right_lo[axis] = split;
    split_cell(out, child, (lo, left_hi), count * 0.5, threshold, depth + 1);
    split_cell(out, child + 1, (right_lo, hi), count * 0.5, threshold, depth + 1);
}

/// One path vertex's training record: its cell and side's histogram (`cell * SIDES + side`),
/// the bin its bounce went into and its estimate of the bin's integral of incident radiance
/// (luminance over the bounce's density).
#[derive(Clone, Copy, Debug)]
pub struct Record {
    histogram: u32,
    bin: u16,
    value: f32,
}

/// A cell's learnt directional distribution: each bin's probability and the rows' cumulative
/// probabilities (a draw picks a row, then walks its 32 columns: a few cache lines a bounce).
#[derive(Clone, Debug)]
pub struct Histogram {
    probability: [f32; BINS],
    rows: [f32; Z_BINS],
}

impl Histogram {
    /// From summed bin estimates; `None` if they hold no light.
    fn new(sums: &[f32]) -> Option<Self> {
        let total: f64 = sums.iter().map(|&s| f64::from(s)).sum();
        if !(total > 0.0 && total.is_finite()) {
            return None;
        }
        let mut probability = [0.0f32; BINS];
        for (p, s) in probability.iter_mut().zip(sums) {
            *p = (f64::from(1.0 - UNIFORM_SHARE) * f64::from(*s) / total + f64::from(UNIFORM_SHARE) / BINS as f64)
                as f32;
        }
        let mut rows = [0.0f32; Z_BINS];
        let mut acc = 0.0f32;
        for (r, row) in rows.iter_mut().zip(probability.chunks(PHI_BINS)) {
            acc += row.iter().sum::<f32>();
            *r = acc;
        }
        // The last row ends the distribution, whatever the rounding.
        rows[Z_BINS - 1] = f32::INFINITY;
        Some(Self { probability, rows })
    }

    /// Density per steradian of direction `d`.
    pub fn pdf(&self, d: Vec3) -> f32 {
        self.probability[bin_of(d)] * (1.0 / BIN_SOLID_ANGLE)
    }

    /// A direction drawn with two uniform numbers: `u` picks the row, then (rescaled) the
    /// column and the height within the bin; `v` the azimuth within it.
    pub fn sample(&self, u: f32, v: f32) -> Vec3 {
        let row = self.rows.partition_point(|&c| c <= u).min(Z_BINS - 1);
        let start = if row == 0 { 0.0 } else { self.rows[row - 1] };
        let mut left = u - start;
        let columns = &self.probability[row * PHI_BINS..(row + 1) * PHI_BINS];
        let mut col = 0;
        while col + 1 < PHI_BINS && left >= columns[col] {
            left -= columns[col];
            col += 1;
        }
        let within = (left / columns[col]).clamp(0.0, 1.0 - f32::EPSILON);
        direction_in(row * PHI_BINS + col, within, v)
    }

    #[cfg(test)]
    fn bin_probability(&self, bin: usize) -> f32 {
        self.probability[bin]
    }
}

/// What bounces sample from: the tree and each cell's histogram per side (`None`: no light learnt
/// there).
#[derive(Clone, Debug)]
pub struct Guide {
    tree: Tree,
    /// Per cell and side, its histogram's index in `histograms` ([`NONE`]: no light learnt).
    index: Vec<u32>,
    histograms: Vec<Histogram>,
}

/// No histogram.
const NONE: u32 = u32::MAX;

/// The distribution a shading point samples from, if its cell learnt one.
pub type CellGuide<'a> = Option<&'a Histogram>;

impl Guide {
    /// The distribution of the cell holding `p` for surfaces facing `ng`, if it learnt any light.
    pub fn at(&self, p: Vec3, ng: Vec3) -> CellGuide<'_> {
        self.histograms.get(self.index[self.tree.cell(p) * SIDES + side_of(ng)] as usize)
    }

    /// Cells of the tree.
    pub fn cells(&self) -> usize {
        self.tree.boxes.len()
    }
}

/// One training iteration: the tree its records go into and their sums.
#[derive(Clone, Debug)]
pub struct Training {
    tree: Tree,
    /// Per cell and side, where its bins' sums start in `sums` (in bins; [`NONE`]: no record
    /// yet). Only the sides that records reach hold sums, so the sums stay in cache.
    slots: Vec<u32>,
    sums: Vec<f32>,
    counts: Vec<u64>,
    /// Passes this iteration spans, and those added so far.
    passes: u32,
    done: u32,
}

impl Training {
    /// The first iteration (one pass) over the box `lo`-`hi`, one cell.
    pub fn first(lo: Vec3, hi: Vec3) -> Self {
        Self::over(Tree::single(lo, hi), 1)
    }

    fn over(tree: Tree, passes: u32) -> Self {
        let n = tree.boxes.len();
        Self { tree, slots: vec![NONE; n * SIDES], sums: Vec::new(), counts: vec![0; n], passes, done: 0 }
    }

    /// The record of a bounce at `p` (geometric normal `ng`) along `l` with its estimate
    /// `value` of the bin's integral of incident radiance.
    pub fn record(&self, p: Vec3, ng: Vec3, l: Vec3, value: f32) -> Record {
        let cell = self.tree.cell(p);
        let value = if value.is_finite() { value.max(0.0) } else { 0.0 };
        Record { histogram: (cell * SIDES + side_of(ng)) as u32, bin: bin_of(l) as u16, value }
    }

    /// Adds one pass's records (in a fixed order, so a seed gives one image).
    pub fn add(&mut self, records: &[Record]) {
        for r in records {
            self.counts[r.histogram as usize / SIDES] += 1;
            if r.value <= 0.0 {
                continue;
            }
            let slot = &mut self.slots[r.histogram as usize];
            if *slot == NONE {
                *slot = (self.sums.len() / BINS) as u32;
                self.sums.resize(self.sums.len() + BINS, 0.0);
            }
            self.sums[*slot as usize * BINS + usize::from(r.bin)] += r.value;
        }
    }

    /// Counts one more pass; at the iteration's last, returns the guide it learnt and the next
    /// iteration (with twice the passes, over a tree split where this one held many records).
    pub fn finish_pass(&mut self) -> Option<(Guide, Self)> {
        self.done += 1;
        if self.done < self.passes {
            return None;
        }
        let mut histograms = Vec::new();
        let index = self
            .slots
            .iter()
            .map(|&slot| {
                let start = slot as usize * BINS;
                let sums = (slot != NONE).then(|| &self.sums[start..start + BINS]);
                sums.and_then(Histogram::new).map_or(NONE, |h| {
                    histograms.push(h);
                    (histograms.len() - 1) as u32
                })
            })
            .collect();
        let guide = Guide { tree: self.tree.clone(), index, histograms };
        let threshold = SPLIT_THRESHOLD * f64::from(self.passes).sqrt();
        let next = Self::over(self.tree.refined(&self.counts, threshold), self.passes * 2);
        Some((guide, next))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::precompute::rng::Pcg32;

    fn uniform_sphere(rng: &mut Pcg32) -> Vec3 {
        let z = rng.next_f32() * 2.0 - 1.0;
        let phi = rng.next_f32() * std::f32::consts::TAU;
        let r = (1.0 - z * z).max(0.0).sqrt();
        Vec3::new(r * phi.cos(), r * phi.sin(), z)
    }

    #[test]
    fn every_bin_maps_back_to_itself() {
        let mut rng = Pcg32::new(1, 2, 3);
        for bin in 0..BINS {
            for _ in 0..8 {
                let d = direction_in(bin, rng.next_f32(), rng.next_f32());
                assert!((d.length() - 1.0).abs() < 1e-4);
                assert_eq!(bin_of(d), bin, "{d}");
            }
        }
    }

    /// A histogram learnt from a peaked field: its density integrates to one over the sphere,
    /// its samples follow its density, and the peak's bin gets most of them.
    #[test]
    fn a_learnt_histogram_is_a_density_its_samples_follow() {
        let peak = Vec3::new(0.3, -0.5, 0.8).normalize();
        let mut sums = vec![0.0f32; BINS];
        let mut rng = Pcg32::new(4, 5, 6);
        for _ in 0..50_000 {
            let d = uniform_sphere(&mut rng);
            let radiance = if d.dot(peak) > 0.95 { 10.0 } else { 0.1 };
            sums[bin_of(d)] += radiance * 4.0 * std::f32::consts::PI;
        }
        let h = Histogram::new(&sums).expect("light learnt");
        // The density integrates to one (uniform directions, estimate of the integral).
        let n = 200_000;
        let integral: f64 = (0..n).map(|_| f64::from(h.pdf(uniform_sphere(&mut rng)))).sum::<f64>() / n as f64
            * 4.0
            * std::f64::consts::PI;
        assert!((integral - 1.0).abs() < 0.02, "integral {integral}");
        // Samples land in each bin as often as its probability says.
        let mut hits = vec![0u32; BINS];
        for _ in 0..n {
            hits[bin_of(h.sample(rng.next_f32(), rng.next_f32()))] += 1;
        }
        for (bin, &count) in hits.iter().enumerate() {
            let expect = f64::from(h.bin_probability(bin)) * n as f64;
            let got = f64::from(count);
            assert!((got - expect).abs() < 5.0 * expect.sqrt() + 3.0, "bin {bin}: {got} vs {expect}");
        }
        assert!(h.pdf(peak) > 20.0 * h.pdf(-peak), "peak {} vs away {}", h.pdf(peak), h.pdf(-peak));
    }

    #[test]
    fn a_cell_without_light_has_no_guide() {
        assert!(Histogram::new(&[0.0; BINS]).is_none());
    }

    /// A busy cell is split for the next iteration, a quiet one is not, and lookups find the
    /// cell whose box holds the point.
    #[test]
    fn busy_cells_split_and_points_find_their_cell() {
        let mut t = Training::first(Vec3::ZERO, Vec3::new(4.0, 1.0, 1.0));
        let records: Vec<Record> = (0..40_000)
            .map(|i| t.record(Vec3::new(0.5 + (i % 10) as f32 * 0.01, 0.5, 0.5), Vec3::Y, Vec3::X, 1.0))
            .collect();
        t.add(&records);
        let (guide, next) = t.finish_pass().expect("a one-pass iteration");
        assert_eq!(guide.cells(), 1);
        assert!(guide.at(Vec3::new(3.0, 0.2, 0.2), Vec3::Y).is_some());
        assert!(guide.at(Vec3::new(3.0, 0.2, 0.2), Vec3::NEG_Y).is_none(), "the other side learnt nothing");
        assert!(next.tree.boxes.len() >= 4, "{} cells", next.tree.boxes.len());
        for p in [Vec3::new(0.1, 0.9, 0.3), Vec3::new(3.9, 0.1, 0.7), Vec3::new(2.0, 0.5, 0.5)] {
            let (lo, hi) = next.tree.boxes[next.tree.cell(p)];
            assert!(p.cmpge(lo).all() && p.cmple(hi).all(), "{p} outside {lo}-{hi}");
        }
        assert_eq!(next.passes, 2);
    }
}
