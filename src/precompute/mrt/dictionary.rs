//! MRT's dictionary: the six cube shapes' reduced operators ([`super::basis`]) built with one
//! set of parameters, deterministic, with progress (samples gathered of the total, and the time
//! left) and cancellation for the editor and the CLI. [`super::cache`] keeps it on disk.

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::Instant;

use thiserror::Error;

use super::basis::{self, BasisError, Element};
use super::operators::{self, Interfaces};
use super::shape::{Layout, Shape};
pub use crate::settings::mrt_params::{DictionaryParams, InterfaceParams};

/// What can stop a dictionary build.
#[derive(Debug, Error)]
pub enum DictionaryError {
    /// A parameter is out of range.
    #[error("mrt dictionary: {name} = {value} is outside {range}")]
    Param { name: &'static str, value: String, range: &'static str },
    /// The interface operators' precompute failed.
    #[error("mrt dictionary, interface operators: {0}")]
    Interfaces(#[source] BasisError),
    /// An element's precompute failed.
    #[error("mrt dictionary, element {shape}: {source}")]
    Element {
        shape: &'static str,
        #[source]
        source: BasisError,
    },
}

impl DictionaryParams {
    /// Texels gathered by the elements' precompute (the interfaces count as a third more).
    fn element_work(&self) -> usize {
        Shape::ALL.iter().map(|s| Layout::new(*s, self.res).len()).sum::<usize>() * (1 + self.enrichment)
    }

    /// The progress total: the elements' texels, and the interface operators as a third more.
    pub fn total_work(&self) -> usize {
        self.element_work() + self.element_work() / 3
    }
}

/// Progress of a build, shared with the thread that shows it.
#[derive(Debug, Default)]
pub struct Progress {
    done: AtomicUsize,
    total: AtomicUsize,
    started: std::sync::OnceLock<Instant>,
    cancel: AtomicBool,
}

impl Progress {
    /// Asks the build to stop at its next texel.
    pub fn cancel(&self) {
        self.cancel.store(true, Ordering::Relaxed);
    }

    /// The share done (0..=1) and the estimated seconds left (`None` before any work).
    pub fn fraction_and_left(&self) -> (f64, Option<f64>) {
        let (done, total) = (self.done.load(Ordering::Relaxed), self.total.load(Ordering::Relaxed));
        let fraction = if total == 0 { 0.0 } else { done as f64 / total as f64 };
        let left = self.started.get().filter(|_| done > 0).map(|t| {
            let elapsed = t.elapsed().as_secs_f64();
            elapsed * (total - done.min(total)) as f64 / done as f64
        });
        (fraction, left)
    }

    /// Starts counting `total` units of work (the clock starts now).
    pub(crate) fn begin(&self, total: usize) {
        self.total.store(total, Ordering::Relaxed);
        let _ = self.started.set(Instant::now());
    }

    /// Whether the work was asked to stop.
    pub fn cancelled(&self) -> bool {
        self.cancel.load(Ordering::Relaxed)
    }

    /// Counts one texel and says whether to stop.
    pub(crate) fn tick(&self) -> bool {
        self.done.fetch_add(1, Ordering::Relaxed);
        self.cancel.load(Ordering::Relaxed)
    }
}

/// The whole dictionary.
#[derive(Clone, Debug, PartialEq)]
pub struct Dictionary {
    /// What it was built with.
    pub params: DictionaryParams,
    /// One element per shape, in [`Shape::ALL`] order.
    pub elements: Vec<Element>,
    /// The interface operators.
    pub interfaces: Interfaces,
}

impl Dictionary {
    /// The element of `shape`.
    pub fn element(&self, shape: Shape) -> Option<&Element> {
        self.elements.iter().find(|e| e.shape == shape)
    }

    /// Bytes of its operators as the runtime stores them (f32 U_b, T_{d->b}; L_imp kept for
    /// DRT; the interface operators).
    pub fn runtime_bytes(&self) -> usize {
        let i = &self.interfaces;
        let interfaces = i.exits.iter().map(|e| e.r_b_rlf.len()).sum::<usize>()
            + i.turns.iter().map(|t| t.1.len()).sum::<usize>()
            + i.response.u_r.len()
            + i.response.t_rlf_r.len();
        self.elements.iter().map(|e| 4 * (e.u_b.len() + e.t_db.len() + e.l_imp.len())).sum::<usize>() + 4 * interfaces
    }
}

/// Parameters small enough for debug-build tests (3x3 texels, 2x2 x 4x4 light fields).
pub fn test_params() -> DictionaryParams {
    let interfaces =
        InterfaceParams { positions: 2, directions: 4, supersample: 1, k_rlf: 24, k_r: 8, enrichment: 1, bands: 2 };
    DictionaryParams { res: 3, k_d: 16, k_b: 8, rays: 64, enrichment: 1, seed: 2, interfaces }
}

/// Builds the dictionary (element after element; each element's gather runs on every core).
pub fn build(params: &DictionaryParams, progress: &Progress) -> Result<Dictionary, DictionaryError> {
    params.validate().map_err(|e| DictionaryError::Param { name: e.name, value: e.value, range: e.range })?;
    progress.total.store(params.total_work(), Ordering::Relaxed);
    progress.done.store(0, Ordering::Relaxed);
    let _ = progress.started.set(Instant::now());
    let tick = || progress.tick();
    let elements = Shape::ALL
        .iter()
        .map(|&shape| {
            basis::build(shape, params, &tick)
                .map_err(|source| DictionaryError::Element { shape: shape.name(), source })
        })
        .collect::<Result<Vec<_>, _>>()?;
    if progress.cancel.load(Ordering::Relaxed) {
        return Err(DictionaryError::Interfaces(BasisError::Cancelled));
    }
    let interfaces = operators::build(&elements, params, &params.interfaces).map_err(DictionaryError::Interfaces)?;
    progress.done.store(params.total_work(), Ordering::Relaxed);
    Ok(Dictionary { params: *params, elements, interfaces })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tiny() -> DictionaryParams {
        let interfaces =
            InterfaceParams { positions: 2, directions: 4, supersample: 1, k_rlf: 24, k_r: 8, enrichment: 1, bands: 0 };
        DictionaryParams { res: 3, k_d: 16, k_b: 8, rays: 64, enrichment: 1, seed: 2, interfaces }
    }

    #[test]
    fn a_build_is_deterministic_and_reports_its_progress() {
        let progress = Progress::default();
        let a = build(&tiny(), &progress).expect("build");
        assert_eq!(progress.fraction_and_left().0, 1.0);
        let b = build(&tiny(), &Progress::default()).expect("build");
        assert_eq!(a, b, "same parameters, same bits");
        assert_eq!(a.elements.len(), 6);
        assert!(a.element(Shape::Crossroads).is_some_and(|e| e.n == 2 * 9));
    }

    #[test]
    fn a_cancelled_build_stops_with_an_error_and_bad_parameters_are_named() {
        let progress = Progress::default();
        progress.cancel();
        let err = build(&tiny(), &progress).expect_err("cancelled");
        assert!(matches!(err, DictionaryError::Element { source: BasisError::Cancelled, .. }), "{err}");
        let bad = DictionaryParams { k_b: 99, ..tiny() };
        assert!(matches!(build(&bad, &Progress::default()), Err(DictionaryError::Param { name: "k_b", .. })));
    }
}
