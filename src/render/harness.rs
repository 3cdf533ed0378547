//! Driving a [`Renderer`] for measurements: frames until a technique's CPU preparation is done,
//! frames until it stops refining, the mean of frames, and the median of timings. The CLI's
//! `render`, `bench` and `bench --quality`, the tests and the examples all measure through these,
//! so a "converged" image or a "median frame" means the same everywhere (docs/ARCHITECTURE.md,
//! "Measuring").

use std::sync::atomic::AtomicBool;
use std::time::{Duration, Instant};

use super::frame::{RenderError, Renderer};
use super::gi::technique::Readiness;
use super::timing::PassTiming;
use crate::image_io::HdrImage;
use crate::precompute::pathtracer::PathTracer;
use crate::scene::Scene;
use crate::settings::{ReferenceSettings, RenderSettings};

/// How long [`until_ready`] sleeps between frames while a technique prepares on the CPU: long
/// enough to leave the cores to the preparation, short enough to start within a frame of it.
const READY_POLL: Duration = Duration::from_millis(50);

/// The median of `v` (the upper one of an even count; 0 when empty).
pub fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v.get(v.len() / 2).copied().unwrap_or(0.0)
}

/// Renders frames until the technique is no longer preparing on the CPU (MRT's dictionary and
/// level; meanwhile the frame shows direct light) and no rebuild after an edit is in flight.
/// `waiting` hears what it waits for each time that changes. Between frames it waits for the
/// GPU and sleeps [`READY_POLL`], so the preparation has the cores. Returns how many of the
/// frames rendered were the technique's own (the last one: 1), for callers that count frames.
pub fn until_ready(
    renderer: &mut Renderer,
    scene: &Scene,
    settings: &RenderSettings,
    size: (u32, u32),
    mut waiting: impl FnMut(&str),
) -> Result<u32, RenderError> {
    let mut said = String::new();
    loop {
        renderer.render(scene, settings, size)?;
        renderer.wait_for_gpu()?;
        let what = match renderer.readiness() {
            Readiness::Pending { what, .. } => what.clone(),
            Readiness::Ready => match rebuilding(renderer) {
                Some(what) => what,
                None => return Ok(1),
            },
        };
        let head = what.split(" (").next().unwrap_or_default().to_owned();
        if head != said {
            waiting(&what);
            said = head;
        }
        std::thread::sleep(READY_POLL);
    }
}

/// What the active technique says it is rebuilding after an edit (it shows the previous result
/// meanwhile), if anything.
fn rebuilding(renderer: &Renderer) -> Option<String> {
    let status = renderer.technique_status()?;
    status.progress.filter(|p| p.contains("rebuilding"))
}

/// Renders frames until the active technique stops refining (a progressive technique's cache
/// is full, a temporal one has settled: `TechniqueStatus::refining`), at most `limit`; returns
/// the number of frames rendered.
pub fn converge(
    renderer: &mut Renderer,
    scene: &Scene,
    settings: &RenderSettings,
    size: (u32, u32),
    limit: usize,
) -> Result<usize, RenderError> {
    for frame in 1..=limit {
        renderer.render(scene, settings, size)?;
        // Between frames, outside them: a technique's readback issued in this frame (rcs's
        // placement) lands for the next, as it does in the editor, which starts a frame once
        // the last one has finished.
        renderer.wait_for_gpu()?;
        if !renderer.technique_status().is_some_and(|s| s.refining) {
            return Ok(frame);
        }
    }
    Ok(limit)
}

/// The per-pixel mean of the linear images of frames `skip + 1 ..= frames` (the estimator's
/// expectation for a technique whose single frames are noisy).
pub fn mean_of_frames(
    renderer: &mut Renderer,
    scene: &Scene,
    settings: &RenderSettings,
    size: (u32, u32),
    skip: usize,
    frames: usize,
) -> Result<Vec<[f32; 4]>, RenderError> {
    let mut sum = vec![[0.0f32; 4]; size.0 as usize * size.1 as usize];
    let averaged = frames.saturating_sub(skip).max(1) as f32;
    for frame in 0..frames {
        renderer.render(scene, settings, size)?;
        if frame >= skip {
            for (s, p) in sum.iter_mut().zip(renderer.read_hdr()?) {
                (0..4).for_each(|c| s[c] += p[c] / averaged);
            }
        }
    }
    Ok(sum)
}

/// Frames discarded before [`measure`] times: pipeline compilation and first uploads.
const WARM_UP_FRAMES: usize = 3;

/// What [`measure`] found: the median wall-clock frame (submission and waiting for the GPU) and
/// each pass's median GPU time.
#[derive(Clone, Debug)]
pub struct Timed {
    /// Median wall-clock milliseconds per frame.
    pub frame_ms: f64,
    /// Median GPU milliseconds per pass (timestamps; empty without timestamp queries).
    pub passes: Vec<PassTiming>,
}

/// Times `frames` frames of `settings` after the technique is ready and [`WARM_UP_FRAMES`]
/// frames have warmed it up.
pub fn measure(
    renderer: &mut Renderer,
    scene: &Scene,
    settings: &RenderSettings,
    size: (u32, u32),
    frames: usize,
) -> Result<Timed, RenderError> {
    until_ready(renderer, scene, settings, size, |_| {})?;
    for _ in 0..WARM_UP_FRAMES {
        renderer.render(scene, settings, size)?;
        renderer.wait_for_gpu()?;
    }
    let mut times = Vec::new();
    let mut per_pass: Vec<Vec<PassTiming>> = Vec::new();
    for _ in 0..frames {
        let t = Instant::now();
        renderer.render(scene, settings, size)?;
        renderer.wait_for_gpu()?;
        times.push(t.elapsed().as_secs_f64() * 1e3);
        per_pass.push(renderer.timings(true));
    }
    Ok(Timed { frame_ms: median(times), passes: median_passes(&per_pass) })
}

/// Each pass of the last frame in `frames` with its median time over the frames that have it.
pub fn median_passes(frames: &[Vec<PassTiming>]) -> Vec<PassTiming> {
    let names: Vec<String> = frames.last().map(|p| p.iter().map(|t| t.name.clone()).collect()).unwrap_or_default();
    names
        .into_iter()
        .map(|name| {
            let kind =
                frames.last().and_then(|f| f.iter().find(|t| t.name == name)).map(|t| t.kind).unwrap_or_default();
            let ms = median(frames.iter().filter_map(|f| f.iter().find(|t| t.name == name).map(|t| t.ms)).collect());
            PassTiming { name, ms, start_ms: 0.0, kind }
        })
        .collect()
}

/// The reference path tracer's image of `scene` at `size`, all of `settings.spp` samples (on
/// every core, this thread waiting).
pub fn reference_image(scene: &Scene, size: (u32, u32), settings: ReferenceSettings) -> HdrImage {
    let mut tracer = PathTracer::new(scene, size, settings);
    let spp = tracer.settings_spp();
    tracer.render(spp, &AtomicBool::new(false), |_| {});
    HdrImage { width: size.0, height: size.1, pixels: tracer.image() }
}

#[cfg(test)]
mod tests {
    use super::median;

    #[test]
    fn the_median_is_the_middle_value_and_zero_when_empty() {
        assert_eq!(median(vec![3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(vec![4.0, 1.0, 3.0, 2.0]), 3.0);
        assert_eq!(median(Vec::new()), 0.0);
    }
}
