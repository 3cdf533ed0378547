// MRT pass A (Loos 2015 §3.6.3 step 1, §4.4.1): the direct light l_d at every block
// texel, evaluated on the real surface of its geometry image with the frame's shadowed lights,
// as outgoing radiance (albedo x E / pi), plus what the texel sends on its own (an emissive
// surface, or the sky through a window: `geometry_image.rs`). Multi-bounce feedback adds albedo x
// the previous frame's indirect light, clamped at zero (the reduced reconstructions can ring
// negative).
#import common/frame.wgsl
#import common/lights.wgsl
#import render/gi/mrt/mrt_common.wgsl

@group(0) @binding(0) var<uniform> frame: Frame;
@group(0) @binding(1) var<storage, read> lights: array<GpuLight>;
@group(0) @binding(2) var<storage, read> shadow_views: array<mat4x4<f32>>;
@group(0) @binding(3) var shadow_maps: texture_depth_2d_array;
@group(0) @binding(4) var shadow_sampler: sampler_comparison;
@group(0) @binding(5) var<uniform> mp: MrtParams;
@group(0) @binding(6) var<storage, read> texels: array<Texel>;
// Last frame's indirect light per texel (E / pi).
@group(0) @binding(7) var<storage, read> previous: array<vec4<f32>>;
@group(0) @binding(8) var<storage, read_write> l_d: array<vec4<f32>>;

#import common/shadow.wgsl

@compute @workgroup_size(64, 1, 1)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= mp.counts.y {
        return;
    }
    let t = texels[i];
    if t.position.w < 0.5 {
        l_d[i] = vec4<f32>(t.emission.rgb, 1.0);
        return;
    }
    let p = t.position.xyz;
    let n = t.normal.xyz;
    let e = shadowed_irradiance(frame, p, n);
    let bounce = max(previous[i].rgb, vec3<f32>(0.0)) * mp.gains.x;
    l_d[i] = vec4<f32>(t.albedo.rgb * (e / MRT_PI + bounce) + t.emission.rgb, 1.0);
}
