//! A four-wide triangle BVH for CPU rays: each node holds its four children's boxes side by side
//! and each leaf its (at most four) triangles side by side, so one ray meets four boxes or four
//! triangles with a handful of 4-lane instructions (SSE, the x86-64 baseline).
//!
//! Built by collapsing `obvhs`'s binary BVH (PLOC, reinsertion, leaves of at most four
//! triangles): a node takes its two children, then opens the largest inner one until it has four
//! (the usual BVH2-to-BVH4 collapse, as Embree's BVH4 and Wald et al. 2008 describe). Traversal
//! visits the hit children nearest first and skips a popped node whose entry lies beyond the
//! closest hit (any-hit and all-hit walks take them in stack order). Triangles are
//! Möller-Trumbore, both sides. Measured on the reference tracer against `obvhs`'s compressed
//! eight-wide BVH with one triangle test per call (docs/notes/reference-tracer.md).

use glam::{Vec3A, Vec4};
use obvhs::BvhBuildParams;
use obvhs::bvh2::Bvh2;
use obvhs::bvh2::builder::build_bvh2_from_tris;
use obvhs::triangle::Triangle;

/// Marks a child slot that is a leaf: `LEAF | first packet << COUNT_BITS | packets` (room for
/// 2^25 packets, 134 million triangles, far beyond what the tracer's memory holds).
const LEAF: u32 = 1 << 31;
const COUNT_BITS: u32 = 6;
/// Triangles a leaf may hold: one packet.
const LEAF_SIZE: u32 = 4;
/// 1 + 2 gamma_3: the relative error bound of a box's entry and exit distances (Pharr et al.'s
/// gamma_n = n u / (1 - n u), u = 2^-24).
const WIDEN: f32 = 1.0 + 2.0 * (3.0 * f32::EPSILON * 0.5) / (1.0 - 3.0 * f32::EPSILON * 0.5);
/// Traversal stack entries kept on the call stack; a deeper tree (three pushes a level at
/// most) gets one on the heap.
const STACK: usize = 64;

/// Four children's boxes, structure of arrays, and what each child is.
#[derive(Clone, Copy, Debug)]
struct Node {
    lo: [Vec4; 3],
    hi: [Vec4; 3],
    child: [u32; 4],
    /// The lanes that hold a child (bit per lane).
    lanes: u32,
}

impl Node {
    const EMPTY: Self = Self { lo: [Vec4::ZERO; 3], hi: [Vec4::ZERO; 3], child: [0; 4], lanes: 0 };
}

/// Four triangles, structure of arrays: first corner and the two edges from it, per axis.
/// A lane without a triangle has zero edges, which no ray hits.
#[derive(Clone, Copy, Debug)]
struct Packet {
    p0: [Vec4; 3],
    e1: [Vec4; 3],
    e2: [Vec4; 3],
    /// Each lane's triangle, as its index in the input.
    prim: [u32; 4],
}

/// A ray's hit on a packet's triangles: which lanes hit, which of those the ray meets from the
/// front (the counter-clockwise side), and where.
struct PacketHits {
    mask: u32,
    front: u32,
    t: Vec4,
    u: Vec4,
    v: Vec4,
}

/// The four-wide tree and its triangle packets.
#[derive(Clone, Debug, Default)]
pub struct WideBvh {
    nodes: Vec<Node>,
    packets: Vec<Packet>,
    /// Entries a traversal's stack may need.
    stack_len: usize,
}

/// A ray set up for 4-lane tests: origin, direction and reciprocal direction, splat per axis.
struct BoxRay {
    o: [Vec4; 3],
    d: [Vec4; 3],
    inv: [Vec4; 3],
}

impl BoxRay {
    fn new(o: Vec3A, d: Vec3A) -> Self {
        // A zero component gets a huge finite reciprocal of its sign, so (lo - o) * inv is
        // never 0 * inf = NaN.
        let inv = |c: f32| if c.abs() < 1e-30 { 1e30f32.copysign(c) } else { 1.0 / c };
        Self {
            o: [Vec4::splat(o.x), Vec4::splat(o.y), Vec4::splat(o.z)],
            d: [Vec4::splat(d.x), Vec4::splat(d.y), Vec4::splat(d.z)],
            inv: [Vec4::splat(inv(d.x)), Vec4::splat(inv(d.y)), Vec4::splat(inv(d.z))],
        }
    }

    /// Entry distances of the four children and the mask of those entered before `tmax`. The
    /// exit distance and `tmax` are widened by [`WIDEN`] (Ize 2013, "Robust BVH Ray
    /// Traversal"), so neither a ray grazing a box's edge or crossing a flat box (an
    /// axis-aligned wall's) nor a triangle a rounding error nearer than the closest hit so far
    /// is culled by rounding.
    fn test(&self, n: &Node, tmax: f32) -> (Vec4, u32) {
        let mut near = Vec4::ZERO;
        let mut far = Vec4::splat(f32::INFINITY);
        for a in 0..3 {
            let t0 = (n.lo[a] - self.o[a]) * self.inv[a];
            let t1 = (n.hi[a] - self.o[a]) * self.inv[a];
            near = near.max(t0.min(t1));
            far = far.min(t0.max(t1));
        }
        let far = (far * WIDEN).min(Vec4::splat(tmax * WIDEN));
        (near, near.cmple(far).bitmask() & n.lanes)
    }

    /// Möller-Trumbore on four triangles at once: the lanes hit with `tmin < t < tmax`.
    fn triangles(&self, p: &Packet, tmin: f32, tmax: f32) -> PacketHits {
        let cross = |a: &[Vec4; 3], b: &[Vec4; 3]| {
            [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
        };
        let dot = |a: &[Vec4; 3], b: &[Vec4; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let pv = cross(&self.d, &p.e2);
        let det = dot(&p.e1, &pv);
        let inv = Vec4::ONE / det;
        let tv = [self.o[0] - p.p0[0], self.o[1] - p.p0[1], self.o[2] - p.p0[2]];
        let u = dot(&tv, &pv) * inv;
        let qv = cross(&tv, &p.e1);
        let v = dot(&self.d, &qv) * inv;
        let t = dot(&p.e2, &qv) * inv;
        let ok = det.abs().cmpge(Vec4::splat(1e-20))
            & u.cmpge(Vec4::ZERO)
            & u.cmple(Vec4::ONE)
            & v.cmpge(Vec4::ZERO)
            & (u + v).cmple(Vec4::ONE)
            & t.cmpgt(Vec4::splat(tmin))
            & t.cmplt(Vec4::splat(tmax));
        // det = e1 . (d x e2) = -d . (e1 x e2): positive when the ray meets the front.
        PacketHits { mask: ok.bitmask(), front: det.cmpgt(Vec4::ZERO).bitmask(), t, u, v }
    }
}

impl WideBvh {
    /// Builds the tree over `tris` (corners in world space): `obvhs`'s binary BVH with its
    /// medium-quality settings and leaves of at most four triangles, collapsed four-wide.
    pub fn build(tris: &[[Vec3A; 3]]) -> Self {
        let mut out = Self { nodes: Vec::new(), packets: Vec::new(), stack_len: 1 };
        if tris.is_empty() {
            return out;
        }
        let prims: Vec<Triangle> = tris.iter().map(|t| Triangle { v0: t[0], v1: t[1], v2: t[2] }).collect();
        let params = BvhBuildParams { max_prims_per_leaf: LEAF_SIZE, ..BvhBuildParams::medium_build() };
        let bvh2 = build_bvh2_from_tris(&prims, params, &mut std::time::Duration::default());
        if !bvh2.nodes.is_empty() {
            out.collapse(&bvh2, tris, 0, 1);
        }
        out
    }

    /// The packets of a leaf's triangles; returns the leaf's child code.
    fn leaf(&mut self, bvh2: &Bvh2, tris: &[[Vec3A; 3]], first: u32, count: u32) -> u32 {
        let start = self.packets.len() as u32;
        let slots = &bvh2.primitive_indices[first as usize..(first + count) as usize];
        for chunk in slots.chunks(LEAF_SIZE as usize) {
            let mut p = Packet { p0: [Vec4::ZERO; 3], e1: [Vec4::ZERO; 3], e2: [Vec4::ZERO; 3], prim: [0; 4] };
            for (lane, &prim) in chunk.iter().enumerate() {
                let [a, b, c] = tris[prim as usize];
                let (e1, e2) = (b - a, c - a);
                for axis in 0..3 {
                    p.p0[axis][lane] = a[axis];
                    p.e1[axis][lane] = e1[axis];
                    p.e2[axis][lane] = e2[axis];
                }
                p.prim[lane] = prim;
            }
            self.packets.push(p);
        }
        LEAF | (start << COUNT_BITS) | (self.packets.len() as u32 - start)
    }

    /// Appends the node whose children are `index`'s (opened up to four), `depth` levels down,
    /// and returns its slot.
    fn collapse(&mut self, bvh2: &Bvh2, tris: &[[Vec3A; 3]], index: usize, depth: usize) -> u32 {
        self.stack_len = self.stack_len.max(3 * depth + 1);
        let slot = self.nodes.len();
        self.nodes.push(Node::EMPTY);
        let root = &bvh2.nodes[index];
        let mut kids =
            if root.is_leaf() { vec![index] } else { vec![root.first_index as usize, root.first_index as usize + 1] };
        while kids.len() < 4 {
            let widest = kids
                .iter()
                .enumerate()
                .filter(|(_, k)| !bvh2.nodes[**k].is_leaf())
                .max_by(|a, b| bvh2.nodes[*a.1].aabb().half_area().total_cmp(&bvh2.nodes[*b.1].aabb().half_area()));
            let Some((i, _)) = widest else { break };
            let open = kids.swap_remove(i);
            let first = bvh2.nodes[open].first_index as usize;
            kids.extend([first, first + 1]);
        }
        let mut node = Node::EMPTY;
        for (lane, &k) in kids.iter().enumerate() {
            let n = &bvh2.nodes[k];
            let b = n.aabb();
            for a in 0..3 {
                node.lo[a][lane] = b.min[a] - outward(b.min[a]);
                node.hi[a][lane] = b.max[a] + outward(b.max[a]);
            }
            node.lanes |= 1 << lane;
            node.child[lane] = if n.is_leaf() {
                self.leaf(bvh2, tris, n.first_index, n.prim_count)
            } else {
                self.collapse(bvh2, tris, k, depth + 1)
            };
        }
        self.nodes[slot] = node;
        slot as u32
    }

    /// The closest triangle hit along `o + t d` with `0 < t < tmax`: the triangle's index in the
    /// input, `t` and the barycentric weights `u`, `v` of its second and third corners.
    pub fn closest(&self, o: Vec3A, d: Vec3A, tmax: f32) -> Option<(u32, f32, f32, f32)> {
        if self.nodes.is_empty() {
            return None;
        }
        let ray = BoxRay::new(o, d);
        let mut best = None;
        let (mut t_best, mut best_front) = (tmax, false);
        let (mut local, mut heap) = ([(0u32, 0.0f32); STACK], Vec::new());
        let stack = self.stack(&mut local, &mut heap);
        let mut top = 1;
        while top > 0 {
            top -= 1;
            let (child, entry) = stack[top];
            if entry > t_best * WIDEN {
                continue;
            }
            if child & LEAF != 0 {
                for p in &self.packets[leaf_packets(child)] {
                    // Up to and including the closest so far: a hit as near may be the one to keep.
                    let limit = if best.is_some() { t_best.next_up() } else { tmax };
                    let mut h = ray.triangles(p, 0.0, limit);
                    while h.mask != 0 {
                        let lane = h.mask.trailing_zeros() as usize;
                        h.mask &= h.mask - 1;
                        let front = h.front & (1 << lane) != 0;
                        if nearer(h.t[lane], front, t_best, best_front) {
                            (t_best, best_front) = (h.t[lane], front);
                            best = Some((p.prim[lane], h.t[lane], h.u[lane], h.v[lane]));
                        }
                    }
                }
                continue;
            }
            let node = &self.nodes[child as usize];
            let (near, mask) = ray.test(node, t_best);
            top = push_nearest_last(stack, top, node, near, mask);
        }
        best
    }

    /// Every triangle hit along the ray with `0 < t < tmax`, in no particular order: `visit`
    /// gets the triangle's index in the input and `t`. Only the tests call it, to check that
    /// [`Self::walk`] (what [`Self::any`] stops early) reaches every leaf the ray enters.
    #[cfg(test)]
    fn all(&self, o: Vec3A, d: Vec3A, tmax: f32, mut visit: impl FnMut(u32, f32)) {
        self.walk(o, d, tmax, |p, h| {
            let mut mask = h.mask;
            while mask != 0 {
                let lane = mask.trailing_zeros() as usize;
                mask &= mask - 1;
                visit(p.prim[lane], h.t[lane]);
            }
            false
        });
    }

    /// Whether any triangle lies along the ray with `0 < t < tmax`.
    pub fn any(&self, o: Vec3A, d: Vec3A, tmax: f32) -> bool {
        self.walk(o, d, tmax, |_, h| h.mask != 0)
    }

    /// Visits, in no particular order, the packets of every leaf the ray enters before `tmax`
    /// with their hits, until `visit` returns true (then returns true).
    fn walk(&self, o: Vec3A, d: Vec3A, tmax: f32, mut visit: impl FnMut(&Packet, PacketHits) -> bool) -> bool {
        if self.nodes.is_empty() {
            return false;
        }
        let ray = BoxRay::new(o, d);
        let (mut local, mut heap) = ([0u32; STACK], Vec::new());
        let stack = self.stack(&mut local, &mut heap);
        let mut top = 1;
        while top > 0 {
            top -= 1;
            let child = stack[top];
            if child & LEAF != 0 {
                for p in &self.packets[leaf_packets(child)] {
                    if visit(p, ray.triangles(p, 0.0, tmax)) {
                        return true;
                    }
                }
                continue;
            }
            let node = &self.nodes[child as usize];
            let (_, mut mask) = ray.test(node, tmax);
            while mask != 0 {
                let lane = mask.trailing_zeros() as usize;
                mask &= mask - 1;
                stack[top] = node.child[lane];
                top += 1;
            }
        }
        false
    }

    /// The traversal stack: `local` when the tree is shallow enough, else `heap`, grown.
    fn stack<'a, T: Copy + Default>(&self, local: &'a mut [T; STACK], heap: &'a mut Vec<T>) -> &'a mut [T] {
        if self.stack_len <= STACK {
            local
        } else {
            heap.resize(self.stack_len, T::default());
            heap
        }
    }
}

/// Whether a hit at `t` (met from the front or not) replaces the closest so far: nearer, or
/// exactly as near and met from the front where the closest so far is met from behind. Two
/// faces at the same distance are where solids touch or a ray grazes an edge; a ray that got
/// there through empty space meets the front one. Between two faces that face the same way the
/// tree's order still decides, which changes nothing the tracer reads but the triangle.
fn nearer(t: f32, front: bool, t_best: f32, best_front: bool) -> bool {
    t < t_best || (t == t_best && front && !best_front)
}

/// How far a box's face at coordinate `c` is moved outward (a few ulps of `c`, and a little
/// at 0): a ray that lies in the face's plane (an axis-aligned ray along a wall's edge) is then
/// inside the box's slab, not on its border, where the zero direction component's huge
/// reciprocal would put it inside or outside by its sign. `obvhs`'s compressed nodes rounded
/// their boxes outward the same way.
fn outward(c: f32) -> f32 {
    c.abs() * (1.0 / (1 << 21) as f32) + 1e-20
}

/// The packets a leaf child lists.
fn leaf_packets(child: u32) -> std::ops::Range<usize> {
    let first = ((child & !LEAF) >> COUNT_BITS) as usize;
    first..first + (child & ((1 << COUNT_BITS) - 1)) as usize
}

/// Pushes the hit children so that the nearest is popped first; returns the new top.
fn push_nearest_last(stack: &mut [(u32, f32)], mut top: usize, node: &Node, near: Vec4, mut mask: u32) -> usize {
    let start = top;
    while mask != 0 {
        let lane = mask.trailing_zeros() as usize;
        mask &= mask - 1;
        let item = (node.child[lane], near[lane]);
        // Insertion by descending entry distance (at most four items).
        let mut i = top;
        while i > start && stack[i - 1].1 < item.1 {
            stack[i] = stack[i - 1];
            i -= 1;
        }
        stack[i] = item;
        top += 1;
    }
    top
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::precompute::rng::Pcg32;

    /// Möller-Trumbore on one triangle, scalar: the twin of the packet test.
    fn hit(tri: &[Vec3A; 3], o: Vec3A, d: Vec3A, tmax: f32) -> Option<f32> {
        let (e1, e2) = (tri[1] - tri[0], tri[2] - tri[0]);
        let pv = d.cross(e2);
        let det = e1.dot(pv);
        if det.abs() < 1e-20 {
            return None;
        }
        let inv = 1.0 / det;
        let tv = o - tri[0];
        let u = tv.dot(pv) * inv;
        let qv = tv.cross(e1);
        let v = d.dot(qv) * inv;
        let t = e2.dot(qv) * inv;
        ((0.0..=1.0).contains(&u) && v >= 0.0 && u + v <= 1.0 && t > 0.0 && t < tmax).then_some(t)
    }

    fn point(rng: &mut Pcg32, size: f32) -> Vec3A {
        Vec3A::new(rng.next_f32() - 0.5, rng.next_f32() - 0.5, rng.next_f32() - 0.5) * size
    }

    /// Origin, direction and the distance limit.
    type TestRay = (Vec3A, Vec3A, f32);

    /// A soup of large, small, sliver and degenerate triangles, and rays among them, some
    /// along the axes with negative zero components.
    fn soup() -> (Vec<[Vec3A; 3]>, Vec<TestRay>) {
        let mut rng = Pcg32::new(21, 0, 0);
        let tris = (0..600)
            .map(|i| {
                let c = point(&mut rng, 10.0);
                let size = [4.0, 0.5, 0.05][i % 3];
                let mut t = [c + point(&mut rng, size), c + point(&mut rng, size), c + point(&mut rng, size)];
                if i % 50 == 0 {
                    t[2] = t[1]; // degenerate: no ray hits it
                }
                if i % 7 == 0 {
                    t[2] = t[0] + (t[1] - t[0]) * 0.5 + point(&mut rng, 1e-3); // sliver
                }
                t
            })
            .collect();
        let axes = [Vec3A::new(-0.0, -1.0, -0.0), Vec3A::X, Vec3A::new(0.0, 0.0, -1.0)];
        let rays = (0..3000)
            .map(|i| {
                let o = point(&mut rng, 12.0);
                let d = if i % 10 == 0 { axes[i % 3] } else { point(&mut rng, 2.0).normalize() };
                let tmax = if i % 4 == 0 { 3.0 } else { f32::INFINITY };
                (o, d, tmax)
            })
            .collect();
        (tris, rays)
    }

    #[test]
    fn closest_any_and_all_match_testing_every_triangle() {
        let (tris, rays) = soup();
        let bvh = WideBvh::build(&tris);
        let mut hits = 0;
        for &(o, d, tmax) in &rays {
            let mut every: Vec<(u32, f32)> =
                tris.iter().enumerate().filter_map(|(i, t)| hit(t, o, d, tmax).map(|t| (i as u32, t))).collect();
            every.sort_by(|a, b| a.1.total_cmp(&b.1));
            let closest = bvh.closest(o, d, tmax);
            match (closest, every.first()) {
                (None, None) => {}
                (Some((_, t, u, v)), Some(&(_, t_ref))) => {
                    assert!((t - t_ref).abs() <= 1e-5 * t_ref.max(1.0), "ray {o} {d}: t {t} vs {t_ref}");
                    assert!(u >= 0.0 && v >= 0.0 && u + v <= 1.0);
                    hits += 1;
                }
                (got, want) => panic!("ray {o} {d}: closest {got:?}, every triangle {want:?}"),
            }
            assert_eq!(bvh.any(o, d, tmax), !every.is_empty(), "ray {o} {d}");
            let mut all = Vec::new();
            bvh.all(o, d, tmax, |tri, _| all.push(tri));
            all.sort_unstable();
            let mut want: Vec<u32> = every.iter().map(|h| h.0).collect();
            want.sort_unstable();
            assert_eq!(all, want, "ray {o} {d}");
        }
        assert!(hits > 300, "the soup should be hit often: {hits}");
    }

    /// Every hit of a ray, nearest first, by testing every triangle.
    fn every_hit(tris: &[[Vec3A; 3]], o: Vec3A, d: Vec3A, tmax: f32) -> Vec<f32> {
        let mut ts: Vec<f32> = tris.iter().filter_map(|t| hit(t, o, d, tmax)).collect();
        ts.sort_by(f32::total_cmp);
        ts
    }

    /// The twelve triangles of the box `lo`-`hi`.
    fn cuboid(lo: Vec3A, hi: Vec3A) -> Vec<[Vec3A; 3]> {
        let c = |x: bool, y: bool, z: bool| {
            Vec3A::new(if x { hi.x } else { lo.x }, if y { hi.y } else { lo.y }, if z { hi.z } else { lo.z })
        };
        let (f, t) = (false, true);
        let faces = [
            [c(f, f, f), c(f, t, f), c(f, t, t), c(f, f, t)],
            [c(t, f, f), c(t, f, t), c(t, t, t), c(t, t, f)],
            [c(f, f, f), c(f, f, t), c(t, f, t), c(t, f, f)],
            [c(f, t, f), c(t, t, f), c(t, t, t), c(f, t, t)],
            [c(f, f, f), c(t, f, f), c(t, t, f), c(f, t, f)],
            [c(f, f, t), c(f, t, t), c(t, t, t), c(t, f, t)],
        ];
        faces.iter().flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]]).collect()
    }

    /// Slabs and boxes that touch, and rays as the precomputes cast them: from points just off
    /// each face (at its corners, its edges' middles and at random), along its normal both ways
    /// and along the axes with zero and negative-zero components, which lie in other boxes'
    /// faces. Fails when the boxes are not moved outward (`outward`): an axis-aligned ray in a
    /// box's face plane misses the edge hits inside it.
    #[test]
    fn axis_aligned_rays_from_slab_faces_find_every_hit() {
        let tris: Vec<[Vec3A; 3]> = [
            cuboid(Vec3A::new(0.0, 0.0, 0.0), Vec3A::new(5.0, 0.2, 4.0)),
            cuboid(Vec3A::new(0.0, 0.2, 0.0), Vec3A::new(0.2, 3.0, 4.0)),
            cuboid(Vec3A::new(0.2, 0.2, 0.0), Vec3A::new(4.8, 3.0, 0.2)),
            cuboid(Vec3A::new(0.0, 3.0, 0.0), Vec3A::new(5.0, 3.2, 4.0)),
            cuboid(Vec3A::new(1.3, 0.2, 1.1), Vec3A::new(2.1, 0.95, 1.7)),
            cuboid(Vec3A::new(1.3, 0.95, 1.1), Vec3A::new(1.7, 1.4, 1.7)),
        ]
        .concat();
        let bvh = WideBvh::build(&tris);
        let mut rng = Pcg32::new(8, 8, 8);
        let eps = 4e-4;
        let axes =
            [Vec3A::X, Vec3A::new(-1.0, -0.0, -0.0), Vec3A::Y, Vec3A::new(-0.0, -1.0, -0.0), Vec3A::Z, Vec3A::NEG_Z];
        let spots = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (0.5, 0.0), (0.0, 0.5), (0.5, 0.5)];
        for tri in &tris {
            let n = (tri[1] - tri[0]).cross(tri[2] - tri[0]).normalize();
            let random = (0..6).map(|_| (rng.next_f32() * 0.5, rng.next_f32() * 0.5));
            for (a, b) in spots.into_iter().chain(random) {
                let p = tri[0] + (tri[1] - tri[0]) * a + (tri[2] - tri[0]) * b;
                let rays = [(p - n * eps, -n), (p + n * eps, n)].into_iter().chain(axes.map(|d| (p + n * eps, d)));
                for (o, d) in rays {
                    let want = every_hit(&tris, o, d, f32::MAX);
                    let mut got = Vec::new();
                    bvh.all(o, d, f32::MAX, |_, t| got.push(t));
                    got.sort_by(f32::total_cmp);
                    assert_eq!(got, want, "all hits of {o} along {d}");
                    assert_eq!(bvh.closest(o, d, f32::MAX).map(|h| h.1), want.first().copied(), "{o} along {d}");
                    assert_eq!(bvh.any(o, d, f32::MAX), !want.is_empty(), "{o} along {d}");
                }
            }
        }
    }

    #[test]
    fn a_tree_deeper_than_the_local_stack_traverses_on_the_heap() {
        let (tris, rays) = soup();
        let shallow = WideBvh::build(&tris);
        let mut deep = shallow.clone();
        deep.stack_len = STACK + 1;
        for &(o, d, tmax) in rays.iter().take(500) {
            assert_eq!(deep.closest(o, d, tmax).map(|h| h.1), shallow.closest(o, d, tmax).map(|h| h.1));
            assert_eq!(deep.any(o, d, tmax), shallow.any(o, d, tmax));
        }
    }

    #[test]
    fn no_triangles_no_hits() {
        let bvh = WideBvh::build(&[]);
        assert!(bvh.closest(Vec3A::ZERO, Vec3A::X, f32::INFINITY).is_none());
        assert!(!bvh.any(Vec3A::ZERO, Vec3A::X, f32::INFINITY));
        let mut all = 0;
        bvh.all(Vec3A::ZERO, Vec3A::X, f32::INFINITY, |_, _| all += 1);
        assert_eq!(all, 0);
    }

    /// One triangle: the root is a leaf. Hit inside with its barycentrics, missed beside it.
    #[test]
    fn a_single_triangle_is_a_root_leaf() {
        let tri = [Vec3A::ZERO, Vec3A::X, Vec3A::Y];
        let bvh = WideBvh::build(&[tri]);
        let (prim, t, u, v) = bvh.closest(Vec3A::new(0.25, 0.5, 1.0), Vec3A::NEG_Z, f32::INFINITY).expect("hit");
        assert_eq!(prim, 0);
        assert!((t - 1.0).abs() < 1e-6 && (u - 0.25).abs() < 1e-6 && (v - 0.5).abs() < 1e-6, "{t} {u} {v}");
        assert!(bvh.closest(Vec3A::new(0.75, 0.5, 1.0), Vec3A::NEG_Z, f32::INFINITY).is_none());
        assert!(!bvh.any(Vec3A::new(0.25, 0.5, 1.0), Vec3A::NEG_Z, 0.5));
    }

    /// A ray along an axis-aligned wall's corner edge: the walls' boxes are flat, and the
    /// widened exit keeps rounding from culling them.
    #[test]
    fn rays_grazing_flat_boxes_still_hit() {
        // A floor at y = 0 and a wall at x = 0, each two triangles, meeting along the z axis.
        let floor = [
            [Vec3A::new(0.0, 0.0, -1.0), Vec3A::new(1.0, 0.0, -1.0), Vec3A::new(1.0, 0.0, 1.0)],
            [Vec3A::new(0.0, 0.0, -1.0), Vec3A::new(1.0, 0.0, 1.0), Vec3A::new(0.0, 0.0, 1.0)],
        ];
        let wall = [
            [Vec3A::new(0.0, 0.0, -1.0), Vec3A::new(0.0, 1.0, -1.0), Vec3A::new(0.0, 1.0, 1.0)],
            [Vec3A::new(0.0, 0.0, -1.0), Vec3A::new(0.0, 1.0, 1.0), Vec3A::new(0.0, 0.0, 1.0)],
        ];
        let tris: Vec<[Vec3A; 3]> = floor.into_iter().chain(wall).collect();
        let bvh = WideBvh::build(&tris);
        let mut rng = Pcg32::new(4, 4, 4);
        for _ in 0..2000 {
            // From above the room's corner towards a point of the floor just beside the wall.
            let target = Vec3A::new(1e-6 * rng.next_f32(), 0.0, rng.next_f32() * 1.8 - 0.9);
            let o = Vec3A::new(0.3 + rng.next_f32(), 0.5 + rng.next_f32(), rng.next_f32() - 0.5);
            let d = (target - o).normalize();
            assert!(bvh.closest(o, d, f32::INFINITY).is_some(), "{o} towards {target}");
            assert!(bvh.any(o, d, f32::INFINITY), "{o} towards {target}");
        }
    }
}
