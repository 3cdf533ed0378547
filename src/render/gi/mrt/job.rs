//! MRT's CPU work off the frame: the dictionary (loaded from the cache or built, with progress
//! and cancellation) and, once it is there, the level (proxy blocks from the scene, or fitted to
//! its geometry when it has none; the geometry images; T_{b->r}; the packed GPU records). A
//! level job is started for every scene edit; the frame keeps showing the previous level until
//! the new one is ready, so a block drag never blanks the view.

use std::sync::{Arc, Mutex};
use std::time::Instant;

use super::drt_pack::DrtPacked;
use super::pack::{Packed, pack};
use crate::precompute::bvh::SceneBvh;
use crate::precompute::drt::SceneTexel;
use crate::precompute::mrt::dictionary::{Dictionary, DictionaryParams, Progress};
use crate::precompute::mrt::proxy;
use crate::precompute::mrt::{cache, geometry_image};
use crate::scene::{ObjectRole, Scene};
use crate::settings::BlockOverride;
use crate::settings::DrtSettings;

/// A result slot a worker thread fills.
type Slot<T> = Arc<Mutex<Option<Result<T, String>>>>;

/// Runs `work` on a named thread; its result lands in the returned slot.
fn spawn<T: Send + 'static>(name: &str, work: impl FnOnce() -> Result<T, String> + Send + 'static) -> Slot<T> {
    let slot: Slot<T> = Arc::new(Mutex::new(None));
    let s = slot.clone();
    let what = name.to_owned();
    let spawned = std::thread::Builder::new().name(name.into()).spawn(move || {
        // A panic in the work must still end the job, or the technique would wait forever.
        let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(work))
            .unwrap_or_else(|_| Err(format!("the {what} work failed (a panic; see the log)")));
        if let Ok(mut guard) = s.lock() {
            *guard = Some(result);
        }
    });
    if let Err(e) = spawned
        && let Ok(mut guard) = slot.lock()
    {
        *guard = Some(Err(format!("cannot start the {name} thread: {e}")));
    }
    slot
}

/// Takes a finished result out of `slot`.
fn take<T>(slot: &Slot<T>) -> Option<Result<T, String>> {
    slot.lock().ok().and_then(|mut g| g.take())
}

/// The dictionary being loaded or built for one parameter set.
pub struct DictionaryJob {
    /// Its parameters.
    pub params: DictionaryParams,
    progress: Arc<Progress>,
    slot: Slot<(Dictionary, String)>,
}

impl DictionaryJob {
    /// Starts loading (or building and caching) the dictionary for `params`.
    pub fn start(params: DictionaryParams) -> Self {
        let progress = Arc::new(Progress::default());
        let p = progress.clone();
        let slot = spawn("mrt dictionary", move || {
            let (d, source) = cache::load_or_build(&cache::default_dir(), &params, &p).map_err(|e| e.to_string())?;
            Ok((d, source.describe()))
        });
        Self { params, progress, slot }
    }

    /// The finished dictionary and how it was obtained, once.
    pub fn finished(&self) -> Option<Result<(Dictionary, String), String>> {
        take(&self.slot)
    }

    /// The share done and the seconds left.
    pub fn progress(&self) -> (f64, Option<f64>) {
        self.progress.fraction_and_left()
    }
}

impl Drop for DictionaryJob {
    fn drop(&mut self) {
        self.progress.cancel();
    }
}

/// A level ready to upload.
pub struct BuiltLevel {
    /// The GPU records.
    pub packed: Packed,
    /// The blocks were fitted to the geometry (the scene had none).
    pub fitted: bool,
    /// The blocks (world boxes and shapes) for the inspector and the overlay.
    pub blocks: Vec<crate::precompute::mrt::level::Block>,
    /// Links between blocks (both directions counted).
    pub links: usize,
    /// Each linked side's centre and the share of it that is open.
    pub openings: Vec<(glam::Vec3, f32)>,
    /// What the level could not honour (an override naming nothing).
    pub warnings: Vec<String>,
    /// Open sides leading nowhere.
    pub unlinked: usize,
    /// What the blocks leave out (their bounds, for the overlay; their sentences are in
    /// `warnings`).
    pub gaps: Vec<proxy::GapNote>,
    /// Per linked side, its block's centre and the side's centre (the overlay's links).
    pub link_lines: Vec<(glam::Vec3, glam::Vec3)>,
    /// CPU time of the build (ms).
    pub millis: f64,
}

/// Per linked side of `level`, its block's centre and the side's centre.
fn link_lines(level: &crate::precompute::mrt::level::Level) -> Vec<(glam::Vec3, glam::Vec3)> {
    level
        .linked_sides()
        .into_iter()
        .map(|(i, w)| {
            let (plane, lo, hi) = level.side_rect(i, w);
            let mut side = 0.5 * (lo + hi);
            side[w.axis()] = plane;
            (0.5 * (lo + hi), side)
        })
        .collect()
}

/// Each object's overridden block (level block index, or `pack::NONE`), and a sentence for each
/// override naming nothing.
fn overrides(scene: &Scene, block_objects: &[usize], list: &[BlockOverride]) -> (Vec<u32>, Vec<String>) {
    let objects = scene.objects();
    let mut table = vec![super::pack::NONE; objects.len()];
    let mut unknown = Vec::new();
    for o in list {
        let object = objects.iter().position(|x| x.name == o.object);
        let block = block_objects.iter().position(|&i| objects.get(i).is_some_and(|x| x.name == o.block));
        match (object, block) {
            (Some(i), Some(b)) => table[i] = b as u32,
            (None, _) => unknown.push(format!("mrt block override: no object named {:?}", o.object)),
            (_, None) => unknown.push(format!("mrt block override: no proxy block named {:?}", o.block)),
        }
    }
    (table, unknown)
}

/// Builds the level of `scene` (its proxy blocks, or fitted ones) with `dictionary`, `depth`
/// blocks of propagation, the artist's block `overrides` and delta radiance transfer for its
/// clutter as `drt` says; `progress` counts the DRT rays' texels and cancels them.
pub fn build_level(
    scene: &Scene,
    dictionary: &Dictionary,
    depth: usize,
    block_overrides: &[BlockOverride],
    drt: &DrtSettings,
    progress: &Progress,
) -> Result<BuiltLevel, String> {
    let started = Instant::now();
    let has_blocks = scene.objects().iter().any(|o| o.role == ObjectRole::ProxyBlock);
    let full_bvh = SceneBvh::build(scene);
    let (level, block_objects, gaps) = if has_blocks {
        let (level, objects) = proxy::level(scene).map_err(|e| e.to_string())?;
        let gaps = proxy::gaps_of(scene, &full_bvh, &level, &objects);
        (level, objects, gaps)
    } else {
        let fitted = proxy::fit_scene(scene, &full_bvh)
            .map_err(|e| format!("the scene has no proxy blocks and none could be fitted: {e}"))?;
        let (level, objects) = proxy::level_of(&fitted.objects).map_err(|e| e.to_string())?;
        (level, objects, fitted.gaps)
    };
    let mut level = level;
    // With DRT the blocks' geometry images and openings see the level without its clutter (a
    // crate's top is not the floor's texel); DRT adds what the clutter changes.
    let found = if drt.enabled {
        crate::precompute::drt::find_clutter(scene, &full_bvh, &level, drt.automatic, &drt.not_clutter)
    } else {
        crate::precompute::drt::Found::default()
    };
    let static_bvh = (!found.is_empty()).then(|| SceneBvh::build_where(scene, |i| !found.contains(i)));
    let bvh = static_bvh.as_ref().unwrap_or(&full_bvh);
    let mut openings = Vec::new();
    for ((i, w), opening) in geometry_image::openings(scene, bvh, &level, dictionary.interfaces.positions.positions) {
        let share = opening.share();
        level.set_opening(i, w, opening);
        let (plane, lo, hi) = level.side_rect(i, w);
        let mut centre = 0.5 * (lo + hi);
        centre[w.axis()] = plane;
        openings.push((centre, share as f32));
    }
    let mut packed = pack(scene, bvh, &level, dictionary, depth);
    if !found.is_empty() {
        let texels: Vec<SceneTexel> = packed
            .texels
            .iter()
            .map(|t| SceneTexel {
                position: glam::Vec3::from_slice(&t.position[..3]),
                normal: glam::Vec3::from_slice(&t.normal[..3]),
                found: t.position[3] > 0.5,
            })
            .collect();
        let built = crate::precompute::drt::build(
            scene,
            &full_bvh,
            &level,
            &found,
            crate::precompute::drt::BlockTexels { texels: &texels, res: packed.res as usize },
            &drt.params(),
            progress,
        )
        .ok_or_else(|| CANCELLED.to_owned())?;
        packed.drt = Some(DrtPacked::new(&built));
    }
    let (mut table, mut warnings) = overrides(scene, if has_blocks { &block_objects } else { &[] }, block_overrides);
    warnings.extend(gaps.iter().map(|g| g.text.clone()));
    // One NONE past the objects (see `pack`: never an empty or zero-padded table).
    table.push(super::pack::NONE);
    packed.object_block = table;
    Ok(BuiltLevel {
        packed,
        fitted: !has_blocks,
        links: level.link_count(),
        openings,
        warnings,
        unlinked: level.unlinked().len(),
        gaps,
        link_lines: link_lines(&level),
        blocks: level.blocks,
        millis: started.elapsed().as_secs_f64() * 1e3,
    })
}

/// What a cancelled level build says (never shown: a newer build replaces it).
pub const CANCELLED: &str = "cancelled by a newer edit";

/// A level being built (dropping it cancels the DRT rays in flight).
pub struct LevelJob {
    slot: Slot<BuiltLevel>,
    progress: Arc<Progress>,
}

impl LevelJob {
    /// Starts building `scene`'s level.
    pub fn start(
        scene: &Scene,
        dictionary: Arc<Dictionary>,
        depth: usize,
        overrides: &[BlockOverride],
        drt: &DrtSettings,
    ) -> Self {
        let scene_copy = scene.clone();
        let overrides = overrides.to_vec();
        let drt = drt.clone();
        let progress = Arc::new(Progress::default());
        let p = progress.clone();
        let slot = spawn("mrt level", move || build_level(&scene_copy, &dictionary, depth, &overrides, &drt, &p));
        Self { slot, progress }
    }

    /// The finished level, once.
    pub fn finished(&self) -> Option<Result<BuiltLevel, String>> {
        take(&self.slot)
    }

    /// The share of the DRT rays traced and the seconds left.
    pub fn progress(&self) -> (f64, Option<f64>) {
        self.progress.fraction_and_left()
    }
}

impl Drop for LevelJob {
    fn drop(&mut self) {
        self.progress.cancel();
    }
}
