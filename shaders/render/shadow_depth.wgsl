// Depth-only rendering of one shadow-map layer, objects drawn instanced. All geometry occludes
// (no culling), as in the reference path tracer: one-sided surfaces still block light.
#import common/object.wgsl

struct ShadowLayer {
    clip_from_world: mat4x4<f32>,
}

@group(0) @binding(0) var<uniform> layer: ShadowLayer;
@group(1) @binding(0) var<storage, read> objects: array<Object>;

@vertex
fn vs_main(@location(0) position: vec3<f32>, @builtin(instance_index) instance: u32) -> @builtin(position) vec4<f32> {
    return layer.clip_from_world * (objects[instance].world_from_local * vec4<f32>(position, 1.0));
}
