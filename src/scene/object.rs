//! Scene objects: a mesh with a material, a transform, a sampling weight and a role.

use glam::{Mat4, Quat, Vec3};
use serde::{Deserialize, Serialize};

use super::{SceneError, check_finite};

/// Translation, rotation and scale (applied scale first, then rotation, then translation).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Transform {
    /// Translation in metres.
    pub translation: Vec3,
    /// Unit quaternion.
    pub rotation: Quat,
    /// Per-axis scale.
    pub scale: Vec3,
}

impl Default for Transform {
    fn default() -> Self {
        Self { translation: Vec3::ZERO, rotation: Quat::IDENTITY, scale: Vec3::ONE }
    }
}

impl Transform {
    /// World-from-object matrix.
    pub fn matrix(&self) -> Mat4 {
        Mat4::from_scale_rotation_translation(self.scale, self.rotation, self.translation)
    }

    /// A transform that is exactly `m`, if `m` has no shear and no mirroring.
    pub fn from_matrix_exact(m: &Mat4) -> Option<Self> {
        if m.determinant() <= 0.0 || m.row(3) != glam::Vec4::W {
            return None;
        }
        let (scale, rotation, translation) = m.to_scale_rotation_translation();
        // Decomposition noise (0.99999994 for a pure rotation) would leak into project files.
        let scale = scale.map(|s| if (s - s.round()).abs() < 1e-6 && s.round() != 0.0 { s.round() } else { s });
        let t = Self { translation, rotation, scale };
        let err = (t.matrix() - *m).to_cols_array().iter().fold(0.0f32, |a, v| a.max(v.abs()));
        let size = m.to_cols_array().iter().fold(1.0f32, |a, v| a.max(v.abs()));
        (err <= 1e-5 * size).then_some(t)
    }
}

/// What an object is for.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum ObjectRole {
    /// Ordinary static scene geometry.
    #[default]
    Static,
    /// A proxy block: a closed box for Modular Radiance Transfer.
    ProxyBlock,
    /// Clutter: a small movable object handled by Delta Radiance Transfer.
    Clutter,
}

/// Where an object's mesh comes from, so a project file can rebuild it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum MeshSource {
    /// Primitive `primitive` of mesh `mesh` in asset `asset` (index into the project's assets).
    Asset {
        /// Index of the asset in the project's asset list.
        asset: usize,
        /// glTF mesh index.
        mesh: usize,
        /// glTF primitive index within the mesh.
        primitive: usize,
        /// A world matrix baked into the vertices (sheared or mirrored node transforms).
        baked: Option<Mat4>,
    },
    /// A generated box of the given full size.
    Cuboid {
        /// Full size along X, Y, Z.
        size: Vec3,
        /// Faces that are open (+X, -X, +Y, -Y, +Z, -Z): for proxy blocks, the interfaces
        /// through which light passes to a neighbouring block.
        #[serde(default)]
        openings: [bool; 6],
    },
    /// A generated square facing +Y.
    Plane {
        /// Side length.
        size: f32,
    },
}

/// A renderable object.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Object {
    /// Display name.
    pub name: String,
    /// Where the mesh comes from.
    pub source: MeshSource,
    /// Index into the scene's meshes (runtime; rebuilt from `source` when loading).
    #[serde(skip)]
    pub mesh: usize,
    /// Index into the scene's materials.
    pub material: usize,
    /// Object-to-world transform.
    pub transform: Transform,
    /// Multiplies triangle area when scene sample points are distributed (>= 0, default 1).
    pub sampling_weight: f32,
    /// Static geometry, proxy block or clutter.
    pub role: ObjectRole,
    /// Hidden objects are neither drawn nor traced.
    pub visible: bool,
}

impl Object {
    /// Whether the object is drawn and traced as geometry. Proxy blocks are approximations
    /// of the level for MRT and show only as wireframes.
    pub fn is_rendered(&self) -> bool {
        self.visible && self.role != ObjectRole::ProxyBlock
    }

    /// Checks numbers and ranges.
    pub fn validate(&self) -> Result<(), SceneError> {
        let what = format!("object {:?}", self.name);
        let t = &self.transform;
        check_finite(&what, &t.translation.to_array())?;
        check_finite(&what, &t.rotation.to_array())?;
        check_finite(&what, &t.scale.to_array())?;
        check_finite(&what, &[self.sampling_weight])?;
        super::limits::check_position(&what, t.translation)?;
        super::limits::check_rotation(&what, t.rotation)?;
        super::limits::check_scale(&what, t.scale)?;
        if self.sampling_weight < 0.0 {
            return Err(SceneError::BadValue { what, why: "sampling weight must be >= 0".into() });
        }
        match &self.source {
            MeshSource::Cuboid { size, .. } if size.min_element() <= 0.0 || !size.is_finite() => {
                Err(SceneError::BadValue { what, why: format!("box size {size} must be positive") })
            }
            MeshSource::Plane { size } if *size <= 0.0 || !size.is_finite() => {
                Err(SceneError::BadValue { what, why: format!("plane size {size} must be positive") })
            }
            _ => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_decomposition() {
        let t = Transform {
            translation: Vec3::new(1.0, 2.0, 3.0),
            rotation: Quat::from_rotation_y(0.3),
            scale: Vec3::new(2.0, 1.0, 0.5),
        };
        let back = Transform::from_matrix_exact(&t.matrix()).expect("decomposes");
        assert!((back.matrix() - t.matrix()).abs_diff_eq(Mat4::ZERO, 1e-5));
        let mirror = Mat4::from_scale(Vec3::new(-1.0, 1.0, 1.0));
        assert!(Transform::from_matrix_exact(&mirror).is_none());
        let shear =
            Mat4::from_cols_array(&[1.0, 0.0, 0.0, 0.0, 0.5, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0]);
        assert!(Transform::from_matrix_exact(&shear).is_none());
    }
}
