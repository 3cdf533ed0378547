//! `probe-mrt`'s brute force: the light a real surface point gets, by cosine rays into the real
//! scene along paths of `--multi` diffuse bounces, with `--source`, `--uniform` and `--mimic`
//! deciding what sends light and what counts as a bounce.

use super::*;

/// The brute force: cosine rays from a real surface point into the real scene, paths of
/// `--multi` diffuse bounces.
pub(super) struct Brute<'a> {
    probe: &'a Probe<'a>,
    bounces: usize,
    /// `--source K`'s linked sides (world side, plane).
    source_sides: Vec<(Face, f32)>,
    /// Every linked side: (axis, plane, lower corner, upper corner).
    linked: Vec<(usize, f32, Vec3, Vec3)>,
}

impl<'a> Brute<'a> {
    pub(super) fn new(probe: &'a Probe<'a>) -> Self {
        let lvl = probe.lvl;
        let source_sides = probe.args.source.map_or(Vec::new(), |k| {
            lvl.linked_sides().into_iter().filter(|(i, _)| *i == k).map(|(_, w)| (w, lvl.side_rect(k, w).0)).collect()
        });
        let linked = lvl
            .linked_sides()
            .into_iter()
            .map(|(i, w)| {
                let (plane, lo, hi) = lvl.side_rect(i, w);
                (w.axis(), plane, lo, hi)
            })
            .collect();
        Self { probe, bounces: probe.args.multi.max(1), source_sides, linked }
    }

    /// Whether `p` may send light (`--source K`: inside block K's box, grown by 0.15 m as
    /// fitted boxes stop short of the outer walls, but never past a linked side, where the
    /// rooms beyond start).
    fn inside(&self, p: Vec3) -> bool {
        self.probe.args.source.is_none_or(|k| {
            let b = &self.probe.lvl.blocks[k];
            (p - b.origin).cmpge(Vec3::splat(-0.15)).all()
                && (b.origin + b.size - p).cmpge(Vec3::splat(-0.15)).all()
                && self
                    .source_sides
                    .iter()
                    .all(|(w, plane)| if w.positive() { p[w.axis()] <= *plane } else { p[w.axis()] >= *plane })
        })
    }

    /// Whether the surface at `p` with normal `ng` belongs to a linked side (within 0.15 m of
    /// it, facing across it).
    fn on_side(&self, p: Vec3, ng: Vec3) -> bool {
        self.linked.iter().any(|(axis, plane, lo, hi)| {
            ng[*axis].abs() > 0.5
                && (p[*axis] - plane).abs() < 0.15
                && (0..3).filter(|a| a != axis).all(|a| p[a] >= lo[a] - 0.01 && p[a] <= hi[a] + 0.01)
        })
    }

    /// The light gathered at `q` with normal `n` (the rays' seed `seed`).
    pub(super) fn gather(&self, q: Vec3, n: Vec3, seed: u64) -> f64 {
        let mut rng = Pcg32::new(5, seed, 0);
        let (tt, bb) = n.any_orthonormal_pair();
        let side = (self.probe.args.rays as f64).sqrt() as usize;
        let mut sum = 0.0;
        for a in 0..side {
            for c in 0..side {
                let r1 = (a as f32 + rng.next_f32()) / side as f32;
                let r2 = (c as f32 + rng.next_f32()) / side as f32;
                let (r, phi) = (r1.sqrt(), std::f32::consts::TAU * r2);
                let d = (tt * r * phi.cos() + bb * r * phi.sin() + n * (1.0 - r1).max(0.0).sqrt()).normalize();
                self.path(&mut rng, q + n * 1e-3 * self.probe.bvh.scale, d, &mut sum);
            }
        }
        sum / (side * side) as f64
    }

    /// One path from `origin` along `d`: adds the light it meets (times its throughput) to `sum`.
    fn path(&self, rng: &mut Pcg32, mut origin: Vec3, mut d: Vec3, sum: &mut f64) {
        let (scene, bvh) = (self.probe.scene, self.probe.bvh);
        let (mimic, uniform) = (self.probe.args.mimic, self.probe.args.uniform);
        let mut throughput = 1.0;
        let mut k = 0;
        let mut steps = 0;
        while k < self.bounces && steps < 64 {
            steps += 1;
            let Some(hit) = bvh.intersect(origin, d, f32::INFINITY) else { break };
            let tri = &bvh.tris[hit.tri as usize];
            let p = origin + d * hit.t;
            let ng = if tri.ng.dot(d) < 0.0 { tri.ng } else { break };
            let albedo = geometry_image::albedo(scene, tri.material);
            let mimicked = mimic && self.on_side(p, ng);
            if mimicked {
                // MRT's closed part of a linked side: no direct light, a reflection within the
                // same bounce.
            } else if uniform {
                if self.inside(p) && !self.on_side(p, ng) {
                    *sum += throughput;
                }
            } else if self.inside(p) {
                *sum += throughput * lum(direct(scene, bvh, p, ng, albedo));
            }
            if !mimicked {
                k += 1;
                if k == self.bounces {
                    break;
                }
            }
            throughput *= lum(albedo);
            let (t2, b2) = ng.any_orthonormal_pair();
            let (u1, u2) = (rng.next_f32(), rng.next_f32());
            let (r, phi) = (u1.sqrt(), std::f32::consts::TAU * u2);
            d = (t2 * r * phi.cos() + b2 * r * phi.sin() + ng * (1.0 - u1).max(0.0).sqrt()).normalize();
            origin = p + ng * 1e-3 * bvh.scale;
        }
    }

    /// The brute force at every texel (0 where it has no surface).
    pub(super) fn texels(&self, texels: &[Vec<Texel>]) -> Light {
        texels
            .iter()
            .enumerate()
            .map(|(x, t)| {
                t.par_iter()
                    .enumerate()
                    .map(|(i, s)| s.map_or(0.0, |(q, n, _)| self.gather(q, n, (x * 100_000 + i) as u64)))
                    .collect()
            })
            .collect()
    }
}
