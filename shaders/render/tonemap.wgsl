// Exposure and tonemapping of linear radiance to gamma-encoded sRGB in an rgba8unorm image (the
// format egui displays and PNG files store).
#import common/color.wgsl

struct TonemapParams {
    // exposure multiplier, unused x3.
    exposure: vec4<f32>,
    // operator, unused x3.
    op: vec4<u32>,
}

@group(0) @binding(0) var<uniform> params: TonemapParams;
@group(0) @binding(1) var hdr: texture_2d<f32>;
@group(0) @binding(2) var ldr: texture_storage_2d<rgba8unorm, write>;

@compute @workgroup_size(8, 8, 1)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(hdr);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    let c = textureLoad(hdr, id.xy, 0).rgb * params.exposure.x;
    let mapped = tonemap(max(c, vec3<f32>(0.0)), params.op.x);
    textureStore(ldr, id.xy, vec4<f32>(srgb_from_linear(mapped), 1.0));
}
