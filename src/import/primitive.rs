//! Mesh primitives to [`Mesh`]es: attribute reading, index checks, strips and fans to lists,
//! computed normals and tangents.

use std::path::Path;

use glam::{Vec2, Vec3, Vec4};
use gltf::mesh::Mode;

use super::{ImportError, accessor};
use crate::scene::Mesh;

type Primitives = Vec<((usize, usize), Mesh, Option<usize>)>;

pub(super) fn load_primitives(
    doc: &gltf::Document,
    buffers: &[Vec<u8>],
    path: &Path,
) -> Result<Primitives, ImportError> {
    let mut out = Vec::new();
    for mesh in doc.meshes() {
        if mesh.primitives().len() == 0 {
            return Err(ImportError::Parse {
                path: path.to_owned(),
                message: format!("mesh {} has no primitives (glTF requires at least one)", mesh.index()),
            });
        }
        for prim in mesh.primitives() {
            if !is_triangles(prim.mode()) {
                log::warn!(
                    "{}: mesh {} primitive {} is {:?}, not triangles: skipped",
                    path.display(),
                    mesh.index(),
                    prim.index(),
                    prim.mode()
                );
                continue;
            }
            let err = |message: String| ImportError::Primitive {
                path: path.to_owned(),
                mesh: mesh.index(),
                primitive: prim.index(),
                message,
            };
            let name = format!("{}#{}", mesh.name().unwrap_or("mesh"), prim.index());
            let loaded = load(&prim, buffers, name).map_err(err)?;
            out.push(((mesh.index(), prim.index()), loaded, prim.material().index()));
        }
    }
    Ok(out)
}

/// Whether a primitive is made of triangles (lists, strips or fans): points and lines have no
/// surface to light and are skipped with a warning, not an error for the whole file.
pub(super) fn is_triangles(mode: Mode) -> bool {
    matches!(mode, Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan)
}

fn load(prim: &gltf::Primitive<'_>, buffers: &[Vec<u8>], name: String) -> Result<Mesh, String> {
    let acc_err = |e: accessor::AccessorError| e.to_string();
    let positions = prim.get(&gltf::Semantic::Positions).ok_or("no POSITION attribute")?;
    let positions: Vec<Vec3> = accessor::read_vec::<3>(&positions, buffers, "VEC3 float")
        .map_err(acc_err)?
        .into_iter()
        .map(Vec3::from)
        .collect();
    let n = positions.len();
    if let Some(i) = positions.iter().position(|p| !p.is_finite()) {
        return Err(format!("POSITION {i} is not finite"));
    }
    let mut indices = match prim.indices() {
        Some(a) => accessor::read_indices(&a, buffers).map_err(acc_err)?,
        None => (0..n as u32).collect(),
    };
    if let Some(bad) = indices.iter().find(|&&i| i as usize >= n) {
        return Err(format!("index {bad} is out of range for {n} vertices"));
    }
    indices = match prim.mode() {
        Mode::Triangles => indices,
        Mode::TriangleStrip => strip_to_list(&indices),
        Mode::TriangleFan => fan_to_list(&indices),
        other => {
            return Err(format!("mode {other:?} is not triangles; only triangle primitives are supported"));
        }
    };
    if indices.len() % 3 != 0 {
        return Err(format!("{} indices is not a whole number of triangles", indices.len()));
    }
    let attr = |sem: gltf::Semantic| prim.get(&sem);
    let normals = match attr(gltf::Semantic::Normals) {
        Some(a) => {
            let v = accessor::read_vec::<3>(&a, buffers, "VEC3 float").map_err(acc_err)?;
            Some(v.into_iter().map(Vec3::from).collect::<Vec<_>>())
        }
        None => None,
    };
    let uvs = match attr(gltf::Semantic::TexCoords(0)) {
        Some(a) => accessor::read_vec::<2>(&a, buffers, "VEC2 float or normalized")
            .map_err(acc_err)?
            .into_iter()
            .map(Vec2::from)
            .collect(),
        None => vec![Vec2::ZERO; n],
    };
    let tangents = match attr(gltf::Semantic::Tangents) {
        Some(a) => Some(
            accessor::read_vec::<4>(&a, buffers, "VEC4 float").map_err(acc_err)?.into_iter().map(Vec4::from).collect(),
        ),
        None => None,
    };
    let mut mesh = Mesh { name, positions, normals: Vec::new(), uvs, tangents: Vec::new(), indices };
    for (what, len) in [
        ("NORMAL", normals.as_ref().map(Vec::len)),
        ("TEXCOORD_0", Some(mesh.uvs.len())),
        ("TANGENT", tangents.as_ref().map(Vec::len)),
    ] {
        if let Some(len) = len.filter(|l| *l != n) {
            return Err(format!("{what} has {len} entries for {n} positions"));
        }
    }
    match normals {
        Some(v) if v.iter().all(|x| x.is_finite()) => {
            mesh.normals = v.into_iter().map(|x| x.try_normalize().unwrap_or(Vec3::Y)).collect();
        }
        Some(_) => return Err("NORMAL has non-finite values".into()),
        None => mesh.compute_normals(),
    }
    if mesh.uvs.iter().any(|u| !u.is_finite()) {
        return Err("TEXCOORD_0 has non-finite values".into());
    }
    match tangents {
        Some(t) if t.iter().all(|x| x.is_finite()) => mesh.tangents = t,
        Some(_) => return Err("TANGENT has non-finite values".into()),
        None => mesh.tangents = compute_tangents(&mesh),
    }
    mesh.validate().map_err(|e| e.to_string())?;
    Ok(mesh)
}

fn strip_to_list(idx: &[u32]) -> Vec<u32> {
    let mut out = Vec::with_capacity(idx.len().saturating_sub(2) * 3);
    for i in 2..idx.len() {
        if i % 2 == 0 {
            out.extend([idx[i - 2], idx[i - 1], idx[i]]);
        } else {
            out.extend([idx[i - 1], idx[i - 2], idx[i]]);
        }
    }
    out
}

fn fan_to_list(idx: &[u32]) -> Vec<u32> {
    let mut out = Vec::with_capacity(idx.len().saturating_sub(2) * 3);
    for i in 2..idx.len() {
        out.extend([idx[0], idx[i - 1], idx[i]]);
    }
    out
}

/// Per-vertex tangents from UV derivatives (accumulated per triangle, Gram-Schmidt against the
/// normal, handedness in `w`). Vertices without usable UVs get an arbitrary perpendicular.
pub fn compute_tangents(mesh: &Mesh) -> Vec<Vec4> {
    let n = mesh.positions.len();
    let mut tan = vec![Vec3::ZERO; n];
    let mut bit = vec![Vec3::ZERO; n];
    for tri in mesh.indices.chunks_exact(3) {
        let [a, b, c] = [tri[0] as usize, tri[1] as usize, tri[2] as usize];
        let (e1, e2) = (mesh.positions[b] - mesh.positions[a], mesh.positions[c] - mesh.positions[a]);
        let (d1, d2) = (mesh.uvs[b] - mesh.uvs[a], mesh.uvs[c] - mesh.uvs[a]);
        let det = d1.x * d2.y - d2.x * d1.y;
        if det.abs() < 1e-12 {
            continue;
        }
        let r = 1.0 / det;
        let t = (e1 * d2.y - e2 * d1.y) * r;
        let bt = (e2 * d1.x - e1 * d2.x) * r;
        for v in [a, b, c] {
            tan[v] += t;
            bit[v] += bt;
        }
    }
    (0..n)
        .map(|v| {
            let nrm = mesh.normals[v];
            let t = (tan[v] - nrm * nrm.dot(tan[v])).try_normalize().unwrap_or_else(|| nrm.any_orthonormal_vector());
            let w = if nrm.cross(t).dot(bit[v]) < 0.0 { -1.0 } else { 1.0 };
            t.extend(w)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strips_and_fans() {
        assert_eq!(strip_to_list(&[0, 1, 2, 3]), vec![0, 1, 2, 2, 1, 3]);
        assert_eq!(fan_to_list(&[0, 1, 2, 3]), vec![0, 1, 2, 0, 2, 3]);
        assert!(strip_to_list(&[0]).is_empty());
    }

    #[test]
    fn plane_tangent_is_u() {
        let m = Mesh::plane("p", 1.0);
        let t = compute_tangents(&m);
        assert!(t.iter().all(|t| (t.truncate() - Vec3::X).length() < 1e-5));
    }
}
