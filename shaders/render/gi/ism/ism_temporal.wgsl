// ISM pass P12 (Knecht 2009 section 3.5): undo the split and merge the new interleaved indirect with the history
// reprojected through the movement buffer, weighted by a confidence
//   conf = c_base * saturate(1 - max(d_pos, d_normal, d_illum))
//   d_pos = |(motion, depth - depth_prev) * w_pos|, d_normal = (1 - n . n_prev) w_normal,
//   d_illum = saturate(|I_new - I_prev|^3) w_illum,
// zero off screen and after a reset. History rgb = blended indirect, a = normalised depth.
// Two additions to the thesis (`IsmSettings::still_frames`):
// - the history's effective sample count m (the frames its average is worth, `count`) caps the
//   confidence at m / (m + 1), so a fresh history is a plain mean of its frames instead of
//   keeping its first frame's noise at weight c_base^k for tens of frames;
// - c_base is replaced by `params.z`: c_base while anything moves, and 1 - 1 / still_frames
//   once the camera, lights and objects stand still (after an edit: once its old light has
//   faded, `stillness.rs`), so a still view keeps refining (a time constant of still_frames
//   frames) instead of holding VPL resampling noise of 1 / sqrt(19) of a frame's; a still view
//   also gets w_illum = 0 (no light changed; the term only weighted VPL noise's bright frames up).
// m follows the blend exactly: the variance of conf h + (1 - conf) x is sigma^2 (conf^2 / m +
// (1 - conf)^2), so m' = 1 / (conf^2 / m + (1 - conf)^2) (m + 1 at conf = m / (m + 1)).
#import common/frame.wgsl
#import common/octahedral.wgsl
#import common/interleave.wgsl

struct TemporalParams {
    // reset (1 = ignore history), n when `raw` is in the split layout (0: full layout), unused x2.
    flags: vec4<u32>,
    // c_base (unused here: the cap in params.z stands for it), w_pos, w_normal, w_illum.
    weights: vec4<f32>,
    // depth range (metres), exposure multiplier, the confidence's cap (c_base, or
    // 1 - 1 / still_frames while nothing moves), unused.
    params: vec4<f32>,
}

@group(0) @binding(0) var<uniform> frame: Frame;
@group(0) @binding(1) var<uniform> tp: TemporalParams;
@group(0) @binding(2) var raw: texture_2d<f32>;
@group(0) @binding(3) var history_in: texture_2d<f32>;
@group(0) @binding(4) var depth_tex: texture_depth_2d;
@group(0) @binding(5) var normal_tex: texture_2d<f32>;
@group(0) @binding(6) var prev_normal_tex: texture_2d<f32>;
@group(0) @binding(7) var motion_tex: texture_2d<f32>;
@group(0) @binding(8) var history_out: texture_storage_2d<rgba32float, write>;
@group(0) @binding(9) var confidence_out: texture_storage_2d<rgba32float, write>;
@group(0) @binding(10) var count_in: texture_2d<f32>;
@group(0) @binding(11) var count_out: texture_storage_2d<r32float, write>;

// The effective sample count after blending a history worth m frames with confidence conf.
fn blended_count(m: f32, conf: f32) -> f32 {
    if conf <= 0.0 || m <= 0.0 {
        return 1.0;
    }
    let one_minus = 1.0 - conf;
    return 1.0 / (conf * conf / m + one_minus * one_minus);
}

@compute @workgroup_size(8, 8, 1)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = vec2<u32>(frame.size.xy);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    let d = textureLoad(depth_tex, id.xy, 0);
    var raw_at = id.xy;
    if tp.flags.y > 0u {
        raw_at = split_address(id.xy, size, tp.flags.y);
    }
    let i_new = textureLoad(raw, raw_at, 0).rgb;
    if d <= 0.0 {
        textureStore(history_out, id.xy, vec4<f32>(0.0, 0.0, 0.0, -1.0));
        textureStore(confidence_out, id.xy, vec4<f32>(0.0));
        textureStore(count_out, id.xy, vec4<f32>(0.0));
        return;
    }
    let depth = length(world_from_pixel(frame, id.xy, d) - frame.camera_position.xyz) / tp.params.x;
    let m = textureLoad(motion_tex, id.xy, 0).xy;
    let uv = (vec2<f32>(id.xy) + 0.5) * frame.size.zw;
    let uv_prev = uv - m;
    let inside = all(uv_prev >= vec2<f32>(0.0)) && all(uv_prev < vec2<f32>(1.0));
    var conf = 0.0;
    var i_prev = vec3<f32>(0.0);
    var dp = 1.0;
    var dn = 1.0;
    var di = 1.0;
    var frames = 0.0;
    if inside && tp.flags.x == 0u {
        let q = vec2<u32>(uv_prev * frame.size.xy);
        let hist = textureLoad(history_in, q, 0);
        i_prev = hist.rgb;
        frames = textureLoad(count_in, q, 0).r;
        let n = oct_decode(textureLoad(normal_tex, id.xy, 0).xy);
        let n_prev = oct_decode(textureLoad(prev_normal_tex, q, 0).xy);
        let w = tp.weights;
        if hist.a >= 0.0 {
            dp = length(vec3<f32>(m * w.y, (depth - hist.a) * 2.5 * w.y));
            dn = (1.0 - dot(n, n_prev)) * w.z;
            let e = length(i_new - i_prev) * tp.params.y;
            di = clamp(e * e * e, 0.0, 1.0) * w.w;
            conf = tp.params.z * clamp(1.0 - max(dp, max(dn, di)), 0.0, 1.0);
            conf = min(conf, frames / (frames + 1.0));
        }
    }
    let blended = conf * i_prev + (1.0 - conf) * i_new;
    textureStore(history_out, id.xy, vec4<f32>(blended, depth));
    textureStore(count_out, id.xy, vec4<f32>(blended_count(frames, conf), 0.0, 0.0, 0.0));
    textureStore(confidence_out, id.xy, vec4<f32>(clamp(dp, 0.0, 1.0), clamp(dn, 0.0, 1.0), clamp(di, 0.0, 1.0), conf));
}
