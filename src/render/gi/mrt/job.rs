//! MRT's CPU work off the frame: the dictionary (loaded from the cache or built, with progress
//! and cancellation) and, once it is there, the level (proxy blocks from the scene, or fitted to
//! its geometry when it has none; the geometry images; T_{b->r}; the packed GPU records). A
//! level job is started for every scene edit; the frame keeps showing the previous level until
//! the new one is ready, so a block drag never blanks the view.

use std::sync::{Arc, Mutex};
use std::time::Instant;

use super::pack::{Packed, pack};
use crate::precompute::bvh::SceneBvh;
use crate::precompute::mrt::dictionary::{Dictionary, DictionaryParams, Progress};
use crate::precompute::mrt::proxy;
use crate::precompute::mrt::{cache, geometry_image};
use crate::scene::{ObjectRole, Scene};

/// A result slot a worker thread fills.
type Slot<T> = Arc<Mutex<Option<Result<T, String>>>>;

/// Runs `work` on a named thread; its result lands in the returned slot.
fn spawn<T: Send + 'static>(name: &str, work: impl FnOnce() -> Result<T, String> + Send + 'static) -> Slot<T> {
    let slot: Slot<T> = Arc::new(Mutex::new(None));
    let s = slot.clone();
    let spawned = std::thread::Builder::new().name(name.into()).spawn(move || {
        let result = work();
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
            let how = match source {
                cache::Source::Loaded(path) => format!("loaded from {}", path.display()),
                cache::Source::Built { path, why } => format!("built ({why}) and cached in {}", path.display()),
            };
            Ok((d, how))
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
    /// Open sides leading nowhere.
    pub unlinked: usize,
    /// CPU time of the build (ms).
    pub millis: f64,
}

/// Builds the level of `scene` (its proxy blocks, or fitted ones) with `dictionary`.
pub fn build_level(scene: &Scene, dictionary: &Dictionary, depth: usize) -> Result<BuiltLevel, String> {
    let started = Instant::now();
    let has_blocks = scene.objects().iter().any(|o| o.role == ObjectRole::ProxyBlock);
    let fitted_scene;
    let source = if has_blocks {
        scene
    } else {
        let fitted = proxy::fitted_objects(scene)
            .map_err(|e| format!("the scene has no proxy blocks and none could be fitted: {e}"))?;
        let mut s = scene.clone();
        s.desc_mut().objects.extend(fitted);
        fitted_scene = s;
        &fitted_scene
    };
    let (mut level, _) = proxy::level(source).map_err(|e| e.to_string())?;
    let bvh = SceneBvh::build(scene);
    let mut openings = Vec::new();
    for ((i, w), share) in geometry_image::transmissions(&bvh, &level) {
        level.set_transmission(i, w, share);
        let (plane, lo, hi) = level.side_rect(i, w);
        let mut centre = 0.5 * (lo + hi);
        centre[w.axis()] = plane;
        openings.push((centre, share as f32));
    }
    let packed = pack(scene, &bvh, &level, dictionary, depth);
    Ok(BuiltLevel {
        packed,
        fitted: !has_blocks,
        links: level.link_count(),
        openings,
        unlinked: level.unlinked().len(),
        blocks: level.blocks,
        millis: started.elapsed().as_secs_f64() * 1e3,
    })
}

/// A level being built.
pub struct LevelJob {
    slot: Slot<BuiltLevel>,
    /// The scene revision it builds.
    pub revision: u64,
}

impl LevelJob {
    /// Starts building `scene`'s level.
    pub fn start(scene: &Scene, dictionary: Arc<Dictionary>, depth: usize) -> Self {
        let scene_copy = scene.clone();
        let slot = spawn("mrt level", move || build_level(&scene_copy, &dictionary, depth));
        Self { slot, revision: scene.revision() }
    }

    /// The finished level, once.
    pub fn finished(&self) -> Option<Result<BuiltLevel, String>> {
        take(&self.slot)
    }
}
