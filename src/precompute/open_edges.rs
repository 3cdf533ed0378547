//! Where each ISM sample point's surface ends: the open edges (boundaries and creases sharper
//! than [`CREASE_DEGREES`]) of the surface within reach of the point's splat. An ISM splat is the
//! footprint of a disk standing for the point's share of the surface; near an edge that disk
//! hangs past the geometry (over a doorway, past a wall's end) and casts a shadow no surface
//! casts. The splat pass clips each disk against the point's nearby open edges, so occluders
//! stop where the geometry stops and splats can be large enough to leave no holes.
//!
//! Edges are found in object space once per point distribution (they move with their
//! objects); [`PointClips::world_lines`] turns them into world-space lines in each point's plane.

use std::collections::HashMap;

use glam::Vec3;

use super::bvh::SceneBvh;
use super::sample_points::SamplePoint;
use crate::scene::{Mesh, Scene};

/// Clip lines kept per point (the nearest open edges; a box face's corner needs two).
pub const CLIPS_PER_POINT: usize = 4;

/// Edges whose two faces' normals differ by more than this are creases (open): a box's 90°
/// edges are, a 16-sided cylinder's 22.5° facet edges are not (the disk spans smooth curvature
/// as before).
pub const CREASE_DEGREES: f32 = 30.0;

/// Triangles searched per point at most (the coplanar region within the splat's reach).
const MAX_VISITS: usize = 64;

/// No clip line (the slot's index).
pub const NO_CLIP: u32 = u32::MAX;

/// One open edge in object space: its end points and a point on its inner side (the opposite
/// vertex of its triangle).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClipEdge {
    /// Object index in the scene.
    pub object: u32,
    /// The edge's end points (object space).
    pub a: Vec3,
    /// Second end point.
    pub b: Vec3,
    /// The opposite vertex of the edge's triangle: the side the surface is on.
    pub inner: Vec3,
    /// Other geometry continues the surface past the edge (`abuts`): splats are clipped only
    /// [`ClipEdge::overhang`] past it, and the ISM lookup's neighbour test stops at it (see
    /// [`SEAM_SCALE`]).
    pub seam: bool,
    /// At a seam, how far (world metres, along the face's plane) the solid the surface runs
    /// into extends past the edge (`solid_past`): a disk may hang that far into it and no
    /// farther. A partition's face hung 1.2 m past the 0.15 m corridor wall it butts into and
    /// shadowed the corridor beyond (the held-out offices' lamp lit its far end 0.73 of the
    /// rays' light, `bouncelab probe-ism`). Where the face is buried in a solid that ends at
    /// the edge (an opening's jamb, [`buried_end`]) about 0; where nothing says how far, the
    /// splat's reach (not clipped). 0 where the edge is open.
    pub overhang: f32,
}

/// Seam lines are stored scaled by this factor plus the seam's overhang in metres (direction
/// and offset alike, so the half-plane is the same): the splats and a texel's own lookup clip
/// at the line moved out by the overhang (a disk overhanging a seam hangs into solid geometry,
/// but no farther than that solid reaches), while a neighbouring texel's point may not shadow
/// a ray past the seam itself (a partition's plane, continued through the wall it butts into,
/// falsely shadowed the corridor beyond it).
pub const SEAM_SCALE: f32 = 2.0;

/// Whether `h` passes one world clip `line` of [`PointClips::world_lines`], less `margin`: an
/// open edge's line (unit xyz) when dot(xyz, h) >= w; a seam's (xyz of length s =
/// [`SEAM_SCALE`] + overhang) when `h` lies no more than the overhang past it, or with `seams`
/// when it lies inside the seam itself. The CPU statement of `within_edges` in `ism_clips.wgsl`.
pub fn line_admits(line: &[f32; 4], h: Vec3, margin: f32, seams: bool) -> bool {
    let d = Vec3::new(line[0], line[1], line[2]);
    let s = d.length();
    if !seams && s * s > 2.0 {
        d.dot(h) / s >= line[3] / s - (s - SEAM_SCALE) - margin
    } else {
        d.dot(h) >= line[3] - margin
    }
}

/// The open edges near each sample point.
#[derive(Clone, Debug, Default)]
pub struct PointClips {
    /// Distinct edges (object space).
    pub edges: Vec<ClipEdge>,
    /// Per point, up to [`CLIPS_PER_POINT`] indices into `edges` (nearest first; [`NO_CLIP`]
    /// fills the rest).
    pub per_point: Vec<[u32; CLIPS_PER_POINT]>,
}

/// An undirected edge by the bit patterns of its end points (lower first).
type EdgeKey = ([u32; 3], [u32; 3]);

/// For each triangle edge (k: vertex k to k + 1) the triangle across it when the two join
/// smoothly, else `NO_CLIP` (an open edge).
fn smooth_neighbours(mesh: &Mesh) -> Vec<[u32; 3]> {
    let key = |p: Vec3| (p + Vec3::ZERO).to_array().map(f32::to_bits);
    let mut by_edge: HashMap<EdgeKey, Vec<(u32, usize)>> = HashMap::new();
    let tris = mesh.triangle_count();
    for t in 0..tris {
        let v = mesh.triangle(t);
        for k in 0..3 {
            let (a, b) = (key(v[k]), key(v[(k + 1) % 3]));
            by_edge.entry(if a < b { (a, b) } else { (b, a) }).or_default().push((t as u32, k));
        }
    }
    let normal = |t: u32| {
        let [a, b, c] = mesh.triangle(t as usize);
        (b - a).cross(c - a).normalize_or_zero()
    };
    let crease = CREASE_DEGREES.to_radians().cos();
    let mut out = vec![[NO_CLIP; 3]; tris];
    for sharing in by_edge.values() {
        if let [(t0, k0), (t1, k1)] = sharing.as_slice()
            && normal(*t0).dot(normal(*t1)) >= crease
        {
            out[*t0 as usize][*k0] = *t1;
            out[*t1 as usize][*k1] = *t0;
        }
    }
    out
}

/// Distance from `p` to the segment a..b.
fn segment_distance(p: Vec3, a: Vec3, b: Vec3) -> f32 {
    let ab = b - a;
    let s = ((p - a).dot(ab) / ab.length_squared().max(f32::MIN_POSITIVE)).clamp(0.0, 1.0);
    (p - (a + ab * s)).length()
}

/// Whether other geometry continues the surface past `edge` (world transform `m`): a wall's
/// face ending on the floor it stands on, or against the wall it butts into. Rays from just
/// inside the edge and `eps` in front of the face, running outwards along the face, hit that
/// geometry within a few `eps` at all three test positions. Such an edge is a concave seam, not
/// a place where the surface ends: a disk overhanging it hangs into solid geometry and casts no
/// shadow that geometry does not, and clipping there would leave a crack along every seam
/// (light leaked through the held-out apartment's wall bases).
fn abuts(bvh: &SceneBvh, edge: &ClipEdge, m: glam::Mat4, eps: f32) -> bool {
    let (a, b, inner) = (m.transform_point3(edge.a), m.transform_point3(edge.b), m.transform_point3(edge.inner));
    let Some(n) = (b - a).cross(inner - a).try_normalize() else { return false };
    let Some(mut inward) = n.cross(b - a).try_normalize() else { return false };
    if inward.dot(inner - a) < 0.0 {
        inward = -inward;
    }
    // The front side only: from behind, a ray inside a slab meets the slab's own next face.
    [0.25f32, 0.5, 0.75].into_iter().all(|s| {
        let origin = a + (b - a) * s + inward * eps + n * eps;
        bvh.occluded(origin, -inward, 4.0 * eps)
    })
}

/// How far past `edge` (world transform `m`, a seam) the solid it abuts reaches along the face's
/// plane: from the three positions `abuts` tests, `eps` in front of the face, the nearest exit
/// from a solid (a triangle met from behind, after one met from the front) along the outward
/// direction. A position whose first hit is an exit starts inside a third solid overlapping the
/// corner (a floor's edge under the partition standing on it, a face buried against another
/// solid) and says nothing unless that solid ends at an opening's jamb ([`buried_end`]); the
/// largest of what the positions say is taken, and `limit` (the disk is not clipped) where none
/// says anything: such seams, clipped where they stand, let light along the walls' bases (the suite's
/// third room read 1.27x the reference).
fn solid_past(bvh: &SceneBvh, edge: &ClipEdge, m: glam::Mat4, eps: f32, limit: f32) -> f32 {
    let (a, b, inner) = (m.transform_point3(edge.a), m.transform_point3(edge.b), m.transform_point3(edge.inner));
    let Some(n) = (b - a).cross(inner - a).try_normalize() else { return limit };
    let Some(mut inward) = n.cross(b - a).try_normalize() else { return limit };
    if inward.dot(inner - a) < 0.0 {
        inward = -inward;
    }
    [0.25f32, 0.5, 0.75]
        .into_iter()
        .filter_map(|s| {
            let origin = a + (b - a) * s + inward * eps + n * eps;
            let hits = bvh.hits_along(origin, -inward, limit + eps);
            match hits.as_slice() {
                [(_, false), ..] => {
                    Some(hits.iter().find(|&&(_, back)| back).map_or(limit, |&(t, _)| (t - eps).clamp(0.0, limit)))
                }
                [(exit, true), ..] => buried_end(bvh, origin, -inward, n, *exit, eps, limit),
                [] => None,
            }
        })
        .reduce(f32::max)
        .unwrap_or(limit)
}

/// At a seam whose test position (`origin`, `eps` in front of the face of normal `n`, looking
/// `out` along it) lies inside a solid: the face is buried against that solid (a corridor wall's
/// end against the room wall it meets). Where the solid ends (`exit`, the first hit, met from
/// behind) at the jamb of an opening, a disk hanging past it hangs across the opening and shadows
/// what shines through it (the slab-built corridor level read 0.73 of the path tracer's energy,
/// `bouncelab probe`): it may hang only as far as the solid reaches. That holds where, just past
/// the exit, the point lies in no solid ([`super::facing::is_buried`]), no surface runs on in
/// the face's plane (a partition's face below a ceiling slab's buried end), and geometry
/// encloses it every way (an opening inside the level, not the void outside its shell, where a
/// disk shadows nothing; clipping those read the rooms at 1.141). Elsewhere nothing is said.
fn buried_end(bvh: &SceneBvh, origin: Vec3, out: Vec3, n: Vec3, exit: f32, eps: f32, limit: f32) -> Option<f32> {
    let past = origin + out * (exit + 2.0 * eps);
    let open = !super::facing::is_buried(bvh, past, out, 0.0);
    let continued = bvh.occluded(past, -n, 3.0 * eps);
    let side = n.cross(out);
    let enclosed = [out, -out, n, -n, side, -side].into_iter().all(|d| bvh.occluded(past, d, f32::MAX));
    (open && !continued && enclosed).then(|| (exit - eps).clamp(0.0, limit))
}

/// Finds the open edges within `reach` metres of each point (searched over the smooth surface
/// around the point's triangle), keeping only edges the point lies inside of; `eps` is the
/// distance within which other geometry continuing the surface makes an edge a seam (`abuts`).
pub fn point_clips(scene: &Scene, points: &[SamplePoint], reach: f32, eps: f32) -> PointClips {
    let objects = scene.objects();
    let meshes = &scene.resources().meshes;
    let mut topology: HashMap<usize, Vec<[u32; 3]>> = HashMap::new();
    let bvh = SceneBvh::build(scene);
    // Per (object, triangle, edge): the edge's index in `edges`, or NO_CLIP where it abuts
    // other geometry.
    let mut ids: HashMap<(u32, u32, usize), u32> = HashMap::new();
    let mut out = PointClips { edges: Vec::new(), per_point: Vec::with_capacity(points.len()) };
    for sp in points {
        let mut slots = [NO_CLIP; CLIPS_PER_POINT];
        let Some((object, mesh)) = objects.get(sp.object as usize).and_then(|o| meshes.get(o.mesh).map(|m| (o, m)))
        else {
            out.per_point.push(slots);
            continue;
        };
        if sp.triangle as usize >= mesh.triangle_count() {
            out.per_point.push(slots);
            continue;
        }
        let neighbours = topology.entry(object.mesh).or_insert_with(|| smooth_neighbours(mesh));
        // Reach in object space: the world radius over the smallest scale.
        let scale = object.transform.scale.abs().min_element().max(1.0e-6);
        let r = reach / scale;
        let [a, b, c] = mesh.triangle(sp.triangle as usize);
        let p = a + (b - a) * sp.bary.x + (c - a) * sp.bary.y;
        let n = (b - a).cross(c - a).normalize_or_zero();
        let mut found: Vec<(f32, u32, usize)> = Vec::new();
        let mut queue = vec![sp.triangle];
        let mut seen = vec![sp.triangle];
        while let Some(t) = queue.pop() {
            let v = mesh.triangle(t as usize);
            for k in 0..3 {
                let (ea, eb, inner) = (v[k], v[(k + 1) % 3], v[(k + 2) % 3]);
                let d = segment_distance(p, ea, eb);
                if d > r {
                    continue;
                }
                let across = neighbours[t as usize][k];
                if across == NO_CLIP {
                    let inward = n.cross(eb - ea);
                    let side = inward.dot(inner - ea).signum();
                    if inward.dot(p - ea) * side > 0.0 {
                        found.push((d, t, k));
                    }
                } else if !seen.contains(&across) && seen.len() < MAX_VISITS {
                    seen.push(across);
                    queue.push(across);
                }
            }
        }
        found.sort_by(|x, y| x.0.total_cmp(&y.0));
        let m = object.transform.matrix();
        let found: Vec<u32> = found
            .into_iter()
            .map(|(_, t, k)| {
                *ids.entry((sp.object, t, k)).or_insert_with(|| {
                    let v = mesh.triangle(t as usize);
                    let mut edge = ClipEdge {
                        object: sp.object,
                        a: v[k],
                        b: v[(k + 1) % 3],
                        inner: v[(k + 2) % 3],
                        seam: false,
                        overhang: 0.0,
                    };
                    edge.seam = abuts(&bvh, &edge, m, eps);
                    if edge.seam {
                        edge.overhang = solid_past(&bvh, &edge, m, eps, reach);
                    }
                    out.edges.push(edge);
                    (out.edges.len() - 1) as u32
                })
            })
            .collect();
        // The nearest open edges first (the splats' clips), then the nearest seams.
        let (open, seams): (Vec<u32>, Vec<u32>) = found.into_iter().partition(|&id| !out.edges[id as usize].seam);
        for (slot, id) in slots.iter_mut().zip(open.into_iter().chain(seams)) {
            *slot = id;
        }
        out.per_point.push(slots);
    }
    out
}

impl PointClips {
    /// World-space clip lines, [`CLIPS_PER_POINT`] per point in point order: xyz the inward
    /// direction in the point's plane (world normal `normals[i]`), w its offset; a texel's hit h
    /// on the point's plane is on the surface when dot(xyz, h) >= w for every open edge's line
    /// (unit xyz) and dot(xyz, h) / s >= w / s - (s - [`SEAM_SCALE`]) for every seam's (xyz of
    /// length s = [`SEAM_SCALE`] + its overhang), and within its seams when dot(xyz, h) >= w
    /// for the seams' too. Empty slots are (0, 0, 0, -1), which every hit passes.
    pub fn world_lines(&self, scene: &Scene, normals: &[Vec3]) -> Vec<[f32; 4]> {
        let objects = scene.objects();
        let mut lines = Vec::with_capacity(self.per_point.len() * CLIPS_PER_POINT);
        for (slots, n) in self.per_point.iter().zip(normals) {
            for &slot in slots {
                let line = self.edges.get(slot as usize).and_then(|e| {
                    let m = objects.get(e.object as usize)?.transform.matrix();
                    let (a, b, inner) = (m.transform_point3(e.a), m.transform_point3(e.b), m.transform_point3(e.inner));
                    let mut inward = n.cross(b - a).normalize_or_zero();
                    if inward.dot(inner - a) < 0.0 {
                        inward = -inward;
                    }
                    let scale = if e.seam { SEAM_SCALE + e.overhang } else { 1.0 };
                    (inward != Vec3::ZERO).then(|| (inward * scale).extend(inward.dot(a) * scale).to_array())
                });
                lines.push(line.unwrap_or([0.0, 0.0, 0.0, -1.0]));
            }
        }
        lines
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 4 x 4 m floor slab and a free-standing 2 m wide, 2 m high, 0.2 m thick wall on it.
    fn wall_on_floor() -> Scene {
        let parts = [
            ("floor", Vec3::new(0.0, -0.1, 0.0), Vec3::new(4.0, 0.2, 4.0)),
            ("wall", Vec3::new(0.0, 1.0, 0.0), Vec3::new(2.0, 2.0, 0.2)),
        ];
        crate::precompute::test_scenes::scene_of_slabs(&parts, Vec::new())
    }

    /// Whether `h` lies within point `i`'s clip `lines` (past its seams by their overhang at
    /// most; with `seams`, within the seams themselves), as `within_edges` in `ism_clips.wgsl`.
    fn within(lines: &[[f32; 4]], i: usize, h: Vec3, seams: bool) -> bool {
        lines[i * CLIPS_PER_POINT..(i + 1) * CLIPS_PER_POINT].iter().all(|l| line_admits(l, h, 0.0, seams))
    }

    /// Per sample point its object, world position and normal, and the points' clip lines.
    type Clipped = (Vec<u32>, Vec<(Vec3, Vec3)>, Vec<[f32; 4]>);

    /// Sample points of `scene` with their world positions and normals, and their clip lines.
    fn clipped_points(scene: &Scene) -> Clipped {
        let points = crate::precompute::sample_points::distribute(scene, 4000, 1, 3);
        let clips = point_clips(scene, &points.points, 10.0, 0.01);
        let world = points.world(scene);
        let normals: Vec<Vec3> = world.iter().map(|(_, n)| *n).collect();
        let lines = clips.world_lines(scene, &normals);
        (points.points.iter().map(|p| p.object).collect(), world, lines)
    }

    #[test]
    fn a_partitions_disk_hangs_into_the_wall_it_butts_into_but_not_through_it() {
        // A 0.15 m wall (z in [0, 0.15]) and a partition butting into it (x in [0, 0.15],
        // z from 0.15), both on a floor: the held-out offices' corridor wall and partition.
        let parts = [
            ("floor", Vec3::new(0.0, -0.1, 0.0), Vec3::new(6.0, 0.2, 6.0)),
            ("wall", Vec3::new(0.0, 1.0, 0.075), Vec3::new(6.0, 2.0, 0.15)),
            ("partition", Vec3::new(0.075, 1.0, 1.575), Vec3::new(0.15, 2.0, 2.85)),
        ];
        let scene = crate::precompute::test_scenes::scene_of_slabs(&parts, Vec::new());
        let (objects, world, lines) = clipped_points(&scene);
        let mut checked = 0;
        for (i, (p, n)) in world.iter().enumerate() {
            // Points on the partition's face x = 0.15 within a disk's reach of the wall.
            if objects[i] != 2 || n.x < 0.99 || p.z > 0.6 || p.y < 0.3 || p.y > 1.7 {
                continue;
            }
            checked += 1;
            // Inside the wall the disk may hang (the seam is no crack) ...
            assert!(within(&lines, i, Vec3::new(0.15, p.y, 0.05), false), "point {p}: clipped inside the wall");
            // ... but not through it into the space on the wall's other side.
            assert!(!within(&lines, i, Vec3::new(0.15, p.y, -0.3), false), "point {p}: hangs through the wall");
            assert!(!within(&lines, i, Vec3::new(0.15, p.y, 0.05), true), "point {p}: no seam line at the wall");
        }
        assert!(checked > 3, "points on the partition's face near the wall: {checked}");
    }

    /// Two 5 x 3 x 4 m rooms of 0.2 m slabs joined by a 0.6 m slab corridor with 1.8 x 2.4 m
    /// doorways at its ends (`slab_corridors` in `tools/unseen_levels.py`, two rooms); the
    /// index of the first room's corridor wall on the doorway's low-z side.
    fn slab_corridor() -> (Scene, u32) {
        let (t, h, x, z, gap, dz0, dz1, dh) = (0.2f32, 3.0f32, 5.0f32, 4.0f32, 0.6f32, 1.1f32, 2.9f32, 2.4f32);
        let mut boxes: Vec<(String, Vec3, Vec3)> = Vec::new();
        let mut add = |name: String, lo: Vec3, hi: Vec3| boxes.push((name, lo, hi));
        for k in 0..2 {
            let x0 = k as f32 * (x + 2.0 * t + gap);
            add(format!("floor{k}"), Vec3::new(x0 - t, -t, -t), Vec3::new(x0 + x + t, 0.0, z + t));
            add(format!("ceiling{k}"), Vec3::new(x0 - t, h, -t), Vec3::new(x0 + x + t, h + t, z + t));
            add(format!("south{k}"), Vec3::new(x0 - t, 0.0, -t), Vec3::new(x0 + x + t, h, 0.0));
            add(format!("north{k}"), Vec3::new(x0 - t, 0.0, z), Vec3::new(x0 + x + t, h, z + t));
            for (door, xa) in [(k == 1, x0 - t), (k == 0, x0 + x)] {
                if door {
                    add(format!("jamb{k}a{xa}"), Vec3::new(xa, 0.0, 0.0), Vec3::new(xa + t, h, dz0));
                    add(format!("jamb{k}b{xa}"), Vec3::new(xa, 0.0, dz1), Vec3::new(xa + t, h, z));
                    add(format!("lintel{k}{xa}"), Vec3::new(xa, dh, dz0), Vec3::new(xa + t, h, dz1));
                } else {
                    add(format!("end{k}{xa}"), Vec3::new(xa, 0.0, 0.0), Vec3::new(xa + t, h, z));
                }
            }
        }
        let xa = x + t;
        add("corridor_floor".into(), Vec3::new(xa, -t, dz0 - t), Vec3::new(xa + gap, 0.0, dz1 + t));
        add("corridor_ceiling".into(), Vec3::new(xa, dh, dz0 - t), Vec3::new(xa + gap, dh + t, dz1 + t));
        add("corridor_south".into(), Vec3::new(xa, 0.0, dz0 - t), Vec3::new(xa + gap, dh, dz0));
        add("corridor_north".into(), Vec3::new(xa, 0.0, dz1), Vec3::new(xa + gap, dh, dz1 + t));
        let wall = boxes.iter().position(|(n, _, _)| n == "corridor_south").expect("wall") as u32;
        let parts: Vec<(&str, Vec3, Vec3)> =
            boxes.iter().map(|(n, lo, hi)| (n.as_str(), (*lo + *hi) * 0.5, *hi - *lo)).collect();
        (crate::precompute::test_scenes::scene_of_slabs(&parts, Vec::new()), wall)
    }

    #[test]
    fn a_corridor_walls_buried_end_does_not_hang_across_the_doorway_it_meets() {
        // The corridor wall's end (x = 5.2, facing the first room) is buried against the room
        // wall, whose jamb (z = 1.1) is where the wall's end stops: its disks hung past it, as
        // far as their reach, into the doorway and shadowed the next room (the slab corridor
        // level read 0.73).
        let (scene, wall) = slab_corridor();
        let points = crate::precompute::sample_points::distribute(&scene, 40_000, 1, 3);
        let clips = point_clips(&scene, &points.points, 0.5, 0.001);
        let world = points.world(&scene);
        let normals: Vec<Vec3> = world.iter().map(|(_, n)| *n).collect();
        let lines = clips.world_lines(&scene, &normals);
        let mut checked = 0;
        for (i, (p, n)) in world.iter().enumerate() {
            if points.points[i].object != wall || n.x > -0.99 || p.y < 0.3 || p.y > 2.1 {
                continue;
            }
            checked += 1;
            assert!(within(&lines, i, Vec3::new(5.2, p.y, 1.0), false), "point {p}: clipped on its own face");
            assert!(!within(&lines, i, Vec3::new(5.2, p.y, 1.15), false), "point {p}: hangs into the doorway");
        }
        assert!(checked >= 3, "points on the corridor wall's buried end: {checked}");
        // The corridor floor's end (x = 5.2, buried against the room's floor slab) ends where
        // that slab ends too, at the building's underside: past it lies the void outside the
        // level, not an opening, and its disks keep hanging there (clipping such disks read
        // the suite's rooms at 1.141).
        let floor = scene.objects().iter().position(|o| o.name == "corridor_floor").expect("floor") as u32;
        let mut under = 0;
        for (i, (p, n)) in world.iter().enumerate() {
            if points.points[i].object != floor || n.x > -0.99 || p.z < 1.3 || p.z > 2.7 {
                continue;
            }
            under += 1;
            assert!(within(&lines, i, Vec3::new(5.2, -0.3, p.z), false), "point {p}: clipped at the shell");
        }
        assert!(under >= 3, "points on the corridor floor's buried end: {under}");
    }

    #[test]
    fn splats_are_clipped_at_a_walls_free_end_and_top_but_not_where_it_stands() {
        let scene = wall_on_floor();
        let (objects, world, lines) = clipped_points(&scene);
        let within = |i: usize, h: Vec3, seams: bool| within(&lines, i, h, seams);
        let inside = |i: usize, h: Vec3| within(i, h, false);
        let mut checked = 0;
        for (i, (p, n)) in world.iter().enumerate() {
            // Points on the wall's front face (z = 0.1, facing +z).
            if objects[i] != 1 || n.z < 0.99 {
                continue;
            }
            checked += 1;
            // Past the free end (x > 1) and above the top (y > 2): off the surface.
            assert!(!inside(i, Vec3::new(1.2, p.y, 0.1)), "point {p}: the free end clips");
            assert!(!inside(i, Vec3::new(p.x, 2.2, 0.1)), "point {p}: the top clips");
            // Below the bottom edge the wall stands on the floor (y in [-0.2, 0]): a seam, not
            // clipped within the floor's slab ...
            assert!(inside(i, Vec3::new(p.x, -0.15, 0.1)), "point {p}: the seam with the floor clips");
            // ... but below it, where the floor no longer stands behind the plane.
            assert!(!inside(i, Vec3::new(p.x, -0.3, 0.1)), "point {p}: the disk hangs below the floor");
            // ... and the seam line itself is there for the lookups' neighbour test.
            assert!(!within(i, Vec3::new(p.x, -0.1, 0.1), true), "point {p}: no seam line at the floor");
            assert!(within(i, *p, true), "point {p} lies inside its seams");
            assert!(inside(i, *p), "point {p} lies inside its own lines");
        }
        assert!(checked > 50, "points on the wall's front face: {checked}");
    }
}
