//! The point pool's clusters for per-VPL point selection (`ism_select.wgsl`): the pool's points
//! are put in Morton order of their world positions and cut into runs of [`CLUSTER_POINTS`],
//! each with its bounding sphere and area, so that one GPU workgroup per VPL can weigh the
//! whole pool by solid angle in a few thousand steps instead of one per point. Rebuilt on the
//! CPU with the point data, i.e. only when geometry, transforms or weights change.

use glam::Vec3;

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
        .map(|first| {
            let range = first..(first + CLUSTER_POINTS).min(n);
            let (mut a, mut b) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
            let mut area = 0.0f32;
            for i in range.clone() {
                let p = Vec3::new(data.positions[i][0], data.positions[i][1], data.positions[i][2]);
                a = a.min(p);
                b = b.max(p);
                area += area_of(data.normals[i][3]);
            }
            let centre = (a + b) * 0.5;
            let radius = range
                .clone()
                .map(|i| Vec3::new(data.positions[i][0], data.positions[i][1], data.positions[i][2]).distance(centre))
                .fold(0.0f32, f32::max);
            GpuCluster {
                sphere: [centre.x, centre.y, centre.z, radius],
                first: first as u32,
                count: range.len() as u32,
                area,
                pad: 0,
            }
        })
        .collect()
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
}
