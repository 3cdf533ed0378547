//! The per-view render targets: the G-buffer, the direct term (and its exitance, what a diffuse
//! sender sends), the GI technique's indirect term, the linear HDR image and the tonemapped display
//! image. Recreated on resize.
//!
//! G-buffer packing (see `shaders/render/gbuffer.wgsl`):
//! - `albedo` Rgba16Float: linear albedo (8-bit storage would cost up to 2.6% error on dark
//!   channels such as the Cornell red wall's 0.065; half floats keep it under 0.05%);
//! - `normal` Rgba16Float: xy octahedral shading normal, zw octahedral geometric normal;
//! - `material` Rgba8Unorm: specular colour and roughness;
//! - `motion` Rg16Float: screen-uv motion to the previous frame;
//! - `object_id` R32Uint: object index + 1, 0 for background;
//! - `emission` Rgba16Float: the radiance the front faces of emissive surfaces send to the
//!   camera (`shaders/render/emission.wgsl`; a separate pass, since the five G-buffer targets
//!   already use 28 of the 32 bytes a sample that WebGPU guarantees);
//! - `depth` Depth32Float: reversed hardware depth (1 near, 0 far); positions are reconstructed
//!   from it.

/// Formats of the targets.
pub mod formats {
    pub const ALBEDO: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
    pub const NORMAL: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
    pub const MATERIAL: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;
    pub const MOTION: wgpu::TextureFormat = wgpu::TextureFormat::Rg16Float;
    pub const OBJECT_ID: wgpu::TextureFormat = wgpu::TextureFormat::R32Uint;
    pub const EMISSION: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
    pub const EXITANCE: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;
    pub const DEPTH: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
    pub const HDR: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;
    pub const LDR: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;
}

/// A texture and its default view.
pub struct Target {
    pub texture: wgpu::Texture,
    pub view: wgpu::TextureView,
}

impl Target {
    /// A 2D target of `format` with `usage`.
    pub fn new(
        device: &wgpu::Device,
        label: &str,
        size: (u32, u32),
        format: wgpu::TextureFormat,
        usage: wgpu::TextureUsages,
    ) -> Self {
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some(label),
            size: wgpu::Extent3d { width: size.0.max(1), height: size.1.max(1), depth_or_array_layers: 1 },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage,
            view_formats: &[],
        });
        let view = texture.create_view(&wgpu::TextureViewDescriptor { label: Some(label), ..Default::default() });
        Self { texture, view }
    }
}

/// All per-view targets.
pub struct ViewTargets {
    pub size: (u32, u32),
    pub albedo: Target,
    pub normal: Target,
    pub material: Target,
    pub motion: Target,
    pub object_id: Target,
    /// Emitted radiance of the emissive surfaces the camera sees.
    pub emission: Target,
    pub depth: Target,
    /// Shadowed direct radiance (the lighting pass); GI techniques may read it.
    pub direct: Target,
    /// The direct term as a diffuse sender sends it (the lighting pass): radiant exitance / pi,
    /// the glossy lobe's share in every direction instead of towards the camera; f32 like
    /// `direct` (16 bytes a pixel), so the two agree to float rounding where there is no lobe.
    pub exitance: Target,
    /// Indirect light written by the active GI technique; what it holds (E / pi, outgoing
    /// radiance, the whole image) is the technique's `GiOutput` for the frame.
    pub indirect: Target,
    /// Linear radiance (the EXR output).
    pub hdr: Target,
    /// Tonemapped, gamma-encoded display image (the PNG output and the egui texture).
    pub ldr: Target,
    /// Volumetric obscurance before the blur (r: the factor, g: the obscurance V).
    pub vo_raw: Target,
    /// Volumetric obscurance after the blur's first (row) pass.
    pub vo_rows: Target,
    /// Volumetric obscurance after the bilateral blur (r: the factor the composite applies).
    pub vo: Target,
}

impl ViewTargets {
    /// Every target.
    pub fn all(&self) -> [&Target; 15] {
        [
            &self.albedo,
            &self.normal,
            &self.material,
            &self.motion,
            &self.object_id,
            &self.emission,
            &self.depth,
            &self.direct,
            &self.exitance,
            &self.indirect,
            &self.hdr,
            &self.ldr,
            &self.vo_raw,
            &self.vo_rows,
            &self.vo,
        ]
    }

    /// Creates targets of `size` pixels.
    pub fn new(device: &wgpu::Device, size: (u32, u32)) -> Self {
        use wgpu::TextureUsages as U;
        let rt = U::RENDER_ATTACHMENT | U::TEXTURE_BINDING | U::COPY_SRC;
        let storage = U::STORAGE_BINDING | U::TEXTURE_BINDING | U::COPY_SRC | U::COPY_DST;
        Self {
            size,
            albedo: Target::new(device, "gbuffer albedo", size, formats::ALBEDO, rt),
            normal: Target::new(device, "gbuffer normal", size, formats::NORMAL, rt),
            material: Target::new(device, "gbuffer material", size, formats::MATERIAL, rt),
            motion: Target::new(device, "gbuffer motion", size, formats::MOTION, rt),
            object_id: Target::new(device, "gbuffer object id", size, formats::OBJECT_ID, rt),
            emission: Target::new(device, "emission", size, formats::EMISSION, rt),
            depth: Target::new(device, "gbuffer depth", size, formats::DEPTH, rt),
            direct: Target::new(device, "direct radiance", size, formats::HDR, storage),
            exitance: Target::new(device, "direct exitance", size, formats::EXITANCE, storage),
            indirect: Target::new(device, "indirect radiance", size, formats::HDR, storage | U::RENDER_ATTACHMENT),
            hdr: Target::new(device, "hdr radiance", size, formats::HDR, storage),
            ldr: Target::new(device, "ldr display", size, formats::LDR, storage | U::RENDER_ATTACHMENT),
            vo_raw: Target::new(device, "volumetric obscurance raw", size, formats::HDR, storage),
            vo_rows: Target::new(device, "volumetric obscurance blurred along rows", size, formats::HDR, storage),
            vo: Target::new(device, "volumetric obscurance", size, formats::HDR, storage),
        }
    }
}

/// A colour attachment of `view` cleared to transparent black and stored.
pub fn cleared(view: &wgpu::TextureView) -> Option<wgpu::RenderPassColorAttachment<'_>> {
    Some(wgpu::RenderPassColorAttachment {
        view,
        depth_slice: None,
        resolve_target: None,
        ops: wgpu::Operations { load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT), store: wgpu::StoreOp::Store },
    })
}
