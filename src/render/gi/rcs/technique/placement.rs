//! The frame's placement (`rcs` technique): the splat of the cache, the last frame's readback
//! taken without waiting, this frame's rounds of records on its candidates, and the readback
//! issued for the next frame.

use super::{CoverageInputs, FrameStats, RcsTechnique};
use crate::render::RenderError;
use crate::render::gi::inputs::GiInputs;
use crate::render::gi::rcs::coverage::order;
use crate::render::gi::rcs::flight::{Issued, Landing};
use crate::render::gi::rcs::hemisphere::HemisphereInputs;
use crate::render::gi::rcs::light_check::CheckMode;
use crate::render::gi::rcs::record::Candidate;
use crate::render::gi::rcs::splat::Splat;
use crate::render::gi::rcs::staging;
use crate::render::gi::rcs::store::Store;
use crate::settings::RcsSettings;

impl RcsTechnique {
    /// The frame's placement: splats the cache, takes the last frame's readback if it has
    /// landed (never waiting for it), runs this frame's rounds on its candidates, and issues
    /// the next readback. Rounds after the first wait for their coverage (`rounds` > 1).
    pub(super) fn rounds(
        &mut self,
        inputs: &mut GiInputs<'_>,
        store: &mut Store,
        quiet: bool,
        now: &CoverageInputs,
    ) -> Result<FrameStats, RenderError> {
        let settings = inputs.settings.rcs.clone();
        let mut stats = FrameStats { reused: self.cache.live() as u64, ..FrameStats::default() };
        let Some(accum) = self.splat.accum().map(|a| a.weighted.clone()) else { return Ok(stats) };
        if quiet {
            // The records, the G-buffer and the settings are those of the frame that set
            // `quiet`: the splat buffers already hold this frame's splat (only the resolve runs).
            stats.settled = true;
            return Ok(stats);
        }
        let landed = match self.flight.take(inputs.device, self.generation)? {
            Landing::Landed(bytes, issued) => Some((bytes, issued)),
            Landing::InFlight => {
                // The records the flight computed are in the GPU's records already.
                self.splat.record(inputs, store, Splat::All(self.cache.high_water()), settings.accuracy);
                return Ok(stats);
            }
            Landing::Nothing | Landing::Stale => None,
        };
        let mut candidates_from = None;
        let mut bytes = Vec::new();
        if let Some((b, issued)) = landed {
            self.absorb(&b, store, &issued, &settings, &mut stats);
            candidates_from = Some(issued.key);
            bytes = b;
        }
        let checked = self.light_check && self.cache.live() > 0;
        if checked {
            self.check.record(inputs, store, CheckMode::Compare, self.cache.high_water(), settings.light_tolerance);
            let l = store.layout;
            inputs.encoder.copy_buffer_to_buffer(&store.changed, 0, &store.staging, l.changed, l.changed_len);
        }
        self.light_check = false;
        let mut jobs = 0;
        if candidates_from.is_some() {
            jobs = self.placement(inputs, store, &accum, bytes, &settings, &mut stats)?;
        }
        if stats.rounds == 0 {
            // No round splatted the cache this frame.
            self.splat.record(inputs, store, Splat::All(self.cache.high_water()), settings.accuracy);
        }
        let idle = stats.rounds == 0 && stats.uncovered_tiles == 0 && stats.light_renewals == 0 && !checked;
        if idle && candidates_from.as_ref() == Some(now) && self.nothing_queued() {
            // The view's coverage found nothing to do and nothing changed since: no readback.
            stats.settled = true;
            return Ok(stats);
        }
        self.coverage.record(inputs, store, &accum, stats.readbacks as u32);
        let issued = Issued { generation: self.generation, jobs, checked, key: now.clone() };
        self.flight.issue(inputs, store, issued);
        Ok(stats)
    }

    /// Whether no secondary site or renewal waits.
    pub(super) fn nothing_queued(&self) -> bool {
        self.secondary.is_empty() && self.cache.pending_renewals() == 0
    }

    /// Takes in a readback: the light check's changed records, the results and proposed sites
    /// of the round it followed, and its uncovered tiles' count.
    fn absorb(
        &mut self,
        bytes: &[u8],
        store: &Store,
        issued: &Issued<CoverageInputs>,
        settings: &RcsSettings,
        stats: &mut FrameStats,
    ) {
        if issued.checked {
            let changed = staging::changed_slots(bytes, store);
            stats.light_renewals += changed.len() as u64;
            changed.into_iter().for_each(|s| self.cache.invalidate(s));
        }
        if issued.jobs > 0 {
            self.computed(bytes, store, issued.jobs);
            let proposed = staging::secondaries(bytes, store);
            let before = self.secondary.len();
            self.queue_secondaries(proposed, settings);
            stats.secondary += (self.secondary.len() - before) as u64;
            self.grid_dirty = true;
        }
        stats.uncovered_tiles = u64::from(staging::candidates(bytes, store).0);
    }

    /// Notes the radii and irradiance of a round's `n` computed records.
    fn computed(&mut self, bytes: &[u8], store: &Store, n: u32) {
        let l = store.layout;
        let results: Vec<[f32; 4]> = bytemuck::pod_collect_to_vec(
            bytes.get(l.results as usize..(l.results + u64::from(n) * 16) as usize).unwrap_or(&[]),
        );
        for r in results {
            let change = self.cache.computed(r[2].to_bits(), r[0], r[1]);
            if self.cache.get(r[2].to_bits()).is_some_and(|c| c.computed > 1) {
                // Relative to the record's own light: a dim room far down the light path
                // counts as much as the lit one.
                self.pass.0 += if change > 0.0 { f64::from(change / r[1].max(change)) } else { 0.0 };
                self.pass.1 += 1.0;
            }
        }
    }

    /// This frame's rounds on the candidates in `bytes`: each computes a batch of records and
    /// splats them; a further round waits for the coverage after it. Returns the last round's
    /// job count (its results land with the frame's readback).
    fn placement(
        &mut self,
        inputs: &mut GiInputs<'_>,
        store: &mut Store,
        accum: &wgpu::Buffer,
        mut bytes: Vec<u8>,
        settings: &RcsSettings,
        stats: &mut FrameStats,
    ) -> Result<u32, RenderError> {
        let mut budget = settings.records_per_frame;
        let mut last = 0;
        for round in 1..=settings.rounds {
            if round > 1 {
                if last == 0 {
                    break;
                }
                self.coverage.record(inputs, store, accum, stats.readbacks as u32);
                bytes = staging::submit_and_read(inputs, store)?;
                stats.readbacks += 1;
                self.computed(&bytes, store, last);
                let proposed = staging::secondaries(&bytes, store);
                let before = self.secondary.len();
                self.queue_secondaries(proposed, settings);
                stats.secondary += (self.secondary.len() - before) as u64;
                self.grid_dirty = true;
                last = 0;
            }
            let (count, candidates) = staging::candidates(&bytes, store);
            stats.uncovered_tiles = u64::from(count);
            if count == 0 && self.nothing_queued() {
                self.next_pass(settings.convergence);
            }
            if budget == 0 || (candidates.is_empty() && self.nothing_queued()) {
                break;
            }
            let n = self.round(inputs, store, &candidates, budget, settings, stats);
            if n == 0 {
                break;
            }
            budget = budget.saturating_sub(n);
            last = n;
        }
        Ok(last)
    }

    /// One round: computes the jobs made from `candidates`, queued sites and renewals, copies
    /// their results to the staging buffer and splats them; returns how many.
    fn round(
        &mut self,
        inputs: &mut GiInputs<'_>,
        store: &mut Store,
        candidates: &[Candidate],
        budget: u32,
        settings: &RcsSettings,
        stats: &mut FrameStats,
    ) -> u32 {
        let lookup = settings.bounces > 1 && !settings.furnace && self.cache.live() > 0;
        if lookup {
            self.refresh_grid(inputs, store, settings.accuracy);
        }
        let ordered = order(candidates.to_vec());
        let (jobs, new) = self.jobs(&ordered, budget.min(store.jobs_capacity), settings, lookup);
        if jobs.is_empty() {
            return 0;
        }
        let n = jobs.len() as u32;
        stats.rounds += 1;
        stats.made += new as u64;
        stats.renewed += (jobs.len() - new) as u64;
        inputs.queue.write_buffer(&store.jobs, 0, bytemuck::cast_slice(&jobs));
        let slots: Vec<u32> = jobs.iter().map(|j| j.normal[3].to_bits()).collect();
        inputs.queue.write_buffer(&store.splat_list, 0, bytemuck::cast_slice(&slots));
        let background = if settings.furnace { 1.0 } else { 0.0 };
        let buffers = HemisphereInputs {
            jobs: &store.jobs,
            records: &store.records,
            grid_params: &store.grid_params,
            grid_cells: &store.grid_cells,
            grid_items: &store.grid_items,
        };
        self.hemisphere.record(inputs, &buffers, n, background);
        if let Some(atlas) = self.hemisphere.atlas() {
            self.reduce.record(inputs, atlas, store, n);
        }
        self.check.record(inputs, store, CheckMode::Store, n, settings.light_tolerance);
        let l = store.layout;
        inputs.encoder.copy_buffer_to_buffer(&store.results, 0, &store.staging, l.results, u64::from(n) * 16);
        inputs.encoder.copy_buffer_to_buffer(&store.secondaries, 0, &store.staging, l.secondaries, l.secondaries_len);
        // The frame's first round splats the whole cache, its records included (one splat of
        // everything a frame, and so one write of the splat's parameters a submission); a later
        // round adds its records, unless it renewed some, whose old values are in the sums.
        let first = stats.rounds == 1;
        let which = if !first && new == jobs.len() { Splat::New(n) } else { Splat::All(self.cache.high_water()) };
        self.splat.record(inputs, store, which, settings.accuracy);
        n
    }
}
