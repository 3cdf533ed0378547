// sshgi temporal filter (Soler et al. 2010, Sec. 4, "Temporal filtering", Eq. 6):
// F_i = a W(H) + (1 - a) I_i, W the warp of the history to this frame through the motion buffer.
// The history is checked against this pixel's surface: each of the 2x2 bilinear taps around the
// previous position is kept only where its stored world position lies within 5% of the distance to
// the camera and its normal within 25 degrees, so disocclusions and moving edges start afresh. H
// is F_i-1 (a recursive, exponential history: the default) or the previous raw gather I_i-1 (the
// paper's 2-tap blend).
#import common/frame.wgsl
#import common/octahedral.wgsl

struct TemporalParams {
    // a, 2-tap (1) or recursive (0), history valid (1) or reset (0), unused.
    p: vec4<f32>,
}

@group(0) @binding(0) var<uniform> frame: Frame;
@group(0) @binding(1) var<uniform> tp: TemporalParams;
@group(0) @binding(2) var depth_tex: texture_depth_2d;
@group(0) @binding(3) var normal_tex: texture_2d<f32>;
@group(0) @binding(4) var motion_tex: texture_2d<f32>;
@group(0) @binding(5) var current: texture_2d<f32>;
@group(0) @binding(6) var history_in: texture_2d<f32>;
// Previous frame: world position xyz, w = its octahedral normal quantised to an exact integer
// (`pack_normal`); w = 0 where there was no geometry.
@group(0) @binding(7) var geometry_in: texture_2d<f32>;
@group(0) @binding(8) var out_indirect: texture_storage_2d<rgba32float, write>;
@group(0) @binding(9) var history_out: texture_storage_2d<rgba32float, write>;
@group(0) @binding(10) var geometry_out: texture_storage_2d<rgba32float, write>;
// r = the history's weight in the blend (0 = rejected or reset), g = the taps kept (of 1).
@group(0) @binding(11) var accept_out: texture_storage_2d<rgba32float, write>;

// An octahedral normal as an integer-valued float in 1..65536 (8 bits per component; exact in f32).
fn pack_normal(n: vec3<f32>) -> f32 {
    let q = round(clamp(oct_encode(n), vec2<f32>(-1.0), vec2<f32>(1.0)) * 127.0 + 127.0);
    return 1.0 + q.x + 256.0 * q.y;
}

fn unpack_normal(w: f32) -> vec3<f32> {
    let v = w - 1.0;
    let y = floor(v / 256.0);
    return oct_decode((vec2<f32>(v - 256.0 * y, y) - 127.0) / 127.0);
}

@compute @workgroup_size(8, 8, 1)
fn temporal(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = vec2<u32>(frame.size.xy);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    let cur = textureLoad(current, id.xy, 0).rgb;
    let d = textureLoad(depth_tex, id.xy, 0);
    if d <= 0.0 {
        textureStore(out_indirect, id.xy, vec4<f32>(0.0, 0.0, 0.0, 1.0));
        textureStore(history_out, id.xy, vec4<f32>(0.0));
        textureStore(geometry_out, id.xy, vec4<f32>(0.0));
        textureStore(accept_out, id.xy, vec4<f32>(0.0));
        return;
    }
    let p = world_from_pixel(frame, id.xy, d);
    let n = oct_decode(textureLoad(normal_tex, id.xy, 0).zw);
    let tolerance = 0.05 * length(p - frame.camera_position.xyz);
    var sum = vec3<f32>(0.0);
    var weight = 0.0;
    if tp.p.z > 0.5 {
        let uv = (vec2<f32>(id.xy) + 0.5) * frame.size.zw - textureLoad(motion_tex, id.xy, 0).xy;
        let c = uv * frame.size.xy - 0.5;
        let base = vec2<i32>(floor(c));
        let f = c - floor(c);
        for (var i = 0; i < 4; i = i + 1) {
            let o = vec2<i32>(i & 1, i >> 1);
            let q = base + o;
            if any(q < vec2<i32>(0)) || any(q >= vec2<i32>(size)) {
                continue;
            }
            let g = textureLoad(geometry_in, q, 0);
            if g.w == 0.0 {
                continue;
            }
            let n_prev = unpack_normal(g.w);
            if distance(g.xyz, p) > tolerance || dot(n, n_prev) < 0.9 {
                continue;
            }
            let w = select(1.0 - f.x, f.x, o.x == 1) * select(1.0 - f.y, f.y, o.y == 1);
            sum = sum + textureLoad(history_in, q, 0).rgb * w;
            weight = weight + w;
        }
    }
    var a = 0.0;
    var blended = cur;
    if weight > 1.0e-3 {
        a = tp.p.x;
        blended = a * (sum / weight) + (1.0 - a) * cur;
    }
    textureStore(out_indirect, id.xy, vec4<f32>(blended, 1.0));
    textureStore(history_out, id.xy, vec4<f32>(select(blended, cur, tp.p.y > 0.5), 1.0));
    textureStore(geometry_out, id.xy, vec4<f32>(p, pack_normal(n)));
    textureStore(accept_out, id.xy, vec4<f32>(a, weight, 0.0, 1.0));
}
