//! The CPU oracle of ISM's GPU passes: what the imperfect shadow maps and their lookups should
//! give, found by rays through the scene's BVH, against what a rendered ISM frame holds. It
//! exists because the GPU passes cannot be checked by eye: a map that misses a wall, a lookup
//! that lets light through a door's head or a bounce pass that loses power all show on screen
//! only as a slightly wrong brightness, far from where the fault is. Per bounce set it measures:
//!
//! - [`map_errors`]: per atlas texel (every fourth VPL), the share of cosine-weighted directions
//!   whose stored depth is a false occluder (nearer than the rays' first hit) or a hole (farther);
//! - [`lookups`]: per (VPL, receiver) pair, receivers spread over the surfaces by area, the lit
//!   share the ISM lookups give (`AtlasTexel` and [`IsmLookupData::lit`], the CPU twin of
//!   `ism_lit`) against the rays', with false shadow and false light;
//! - [`bounce_power`]: the power a set's VPLs hand to the next set (the bounce pass) against the
//!   power they reflect with exact visibility.
//!
//! `bouncelab probe-ism` prints these reports (docs/notes/ism-tuning.md, "Checking the imperfect
//! shadow maps"); `tests/integration/ism_oracle.rs` holds the suite's three rooms to them. Read a
//! rendered frame with [`Capture::read`], spread receivers with [`Receivers::distribute`].

use std::collections::BTreeMap;

use glam::{Vec2, Vec3};
use rayon::prelude::*;

use crate::precompute::bvh::SceneBvh;
use crate::precompute::facing;
use crate::precompute::ism::atlas_word::{self, AtlasTexel, IsmLookupData};
use crate::precompute::open_edges::CLIPS_PER_POINT;
use crate::precompute::sample_points;
use crate::render::gi::ism::technique::IsmTechnique;
use crate::render::gi::ism::vpl_pass::GpuVpl;
use crate::render::{RenderError, Renderer};
use crate::scene::Scene;
use crate::settings::{IsmSettings, RenderSettings};

/// The view size the oracle renders at (the maps do not depend on it; the VPLs' importance
/// does, a little).
pub const VIEW_SIZE: (u32, u32) = (128, 72);

/// Frames rendered before the oracle reads the maps (the first frame has no history).
pub const WARM_UP_FRAMES: usize = 2;

/// Receivers spread over the surfaces by default.
pub const RECEIVERS: usize = 20_000;

/// The most example pairs a set's [`LookupReport`] lists.
pub const SHOWN_PAIRS: usize = 12;

/// What a false-light texel holds, the rows of [`LookupReport::false_light_kinds`].
pub const FALSE_LIGHT_KINDS: [&str; 6] = [
    "empty",
    "pull-push fill or depth only",
    "the receiver's own surface (a hole)",
    "a surface beyond the true occluder",
    "a nearer surface, receiver on its plane",
    "a nearer surface, ray past its clips",
];

/// Cosines of the VPL elevation bands (3, 10 and 30 degrees): the columns of
/// [`LookupReport::false_light_kinds`] are below 3, 3-10, 10-30 and above 30 degrees.
const ELEVATION_BANDS: [f32; 3] = [0.0523, 0.1736, 0.5];

/// Why the oracle could not read or measure a frame.
#[derive(Debug, thiserror::Error)]
pub enum OracleError {
    /// Reading the technique's buffers back failed.
    #[error(transparent)]
    Render(#[from] RenderError),
    /// The renderer's active technique is not ISM.
    #[error("the renderer's active technique is not ism: render a frame in GiMode::Ism first")]
    NotIsm,
    /// A buffer read back does not fit the ISM settings given.
    #[error("{what} is {got} where these ISM settings need {need}: was the frame rendered with them?")]
    Mismatch { what: &'static str, got: usize, need: usize },
    /// A tile that holds no live VPL of this frame.
    #[error("tile {tile} holds no live VPL (this frame's VPLs fill tiles 0..{tiles})")]
    NoTile { tile: usize, tiles: usize },
}

/// Renders `frames` frames of `settings` (whose mode should be ISM) at [`VIEW_SIZE`]: what the
/// oracle reads afterwards.
pub fn render_frames(
    renderer: &mut Renderer,
    scene: &Scene,
    settings: &RenderSettings,
    frames: usize,
) -> Result<(), RenderError> {
    (0..frames).try_for_each(|_| renderer.render(scene, settings, VIEW_SIZE))
}

/// A rendered ISM frame as the oracle reads it: the atlas's words, the lookups' point data,
/// every set's VPLs, with the scene's BVH.
pub struct Capture<'a> {
    scene: &'a Scene,
    ism: IsmSettings,
    words: Vec<u32>,
    side: usize,
    lookup: IsmLookupData,
    vpls: Vec<GpuVpl>,
    bvh: SceneBvh,
    d_max: f32,
}

/// One VPL the oracle takes: its atlas tile, the VPL, its position and normal.
#[derive(Clone, Copy)]
struct Sampled {
    tile: usize,
    vpl: GpuVpl,
    o: Vec3,
    n: Vec3,
}

impl<'a> Capture<'a> {
    /// Reads the last frame `renderer` rendered in ISM mode, with settings `ism`, of `scene`.
    pub fn read(renderer: &Renderer, scene: &'a Scene, ism: &IsmSettings) -> Result<Self, OracleError> {
        let t = renderer.technique_as::<IsmTechnique>().ok_or(OracleError::NotIsm)?;
        let (device, queue) = (renderer.device(), renderer.queue());
        let (words, side) = t.read_atlas_words(device, queue)?;
        let capture = Self {
            scene,
            ism: ism.clone(),
            words,
            side: side as usize,
            lookup: t.read_lookup_data(device, queue)?,
            vpls: t.read_all_vpls(device, queue)?,
            bvh: SceneBvh::build(scene),
            d_max: 2.0 * scene.bounds().map_or(1.0, |b| b.radius()),
        };
        capture.check()?;
        Ok(capture)
    }

    /// Reads the VPLs of the frame `renderer` rendered since (the maps stay those read first).
    pub fn reread_vpls(&mut self, renderer: &Renderer) -> Result<(), OracleError> {
        let t = renderer.technique_as::<IsmTechnique>().ok_or(OracleError::NotIsm)?;
        self.vpls = t.read_all_vpls(renderer.device(), renderer.queue())?;
        self.check()
    }

    /// The ISM settings the frame was rendered with.
    pub fn settings(&self) -> &IsmSettings {
        &self.ism
    }

    /// Whether the buffers fit the settings, so that every index the oracle takes is in range.
    fn check(&self) -> Result<(), OracleError> {
        let need = |what, got: usize, need: usize| {
            (got >= need).then_some(()).ok_or(OracleError::Mismatch { what, got, need })
        };
        let res = self.res().max(1);
        need("the ISM resolution", self.res(), 1)?;
        if !self.side.is_multiple_of(res) {
            return Err(OracleError::Mismatch { what: "the atlas side", got: self.side, need: self.side / res * res });
        }
        let tiles = self.ism.bounces as usize * self.n();
        need("the atlas's tile count", self.columns() * self.columns(), tiles)?;
        need("the atlas's word count", self.words.len(), self.side * self.side)?;
        need("the VPL count", self.vpls.len(), tiles)
    }

    /// The side of one VPL's map in texels.
    fn res(&self) -> usize {
        self.ism.ism_resolution as usize
    }

    /// Maps per atlas row.
    fn columns(&self) -> usize {
        self.side / self.res().max(1)
    }

    /// VPLs per set.
    fn n(&self) -> usize {
        self.ism.vpl_count as usize
    }

    /// The atlas texel (x, y) of tile `tile`'s map: its index in the words.
    fn texel_index(&self, tile: usize, x: usize, y: usize) -> usize {
        let (c, res) = (self.columns(), self.res());
        ((tile / c) * res + y) * self.side + (tile % c) * res + x
    }

    /// The live VPL of tile `tile`, if any.
    fn vpl(&self, tile: usize) -> Option<Sampled> {
        let vpl = *self.vpls.get(tile).filter(|v| v.position[3] > 0.0)?;
        Some(Sampled { tile, vpl, o: Vec3::from_slice(&vpl.position[..3]), n: Vec3::from_slice(&vpl.normal[..3]) })
    }

    /// Every fourth live VPL of set `set` (the maps and lookups checked).
    fn sampled(&self, set: usize) -> Vec<Sampled> {
        (0..self.n()).step_by(4).filter_map(|k| self.vpl(set * self.n() + k)).collect()
    }

    /// The pool point (position, normal) an atlas word of tile `tile` names, if any.
    fn word_point(&self, word: u32, tile: usize) -> Option<([f32; 4], [f32; 4])> {
        let lookup = &self.lookup;
        let slot = atlas_word::slot(word)? as usize;
        let j = *lookup.chosen_all.get(tile * lookup.per_ism as usize + slot)? as usize;
        Some((*lookup.points.get(j)?, *lookup.normals.get(j)?))
    }

    /// The first hit along unit `dir` from the VPL at `o` (normal `n`), leaving 2 mm above its
    /// surface; infinity where the ray leaves the scene.
    fn first_hit(&self, o: Vec3, n: Vec3, dir: Vec3) -> f32 {
        self.bvh.intersect(o + n * 2e-3, dir, 1e30).map_or(f32::INFINITY, |h| h.t)
    }
}

/// The tangents completing unit `n` as `onb_tangent` / `onb_bitangent` in `common/onb.wgsl` do
/// (their CPU twin, [`crate::precompute::ism::paraboloid::frame`]).
fn onb(n: Vec3) -> (Vec3, Vec3) {
    let (t, b, _) = crate::precompute::ism::paraboloid::frame(n);
    (t, b)
}

/// A VPL's paraboloid map frame: its position, tangents and normal (`paraboloid` in
/// `common/onb.wgsl`).
struct MapFrame {
    o: Vec3,
    t: Vec3,
    b: Vec3,
    n: Vec3,
}

impl MapFrame {
    fn new(o: Vec3, n: Vec3) -> Self {
        let (t, b) = onb(n);
        Self { o, t, b, n }
    }

    /// The map coordinates (0..1 across the tile) of the point `q`.
    fn uv(&self, q: Vec3) -> Vec2 {
        let v = q - self.o;
        let l = Vec3::new(v.dot(self.t), v.dot(self.b), v.dot(self.n)) / v.length().max(1e-9);
        Vec2::new(l.x, l.y) / (1.0 + l.z) * 0.5 + Vec2::splat(0.5)
    }

    /// The direction of the centre of texel (x, y) of a map of side `res` in the frame's own
    /// coordinates (z along the normal), `None` past the rim.
    fn texel_local(x: f32, y: f32, res: f32) -> Option<Vec3> {
        let s = Vec2::new(x + 0.5, y + 0.5) / res * 2.0 - Vec2::ONE;
        let ss = s.dot(s);
        (ss <= 1.0).then(|| Vec3::new(2.0 * s.x, 2.0 * s.y, 1.0 - ss) / (1.0 + ss))
    }

    /// A direction in the frame's coordinates, in the world.
    fn world(&self, l: Vec3) -> Vec3 {
        (self.t * l.x + self.b * l.y + self.n * l.z).normalize()
    }
}

/// Luminance (Rec. 709) of an RGB(A) colour.
fn luminance(c: [f32; 4]) -> f64 {
    0.2126 * f64::from(c[0]) + 0.7152 * f64::from(c[1]) + 0.0722 * f64::from(c[2])
}

// ---------------------------------------------------------------------------------------------
// The maps.

/// How one set's maps differ from the rays: shares of the cosine-weighted directions of every
/// fourth live VPL's map.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MapReport {
    /// The bounce set.
    pub set: usize,
    /// Stored depth below 0.8 of the first hit (less 2% of the scene's span): a false occluder.
    pub false_occluder: f64,
    /// The false occluders nearer than 5% of the scene's span.
    pub near: f64,
    /// Stored depth beyond 1.25 of the first hit (plus 2% of the span): a hole.
    pub hole: f64,
}

/// One texel of a VPL's map: the direction's cosine weight, the stored distance and the rays'
/// (infinity: nothing), `None` past the rim.
fn texel_depths(c: &Capture, s: &Sampled, frame: &MapFrame, x: usize, y: usize) -> Option<(f64, f32, f32)> {
    let res = c.res();
    let l = MapFrame::texel_local(x as f32, y as f32, res as f32)?;
    let w = f64::from(l.z * (1.0 + l.z) * (1.0 + l.z));
    let truth = c.first_hit(s.o, s.n, frame.world(l));
    let d = atlas_word::depth(c.words[c.texel_index(s.tile, x, y)]);
    let stored = if d >= 1.0 { f32::INFINITY } else { d * c.d_max };
    Some((w, stored, truth))
}

/// One VPL's map: the weights of all directions, false occluders, near ones and holes.
fn tile_errors(c: &Capture, s: &Sampled) -> [f64; 4] {
    let frame = MapFrame::new(s.o, s.n);
    let mut sums = [0.0f64; 4];
    for y in 0..c.res() {
        for x in 0..c.res() {
            let Some((w, stored, truth)) = texel_depths(c, s, &frame, x, y) else { continue };
            sums[0] += w;
            if stored < 0.8 * truth - 0.02 * c.d_max {
                sums[1] += w;
                if stored < 0.05 * c.d_max {
                    sums[2] += w;
                }
            } else if stored > 1.25 * truth + 0.02 * c.d_max {
                sums[3] += w;
            }
        }
    }
    sums
}

/// How set `set`'s maps (every fourth live VPL's) differ from the rays through the scene.
pub fn map_errors(c: &Capture, set: usize) -> MapReport {
    let per_tile: Vec<[f64; 4]> = c.sampled(set).par_iter().map(|s| tile_errors(c, s)).collect();
    let sums = per_tile.iter().fold([0.0f64; 4], |a, t| std::array::from_fn(|i| a[i] + t[i]));
    MapReport { set, false_occluder: sums[1] / sums[0], near: sums[2] / sums[0], hole: sums[3] / sums[0] }
}

/// An RGBA8 image.
#[derive(Clone, Debug, PartialEq)]
pub struct Rgba8 {
    /// Width and height in pixels.
    pub width: u32,
    pub height: u32,
    /// Row-major RGBA, 4 bytes a pixel.
    pub pixels: Vec<u8>,
}

/// Tile `tile`'s stored depths (left) beside the rays' (right), white near and black from half
/// the scene's span on.
pub fn tile_depths(c: &Capture, tile: usize) -> Result<Rgba8, OracleError> {
    let tiles = c.ism.bounces as usize * c.n();
    let s = c.vpl(tile).filter(|_| tile < tiles).ok_or(OracleError::NoTile { tile, tiles })?;
    let (res, frame) = (c.res(), MapFrame::new(s.o, s.n));
    let shade = |t: f32| (255.0 * (1.0 - (t / (0.5 * c.d_max)).min(1.0))) as u8;
    let mut pixels = vec![0u8; res * 2 * res * 4];
    for y in 0..res {
        for x in 0..res {
            let Some((_, stored, truth)) = texel_depths(c, &s, &frame, x, y) else { continue };
            for (col, t) in [(x, stored), (x + res, truth)] {
                let i = (y * 2 * res + col) * 4;
                pixels[i..i + 4].copy_from_slice(&[shade(t), shade(t), shade(t), 255]);
            }
        }
    }
    Ok(Rgba8 { width: 2 * res as u32, height: res as u32, pixels })
}

mod bounce;
mod lanes;
mod lookups;
mod points;

pub use bounce::*;
pub use lanes::*;
pub use lookups::*;
pub use points::*;
