// Depth-only rendering of one shadow-map layer. All geometry occludes (no culling), as in the
// reference path tracer: one-sided surfaces still block light.
struct ShadowDraw {
    clip_from_local: mat4x4<f32>,
}

@group(0) @binding(0) var<uniform> draw: ShadowDraw;

@vertex
fn vs_main(@location(0) position: vec3<f32>) -> @builtin(position) vec4<f32> {
    return draw.clip_from_local * vec4<f32>(position, 1.0);
}
