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
/// (n.z = -0 counts as positive there).
fn onb(n: Vec3) -> (Vec3, Vec3) {
    let s = if n.z >= 0.0 { 1.0 } else { -1.0 };
    let a = -1.0 / (s + n.z);
    let b = n.x * n.y * a;
    (Vec3::new(1.0 + s * n.x * n.x * a, s * b, -s * n.x), Vec3::new(b, s + n.y * n.y * a, -n.y))
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

// ---------------------------------------------------------------------------------------------
// Receivers and rooms.

/// Points spread over the scene's surfaces by area (the pool's distribution), each with what the
/// oracle asks of it.
pub struct Receivers {
    /// Position and normal.
    world: Vec<(Vec3, Vec3)>,
    /// Whether the point lies inside solid geometry (a floor's face running on under a wall).
    buried: Vec<bool>,
    /// Luminance of its material's base colour (the Lambertian albedo).
    albedo: Vec<f64>,
    /// The area each stands for.
    area: f64,
}

impl Receivers {
    /// About `count` receivers over `c`'s scene (seed 9, one block).
    pub fn distribute(c: &Capture, count: usize) -> Self {
        let scene = c.scene;
        let samples = sample_points::distribute(scene, count, 1, 9);
        let world = samples.world(scene);
        let buried = world.par_iter().map(|&(p, n)| facing::is_buried(&c.bvh, p, n, 1e-4 * c.bvh.scale)).collect();
        let albedo = samples
            .points
            .iter()
            .map(|pt| {
                let material = scene.objects().get(pt.object as usize).map_or(usize::MAX, |o| o.material);
                luminance(scene.materials().get(material).cloned().unwrap_or_default().base_color)
            })
            .collect();
        let area = samples.weighted_area.iter().sum::<f64>() / world.len().max(1) as f64;
        Self { world, buried, albedo, area }
    }

    /// How many there are.
    pub fn len(&self) -> usize {
        self.world.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.world.is_empty()
    }
}

/// Which (VPL, receiver) pairs count, by the rooms they are in.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PairFilter {
    /// Split the plan into rooms at x and z (room = [x >] + 2 [z >]); `None`: the suite's three
    /// rooms, x / 5.2.
    pub grid: Option<(f32, f32)>,
    /// Only pairs in different rooms (light through doorways).
    pub cross: bool,
    /// Only VPLs in room a (any: -1) and receivers in room b.
    pub pair: Option<(f32, f32)>,
}

impl PairFilter {
    /// The room point `p` is in.
    pub fn room(&self, p: Vec3) -> f32 {
        match self.grid {
            Some((x, z)) => f32::from(u8::from(p.x > x)) + 2.0 * f32::from(u8::from(p.z > z)),
            None => (p.x / 5.2).floor(),
        }
    }

    /// Whether the pair of a VPL at `o` and a receiver at `p` counts.
    pub fn keeps(&self, o: Vec3, p: Vec3) -> bool {
        let (a, b) = (self.room(o), self.room(p));
        !(self.cross && a == b) && self.pair.is_none_or(|(pa, pb)| (pa < 0.0 || pa == a) && pb == b)
    }

    /// The room of `p` as an index of the four [`BounceReport`] keeps (clamped to 0..=3).
    fn room_index(&self, p: Vec3) -> usize {
        self.room(p).clamp(0.0, 3.0) as usize
    }
}

/// Set `set`'s live VPLs by room: count and luminance power.
pub fn vpls_by_room(c: &Capture, filter: &PairFilter, set: usize) -> BTreeMap<i32, (u32, f64)> {
    let mut rooms = BTreeMap::<i32, (u32, f64)>::new();
    for v in (0..c.n()).filter_map(|k| c.vpl(set * c.n() + k)) {
        let e = rooms.entry(filter.room(v.o) as i32).or_default();
        e.0 += 1;
        e.1 += luminance(v.vpl.power);
    }
    rooms
}

/// Whether receiver `p` (normal `pn`) sees the VPL at `o` (normal `nn`): the ray between them,
/// each end lifted off its surface by 1 mm (a first-bounce VPL comes from the light's G-buffer
/// depth and may lie a fraction of a millimetre inside its surface, which a ray to the exact
/// position would count as shadowing every receiver).
fn sees(bvh: &SceneBvh, p: Vec3, pn: Vec3, o: Vec3, nn: Vec3) -> bool {
    let (a, b) = (p + pn * 1e-3, o + nn * 1e-3);
    let d = (b - a).length();
    d <= 0.0 || !bvh.occluded(a, (b - a) / d, d)
}

/// A VPL and a receiver that face each other: distance, the cosines at the VPL and at the
/// receiver.
#[derive(Clone, Copy)]
struct Facing {
    d: f32,
    cos_s: f32,
    cos_r: f32,
}

/// The pair's geometry, `None` unless they face each other at least 1 mm apart.
fn facing(o: Vec3, nn: Vec3, p: Vec3, pn: Vec3) -> Option<Facing> {
    let to_p = p - o;
    let d = to_p.length();
    let dir = to_p / d;
    let (cos_s, cos_r) = (nn.dot(dir), pn.dot(-dir));
    (cos_s > 0.0 && cos_r > 0.0 && d >= 1e-3).then_some(Facing { d, cos_s, cos_r })
}

// ---------------------------------------------------------------------------------------------
// The lookups.

/// What the lookups of one set give against the rays. The weights are each pair's form factor
/// cos_s cos_r / d^2 (times the VPL's luminance power with [`LookupOptions::power_weighted`]).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LookupReport {
    /// The bounce set.
    pub set: usize,
    /// The weight of the pairs the rays light.
    pub rays: f64,
    /// The weight of the pairs the ISM lookups light.
    pub ism: f64,
    /// Lit by the rays, shadowed by the lookups.
    pub false_shadow: f64,
    /// The part of `false_shadow` the texel's own point's slab casts.
    pub own_slab: f64,
    /// Shadowed by the rays, lit by the lookups.
    pub false_light: f64,
    /// The weight of every pair.
    pub pairs: f64,
    /// The false light's weight times the VPL's power (r + g + b), by what the texel holds
    /// ([`FALSE_LIGHT_KINDS`]) and the VPL's elevation band (below 3, 3-10, 10-30, above 30
    /// degrees).
    pub false_light_kinds: [[f64; 4]; 6],
    /// Up to [`SHOWN_PAIRS`] wrongly lit or shadowed pairs, as [`ShowOptions`] asks.
    pub examples: Vec<PairExample>,
}

impl LookupReport {
    /// The lit share the lookups give over the rays' (1: right on average).
    pub fn lit_ratio(&self) -> f64 {
        self.ism / self.rays
    }

    /// Adds another VPL's pairs (its examples after these, up to [`SHOWN_PAIRS`]).
    fn add(&mut self, o: LookupReport) {
        self.rays += o.rays;
        self.ism += o.ism;
        self.false_shadow += o.false_shadow;
        self.own_slab += o.own_slab;
        self.false_light += o.false_light;
        self.pairs += o.pairs;
        for (row, other) in self.false_light_kinds.iter_mut().zip(o.false_light_kinds) {
            row.iter_mut().zip(other).for_each(|(a, b)| *a += b);
        }
        let room = SHOWN_PAIRS.saturating_sub(self.examples.len());
        self.examples.extend(o.examples.into_iter().take(room));
    }
}

/// Which pairs [`lookups`] counts and lists.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LookupOptions {
    /// Which pairs count, by room.
    pub filter: PairFilter,
    /// Weight the pairs by the VPL's luminance power too (what the screen sees).
    pub power_weighted: bool,
    /// Only receivers on surfaces open to the air (not a floor under a wall).
    pub unburied: bool,
    /// Which wrongly lit or shadowed pairs to list.
    pub show: ShowOptions,
}

/// Which wrongly lit or shadowed pairs [`LookupReport::examples`] lists.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ShowOptions {
    /// False light (lit by the lookups, shadowed by the rays).
    pub false_light: bool,
    /// False shadow, of the last set, with both cosines above 0.2.
    pub false_shadow: bool,
    /// Each with the texel's four neighbours and its coarse levels.
    pub neighbours: bool,
    /// False light of this row of [`FALSE_LIGHT_KINDS`] only.
    pub kind: Option<usize>,
    /// False light of VPLs above this cosine of elevation only.
    pub min_cos: f32,
}

/// A wrongly lit or shadowed (VPL, receiver) pair.
#[derive(Clone, Debug, PartialEq)]
pub struct PairExample {
    /// The VPL's atlas tile.
    pub tile: usize,
    /// The VPL's position and normal.
    pub vpl: (Vec3, Vec3),
    /// The receiver's position and normal.
    pub receiver: (Vec3, Vec3),
    /// The map texel looked up.
    pub texel: Vec2,
    /// The texel's stored distance in metres.
    pub stored: f32,
    /// The distance of the lookup point q (the receiver lifted by the bias) from the VPL.
    pub q_distance: f32,
    /// The rays' first hit towards q, from the VPL.
    pub first_hit: f32,
    /// False shadow or false light, with what each adds.
    pub what: ExampleKind,
    /// The texel's neighbours and coarse levels ([`ShowOptions::neighbours`]; else empty).
    pub neighbours: Vec<NeighbourWord>,
}

/// Whether a [`PairExample`] is false shadow or false light.
#[derive(Clone, Debug, PartialEq)]
pub enum ExampleKind {
    /// Lit by the rays, not by the lookup: the texel's slot.
    FalseShadow { slot: Option<u32> },
    /// Lit by the lookup, not by the rays: the VPL's point spacing, the lookup point, the
    /// texel's mark bit (depth only) and the point its word names.
    FalseLight { sigma: f32, q: Vec3, mark: u32, point: Option<([f32; 4], [f32; 4])> },
}

/// A texel near the one looked up: where, its distance in metres, the point it names.
#[derive(Clone, Debug, PartialEq)]
pub struct NeighbourWord {
    /// Which texel.
    pub at: NeighbourAt,
    /// Its stored distance in metres.
    pub depth: f32,
    /// The pool point (position, normal) its word names, if any.
    pub point: Option<([f32; 4], [f32; 4])>,
}

/// Where a [`NeighbourWord`] is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NeighbourAt {
    /// Offset from the texel (0, 0 is the texel itself).
    Offset(i64, i64),
    /// The texel's word at this coarse level (1: half the side).
    Level(u32),
}

/// The texel at atlas index `at` and its four neighbours, then its coarse levels: their
/// distances and points (one texel holds one surface; the lost one is often next door).
fn neighbours(c: &Capture, at: usize, tile: usize) -> Vec<NeighbourWord> {
    let side = c.side as i64;
    let word = |at: NeighbourAt, i: i64| {
        let w = *c.words.get(usize::try_from(i).ok()?)?;
        Some(NeighbourWord { at, depth: atlas_word::depth(w) * c.d_max, point: c.word_point(w, tile) })
    };
    let mut list: Vec<NeighbourWord> = [(0i64, 0i64), (-1, 0), (1, 0), (0, -1), (0, 1)]
        .into_iter()
        .filter_map(|(dx, dy)| word(NeighbourAt::Offset(dx, dy), at as i64 + dy * side + dx))
        .collect();
    let (x, y, s) = ((at % c.side) as u32, (at / c.side) as u32, c.side as u32);
    for level in 1..=atlas_word::HOLE_LEVELS {
        let i = s * s + atlas_word::level_base(s, level) + (y >> level) * (s >> level) + (x >> level);
        list.extend(word(NeighbourAt::Level(level), i64::from(i)));
    }
    list
}

/// Which row of [`FALSE_LIGHT_KINDS`] a false-light lookup's texel word is: receiver `p`
/// (normal `pn`) whose ray from VPL `o` along `dir` first meets geometry at `wall`.
fn false_light_kind(
    c: &Capture,
    word: u32,
    tile: usize,
    (p, pn): (Vec3, Vec3),
    wall: f32,
    dir: Vec3,
    o: Vec3,
) -> usize {
    if word == u32::MAX {
        return 0;
    }
    let Some((sp, sn)) = c.word_point(word, tile).filter(|_| word & 1 == 0) else { return 1 };
    let (sp, sn) = (Vec3::from_slice(&sp[..3]), Vec3::from_slice(&sn[..3]));
    if sn.dot(pn) > 0.99 && (sp - p).dot(pn).abs() < 0.02 {
        return 2;
    }
    if (sp - o).length() > wall * 1.05 {
        return 3;
    }
    let den = dir.dot(sn);
    let t = if den.abs() > 1e-6 { (sp - o).dot(sn) / den } else { -1.0 };
    if t <= 0.0 || t >= (p - o).length() * 0.999 { 4 } else { 5 }
}

/// One ISM lookup as `ism_lit` makes it: the lookup point q (the receiver lifted along its
/// normal by the bias), its offset from the VPL and distance, the texel, its atlas index, and
/// whether the lookup lights it.
struct Lookup {
    q: Vec3,
    dir: Vec3,
    qd: f32,
    texel: Vec2,
    at: usize,
    lit: bool,
}

/// The lookup for receiver `p` (normal `pn`) of VPL `s` (map frame `frame`).
fn look_up(c: &Capture, s: &Sampled, frame: &MapFrame, (p, pn): (Vec3, Vec3), f: &Facing) -> Lookup {
    let (res, sigma) = (c.res() as f32, s.vpl.normal[3]);
    let sin_r = (1.0 - f.cos_r * f.cos_r).max(0.0).sqrt();
    let delta = f.d * sigma * (c.ism.bias_constant + c.ism.bias_slope * sin_r);
    let q = p + pn * delta;
    let qq = q - s.o;
    let qd = qq.length();
    let texel = ((frame.uv(q) * res).floor().max(Vec2::ZERO)).min(Vec2::splat(res - 1.0));
    let at = c.texel_index(s.tile, texel.x as usize, texel.y as usize);
    let atlas = AtlasTexel {
        words: &c.words,
        r: c.res() as u32,
        c: c.columns() as u32,
        texel: (texel.x as u32, texel.y as u32),
    };
    let lit = c.lookup.lit(atlas, s.o, sigma, s.tile as u32, qq / qd, qd, qd / c.d_max, 8.0 / res);
    Lookup { q, dir: qq / qd, qd, texel, at, lit }
}

/// One sampled VPL's pairs as [`lookups`] counts them.
struct VplPairs<'c, 'a> {
    c: &'c Capture<'a>,
    s: Sampled,
    frame: MapFrame,
    opts: &'c LookupOptions,
    /// Whether this is the last set (the only one whose false shadow is listed).
    last_set: bool,
    rep: LookupReport,
}

impl VplPairs<'_, '_> {
    /// Counts the pair of this VPL and receiver `recv` (`buried`: inside solid geometry).
    fn pair(&mut self, recv: (Vec3, Vec3), buried: bool) {
        let (c, s, opts) = (self.c, self.s, self.opts);
        let Some(f) = facing(s.o, s.n, recv.0, recv.1) else { return };
        if !opts.filter.keeps(s.o, recv.0) || (opts.unburied && buried) {
            return;
        }
        let mut w = f64::from(f.cos_s * f.cos_r / (f.d * f.d).max(0.01));
        if opts.power_weighted {
            w *= luminance(s.vpl.power);
        }
        let by_rays = sees(&c.bvh, recv.0, recv.1, s.o, s.n);
        let l = look_up(c, &s, &self.frame, recv, &f);
        self.rep.pairs += w;
        if by_rays {
            self.rep.rays += w;
        }
        if l.lit {
            self.rep.ism += w;
        }
        if by_rays && !l.lit {
            self.false_shadow(recv, &l, &f, w);
        }
        if !by_rays && l.lit {
            self.false_light(recv, &l, &f, w);
        }
    }

    /// Counts a pair the rays light and the lookup does not, and lists it if asked.
    fn false_shadow(&mut self, recv: (Vec3, Vec3), l: &Lookup, f: &Facing, w: f64) {
        let (c, s) = (self.c, self.s);
        self.rep.false_shadow += w;
        let word = c.words[l.at];
        let per = c.lookup.per_ism as usize;
        let own = atlas_word::slot(word).and_then(|slot| c.lookup.chosen_all.get(s.tile * per + slot as usize));
        let reach = atlas_word::NEIGHBOUR_REACH * s.vpl.normal[3];
        if own.is_some_and(|&j| c.lookup.slab_blocks(j, s.o, l.dir, l.qd, reach)) {
            self.rep.own_slab += w;
        }
        let show = self.opts.show.false_shadow && self.last_set && f.cos_s > 0.2 && f.cos_r > 0.2;
        if show && self.rep.examples.len() < SHOWN_PAIRS {
            let wall = c.first_hit(s.o, s.n, l.dir);
            let example = self.example(recv, l, wall, ExampleKind::FalseShadow { slot: atlas_word::slot(word) });
            self.rep.examples.push(example);
        }
    }

    /// Counts a pair the lookup lights and the rays do not, by what its texel holds and the
    /// VPL's elevation, and lists it if asked.
    fn false_light(&mut self, recv: (Vec3, Vec3), l: &Lookup, f: &Facing, w: f64) {
        let (c, s, show) = (self.c, self.s, self.opts.show);
        self.rep.false_light += w;
        let wall = c.first_hit(s.o, s.n, l.dir);
        let word = c.words[l.at];
        let kind = false_light_kind(c, word, s.tile, recv, wall, l.dir, s.o);
        let band = ELEVATION_BANDS.iter().position(|&b| f.cos_s < b).unwrap_or(ELEVATION_BANDS.len());
        let power = s.vpl.power[0] + s.vpl.power[1] + s.vpl.power[2];
        self.rep.false_light_kinds[kind][band] += w * f64::from(power);
        let listed = show.false_light && f.cos_s >= show.min_cos && show.kind.is_none_or(|k| k == kind);
        if listed && self.rep.examples.len() < SHOWN_PAIRS {
            let point = c.word_point(word, s.tile);
            let what = ExampleKind::FalseLight { sigma: s.vpl.normal[3], q: l.q, mark: word & 1, point };
            let example = self.example(recv, l, wall, what);
            self.rep.examples.push(example);
        }
    }

    /// The example a wrongly decided pair makes.
    fn example(&self, receiver: (Vec3, Vec3), l: &Lookup, wall: f32, what: ExampleKind) -> PairExample {
        let c = self.c;
        PairExample {
            tile: self.s.tile,
            vpl: (self.s.o, self.s.n),
            receiver,
            texel: l.texel,
            stored: atlas_word::depth(c.words[l.at]) * c.d_max,
            q_distance: l.qd,
            first_hit: wall,
            what,
            neighbours: if self.opts.show.neighbours { neighbours(c, l.at, self.s.tile) } else { Vec::new() },
        }
    }
}

/// Set `set`'s lookups against the rays: every fourth live VPL with every receiver that faces
/// it and that `opts` keeps.
pub fn lookups(c: &Capture, recv: &Receivers, opts: &LookupOptions, set: usize) -> LookupReport {
    let last_set = set + 1 >= c.ism.bounces as usize;
    let per_vpl: Vec<LookupReport> = c
        .sampled(set)
        .into_par_iter()
        .map(|s| {
            let rep = LookupReport { set, ..LookupReport::default() };
            let mut pairs = VplPairs { c, s, frame: MapFrame::new(s.o, s.n), opts, last_set, rep };
            for (&p, &buried) in recv.world.iter().zip(&recv.buried) {
                pairs.pair(p, buried);
            }
            pairs.rep
        })
        .collect();
    per_vpl.into_iter().fold(LookupReport { set, ..LookupReport::default() }, |mut all, r| {
        all.add(r);
        all
    })
}

// ---------------------------------------------------------------------------------------------
// The bounce.

/// The power one set's VPLs hand the next (the bounce pass) against the power they reflect with
/// exact visibility (receivers by area, the bounce pass's form factor), in luminance, by the
/// room ([`PairFilter::room`], clamped to 0..=3) the power lands in.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BounceReport {
    /// The set whose VPLs reflect (the next set receives).
    pub source: usize,
    /// The power of the next set's VPLs these VPLs made, by the room each lies in.
    pub handed: [f64; 4],
    /// The power these VPLs reflect off the receivers, by the receiver's room.
    pub reflected: [f64; 4],
}

impl BounceReport {
    /// The power handed over the power reflected (1: the bounce pass keeps the energy).
    pub fn ratio(&self) -> f64 {
        self.handed.iter().sum::<f64>() / self.reflected.iter().sum::<f64>()
    }

    /// [`BounceReport::ratio`] per room.
    pub fn room_ratios(&self) -> [f64; 4] {
        std::array::from_fn(|i| self.handed[i] / self.reflected[i])
    }

    /// Adds another frame's report of the same set.
    pub fn accumulate(&mut self, other: &BounceReport) {
        for i in 0..4 {
            self.handed[i] += other.handed[i];
            self.reflected[i] += other.reflected[i];
        }
    }
}

/// How many source sets [`bounce_power`] can compare: all but the last, and not the one before
/// it either when the bounce tail is on (the last set then carries the tail's 1 / (1 - r), the
/// later bounces' power, not the power its sources reflect).
pub fn compared_sets(ism: &IsmSettings) -> usize {
    ism.bounces.saturating_sub(1 + u32::from(ism.bounce_tail)) as usize
}

/// What VPL `k` of set `source` hands its successor and reflects (handed, reflected by room).
fn vpl_bounce(c: &Capture, recv: &Receivers, filter: &PairFilter, source: usize, k: usize) -> [[f64; 4]; 2] {
    let n = c.n();
    let mut out = [[0.0f64; 4]; 2];
    let Some(s) = c.vpl(source * n + k) else { return out };
    let n2 = f64::from(c.ism.interleave * c.ism.interleave);
    let power = luminance(s.vpl.power) / n2 / std::f64::consts::PI;
    for (&(p, pn), albedo) in recv.world.iter().zip(&recv.albedo) {
        let Some(f) = facing(s.o, s.n, p, pn) else { continue };
        if !sees(&c.bvh, p, pn, s.o, s.n) {
            continue;
        }
        // The receiving patch as a disk of its area (`incident_power` in `ism_bounce.wgsl`).
        let d2 = f64::from(f.d * f.d) + recv.area / std::f64::consts::PI;
        out[1][filter.room_index(p)] += albedo * power * f64::from(f.cos_s * f.cos_r) / d2 * recv.area;
    }
    if let Some(next) = c.vpls.get((source + 1) * n + k) {
        out[0][filter.room_index(Vec3::from_slice(&next.position[..3]))] += luminance(next.power) / n2;
    }
    out
}

/// The power set `source`'s VPLs hand set `source + 1` against what they reflect with exact
/// visibility ([`compared_sets`] says which sources compare).
pub fn bounce_power(c: &Capture, recv: &Receivers, filter: &PairFilter, source: usize) -> BounceReport {
    let per_vpl: Vec<[[f64; 4]; 2]> =
        (0..c.n()).into_par_iter().map(|k| vpl_bounce(c, recv, filter, source, k)).collect();
    let mut report = BounceReport { source, ..BounceReport::default() };
    for [handed, reflected] in per_vpl {
        report.accumulate(&BounceReport { source, handed, reflected });
    }
    report
}

/// [`bounce_power`] of every compared set ([`compared_sets`]), summed over `frames` frames: the
/// captured frame, then each further frame `renderer` renders of `scene` with `settings` (the
/// capture's VPLs are read again; its maps stay). One frame's ratios scatter by a percent or two
/// (the bounce pass estimates each next VPL's power from a few VPLs); the sum tells the bias.
pub fn bounce_over_frames(
    renderer: &mut Renderer,
    settings: &RenderSettings,
    capture: &mut Capture<'_>,
    recv: &Receivers,
    filter: &PairFilter,
    frames: usize,
) -> Result<Vec<BounceReport>, OracleError> {
    let sets = compared_sets(capture.settings());
    let mut sums: Vec<BounceReport> =
        (0..sets).map(|source| BounceReport { source, ..BounceReport::default() }).collect();
    for frame in 0..frames {
        if frame > 0 {
            render_frames(renderer, capture.scene, settings, 1)?;
            capture.reread_vpls(renderer)?;
        }
        for sum in &mut sums {
            sum.accumulate(&bounce_power(capture, recv, filter, sum.source));
        }
    }
    Ok(sums)
}

// ---------------------------------------------------------------------------------------------
// A tile's points.

/// Which points [`list_points`] lists.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PointsQuery {
    /// The atlas tile (its VPL's index over all sets).
    pub tile: usize,
    /// Only points inside this box (x0, y0, z0, x1, y1, z1).
    pub bbox: Option<[f32; 6]>,
    /// Whether each point covers this map texel as the splat pass decides it.
    pub texel: Option<(f32, f32)>,
    /// With that, the point's clip lines.
    pub clips: bool,
}

/// A tile's chosen points.
#[derive(Clone, Debug, PartialEq)]
pub struct PointsReport {
    /// The atlas tile.
    pub tile: usize,
    /// The tile's VPL's position and normal (as the GPU holds them, w included).
    pub position: [f32; 4],
    pub normal: [f32; 4],
    /// Whether the tile is of the last set, the only one whose splat areas are kept
    /// (`IsmTechnique::read_chosen`): the others' points come without footprints.
    pub last_set: bool,
    /// The chosen points, by slot.
    pub points: Vec<ChosenPoint>,
}

/// One chosen point of a tile.
#[derive(Clone, Debug, PartialEq)]
pub struct ChosenPoint {
    /// Its slot in the tile's sample and its index in the pool.
    pub slot: usize,
    pub index: u32,
    /// Its position and normal (as the pool holds them).
    pub position: [f32; 4],
    pub normal: [f32; 4],
    /// Its splat (tiles of the last set only).
    pub footprint: Option<Footprint>,
}

/// A point's splat as `ism_splat.wgsl` makes it: radius, and in texels the centre and the
/// images of the two tangents.
#[derive(Clone, Debug, PartialEq)]
pub struct Footprint {
    /// The splat disk's radius in metres.
    pub radius: f32,
    /// The disk's centre in map texels.
    pub centre: Vec2,
    /// The images of the disk's two tangent radii in map texels.
    pub ta: Vec2,
    pub tb: Vec2,
    /// Whether it covers [`PointsQuery::texel`].
    pub texel: Option<TexelCover>,
}

/// Whether a splat covers a texel, as the splat pass decides it.
#[derive(Clone, Debug, PartialEq)]
pub enum TexelCover {
    /// The texel lies past the paraboloid's rim.
    PastRim,
    /// Inside the footprint's ellipse, where the texel's ray meets the point's plane, whether
    /// that hit is on the point's surface (within its clip lines), and the clip lines with the
    /// hit point ([`PointsQuery::clips`]).
    Decided { inside: bool, hit: f32, on_surface: bool, clips: Option<(Vec<[f32; 4]>, Vec3)> },
}

/// Tile `q.tile`'s chosen points (those inside the box), with their splats where the renderer
/// kept their areas (the last set's tiles).
pub fn list_points(c: &Capture, renderer: &Renderer, q: &PointsQuery) -> Result<PointsReport, OracleError> {
    let t = renderer.technique_as::<IsmTechnique>().ok_or(OracleError::NotIsm)?;
    let chosen = t.read_chosen(renderer.device(), renderer.queue())?;
    let tiles = c.vpls.len();
    let vpl = *c.vpls.get(q.tile).ok_or(OracleError::NoTile { tile: q.tile, tiles })?;
    let last_set = q.tile / c.n().max(1) + 1 == c.ism.bounces.max(1) as usize;
    let frame = MapFrame::new(Vec3::from_slice(&vpl.position[..3]), Vec3::from_slice(&vpl.normal[..3]));
    let per = c.lookup.per_ism as usize;
    let points = (0..per)
        .filter_map(|slot| {
            let mut point = chosen_point(c, q, slot)?;
            let area = chosen.get(q.tile % c.n().max(1) * per + slot).map(|a| a.1).filter(|_| last_set);
            point.footprint = area.map(|area| footprint(c, &frame, q, &point, area));
            Some(point)
        })
        .collect();
    Ok(PointsReport { tile: q.tile, position: vpl.position, normal: vpl.normal, last_set, points })
}

/// The point in slot `slot` of the tile, if one is there and inside the box.
fn chosen_point(c: &Capture, q: &PointsQuery, slot: usize) -> Option<ChosenPoint> {
    let index = *c.lookup.chosen_all.get(q.tile * c.lookup.per_ism as usize + slot)?;
    let position = *c.lookup.points.get(index as usize)?;
    let normal = *c.lookup.normals.get(index as usize)?;
    let inside = q.bbox.is_none_or(|b| (0..3).all(|a| position[a] >= b[a] && position[a] <= b[3 + a]));
    inside.then_some(ChosenPoint { slot, index, position, normal, footprint: None })
}

/// The splat of point `point`, of splat area `area`, in the map of `frame`.
fn footprint(c: &Capture, frame: &MapFrame, q: &PointsQuery, point: &ChosenPoint, area: f32) -> Footprint {
    let fr = c.res() as f32;
    let radius = (c.ism.splat_radius.powi(2) / std::f32::consts::PI * area).sqrt();
    let (pp, pn) = (Vec3::from_slice(&point.position[..3]), Vec3::from_slice(&point.normal[..3]));
    let (a, b) = onb(pn);
    let centre = frame.uv(pp) * fr;
    let (ta, tb) = (frame.uv(pp + a * radius) * fr - centre, frame.uv(pp + b * radius) * fr - centre);
    let mut fp = Footprint { radius, centre, ta, tb, texel: None };
    fp.texel = q.texel.map(|texel| texel_cover(c, frame, &fp, point, texel, q.clips));
    fp
}

/// Whether the splat `fp` of `point` covers map texel `(x, y)` as the splat pass decides it:
/// inside the footprint's ellipse, the texel's ray's hit on the point's plane within its clip
/// lines.
fn texel_cover(
    c: &Capture,
    frame: &MapFrame,
    fp: &Footprint,
    point: &ChosenPoint,
    (x, y): (f32, f32),
    clips: bool,
) -> TexelCover {
    let Some(l) = MapFrame::texel_local(x, y, c.res() as f32) else { return TexelCover::PastRim };
    let (ta, tb) = (fp.ta, fp.tb);
    let m00 = ta.x * ta.x + tb.x * tb.x + 0.25;
    let m01 = ta.x * ta.y + tb.x * tb.y;
    let m11 = ta.y * ta.y + tb.y * tb.y + 0.25;
    let e = Vec2::new(x + 0.5, y + 0.5) - fp.centre;
    let inside = m11 * e.x * e.x - 2.0 * m01 * e.x * e.y + m00 * e.y * e.y <= m00 * m11 - m01 * m01;
    let (pp, pn) = (Vec3::from_slice(&point.position[..3]), Vec3::from_slice(&point.normal[..3]));
    let dir = frame.world(l);
    let den = dir.dot(pn);
    let hit = if den.abs() <= 1e-6 { 0.0 } else { (pp - frame.o).dot(pn) / den };
    let h = frame.o + dir * hit;
    let on_surface = c.lookup.on_surface(point.index, h, 0.01 * fp.radius);
    let k = point.index as usize * CLIPS_PER_POINT;
    let clips = clips.then(|| (c.lookup.clips.get(k..k + CLIPS_PER_POINT).unwrap_or_default().to_vec(), h));
    TexelCover::Decided { inside, hit, on_surface, clips }
}
