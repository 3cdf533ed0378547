//! Which objects are clutter (Loos 2015 ch. 5: small movable objects inside MRT blocks that the
//! blocks' operators ignore) and each one's lightmap: its world bounding box's six faces at
//! `res` x `res` texels, every texel standing for the object's own surface met along the face's
//! inward normal (a box's face is its bounding face; a cylinder's side is found where the ray
//! from the box face meets it). The DRT operators gather onto these texels and the apply pass
//! reads them for the object's pixels, choosing the face by the pixel's normal.

use glam::Vec3;

use crate::precompute::bvh::SceneBvh;
use crate::precompute::mrt::geometry_image::albedo;
use crate::precompute::mrt::level::Block;
use crate::precompute::mrt::shape::Face;
use crate::scene::{ObjectRole, Scene};

/// One clutter object and where its texels start.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Clutter {
    /// Scene object index.
    pub object: usize,
    /// World bounding box.
    pub lo: Vec3,
    pub hi: Vec3,
    /// First of its 6 x res^2 texels.
    pub first: usize,
}

/// One clutter texel's surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClutterTexel {
    /// World position (the bounding face's point where the object's surface was not found).
    pub position: Vec3,
    /// Unit normal, out of the object.
    pub normal: Vec3,
    /// Diffuse albedo.
    pub albedo: Vec3,
    /// The emission of the surface's front face at the texel's point, its emission texture
    /// included (zero for a back face or none).
    pub emission: Vec3,
    /// Whether the object's own surface was found.
    pub found: bool,
}

/// How an object became clutter (or did not), for the GI panel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Why {
    /// The artist marked it (role `Clutter`).
    Marked,
    /// Small and inside a block: automatic.
    Automatic,
}

/// The largest horizontal extent of automatic clutter, as a share of its block's smaller
/// horizontal extent (a wall stub or a long counter is structure).
pub const SMALL_SHARE: f32 = 0.5;
/// The largest height of automatic clutter, as a share of its block's height (a pillar from floor
/// to ceiling is structure).
pub const LOW_SHARE: f32 = 0.9;

/// Each object's world bounding box from the traced triangles (`None` for objects with none).
pub fn object_bounds(bvh: &SceneBvh, objects: usize) -> Vec<Option<(Vec3, Vec3)>> {
    let mut out: Vec<Option<(Vec3, Vec3)>> = vec![None; objects];
    for t in &bvh.tris {
        let Some(slot) = out.get_mut(t.object as usize) else { continue };
        let (lo, hi) =
            t.p.iter().fold((Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)), |(a, b), p| (a.min(*p), b.max(*p)));
        *slot = Some(slot.map_or((lo, hi), |(a, b)| (a.min(lo), b.max(hi))));
    }
    out
}

/// How far (metres) an automatic clutter object's box may reach past its block's, across and
/// up or down. Horizontally 1 cm: a lintel or a wall stub sits in the wall between two blocks and
/// reaches past both (taking it for clutter took the suite's rooms from FLIP 0.235 to 0.27).
/// Vertically 10 cm: fitted blocks lie on a voxel grid a few centimetres inside the room's
/// surfaces (the held-out cluttered room's blocks start 1.6 cm above its floor, so every crate
/// standing on it fell outside), and a crate stands on the floor.
pub const TOLERANCE: Vec3 = Vec3::new(0.01, 0.1, 0.01);

/// The clutter among `scene`'s objects: those marked `Clutter`, and (with `automatic`) every
/// static object not named in `exempt` whose bounding box lies inside one of `blocks` (within
/// [`TOLERANCE`]), lower than [`LOW_SHARE`] of it and narrower than [`SMALL_SHARE`] of its
/// smaller horizontal extent.
pub fn classify(
    scene: &Scene,
    bounds: &[Option<(Vec3, Vec3)>],
    blocks: &[Block],
    automatic: bool,
    exempt: &[String],
) -> Vec<(usize, Why)> {
    let mut out = Vec::new();
    for (i, object) in scene.objects().iter().enumerate() {
        let Some(Some((lo, hi))) = bounds.get(i) else { continue };
        match object.role {
            ObjectRole::Clutter => out.push((i, Why::Marked)),
            ObjectRole::Static if automatic && !exempt.contains(&object.name) => {
                let size = *hi - *lo;
                let inside = blocks.iter().any(|b| {
                    let (blo, bhi) = (b.origin - TOLERANCE, b.origin + b.size + TOLERANCE);
                    lo.cmpge(blo).all()
                        && hi.cmple(bhi).all()
                        && size.y < LOW_SHARE * b.size.y
                        && size.x.max(size.z) < SMALL_SHARE * b.size.x.min(b.size.z)
                });
                if inside {
                    out.push((i, Why::Automatic));
                }
            }
            _ => {}
        }
    }
    out
}

/// The clutter records for `objects` (scene indices) with their bounding boxes, `res` x `res`
/// texels per face.
pub fn records(objects: &[usize], bounds: &[Option<(Vec3, Vec3)>], res: usize) -> Vec<Clutter> {
    let mut first = 0;
    objects
        .iter()
        .filter_map(|&object| {
            let (lo, hi) = bounds.get(object).copied().flatten()?;
            let c = Clutter { object, lo, hi, first };
            first += 6 * res * res;
            Some(c)
        })
        .collect()
}

/// The texel of face `f`, in-plane index (s, t), of a clutter box: the world point on the
/// bounding face and the face's outward normal.
fn face_point(c: &Clutter, f: Face, s: usize, t: usize, res: usize) -> (Vec3, Vec3) {
    let unit = f.point((s as f32 + 0.5) / res as f32, (t as f32 + 0.5) / res as f32);
    (c.lo + (c.hi - c.lo) * unit, -f.inward_normal())
}

/// Every clutter object's texels (6 faces in [`Face::ALL`] order, each `res` x `res`, row t then
/// column s), found on the object's own triangles in `bvh`.
pub fn texels(scene: &Scene, bvh: &SceneBvh, clutter: &[Clutter], res: usize) -> Vec<ClutterTexel> {
    let mut out = Vec::with_capacity(clutter.len() * 6 * res * res);
    for c in clutter {
        let extent = c.hi - c.lo;
        let eps = 1e-3 * extent.length().max(1e-3);
        let material = scene.objects().get(c.object).map_or(0, |o| o.material as u32);
        for f in Face::ALL {
            let depth = extent[f.axis()] + 2.0 * eps;
            for t in 0..res {
                for s in 0..res {
                    let (q, n) = face_point(c, f, s, t, res);
                    let start = q + n * eps;
                    let hit = bvh
                        .intersect(start, -n, depth)
                        .filter(|h| bvh.tris[h.tri as usize].object as usize == c.object);
                    out.push(match hit {
                        Some(h) => {
                            let tri = &bvh.tris[h.tri as usize];
                            let front = tri.ng.dot(n) >= 0.0;
                            let normal = if front { tri.ng } else { -tri.ng };
                            let images = &scene.resources().images;
                            let emission = scene
                                .materials()
                                .get(tri.material as usize)
                                .filter(|_| front)
                                .map_or(Vec3::ZERO, |m| {
                                    crate::precompute::emitters::emission_at(m, images, tri, h.u, h.v)
                                });
                            ClutterTexel {
                                position: start - n * h.t,
                                normal,
                                albedo: albedo(scene, tri.material),
                                emission,
                                found: true,
                            }
                        }
                        None => ClutterTexel {
                            position: q,
                            normal: n,
                            albedo: albedo(scene, material),
                            emission: Vec3::ZERO,
                            found: false,
                        },
                    });
                }
            }
        }
    }
    out
}

/// The face of a clutter box a surface with normal `n` reads (its dominant axis and sign), and
/// the bilinear taps (texel index, weight) of world point `p` on it. The apply pass
/// (`mrt_apply.wgsl`, `clutter_lookup`) reads the same texels.
pub fn taps(c: &Clutter, p: Vec3, n: Vec3, res: usize) -> [(usize, f32); 4] {
    let axis = n.abs().max_position();
    let f = Face::from_axis(axis, n[axis] > 0.0);
    let extent = (c.hi - c.lo).max(Vec3::splat(1e-6));
    let u = ((p - c.lo) / extent).clamp(Vec3::ZERO, Vec3::ONE);
    let (a, b) = f.plane_axes();
    let r = res as f32;
    let coord = |v: f32| {
        let x = (v * r - 0.5).clamp(0.0, r - 1.0);
        let i = (x.floor() as usize).min(res - 1);
        (i, (i + 1).min(res - 1), x - i as f32)
    };
    let (s0, s1, fs) = coord(u[a]);
    let (t0, t1, ft) = coord(u[b]);
    let base = c.first + f as usize * res * res;
    let at = |s: usize, t: usize| base + t * res + s;
    [
        (at(s0, t0), (1.0 - fs) * (1.0 - ft)),
        (at(s1, t0), fs * (1.0 - ft)),
        (at(s0, t1), (1.0 - fs) * ft),
        (at(s1, t1), fs * ft),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_point_reads_the_face_its_normal_points_out_of() {
        let c = Clutter { object: 0, lo: Vec3::ZERO, hi: Vec3::ONE, first: 0 };
        let res = 4;
        // The +y face (index 3), point at (s, t) = (x, z) = (0.125, 0.875): texel (0, 3).
        let t = taps(&c, Vec3::new(0.125, 1.0, 0.875), Vec3::Y, res);
        assert_eq!(t[0].0, 3 * 16 + 3 * 4);
        assert!((t[0].1 - 1.0).abs() < 1e-6, "{t:?}");
        // -x face (index 0): (s, t) = (z, y).
        let t = taps(&c, Vec3::new(0.0, 0.375, 0.625), -Vec3::X, res);
        assert_eq!(t[0].0, 4 + 2);
        let total: f32 = t.iter().map(|x| x.1).sum();
        assert!((total - 1.0).abs() < 1e-6);
    }
}
