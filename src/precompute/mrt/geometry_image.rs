//! MRT's geometry images (Loos 2015 §3.5.2 and §4.4.1): for every texel of every block face, the
//! *real* surface that the texel stands for, so that the direct light l_d is evaluated on the
//! level's walls and not on the proxy box, as §4.4.1 requires. The texel's surface is the
//! first one met along the face's normal through the texel centre, searched from inside the
//! block back through the face to as far behind it (the wall just behind a face fitted to a
//! wall's mid-plane, or a surface standing in front of it). Its albedo is stored with it so that
//! l_d is outgoing radiance. A texel with no surface near (an opening's glass, open sky) stores
//! none and receives no direct light; instead it lets in the sky: its radiance is the sky's
//! cosine-weighted mean over the directions out of the block that no geometry blocks (a window
//! is a portal that emits the sky it sees). An emissive front face adds its emission, so the
//! block's transfer carries emitters' light like any other l_d (the brief's "sky and emissive
//! light enter l_d").

use glam::Vec3;

use super::level::{Block, Level};
use super::opening::Opening;
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
    /// Radiance the texel sends into the block on its own: the emission of the surface's front
    /// face (its emission texture read at the texel's point), or where no surface was found, the
    /// sky seen through it.
    pub emission: Vec3,
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
        return TexelSurface { position: p, normal: n, albedo: Vec3::ZERO, emission: Vec3::ZERO, found: false };
    };
    let tri = &bvh.tris[hit.tri as usize];
    let front = tri.ng.dot(n) > 0.0;
    let normal = if front { tri.ng } else { -tri.ng };
    let emission = match scene.materials().get(tri.material as usize) {
        Some(m) if front && m.emits() => {
            crate::precompute::emitters::emission_at(m, &scene.resources().images, tri, hit.u, hit.v)
        }
        _ => Vec3::ZERO,
    };
    TexelSurface { position: start - n * hit.t, normal, albedo: albedo(scene, tri.material), emission, found: true }
}

/// Directions for [`sky_through`]: a Hammersley set, cosine-distributed about +Z.
const SKY_RAYS: u32 = 64;

/// The sky's cosine-weighted mean radiance over the directions out of a block (about `out`)
/// from `p` that no geometry blocks: what a hole in a closed face lets in (`sky`: the scene's
/// [`Scene::sky_texels`]).
pub fn sky_through(scene: &Scene, sky: Option<&crate::scene::SkyImage>, bvh: &SceneBvh, p: Vec3, out: Vec3) -> Vec3 {
    if !scene.has_sky() {
        return Vec3::ZERO;
    }
    let (t, b) = crate::scene::basis::basis(out);
    let mut sum = Vec3::ZERO;
    for i in 0..SKY_RAYS {
        let u = (i as f32 + 0.5) / SKY_RAYS as f32;
        let v = (i.reverse_bits() as f64 / 4_294_967_296.0) as f32;
        let (r, phi) = (u.sqrt(), 2.0 * std::f32::consts::PI * v);
        let d = (t * (r * phi.cos()) + b * (r * phi.sin()) + out * (1.0 - u).max(0.0).sqrt()).normalize();
        if bvh.occluded(p, d, f32::INFINITY) {
            continue;
        }
        sum += scene.environment().radiance(d, sky);
    }
    sum / SKY_RAYS as f32
}

/// The geometry image of `block`: one surface per sample of its layout at `res` texels per side
/// (`sky`: the scene's [`Scene::sky_texels`], computed once per level by the caller: the analytic
/// sky is baked on each call).
pub fn geometry_image(
    scene: &Scene,
    sky: Option<&crate::scene::SkyImage>,
    bvh: &SceneBvh,
    block: &Block,
    res: usize,
) -> Vec<TexelSurface> {
    let layout = Layout::new(block.shape, res);
    (0..layout.len())
        .map(|i| {
            let (face, _, p, n) = layout.sample(i);
            let w = block.world_point(p);
            let nw = block.world_dir(n).normalize_or_zero();
            let across = block.size[block.world_face(face).axis()];
            let mut s = surface(scene, bvh, w, nw, SEARCH.min(0.45 * across));
            if !s.found {
                s.emission = sky_through(scene, sky, bvh, w, -nw);
            }
            s
        })
        .collect()
}

/// The frame of light leaving a block through one of its world sides (`lightfield::frame` in
/// world space): opening coordinates (u across, v up, both 0..1) to world points on the side.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SideFrame {
    /// The side's centre on its plane.
    pub centre: Vec3,
    /// Unit normal out of the block.
    pub n: Vec3,
    /// Unit u direction (n x up).
    pub u: Vec3,
    /// The side's width along u and its bottom and top heights.
    pub width: f32,
    pub bottom: f32,
    pub top: f32,
}

impl SideFrame {
    /// The frame of block `i`'s world side `w`; `None` for a floor or ceiling (no up-aligned u).
    pub fn new(level: &Level, i: usize, w: Face) -> Option<Self> {
        let axis = w.axis();
        if axis == 1 {
            return None;
        }
        let mut n = Vec3::ZERO;
        n[axis] = if w.positive() { 1.0 } else { -1.0 };
        let u = n.cross(Vec3::Y);
        let (plane, lo, hi) = level.side_rect(i, w);
        let mut centre = 0.5 * (lo + hi);
        centre[axis] = plane;
        let width = level.blocks[i].size[u.abs().max_position()];
        Some(Self { centre, n, u, width, bottom: lo.y, top: hi.y })
    }

    /// The world point at opening coordinates (`fu`, `fv`) in [0, 1]^2.
    pub fn point(&self, fu: f32, fv: f32) -> Vec3 {
        let mut q = self.centre + self.u * (self.width * (fu - 0.5));
        q.y = self.bottom + (self.top - self.bottom) * fv;
        q
    }
}

/// What the real geometry leaves open of each linked block side, per light-field position
/// (`positions`^2 cells in the frame of light leaving the block: u = n x up, v = up; see
/// [`super::opening`]): 3 x 3 segments per cell across the side (`SEARCH` either way, at most
/// 45% of the block's depth across it), the share that meets no surface, and the grey albedo of
/// the surface that closes the rest as seen from inside the block. A room's doorway side is open
/// only at the doorway (lintel closed); a side between two parts of one room is open everywhere.
pub fn openings(scene: &Scene, bvh: &SceneBvh, level: &Level, positions: usize) -> Vec<((usize, Face), Opening)> {
    const SUB: usize = 3;
    let p = positions.max(1);
    level
        .linked_sides()
        .into_iter()
        .map(|(i, w)| {
            let Some(frame) = SideFrame::new(level, i, w) else {
                // A floor or ceiling opening has no up-aligned frame: counted open.
                return ((i, w), Opening::uniform(p, 1.0, 0.0));
            };
            let n = frame.n;
            let reach = SEARCH.min(0.45 * level.blocks[i].size[w.axis()]);
            let mut open = vec![0.0; p * p];
            let mut grey = vec![0.0; p * p];
            for (cell, (o, a)) in open.iter_mut().zip(grey.iter_mut()).enumerate() {
                let (ci, cj) = (cell % p, cell / p);
                let (mut passed, mut closed_albedo) = (0usize, 0.0f32);
                for sub in 0..SUB * SUB {
                    let fu = ((ci * SUB + sub % SUB) as f32 + 0.5) / (p * SUB) as f32;
                    let fv = ((cj * SUB + sub / SUB) as f32 + 0.5) / (p * SUB) as f32;
                    match bvh.intersect(frame.point(fu, fv) - n * reach, n, 2.0 * reach) {
                        None => passed += 1,
                        Some(hit) => {
                            let c = albedo(scene, bvh.tris[hit.tri as usize].material);
                            closed_albedo += (c.x + c.y + c.z) / 3.0;
                        }
                    }
                }
                let closed = SUB * SUB - passed;
                *o = passed as f64 / (SUB * SUB) as f64;
                *a = if closed > 0 { f64::from(closed_albedo) / closed as f64 } else { 0.0 };
            }
            ((i, w), Opening { open, albedo: grey })
        })
        .collect()
}
