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

use glam::{IVec3, UVec3, Vec3};

use crate::scene::Scene;

/// The smallest voxel (m): a level of a few metres needs no finer grid than this.
const MIN_VOXEL: f32 = 0.02;

/// How far (voxels) [`SurfaceVoxels::blocked`] moves a segment's ends along their normals.
pub const OFF_SURFACE: f32 = 1.5;

/// How far (voxels) from either end [`SurfaceVoxels::blocked`] leaves voxels out.
pub const END_SKIP: f32 = 0.5;

/// The surface voxels of a scene.
#[derive(Clone, Debug, PartialEq)]
pub struct SurfaceVoxels {
    /// The grid's minimum corner (world, m).
    pub origin: Vec3,
    /// The voxel's side (m).
    pub h: f32,
    /// Voxels along x, y, z.
    pub dims: UVec3,
    /// One bit per voxel, x fastest, then y, then z (bit i in word i / 32).
    pub words: Vec<u32>,
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
        let mut grid = Self { origin, h, dims, words: vec![0; count.div_ceil(32)] };
        for t in tris {
            grid.mark(t);
        }
        Some(grid)
    }

    /// The grid of `scene`'s rendered objects ([`Self::build`]).
    pub fn of_scene(scene: &Scene, along: u32) -> Option<Self> {
        Self::build(&world_triangles(scene), along)
    }

    /// The bit index of voxel `c` (inside the grid).
    fn index(&self, c: UVec3) -> usize {
        (c.z as usize * self.dims.y as usize + c.y as usize) * self.dims.x as usize + c.x as usize
    }

    /// Whether voxel `c` holds a surface (outside the grid: no).
    pub fn get(&self, c: IVec3) -> bool {
        if c.cmplt(IVec3::ZERO).any() || c.as_uvec3().cmpge(self.dims).any() {
            return false;
        }
        let i = self.index(c.as_uvec3());
        self.words[i / 32] >> (i % 32) & 1 == 1
    }

    /// Marks the voxels triangle `t` overlaps.
    fn mark(&mut self, t: &[Vec3; 3]) {
        let lo = ((t[0].min(t[1]).min(t[2]) - self.origin) / self.h).floor().as_ivec3().max(IVec3::ZERO);
        let hi = ((t[0].max(t[1]).max(t[2]) - self.origin) / self.h).floor().as_ivec3().min(self.dims.as_ivec3() - 1);
        // A hair over half a voxel: a plane on a voxel boundary marks the voxels on both sides,
        // never neither (rounding).
        let half = Vec3::splat(0.5 * self.h * (1.0 + 1e-3));
        for z in lo.z..=hi.z {
            for y in lo.y..=hi.y {
                for x in lo.x..=hi.x {
                    let c = IVec3::new(x, y, z);
                    let centre = self.origin + (c.as_vec3() + 0.5) * self.h;
                    if triangle_overlaps_box(t, centre, half) {
                        let i = self.index(c.as_uvec3());
                        self.words[i / 32] |= 1 << (i % 32);
                    }
                }
            }
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
    /// is in within `skip` metres of either end. Outside the grid nothing blocks. An
    /// Amanatides-Woo traversal: every voxel the segment touches is visited.
    pub fn blocked_between(&self, a: Vec3, b: Vec3, skip: f32) -> bool {
        let len = (b - a).length();
        if len <= 2.0 * skip {
            return false;
        }
        let p = (a - self.origin) / self.h;
        let d = (b - a) / self.h;
        let Some((t0, t1)) = clip_to_box(p, d, self.dims.as_vec3()) else { return false };
        let start = p + d * t0;
        let mut c = start.floor().as_ivec3().clamp(IVec3::ZERO, self.dims.as_ivec3() - 1);
        let step = IVec3::new(sign(d.x), sign(d.y), sign(d.z));
        let next_edge = c.as_vec3() + step.max(IVec3::ZERO).as_vec3();
        let inv = Vec3::new(inverse(d.x), inverse(d.y), inverse(d.z));
        let mut t_max = Vec3::new(
            if step.x == 0 { f32::MAX } else { (next_edge.x - p.x) * inv.x },
            if step.y == 0 { f32::MAX } else { (next_edge.y - p.y) * inv.y },
            if step.z == 0 { f32::MAX } else { (next_edge.z - p.z) * inv.z },
        );
        let t_delta = inv.abs();
        let (near, far) = (skip / len, 1.0 - skip / len);
        let mut t = t0;
        let limit = self.dims.x + self.dims.y + self.dims.z + 3;
        for _ in 0..limit {
            let t_next = t_max.min_element().min(t1);
            if t_next > near && t < far && self.get(c) {
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

    /// Bytes of the bits.
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
