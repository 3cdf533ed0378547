//! The placement readback in flight: a frame's last coverage (and its round's results, and the
//! light check's list) copied to the staging buffer and mapped when the frame's commands are
//! submitted, then taken by a later frame once the GPU has finished it. No frame waits for it:
//! a frame that finds it still in flight only splats (the budget's "no CPU wait inside a
//! frame"; Gautron et al. read the coverage back within the frame).

use std::sync::{Arc, Mutex};

use super::store::Store;
use crate::render::RenderError;
use crate::render::gi::inputs::GiInputs;

/// What the readback carries besides the bytes: how to read them, and whether they still apply.
#[derive(Clone, Debug, PartialEq)]
pub struct Issued<K> {
    /// The cache generation it was issued in (a dropped cache discards it).
    pub generation: u64,
    /// The jobs of the frame's last round, whose results it carries.
    pub jobs: u32,
    /// Whether it carries a light check's list of changed records.
    pub checked: bool,
    /// What the coverage was found from (scene revision, view size, settings).
    pub key: K,
}

/// What [`Flight::take`] found.
pub enum Landing<K> {
    /// Nothing was in flight.
    Nothing,
    /// The GPU has not finished the frame that issued it: try again next frame.
    InFlight,
    /// It landed in an older cache generation: discarded.
    Stale,
    /// The bytes of the staging buffer, and what was issued with them.
    Landed(Vec<u8>, Issued<K>),
}

/// Set by the mapping's callback: whether the buffer mapped.
type Done = Arc<Mutex<Option<Result<(), String>>>>;

/// The readback in flight, if any: what was issued, its callback's outcome and the buffer.
pub struct Flight<K> {
    pending: Option<(Issued<K>, Done, wgpu::Buffer)>,
}

impl<K> Default for Flight<K> {
    fn default() -> Self {
        Self { pending: None }
    }
}

impl<K> Flight<K> {
    /// Whether a readback is in flight.
    pub fn busy(&self) -> bool {
        self.pending.is_some()
    }

    /// Maps `store`'s staging buffer when the frame's encoder is submitted (the copies into it
    /// must already be recorded).
    pub fn issue(&mut self, inputs: &mut GiInputs<'_>, store: &Store, issued: Issued<K>) {
        let state: Done = Arc::new(Mutex::new(None));
        let done = Arc::clone(&state);
        inputs.encoder.map_buffer_on_submit(&store.staging, wgpu::MapMode::Read, .., move |r| {
            if let Ok(mut d) = done.lock() {
                *d = Some(r.map_err(|e| e.to_string()));
            }
        });
        self.pending = Some((issued, state, store.staging.clone()));
    }

    /// Takes the readback if the GPU has finished it (polls without waiting).
    pub fn take(&mut self, device: &wgpu::Device, generation: u64) -> Result<Landing<K>, RenderError> {
        let Some((_, state, _)) = &self.pending else { return Ok(Landing::Nothing) };
        let _ = device.poll(wgpu::PollType::Poll);
        let result = state.lock().ok().and_then(|mut s| s.take());
        let Some(result) = result else { return Ok(Landing::InFlight) };
        let Some((issued, _, buffer)) = self.pending.take() else { return Ok(Landing::Nothing) };
        result.map_err(|e| RenderError::Gpu(format!("rcs placement readback: {e}")))?;
        let bytes = buffer
            .slice(..)
            .get_mapped_range()
            .map_err(|e| RenderError::Gpu(format!("rcs placement readback: {e}")))?
            .to_vec();
        buffer.unmap();
        if issued.generation != generation {
            return Ok(Landing::Stale);
        }
        Ok(Landing::Landed(bytes, issued))
    }

    /// Forgets the readback (its store is being replaced or freed).
    pub fn forget(&mut self) {
        self.pending = None;
    }
}
