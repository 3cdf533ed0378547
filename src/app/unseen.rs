//! The GI panel's measure of `sshgi`'s known limitation on the view in hand: the share of the
//! path tracer's indirect light that leaves surfaces the screen does not show
//! ([`crate::precompute::unseen`]). It runs on a thread of its own once the view has been still
//! for a moment (a move or an edit starts it again and drops a run for an older view), at a
//! small size: 54 rows at 16 paths a pixel, 23-75 ms on two cores in a release build on the
//! suite's scenes, the BVH build included (`bouncelab unseen-light --size 96x54 --spp 16`).

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use crate::precompute::unseen::{UnseenShare, unseen_share};
use crate::scene::Scene;

/// Rows of the measured view (its width follows the viewport's aspect).
const ROWS: u32 = 54;
/// Paths per pixel.
const SPP: u32 = 16;
/// How long the view must stay unchanged before a measurement starts.
const SETTLE: Duration = Duration::from_millis(250);

/// A measurement under way for one scene revision.
struct Job {
    revision: u64,
    result: mpsc::Receiver<Option<UnseenShare>>,
    cancel: Arc<AtomicBool>,
}

impl Drop for Job {
    fn drop(&mut self) {
        self.cancel.store(true, Ordering::Relaxed);
    }
}

/// The measurement for the view, kept while the scene's revision is unchanged.
#[derive(Default)]
pub struct UnseenProbe {
    job: Option<Job>,
    done: Option<(u64, UnseenShare)>,
    /// The revision last seen and since when it has been unchanged.
    seen: Option<(u64, Instant)>,
}

impl UnseenProbe {
    /// Collects a finished run and starts one for `scene` when its view has settled; `size` is
    /// the viewport's (for the aspect).
    pub fn update(&mut self, scene: &Scene, size: (u32, u32)) {
        let revision = scene.revision();
        if let Some(job) = &self.job {
            match job.result.try_recv() {
                Ok(Some(share)) => self.done = Some((job.revision, share)),
                Ok(None) | Err(mpsc::TryRecvError::Disconnected) => {}
                Err(mpsc::TryRecvError::Empty) if job.revision == revision => return,
                Err(mpsc::TryRecvError::Empty) => {}
            }
            self.job = None;
        }
        let since = match self.seen {
            Some((r, since)) if r == revision => since,
            _ => {
                self.seen = Some((revision, Instant::now()));
                return;
            }
        };
        if self.current(scene).is_some() || since.elapsed() < SETTLE {
            return;
        }
        self.job = Self::start(scene, size);
    }

    /// Starts a measurement of `scene` on a thread of its own.
    fn start(scene: &Scene, size: (u32, u32)) -> Option<Job> {
        let aspect = size.0.max(1) as f32 / size.1.max(1) as f32;
        let view = (((ROWS as f32 * aspect).round() as u32).clamp(1, 4 * ROWS), ROWS);
        let (tx, rx) = mpsc::channel();
        let cancel = Arc::new(AtomicBool::new(false));
        let revision = scene.revision();
        let (scene, flag) = (scene.clone(), cancel.clone());
        let spawned = std::thread::Builder::new().name("unseen light".into()).spawn(move || {
            let _ = tx.send(unseen_share(&scene, view, SPP, &flag));
        });
        match spawned {
            Ok(_) => Some(Job { revision, result: rx, cancel }),
            Err(e) => {
                log::warn!("the unseen-light measurement did not start: {e}");
                None
            }
        }
    }

    /// The measurement of `scene` as it is now, if done.
    pub fn current(&self, scene: &Scene) -> Option<&UnseenShare> {
        self.done.as_ref().filter(|(r, _)| *r == scene.revision()).map(|(_, s)| s)
    }

    /// Whether a measurement is under way.
    pub fn running(&self) -> bool {
        self.job.is_some()
    }

    /// Whether the panel should look again soon: a measurement of `scene` is under way or
    /// waits for the view to settle.
    pub fn wants_repaint(&self, scene: &Scene) -> bool {
        self.current(scene).is_none()
    }

    /// The panel's line: the measurement, or what it waits for.
    pub fn line(&self, scene: &Scene) -> String {
        match self.current(scene) {
            Some(share) => share.describe(),
            None if self.running() => "measuring how much light leaves surfaces off screen…".to_owned(),
            None => "how much light leaves surfaces off screen is measured once the view is still".to_owned(),
        }
    }
}
