// rcs splatting (notes: "splat existing records"): one screen-aligned quad per record bounding
// the projection of its zone of influence, the sphere (P_k, a R_k) (the 8 corners of its box
// projected; a full-screen quad when the box reaches behind the camera). The fragment reads the
// G-buffer, evaluates Ward's full weight and discards where w <= 1/a; blending adds
//   0: (w E^_k(P), w)   E^ with the gradients (rotational with the shading normal)
//   1: (w E_k, 1)       the plain record value, and the count of records reaching the pixel
// so that the resolve divides by the summed weight.
#import common/frame.wgsl
#import common/octahedral.wgsl
#import render/gi/rcs/rcs_common.wgsl

struct SplatParams {
    // x = accuracy a, yzw unused.
    accuracy: vec4<f32>,
    // x = 1: instance i splats records[list[i]]; 0: records[i]. yzw unused.
    mode: vec4<u32>,
}

@group(0) @binding(0) var<uniform> frame: Frame;
@group(0) @binding(1) var<uniform> params: SplatParams;
@group(0) @binding(2) var<storage, read> records: array<Record>;
@group(0) @binding(3) var<storage, read> list: array<u32>;
@group(0) @binding(4) var depth_tex: texture_depth_2d;
@group(0) @binding(5) var normal_tex: texture_2d<f32>;

struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) @interpolate(flat) record: u32,
}

@vertex
fn vs_main(@builtin(vertex_index) vertex: u32, @builtin(instance_index) instance: u32) -> VertexOut {
    var out: VertexOut;
    var index = instance;
    if params.mode.x == 1u {
        index = list[instance];
    }
    out.record = index;
    let r = records[index];
    // Two triangles: corners (0,0) (1,0) (0,1) (0,1) (1,0) (1,1).
    let corners = array<vec2<f32>, 6>(
        vec2<f32>(0.0, 0.0), vec2<f32>(1.0, 0.0), vec2<f32>(0.0, 1.0),
        vec2<f32>(0.0, 1.0), vec2<f32>(1.0, 0.0), vec2<f32>(1.0, 1.0),
    );
    let corner = corners[vertex];
    if r.position.w <= 0.0 {
        out.clip = vec4<f32>(2.0, 2.0, 0.5, 1.0);
        return out;
    }
    let rho = params.accuracy.x * r.position.w;
    var lo = vec2<f32>(1.0e9);
    var hi = vec2<f32>(-1.0e9);
    var behind = false;
    for (var i = 0u; i < 8u; i = i + 1u) {
        let s = vec3<f32>(f32(i & 1u), f32((i >> 1u) & 1u), f32((i >> 2u) & 1u)) * 2.0 - 1.0;
        let c = frame.clip_from_world * vec4<f32>(r.position.xyz + s * rho, 1.0);
        if c.w <= 1.0e-6 {
            behind = true;
        }
        let ndc = c.xy / max(c.w, 1.0e-6);
        lo = min(lo, ndc);
        hi = max(hi, ndc);
    }
    if behind {
        lo = vec2<f32>(-1.0);
        hi = vec2<f32>(1.0);
    }
    lo = clamp(lo, vec2<f32>(-1.0), vec2<f32>(1.0));
    hi = clamp(hi, vec2<f32>(-1.0), vec2<f32>(1.0));
    out.clip = vec4<f32>(mix(lo, hi, corner), 0.5, 1.0);
    return out;
}

struct SplatOut {
    @location(0) weighted: vec4<f32>,
    @location(1) plain: vec4<f32>,
}

@fragment
fn fs_main(in: VertexOut) -> SplatOut {
    let pixel = vec2<u32>(in.clip.xy);
    let depth = textureLoad(depth_tex, pixel, 0);
    if depth <= 0.0 {
        discard;
    }
    let p = world_from_pixel(frame, pixel, depth);
    let enc = textureLoad(normal_tex, pixel, 0);
    let n_shading = oct_decode(enc.xy);
    let n = oct_decode(enc.zw);
    let r = records[in.record];
    let w = ward_weight(r, p, n);
    if w <= 1.0 / params.accuracy.x {
        discard;
    }
    var out: SplatOut;
    out.weighted = vec4<f32>(record_extrapolated(r, p, n_shading) * w, w);
    out.plain = vec4<f32>(r.irradiance.rgb * w, 1.0);
    return out;
}
