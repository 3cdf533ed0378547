// ISM pass P13 for shading at a gathering step s = 2 (`IsmSettings::shade_resolution`): the
// geometry-aware n x n box filter of `ism_filter.wgsl`, its taps taken from the gathered
// samples instead of the view's pixels. Sample q stands at pixel s q (`ism_split.wgsl`); pixel p
// takes the n x n samples whose pixels are centred on it (every interleave phase once), each
// tested with the position and normals the split G-buffer stored for it against p's own
// tangent plane and normal (alpha, beta as in `ism_filter.wgsl`). Where no sample passes (a
// surface narrower than s pixels that no sample landed on), the sample nearest p's plane with
// the closest normal stands in alone: one interleave phase, right in expectation.
#import common/frame.wgsl
#import common/octahedral.wgsl
#import common/interleave.wgsl
#import render/gi/ism/ism_filter_centre.wgsl

struct UpsampleParams {
    // interleave n, gathering step s, gathered samples along x and y.
    counts: vec4<u32>,
    // alpha (normalised depth), beta (min cosine), depth range (metres), unused.
    params: vec4<f32>,
}

@group(0) @binding(0) var<uniform> frame: Frame;
@group(0) @binding(1) var<uniform> up: UpsampleParams;
@group(0) @binding(2) var raw: texture_2d<f32>;
@group(0) @binding(3) var split_position: texture_2d<f32>;
@group(0) @binding(4) var split_normal: texture_2d<f32>;
@group(0) @binding(5) var depth_tex: texture_depth_2d;
@group(0) @binding(6) var normal_tex: texture_2d<f32>;
@group(0) @binding(7) var out_indirect: texture_storage_2d<rgba32float, write>;

// floor(a / b) for b > 0.
fn floor_div(a: i32, b: i32) -> i32 {
    return (a - (((a % b) + b) % b)) / b;
}

// First sample of the n along one axis whose pixels s q are centred on pixel p, moved inside
// the `count` samples so that the window keeps every phase at the view's borders.
fn window_start(p: i32, n: i32, s: i32, count: i32) -> i32 {
    let q0 = floor_div(2 * p + s - s * n, 2 * s);
    return clamp(q0, 0, max(count - n, 0));
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
    let tolerance = up.params.x * up.params.z;
    let n = i32(up.counts.x);
    let s = i32(up.counts.y);
    let count = vec2<i32>(up.counts.zw);
    let start = vec2<i32>(window_start(p.x, n, s, count.x), window_start(p.y, n, s, count.y));
    var acc = vec3<f32>(0.0);
    var w = 0.0;
    var best = vec3<f32>(0.0);
    var best_score = 3.4e38;
    for (var dy = 0; dy < n; dy = dy + 1) {
        for (var dx = 0; dx < n; dx = dx + 1) {
            let q = clamp(start + vec2<i32>(dx, dy), vec2<i32>(0), count - 1);
            let at = split_address(vec2<u32>(q), vec2<u32>(count), up.counts.x);
            let pq = textureLoad(split_position, at, 0);
            if pq.w < 0.5 {
                continue;
            }
            let nq = oct_decode(textureLoad(split_normal, at, 0).xy);
            let value = textureLoad(raw, at, 0).rgb;
            if filter_accepts(centre, pq.xyz, nq, tolerance, up.params.y) {
                acc = acc + value;
                w = w + 1.0;
            }
            // The stand-in: nearest the plane, then the closest normal.
            let off_plane = abs(dot(pq.xyz - centre.position.xyz, centre.geometric));
            let score = off_plane / max(tolerance, 1.0e-12) + max(up.params.y - dot(nq, centre.normal), 0.0) * 1.0e3;
            if score < best_score {
                best_score = score;
                best = value;
            }
        }
    }
    var result = best;
    if w > 0.0 {
        result = acc / w;
    }
    textureStore(out_indirect, id.xy, vec4<f32>(result, 1.0));
}
