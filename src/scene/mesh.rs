//! Triangle meshes in object space, with the helpers the importer and the samplers need
//! (bounds, computed normals, transforms baked into vertices).

use glam::{Mat3, Mat4, Vec2, Vec3, Vec4};

/// An indexed triangle mesh. All attribute arrays have one entry per vertex.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// Display name.
    pub name: String,
    /// Object-space positions.
    pub positions: Vec<Vec3>,
    /// Object-space unit normals.
    pub normals: Vec<Vec3>,
    /// Texture coordinates (set 0); zero when the source had none.
    pub uvs: Vec<Vec2>,
    /// Tangents with handedness in `w`; zero when not needed.
    pub tangents: Vec<Vec4>,
    /// Three indices per triangle, counter-clockwise = front.
    pub indices: Vec<u32>,
}

/// Axis-aligned bounds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    /// Minimum corner.
    pub min: Vec3,
    /// Maximum corner.
    pub max: Vec3,
}

/// Inconsistent mesh data.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum MeshError {
    /// An attribute has a different length than the positions.
    #[error("attribute {0} has {1} entries for {2} vertices")]
    AttributeLength(&'static str, usize, usize),
    /// The index count is not a multiple of three.
    #[error("index count {0} is not a multiple of 3")]
    NotTriangles(usize),
    /// An index points past the vertices.
    #[error("index {0} is out of range for {1} vertices")]
    IndexOutOfRange(u32, usize),
    /// A position or normal is NaN or infinite.
    #[error("vertex {0} has a non-finite value")]
    NonFinite(usize),
}

impl Aabb {
    /// Bounds of a point set, `None` when empty.
    pub fn from_points(points: impl IntoIterator<Item = Vec3>) -> Option<Self> {
        let mut it = points.into_iter();
        let first = it.next()?;
        Some(it.fold(Self { min: first, max: first }, |b, p| Self { min: b.min.min(p), max: b.max.max(p) }))
    }

    /// The smallest box containing both.
    pub fn union(&self, other: &Self) -> Self {
        Self { min: self.min.min(other.min), max: self.max.max(other.max) }
    }

    /// The bounds of this box's eight corners after `m`.
    pub fn transformed(&self, m: &Mat4) -> Self {
        let corners = (0..8).map(|i| {
            let c = Vec3::new(
                if i & 1 == 0 { self.min.x } else { self.max.x },
                if i & 2 == 0 { self.min.y } else { self.max.y },
                if i & 4 == 0 { self.min.z } else { self.max.z },
            );
            m.transform_point3(c)
        });
        Self::from_points(corners).unwrap_or(*self)
    }

    /// Centre point.
    pub fn center(&self) -> Vec3 {
        0.5 * (self.min + self.max)
    }

    /// Half the diagonal length.
    pub fn radius(&self) -> f32 {
        0.5 * (self.max - self.min).length()
    }
}

impl Mesh {
    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.indices.len() / 3
    }

    /// Object-space bounds.
    pub fn bounds(&self) -> Option<Aabb> {
        Aabb::from_points(self.positions.iter().copied())
    }

    /// The three corners of triangle `t`.
    pub fn triangle(&self, t: usize) -> [Vec3; 3] {
        let i = |k: usize| self.positions[self.indices[3 * t + k] as usize];
        [i(0), i(1), i(2)]
    }

    /// Checks lengths, index ranges and finiteness.
    pub fn validate(&self) -> Result<(), MeshError> {
        let n = self.positions.len();
        for (name, len) in [("normals", self.normals.len()), ("uvs", self.uvs.len()), ("tangents", self.tangents.len())]
        {
            if len != n {
                return Err(MeshError::AttributeLength(name, len, n));
            }
        }
        if !self.indices.len().is_multiple_of(3) {
            return Err(MeshError::NotTriangles(self.indices.len()));
        }
        if let Some(&bad) = self.indices.iter().find(|&&i| i as usize >= n) {
            return Err(MeshError::IndexOutOfRange(bad, n));
        }
        for (i, (p, nrm)) in self.positions.iter().zip(&self.normals).enumerate() {
            if !p.is_finite() || !nrm.is_finite() {
                return Err(MeshError::NonFinite(i));
            }
        }
        Ok(())
    }

    /// Area-weighted vertex normals from the triangles (for sources without normals).
    /// Vertices of degenerate-only triangles get +Y.
    pub fn compute_normals(&mut self) {
        let mut acc = vec![Vec3::ZERO; self.positions.len()];
        for tri in self.indices.chunks_exact(3) {
            let [a, b, c] = [tri[0] as usize, tri[1] as usize, tri[2] as usize];
            let (Some(pa), Some(pb), Some(pc)) = (self.positions.get(a), self.positions.get(b), self.positions.get(c))
            else {
                continue;
            };
            let n = (*pb - *pa).cross(*pc - *pa);
            for v in [a, b, c] {
                acc[v] += n;
            }
        }
        self.normals = acc.into_iter().map(|n| n.try_normalize().unwrap_or(Vec3::Y)).collect();
    }

    /// Applies `m` to the vertices (normals by the inverse transpose) and flips the winding when
    /// `m` mirrors, so the front face stays the counter-clockwise one.
    pub fn bake_transform(&mut self, m: &Mat4) {
        let normal_m = Mat3::from_mat4(*m).inverse().transpose();
        for p in &mut self.positions {
            *p = m.transform_point3(*p);
        }
        for n in &mut self.normals {
            *n = (normal_m * *n).try_normalize().unwrap_or(Vec3::Y);
        }
        for t in &mut self.tangents {
            let d = (Mat3::from_mat4(*m) * t.truncate()).try_normalize().unwrap_or(Vec3::X);
            *t = d.extend(t.w);
        }
        if m.determinant() < 0.0 {
            for tri in self.indices.chunks_exact_mut(3) {
                tri.swap(1, 2);
            }
        }
    }

    /// An axis-aligned box of the given full size centred at the origin, faces outward.
    pub fn cuboid(name: &str, size: Vec3) -> Self {
        let h = 0.5 * size;
        let mut mesh = Self { name: name.to_owned(), ..Self::default() };
        // (normal, u axis, v axis): u x v = normal so the quad is CCW seen from outside.
        let faces = [
            (Vec3::X, Vec3::NEG_Z, Vec3::Y),
            (Vec3::NEG_X, Vec3::Z, Vec3::Y),
            (Vec3::Y, Vec3::X, Vec3::NEG_Z),
            (Vec3::NEG_Y, Vec3::X, Vec3::Z),
            (Vec3::Z, Vec3::X, Vec3::Y),
            (Vec3::NEG_Z, Vec3::NEG_X, Vec3::Y),
        ];
        for (n, u, v) in faces {
            let base = mesh.positions.len() as u32;
            let c = n * h;
            let (du, dv) = (u * h, v * h);
            for (su, sv) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
                mesh.positions.push(c + du * su + dv * sv);
                mesh.normals.push(n);
                mesh.uvs.push(Vec2::new(0.5 + 0.5 * su, 0.5 - 0.5 * sv));
                mesh.tangents.push(u.extend(1.0));
            }
            mesh.indices.extend([base, base + 1, base + 2, base, base + 2, base + 3]);
        }
        mesh
    }

    /// A square in the XZ plane facing +Y, of the given side length, centred at the origin.
    pub fn plane(name: &str, size: f32) -> Self {
        let h = 0.5 * size;
        Self {
            name: name.to_owned(),
            positions: vec![Vec3::new(-h, 0.0, h), Vec3::new(h, 0.0, h), Vec3::new(h, 0.0, -h), Vec3::new(-h, 0.0, -h)],
            normals: vec![Vec3::Y; 4],
            uvs: vec![Vec2::new(0.0, 1.0), Vec2::new(1.0, 1.0), Vec2::new(1.0, 0.0), Vec2::ZERO],
            tangents: vec![Vec4::new(1.0, 0.0, 0.0, 1.0); 4],
            indices: vec![0, 1, 2, 0, 2, 3],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cuboid_faces_point_outward() {
        let m = Mesh::cuboid("b", Vec3::new(1.0, 2.0, 3.0));
        m.validate().expect("valid");
        for t in 0..m.triangle_count() {
            let [a, b, c] = m.triangle(t);
            let n = (b - a).cross(c - a);
            assert!(n.dot((a + b + c) / 3.0) > 0.0, "triangle {t} faces inward");
        }
    }

    #[test]
    fn computed_normals_match_winding() {
        let mut m = Mesh::plane("p", 2.0);
        m.normals.clear();
        m.compute_normals();
        assert!(m.normals.iter().all(|n| (*n - Vec3::Y).length() < 1e-6));
    }

    #[test]
    fn mirror_flips_winding() {
        let mut m = Mesh::plane("p", 2.0);
        m.bake_transform(&Mat4::from_scale(Vec3::new(-1.0, 1.0, 1.0)));
        let [a, b, c] = m.triangle(0);
        assert!((b - a).cross(c - a).y > 0.0);
        assert!(m.normals.iter().all(|n| (*n - Vec3::Y).length() < 1e-6));
    }
}
