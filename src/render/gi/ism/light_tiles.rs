//! Where every light's view lives in ISM's light G-buffer: one square atlas of equal tiles, one
//! tile per spot light (its cone's frustum), six per point light (cube faces) and one per
//! directional light (an orthographic view fitted to the scene bounds, like its shadow map),
//! then, where objects or the sky emit, the emitter tiles: their texels hold candidate VPLs on
//! the emissive surfaces and the sky ([`super::emitter_points`]), at least
//! [`EMITTER_CANDIDATES`] of them.
//! Each texel stores the power its surface patch reflects in absolute watts, so one importance
//! pyramid over the whole atlas spreads the VPLs over all lights in proportion to the power they
//! put into the scene (Knecht 2009 section 3.3 generalised from one spot light to any set).

use glam::camera::rh::proj::directx;
use glam::camera::rh::view::look_at_mat4;
use glam::{Mat4, Vec3};

use crate::scene::{Aabb, LightKind, Scene};

/// Side of the atlas for up to 16 tiles (one spot light keeps the whole 256^2, a point light
/// 64^2 per face, as before the atlas held several lights).
pub const BASE_SIDE: u32 = 256;
/// Smallest tile once more than 16 tiles share the atlas.
pub const MIN_TILE: u32 = 64;
/// Largest atlas side (1024 tiles of 64^2: 170 point lights).
pub const MAX_SIDE: u32 = 2048;
/// Fewest candidate VPLs on the emissive surfaces: one tile of 128^2, four of 64^2 (each frame's
/// VPLs are drawn among them by power, so more candidates only refine the sampling).
pub const EMITTER_CANDIDATES: u32 = 16384;
/// Most tiles the emitters take (four of 64^2 hold [`EMITTER_CANDIDATES`]).
const MAX_EMITTER_TILES: usize = 4;

/// One light's view in the atlas.
#[derive(Clone, Debug, PartialEq)]
pub struct LightTile {
    /// Index of the light in the scene.
    pub light: usize,
    /// Clip-from-world of the tile's view.
    pub clip_from_world: Mat4,
    /// The view axis (spot direction, cube face or sun direction).
    pub axis: Vec3,
    /// tan(half field of view) of a perspective tile; 0 for an orthographic one.
    pub tan_half: f32,
    /// World area of one texel of an orthographic tile (m^2); 0 for a perspective one.
    pub ortho_texel_area: f32,
}

/// The atlas layout of this frame.
#[derive(Clone, Debug, PartialEq)]
pub struct LightTiles {
    /// Tiles in atlas order (row-major).
    pub tiles: Vec<LightTile>,
    /// Atlas side in texels (a power of two).
    pub side: u32,
    /// Tiles per atlas row (a power of two).
    pub per_row: u32,
    /// Tile side in texels.
    pub tile_size: u32,
    /// Lights left out because the atlas was full (the GI panel names them).
    pub skipped: Vec<usize>,
    /// Emitter tiles after the light tiles (0: nothing emits); texel `i` of them, counted
    /// row-major within each tile and tile after tile, holds emitter candidate `i`.
    pub emitters: u32,
}

fn up_for(dir: Vec3) -> Vec3 {
    if dir.y.abs() > 0.99 { Vec3::Z } else { Vec3::Y }
}

/// The tiles of light `index`. A light switched off keeps its tiles: they reflect nothing, so
/// the warp never picks them, and the temporal history fades as it should (an afterglow, not
/// a jump).
fn tiles_of(scene: &Scene, index: usize, bounds: &Aabb) -> Vec<LightTile> {
    let Some(l) = scene.lights().get(index) else { return Vec::new() };
    let (center, radius) = (bounds.center(), bounds.radius().max(1e-3));
    let far = radius + (center - l.position).length() + 0.01;
    let near = 0.01f32.min(0.1 * radius);
    match l.kind {
        LightKind::Spot { outer_cone_angle, .. } => {
            let fov = (2.0 * outer_cone_angle).min(170f32.to_radians());
            let view = look_at_mat4(l.position, l.position + l.direction, up_for(l.direction));
            vec![LightTile {
                light: index,
                clip_from_world: directx::perspective(fov, 1.0, near, far) * view,
                axis: l.direction,
                tan_half: (0.5 * fov).tan(),
                ortho_texel_area: 0.0,
            }]
        }
        LightKind::Point => {
            let proj = directx::perspective(std::f32::consts::FRAC_PI_2, 1.0, near, far);
            let axes = [Vec3::X, Vec3::NEG_X, Vec3::Y, Vec3::NEG_Y, Vec3::Z, Vec3::NEG_Z];
            crate::render::shadows::face_views(l.position)
                .iter()
                .zip(axes)
                .map(|(v, axis)| LightTile {
                    light: index,
                    clip_from_world: proj * *v,
                    axis,
                    tan_half: 1.0,
                    ortho_texel_area: 0.0,
                })
                .collect()
        }
        LightKind::Directional => {
            let dir = l.direction.normalize_or(Vec3::NEG_Y);
            let eye = center - dir * (2.0 * radius);
            let view = look_at_mat4(eye, center, up_for(dir));
            let proj = directx::orthographic(-radius, radius, -radius, radius, 0.0, 4.0 * radius);
            vec![LightTile {
                light: index,
                clip_from_world: proj * view,
                axis: dir,
                tan_half: 0.0,
                // Filled in once the tile size is known.
                ortho_texel_area: (2.0 * radius) * (2.0 * radius),
            }]
        }
    }
}

/// Lays out every emitting light of `scene`, and its emissive surfaces.
pub fn layout(scene: &Scene) -> LightTiles {
    let bounds = scene.bounds().unwrap_or(Aabb { min: Vec3::splat(-1.0), max: Vec3::splat(1.0) });
    let emissive = super::emitter_points::has_area_lights(scene);
    let max_tiles = (MAX_SIDE / MIN_TILE).pow(2) as usize - if emissive { MAX_EMITTER_TILES } else { 0 };
    let mut tiles = Vec::new();
    let mut skipped = Vec::new();
    for i in 0..scene.lights().len() {
        let t = tiles_of(scene, i, &bounds);
        if tiles.len() + t.len() > max_tiles {
            skipped.push(i);
        } else {
            tiles.extend(t);
        }
    }
    let grid = |count: usize| {
        let per_row = ((count.max(1) as f64).sqrt().ceil() as u32).next_power_of_two();
        let side = (per_row * MIN_TILE).clamp(BASE_SIDE, MAX_SIDE);
        (per_row, side, side / per_row)
    };
    let mut emitters = 0;
    if emissive {
        emitters = 1;
        while (emitters as usize) < MAX_EMITTER_TILES
            && emitters * grid(tiles.len() + emitters as usize).2.pow(2) < EMITTER_CANDIDATES
        {
            emitters += 1;
        }
    }
    let (per_row, side, tile_size) = grid(tiles.len() + emitters as usize);
    for t in &mut tiles {
        // World extent squared / texels squared.
        t.ortho_texel_area /= (tile_size * tile_size) as f32;
    }
    LightTiles { tiles, side, per_row, tile_size, skipped, emitters }
}

impl LightTiles {
    /// The top-left texel of tile `t`.
    pub fn origin(&self, t: usize) -> (u32, u32) {
        let t = t as u32;
        ((t % self.per_row) * self.tile_size, (t / self.per_row) * self.tile_size)
    }

    /// The tile that atlas texel `texel` (row-major index) belongs to, if any (light tiles
    /// first, then the emitter tiles).
    pub fn tile_of_texel(&self, texel: usize) -> Option<usize> {
        let (x, y) = ((texel as u32) % self.side, (texel as u32) / self.side);
        let t = (y / self.tile_size) * self.per_row + x / self.tile_size;
        ((t as usize) < self.count()).then_some(t as usize)
    }

    /// Light and emitter tiles together.
    pub fn count(&self) -> usize {
        self.tiles.len() + self.emitters as usize
    }

    /// How many emitter candidates the emitter tiles hold.
    pub fn emitter_candidates(&self) -> usize {
        self.emitters as usize * (self.tile_size * self.tile_size) as usize
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Camera, Light, Resources, SceneDesc};

    fn scene_with(lights: Vec<Light>) -> Scene {
        let project =
            crate::project_file::Project::load(&crate::project_file::default_project_path()).expect("default project");
        let desc = SceneDesc { lights, camera: Camera::default(), ..project.scene.desc().clone() };
        Scene::new(desc, Resources { ..project.scene.resources().clone() }).expect("scene")
    }

    #[test]
    fn one_light_keeps_the_single_light_layout_and_several_share_the_atlas() {
        let spot = Light::spot("s", Vec3::Y, Vec3::NEG_Y, 5.0, 0.3, 0.6);
        let point = Light::point("p", Vec3::Y, 5.0);
        let sun = Light::directional("d", Vec3::new(0.3, -1.0, 0.2), 2.0);
        let one = layout(&scene_with(vec![spot.clone()]));
        assert_eq!((one.side, one.tile_size, one.tiles.len()), (256, 256, 1));
        let cube = layout(&scene_with(vec![point.clone()]));
        assert_eq!((cube.side, cube.tile_size, cube.per_row, cube.tiles.len()), (256, 64, 4, 6));
        let three = layout(&scene_with(vec![spot, point, sun]));
        assert_eq!(three.tiles.len(), 8);
        assert_eq!(three.tiles.iter().filter(|t| t.light == 2).count(), 1);
        let sun_tile = three.tiles.iter().find(|t| t.light == 2).expect("sun tile");
        assert!(sun_tile.ortho_texel_area > 0.0 && sun_tile.tan_half == 0.0);
        // Every tile fits the atlas and texels map back to their tile.
        for t in 0..three.tiles.len() {
            let (x, y) = three.origin(t);
            assert!(x + three.tile_size <= three.side && y + three.tile_size <= three.side);
            assert_eq!(three.tile_of_texel((y * three.side + x) as usize), Some(t));
        }
        let many = layout(&scene_with((0..20).map(|i| Light::point("p", Vec3::splat(i as f32 * 0.01), 1.0)).collect()));
        assert_eq!((many.tiles.len(), many.tile_size), (120, 64));
        assert!(many.side <= MAX_SIDE && many.skipped.is_empty());
        let dark = layout(&scene_with(vec![Light::point("off", Vec3::Y, 0.0)]));
        assert_eq!(dark.tiles.len(), 6, "a light switched off keeps its tiles (its history fades)");
        assert!(layout(&scene_with(Vec::new())).tiles.is_empty());
    }

    /// Emissive objects take the tiles after the lights', enough for [`EMITTER_CANDIDATES`].
    #[test]
    fn emitters_take_enough_tiles_after_the_lights() {
        let glowing = |lights: Vec<Light>| {
            let mut scene = scene_with(lights);
            let m = scene.objects()[0].material;
            scene.desc_mut().materials[m].emissive_strength = 2.0;
            scene.desc_mut().materials[m].emissive_color = [1.0; 3];
            scene
        };
        assert_eq!(layout(&scene_with(Vec::new())).emitters, 0, "nothing emits");
        let alone = layout(&glowing(Vec::new()));
        assert_eq!((alone.emitters, alone.tile_size, alone.count()), (1, 256, 1));
        assert_eq!(alone.tile_of_texel(0), Some(0));
        let spot = Light::spot("s", Vec3::Y, Vec3::NEG_Y, 5.0, 0.3, 0.6);
        let with_spot = layout(&glowing(vec![spot]));
        assert_eq!((with_spot.tiles.len(), with_spot.emitters, with_spot.tile_size), (1, 1, 128));
        let points = layout(&glowing((0..3).map(|i| Light::point("p", Vec3::splat(i as f32), 1.0)).collect()));
        assert_eq!((points.tiles.len(), points.emitters, points.tile_size), (18, 4, 64));
        assert!(points.emitter_candidates() >= EMITTER_CANDIDATES as usize);
        let (x, y) = points.origin(points.count() - 1);
        assert_eq!(points.tile_of_texel((y * points.side + x) as usize), Some(21), "the last emitter tile");
    }
}
