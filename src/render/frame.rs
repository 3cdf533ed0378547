//! The frame: one function that runs the passes in order over typed resources.

use glam::Mat4;
use wgpu::util::DeviceExt as _;

use super::composite::CompositePass;
use super::emission::EmissionPass;
use super::gbuffer::GbufferPass;
use super::gi::inputs::{GiInputs, GpuLights, PyramidView};
use super::gi::registry::{self, Registry};
use super::gi::{ChangeDetector, GiOutput, Readiness, SupportQuery};
use super::layouts::Layouts;
use super::lighting::{LightingInputs, LightingPass};
use super::pyramid::ViewPyramid;
use super::readback::{self, ReadbackError};
use super::scene_gpu::SceneGpu;
use super::shaders::ShaderError;
use super::shadows::ShadowPass;
use super::targets::{Target, ViewTargets, formats};
use super::timing::{GpuTimer, PassTiming};
use super::tonemap::TonemapPass;
use super::uniforms::{FrameUniforms, GpuLight};
use crate::scene::Scene;
use crate::settings::{RenderSettings, SettingsError};

mod inspect;
mod techniques;
pub use techniques::area_light_shortfall;

/// Why a frame could not be rendered.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// A shader is missing from the build.
    #[error(transparent)]
    Shader(#[from] ShaderError),
    /// The GI mode is not available in this build or on this adapter.
    #[error("GI mode {mode:?} is not available: {reason}")]
    Unsupported { mode: &'static str, reason: String },
    /// A setting is out of range.
    #[error(transparent)]
    Settings(#[from] SettingsError),
    /// The requested size is empty or too large for the adapter.
    #[error("image size {0}x{1} is outside 1..={2} pixels per side")]
    Size(u32, u32, u32),
    /// wgpu reported a validation or out-of-memory error while recording the frame.
    #[error("GPU error: {0}")]
    Gpu(String),
    /// `--buffer` named a buffer that does not exist.
    #[error("unknown buffer {name:?}; available: {known}")]
    UnknownBuffer { name: String, known: String },
    /// Reading results back failed.
    #[error(transparent)]
    Readback(#[from] ReadbackError),
}

struct SizedResources {
    targets: ViewTargets,
    lighting_targets: wgpu::BindGroup,
    composite: wgpu::BindGroup,
    tonemap: wgpu::BindGroup,
    vo: super::obscurance::VoGroups,
}

/// What one frame renders.
struct FrameRequest<'a> {
    scene: &'a Scene,
    settings: &'a RenderSettings,
    size: (u32, u32),
}

/// What the recording stages of one frame share.
struct FramePlan<'a> {
    scene: &'a Scene,
    settings: &'a RenderSettings,
    size: (u32, u32),
    /// The packed lights of this frame.
    lights: &'a [GpuLight],
    /// This frame's constants.
    frame: &'a FrameUniforms,
    needs: FrameNeeds,
}

/// The shared inputs this frame's technique asked for.
#[derive(Clone, Copy)]
struct FrameNeeds {
    /// The technique reads the depth/normal pyramid.
    pyramid: bool,
    /// The pyramid is recorded (for the technique or for the inspector).
    wants_pyramid: bool,
}

/// Owns every pipeline and per-view resource; long-lived.
pub struct Renderer {
    device: wgpu::Device,
    queue: wgpu::Queue,
    layouts: Layouts,
    gbuffer: GbufferPass,
    emission: EmissionPass,
    /// The environment's uniforms and image.
    sky: super::sky::SkyGpu,
    shadows: ShadowPass,
    lighting: LightingPass,
    composite: CompositePass,
    /// Volumetric obscurance on the indirect term.
    vo: super::obscurance::VoPass,
    tonemap: TonemapPass,
    pyramid: ViewPyramid,
    frame_buffer: wgpu::Buffer,
    frame_bind_group: wgpu::BindGroup,
    lights_buffer: wgpu::Buffer,
    shadow_views_buffer: wgpu::Buffer,
    lighting_inputs: Option<(u64, wgpu::BindGroup)>,
    inputs_generation: u64,
    scene_gpu: Option<SceneGpu>,
    sized: Option<SizedResources>,
    /// The previous frame's final HDR image, kept while the active technique needs it.
    previous: Option<Target>,
    timer: GpuTimer,
    /// Every GI technique created so far and the active one.
    techniques: Registry,
    /// Turns edits into the techniques' reset reasons.
    changes: ChangeDetector,
    /// The inspected buffer (techniques keep debug copies only while shown).
    inspected: Option<String>,
    /// What the active technique wrote last frame, and whether it was ready.
    output: GiOutput,
    readiness: Readiness,
    prev_clip_from_world: Option<Mat4>,
    frame_index: u32,
}

fn storage_buffer(device: &wgpu::Device, label: &str, bytes: &[u8]) -> wgpu::Buffer {
    device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some(label),
        contents: bytes,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
    })
}

impl Renderer {
    /// Creates every pipeline (fails only if a shader is missing; validation errors surface
    /// through wgpu's error handler).
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue) -> Result<Self, RenderError> {
        let layouts = Layouts::new(device);
        let frame_buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("frame uniforms"),
            size: std::mem::size_of::<FrameUniforms>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let frame_bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("frame bind group"),
            layout: &layouts.frame,
            entries: &[wgpu::BindGroupEntry { binding: 0, resource: frame_buffer.as_entire_binding() }],
        });
        Ok(Self {
            gbuffer: GbufferPass::new(device, &layouts)?,
            emission: EmissionPass::new(device, &layouts)?,
            sky: super::sky::SkyGpu::new(device),
            shadows: ShadowPass::new(device, &layouts)?,
            lighting: LightingPass::new(device)?,
            composite: CompositePass::new(device)?,
            vo: super::obscurance::VoPass::new(device)?,
            tonemap: TonemapPass::new(device)?,
            pyramid: ViewPyramid::new(device)?,
            lights_buffer: storage_buffer(device, "lights", bytemuck::bytes_of(&GpuLight::default())),
            shadow_views_buffer: storage_buffer(
                device,
                "shadow views",
                bytemuck::bytes_of(&Mat4::IDENTITY.to_cols_array()),
            ),
            lighting_inputs: None,
            inputs_generation: 0,
            frame_buffer,
            frame_bind_group,
            layouts,
            scene_gpu: None,
            sized: None,
            previous: None,
            timer: GpuTimer::new(device, queue),
            techniques: Registry::default(),
            changes: ChangeDetector::default(),
            inspected: None,
            output: GiOutput::Nothing,
            readiness: Readiness::Ready,
            prev_clip_from_world: None,
            frame_index: 0,
            device: device.clone(),
            queue: queue.clone(),
        })
    }

    /// Whether `mode` can run on this device with `settings` at `size`; the error is a
    /// sentence a user can act on (the editor greys the mode out with it).
    pub fn support(&self, settings: &RenderSettings, size: (u32, u32)) -> Result<(), String> {
        let limits = self.device.limits();
        let query = SupportQuery { limits: &limits, features: self.device.features(), size, settings };
        registry::support(settings.mode, &query)
    }

    /// Renders one frame of `scene` at `size` into the view targets (HDR and display image).
    pub fn render(&mut self, scene: &Scene, settings: &RenderSettings, size: (u32, u32)) -> Result<(), RenderError> {
        self.render_then(scene, settings, size, &mut |_, _| {})
    }

    /// [`Renderer::render`], with `then` recording more commands (a readback copy) into the
    /// frame's own command buffer. One submission per frame: on lavapipe a second submission
    /// blocks the caller until the first has finished on the GPU (measured: 6.4 s after a GI
    /// frame at 1000x760), which would stall the editor's interface.
    pub fn render_then(
        &mut self,
        scene: &Scene,
        settings: &RenderSettings,
        size: (u32, u32),
        then: &mut dyn FnMut(&mut wgpu::CommandEncoder, &ViewTargets),
    ) -> Result<(), RenderError> {
        let validation = self.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let memory = self.device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
        let result = self.render_inner(FrameRequest { scene, settings, size }, then);
        let oom = pollster::block_on(memory.pop());
        let invalid = pollster::block_on(validation.pop());
        let failed = oom.or(invalid);
        if result.is_err() || failed.is_some() {
            // The frame's shadow layers may not have been drawn: draw them all again.
            self.shadows.invalidate();
        }
        result?;
        match failed {
            Some(e) => Err(RenderError::Gpu(e.to_string())),
            None => Ok(()),
        }
    }

    /// The frame in stages: check the request, bring the scene and lights to the GPU, prepare
    /// the technique, then record and submit G-buffer -> shadow maps -> direct light ->
    /// [pyramid] -> GI -> [obscurance] -> composite -> tonemap.
    fn render_inner(
        &mut self,
        request: FrameRequest<'_>,
        then: &mut dyn FnMut(&mut wgpu::CommandEncoder, &ViewTargets),
    ) -> Result<(), RenderError> {
        let FrameRequest { scene, settings, size } = request;
        self.check_request(settings, size)?;
        self.ensure_size(size);
        self.sync_scene(scene);
        // Shadow layers, packed lights and frame constants.
        let assignment = self.shadows.prepare(&self.device, scene, &settings.shadows);
        self.upload_lights(&assignment.lights);
        let frame = self.write_frame_uniforms(scene, settings, size, assignment.lights.len() as u32);
        let needs = self.prepare_technique(scene, settings, size)?;
        if self.scene_gpu.is_none() || self.sized.is_none() {
            return Ok(());
        }
        self.ensure_lighting_inputs();
        let plan = FramePlan { scene, settings, size, lights: &assignment.lights, frame: &frame, needs };
        self.record_frame(&plan, then)
    }

    /// Settings in range, a size the adapter can hold, a mode this adapter supports.
    fn check_request(&self, settings: &RenderSettings, size: (u32, u32)) -> Result<(), RenderError> {
        settings.validate()?;
        let max = self.device.limits().max_texture_dimension_2d;
        if size.0 == 0 || size.1 == 0 || size.0 > max || size.1 > max {
            return Err(RenderError::Size(size.0, size.1, max));
        }
        self.support(settings, size).map_err(|reason| RenderError::Unsupported { mode: settings.mode.name(), reason })
    }

    /// Uploads the scene the first time, and what changed since the last frame after that.
    fn sync_scene(&mut self, scene: &Scene) {
        let (device, queue) = (&self.device.clone(), &self.queue.clone());
        match &mut self.scene_gpu {
            Some(gpu) => gpu.sync(device, queue, &self.layouts, scene),
            None => self.scene_gpu = Some(SceneGpu::new(device, queue, &self.layouts, scene)),
        }
        self.sky.sync(device, queue, scene);
    }

    /// Writes this frame's constants (camera, previous camera, size, light and shadow counts)
    /// and advances the frame index.
    fn write_frame_uniforms(
        &mut self,
        scene: &Scene,
        settings: &RenderSettings,
        size: (u32, u32),
        light_count: u32,
    ) -> FrameUniforms {
        let camera = scene.camera();
        let clip_from_world = camera.clip_from_view(size.0 as f32 / size.1 as f32) * camera.view_from_world();
        let prev = self.prev_clip_from_world.unwrap_or(clip_from_world);
        let res = self.shadows.resolution() as f32;
        let frame = FrameUniforms {
            clip_from_world: clip_from_world.to_cols_array_2d(),
            world_from_clip: clip_from_world.inverse().to_cols_array_2d(),
            prev_clip_from_world: prev.to_cols_array_2d(),
            camera_position: camera.position.extend(1.0).to_array(),
            size: [size.0 as f32, size.1 as f32, 1.0 / size.0 as f32, 1.0 / size.1 as f32],
            params: [
                light_count,
                self.frame_index,
                settings.shadows.pcf_radius,
                self.shadows.layer_matrices.len() as u32,
            ],
            shadow: [settings.shadows.normal_bias_texels, res, 1.0 / res, 0.0],
        };
        self.queue.write_buffer(&self.frame_buffer, 0, bytemuck::bytes_of(&frame));
        self.prev_clip_from_world = Some(clip_from_world);
        self.frame_index = self.frame_index.wrapping_add(1);
        frame
    }

    /// The active technique: created on first use, told what changed, prepared on the CPU; the
    /// shared inputs it needs (the pyramid, the previous frame) kept or freed.
    fn prepare_technique(
        &mut self,
        scene: &Scene,
        settings: &RenderSettings,
        size: (u32, u32),
    ) -> Result<FrameNeeds, RenderError> {
        let reasons = self.changes.detect(scene, settings, size);
        let device = &self.device.clone();
        let technique = self.techniques.activate(settings.mode, device, &self.layouts)?;
        for reason in reasons {
            technique.reset(reason);
        }
        technique.set_inspected(self.inspected.as_deref());
        self.readiness = technique.prepare(scene, settings, size);
        let needs = technique.needs();
        let wants_pyramid = needs.pyramid || self.inspected.as_deref().is_some_and(|n| n.starts_with("pyramid_"));
        if !wants_pyramid {
            self.pyramid.release();
        }
        if !needs.previous_frame {
            self.previous = None;
        } else if self.previous.as_ref().is_none_or(|p| p.texture.width() != size.0 || p.texture.height() != size.1) {
            use wgpu::TextureUsages as U;
            let usage = U::TEXTURE_BINDING | U::COPY_DST | U::COPY_SRC;
            self.previous = Some(Target::new(device, "previous frame radiance", size, formats::HDR, usage));
        }
        Ok(FrameNeeds { pyramid: needs.pyramid, wants_pyramid })
    }

    /// The direct-lighting pass's inputs (frame, lights, shadow maps), rebuilt when one of them
    /// was replaced.
    fn ensure_lighting_inputs(&mut self) {
        let generation = (self.shadows.generation * 1_000_003 + self.inputs_generation) * 1_009 + self.sky.generation;
        if self.lighting_inputs.as_ref().is_none_or(|(g, _)| *g != generation) {
            let inputs = LightingInputs {
                frame: &self.frame_buffer,
                lights: &self.lights_buffer,
                shadow_views: &self.shadow_views_buffer,
                shadow_maps: &self.shadows.array_view,
                sky: &self.sky,
            };
            self.lighting_inputs = Some((generation, self.lighting.inputs_bind_group(&self.device, &inputs)));
        }
    }

    /// Records the frame into one command buffer (`then` adds its own commands last) and
    /// submits it.
    fn record_frame(
        &mut self,
        plan: &FramePlan<'_>,
        then: &mut dyn FnMut(&mut wgpu::CommandEncoder, &ViewTargets),
    ) -> Result<(), RenderError> {
        let mut encoder =
            self.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("frame encoder") });
        self.timer.begin_frame();
        self.record_direct(&mut encoder, plan);
        self.output = self.record_gi(&mut encoder, plan)?;
        self.record_post(&mut encoder, plan);
        if let Some(sized) = &self.sized {
            then(&mut encoder, &sized.targets);
        }
        self.timer.resolve(&mut encoder);
        self.queue.submit([encoder.finish()]);
        self.shadows.submitted();
        self.timer.after_submit();
        Ok(())
    }

    /// G-buffer, shadow maps, direct light and (when wanted) the depth/normal pyramid.
    fn record_direct(&mut self, encoder: &mut wgpu::CommandEncoder, plan: &FramePlan<'_>) {
        let (Some(gpu), Some(sized), Some((_, lighting_inputs))) =
            (&self.scene_gpu, &self.sized, &self.lighting_inputs)
        else {
            return;
        };
        let (device, queue) = (&self.device, &self.queue);
        self.gbuffer.record(
            encoder,
            &sized.targets,
            &self.frame_bind_group,
            gpu,
            self.timer.scope("gbuffer").map(|t| t.render_writes(true, true)),
        );
        let emission_ts = if gpu.has_emissive() { self.timer.scope("emission") } else { None };
        self.emission.record(
            encoder,
            &sized.targets,
            &self.frame_bind_group,
            gpu,
            emission_ts.map(|t| t.render_writes(true, true)),
        );
        let stale = self.shadows.stale_layers(gpu);
        let shadow_ts = if stale.is_empty() { None } else { self.timer.scope("shadows") };
        self.shadows.record(device, queue, encoder, gpu, &stale, shadow_ts);
        self.lighting.record(
            encoder,
            lighting_inputs,
            &sized.lighting_targets,
            plan.size,
            self.timer.scope("lighting").map(|t| t.compute_writes()),
        );
        if plan.needs.wants_pyramid {
            let ts = self.timer.scope("pyramid");
            self.pyramid.record(device, encoder, &self.frame_buffer, &sized.targets, ts);
        }
    }

    /// The active technique's passes when it is ready (nothing while it prepares on the CPU).
    fn record_gi(&mut self, encoder: &mut wgpu::CommandEncoder, plan: &FramePlan<'_>) -> Result<GiOutput, RenderError> {
        let settings = plan.settings;
        let technique = self.techniques.active_mut().ok_or_else(|| RenderError::Unsupported {
            mode: settings.mode.name(),
            reason: "no active technique".into(),
        })?;
        let (Readiness::Ready, Some(gpu), Some(sized)) = (&self.readiness, &self.scene_gpu, &self.sized) else {
            return Ok(GiOutput::Nothing);
        };
        let mut inputs = GiInputs {
            device: &self.device,
            queue: &self.queue,
            encoder,
            scene: plan.scene,
            scene_gpu: gpu,
            layouts: &self.layouts,
            mode: settings.mode,
            settings,
            frame_buffer: &self.frame_buffer,
            frame: plan.frame,
            lights: GpuLights {
                packed: plan.lights,
                buffer: &self.lights_buffer,
                shadow_views: &self.shadow_views_buffer,
                shadow_maps: &self.shadows.array_view,
                shadow_matrices: &self.shadows.layer_matrices,
            },
            targets: &sized.targets,
            previous: self.previous.as_ref(),
            pyramid: self.pyramid.levels().filter(|_| plan.needs.pyramid).map(|levels| PyramidView { levels }),
            frame_index: self.frame_index,
            timer: &mut self.timer,
            sky: &self.sky,
        };
        technique.render(&mut inputs)
    }

    /// After the technique: an empty indirect term cleared (the inspector stays honest),
    /// obscurance where it applies, composite, tonemap, and the previous frame kept when a
    /// technique reprojects it.
    fn record_post(&mut self, encoder: &mut wgpu::CommandEncoder, plan: &FramePlan<'_>) {
        let Some(sized) = &self.sized else { return };
        let (settings, size) = (plan.settings, plan.size);
        if self.output == GiOutput::Nothing {
            // Keep the inspector honest: nothing was written, so `indirect` shows black.
            clear(encoder, &sized.targets.indirect.view);
        }
        let obscurance = self.output != GiOutput::Nothing
            && self.output != GiOutput::Complete
            && registry::obscurance_applies(settings.mode, &settings.vo);
        if obscurance {
            self.vo.set(&self.queue, &settings.vo);
            self.vo.record(encoder, &sized.vo, &mut self.timer);
        }
        let ts = self.timer.scope("composite");
        let what = super::composite::Composite { output: self.output, obscurance };
        self.composite.record(&self.queue, encoder, &sized.composite, what, size, ts);
        self.tonemap.record(&self.queue, encoder, &sized.tonemap, &settings.view, size, self.timer.scope("tonemap"));
        if let Some(previous) = &self.previous {
            encoder.copy_texture_to_texture(
                sized.targets.hdr.texture.as_image_copy(),
                previous.texture.as_image_copy(),
                previous.texture.size(),
            );
        }
    }

    fn ensure_size(&mut self, size: (u32, u32)) {
        if self.sized.as_ref().is_some_and(|s| s.targets.size == size) {
            return;
        }
        let targets = ViewTargets::new(&self.device, size);
        let lighting_targets = self.lighting.targets_bind_group(&self.device, &targets);
        let composite = self.composite.bind_group(&self.device, &self.frame_buffer, &targets);
        let tonemap = self.tonemap.bind_group(&self.device, &targets.hdr.view, &targets.ldr.view);
        let vo = self.vo.bind_groups(&self.device, &self.frame_buffer, &targets);
        self.sized = Some(SizedResources { targets, lighting_targets, composite, tonemap, vo });
        self.prev_clip_from_world = None;
    }

    fn upload_lights(&mut self, lights: &[GpuLight]) {
        let empty = [GpuLight::default()];
        let light_bytes: &[u8] = bytemuck::cast_slice(if lights.is_empty() { &empty } else { lights });
        let views: Vec<[f32; 16]> = self.shadows.layer_matrices.iter().map(Mat4::to_cols_array).collect();
        let view_bytes: Vec<u8> = if views.is_empty() {
            bytemuck::bytes_of(&Mat4::IDENTITY.to_cols_array()).to_vec()
        } else {
            bytemuck::cast_slice(&views).to_vec()
        };
        if self.lights_buffer.size() < light_bytes.len() as u64 {
            self.lights_buffer =
                storage_buffer(&self.device, "lights", &vec![0u8; light_bytes.len().next_power_of_two()]);
            self.inputs_generation += 1;
        }
        if self.shadow_views_buffer.size() < view_bytes.len() as u64 {
            self.shadow_views_buffer =
                storage_buffer(&self.device, "shadow views", &vec![0u8; view_bytes.len().next_power_of_two()]);
            self.inputs_generation += 1;
        }
        self.queue.write_buffer(&self.lights_buffer, 0, light_bytes);
        self.queue.write_buffer(&self.shadow_views_buffer, 0, &view_bytes);
    }

    /// Whether the last frame's technique was ready, or still preparing on the CPU (a bake, a
    /// precompute): the frame then showed direct light.
    pub fn readiness(&self) -> &Readiness {
        &self.readiness
    }

    /// The current view targets (after the first render).
    pub fn targets(&self) -> Option<&ViewTargets> {
        self.sized.as_ref().map(|s| &s.targets)
    }

    /// Latest per-pass GPU timings (`wait` blocks until this frame's are in).
    pub fn timings(&mut self, wait: bool) -> Vec<PassTiming> {
        self.timer.collect(&self.device, wait).to_vec()
    }

    /// The latest collected frame's timings with every piece of a pass recorded in pieces apart
    /// (after [`Self::timings`]; what a trace shows).
    pub fn timing_pieces(&self) -> Vec<PassTiming> {
        self.timer.pieces().to_vec()
    }

    /// How many shadow-map layers the last frame drew; the others kept their depth from an
    /// earlier frame (nothing they depend on had changed: `shadows.rs`).
    pub fn shadow_layers_drawn(&self) -> usize {
        self.shadows.last_drawn
    }

    /// Makes every shadow-map layer stale, so the next frame draws them all (what a frame after
    /// an object moved costs; the profile measures it).
    pub fn invalidate_shadow_maps(&mut self) {
        self.shadows.invalidate();
    }

    /// Whether per-pass GPU timings are measured.
    pub fn has_gpu_timings(&self) -> bool {
        self.timer.enabled()
    }

    /// Reads the linear HDR radiance of the last frame (row-major RGBA).
    pub fn read_hdr(&self) -> Result<Vec<[f32; 4]>, RenderError> {
        let t = self.targets().ok_or(RenderError::Size(0, 0, 0))?;
        Ok(readback::read_rgba32f(&self.device, &self.queue, &t.hdr.texture)?)
    }

    /// Blocks until the GPU has finished every frame submitted so far.
    pub fn wait_for_gpu(&self) -> Result<(), RenderError> {
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map(|_| ())
            .map_err(|e| RenderError::Gpu(format!("waiting for the GPU: {e}")))
    }

    /// Reads the tonemapped display image of the last frame (RGBA8, sRGB-encoded).
    pub fn read_ldr(&self) -> Result<Vec<u8>, RenderError> {
        let t = self.targets().ok_or(RenderError::Size(0, 0, 0))?;
        Ok(readback::read_texture(&self.device, &self.queue, &t.ldr.texture)?)
    }

    /// Forgets temporal state: motion vectors restart from zero and the active technique
    /// drops its history as for a camera cut.
    pub fn reset_history(&mut self) {
        self.prev_clip_from_world = None;
        if let Some(gpu) = &mut self.scene_gpu {
            gpu.reset_motion();
        }
        if let Some(t) = self.techniques.active_mut() {
            t.reset(super::gi::ResetReason::CameraCut);
        }
    }

    /// Frames rendered so far (temporal techniques seed from it).
    pub fn frame_index(&self) -> u32 {
        self.frame_index
    }

    /// Sets the frame counter every random sequence of the temporal techniques seeds from: a
    /// renderer started at another index draws another realization of the same estimators
    /// (`probe --seed`, to tell a change from the spread between realizations).
    pub fn set_frame_index(&mut self, index: u32) {
        self.frame_index = index;
    }
}

fn clear(encoder: &mut wgpu::CommandEncoder, view: &wgpu::TextureView) {
    encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some("clear indirect"),
        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
            view,
            depth_slice: None,
            resolve_target: None,
            ops: wgpu::Operations { load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT), store: wgpu::StoreOp::Store },
        })],
        depth_stencil_attachment: None,
        timestamp_writes: None,
        occlusion_query_set: None,
        multiview_mask: None,
    });
}
