//! A progressive reference render on a background thread, restarted when the scene, its
//! settings or the view size change, cancelled when dropped.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};

use crate::image_io::HdrImage;
use crate::precompute::pathtracer::{PathTracer, Progress};
use crate::scene::Scene;
use crate::settings::ReferenceSettings;

type Latest = Arc<Mutex<Option<(HdrImage, Progress)>>>;

/// A running reference render.
pub struct ReferenceJob {
    cancel: Arc<AtomicBool>,
    latest: Latest,
    revision: u64,
    settings: crate::settings::ReferenceSettings,
    size: (u32, u32),
}

impl ReferenceJob {
    /// Starts rendering `scene` at `size` until `settings.spp`.
    pub fn start(scene: &Scene, settings: &ReferenceSettings, size: (u32, u32)) -> Self {
        let cancel = Arc::new(AtomicBool::new(false));
        let latest: Latest = Arc::new(Mutex::new(None));
        let settings = settings.clone();
        let mut tracer = PathTracer::new(scene, size, settings.clone());
        let (c, l, spp) = (cancel.clone(), latest.clone(), settings.spp);
        // Leave a core for the UI and the GPU driver (a software adapter renders on the CPU too).
        let threads = std::thread::available_parallelism().map_or(1, |n| n.get().saturating_sub(1).max(1));
        let spawned = std::thread::Builder::new().name("reference".into()).spawn(move || {
            let pool = match rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .thread_name(|i| format!("reference {i}"))
                .build()
            {
                Ok(p) => p,
                Err(e) => {
                    log::error!("reference thread pool: {e}");
                    return;
                }
            };
            pool.install(|| {
                while tracer.spp() < spp && !c.load(Ordering::Relaxed) {
                    if let Some(p) = tracer.add_sample(&c)
                        && let Ok(mut slot) = l.lock()
                    {
                        *slot = Some((HdrImage { width: size.0, height: size.1, pixels: tracer.image() }, p));
                    }
                }
            });
        });
        if let Err(e) = spawned {
            log::error!("cannot start the reference render: {e}");
        }
        Self { cancel, latest, revision: scene.revision(), settings, size }
    }

    /// Whether this job renders the current state of `scene` with `settings` at `size`.
    pub fn matches(&self, scene: &Scene, settings: &ReferenceSettings, size: (u32, u32)) -> bool {
        self.revision == scene.revision() && self.settings == *settings && self.size == size
    }

    /// The newest image and progress, if a pass has finished.
    pub fn latest(&self) -> Option<(HdrImage, Progress)> {
        self.latest.lock().ok().and_then(|s| s.clone())
    }
}

impl Drop for ReferenceJob {
    fn drop(&mut self) {
        self.cancel.store(true, Ordering::Relaxed);
    }
}
