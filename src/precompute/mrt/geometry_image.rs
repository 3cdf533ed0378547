//! MRT's geometry images (Loos 2015 §4.4.1, digest section 6.2): for every texel of every block
//! face, the *real* surface that the texel stands for, so that the direct light l_d is evaluated
//! on the level's walls and not on the proxy box (digest pitfall 4). The texel's surface is the
//! first one met along the face's normal through the texel centre, searched from inside the
//! block back through the face to as far behind it (the wall just behind a face fitted to a
//! wall's mid-plane, or a surface standing in front of it). Its albedo is stored with it so that
//! l_d is outgoing radiance. A texel with no surface near (an opening's glass, open sky) stores
//! none and receives no direct light.

use glam::Vec3;

use super::level::{Block, Level};
use super::shape::Face;
use super::shape::Layout;
use crate::precompute::bvh::SceneBvh;
use crate::scene::Scene;

/// How far (metres, at most 45% of the block across the face) the search reaches either side of
/// a face: walls are fitted to their mid-plane, so their surface lies half a wall thickness in.
pub const SEARCH: f32 = 0.5;

/// The real surface of one texel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TexelSurface {
    /// World position (the proxy texel centre where none was found).
    pub position: Vec3,
    /// Unit normal, facing into the block.
    pub normal: Vec3,
    /// Diffuse albedo (zero where none was found).
    pub albedo: Vec3,
    /// Whether a real surface was found.
    pub found: bool,
}

/// The albedo of a material index (its base colour factor; textures are not read).
pub fn albedo(scene: &Scene, material: u32) -> Vec3 {
    scene.materials().get(material as usize).map_or(Vec3::splat(0.8), |m| Vec3::from_slice(&m.base_color[..3]))
}

/// The real surface behind the world point `p` of a face with inward unit normal `n`, searched
/// `reach` metres either side.
pub fn surface(scene: &Scene, bvh: &SceneBvh, p: Vec3, n: Vec3, reach: f32) -> TexelSurface {
    let start = p + n * reach;
    let Some(hit) = bvh.intersect(start, -n, 2.0 * reach) else {
        return TexelSurface { position: p, normal: n, albedo: Vec3::ZERO, found: false };
    };
    let tri = &bvh.tris[hit.tri as usize];
    let normal = if tri.ng.dot(n) > 0.0 { tri.ng } else { -tri.ng };
    TexelSurface { position: start - n * hit.t, normal, albedo: albedo(scene, tri.material), found: true }
}

/// The geometry image of `block`: one surface per sample of its layout at `res` texels per side.
pub fn geometry_image(scene: &Scene, bvh: &SceneBvh, block: &Block, res: usize) -> Vec<TexelSurface> {
    let layout = Layout::new(block.shape, res);
    (0..layout.len())
        .map(|i| {
            let (face, _, p, n) = layout.sample(i);
            let w = block.world_point(p);
            let nw = block.world_dir(n).normalize_or_zero();
            let across = block.size[block.world_face(face).axis()];
            surface(scene, bvh, w, nw, SEARCH.min(0.45 * across))
        })
        .collect()
}

/// The share of each linked block side that the real geometry leaves open: the points of an
/// 8 x 8 grid on the side whose segment across it (`SEARCH` either way, at most 45% of the
/// block's depth across the side) meets no surface. A room's doorway side passes only the
/// doorway's share (lintel included); a side between two parts of one room passes all.
pub fn transmissions(bvh: &SceneBvh, level: &Level) -> Vec<((usize, Face), f64)> {
    const GRID: usize = 8;
    level
        .linked_sides()
        .into_iter()
        .map(|(i, w)| {
            let (plane, lo, hi) = level.side_rect(i, w);
            let axis = w.axis();
            let (a, b) = ((axis + 1) % 3, (axis + 2) % 3);
            let reach = SEARCH.min(0.45 * level.blocks[i].size[axis]);
            let mut n = Vec3::ZERO;
            n[axis] = 1.0;
            let mut open = 0;
            for u in 0..GRID {
                for v in 0..GRID {
                    let mut p = Vec3::ZERO;
                    p[axis] = plane;
                    p[a] = lo[a] + (hi[a] - lo[a]) * (u as f32 + 0.5) / GRID as f32;
                    p[b] = lo[b] + (hi[b] - lo[b]) * (v as f32 + 0.5) / GRID as f32;
                    if !bvh.occluded(p - n * reach, n, 2.0 * reach) {
                        open += 1;
                    }
                }
            }
            ((i, w), f64::from(open) / (GRID * GRID) as f64)
        })
        .collect()
}
