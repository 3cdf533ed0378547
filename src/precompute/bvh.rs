//! World-space triangles of a scene in a four-wide BVH (`wide_bvh.rs`, collapsed from `obvhs`'s
//! binary one), for the path tracer and any other CPU ray queries (picking, visibility
//! precomputation).

use super::wide_bvh::WideBvh;
use glam::{Vec2, Vec3, Vec3A, Vec4};

use crate::scene::Scene;

/// One world-space triangle with its shading attributes.
#[derive(Clone, Copy, Debug)]
pub struct Tri {
    pub p: [Vec3; 3],
    pub n: [Vec3; 3],
    pub uv: [Vec2; 3],
    pub tangent: [Vec4; 3],
    /// Unit geometric normal of the CCW (front) side.
    pub ng: Vec3,
    /// Object index in the scene.
    pub object: u32,
    /// Material index.
    pub material: u32,
}

/// A ray hit: distance, triangle and barycentrics (weights `1-u-v`, `u`, `v`).
#[derive(Clone, Copy, Debug)]
pub struct Hit {
    pub t: f32,
    pub tri: u32,
    pub u: f32,
    pub v: f32,
}

/// The scene's triangles and their BVH.
pub struct SceneBvh {
    pub tris: Vec<Tri>,
    bvh: WideBvh,
    /// Scene size (bounds radius), for epsilons.
    pub scale: f32,
}

impl SceneBvh {
    /// Collects visible objects' triangles in world space and builds the BVH.
    pub fn build(scene: &Scene) -> Self {
        Self::build_where(scene, |_| true)
    }

    /// [`Self::build`] of the objects for which `keep(object index)` holds (MRT's geometry
    /// images leave clutter out).
    pub fn build_where(scene: &Scene, keep: impl Fn(usize) -> bool) -> Self {
        let mut tris = Vec::new();
        for (oi, object) in scene.objects().iter().enumerate() {
            if !keep(oi) {
                continue;
            }
            let Some(mesh) = scene.resources().meshes.get(object.mesh).filter(|_| object.is_rendered()) else {
                continue;
            };
            let m = object.transform.matrix();
            let nm = glam::Mat3::from_mat4(m).inverse().transpose();
            let flip = m.determinant() < 0.0;
            for idx in mesh.indices.chunks_exact(3) {
                let mut k = [idx[0] as usize, idx[1] as usize, idx[2] as usize];
                if flip {
                    k.swap(1, 2);
                }
                let p = k.map(|i| m.transform_point3(mesh.positions[i]));
                let ng = (p[1] - p[0]).cross(p[2] - p[0]);
                let Some(ng) = ng.try_normalize() else { continue };
                tris.push(Tri {
                    p,
                    n: k.map(|i| (nm * mesh.normals[i]).try_normalize().unwrap_or(ng)),
                    uv: k.map(|i| mesh.uvs[i]),
                    tangent: k.map(|i| {
                        let t = mesh.tangents[i];
                        (glam::Mat3::from_mat4(m) * t.truncate()).normalize_or_zero().extend(t.w)
                    }),
                    ng,
                    object: oi as u32,
                    material: object.material as u32,
                });
            }
        }
        let corners: Vec<[Vec3A; 3]> = tris.iter().map(|t| t.p.map(Vec3A::from)).collect();
        let bvh = WideBvh::build(&corners);
        let scale = scene.bounds().map_or(1.0, |b| b.radius().max(1e-3));
        Self { tris, bvh, scale }
    }

    /// The closest hit along `o + t d` for `0 < t < tmax`.
    pub fn intersect(&self, o: Vec3, d: Vec3, tmax: f32) -> Option<Hit> {
        let (tri, t, u, v) = self.bvh.closest(Vec3A::from(o), Vec3A::from(d), tmax)?;
        Some(Hit { t, tri, u, v })
    }

    /// Every hit along `o + t d` for `0 < t < tmax`, nearest first: its distance and whether
    /// the ray meets the triangle's back (it leaves a solid there).
    pub fn hits_along(&self, o: Vec3, d: Vec3, tmax: f32) -> Vec<(f32, bool)> {
        let mut hits = Vec::new();
        self.bvh.all(Vec3A::from(o), Vec3A::from(d), tmax, |tri, t| {
            hits.push((t, self.tris[tri as usize].ng.dot(d) > 0.0));
        });
        hits.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        hits
    }

    /// Whether anything lies along `o + t d` for `0 < t < tmax`.
    pub fn occluded(&self, o: Vec3, d: Vec3, tmax: f32) -> bool {
        self.bvh.any(Vec3A::from(o), Vec3A::from(d), tmax)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Material, Mesh, MeshSource, Object, ObjectRole, Resources, SceneDesc, Transform};

    #[test]
    fn negative_zero_directions_hit() {
        let desc = SceneDesc {
            materials: vec![Material::default()],
            objects: vec![Object {
                name: "floor".into(),
                source: MeshSource::Plane { size: 4.0 },
                mesh: 0,
                material: 0,
                transform: Transform::default(),
                sampling_weight: 1.0,
                role: ObjectRole::Static,
                visible: true,
            }],
            ..SceneDesc::default()
        };
        let scene = Scene::new(desc, Resources { meshes: vec![Mesh::plane("floor", 4.0)], images: vec![], sky: None })
            .expect("scene");
        let bvh = SceneBvh::build(&scene);
        let o = Vec3::new(0.48, 1.0, 0.13);
        let hit = bvh.intersect(o, Vec3::new(-0.0, -1.0, -0.0), f32::INFINITY).expect("hits the floor");
        assert!((hit.t - 1.0).abs() < 1e-5);
        assert!(bvh.occluded(o, Vec3::new(-0.0, -1.0, -0.0), 2.0));
        assert!(!bvh.occluded(o, Vec3::new(-0.0, -1.0, -0.0), 0.5));
    }
}
