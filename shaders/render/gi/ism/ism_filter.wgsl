// ISM pass P13: the geometry-aware n x n box filter (Laine et al. 2007 as used by Knecht 2009):
// offsets [-n/2, n/2 - 1] cover each of the n^2 interleave phases once; a neighbour is rejected
// when its normal differs by a cosine below beta or its distance from this pixel's tangent
// plane exceeds alpha (normalised by the scene diameter). The thesis compares view depths;
// along the plane, walls seen at grazing angles keep their taps instead of showing the
// interleave pattern as stripes (measured in tests/integration/ism_sh.rs).
#import common/frame.wgsl
#import common/octahedral.wgsl
#import common/interleave.wgsl
#import render/gi/ism/ism_filter_centre.wgsl

struct FilterParams {
    // interleave n, n when `raw` is in the split layout (0: full layout), unused x2.
    counts: vec4<u32>,
    // alpha (normalised depth), beta (min cosine), depth range (metres), unused.
    params: vec4<f32>,
}

@group(0) @binding(0) var<uniform> frame: Frame;
@group(0) @binding(1) var<uniform> fp: FilterParams;
@group(0) @binding(2) var raw: texture_2d<f32>;
@group(0) @binding(3) var depth_tex: texture_depth_2d;
@group(0) @binding(4) var normal_tex: texture_2d<f32>;
@group(0) @binding(5) var out_indirect: texture_storage_2d<rgba32float, write>;

fn position(pixel: vec2<u32>) -> vec4<f32> {
    return position_at(frame, depth_tex, pixel);
}

@compute @workgroup_size(8, 8, 1)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = vec2<i32>(frame.size.xy);
    let p = vec2<i32>(id.xy);
    if p.x >= size.x || p.y >= size.y {
        return;
    }
    let centre = filter_centre(frame, depth_tex, normal_tex, id.xy);
    if centre.position.w < 0.5 {
        textureStore(out_indirect, id.xy, vec4<f32>(0.0));
        return;
    }
    let tolerance = fp.params.x * fp.params.z;
    let half = i32(fp.counts.x / 2u);
    let n = i32(fp.counts.x);
    var acc = vec3<f32>(0.0);
    var w = 0.0;
    for (var dy = -half; dy < n - half; dy = dy + 1) {
        for (var dx = -half; dx < n - half; dx = dx + 1) {
            let q = clamp(p + vec2<i32>(dx, dy), vec2<i32>(0), size - 1);
            let pq = position(vec2<u32>(q));
            let nq = oct_decode(textureLoad(normal_tex, vec2<u32>(q), 0).xy);
            if pq.w > 0.5 && filter_accepts(centre, pq.xyz, nq, tolerance, fp.params.y) {
                var at = vec2<u32>(q);
                if fp.counts.y > 0u {
                    at = split_address(at, vec2<u32>(size), fp.counts.y);
                }
                acc = acc + textureLoad(raw, at, 0).rgb;
                w = w + 1.0;
            }
        }
    }
    textureStore(out_indirect, id.xy, vec4<f32>(acc / max(w, 1.0), 1.0));
}
