//! The reference path tracer: progressive, unbiased, deterministic for a seed.
//!
//! Same scene, materials and light conventions as the rasteriser: punctual lights by next-event
//! estimation with the KHR spot falloff and inverse-square distance, the Lambertian + Blinn-Phong
//! BRDF of `brdf.rs`, one-sided surfaces (a back-face hit ends the path black but occludes),
//! base-colour textures and normal maps. Emissive surfaces (front faces only) and the sky are
//! lights too: next-event estimation samples an emissive triangle by power (`emitters.rs`) and
//! an image sky by luminance (`sky_sampler.rs`), BRDF sampling finds them as well, and the two
//! are combined by multiple importance sampling with the power heuristic (Veach 1997, ch. 9); a
//! constant sky is left to BRDF sampling alone. Paths continue by BRDF importance sampling or,
//! with path guiding on (`guiding.rs`), by its mixture with a guide learnt from earlier passes
//! (every MIS weight then uses the mixture's density), with Russian roulette from `rr_start`;
//! `max_bounces = 1` is direct light only (the BRDF-sampled ray is still traced, to find
//! emitters and the sky for MIS, but the path ends). One call of
//! [`PathTracer::add_sample`] adds one jittered (box-filtered) sample to every pixel, in parallel
//! over rows with rayon, and can be cancelled. Each path draws its decisions from its pixel's
//! Owen-scrambled Sobol sequence (`sampler.rs`), so a pixel's samples spread evenly.

use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use glam::{Vec2, Vec3};
use rayon::prelude::*;

use super::brdf::{Surface, phong_exponent};
use super::bvh::{Hit, SceneBvh};
use super::emitters::{Emitters, power_heuristic};
use super::guiding::{CellGuide, GUIDE_SHARE, Guide, Record, TRAINING_PASSES, Training};
use super::sampler::{PathSampler, Sampler};
use super::sky_sampler::{SkyDistribution, luminance, sky_distribution};
use crate::image_io::srgb_to_linear;
use crate::scene::{Camera, Environment, Image, Light, LightKind, Material, Scene, SkyImage};
use crate::settings::ReferenceSettings;

/// Bump when what the tracer converges to changes (its conventions or light transport): cached
/// suite references keyed on it go stale. A change of its noise alone (the sampler, where
/// Russian roulette starts) leaves every reference an estimate of the same image.
pub const TRACER_VERSION: u32 = 1;
/// Progress after a pass.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Progress {
    /// Samples per pixel accumulated.
    pub spp: u32,
    /// Rays traced per second (camera, bounce and shadow rays), over the whole run.
    pub rays_per_second: f64,
    /// Samples (paths) per second, over the whole run.
    pub samples_per_second: f64,
}

/// A progressive reference render of one view.
pub struct PathTracer {
    bvh: SceneBvh,
    materials: Vec<Material>,
    images: Vec<Image>,
    lights: Vec<Light>,
    emitters: Emitters,
    environment: Environment,
    sky: Option<std::sync::Arc<SkyImage>>,
    sky_distribution: Option<SkyDistribution>,
    camera: Camera,
    size: (u32, u32),
    settings: ReferenceSettings,
    accum: Vec<[f64; 3]>,
    /// Path guiding (`guiding.rs`): what bounces sample from, and the iteration learning the next.
    guide: Option<Guide>,
    training: Option<Training>,
    spp: u32,
    rays: u64,
    elapsed: Duration,
}

fn texel(img: &Image, x: i64, y: i64) -> [f32; 4] {
    let (w, h) = (i64::from(img.width), i64::from(img.height));
    let (x, y) = (x.rem_euclid(w) as usize, y.rem_euclid(h) as usize);
    let i = 4 * (y * img.width as usize + x);
    let p = &img.rgba8[i..i + 4];
    [p[0], p[1], p[2], p[3]].map(|c| f32::from(c) / 255.0)
}

/// Bilinear, repeating lookup; `srgb` decodes each texel before filtering (as the GPU does).
pub(crate) fn sample_image(img: &Image, uv: Vec2, srgb: bool) -> Vec3 {
    let x = uv.x * img.width as f32 - 0.5;
    let y = uv.y * img.height as f32 - 0.5;
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = (x - x0, y - y0);
    let get = |dx: i64, dy: i64| {
        let t = texel(img, x0 as i64 + dx, y0 as i64 + dy);
        let c = Vec3::new(t[0], t[1], t[2]);
        if srgb { Vec3::new(srgb_to_linear(c.x), srgb_to_linear(c.y), srgb_to_linear(c.z)) } else { c }
    };
    let top = get(0, 0).lerp(get(1, 0), fx);
    let bottom = get(0, 1).lerp(get(1, 1), fx);
    top.lerp(bottom, fy)
}

impl PathTracer {
    /// Prepares a render of `scene` from its camera at `size`.
    pub fn new(scene: &Scene, size: (u32, u32), settings: ReferenceSettings) -> Self {
        let n = size.0 as usize * size.1 as usize;
        let bvh = SceneBvh::build(scene);
        bvh.wide(); // Built here, not in the first sample's time.
        let emitters = Emitters::new(&bvh, scene.materials());
        let sky = scene.sky_texels();
        let training = settings.guiding.then(|| scene.bounds()).flatten().map(|b| Training::first(b.min, b.max));
        Self {
            guide: None,
            training,
            bvh,
            materials: scene.materials().to_vec(),
            images: scene.resources().images.clone(),
            lights: scene.lights().to_vec(),
            emitters,
            environment: scene.environment().clone(),
            sky_distribution: sky_distribution(scene.environment(), sky.as_deref()),
            sky,
            camera: *scene.camera(),
            size,
            settings,
            accum: vec![[0.0; 3]; n],
            spp: 0,
            rays: 0,
            elapsed: Duration::ZERO,
        }
    }

    /// The target samples per pixel of its settings.
    pub fn settings_spp(&self) -> u32 {
        self.settings.spp
    }

    /// Samples per pixel so far.
    pub fn spp(&self) -> u32 {
        self.spp
    }

    /// Current progress figures.
    pub fn progress(&self) -> Progress {
        let secs = self.elapsed.as_secs_f64().max(1e-9);
        let pixels = self.accum.len() as f64;
        Progress {
            spp: self.spp,
            rays_per_second: self.rays as f64 / secs,
            samples_per_second: f64::from(self.spp) * pixels / secs,
        }
    }

    /// Adds one sample to every pixel; returns `None` (and adds nothing) if cancelled.
    pub fn add_sample(&mut self, cancel: &AtomicBool) -> Option<Progress> {
        let start = Instant::now();
        let w = self.size.0 as usize;
        let train = self.training.is_some();
        let mut pass = vec![[0.0f32; 3]; self.accum.len()];
        let mut rays = 0u64;
        // While guiding trains, rows go in bands whose records are added in row order (so a
        // seed gives one image) without holding a whole pass's records.
        let band = if train { BAND_ROWS * w } else { pass.len().max(1) };
        for (b, chunk) in pass.chunks_mut(band).enumerate() {
            let rows: Vec<(u64, Vec<Record>)> = chunk
                .par_chunks_mut(w)
                .enumerate()
                .map(|(i, row)| self.row(b * band / w + i, row, cancel, train))
                .collect();
            if cancel.load(Ordering::Relaxed) {
                return None;
            }
            for (r, records) in rows {
                rays += r;
                if let Some(t) = &mut self.training {
                    t.add(&records);
                }
            }
        }
        for (a, p) in self.accum.iter_mut().zip(&pass) {
            for c in 0..3 {
                a[c] += f64::from(p[c]);
            }
        }
        self.spp += 1;
        self.learn();
        self.rays += rays;
        self.elapsed += start.elapsed();
        Some(self.progress())
    }

    /// One sample of every pixel of row `y` into `row`: the rays traced and, if `train`, the
    /// guiding records of its paths.
    fn row(&self, y: usize, row: &mut [[f32; 3]], cancel: &AtomicBool, train: bool) -> (u64, Vec<Record>) {
        let mut sink = Sink::default();
        if cancel.load(Ordering::Relaxed) {
            return (0, sink.records);
        }
        let mut rays = 0u64;
        let w = self.size.0 as u64;
        for (x, out) in row.iter_mut().enumerate() {
            let pixel = y as u64 * w + x as u64;
            let mut sampler = PathSampler::new(self.settings.seed, pixel, self.spp);
            let dir = self.camera_ray(x as f32, y as f32, &mut sampler);
            // A quarter of the paths (a different quarter each pass) train the guide.
            let trains = train && (x as u64 + 2 * (y as u64 & 1) + u64::from(self.spp)).is_multiple_of(TRAINING_STRIDE);
            let into = if trains { Some(&mut sink) } else { None };
            let (l, r) = self.radiance_into(self.camera.position, dir, &mut sampler, into);
            *out = l.to_array();
            rays += r;
        }
        (rays, sink.records)
    }

    /// After a pass: ends the training iteration if it is complete (its guide replaces the
    /// last; training stops after [`TRAINING_PASSES`]).
    fn learn(&mut self) {
        let Some((guide, next)) = self.training.as_mut().and_then(Training::finish_pass) else { return };
        self.guide = Some(guide);
        self.training = (self.spp < TRAINING_PASSES).then_some(next);
    }

    /// Cells of the path-guiding tree the tracer samples from (0 before the first pass or
    /// with guiding off).
    pub fn guide_cells(&self) -> usize {
        self.guide.as_ref().map_or(0, Guide::cells)
    }

    /// Adds samples until `spp` are accumulated (or cancelled), reporting after each pass.
    pub fn render(&mut self, spp: u32, cancel: &AtomicBool, mut on_progress: impl FnMut(&Progress)) {
        while self.spp < spp {
            match self.add_sample(cancel) {
                Some(p) => on_progress(&p),
                None => return,
            }
        }
    }

    /// The current estimate: mean radiance per pixel (RGBA, alpha 1).
    pub fn image(&self) -> Vec<[f32; 4]> {
        let inv = 1.0 / f64::from(self.spp.max(1));
        self.accum.iter().map(|a| [(a[0] * inv) as f32, (a[1] * inv) as f32, (a[2] * inv) as f32, 1.0]).collect()
    }

    fn surface(&self, hit: &Hit) -> (Vec3, Vec3, Surface) {
        let tri = &self.bvh.tris[hit.tri as usize];
        let (w0, w1, w2) = (1.0 - hit.u - hit.v, hit.u, hit.v);
        let p = tri.p[0] * w0 + tri.p[1] * w1 + tri.p[2] * w2;
        let mut n = (tri.n[0] * w0 + tri.n[1] * w1 + tri.n[2] * w2).try_normalize().unwrap_or(tri.ng);
        let uv = tri.uv[0] * w0 + tri.uv[1] * w1 + tri.uv[2] * w2;
        let fallback;
        let m = match self.materials.get(tri.material as usize) {
            Some(m) => m,
            None => {
                fallback = Material::default();
                &fallback
            }
        };
        let mut albedo = Vec3::new(m.base_color[0], m.base_color[1], m.base_color[2]);
        if let Some(img) = m.base_color_texture.and_then(|t| self.images.get(t.image)) {
            albedo *= sample_image(img, uv, true);
        }
        if let Some(img) = m.normal_texture.and_then(|t| self.images.get(t.image)) {
            let tw = tri.tangent[0] * w0 + tri.tangent[1] * w1 + tri.tangent[2] * w2;
            let t = (tw.truncate() - n * n.dot(tw.truncate())).normalize_or_zero();
            let b = n.cross(t) * if tw.w >= 0.0 { 1.0 } else { -1.0 };
            let mut mm = sample_image(img, uv, false) * 2.0 - Vec3::ONE;
            mm.x *= m.normal_scale;
            mm.y *= m.normal_scale;
            n = (t * mm.x + b * mm.y + n * mm.z).try_normalize().unwrap_or(n);
        }
        let surface =
            Surface { albedo, specular: Vec3::from_array(m.specular), exponent: phong_exponent(m.roughness), n };
        (p, tri.ng, surface)
    }

    /// The direction of a camera ray through pixel (x, y), jittered within the pixel.
    pub fn camera_ray(&self, x: f32, y: f32, rng: &mut impl Sampler) -> Vec3 {
        let (w, h) = self.size;
        let (jx, jy) = rng.next_2d();
        self.camera.ray_direction(x + jx, y + jy, w, h)
    }

    /// The scene's ray-tracing BVH.
    pub fn bvh(&self) -> &SceneBvh {
        &self.bvh
    }

    /// The camera the view is traced from.
    pub fn camera(&self) -> &Camera {
        &self.camera
    }

    /// One path estimate of the radiance arriving at `origin` from direction `-dir` (the ray
    /// `origin + t dir`), and the number of rays traced.
    pub fn radiance(&self, origin: Vec3, dir: Vec3, rng: &mut impl Sampler) -> (Vec3, u64) {
        self.radiance_into(origin, dir, rng, None)
    }

    /// [`Self::radiance`], handing the path's guiding records to `records`.
    fn radiance_into(
        &self,
        origin: Vec3,
        dir: Vec3,
        rng: &mut impl Sampler,
        records: Option<&mut Sink>,
    ) -> (Vec3, u64) {
        let mut radiance = Vec3::ZERO;
        let rays = self.follow(origin, dir, rng, &mut |vertex| radiance += vertex.light, records);
        if let Some(c) = self.settings.clamp {
            let m = radiance.max_element();
            if m > c {
                radiance *= c / m;
            }
        }
        (radiance, rays)
    }

    /// Follows one path from `origin` along `dir`, handing each surface it meets to `visit`
    /// with the light that surface sends along the path to `origin` (its own emission if it is
    /// the first, its next-event estimate, and the MIS-weighted emission and sky its sampled
    /// bounce ray finds, times the path's throughput); a first ray that leaves the scene hands
    /// over the sky it sees as a vertex at depth 0 far along `dir`. Returns the rays traced.
    pub fn walk(&self, origin: Vec3, dir: Vec3, rng: &mut impl Sampler, mut visit: impl FnMut(Vertex)) -> u64 {
        self.follow(origin, dir, rng, &mut visit, None)
    }

    /// [`Self::walk`], handing the path's guiding records (one a bounce) to `records`.
    fn follow(
        &self,
        mut origin: Vec3,
        mut dir: Vec3,
        rng: &mut impl Sampler,
        visit: &mut dyn FnMut(Vertex),
        records: Option<&mut Sink>,
    ) -> u64 {
        let mut trail = records.zip(self.training.as_ref()).map(|(r, t)| Trail::new(r, t));
        let mut throughput = Vec3::ONE;
        let mut rays = 1u64;
        let eps = 1e-4 * self.bvh.scale;
        let area_lights = !self.emitters.is_empty() || self.environment.emits(self.sky.as_deref());
        let mut hit = self.bvh.trace(origin, dir, f32::INFINITY);
        for depth in 0..self.settings.max_bounces {
            let Some(h) = hit else {
                if depth == 0 {
                    let sky = self.sky_radiance(dir);
                    visit(Vertex { depth, p: origin + dir * 1e6 * self.bvh.scale.max(1.0), ng: -dir, light: sky });
                }
                break;
            };
            let (p, ng, surface) = self.surface(&h);
            let v = -dir;
            if ng.dot(v) <= 0.0 {
                break; // One-sided: the back of a surface is black.
            }
            let lifted = p + ng * eps;
            let guide = self.guide.as_ref().and_then(|g| g.at(p, ng));
            let at = ShadingPoint { p, ng, lifted, v, surface: &surface, guide };
            let mut light = throughput * self.next_event(&at, rng, &mut rays);
            if depth == 0 {
                light += self.emitted(&h);
            }
            let last = depth + 1 >= self.settings.max_bounces;
            if last && !area_lights {
                visit(Vertex { depth, p, ng, light });
                if let Some(t) = &mut trail {
                    t.add(light);
                }
                break;
            }
            let Some((l, pdf)) = sample_bounce(&at, rng) else {
                visit(Vertex { depth, p, ng, light });
                if let Some(t) = &mut trail {
                    t.add(light);
                }
                break;
            };
            throughput *= surface.eval(v, l) * surface.n.dot(l) / pdf;
            if let Some(t) = &mut trail {
                t.bounce(p, ng, l, pdf, throughput, light);
            }
            rays += 1;
            hit = self.bvh.trace(lifted, l, f32::INFINITY);
            light += throughput * self.found_light(l, hit.as_ref(), pdf);
            visit(Vertex { depth, p, ng, light });
            if let Some(t) = &mut trail {
                t.add(light);
            }
            if last {
                break;
            }
            if depth + 1 >= self.settings.rr_start {
                let q = throughput.max_element().min(0.95);
                if q <= 0.0 || rng.next_1d() >= q {
                    break;
                }
                throughput /= q;
            }
            origin = lifted;
            dir = l;
        }
        if let Some(t) = trail {
            t.finish();
        }
        rays
    }

    /// The radiance a bounce ray along `l` (sampled with density `pdf`) finds by
    /// reaching an emitter's front or the sky, weighted against next-event estimation.
    fn found_light(&self, l: Vec3, hit: Option<&Hit>, pdf: f32) -> Vec3 {
        match hit {
            None => {
                let pdf_light = self.sky_pdf(l);
                self.sky_radiance(l) * power_heuristic(pdf, pdf_light)
            }
            Some(h) => {
                let tri = &self.bvh.tris[h.tri as usize];
                let cos_light = tri.ng.dot(-l);
                let pdf_area = self.emitters.pdf_area(h.tri);
                if cos_light <= 0.0 || pdf_area <= 0.0 {
                    return Vec3::ZERO;
                }
                let pdf_light = pdf_area * h.t * h.t / cos_light;
                self.emitted(h) * power_heuristic(pdf, pdf_light)
            }
        }
    }

    /// The sky's radiance along world direction `d` (towards the sky).
    fn sky_radiance(&self, d: Vec3) -> Vec3 {
        self.environment.radiance(d, self.sky.as_deref())
    }

    /// The density per steradian with which next-event estimation picks sky direction `d`.
    fn sky_pdf(&self, d: Vec3) -> f32 {
        self.sky_distribution.as_ref().map_or(0.0, |s| s.pdf(self.environment.to_sky(d)))
    }

    /// The radiance the front of the surface at `hit` emits (emission colour x strength x
    /// texture); zero for materials that do not emit.
    fn emitted(&self, hit: &Hit) -> Vec3 {
        let tri = &self.bvh.tris[hit.tri as usize];
        let Some(m) = self.materials.get(tri.material as usize).filter(|m| m.emits()) else { return Vec3::ZERO };
        super::emitters::emission_at(m, &self.images, tri, hit.u, hit.v)
    }

    /// The light every light sends off the shading point towards its viewer by next-event
    /// estimation: each punctual light, one point on an emissive triangle and one sky direction
    /// (the last two weighted against BRDF sampling); counts the shadow rays in `rays`.
    fn next_event(&self, at: &ShadingPoint<'_>, rng: &mut impl Sampler, rays: &mut u64) -> Vec3 {
        let mut out = self.punctual(at, rays);
        if !self.emitters.is_empty() {
            out += self.emitter_sample(at, rng, rays);
        }
        if let Some(dist) = &self.sky_distribution {
            let (d, pdf) = dist.sample(rng.next_2d());
            let l = self.environment.to_world(d);
            if let Some(cos) = at.facing(l).filter(|_| pdf > 0.0) {
                *rays += 1;
                if !self.bvh.trace_occluded(at.lifted, l, f32::INFINITY) {
                    let w = power_heuristic(pdf, at.bounce_pdf(l));
                    out += at.surface.eval(at.v, l) * self.sky_radiance(l) * cos / pdf * w;
                }
            }
        }
        out
    }

    /// One point on an emissive triangle, its light weighted against BRDF sampling.
    fn emitter_sample(&self, at: &ShadingPoint<'_>, rng: &mut impl Sampler, rays: &mut u64) -> Vec3 {
        // The point on the triangle takes the pattern's first two dimensions, the pick the third.
        let [x, y, pick] = rng.next_3d();
        let Some(s) = self.emitters.sample(&self.bvh, [pick, x, y]) else {
            return Vec3::ZERO;
        };
        let to = s.p - at.lifted;
        let dist = to.length();
        if dist <= 0.0 {
            return Vec3::ZERO;
        }
        let l = to / dist;
        let cos_light = self.bvh.tris[s.tri as usize].ng.dot(-l);
        let Some(cos) = at.facing(l).filter(|_| cos_light > 0.0) else { return Vec3::ZERO };
        *rays += 1;
        if self.bvh.trace_occluded(at.lifted, l, dist * (1.0 - 1e-4)) {
            return Vec3::ZERO;
        }
        let pdf = s.pdf_area * dist * dist / cos_light;
        let hit = Hit { t: dist, tri: s.tri, u: s.u, v: s.v };
        let w = power_heuristic(pdf, at.bounce_pdf(l));
        at.surface.eval(at.v, l) * self.emitted(&hit) * cos / pdf * w
    }

    /// The light every punctual light sends off the shading point (a shadow ray each).
    fn punctual(&self, at: &ShadingPoint<'_>, rays: &mut u64) -> Vec3 {
        let mut out = Vec3::ZERO;
        for light in &self.lights {
            let (l, e) = light.incident(at.p);
            let Some(cos) = at.facing(l).filter(|_| e.max_element() > 0.0) else { continue };
            let dist = match light.kind {
                LightKind::Directional => f32::INFINITY,
                _ => (light.position - at.lifted).length(),
            };
            *rays += 1;
            if !self.bvh.trace_occluded(at.lifted, l, dist) {
                out += at.surface.eval(at.v, l) * e * cos;
            }
        }
        out
    }
}

/// A surface point being shaded: the point, its geometric normal, the point lifted off the
/// surface for shadow rays, the direction to its viewer and its BRDF.
struct ShadingPoint<'a> {
    p: Vec3,
    ng: Vec3,
    lifted: Vec3,
    v: Vec3,
    surface: &'a Surface,
    /// The guiding distribution of the point's cell, if one was learnt.
    guide: CellGuide<'a>,
}

impl ShadingPoint<'_> {
    /// The shading cosine towards light direction `l`, if `l` is above both the geometric and
    /// the shading normal (one-sided surfaces).
    fn facing(&self, l: Vec3) -> Option<f32> {
        let cos = self.surface.n.dot(l);
        (self.ng.dot(l) > 0.0 && cos > 0.0).then_some(cos)
    }

    /// The density with which [`sample_bounce`] picks `l`: the BRDF's, or its mixture with the
    /// guide's where the cell has one.
    fn bounce_pdf(&self, l: Vec3) -> f32 {
        let brdf = self.surface.pdf(self.v, l);
        match self.guide {
            Some(g) => GUIDE_SHARE * g.pdf(l) + (1.0 - GUIDE_SHARE) * brdf,
            None => brdf,
        }
    }
}

/// A bounce direction above the geometric and the shading normal, sampled from the BRDF or,
/// where the point's cell learnt a guide, from the one-sample mixture of the BRDF and the guide
/// (the choice number picks the strategy, then the lobe); with its density. `None` ends the path
/// (a direction below the surface carries no light).
fn sample_bounce(at: &ShadingPoint<'_>, rng: &mut impl Sampler) -> Option<(Vec3, f32)> {
    let [u0, u1, choice] = rng.next_3d();
    let l = match at.guide {
        Some(g) if choice < GUIDE_SHARE => g.sample(u0, u1),
        Some(_) => at.surface.sample(at.v, (u0, u1), (choice - GUIDE_SHARE) / (1.0 - GUIDE_SHARE))?,
        None => at.surface.sample(at.v, (u0, u1), choice)?,
    };
    if at.ng.dot(l) <= 0.0 || at.surface.n.dot(l) <= 0.0 {
        return None;
    }
    let pdf = at.bounce_pdf(l);
    (pdf > 0.0).then_some((l, pdf))
}

/// One path in this many trains the guide (the rest only use it): a quarter of the paths
/// learn about as well as all of them and cost a quarter as much (docs/notes/reference-tracer.md).
const TRAINING_STRIDE: u64 = 4;

/// Rows of a band while guiding trains.
const BAND_ROWS: usize = 32;

/// A path's bounces, for guiding's training: each bounce's estimate of the radiance arriving
/// along its direction is all the light the path gathers after it, over the throughput it had
/// just after it.
struct Trail<'a> {
    sink: &'a mut Sink,
    training: &'a Training,
    gathered: Vec3,
}

/// Where a row's paths leave their guiding records, with room for one path's bounces.
#[derive(Default)]
struct Sink {
    records: Vec<Record>,
    bounces: Vec<Bounce>,
}

/// A bounce of a [`Trail`].
struct Bounce {
    p: Vec3,
    ng: Vec3,
    l: Vec3,
    pdf: f32,
    throughput: Vec3,
    before: Vec3,
}

impl<'a> Trail<'a> {
    fn new(sink: &'a mut Sink, training: &'a Training) -> Self {
        sink.bounces.clear();
        Self { sink, training, gathered: Vec3::ZERO }
    }

    /// A bounce at `p` (normal `ng`) along `l` (density `pdf`); `throughput` is the path's just
    /// after it, `light` what the vertex sent before it.
    fn bounce(&mut self, p: Vec3, ng: Vec3, l: Vec3, pdf: f32, throughput: Vec3, light: Vec3) {
        self.sink.bounces.push(Bounce { p, ng, l, pdf, throughput, before: self.gathered + light });
    }

    /// A vertex's whole light, once visited.
    fn add(&mut self, light: Vec3) {
        self.gathered += light;
    }

    /// Hands over each bounce's record.
    fn finish(self) {
        let Sink { records, bounces } = self.sink;
        for b in bounces.iter() {
            let after = self.gathered - b.before;
            let incident = Vec3::select(b.throughput.cmpgt(Vec3::ZERO), after / b.throughput, Vec3::ZERO);
            records.push(self.training.record(b.p, b.ng, b.l, luminance(incident) / b.pdf));
        }
    }
}

/// A surface a path meets ([`PathTracer::walk`]).
#[derive(Clone, Copy, Debug)]
pub struct Vertex {
    /// 0 for the first surface (the one a camera ray shows).
    pub depth: u32,
    /// The point and its geometric normal.
    pub p: Vec3,
    pub ng: Vec3,
    /// The light this surface sends along the path to its origin.
    pub light: Vec3,
}
