//! MRT's geometry images (Loos 2015 §4.4.1, digest section 6.2): for every texel of every block
//! face, the *real* surface that the texel stands for, so that the direct light l_d is evaluated
//! on the level's walls and not on the proxy box (digest pitfall 4). The texel's surface is the
//! first one met along the face's normal through the texel centre, searched from inside the
//! block back through the face to as far behind it (the wall just behind a face fitted to a
//! wall's mid-plane, or a surface standing in front of it). Its albedo is stored with it so that
//! l_d is outgoing radiance. A texel with no surface near (an opening's glass, open sky) stores
//! none and receives no direct light.

use glam::Vec3;

use super::level::Block;
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
fn albedo(scene: &Scene, material: u32) -> Vec3 {
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
