//! The `rcs` technique behind the GI seam: each frame splats the cache, then runs a placement
//! round on the uncovered pixels the last frame's readback found (compute their records by
//! hemisphere rasterisation, splat them at once; [`placement`]) within a per-frame record
//! budget, renews records in place for later bounces and after edits, and writes E / pi. The cache is world-space and survives camera moves: a frame
//! of a moved camera only adds records where newly visible surfaces are uncovered.

use glam::Vec3;

mod placement;

use super::cache::{Cache, changed_boxes, object_boxes};
use super::coverage::{CoveragePass, tiles};
use super::flight::Flight;
use super::grid::HashGrid;
use super::hemisphere::HemispherePass;
use super::inspect::Inspected;
use super::light_check::LightCheckPass;
use super::record::{Candidate, GpuJob, GpuRecord, JobFlags, Site};
use super::reduce::ReducePass;
use super::splat::SplatPass;
use super::store::Store;
use crate::image_io::HdrImage;
use crate::render::gi::inputs::GiInputs;
use crate::render::gi::technique::{
    GiOutput, GiTechnique, Overlay, OverlayPoint, Readiness, ResetReason, SupportQuery, TechniqueStatus, note_reset,
};
use crate::render::readback::ReadbackError;
use crate::render::{RenderError, readback};
use crate::scene::{Aabb, Scene};
use crate::settings::{RcsSettings, RenderSettings};

/// What the last frame did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct FrameStats {
    made: u64,
    secondary: u64,
    renewed: u64,
    rounds: u64,
    uncovered_tiles: u64,
    light_renewals: u64,
    reused: u64,
    /// Readbacks the CPU waited for (one per round after the first; the frame's own readback
    /// lands in a later frame).
    readbacks: u64,
    /// The readback taken this frame showed the current view fully covered with nothing left
    /// to do: no further readback was issued.
    settled: bool,
}

/// Radiance cache splatting.
pub struct RcsTechnique {
    hemisphere: HemispherePass,
    reduce: ReducePass,
    check: LightCheckPass,
    splat: SplatPass,
    coverage: CoveragePass,
    store: Option<Store>,
    cache: Cache,
    grid_dirty: bool,
    /// Object bounds and materials as the cache last saw them.
    boxes: Option<Vec<(Aabb, u64)>>,
    /// Bounds of objects changed since the last frame.
    changed: Vec<Aabb>,
    light_check: bool,
    drop_all: bool,
    /// The sky and emission the records were computed with.
    emitters: crate::render::gi::changes::EmittersWatch,
    /// Secondary record sites proposed by hemispheres and not made yet, with their depth.
    secondary: Vec<(Site, u32)>,
    /// The running bounce pass: summed relative luminance change of its renewals, and their
    /// count.
    pass: (f64, f64),
    /// Bounce passes run so far since the cache last filled.
    passes: u32,
    /// The bounce passes converged: new records need one renewal, not a pass of everyone.
    converged: bool,
    /// The settings the records were computed with (a change of these drops the cache).
    made_with: Option<RcsSettings>,
    frame: u64,
    last: FrameStats,
    totals: FrameStats,
    dropped: u64,
    /// The tallest view rendered since the technique last held memory (pixels): the zone
    /// clamp's pixels are that view's, so records made in a reduced-resolution preview are as
    /// fine as the full view's.
    tallest_view: u32,
    /// tan of the camera's half vertical field of view.
    tan_half_fov: Option<f32>,
    /// What the last frame's coverage was found from, when it found nothing to do (no
    /// uncovered tile, no queued site or renewal, no invalidation, no bounce pass to start): a
    /// frame with the same inputs would find the same, so it skips the coverage pass and its
    /// readback, the one GPU wait of a warm frame, and the splat, whose targets (the
    /// technique's own) still hold the same sums; only the resolve into the frame runs.
    quiet: Option<CoverageInputs>,
    /// The placement readback in flight.
    flight: Flight<CoverageInputs>,
    /// Bumped whenever records are dropped: a readback issued before holds their slots.
    generation: u64,
    status: TechniqueStatus,
}

/// What a frame's coverage depends on besides the cache: the scene (every edit, camera moves
/// included, changes its revision), the view's size and the settings.
#[derive(Clone, Debug, PartialEq)]
struct CoverageInputs {
    revision: u64,
    size: (u32, u32),
    settings: RcsSettings,
}

/// The settings whose change invalidates every record (the bounce settings too: targets are
/// fixed when records are made).
fn cache_key(s: &RcsSettings) -> RcsSettings {
    RcsSettings { records_per_frame: 0, rounds: 0, gradients: false, light_tolerance: 0.0, ..s.clone() }
}

impl RcsTechnique {
    /// Creates the pipelines.
    pub fn new(device: &wgpu::Device, layouts: &crate::render::layouts::Layouts) -> Result<Self, RenderError> {
        Ok(Self {
            hemisphere: HemispherePass::new(device, layouts)?,
            reduce: ReducePass::new(device)?,
            check: LightCheckPass::new(device)?,
            splat: SplatPass::new(device)?,
            coverage: CoveragePass::new(device)?,
            store: None,
            cache: Cache::default(),
            grid_dirty: true,
            boxes: None,
            changed: Vec::new(),
            light_check: false,
            drop_all: true,
            emitters: Default::default(),
            secondary: Vec::new(),
            pass: (0.0, 0.0),
            passes: 0,
            converged: false,
            made_with: None,
            frame: 0,
            last: FrameStats::default(),
            totals: FrameStats::default(),
            dropped: 0,
            tallest_view: 0,
            tan_half_fov: None,
            quiet: None,
            flight: Flight::default(),
            generation: 0,
            status: TechniqueStatus::default(),
        })
    }

    /// Needs storage bindings large enough for the view's splat sums (16 bytes a pixel) and
    /// for `max_records` records' check strata.
    pub fn support(query: &SupportQuery<'_>) -> Result<(), String> {
        let limit = query.limits.max_storage_buffer_binding_size.min(query.limits.max_buffer_size);
        let (w, h) = query.size;
        let sums = u64::from(w) * u64::from(h) * super::splat::ACCUM_TEXEL_BYTES;
        if sums > limit {
            return Err(format!(
                "rcs sums {w}x{h} pixels in one buffer of {} MiB, over this adapter's {} MiB: render smaller",
                sums >> 20,
                limit >> 20
            ));
        }
        let records = u64::from(query.settings.rcs.max_records);
        let strata = records * super::store::CHECK_STRATA * 16;
        if strata > limit {
            return Err(format!(
                "rcs.max_records = {records} needs {} MiB of check strata in one buffer, over this adapter's {} MiB: lower max_records to {} or fewer",
                strata >> 20,
                limit >> 20,
                limit / (super::store::CHECK_STRATA * 16)
            ));
        }
        Ok(())
    }

    /// The live records (tests and tools).
    pub fn cache(&self) -> &Cache {
        &self.cache
    }

    /// Reads every record slot below the high-water mark.
    pub fn read_records(&self, device: &wgpu::Device, queue: &wgpu::Queue) -> Result<Vec<GpuRecord>, ReadbackError> {
        let Some(store) = &self.store else { return Ok(Vec::new()) };
        let bytes = readback::read_buffer(device, queue, &store.records)?;
        let n = self.cache.high_water() as usize;
        Ok(bytemuck::pod_collect_to_vec::<u8, GpuRecord>(&bytes).into_iter().take(n).collect())
    }

    /// Queues secondary sites, dropping any within two smallest zones of one already queued
    /// (many hemispheres see the same unseen wall).
    fn queue_secondaries(&mut self, proposed: Vec<(Candidate, u32)>, settings: &RcsSettings) {
        let mut proposed = proposed;
        proposed.sort_by_key(|(c, parent)| (*parent, c.tile()));
        for (c, parent) in proposed {
            let Some(p) = self.cache.get(parent) else { continue };
            let depth = p.depth + 1;
            if depth >= settings.bounces {
                continue;
            }
            let site = Site {
                position: c.point(),
                normal: c.direction(),
                near: p.site.near,
                radius_bounds: p.site.radius_bounds,
            };
            let spacing = 2.0 * settings.accuracy * site.radius_bounds.0;
            let crowded = self.secondary.iter().any(|(s, _)| {
                s.position.distance_squared(site.position) < spacing * spacing && s.normal.dot(site.normal) > 0.9
            });
            if !crowded && self.secondary.len() < self.cache.room() as usize {
                self.secondary.push((site, depth));
            }
        }
    }

    /// Ends a finished bounce pass (converged when it changed the records' luminance by less
    /// than `tolerance` on average, each relative to its own) and starts the next while records
    /// ask for more.
    fn next_pass(&mut self, tolerance: f32) {
        let (change, total) = self.pass;
        if total > 0.0 {
            self.passes += 1;
            if change < f64::from(tolerance) * total {
                self.converged = true;
                self.cache.settle();
            }
        }
        self.pass = (0.0, 0.0);
        self.cache.queue_bounces();
    }

    /// The pixel footprint (m per pixel) at `distance` from the camera.
    fn footprint(&self, distance: f32) -> f32 {
        let Some(tan_half) = self.tan_half_fov else { return 1e-3 };
        2.0 * tan_half * distance / self.tallest_view.max(1) as f32
    }

    /// Applies the pending invalidations before the frame's rounds.
    fn invalidate(&mut self, inputs: &mut GiInputs<'_>, store: &Store, tolerance: f32) {
        if self.drop_all {
            self.dropped += self.cache.live() as u64;
            self.cache = Cache::new(store.max_records);
            self.secondary.clear();
            self.pass = (0.0, 0.0);
            self.passes = 0;
            self.converged = false;
            inputs.encoder.clear_buffer(&store.records, 0, None);
            self.grid_dirty = true;
            self.drop_all = false;
            self.generation += 1;
            self.changed.clear();
        }
        if !self.changed.is_empty() {
            // A record within a few near planes of a changed object stood on it.
            let margin = self.cache.iter().map(|(_, r)| r.site.near).fold(0.0f32, f32::max) * 4.0;
            let inv = self.cache.invalidate_boxes(&self.changed, margin.max(1e-4), tolerance);
            for &slot in &inv.dropped {
                let offset = u64::from(slot) * std::mem::size_of::<GpuRecord>() as u64;
                inputs.queue.write_buffer(&store.records, offset, bytemuck::bytes_of(&GpuRecord::default()));
            }
            self.dropped += inv.dropped.len() as u64;
            self.grid_dirty |= !inv.dropped.is_empty();
            self.generation += u64::from(!inv.dropped.is_empty());
            self.changed.clear();
        }
    }

    /// Makes this round's jobs: new records at `candidates` (up to `budget`), then queued
    /// secondary sites, then queued renewals; returns the jobs and how many of them are new.
    fn jobs(
        &mut self,
        candidates: &[Candidate],
        budget: u32,
        settings: &RcsSettings,
        lookup: bool,
    ) -> (Vec<GpuJob>, usize) {
        let mut sites = Vec::new();
        let largest = self.largest_radius();
        // Once the passes converged, a new record's first computation already looks up the
        // converged cache: one renewal settles it (its own secondary records are new as well).
        let target = if self.converged { settings.bounces.min(2) } else { settings.bounces };
        let room = budget.min(self.cache.room()) as usize;
        for c in candidates.iter().take(room) {
            let footprint = self.footprint(c.position[3]);
            let site = Site::new(
                c.point(),
                c.direction(),
                footprint,
                settings.accuracy,
                (settings.min_zone_pixels, settings.max_zone_pixels),
                largest,
            );
            if let Some(slot) = self.cache.allocate(site, self.frame, 0, target) {
                sites.push((slot, site, 0, 0));
            }
        }
        let take = room.saturating_sub(sites.len()).min(self.secondary.len());
        for (site, depth) in self.secondary.drain(..take).collect::<Vec<_>>() {
            if let Some(slot) = self.cache.allocate(site, self.frame, depth, target) {
                sites.push((slot, site, 0, depth));
            }
        }
        let new = sites.len();
        let renewals = self.cache.take_renewals(budget as usize - new);
        for slot in renewals {
            if let Some(r) = self.cache.get(slot) {
                sites.push((slot, r.site, r.computed, r.depth));
            }
        }
        let atlas_origin = |i: u32| self.hemisphere.atlas().map_or((0, 0), |a| a.origin(i));
        let jobs = sites
            .iter()
            .enumerate()
            .map(|(i, (slot, site, computed, depth))| {
                let flags =
                    JobFlags { furnace: settings.furnace, lookup, propose: lookup && depth + 1 < settings.bounces };
                site.job(*slot, atlas_origin(i as u32), flags, *computed)
            })
            .collect();
        (jobs, new)
    }

    /// The largest R_k allowed when no pixel clamp applies: the scene's diagonal.
    fn largest_radius(&self) -> f32 {
        self.boxes
            .as_ref()
            .and_then(|b| b.iter().map(|x| x.0).reduce(|a, b| a.union(&b)))
            .map_or(100.0, |b| (b.max - b.min).length().max(1e-3))
    }

    /// Rebuilds the bounce lookup grid from the computed records.
    fn refresh_grid(&mut self, inputs: &GiInputs<'_>, store: &mut Store, accuracy: f32) {
        if !self.grid_dirty {
            return;
        }
        let listed: Vec<(u32, Vec3, f32)> = self
            .cache
            .iter()
            .filter(|(_, r)| r.radius > 0.0)
            .map(|(s, r)| (s, r.site.position, accuracy * r.radius))
            .collect();
        store.upload_grid(inputs.device, inputs.queue, &HashGrid::build(&listed, accuracy));
        self.grid_dirty = false;
    }
}

impl GiTechnique for RcsTechnique {
    fn prepare(&mut self, scene: &Scene, settings: &RenderSettings, size: (u32, u32)) -> Readiness {
        let boxes = object_boxes(scene);
        if let Some(old) = &self.boxes {
            self.changed.extend(changed_boxes(old, &boxes));
        }
        self.boxes = Some(boxes);
        // The light check relights with the punctual lights only: an edit of the sky or of an
        // emission renews every record.
        if self.emitters.changed(scene) {
            self.drop_all = true;
        }
        let key = cache_key(&settings.rcs);
        if self.made_with.as_ref() != Some(&key) {
            self.drop_all = true;
            self.made_with = Some(key);
        }
        self.tallest_view = self.tallest_view.max(size.1);
        self.tan_half_fov = Some((scene.camera().yfov * 0.5).tan());
        Readiness::Ready
    }

    fn render(&mut self, inputs: &mut GiInputs<'_>) -> Result<GiOutput, RenderError> {
        let settings = inputs.settings.rcs.clone();
        let size = inputs.targets.size;
        let h = settings.hemisphere_resolution;
        let jobs = super::hemisphere::round_capacity(h, settings.records_per_frame);
        let fits = self.store.as_ref().is_some_and(|s| {
            s.max_records == settings.max_records && s.jobs_capacity == jobs && s.tiles >= tiles(size)
        });
        let mut store = match self.store.take() {
            Some(s) if fits => s,
            previous => {
                if previous.as_ref().is_some_and(|s| s.max_records != settings.max_records) || previous.is_none() {
                    self.drop_all = true;
                }
                // A readback in flight reads the old store's staging buffer: let it go.
                self.flight.forget();
                self.generation += 1;
                let mut s = Store::new(inputs.device, settings.max_records, jobs, tiles(size));
                if let Some(old) = previous.filter(|o| o.max_records == settings.max_records) {
                    // Keep the records across a resize: copy them over.
                    inputs.encoder.copy_buffer_to_buffer(&old.records, 0, &s.records, 0, old.records.size());
                    inputs.encoder.copy_buffer_to_buffer(
                        &old.check_strata,
                        0,
                        &s.check_strata,
                        0,
                        old.check_strata.size(),
                    );
                    self.grid_dirty = true;
                }
                s.weights_resolution = 0;
                s
            }
        };
        if self.cache.high_water() == 0 && self.cache.live() == 0 {
            self.cache = Cache::new(settings.max_records);
        }
        store.ensure_weights(inputs.device, inputs.queue, h);
        self.splat.ensure(inputs.device, size);
        self.coverage.ensure(inputs.device, size, settings.rounds);
        self.hemisphere.ensure(inputs.device, h, jobs);
        let now = CoverageInputs { revision: inputs.scene.revision(), size, settings: settings.clone() };
        let untouched = !self.drop_all && self.changed.is_empty() && !self.light_check;
        // Taken in every frame: a frame that drops or changes records must not leave the marker
        // of the quiet frame before it for the next.
        let last_quiet = self.quiet.take();
        let quiet = untouched && last_quiet.as_ref() == Some(&now);
        self.invalidate(inputs, &store, settings.light_tolerance);
        let result = self.rounds(inputs, &mut store, quiet, &now);
        self.splat.resolve(inputs, settings.gradients);
        self.store = Some(store);
        let stats = result?;
        if untouched && stats.settled {
            self.quiet = Some(now);
        }
        self.frame += 1;
        self.last = stats;
        self.totals.made += stats.made;
        self.totals.renewed += stats.renewed;
        self.totals.secondary += stats.secondary;
        self.totals.light_renewals += stats.light_renewals;
        self.status.history_frames = self.status.history_frames.saturating_add(1);
        // A readback in flight may still find uncovered pixels.
        let filling = stats.uncovered_tiles > 0 || !self.nothing_queued() || self.flight.busy();
        self.status.refining = (filling || self.cache.unsettled()) && self.cache.room() > 0;
        self.status.refine_target = 0;
        self.status.progress = Some(format!(
            "rcs: {} records (+{} new, {} renewed this frame), {} uncovered tiles, bounce pass {}{}{}",
            self.cache.live(),
            stats.made,
            stats.renewed,
            stats.uncovered_tiles,
            self.passes + 1,
            if self.converged { " (converged)" } else { "" },
            if self.cache.room() == 0 { ", cache full" } else { "" }
        ));
        Ok(GiOutput::IrradianceOverPi)
    }

    fn read_buffer(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        name: &str,
    ) -> Option<Result<HdrImage, RenderError>> {
        let views = Inspected { splat: &self.splat, coverage: &self.coverage, hemisphere: &self.hemisphere };
        views.read(device, queue, name)
    }

    fn overlays(&self, _device: &wgpu::Device, _queue: &wgpu::Queue) -> Vec<Overlay> {
        let radii: Vec<f32> = self.cache.iter().map(|(_, r)| r.radius).filter(|r| *r > 0.0).collect();
        let (lo, hi) = radii.iter().fold((f32::INFINITY, 0.0f32), |(a, b), &r| (a.min(r), b.max(r)));
        let span = (hi / lo.max(1e-9)).ln().max(1e-6);
        let accuracy = self.made_with.as_ref().map_or(0.25, |s| s.accuracy);
        // Dots coloured by R_k (log scale, small = blue), circles of the zone a R_k; records
        // the camera never saw (secondary) are smaller dots.
        let points = self
            .cache
            .iter()
            .filter(|(_, r)| r.radius > 0.0)
            .map(|(_, r)| OverlayPoint {
                position: r.site.position,
                tone: ((r.radius / lo.max(1e-9)).ln() / span).clamp(0.0, 1.0),
                radius: if r.depth == 0 { 2.5 } else { 1.5 },
                ring: if r.depth == 0 { accuracy * r.radius } else { 0.0 },
            })
            .collect();
        vec![Overlay { name: "rcs records", points, ..Default::default() }]
    }

    fn reset(&mut self, reason: ResetReason) {
        note_reset(&mut self.status, reason);
        match reason {
            // Memory was released (or never held): start over.
            ResetReason::ModeEntered => self.drop_all = true,
            // Which records: `prepare` compares the objects' bounds.
            ResetReason::SceneEdited => {}
            ResetReason::LightEdited => self.light_check = true,
            // World-space records survive camera moves and resizes; settings that change
            // records are compared in `prepare`.
            ResetReason::CameraCut | ResetReason::SettingsChanged | ResetReason::Resized => {}
        }
    }

    fn release(&mut self) {
        self.flight.forget();
        self.store = None;
        self.hemisphere.release();
        self.splat.release();
        self.coverage.release();
        self.cache = Cache::default();
        self.secondary.clear();
        self.tallest_view = 0;
        self.boxes = None;
        self.made_with = None;
        self.drop_all = true;
        self.quiet = None;
    }

    fn gpu_bytes(&self) -> u64 {
        self.store.as_ref().map_or(0, Store::gpu_bytes)
            + self.hemisphere.gpu_bytes()
            + self.splat.gpu_bytes()
            + self.coverage.gpu_bytes()
    }

    fn limitations(&self, _scene: &Scene, settings: &RenderSettings) -> Vec<String> {
        let mut out = vec![
            "surfaces the records see send diffuse light only (glossy senders reflect as if matte)".to_owned(),
            "later bounces come from the cache: where it has no record yet (a surface the camera never saw) a secondary record is made, and until then the renewed record's own irradiance stands in".to_owned(),
        ];
        if settings.rcs.furnace {
            out.push(
                "white furnace on: every surface the records see emits 1 (a check of E = pi, not lighting)".into(),
            );
        }
        out
    }

    fn status(&self) -> TechniqueStatus {
        let mut s = self.status.clone();
        s.counters = vec![
            ("records", self.cache.live() as u64),
            ("records made", self.totals.made),
            ("records made last frame", self.last.made),
            ("secondary sites queued", self.totals.secondary),
            ("secondary records", self.cache.iter().filter(|(_, r)| r.depth > 0).count() as u64),
            ("records renewed", self.totals.renewed),
            ("records renewed last frame", self.last.renewed),
            ("records reused last frame", self.last.reused),
            ("records dropped", self.dropped),
            ("light check renewals", self.totals.light_renewals),
            ("light check renewals last frame", self.last.light_renewals),
            ("rounds last frame", self.last.rounds),
            ("bounce passes", u64::from(self.passes)),
            ("bounce passes converged", u64::from(self.converged)),
            ("uncovered tiles", self.last.uncovered_tiles),
            ("GPU waits last frame", self.last.readbacks),
        ];
        s
    }

    fn as_any(&self) -> &dyn std::any::Any {
        self
    }
}
