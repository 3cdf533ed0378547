// The shared depth/normal pyramid (render::pyramid): level 0 holds each pixel's linear distance
// to the camera (r), its octahedral geometric normal (gb) and, where there is geometry, a = 1 +
// the pixel's row-major index (0: none; exact in f32 up to 16M pixels), so a coarse texel knows
// which pixel's surface it copied and its point can be rebuilt on that pixel's own ray
// (`pyramid_point` in `common/frame.wgsl`). Rebuilt on the coarse texel's centre ray instead, the
// copied distance put the point up to half a texel's depth slope off its surface, and coplanar
// neighbours lit each other: sshgi's Cornell box read 0.929 of the reference's energy that way,
// 0.890 with the points on their surfaces, whose first bounce has the better FLIP (0.1019);
// each coarser texel takes one of its 2x2 children whole, chosen by vote (the child that agrees
// in distance and normal with most of its siblings; ties go to the nearest), so a level never
// holds an averaged depth or normal that no surface has.
#import common/frame.wgsl
#import common/octahedral.wgsl

@group(0) @binding(0) var<uniform> frame: Frame;
@group(0) @binding(1) var depth_tex: texture_depth_2d;
@group(0) @binding(2) var normal_tex: texture_2d<f32>;
@group(0) @binding(3) var source: texture_2d<f32>;
@group(0) @binding(4) var dest: texture_storage_2d<rgba32float, write>;

// Two children represent the same surface within 5% of distance and 25 degrees of normal.
fn agree(a: vec4<f32>, b: vec4<f32>) -> bool {
    if a.a < 0.5 || b.a < 0.5 {
        return false;
    }
    let close = abs(a.r - b.r) <= 0.05 * max(a.r, b.r);
    return close && dot(oct_decode(a.gb), oct_decode(b.gb)) >= 0.9;
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
    let fine = textureDimensions(source);
    var child: array<vec4<f32>, 4>;
    for (var i = 0u; i < 4u; i = i + 1u) {
        let c = min(id.xy * 2u + vec2<u32>(i & 1u, i >> 1u), fine - 1u);
        child[i] = textureLoad(source, c, 0);
    }
    var best = vec4<f32>(0.0);
    var best_votes = -1;
    for (var i = 0u; i < 4u; i = i + 1u) {
        if child[i].a < 0.5 {
            continue;
        }
        var votes = 0;
        for (var j = 0u; j < 4u; j = j + 1u) {
            if agree(child[i], child[j]) {
                votes = votes + 1;
            }
        }
        if votes > best_votes || (votes == best_votes && child[i].r < best.r) {
            best = child[i];
            best_votes = votes;
        }
    }
    textureStore(dest, id.xy, best);
}
