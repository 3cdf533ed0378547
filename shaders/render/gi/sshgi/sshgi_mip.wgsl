// sshgi illumination levels (Soler et al. 2010, Sec. 4, "Filtering of mipmap levels" and
// "Multi-bounce computation"): the start level's outgoing radiance as the box average of the
// view's 2^s x 2^s blocks, coarser levels by 2x2 box averages (the paper does not say how it
// reduces illumination; depth and normal are voted in `render/pyramid.wgsl`), a later bounce's
// start level as reflectance x the previous bounce's E / pi, and the sum of two levels (bounces).
// The start level's senders are diffuse: the first bounce's send the lighting pass's `exitance`
// (a glossy lobe's share of the light in every direction), later bounces' their reflectance,
// albedo + the lobe's share of diffuse light (`reflectance_seed`).
#import common/brdf.wgsl

struct MipParams {
    // block side (2^s, `box_seed`, `reflectance_seed`), unused x3.
    counts: vec4<u32>,
}

@group(0) @binding(0) var<uniform> mp: MipParams;
@group(0) @binding(1) var a_tex: texture_2d<f32>;
@group(0) @binding(2) var b_tex: texture_2d<f32>;
@group(0) @binding(3) var dest: texture_storage_2d<rgba32float, write>;

// The mean over the block of side counts.x texels at `id` (clamped at a's border) of the texels
// that hold geometry, alpha = their coverage: of a's colour weighted by b's alpha (the G-buffer
// albedo's coverage), or with `reflectance` of the senders' reflectance, albedo (a, alpha its
// coverage) + what the glossy lobe (b: the G-buffer's specular colour and roughness) reflects of
// diffuse light. The depth and normal levels take a surface by vote, so a texel on a silhouette
// must carry that surface's light, not a mean with the empty background.
fn block_mean(id: vec2<u32>, reflectance: bool) -> vec4<f32> {
    let n = mp.counts.x;
    let src = textureDimensions(a_tex);
    var sum = vec3<f32>(0.0);
    var covered = 0.0;
    for (var y = 0u; y < n; y = y + 1u) {
        for (var x = 0u; x < n; x = x + 1u) {
            let q = min(id * n + vec2<u32>(x, y), src - 1u);
            let a = textureLoad(a_tex, q, 0);
            let b = textureLoad(b_tex, q, 0);
            var value = a.rgb;
            var w = b.a;
            if reflectance {
                value = sender_reflectance(a.rgb, b.rgb, b.a);
                w = a.a;
            }
            sum = sum + value * w;
            covered = covered + w;
        }
    }
    return vec4<f32>(sum / max(covered, 1.0e-6), covered / f32(n * n));
}

// dest = the block mean at id (`block_mean`).
fn seed(id: vec3<u32>, reflectance: bool) {
    let size = textureDimensions(dest);
    if id.x < size.x && id.y < size.y {
        textureStore(dest, id.xy, block_mean(id.xy, reflectance));
    }
}

// dest = a's block mean (the start level's light).
@compute @workgroup_size(8, 8, 1)
fn box_seed(@builtin(global_invocation_id) id: vec3<u32>) {
    seed(id, false);
}

// dest = the senders' reflectance, block mean (the start level's, for later bounces).
@compute @workgroup_size(8, 8, 1)
fn reflectance_seed(@builtin(global_invocation_id) id: vec3<u32>) {
    seed(id, true);
}

// dest = the mean of a's 2x2 children weighted by their coverage (alpha), alpha = its mean.
@compute @workgroup_size(8, 8, 1)
fn reduce(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(dest);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    let src = textureDimensions(a_tex);
    var sum = vec3<f32>(0.0);
    var covered = 0.0;
    for (var i = 0u; i < 4u; i = i + 1u) {
        let v = textureLoad(a_tex, min(id.xy * 2u + vec2<u32>(i & 1u, i >> 1u), src - 1u), 0);
        sum = sum + v.rgb * v.a;
        covered = covered + v.a;
    }
    textureStore(dest, id.xy, vec4<f32>(sum / max(covered, 1.0e-6), covered * 0.25));
}

// dest = a x b (albedo x E / pi: the outgoing radiance a later bounce gathers), alpha = a's
// coverage.
@compute @workgroup_size(8, 8, 1)
fn product(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(dest);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    let albedo = textureLoad(a_tex, id.xy, 0);
    textureStore(dest, id.xy, vec4<f32>(albedo.rgb * textureLoad(b_tex, id.xy, 0).rgb, albedo.a));
}

// dest = a + b (the bounces' sum).
@compute @workgroup_size(8, 8, 1)
fn add(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(dest);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    textureStore(dest, id.xy, vec4<f32>(textureLoad(a_tex, id.xy, 0).rgb + textureLoad(b_tex, id.xy, 0).rgb, 1.0));
}

// dest = a + b, alpha = a's coverage (the start level's direct term plus the sky-lit surfaces'
// light, `sshgi_sky.wgsl`: the first bounce's senders).
@compute @workgroup_size(8, 8, 1)
fn add_lit(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(dest);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    let a = textureLoad(a_tex, id.xy, 0);
    textureStore(dest, id.xy, vec4<f32>(a.rgb + textureLoad(b_tex, id.xy, 0).rgb, a.a));
}
