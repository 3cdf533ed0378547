//! The point pool's clusters for per-VPL point selection (`ism_select.wgsl`): the pool's points
//! are put in Morton order of their world positions and cut into runs of [`CLUSTER_POINTS`],
//! each with its bounding sphere and area, so that one GPU workgroup per VPL can weigh the
//! whole pool by solid angle in a few thousand steps instead of one per point. Rebuilt on the
//! CPU with the point data, i.e. only when geometry, transforms or weights change.

use glam::Vec3;

use crate::render::octahedral::{oct_decode, oct_encode};

use super::gather::PointData;
use super::params::GpuCluster;

/// Pool points per cluster: 256k points make 4096 clusters, which one 256-thread workgroup
/// weighs in 16 steps per thread.
pub const CLUSTER_POINTS: usize = 64;

/// Spreads the 10 low bits of `v` to every third bit.
fn spread(v: u32) -> u64 {
    let mut x = u64::from(v & 0x3ff);
    x = (x | (x << 16)) & 0x0300_00ff;
    x = (x | (x << 8)) & 0x0300_f00f;
    x = (x | (x << 4)) & 0x030c_30c3;
    (x | (x << 2)) & 0x0924_9249
}

/// The 30-bit Morton code of `p` within the cube of side `extent` at `lo` (a cube, not the
/// bounds' box: cells must be cubes for runs of codes to be compact in space).
fn morton(p: Vec3, lo: Vec3, extent: f32) -> u64 {
    let q = ((p - lo) / extent.max(1e-12) * 1023.0).clamp(Vec3::ZERO, Vec3::splat(1023.0));
    spread(q.x as u32) | (spread(q.y as u32) << 1) | (spread(q.z as u32) << 2)
}

/// Steps of a plane's quantised octahedral components: 12 bits each, codes 1..=4095 (0 is
/// kept for "no plane").
const OCT_STEPS: f32 = 2047.0;
/// Codes of the thickness per halving: the thickness bound is `radius * 2^((k - 255) / 8)`.
const THICKNESS_PER_OCTAVE: f32 = 8.0;

/// The cluster's plane, packed for `ism_select.wgsl`'s `Cluster.plane`: the points' mean
/// normal `m`, octahedral in 2 x 12 bits, and in the top 8 bits a bound on how far any point
/// lies off the plane through `centre` with normal `m` (log-coded, rounded up, relative to
/// `radius`). With it the selection bounds how far a cluster rises above a VPL's plane far
/// more tightly than its sphere does: a cluster of the VPL's own wall or floor lies wholly
/// behind it (measured: 37-47% of the points chosen by the sphere bound lay there, and the
/// splat drops them). The bound is computed against the *decoded* normal, so quantisation
/// never makes it too small.
fn plane_code(points: &[Vec3], normal_sum: Vec3, centre: Vec3, radius: f32) -> u32 {
    let m = normal_sum.try_normalize().unwrap_or(Vec3::Z);
    let e = oct_encode(m);
    let q = |c: f32| ((c.clamp(-1.0, 1.0) * OCT_STEPS).round() + 2048.0) as u32;
    let (qx, qy) = (q(e.x), q(e.y));
    let (m, _) = plane_of(qx | (qy << 12), radius);
    let thickness = points.iter().map(|p| (*p - centre).dot(m).abs()).fold(0.0f32, f32::max);
    let mut k = 0u32;
    if radius > 0.0 && thickness > 0.0 {
        let code = (255.0 + THICKNESS_PER_OCTAVE * (thickness / radius).log2()).ceil();
        k = code.clamp(0.0, 255.0) as u32;
        while k < 255 && plane_of(k << 24, radius).1 < thickness {
            k += 1;
        }
    }
    qx | (qy << 12) | (k << 24)
}

/// The normal and thickness bound a plane code holds (the shader's decoding).
fn plane_of(code: u32, radius: f32) -> (Vec3, f32) {
    let c = |bits: u32| (bits as f32 - 2048.0) / OCT_STEPS;
    let m = oct_decode([c(code & 0xfff), c((code >> 12) & 0xfff)]);
    let k = (code >> 24) as f32;
    (m, radius * ((k - 255.0) / THICKNESS_PER_OCTAVE).exp2())
}

/// Reorders `data`'s points into Morton order and returns their clusters; `area_of(w)` is the
/// pool area of a point of sampling weight `w`.
pub fn build(data: &mut PointData, area_of: impl Fn(f32) -> f32) -> Vec<GpuCluster> {
    let n = data.positions.len();
    if n == 0 {
        return Vec::new();
    }
    let position = |i: usize| Vec3::new(data.positions[i][0], data.positions[i][1], data.positions[i][2]);
    let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
    for i in 0..n {
        lo = lo.min(position(i));
        hi = hi.max(position(i));
    }
    let extent = (hi - lo).max_element();
    let mut order: Vec<(u64, u32)> = (0..n).map(|i| (morton(position(i), lo, extent), i as u32)).collect();
    order.sort_unstable();
    let permute = |v: &mut Vec<[f32; 4]>| {
        let old = std::mem::take(v);
        *v = order.iter().map(|&(_, i)| old[i as usize]).collect();
    };
    permute(&mut data.positions);
    permute(&mut data.normals);
    permute(&mut data.albedo);
    permute(&mut data.specular);
    // Clip lines: a fixed number per point, moved with it.
    let per = data.clips.len() / n;
    if per > 0 {
        let old = std::mem::take(&mut data.clips);
        data.clips =
            order.iter().flat_map(|&(_, i)| old[i as usize * per..(i as usize + 1) * per].iter().copied()).collect();
    }
    (0..n)
        .step_by(CLUSTER_POINTS)
        .map(|first| cluster(data, first..(first + CLUSTER_POINTS).min(n), &area_of))
        .collect()
}

/// The cluster of `data`'s points in `range`: bounding sphere (centred on the bounding box),
/// pool area and plane.
fn cluster(data: &PointData, range: std::ops::Range<usize>, area_of: &impl Fn(f32) -> f32) -> GpuCluster {
    let points: Vec<Vec3> = range.clone().map(|i| Vec3::from_slice(&data.positions[i][..3])).collect();
    let (a, b) = points
        .iter()
        .fold((Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)), |(a, b), p| (a.min(*p), b.max(*p)));
    let centre = (a + b) * 0.5;
    let radius = points.iter().map(|p| p.distance(centre)).fold(0.0f32, f32::max);
    let area = range.clone().map(|i| area_of(data.normals[i][3])).sum();
    let normal_sum: Vec3 = range.clone().map(|i| Vec3::from_slice(&data.normals[i][..3])).sum();
    GpuCluster {
        sphere: [centre.x, centre.y, centre.z, radius],
        first: range.start as u32,
        count: range.len() as u32,
        area,
        plane: plane_code(&points, normal_sum, centre, radius),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clusters_cover_every_point_once_and_bound_them() {
        let mut data = PointData::default();
        for i in 0..1000u32 {
            let x = (i as f32 * 0.618_034).fract() * 10.0;
            let z = (i as f32 * 0.414_214).fract() * 4.0;
            data.positions.push([x, 0.0, z, 1.0]);
            data.normals.push([0.0, 1.0, 0.0, if i % 2 == 0 { 1.0 } else { 2.0 }]);
            data.albedo.push([i as f32, 0.0, 0.0, 1.0]);
            data.specular.push([0.0; 4]);
        }
        let before: Vec<[f32; 4]> = data.positions.clone();
        let clusters = build(&mut data, |w| 0.04 / w);
        assert_eq!(clusters.iter().map(|c| c.count).sum::<u32>(), 1000);
        let mut next = 0;
        for c in &clusters {
            assert_eq!(c.first, next, "clusters are consecutive runs");
            next += c.count;
            let centre = Vec3::new(c.sphere[0], c.sphere[1], c.sphere[2]);
            for i in c.first..c.first + c.count {
                let p = data.positions[i as usize];
                assert!(Vec3::new(p[0], p[1], p[2]).distance(centre) <= c.sphere[3] + 1e-5);
            }
        }
        // Morton runs are compact: runs of the points in their original (lattice) order span
        // the whole 10 x 4 m plane, Morton runs a fraction of it (a disk of a sixteenth of its
        // area has radius 0.89 m).
        let mean_radius = clusters.iter().map(|c| c.sphere[3]).sum::<f32>() / clusters.len() as f32;
        let unsorted: f32 = before
            .chunks(CLUSTER_POINTS)
            .map(|run| {
                let ps: Vec<Vec3> = run.iter().map(|p| Vec3::new(p[0], p[1], p[2])).collect();
                let (a, b) = ps.iter().fold((Vec3::MAX, Vec3::MIN), |(a, b), p| (a.min(*p), b.max(*p)));
                ps.iter().map(|p| p.distance((a + b) * 0.5)).fold(0.0, f32::max)
            })
            .sum::<f32>()
            / clusters.len() as f32;
        assert!(mean_radius < 2.0 && unsorted > 2.0 * mean_radius, "mean radius {mean_radius}, unsorted {unsorted}");
        let area = clusters.iter().map(|c| c.area).sum::<f32>();
        assert!((area - (500.0 * 0.04 + 500.0 * 0.02)).abs() < 1e-3, "area {area}");
        // Every point moved together with its attributes.
        for (p, a) in data.positions.iter().zip(&data.albedo) {
            assert_eq!(*p, before[a[0] as usize]);
        }
    }

    /// `rise` in `ism_select.wgsl`: how far above the plane through `o` with normal `n` any of
    /// the cluster's points can lie.
    fn rise(c: &GpuCluster, o: Vec3, n: Vec3) -> f32 {
        let (centre, r) = (Vec3::from_slice(&c.sphere[..3]), c.sphere[3]);
        let (m, h) = plane_of(c.plane, r);
        let cm = n.dot(m).abs().min(1.0);
        (centre - o).dot(n) + r.min(h * cm + r * (1.0 - cm * cm).sqrt() + 1e-5 * r)
    }

    /// Points of a floor (y = 0, 6 x 6 m), a tilted ramp and a lumpy pile, in one pool.
    fn pool() -> PointData {
        let mut data = PointData::default();
        let mut push = |p: Vec3, n: Vec3| {
            data.positions.push([p.x, p.y, p.z, 1.0]);
            data.normals.push([n.x, n.y, n.z, 1.0]);
            data.albedo.push([0.0; 4]);
            data.specular.push([0.0; 4]);
        };
        let ramp = Vec3::new(0.0, 0.8, -0.6);
        for i in 0..3000u32 {
            let (a, b) = ((i as f32 * 0.618_034).fract(), (i as f32 * 0.414_214).fract());
            push(Vec3::new(a * 6.0, 0.0, b * 6.0), Vec3::Y);
            push(Vec3::new(8.0 + a * 2.0, 1.0, 0.0) + Vec3::new(0.0, 0.6, 0.8) * b * 2.0, ramp);
            let lump = Vec3::new(a - 0.5, b, (a * 7.0).fract() - 0.5).normalize();
            push(Vec3::new(3.0, 2.0, 9.0) + lump * (1.0 + 0.3 * b), lump);
        }
        data
    }

    #[test]
    fn the_plane_bound_covers_every_point_and_puts_the_floor_behind_a_vpl_on_it() {
        let mut data = pool();
        let clusters = build(&mut data, |_| 0.01);
        let point = |i: u32| Vec3::from_slice(&data.positions[i as usize][..3]);
        let mut rng = crate::precompute::rng::Pcg32::new(7, 1, 0);
        for _ in 0..200 {
            let o = Vec3::new(rng.next_f32() * 12.0, rng.next_f32() * 4.0, rng.next_f32() * 12.0);
            let n = Vec3::new(rng.next_f32() - 0.5, rng.next_f32() - 0.5, rng.next_f32() - 0.5).normalize();
            for c in &clusters {
                let highest = (c.first..c.first + c.count).map(|i| (point(i) - o).dot(n)).fold(f32::MIN, f32::max);
                assert!(rise(c, o, n) >= highest - 1e-5, "cluster {c:?}: bound {} below {highest}", rise(c, o, n));
            }
        }
        // Clusters whose points all share one normal: the floor's and the ramp's own.
        let ramp = Vec3::new(0.0, 0.8, -0.6);
        let all_facing = |c: &&GpuCluster, m: Vec3| {
            (c.first..c.first + c.count).all(|i| Vec3::from_slice(&data.normals[i as usize][..3]) == m)
        };
        // A VPL a millimetre above the floor, facing up: every cluster of the floor lies behind
        // it, while the sphere's top (radius r above the centre) gave each of them weight.
        let floor: Vec<&GpuCluster> = clusters.iter().filter(|c| all_facing(c, Vec3::Y)).collect();
        assert!(floor.len() > 10, "{} floor clusters", floor.len());
        let o = Vec3::new(3.0, 1e-3, 3.0);
        for c in &floor {
            assert!(
                rise(c, o, Vec3::Y) < 0.0,
                "floor cluster {c:?} rises {} above the VPL's plane",
                rise(c, o, Vec3::Y)
            );
            assert!(c.sphere[1] + c.sphere[3] - o.y > 0.0, "the sphere bound alone would keep {c:?}");
        }
        // Seen from a VPL 2 mm above the ramp, the ramp's own clusters lie behind too (a tilted
        // normal, quantised to 12 bits a component).
        let ramp_o = Vec3::new(9.0, 1.0, 0.0) + Vec3::new(0.0, 0.6, 0.8) + ramp * 2e-3;
        let on_ramp: Vec<&GpuCluster> = clusters.iter().filter(|c| all_facing(c, ramp)).collect();
        assert!(on_ramp.len() > 10, "{} ramp clusters", on_ramp.len());
        for c in &on_ramp {
            assert!(
                rise(c, ramp_o, ramp) < 0.0,
                "ramp cluster {c:?} rises {} above the VPL's plane",
                rise(c, ramp_o, ramp)
            );
        }
    }
}
