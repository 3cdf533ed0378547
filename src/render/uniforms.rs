//! CPU mirrors of the WGSL structs (`#[repr(C)]`, `Pod`), with size checks. The WGSL side is in
//! `shaders/common/frame.wgsl`, `lights.wgsl` and `render/gbuffer.wgsl`.

use bytemuck::{Pod, Zeroable};
use glam::{Mat3, Mat4, Vec3};

use crate::scene::{Light, LightKind, Material};

/// `Frame` in `common/frame.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct FrameUniforms {
    pub clip_from_world: [[f32; 4]; 4],
    pub world_from_clip: [[f32; 4]; 4],
    pub prev_clip_from_world: [[f32; 4]; 4],
    pub camera_position: [f32; 4],
    pub size: [f32; 4],
    pub params: [u32; 4],
    pub shadow: [f32; 4],
}

/// `GpuLight` in `common/lights.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, Pod, Zeroable)]
pub struct GpuLight {
    pub position: [f32; 4],
    pub direction: [f32; 4],
    pub radiant: [f32; 4],
    pub cone: [f32; 4],
}

impl GpuLight {
    /// Packs a light; `shadow_layer` is its first shadow layer and `texel_factor` the shadow
    /// texel size per metre of distance (per texel for directional lights).
    pub fn new(light: &Light, shadow_layer: Option<u32>, texel_factor: f32) -> Self {
        let (kind, scale, offset) = match light.kind {
            LightKind::Point => (0.0, 0.0, 0.0),
            LightKind::Spot { inner_cone_angle, outer_cone_angle } => {
                let scale = 1.0 / (inner_cone_angle.cos() - outer_cone_angle.cos()).max(0.001);
                (1.0, scale, -outer_cone_angle.cos() * scale)
            }
            LightKind::Directional => (2.0, 0.0, 0.0),
        };
        let radiant = light.radiant();
        Self {
            position: light.position.extend(kind).to_array(),
            direction: light.direction.normalize_or(Vec3::NEG_Y).extend(light.range.unwrap_or(0.0)).to_array(),
            radiant: radiant.extend(shadow_layer.map_or(-1.0, |l| l as f32)).to_array(),
            cone: [scale, offset, texel_factor, 0.0],
        }
    }
}

/// `Object` in `render/gbuffer.wgsl` (one 256-byte dynamic-offset slot each).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct ObjectUniforms {
    pub world_from_local: [[f32; 4]; 4],
    pub normal_from_local: [[f32; 4]; 4],
    pub prev_world_from_local: [[f32; 4]; 4],
    pub ids: [u32; 4],
    pub _pad: [u32; 12],
}

impl ObjectUniforms {
    /// Packs an object's matrices; `id` is the object index + 1.
    pub fn new(world: Mat4, prev_world: Mat4, id: u32, material: u32) -> Self {
        let normal = Mat4::from_mat3(Mat3::from_mat4(world).inverse().transpose());
        Self {
            world_from_local: world.to_cols_array_2d(),
            normal_from_local: normal.to_cols_array_2d(),
            prev_world_from_local: prev_world.to_cols_array_2d(),
            ids: [id, material, 0, 0],
            _pad: [0; 12],
        }
    }
}

/// `MaterialParams` in `render/gbuffer.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct MaterialUniforms {
    pub base_color: [f32; 4],
    pub specular: [f32; 4],
    pub flags: [u32; 4],
    pub params: [f32; 4],
}

impl MaterialUniforms {
    /// Packs a material.
    pub fn new(m: &Material) -> Self {
        let emission = m.emission();
        Self {
            base_color: m.base_color,
            specular: [m.specular[0], m.specular[1], m.specular[2], m.roughness],
            flags: [
                u32::from(m.base_color_texture.is_some()),
                u32::from(m.normal_texture.is_some()),
                u32::from(m.emissive_texture.is_some()),
                0,
            ],
            params: [m.normal_scale, emission.x, emission.y, emission.z],
        }
    }
}

/// `CompositeParams` in `render/composite.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct CompositeUniforms {
    /// What `indirect` holds: 0 nothing, 1 E / pi, 2 outgoing radiance, 3 the whole image;
    /// volumetric obscurance multiplies the indirect term (1) or not; unused x2.
    pub output: [u32; 4],
}

/// `TonemapParams` in `render/tonemap.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct TonemapUniforms {
    pub exposure: [f32; 4],
    pub op: [u32; 4],
}

const _: () = assert!(std::mem::size_of::<FrameUniforms>() == 256);
const _: () = assert!(std::mem::size_of::<GpuLight>() == 64);
const _: () = assert!(std::mem::size_of::<CompositeUniforms>() == 16);
const _: () = assert!(std::mem::size_of::<ObjectUniforms>() == 256);
const _: () = assert!(std::mem::size_of::<MaterialUniforms>() == 64);
