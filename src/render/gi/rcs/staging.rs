//! A placement round's readback: the frame's encoder submitted, the staging buffer mapped, and
//! the lists in it (candidates, light-check slots, secondary sites) parsed. Each list is a
//! 16-byte header whose first word counts the items, then the items.

use super::record::Candidate;
use super::store::Store;
use crate::render::RenderError;
use crate::render::gi::inputs::GiInputs;
use crate::render::readback;

/// Swaps the frame's encoder for a fresh one, submits what it held and maps the staging
/// buffer: the bytes of the round's readback (one GPU wait per round).
pub fn submit_and_read(inputs: &mut GiInputs<'_>, store: &Store) -> Result<Vec<u8>, RenderError> {
    let fresh = inputs.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("rcs round") });
    let done = std::mem::replace(inputs.encoder, fresh);
    inputs.queue.submit([done.finish()]);
    Ok(readback::map_blocking(inputs.device, &store.staging)?)
}

/// The counter and the items (at most the count) of the list at `offset..offset + len`.
fn list<T: bytemuck::Pod>(bytes: &[u8], offset: u64, len: u64) -> (u32, Vec<T>) {
    let Some(section) = bytes.get(offset as usize..(offset + len) as usize).filter(|s| s.len() >= 16) else {
        return (0, Vec::new());
    };
    let count = u32::from_le_bytes([section[0], section[1], section[2], section[3]]);
    let items: Vec<T> = bytemuck::pod_collect_to_vec(&section[16..]);
    (count, items.into_iter().take(count as usize).collect())
}

/// The uncovered tiles' count and the candidates read back.
pub fn candidates(bytes: &[u8], store: &Store) -> (u32, Vec<Candidate>) {
    list(bytes, store.layout.candidates, store.layout.candidates_len)
}

/// The slots listed by a light check.
pub fn changed_slots(bytes: &[u8], store: &Store) -> Vec<u32> {
    list(bytes, store.layout.changed, store.layout.changed_len).1
}

/// Secondary sites, each with the slot that proposed it.
pub fn secondaries(bytes: &[u8], store: &Store) -> Vec<(Candidate, u32)> {
    let (_, items): (u32, Vec<Candidate>) = list(bytes, store.layout.secondaries, store.layout.secondaries_len);
    items.into_iter().map(|c| (c, c.position[3].to_bits())).collect()
}
