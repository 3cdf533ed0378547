//! A world-space grid of the voxels the scene's surfaces pass through, and a segment test
//! against it: visibility for what a view's own voxels cannot answer. `sshgi` marches the
//! segments of its hidden senders (surfaces the camera's position does not see) through the
//! view's voxel columns; a segment that leaves the view's frustum there has no columns for the
//! part outside, and blocking it outright cut the light of a room beside or behind the camera
//! (`render/gi/sshgi/world_grid.rs` uploads this grid; `sshgi_world_grid.wgsl` is the GPU's copy
//! of [`SurfaceVoxels::blocked`]).
//!
//! Every voxel a triangle overlaps is marked (the separating-axis test of Akenine-Möller 2001),
//! so the grid is conservative: a segment that crosses a surface crosses one of its voxels, and
//! no wall is thin enough to leak. What it costs is false shadow within a voxel of a surface,
//! which the segment test pays back near its ends by skipping the voxels within a voxel and a
//! half of them.

use std::sync::atomic::{AtomicU32, Ordering};

use glam::{IVec3, UVec3, Vec3};
use rayon::prelude::*;

use crate::scene::Scene;

/// The smallest voxel (m): a level of a few metres needs no finer grid than this.
const MIN_VOXEL: f32 = 0.02;

/// How far (voxels) [`SurfaceVoxels::blocked`] moves a segment's ends along their normals.
pub const OFF_SURFACE: f32 = 1.5;

/// How far (voxels) from either end [`SurfaceVoxels::blocked`] leaves voxels out.
pub const END_SKIP: f32 = 0.5;

/// Voxels along a brick's side: the segment test walks the bricks and goes down to the voxels
/// only in bricks that hold a surface (the air of a room is crossed a brick at a time).
pub const BRICK: u32 = 4;

/// The grid's two levels.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Level {
    Voxel,
    Brick,
}

/// The surface voxels of a scene.
#[derive(Clone, Debug, PartialEq)]
pub struct SurfaceVoxels {
    /// The grid's minimum corner (world, m).
    pub origin: Vec3,
    /// The voxel's side (m).
    pub h: f32,
    /// Voxels along x, y, z.
    pub dims: UVec3,
    /// One bit per voxel, x fastest, then y, then z (bit i in word i / 32); from word
    /// `bricks_at` on, one bit per brick of [`BRICK`]^3 voxels, set where any of its voxels is.
    pub words: Vec<u32>,
    /// The first word of the bricks' bits.
    pub bricks_at: usize,
}

impl SurfaceVoxels {
    /// The grid over `tris` with `along` voxels on its longest side (at least [`MIN_VOXEL`]
    /// each), padded by one voxel, with every voxel a triangle overlaps marked. `None` without
    /// triangles.
    pub fn build(tris: &[[Vec3; 3]], along: u32) -> Option<Self> {
        let (lo, hi) = tris
            .iter()
            .flatten()
            .fold((Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)), |(a, b), p| (a.min(*p), b.max(*p)));
        if tris.is_empty() || !lo.is_finite() || !hi.is_finite() {
            return None;
        }
        let h = ((hi - lo).max_element() / along.max(1) as f32).max(MIN_VOXEL);
        let origin = lo - Vec3::splat(h);
        let dims = (((hi - lo) / h).ceil().as_uvec3() + UVec3::splat(2)).max(UVec3::ONE);
        let count = dims.x as usize * dims.y as usize * dims.z as usize;
        let bricks = dims.map(|n| n.div_ceil(BRICK));
        let bricks_at = count.div_ceil(32);
        let brick_count = bricks.x as usize * bricks.y as usize * bricks.z as usize;
        let mut grid = Self { origin, h, dims, words: Vec::new(), bricks_at };
        // The triangles are marked in parallel into shared words (an OR commutes: the grid is
        // the same in any order).
        let words: Vec<AtomicU32> = (0..bricks_at + brick_count.div_ceil(32)).map(|_| AtomicU32::new(0)).collect();
        // Work items are a triangle's rows of voxel columns, so a large floor is shared out.
        tris.par_iter().flat_map_iter(|t| grid.rows(t).map(move |a| (t, a))).for_each(|(t, a)| grid.mark(t, a, &words));
        grid.words = words.into_iter().map(AtomicU32::into_inner).collect();
        Some(grid)
    }

    /// The grid of `scene`'s rendered objects ([`Self::build`]).
    pub fn of_scene(scene: &Scene, along: u32) -> Option<Self> {
        Self::build(&world_triangles(scene), along)
    }

    /// The cells along x, y, z of `level`.
    fn cells(&self, level: Level) -> UVec3 {
        match level {
            Level::Voxel => self.dims,
            Level::Brick => self.dims.map(|n| n.div_ceil(BRICK)),
        }
    }

    /// The bit index of cell `c` of `level` (inside the grid).
    fn index(&self, c: UVec3, level: Level) -> usize {
        let n = self.cells(level);
        let base = if level == Level::Brick { 32 * self.bricks_at } else { 0 };
        base + (c.z as usize * n.y as usize + c.y as usize) * n.x as usize + c.x as usize
    }

    /// Whether cell `c` of `level` holds a surface (outside the grid: no).
    fn cell(&self, c: IVec3, level: Level) -> bool {
        if c.cmplt(IVec3::ZERO).any() || c.as_uvec3().cmpge(self.cells(level)).any() {
            return false;
        }
        let i = self.index(c.as_uvec3(), level);
        self.words[i / 32] >> (i % 32) & 1 == 1
    }

    /// Whether voxel `c` holds a surface (outside the grid: no).
    pub fn get(&self, c: IVec3) -> bool {
        self.cell(c, Level::Voxel)
    }

    /// Marks the voxels triangle `t` overlaps in row `a` of its columns ([`Self::rows`]), and
    /// their bricks.
    fn mark(&self, t: &[Vec3; 3], a: i32, words: &[AtomicU32]) {
        let Some((lo, hi)) = self.bounds(t) else { return };
        // A hair over half a voxel: a plane on a voxel boundary marks the voxels on both sides,
        // never neither (rounding).
        let half = Vec3::splat(0.5 * self.h * (1.0 + 1e-3));
        // Only the voxels of each column along the normal's largest axis that the plane can
        // reach are tested: the bounding box of a large slanted triangle holds n^3 voxels, the
        // plane crosses n^2 of them.
        let (n, (k, u, v)) = Self::axes(t);
        let spread = Self::plane_spread(t, n, k, half.x);
        for b in lo[v]..=hi[v] {
            let (k_lo, k_hi) = self.plane_reach(t[0], n, (k, u, v), (a, b), spread);
            for c_k in k_lo.max(lo[k])..=k_hi.min(hi[k]) {
                let mut c = IVec3::ZERO;
                (c[k], c[u], c[v]) = (c_k, a, b);
                let centre = self.origin + (c.as_vec3() + 0.5) * self.h;
                if triangle_overlaps_box(t, centre, half) {
                    self.set(c.as_uvec3(), words);
                }
            }
        }
    }

    /// Triangle `t`'s normal (unnormalised) and its axes: k the normal's largest, u and v the
    /// other two.
    fn axes(t: &[Vec3; 3]) -> (Vec3, (usize, usize, usize)) {
        let n = (t[1] - t[0]).cross(t[2] - t[0]);
        let k = n.abs().max_position();
        (n, (k, (k + 1) % 3, (k + 2) % 3))
    }

    /// The rows (voxel indices along axis u of [`Self::axes`]) of triangle `t`'s columns.
    fn rows(&self, t: &[Vec3; 3]) -> impl Iterator<Item = i32> + use<> {
        let (_, (_, u, _)) = Self::axes(t);
        self.bounds(t).into_iter().flat_map(move |(lo, hi)| lo[u]..=hi[u])
    }

    /// The voxels of the bounding box of triangle `t`, clamped to the grid (`None` outside it).
    fn bounds(&self, t: &[Vec3; 3]) -> Option<(IVec3, IVec3)> {
        let lo = ((t[0].min(t[1]).min(t[2]) - self.origin) / self.h).floor().as_ivec3().max(IVec3::ZERO);
        let hi = ((t[0].max(t[1]).max(t[2]) - self.origin) / self.h).floor().as_ivec3().min(self.dims.as_ivec3() - 1);
        hi.cmpge(lo).all().then_some((lo, hi))
    }

    /// How far along axis `k` (metres) from the plane's point at a column's centre a box of half
    /// side `half` can still touch triangle `t` of normal `n`: the plane's rise over the
    /// column's square widened by `half`, plus how far the vertices lie off that plane (a
    /// triangle collinear but for rounding has a normal of noise, its vertices up to an edge's
    /// length off its plane). `n[k]` is the normal's largest component.
    fn plane_spread(t: &[Vec3; 3], n: Vec3, k: usize, half: f32) -> f32 {
        let (u, v) = ((k + 1) % 3, (k + 2) % 3);
        let off = n.dot(t[1] - t[0]).abs().max(n.dot(t[2] - t[0]).abs());
        ((n[u].abs() + n[v].abs()) * half + off) / n[k].abs() + half
    }

    /// The voxel indices along axis `k` whose boxes can touch the triangle in the column (`a`,
    /// `b`) of axes `u`, `v`: within `spread` ([`Self::plane_spread`]) of the plane through `p`
    /// of normal `n` at the column's centre, plus one voxel each way for rounding.
    fn plane_reach(
        &self,
        p: Vec3,
        n: Vec3,
        (k, u, v): (usize, usize, usize),
        (a, b): (i32, i32),
        spread: f32,
    ) -> (i32, i32) {
        if n[k] == 0.0 {
            return (i32::MIN, i32::MAX);
        }
        let centre = |axis: usize, i: i32| self.origin[axis] + (i as f32 + 0.5) * self.h;
        // On the plane: x_k = p_k - (n_u (x_u - p_u) + n_v (x_v - p_v)) / n_k.
        let at_centre = p[k] - (n[u] * (centre(u, a) - p[u]) + n[v] * (centre(v, b) - p[v])) / n[k];
        let index = |x: f32| ((x - self.origin[k]) / self.h).floor() as i32;
        (index(at_centre - spread) - 1, index(at_centre + spread) + 1)
    }

    /// Marks voxel `c` and its brick in `words` (this grid's words while it is built).
    fn set(&self, c: UVec3, words: &[AtomicU32]) {
        for (cell, level) in [(c, Level::Voxel), (c / BRICK, Level::Brick)] {
            let i = self.index(cell, level);
            words[i / 32].fetch_or(1 << (i % 32), Ordering::Relaxed);
        }
    }

    /// Whether the segment between surface points `a` and `b` (unit normals `na`, `nb`, facing
    /// the segment; zero for a point in the air) crosses a marked voxel. Each end is first moved
    /// [`OFF_SURFACE`] voxels along its normal, out of its own surface's voxels at any angle
    /// (a plane on a voxel boundary marks both sides), and the voxels within [`END_SKIP`] of
    /// either end are left out (a point near a corner, in its other surface's voxels).
    pub fn blocked(&self, a: Vec3, na: Vec3, b: Vec3, nb: Vec3) -> bool {
        let (a, b) = (a + na * (OFF_SURFACE * self.h), b + nb * (OFF_SURFACE * self.h));
        self.blocked_between(a, b, END_SKIP * self.h)
    }

    /// Whether the segment from `a` to `b` crosses a marked voxel, leaving out the voxels it
    /// is in within `skip` metres of either end. Outside the grid nothing blocks. The bricks
    /// the segment touches are walked (Amanatides-Woo), and in each brick that holds a surface
    /// the voxels it touches there: every voxel on the segment is visited.
    pub fn blocked_between(&self, a: Vec3, b: Vec3, skip: f32) -> bool {
        let len = (b - a).length();
        if len <= 2.0 * skip {
            return false;
        }
        let p = (a - self.origin) / self.h;
        let d = (b - a) / self.h;
        let Some((t0, t1)) = clip_to_box(p, d, self.dims.as_vec3()) else { return false };
        let (near, far) = (skip / len, 1.0 - skip / len);
        let everywhere = (IVec3::ZERO, self.cells(Level::Brick).as_ivec3() - 1);
        self.walk(p, d, (t0, t1), Level::Brick, everywhere, &mut |brick, ta, tb| {
            if tb <= near || ta >= far || !self.cell(brick, Level::Brick) {
                return false;
            }
            let inside = (brick * BRICK as i32, brick * BRICK as i32 + (BRICK as i32 - 1));
            self.walk(p, d, (ta, tb), Level::Voxel, inside, &mut |c, ta, tb| {
                tb > near && ta < far && self.cell(c, Level::Voxel)
            })
        })
    }

    /// Walks the cells of `level` that `p + t d` (voxel units) touches for t in `t0..t1`,
    /// starting in the cell clamped to `bounds` (inclusive), and calls `visit(cell, t in, t
    /// out)` on each until it returns true (then true).
    fn walk(
        &self,
        p: Vec3,
        d: Vec3,
        (t0, t1): (f32, f32),
        level: Level,
        bounds: (IVec3, IVec3),
        visit: &mut dyn FnMut(IVec3, f32, f32) -> bool,
    ) -> bool {
        let size = if level == Level::Brick { BRICK as f32 } else { 1.0 };
        let (q, e) = (p / size, d / size);
        let mut c = (q + e * t0).floor().as_ivec3().clamp(bounds.0, bounds.1);
        let step = IVec3::new(sign(e.x), sign(e.y), sign(e.z));
        let next_edge = c.as_vec3() + step.max(IVec3::ZERO).as_vec3();
        let inv = Vec3::new(inverse(e.x), inverse(e.y), inverse(e.z));
        let mut t_max = Vec3::new(
            if step.x == 0 { f32::MAX } else { (next_edge.x - q.x) * inv.x },
            if step.y == 0 { f32::MAX } else { (next_edge.y - q.y) * inv.y },
            if step.z == 0 { f32::MAX } else { (next_edge.z - q.z) * inv.z },
        );
        let t_delta = inv.abs();
        let mut t = t0;
        let n = self.cells(level);
        for _ in 0..n.x + n.y + n.z + 3 {
            let t_next = t_max.min_element().min(t1);
            if visit(c, t, t_next) {
                return true;
            }
            if t_next >= t1 {
                return false;
            }
            if t_max.x <= t_max.y && t_max.x <= t_max.z {
                c.x += step.x;
                t_max.x += t_delta.x;
            } else if t_max.y <= t_max.z {
                c.y += step.y;
                t_max.y += t_delta.y;
            } else {
                c.z += step.z;
                t_max.z += t_delta.z;
            }
            t = t_next;
        }
        false
    }

    /// Bytes of the bits (voxels and bricks).
    pub fn bytes(&self) -> usize {
        4 * self.words.len()
    }
}

/// The world triangles of `scene`'s rendered objects.
fn world_triangles(scene: &Scene) -> Vec<[Vec3; 3]> {
    let mut tris = Vec::new();
    for object in scene.objects().iter().filter(|o| o.is_rendered()) {
        let Some(mesh) = scene.resources().meshes.get(object.mesh) else { continue };
        let m = object.transform.matrix();
        tris.extend((0..mesh.triangle_count()).map(|t| mesh.triangle(t).map(|v| m.transform_point3(v))));
    }
    tris
}

fn sign(x: f32) -> i32 {
    if x > 0.0 {
        1
    } else if x < 0.0 {
        -1
    } else {
        0
    }
}

fn inverse(x: f32) -> f32 {
    if x == 0.0 { f32::MAX } else { 1.0 / x }
}

/// The parameter interval of `p + t d`, t in 0..1, inside the box 0..`size` (grid units).
fn clip_to_box(p: Vec3, d: Vec3, size: Vec3) -> Option<(f32, f32)> {
    let (mut t0, mut t1) = (0.0_f32, 1.0_f32);
    for k in 0..3 {
        if d[k] == 0.0 {
            if p[k] < 0.0 || p[k] > size[k] {
                return None;
            }
            continue;
        }
        let (a, b) = ((0.0 - p[k]) / d[k], (size[k] - p[k]) / d[k]);
        t0 = t0.max(a.min(b));
        t1 = t1.min(a.max(b));
    }
    (t0 <= t1).then_some((t0, t1))
}

/// Whether triangle `t` overlaps the box of `centre` and half-extent `half` (the 13 separating
/// axes: the box's three, the triangle's normal and the nine edge-by-axis crosses).
pub fn triangle_overlaps_box(t: &[Vec3; 3], centre: Vec3, half: Vec3) -> bool {
    let v = t.map(|p| p - centre);
    let e = [v[1] - v[0], v[2] - v[1], v[0] - v[2]];
    let separated = |axis: Vec3| {
        let p = v.map(|x| x.dot(axis));
        let r = half.dot(axis.abs());
        p[0].min(p[1]).min(p[2]) > r || p[0].max(p[1]).max(p[2]) < -r
    };
    if [Vec3::X, Vec3::Y, Vec3::Z].into_iter().any(separated) {
        return false;
    }
    let n = e[0].cross(e[1]);
    if n.length_squared() > 0.0 && separated(n) {
        return false;
    }
    for edge in e {
        for axis in [Vec3::X, Vec3::Y, Vec3::Z] {
            let c = edge.cross(axis);
            if c.length_squared() > 1e-20 && separated(c) {
                return false;
            }
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The two triangles of an axis-aligned rectangle `lo..hi` (one extent zero).
    fn quad(lo: Vec3, hi: Vec3) -> Vec<[Vec3; 3]> {
        let flat = (hi - lo).to_array().iter().position(|x| x.abs() < 1e-6).unwrap_or(0);
        let (u, v) = ((flat + 1) % 3, (flat + 2) % 3);
        let corner = |a: bool, b: bool| {
            let mut p = lo;
            p[u] = if a { hi[u] } else { lo[u] };
            p[v] = if b { hi[v] } else { lo[v] };
            p
        };
        vec![
            [corner(false, false), corner(true, false), corner(true, true)],
            [corner(false, false), corner(true, true), corner(false, true)],
        ]
    }

    /// The marking before columns were pruned: every voxel of the bounding box tested.
    fn mark_every_box_voxel(grid: &SurfaceVoxels, t: &[Vec3; 3], words: &[AtomicU32]) {
        let Some((lo, hi)) = grid.bounds(t) else { return };
        let half = Vec3::splat(0.5 * grid.h * (1.0 + 1e-3));
        for z in lo.z..=hi.z {
            for y in lo.y..=hi.y {
                for x in lo.x..=hi.x {
                    let c = IVec3::new(x, y, z);
                    if triangle_overlaps_box(t, grid.origin + (c.as_vec3() + 0.5) * grid.h, half) {
                        grid.set(c.as_uvec3(), words);
                    }
                }
            }
        }
    }

    #[test]
    fn pruned_columns_mark_exactly_the_voxels_every_box_voxel_marks() {
        // Random triangles of every size and slant, some slivers and some axis-aligned, in a
        // 64-voxel grid.
        let mut state = 0x9e37_79b9_u32;
        let mut rnd = || {
            state ^= state << 13;
            state ^= state >> 17;
            state ^= state << 5;
            state as f32 / u32::MAX as f32
        };
        let mut tris = Vec::new();
        for i in 0..600 {
            let a = Vec3::new(rnd(), rnd(), rnd()) * 4.0;
            let scale = [0.05, 0.5, 3.0][i % 3];
            let mut b = a + (Vec3::new(rnd(), rnd(), rnd()) - 0.5) * scale;
            let mut c = a + (Vec3::new(rnd(), rnd(), rnd()) - 0.5) * scale;
            if i % 7 == 0 {
                (b.y, c.y) = (a.y, a.y);
            }
            if i % 11 == 0 {
                c = a + (b - a) * 0.5 + Vec3::splat(1e-4);
            }
            // Collinear but for rounding: the cross product is noise.
            if i % 13 == 0 {
                c = a + (b - a) * (0.1 + 0.8 * rnd());
            }
            tris.push([a, b, c]);
        }
        let pruned = SurfaceVoxels::build(&tris, 64).expect("grid");
        let words: Vec<AtomicU32> = pruned.words.iter().map(|_| AtomicU32::new(0)).collect();
        for t in &tris {
            mark_every_box_voxel(&pruned, t, &words);
        }
        let every: Vec<u32> = words.into_iter().map(AtomicU32::into_inner).collect();
        let marked = every.iter().map(|w| w.count_ones()).sum::<u32>();
        assert!(marked > 10_000, "the test's triangles mark too little to compare: {marked}");
        assert!(pruned.words == every, "the pruned marking differs from the every-voxel marking");
    }

    #[test]
    fn a_wall_blocks_every_segment_through_it_and_none_through_its_doorway_or_beside_it() {
        // A 0.1 m thick wall in the plane x = 0 (two faces), 4 m wide and 3 m tall, with a
        // 1 x 2 m doorway at z 0.5..1.5, plus a floor at y = 0.
        let mut tris = Vec::new();
        for x in [-0.05, 0.05] {
            tris.extend(quad(Vec3::new(x, 0.0, -2.0), Vec3::new(x, 3.0, 0.5)));
            tris.extend(quad(Vec3::new(x, 0.0, 1.5), Vec3::new(x, 3.0, 2.0)));
            tris.extend(quad(Vec3::new(x, 2.0, 0.5), Vec3::new(x, 3.0, 1.5)));
        }
        tris.extend(quad(Vec3::new(-3.0, 0.0, -2.0), Vec3::new(3.0, 0.0, 2.0)));
        let grid = SurfaceVoxels::build(&tris, 96).expect("grid");
        assert!(grid.h < 0.07, "voxel {}", grid.h);
        let (up, x, no) = (Vec3::Y, Vec3::X, Vec3::ZERO);
        // Through the wall at every height and angle, between points in the air: blocked (no
        // leak, the grid is conservative).
        for i in 0..40 {
            let f = i as f32 / 39.0;
            let a = Vec3::new(-2.0, 0.3 + 2.5 * f, -1.8 + 2.0 * f);
            let b = Vec3::new(2.5, 2.7 - 2.2 * f, 0.2 - 2.0 * f);
            assert!(grid.blocked(a, no, b, no), "leak from {a} to {b}");
        }
        // Through the doorway, from one floor point to the other: open.
        assert!(!grid.blocked(Vec3::new(-2.0, 0.0, 1.0), up, Vec3::new(2.0, 0.0, 1.0), up));
        assert!(!grid.blocked(Vec3::new(-2.0, 1.0, 0.8), no, Vec3::new(2.0, 1.2, 1.2), no));
        // Along a room from the floor, at a grazing angle too, and from the floor up to the wall
        // beside: open.
        assert!(!grid.blocked(Vec3::new(-2.5, 0.0, -1.5), up, Vec3::new(-1.0, 2.0, 1.8), no));
        assert!(!grid.blocked(Vec3::new(-2.5, 0.0, -1.5), up, Vec3::new(-1.0, 0.2, 1.8), no));
        assert!(!grid.blocked(Vec3::new(-1.5, 0.0, -1.0), up, Vec3::new(-0.05, 1.5, -1.0), -x));
        // Between the floor's two sides (its ends moved off it): blocked.
        assert!(grid.blocked(Vec3::new(-1.5, 0.0, -1.0), up, Vec3::new(-1.0, 0.0, -1.0), -up));
        // Without moving off the floor, a segment from it starts in the floor's voxels.
        assert!(grid.blocked_between(Vec3::new(-1.5, 0.0, -1.0), Vec3::new(-1.0, 1.5, -1.0), 0.0));
        // Outside the grid nothing blocks, and a segment shorter than both skips is open.
        assert!(!grid.blocked(Vec3::new(-9.0, 9.0, -9.0), no, Vec3::new(9.0, 9.0, 9.0), no));
        assert!(!grid.blocked_between(Vec3::new(0.0, 1.0, -1.0), Vec3::new(0.01, 1.0, -1.0), grid.h));
    }

    /// Every voxel that `a .. b` touches beyond `skip` of its ends, one level (the reference
    /// the two-level walk must match).
    fn blocked_voxel_by_voxel(grid: &SurfaceVoxels, a: Vec3, b: Vec3, skip: f32) -> bool {
        let len = (b - a).length();
        let (p, d) = ((a - grid.origin) / grid.h, (b - a) / grid.h);
        let Some((t0, t1)) = clip_to_box(p, d, grid.dims.as_vec3()) else { return false };
        let (near, far) = (skip / len, 1.0 - skip / len);
        let all = (IVec3::ZERO, grid.dims.as_ivec3() - 1);
        len > 2.0 * skip
            && grid.walk(p, d, (t0, t1), Level::Voxel, all, &mut |c, ta, tb| tb > near && ta < far && grid.get(c))
    }

    #[test]
    fn walking_bricks_then_voxels_answers_as_every_voxel_does() {
        // A 4 x 3 x 4 m room of 0.2 m slabs, a partition with a doorway and a crate.
        let v = Vec3::new;
        let scene = crate::precompute::test_scenes::scene_of_slabs(
            &[
                ("floor", v(0.0, -0.1, 0.0), v(4.4, 0.2, 4.4)),
                ("ceiling", v(0.0, 3.1, 0.0), v(4.4, 0.2, 4.4)),
                ("left", v(-2.1, 1.5, 0.0), v(0.2, 3.0, 4.0)),
                ("right", v(2.1, 1.5, 0.0), v(0.2, 3.0, 4.0)),
                ("back", v(0.0, 1.5, -2.1), v(4.4, 3.0, 0.2)),
                ("front", v(0.0, 1.5, 2.1), v(4.4, 3.0, 0.2)),
                ("partition", v(0.0, 1.5, -0.7), v(0.2, 3.0, 2.6)),
                ("lintel", v(0.0, 2.6, 1.3), v(0.2, 0.8, 1.4)),
                ("crate", v(-1.0, 0.4, 1.0), v(0.8, 0.8, 0.8)),
            ],
            vec![],
        );
        let grid = SurfaceVoxels::of_scene(&scene, 80).expect("grid");
        let lo = grid.origin;
        let size = grid.dims.as_vec3() * grid.h;
        let mut rng = crate::precompute::rng::Pcg32::new(11, 0, 0);
        let mut blocked = 0;
        for _ in 0..4000 {
            let mut point = || lo + Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * size;
            let (a, b) = (point(), point());
            let reference = blocked_voxel_by_voxel(&grid, a, b, 0.5 * grid.h);
            assert_eq!(grid.blocked_between(a, b, 0.5 * grid.h), reference, "{a} to {b}");
            blocked += usize::from(reference);
        }
        // Both answers occur.
        assert!((400..3600).contains(&blocked), "{blocked} of 4000 blocked");
    }

    #[test]
    fn the_overlap_test_marks_a_triangle_crossing_a_voxel_and_not_one_beside_it() {
        let t = [Vec3::new(-1.0, 0.0, -1.0), Vec3::new(1.0, 0.0, -1.0), Vec3::new(0.0, 0.0, 1.0)];
        assert!(triangle_overlaps_box(&t, Vec3::new(0.0, 0.04, 0.0), Vec3::splat(0.05)));
        assert!(!triangle_overlaps_box(&t, Vec3::new(0.0, 0.06, 0.0), Vec3::splat(0.05)));
        // Beside the hypotenuse x + z / 2 = 1 (the point (0.9, 0, 0.9) lies outside it).
        assert!(!triangle_overlaps_box(&t, Vec3::new(0.9, 0.0, 0.9), Vec3::splat(0.1)));
        assert!(triangle_overlaps_box(&t, Vec3::new(0.45, 0.0, 0.1), Vec3::splat(0.1)));
        let grid = SurfaceVoxels::build(&[t], 20).expect("grid");
        let marked = (0..grid.dims.z as i32)
            .flat_map(|z| (0..grid.dims.y as i32).flat_map(move |y| (0..grid.dims.x as i32).map(move |x| (x, y, z))))
            .filter(|&(x, y, z)| grid.get(IVec3::new(x, y, z)))
            .count();
        // The triangle's area is 2 m^2, a voxel face 0.01 m^2: about 200 voxels of one layer,
        // more where the plane lies on a voxel boundary (two layers).
        assert!((180..=2 * 260).contains(&marked), "{marked} voxels");
    }
}
