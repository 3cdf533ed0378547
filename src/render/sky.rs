//! The sky on the GPU: the environment's radiance for the pixels that see no surface (the
//! lighting pass writes it into the direct term, so every mode shows the sky the reference path
//! tracer sees). A constant sky is a uniform; an image is an `Rgba32Float` texture read with the
//! same equirectangular mapping and nearest texel as the path tracer
//! ([`crate::scene::equirect_uv`]); it is uploaded again only when the environment's image changes.

use bytemuck::{Pod, Zeroable};

use crate::scene::{Scene, Sky, SkyImage};

/// `SkyParams` in `render/lighting.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct SkyUniforms {
    /// rgb: a constant sky's radiance (colour x intensity); a: the intensity.
    pub radiance: [f32; 4],
    /// 0 no sky, 1 constant, 2 image; image width, height; unused.
    pub kind: [u32; 4],
    /// cos and sin of the rotation about +Y; unused x2.
    pub rotation: [f32; 4],
}

const _: () = assert!(std::mem::size_of::<SkyUniforms>() == 48);

/// The sky's parameter block in the shaders that read it (file, struct, bytes), checked against
/// naga's layout by the shader tests.
pub const PARAM_BLOCKS: &[(&str, &str, usize)] = &[
    ("render/lighting.wgsl", "SkyParams", std::mem::size_of::<SkyUniforms>()),
    ("render/gi/rcs/rcs_reduce.wgsl", "SkyParams", std::mem::size_of::<SkyUniforms>()),
];

/// The sky's GPU resources.
pub struct SkyGpu {
    /// The uniform block.
    pub buffer: wgpu::Buffer,
    /// The image (1 x 1 black without one).
    pub texture: wgpu::Texture,
    pub view: wgpu::TextureView,
    /// The image uploaded, by address (the scene shares it through an `Arc`).
    uploaded: Option<std::sync::Arc<SkyImage>>,
    /// The analytic sky's turbidity and sun (bits) it was baked for.
    baked_for: Option<[u32; 4]>,
    /// Bumped whenever `view` is replaced (bind groups holding it are stale).
    pub generation: u64,
}

fn texture(device: &wgpu::Device, width: u32, height: u32) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some("sky image"),
        size: wgpu::Extent3d { width, height, depth_or_array_layers: 1 },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Rgba32Float,
        usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
        view_formats: &[],
    })
}

impl SkyGpu {
    /// No sky yet.
    pub fn new(device: &wgpu::Device) -> Self {
        let buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("sky uniforms"),
            size: std::mem::size_of::<SkyUniforms>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let texture = texture(device, 1, 1);
        let view =
            texture.create_view(&wgpu::TextureViewDescriptor { label: Some("sky image view"), ..Default::default() });
        Self { buffer, texture, view, uploaded: None, baked_for: None, generation: 0 }
    }

    /// Writes the uniforms and uploads the image if it changed.
    pub fn sync(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, scene: &Scene) {
        let env = scene.environment();
        match &env.sky {
            Sky::Preetham { turbidity } => {
                // Baked again only when the sun or the turbidity moved.
                let sun = env.to_sky(scene.sun_direction()).to_array().map(f32::to_bits);
                let key = [turbidity.to_bits(), sun[0], sun[1], sun[2]];
                if self.baked_for != Some(key) {
                    self.upload(device, queue, scene.sky_texels());
                    self.baked_for = Some(key);
                }
            }
            _ => {
                self.baked_for = None;
                let image = scene.resources().sky.as_ref().filter(|_| matches!(env.sky, Sky::Image(_)));
                let same = match (image, &self.uploaded) {
                    (Some(a), Some(b)) => std::sync::Arc::ptr_eq(a, b),
                    (None, None) => true,
                    _ => false,
                };
                if !same {
                    self.upload(device, queue, image.cloned());
                }
            }
        }
        let image = self.uploaded.as_deref();
        let (kind, rgb) = match (&env.sky, image) {
            (Sky::Constant(c), _) => (1, c.map(|v| v * env.intensity)),
            (Sky::Image(_) | Sky::Preetham { .. }, Some(_)) => (2, [0.0; 3]),
            _ => (0, [0.0; 3]),
        };
        let (w, h) = image.map_or((1, 1), |i| (i.width, i.height));
        let r = env.rotation_degrees.to_radians();
        let uniforms = SkyUniforms {
            radiance: [rgb[0], rgb[1], rgb[2], env.intensity],
            kind: [kind, w, h, 0],
            rotation: [r.cos(), r.sin(), 0.0, 0.0],
        };
        queue.write_buffer(&self.buffer, 0, bytemuck::bytes_of(&uniforms));
    }

    fn upload(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, image: Option<std::sync::Arc<SkyImage>>) {
        let (w, h) = image.as_ref().map_or((1, 1), |i| (i.width, i.height));
        self.texture = texture(device, w, h);
        self.view = self
            .texture
            .create_view(&wgpu::TextureViewDescriptor { label: Some("sky image view"), ..Default::default() });
        if let Some(img) = &image {
            let texels: Vec<[f32; 4]> = img.texels.iter().map(|t| [t[0], t[1], t[2], 1.0]).collect();
            queue.write_texture(
                self.texture.as_image_copy(),
                bytemuck::cast_slice(&texels),
                wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(16 * w), rows_per_image: Some(h) },
                wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
            );
        }
        self.uploaded = image;
        self.generation += 1;
    }
}
