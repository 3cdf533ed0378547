//! Per-pass GPU timing with timestamp queries (where the adapter has them). Results are read
//! back without stalling: a frame's queries are copied to a readback buffer that is mapped
//! asynchronously and collected on a later frame (or waited for by `bench`). A pass recorded in
//! pieces under one name (the ISM's steps, one piece per VPL set) reads as one entry, the sum of
//! its pieces, starting where its first piece began.

use std::cell::Cell;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

/// Queries available per frame (two per scope): `ism` alone records 24 scopes (its maps' steps,
/// per VPL set) beside the frame's other passes.
const MAX_QUERIES: u32 = 256;

/// What kind of GPU work a timed pass is: rasterisation (render passes) or compute. On an H100
/// only a small part of the chip rasterises, so the profile reads the two apart.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum PassKind {
    /// Not known (the scope's writes were never asked for).
    #[default]
    Unknown,
    /// A render pass.
    Raster,
    /// A compute pass.
    Compute,
}

impl PassKind {
    /// "raster", "compute" or "unknown".
    pub fn name(self) -> &'static str {
        match self {
            Self::Unknown => "unknown",
            Self::Raster => "raster",
            Self::Compute => "compute",
        }
    }
}

/// The begin/end query pair of one pass.
pub struct TimestampPair<'a> {
    pub query_set: &'a wgpu::QuerySet,
    pub begin: u32,
    pub end: u32,
    /// Set by the kind of writes the pass asks for.
    kind: &'a Cell<PassKind>,
}

impl<'a> TimestampPair<'a> {
    /// Timestamp writes for a render pass that is (or is not) the first / last of the scope.
    pub fn render_writes(&self, first: bool, last: bool) -> wgpu::RenderPassTimestampWrites<'a> {
        self.kind.set(PassKind::Raster);
        wgpu::RenderPassTimestampWrites {
            query_set: self.query_set,
            beginning_of_pass_write_index: first.then_some(self.begin),
            end_of_pass_write_index: last.then_some(self.end),
        }
    }

    /// Timestamp writes for a compute pass that ends a scope begun by an earlier pass.
    pub fn compute_end_writes(&self) -> wgpu::ComputePassTimestampWrites<'a> {
        self.kind.set(PassKind::Compute);
        wgpu::ComputePassTimestampWrites {
            query_set: self.query_set,
            beginning_of_pass_write_index: None,
            end_of_pass_write_index: Some(self.end),
        }
    }

    /// Timestamp writes for a compute pass that begins a scope a later pass ends.
    pub fn compute_begin_writes(&self) -> wgpu::ComputePassTimestampWrites<'a> {
        self.kind.set(PassKind::Compute);
        wgpu::ComputePassTimestampWrites {
            query_set: self.query_set,
            beginning_of_pass_write_index: Some(self.begin),
            end_of_pass_write_index: None,
        }
    }

    /// Timestamp writes for a single compute pass.
    pub fn compute_writes(&self) -> wgpu::ComputePassTimestampWrites<'a> {
        self.kind.set(PassKind::Compute);
        wgpu::ComputePassTimestampWrites {
            query_set: self.query_set,
            beginning_of_pass_write_index: Some(self.begin),
            end_of_pass_write_index: Some(self.end),
        }
    }
}

/// One pass's measured GPU time.
#[derive(Clone, Debug, PartialEq)]
pub struct PassTiming {
    /// Pass name.
    pub name: String,
    /// Milliseconds.
    pub ms: f64,
    /// When it began, in milliseconds after the frame's first timed pass began (traces).
    pub start_ms: f64,
    /// Raster or compute.
    pub kind: PassKind,
}

struct Gpu {
    query_set: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    readback: wgpu::Buffer,
    pending: Option<(Vec<String>, Vec<PassKind>, Arc<AtomicBool>)>,
    map_requested: bool,
}

/// Timestamp scopes for the current frame and the latest finished results.
pub struct GpuTimer {
    gpu: Option<Gpu>,
    names: Vec<String>,
    /// Per scope of the frame, the kind its pass declared.
    kinds: Box<[Cell<PassKind>]>,
    period_ns: f32,
    latest: Vec<PassTiming>,
    /// The latest frame's scopes as recorded, pieces apart (traces).
    latest_pieces: Vec<PassTiming>,
}

impl GpuTimer {
    /// A timer; without `TIMESTAMP_QUERY` it records nothing.
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue) -> Self {
        let gpu = device.features().contains(wgpu::Features::TIMESTAMP_QUERY).then(|| {
            let size = u64::from(MAX_QUERIES) * 8;
            Gpu {
                query_set: device.create_query_set(&wgpu::QuerySetDescriptor {
                    label: Some("pass timestamps"),
                    ty: wgpu::QueryType::Timestamp,
                    count: MAX_QUERIES,
                }),
                resolve: device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("timestamp resolve"),
                    size,
                    usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
                    mapped_at_creation: false,
                }),
                readback: device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("timestamp readback"),
                    size,
                    usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                }),
                pending: None,
                map_requested: false,
            }
        });
        let kinds = (0..MAX_QUERIES / 2).map(|_| Cell::new(PassKind::Unknown)).collect();
        Self {
            gpu,
            names: Vec::new(),
            kinds,
            period_ns: queue.get_timestamp_period(),
            latest: Vec::new(),
            latest_pieces: Vec::new(),
        }
    }

    /// Whether timestamps are recorded.
    pub fn enabled(&self) -> bool {
        self.gpu.is_some()
    }

    /// Starts a frame's scopes.
    pub fn begin_frame(&mut self) {
        self.names.clear();
    }

    /// Allocates a begin/end pair for pass `name`, if timing is on and the readback is free.
    pub fn scope(&mut self, name: &str) -> Option<TimestampPair<'_>> {
        let gpu = self.gpu.as_ref()?;
        if gpu.pending.is_some() || (self.names.len() as u32 + 1) * 2 > MAX_QUERIES {
            return None;
        }
        let index = self.names.len();
        let begin = index as u32 * 2;
        self.names.push(name.to_owned());
        let kind = &self.kinds[index];
        kind.set(PassKind::Unknown);
        Some(TimestampPair { query_set: &gpu.query_set, begin, end: begin + 1, kind })
    }

    /// Resolves this frame's queries into the readback buffer.
    pub fn resolve(&mut self, encoder: &mut wgpu::CommandEncoder) {
        let Some(gpu) = self.gpu.as_mut() else { return };
        if gpu.pending.is_some() || self.names.is_empty() {
            return;
        }
        let n = self.names.len() as u32 * 2;
        encoder.resolve_query_set(&gpu.query_set, 0..n, &gpu.resolve, 0);
        encoder.copy_buffer_to_buffer(&gpu.resolve, 0, &gpu.readback, 0, u64::from(n) * 8);
        let kinds = self.kinds.iter().take(self.names.len()).map(Cell::get).collect();
        gpu.pending = Some((std::mem::take(&mut self.names), kinds, Arc::new(AtomicBool::new(false))));
    }

    /// After submit: starts mapping the readback buffer.
    pub fn after_submit(&mut self) {
        let Some(gpu) = self.gpu.as_mut() else { return };
        if let Some((_, _, ready)) = &gpu.pending
            && !gpu.map_requested
        {
            gpu.map_requested = true;
            let ready = ready.clone();
            gpu.readback.slice(..).map_async(wgpu::MapMode::Read, move |r| ready.store(r.is_ok(), Ordering::Release));
        }
    }

    /// Collects finished results (non-blocking unless `wait`); returns the latest timings.
    pub fn collect(&mut self, device: &wgpu::Device, wait: bool) -> &[PassTiming] {
        if let Some(gpu) = self.gpu.as_mut()
            && let Some((names, kinds, ready)) = &gpu.pending
        {
            let poll = if wait { wgpu::PollType::wait_indefinitely() } else { wgpu::PollType::Poll };
            let _ = device.poll(poll);
            if ready.load(Ordering::Acquire) {
                if let Ok(view) = gpu.readback.slice(..).get_mapped_range() {
                    let ticks: &[u64] = bytemuck::cast_slice(&view[..names.len() * 16]);
                    let to_ms = |t: u64| t as f64 * f64::from(self.period_ns) * 1e-6;
                    let first = ticks.first().copied().unwrap_or(0);
                    self.latest_pieces = names
                        .iter()
                        .enumerate()
                        .map(|(i, name)| PassTiming {
                            name: name.clone(),
                            ms: to_ms(ticks[2 * i + 1].saturating_sub(ticks[2 * i])),
                            start_ms: to_ms(ticks[2 * i].saturating_sub(first)),
                            kind: kinds.get(i).copied().unwrap_or_default(),
                        })
                        .collect();
                    self.latest = merge_pieces(self.latest_pieces.iter().cloned());
                }
                gpu.readback.unmap();
                gpu.pending = None;
                gpu.map_requested = false;
            }
        }
        &self.latest
    }

    /// The latest collected frame's scopes as recorded: a pass recorded in pieces appears once
    /// per piece, each at its own start (what a trace shows).
    pub fn pieces(&self) -> &[PassTiming] {
        &self.latest_pieces
    }
}

/// One entry per name, in the order names first appear: a pass recorded in several pieces under
/// one name reads as the sum of its pieces, starting where its first piece began.
fn merge_pieces(pieces: impl Iterator<Item = PassTiming>) -> Vec<PassTiming> {
    let mut merged: Vec<PassTiming> = Vec::new();
    for piece in pieces {
        match merged.iter_mut().find(|p| p.name == piece.name) {
            Some(p) => p.ms += piece.ms,
            None => merged.push(piece),
        }
    }
    merged
}

#[cfg(test)]
mod tests {
    use super::*;

    fn piece(name: &str, ms: f64, start_ms: f64) -> PassTiming {
        PassTiming { name: name.to_owned(), ms, start_ms, kind: PassKind::Compute }
    }

    #[test]
    fn pieces_of_one_name_sum_and_keep_the_first_start_and_the_order() {
        let pieces = [piece("ism splat", 2.0, 1.0), piece("ism pull-push", 0.5, 3.0), piece("ism splat", 3.0, 4.0)];
        let merged = merge_pieces(pieces.into_iter());
        assert_eq!(merged, vec![piece("ism splat", 5.0, 1.0), piece("ism pull-push", 0.5, 3.0)]);
    }
}
