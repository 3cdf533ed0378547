// The emission pass: draws the emissive objects again over the G-buffer's depth (compare
// Equal, no depth write; `@invariant` positions, as in `gbuffer.wgsl`, so the depths match
// exactly) and writes the radiance their front faces send to the camera: the material's
// emission colour x strength, times its sRGB emission texture. Back faces are culled: surfaces
// emit from their front face only, as they reflect.
#import common/frame.wgsl
#import common/material.wgsl

@group(0) @binding(0) var<uniform> frame: Frame;

struct VertexOut {
    @builtin(position) @invariant clip: vec4<f32>,
    @location(0) uv: vec2<f32>,
}

@vertex
fn vs_main(v: MeshVertex, @builtin(instance_index) instance: u32) -> VertexOut {
    var out: VertexOut;
    let object = objects[instance];
    let world = object.world_from_local * vec4<f32>(v.position, 1.0);
    out.clip = frame.clip_from_world * world;
    out.uv = v.uv;
    return out;
}

@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4<f32> {
    return vec4<f32>(material_emission(in.uv), 1.0);
}
