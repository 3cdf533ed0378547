// The composite: final radiance = the direct term (`lighting.wgsl`) + the GI technique's
// indirect term, used as its output kind says (render::gi::GiOutput): nothing, E / pi times the
// albedo, outgoing radiance as it is, or the whole image (the reference path tracer) in place
// of the direct term, the indirect term times the volumetric obscurance factor where it applies.
// Background pixels stay black unless the image is complete.
#import common/frame.wgsl

struct CompositeParams {
    // 0 nothing, 1 irradiance / pi, 2 outgoing radiance, 3 complete; volumetric obscurance on
    // the indirect term (1) or not; unused x2.
    output: vec4<u32>,
}

@group(0) @binding(0) var<uniform> frame: Frame;
@group(0) @binding(1) var<uniform> params: CompositeParams;
@group(0) @binding(2) var depth_tex: texture_depth_2d;
@group(0) @binding(3) var albedo_tex: texture_2d<f32>;
@group(0) @binding(4) var direct_tex: texture_2d<f32>;
@group(0) @binding(5) var indirect_tex: texture_2d<f32>;
@group(0) @binding(6) var out_radiance: texture_storage_2d<rgba32float, write>;
// Volumetric obscurance (`render/vo/vo_blur.wgsl`), r = the factor.
@group(0) @binding(7) var vo_tex: texture_2d<f32>;

@compute @workgroup_size(8, 8, 1)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = vec2<u32>(frame.size.xy);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    let pixel = id.xy;
    let kind = params.output.x;
    var indirect = textureLoad(indirect_tex, pixel, 0).rgb;
    if kind == 3u {
        textureStore(out_radiance, pixel, vec4<f32>(indirect, 1.0));
        return;
    }
    var radiance = textureLoad(direct_tex, pixel, 0).rgb;
    if textureLoad(depth_tex, pixel, 0) > 0.0 {
        if params.output.y == 1u {
            indirect = indirect * textureLoad(vo_tex, pixel, 0).r;
        }
        if kind == 1u {
            radiance = radiance + textureLoad(albedo_tex, pixel, 0).rgb * indirect;
        } else if kind == 2u {
            radiance = radiance + indirect;
        }
    }
    textureStore(out_radiance, pixel, vec4<f32>(radiance, 1.0));
}
