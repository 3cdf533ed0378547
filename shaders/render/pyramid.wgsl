// The shared depth/normal pyramid (render::pyramid): level 0 holds each pixel's linear distance
// to the camera (r), its octahedral geometric normal (gb) and, where there is geometry, a = 1 +
// the pixel's row-major index (0: none; exact in f32 up to 16M pixels), so a coarse texel knows
// which pixel's surface it copied and its point can be rebuilt on that pixel's own ray
// (`pyramid_point` in `common/frame.wgsl`). Rebuilt on the coarse texel's centre ray instead, the
// copied distance put the point up to half a texel's depth slope off its surface, and coplanar
// neighbours lit each other: sshgi's Cornell box read 0.929 of the reference's energy that way,
// 0.890 with the points on their surfaces (its first bounce's FLIP unchanged at 0.1019).
// Each coarser texel copies one of its 2x2 children whole (Soler et al. 2010, Eq. 5), so a level
// never holds an averaged depth or normal that no surface has. A child's score sums, over itself
// and its four L1 neighbours in the finer level (also outside the 2x2 block), g1(distance) x
// g3(z' - z), Gaussians with sigma 1 texel and a slope of 0.1 (`support` says why g3 is a slope
// and g2 is left out; the paper gives no sigmas): the most coherent surface wins, and a
// one-texel object between larger regions is dropped instead of winning by being nearest (a
// 6 cm pole panned a quarter pixel per frame appeared on levels 1-2 in 6 of 8 frames with the
// earlier nearest-of-agreeing-siblings rule). Whether the texel holds geometry at all is decided
// by counts (g1 only), so that background, which agrees with background exactly, never wins a
// silhouette texel because two real surfaces agree a little less than exactly.
#import common/frame.wgsl
#import common/octahedral.wgsl

@group(0) @binding(0) var<uniform> frame: Frame;
@group(0) @binding(1) var depth_tex: texture_depth_2d;
@group(0) @binding(2) var normal_tex: texture_2d<f32>;
@group(0) @binding(3) var source: texture_2d<f32>;
@group(0) @binding(4) var dest: texture_storage_2d<rgba32float, write>;

// How much texel b supports texel a (both of the finer level, both with geometry): Eq. 5's
// depth Gaussian g3, measured as the distance of b's point from a's tangent plane relative to
// their separation (the slope of the step between them, sigma 0.1). Measured on sshgi's Cornell
// box (energy against the reference / FLIP): Eq. 5's g3 as a depth difference relative to the
// distance, is large between neighbours on any surface seen at a grazing angle, so the side
// walls, floor and ceiling lost every vote at their borders and eroded level by level (0.698 /
// 0.2526); the slope with the normal Gaussian g2 (sigma 0.2) 0.863 / 0.1551; the slope alone
// 0.881 / 0.1410, against 0.890 / 0.1414 for the earlier nearest-of-agreeing-siblings rule. A
// crease between two surfaces is a steep slope, so the slope covers g2's job there.
// `pa`, `na`: a's point and normal (the caller decodes them once for all four neighbours).
fn support(pa: vec3<f32>, na: vec3<f32>, b: vec4<f32>) -> f32 {
    let delta = pyramid_point(frame, b) - pa;
    let slope = dot(na, delta) / (0.1 * max(length(delta), 1.0e-6));
    return exp(-0.5 * slope * slope);
}

@compute @workgroup_size(8, 8, 1)
fn seed(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(dest);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    let p = position_at(frame, depth_tex, id.xy);
    if p.w <= 0.0 {
        textureStore(dest, id.xy, vec4<f32>(0.0));
        return;
    }
    let d = length(p.xyz - frame.camera_position.xyz);
    let index = f32(id.y * size.x + id.x);
    textureStore(dest, id.xy, vec4<f32>(d, textureLoad(normal_tex, id.xy, 0).zw, 1.0 + index));
}

@compute @workgroup_size(8, 8, 1)
fn reduce(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(dest);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    let fine = vec2<i32>(textureDimensions(source));
    // g1 of the four L1 neighbours (1 texel, sigma 1); the child itself weighs 1.
    let g1 = exp(-0.5);
    var offsets = array<vec2<i32>, 4>(vec2<i32>(-1, 0), vec2<i32>(1, 0), vec2<i32>(0, -1), vec2<i32>(0, 1));
    var best = vec4<f32>(0.0);
    var best_score = -1.0;
    var best_count = 0.0;
    var background_count = 0.0;
    for (var i = 0; i < 4; i = i + 1) {
        let c = min(vec2<i32>(id.xy) * 2 + vec2<i32>(i & 1, i >> 1), fine - 1);
        let child = textureLoad(source, c, 0);
        let geometry = child.a > 0.5;
        let pa = pyramid_point(frame, child);
        let na = oct_decode(child.gb);
        var score = 1.0;
        var count = 1.0;
        for (var k = 0; k < 4; k = k + 1) {
            let q = c + offsets[k];
            if any(q < vec2<i32>(0)) || any(q >= fine) {
                continue;
            }
            let n = textureLoad(source, q, 0);
            if (n.a > 0.5) == geometry {
                count = count + g1;
                if geometry {
                    score = score + g1 * support(pa, na, n);
                }
            }
        }
        if !geometry {
            background_count = max(background_count, count);
            continue;
        }
        // Ties go to the nearer surface.
        if score > best_score + 1.0e-4 || (abs(score - best_score) <= 1.0e-4 && child.r < best.r) {
            best = child;
            best_score = score;
            best_count = count;
        }
    }
    if background_count > best_count {
        best = vec4<f32>(0.0);
    }
    textureStore(dest, id.xy, best);
}
