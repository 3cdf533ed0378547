//! The frame: one function that runs the passes in order over typed resources.

use glam::Mat4;
use wgpu::util::DeviceExt as _;

use super::gbuffer::GbufferPass;
use super::layouts::Layouts;
use super::lighting::{LightingInputs, LightingPass};
use super::readback::{self, ReadbackError};
use super::scene_gpu::SceneGpu;
use super::shaders::ShaderError;
use super::shadows::ShadowPass;
use super::targets::ViewTargets;
use super::timing::{GpuTimer, PassTiming};
use super::tonemap::TonemapPass;
use super::uniforms::{FrameUniforms, GpuLight};
use crate::scene::Scene;
use crate::settings::{GiMode, RenderSettings, SettingsError};

mod inspect;
mod ism_points;

use ism_points::{mean_linear_colour, point_data, point_data_key};

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

/// What the ISM sample-point distribution depends on.
#[derive(Clone, Debug, PartialEq)]
struct IsmPointsKey {
    resources: u64,
    total: u32,
    objects: Vec<(f32, bool, [f32; 3])>,
}

/// Read-back results of the ISM VPL generation.
#[derive(Clone, Debug)]
pub struct IsmVpls {
    /// The generated VPLs.
    pub vpls: Vec<super::gi::ism::vpl_pass::GpuVpl>,
    /// Importance per light-G-buffer texel (mip 0), row-major.
    pub importance: Vec<f32>,
    /// Reflected power (rgb) and importance (a) per texel.
    pub power: Vec<[f32; 4]>,
}

struct SizedResources {
    targets: ViewTargets,
    lighting_targets: wgpu::BindGroup,
    tonemap: wgpu::BindGroup,
}

/// Owns every pipeline and per-view resource; long-lived.
pub struct Renderer {
    device: wgpu::Device,
    queue: wgpu::Queue,
    layouts: Layouts,
    gbuffer: GbufferPass,
    shadows: ShadowPass,
    lighting: LightingPass,
    tonemap: TonemapPass,
    frame_buffer: wgpu::Buffer,
    frame_bind_group: wgpu::BindGroup,
    lights_buffer: wgpu::Buffer,
    shadow_views_buffer: wgpu::Buffer,
    lighting_inputs: Option<(u64, wgpu::BindGroup)>,
    inputs_generation: u64,
    scene_gpu: Option<SceneGpu>,
    sized: Option<SizedResources>,
    timer: GpuTimer,
    vpl_pass: Option<super::gi::ism::vpl_pass::VplPass>,
    last_mode: Option<GiMode>,
    gather: Option<super::gi::ism::gather::IsmGather>,
    /// ISM sample points and the mean linear colour of each scene image (the points' albedo
    /// texture term), both rebuilt only when their key changes, never per frame.
    ism_points: Option<(IsmPointsKey, crate::precompute::sample_points::SamplePoints, Vec<[f32; 3]>)>,
    /// Bumped whenever `ism_points` is rebuilt.
    ism_points_generation: u64,
    /// What the point data on the GPU was built from: (gather buffer generation, point set
    /// generation, [`point_data_key`]); the upload is skipped while it stays equal.
    ism_uploaded: Option<(u64, u64, Vec<u32>)>,
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
            shadows: ShadowPass::new(device)?,
            lighting: LightingPass::new(device)?,
            tonemap: TonemapPass::new(device)?,
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
            timer: GpuTimer::new(device, queue),
            vpl_pass: None,
            last_mode: None,
            gather: None,
            ism_points: None,
            ism_points_generation: 0,
            ism_uploaded: None,
            prev_clip_from_world: None,
            frame_index: 0,
            device: device.clone(),
            queue: queue.clone(),
        })
    }

    /// The modes this renderer can draw now.
    pub fn supports(mode: GiMode) -> Result<(), String> {
        match mode {
            GiMode::Direct | GiMode::Ism | GiMode::IsmRitschel => Ok(()),
            other => Err(format!("{} is not implemented yet in this build", other.name())),
        }
    }

    /// Renders one frame of `scene` at `size` into the view targets (HDR and display image).
    pub fn render(&mut self, scene: &Scene, settings: &RenderSettings, size: (u32, u32)) -> Result<(), RenderError> {
        let validation = self.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let memory = self.device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
        let result = self.render_inner(scene, settings, size);
        let oom = pollster::block_on(memory.pop());
        let invalid = pollster::block_on(validation.pop());
        result?;
        match oom.or(invalid) {
            Some(e) => Err(RenderError::Gpu(e.to_string())),
            None => Ok(()),
        }
    }

    fn render_inner(&mut self, scene: &Scene, settings: &RenderSettings, size: (u32, u32)) -> Result<(), RenderError> {
        settings.validate()?;
        Self::supports(settings.mode)
            .map_err(|reason| RenderError::Unsupported { mode: settings.mode.name(), reason })?;
        let max = self.device.limits().max_texture_dimension_2d;
        if size.0 == 0 || size.1 == 0 || size.0 > max || size.1 > max {
            return Err(RenderError::Size(size.0, size.1, max));
        }
        let ism = matches!(settings.mode, GiMode::Ism | GiMode::IsmRitschel);
        if ism && settings.ism.sh_filter {
            // 56 bytes per pixel of SH coefficients in one storage binding.
            let split = super::gi::ism::screen::split_size(size, settings.ism.interleave);
            let bytes = super::gi::ism::sh_filter::ShFilter::raw_bytes(split);
            let limits = self.device.limits();
            let limit = limits.max_storage_buffer_binding_size.min(limits.max_buffer_size);
            if bytes > limit {
                return Err(RenderError::Unsupported {
                    mode: settings.mode.name(),
                    reason: format!(
                        "the SH filter needs {} MiB of coefficients at {}x{}, this adapter binds at most {} MiB; \
                         lower the resolution or turn the SH filter off",
                        bytes >> 20,
                        size.0,
                        size.1,
                        limit >> 20
                    ),
                });
            }
        }
        self.ensure_size(size);
        let (device, queue) = (&self.device.clone(), &self.queue.clone());
        match &mut self.scene_gpu {
            Some(gpu) => gpu.sync(device, queue, &self.layouts, scene),
            None => self.scene_gpu = Some(SceneGpu::new(device, queue, &self.layouts, scene)),
        }

        // Shadow layers, packed lights and frame constants.
        let assignment = self.shadows.prepare(device, scene, &settings.shadows);
        self.upload_lights(&assignment.lights);
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
                assignment.lights.len() as u32,
                self.frame_index,
                settings.shadows.pcf_radius,
                self.shadows.layer_matrices.len() as u32,
            ],
            shadow: [settings.shadows.normal_bias_texels, res, 1.0 / res, 0.0],
            // The SH filter shades with the full BRDF: `indirect` is outgoing radiance.
            gi: [
                u32::from(matches!(settings.mode, GiMode::Ism | GiMode::IsmRitschel) && settings.ism.sh_filter),
                0,
                0,
                0,
            ],
        };
        queue.write_buffer(&self.frame_buffer, 0, bytemuck::bytes_of(&frame));
        self.prev_clip_from_world = Some(clip_from_world);
        self.frame_index = self.frame_index.wrapping_add(1);

        if self.last_mode != Some(settings.mode) {
            if let Some(g) = &mut self.gather {
                g.screen.reset_history();
            }
            self.last_mode = Some(settings.mode);
        }
        // The brightest spot or point light feeds the VPLs.
        let spot = scene
            .lights()
            .iter()
            .enumerate()
            .filter(|(_, l)| !matches!(l.kind, crate::scene::LightKind::Directional))
            .max_by(|a, b| a.1.intensity.total_cmp(&b.1.intensity))
            .map(|(i, _)| i);
        if ism {
            if self.vpl_pass.is_none() {
                self.vpl_pass = Some(super::gi::ism::vpl_pass::VplPass::new(device, &self.layouts)?);
            }
            if self.gather.is_none() {
                self.gather = Some(super::gi::ism::gather::IsmGather::new(device)?);
            }
            self.update_ism_points(scene, &settings.ism);
        }
        let (Some(gpu), Some(sized)) = (&self.scene_gpu, &self.sized) else {
            return Ok(());
        };
        let generation = self.shadows.generation * 1_000_003 + self.inputs_generation;
        if self.lighting_inputs.as_ref().is_none_or(|(g, _)| *g != generation) {
            let inputs = LightingInputs {
                frame: &self.frame_buffer,
                lights: &self.lights_buffer,
                shadow_views: &self.shadow_views_buffer,
                shadow_maps: &self.shadows.array_view,
            };
            self.lighting_inputs = Some((generation, self.lighting.inputs_bind_group(device, &inputs)));
        }
        let Some((_, lighting_inputs)) = &self.lighting_inputs else {
            return Ok(());
        };

        let mut encoder =
            device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("frame encoder") });
        self.timer.begin_frame();
        self.gbuffer.record(
            &mut encoder,
            &sized.targets,
            &self.frame_bind_group,
            scene,
            gpu,
            self.timer.scope("gbuffer").map(|t| t.render_writes(true, true)),
        );
        let shadow_ts = if self.shadows.layer_matrices.is_empty() { None } else { self.timer.scope("shadows") };
        self.shadows.record(device, queue, &mut encoder, scene, gpu, shadow_ts);
        // The active GI technique writes `targets.indirect` here; `direct` leaves it black.
        let mut wrote_indirect = false;
        if let (true, Some(light), Some(vpl_pass), Some(gather), Some((_, points, means))) =
            (ism, spot, self.vpl_pass.as_mut(), self.gather.as_mut(), self.ism_points.as_ref())
        {
            let frame = self.frame_index;
            if vpl_pass.record(
                device,
                queue,
                &mut encoder,
                scene,
                gpu,
                light,
                &settings.ism,
                frame,
                self.timer.scope("ism vpls"),
            ) {
                let buffers = gather.prepare(device, &settings.ism, points.points.len() as u32);
                let current = (buffers, self.ism_points_generation, point_data_key(scene));
                if self.ism_uploaded.as_ref() != Some(&current) {
                    gather.upload_points(queue, &point_data(scene, points, means));
                    self.ism_uploaded = Some(current);
                }
                let area = points.weighted_area.iter().sum::<f64>() as f32;
                let diameter = 2.0 * scene.bounds().map_or(1.0, |b| b.radius());
                gather.record_maps(
                    queue,
                    &mut encoder,
                    &vpl_pass.vpls,
                    area,
                    diameter,
                    &settings.ism,
                    self.timer.scope("ism maps"),
                );
                gather.record_screen(
                    device,
                    queue,
                    &mut encoder,
                    &self.frame_buffer,
                    &sized.targets,
                    diameter,
                    &settings.ism,
                    settings.mode == GiMode::Ism,
                    settings.view.exposure_ev.exp2(),
                    self.timer.scope("ism shade"),
                );
                wrote_indirect = true;
            }
        }
        if !wrote_indirect {
            clear(&mut encoder, &sized.targets.indirect.view);
        }
        self.lighting.record(
            &mut encoder,
            lighting_inputs,
            &sized.lighting_targets,
            size,
            self.timer.scope("lighting"),
        );
        self.tonemap.record(queue, &mut encoder, &sized.tonemap, &settings.view, size, self.timer.scope("tonemap"));
        self.timer.resolve(&mut encoder);
        queue.submit([encoder.finish()]);
        self.timer.after_submit();
        Ok(())
    }

    fn update_ism_points(&mut self, scene: &Scene, ism: &crate::settings::IsmSettings) {
        let key = IsmPointsKey {
            resources: scene.resources_revision(),
            total: ism.total_points,
            objects: scene
                .objects()
                .iter()
                .map(|o| (o.sampling_weight, o.is_rendered(), o.transform.scale.to_array()))
                .collect(),
        };
        if self.ism_points.as_ref().is_none_or(|(k, _, _)| *k != key) {
            let points = crate::precompute::sample_points::distribute(scene, ism.total_points as usize, 1);
            let means = scene.resources().images.iter().map(mean_linear_colour).collect();
            self.ism_points = Some((key, points, means));
            self.ism_points_generation += 1;
        }
    }

    fn ensure_size(&mut self, size: (u32, u32)) {
        if self.sized.as_ref().is_some_and(|s| s.targets.size == size) {
            return;
        }
        let targets = ViewTargets::new(&self.device, size);
        let lighting_targets = self.lighting.targets_bind_group(&self.device, &targets);
        let tonemap = self.tonemap.bind_group(&self.device, &targets.hdr.view, &targets.ldr.view);
        self.sized = Some(SizedResources { targets, lighting_targets, tonemap });
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

    /// The current view targets (after the first render).
    pub fn targets(&self) -> Option<&ViewTargets> {
        self.sized.as_ref().map(|s| &s.targets)
    }

    /// Latest per-pass GPU timings (`wait` blocks until this frame's are in).
    pub fn timings(&mut self, wait: bool) -> Vec<PassTiming> {
        self.timer.collect(&self.device, wait).to_vec()
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

    /// Reads the tonemapped display image of the last frame (RGBA8, sRGB-encoded).
    pub fn read_ldr(&self) -> Result<Vec<u8>, RenderError> {
        let t = self.targets().ok_or(RenderError::Size(0, 0, 0))?;
        Ok(readback::read_texture(&self.device, &self.queue, &t.ldr.texture)?)
    }

    /// Runs the ISM light G-buffer, importance pyramid and VPL generation for spot light
    /// `light` at `frame`, and reads the results back (tests and the inspector use this while
    /// the `ism` mode is being built).
    pub fn ism_vpls(
        &mut self,
        scene: &Scene,
        settings: &crate::settings::IsmSettings,
        light: usize,
        frame: u32,
    ) -> Result<IsmVpls, RenderError> {
        let (device, queue) = (self.device.clone(), self.queue.clone());
        match &mut self.scene_gpu {
            Some(gpu) => gpu.sync(&device, &queue, &self.layouts, scene),
            None => self.scene_gpu = Some(SceneGpu::new(&device, &queue, &self.layouts, scene)),
        }
        if self.vpl_pass.is_none() {
            self.vpl_pass = Some(super::gi::ism::vpl_pass::VplPass::new(&device, &self.layouts)?);
        }
        let (Some(gpu), Some(pass)) = (&self.scene_gpu, &mut self.vpl_pass) else {
            return Err(RenderError::Size(0, 0, 0));
        };
        let mut encoder =
            device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("ism vpl encoder") });
        if !pass.record(&device, &queue, &mut encoder, scene, gpu, light, settings, frame, None) {
            return Err(RenderError::Unsupported { mode: "ism", reason: format!("light {light} is directional") });
        }
        queue.submit([encoder.finish()]);
        let bytes = readback::read_buffer(&device, &queue, &pass.vpls)?;
        let mut vpls: Vec<super::gi::ism::vpl_pass::GpuVpl> = bytemuck::pod_collect_to_vec(&bytes);
        vpls.truncate(settings.vpl_count as usize);
        let importance =
            readback::read_as_rgba_f32(&device, &queue, &pass.importance)?.into_iter().map(|p| p[0]).collect();
        let power = readback::read_as_rgba_f32(&device, &queue, &pass.power.texture)?;
        Ok(IsmVpls { vpls, importance, power })
    }

    /// The VPLs of every bounce of the last ISM frame (inspector overlay and tests).
    pub fn ism_all_vpls(&self) -> Result<Vec<super::gi::ism::vpl_pass::GpuVpl>, RenderError> {
        let buffer = self.gather.as_ref().and_then(|g| g.all_vpls()).ok_or_else(|| RenderError::UnknownBuffer {
            name: "ism vpls".into(),
            known: "render an ism mode first".into(),
        })?;
        Ok(bytemuck::pod_collect_to_vec(&readback::read_buffer(&self.device, &self.queue, buffer)?))
    }

    /// Forgets temporal state (motion vectors restart from zero).
    pub fn reset_history(&mut self) {
        self.prev_clip_from_world = None;
        if let Some(gpu) = &mut self.scene_gpu {
            gpu.reset_motion();
        }
    }

    /// Frames rendered so far (temporal techniques seed from it).
    pub fn frame_index(&self) -> u32 {
        self.frame_index
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
