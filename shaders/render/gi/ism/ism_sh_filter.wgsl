// Segovia & Wald's screen-space SH filter (their Sec. 3, steps 3 and 4): average
// the incident-radiance SH coefficients of the n x n window that holds each interleave phase
// once (offsets [-n/2, n/2 - 1]), rejecting taps across geometric discontinuities only (other
// object, distance from this pixel's tangent plane >= alpha x scene diameter, geometric normals
// with a cosine <= beta); the shading normal is never tested. Then shade each pixel with its own projected BRDF:
//   L_r = sum_lm L~_lm (k_d Lambda^d_l Y_lm(n_s) + k_s Lambda^phong_l Y_lm(R)),
// R = reflect(-v, n_s), the Blinn-Phong exponent e taken as a Phong lobe of e / 4 around R.
// Outputs: outgoing indirect radiance (rgb, clamped >= 0; a = accepted taps / n^2), and two
// inspector views of the filtered field: DC (mean incident radiance, a = accepted fraction) and
// the band-1 luminance direction (0.5 + 0.5 dir, a = band-2 energy / total).
#import common/frame.wgsl
#import common/octahedral.wgsl
#import common/interleave.wgsl
#import common/sh9.wgsl
#import common/brdf.wgsl
#import common/color.wgsl

struct ShFilterParams {
    // interleave n, unused x3.
    counts: vec4<u32>,
    // alpha (normalised depth), beta (min cosine of geometric normals), depth range, unused.
    params: vec4<f32>,
}

@group(0) @binding(0) var<uniform> frame: Frame;
@group(0) @binding(1) var<uniform> fp: ShFilterParams;
@group(0) @binding(2) var<storage, read> sh_raw: array<u32>;
@group(0) @binding(3) var depth_tex: texture_depth_2d;
@group(0) @binding(4) var normal_tex: texture_2d<f32>;
@group(0) @binding(5) var albedo_tex: texture_2d<f32>;
@group(0) @binding(6) var material_tex: texture_2d<f32>;
@group(0) @binding(7) var id_tex: texture_2d<u32>;
@group(0) @binding(8) var out_radiance: texture_storage_2d<rgba32float, write>;
@group(0) @binding(9) var out_dc: texture_storage_2d<rgba32float, write>;
@group(0) @binding(10) var out_dir: texture_storage_2d<rgba32float, write>;

const SH_WORDS: u32 = 14u;

fn position(pixel: vec2<u32>) -> vec4<f32> {
    return position_at(frame, depth_tex, pixel);
}

@compute @workgroup_size(8, 8, 1)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = vec2<u32>(frame.size.xy);
    if any(id.xy >= size) {
        return;
    }
    let pp = position(id.xy);
    if pp.w < 0.5 {
        textureStore(out_radiance, id.xy, vec4<f32>(0.0));
        textureStore(out_dc, id.xy, vec4<f32>(0.0));
        textureStore(out_dir, id.xy, vec4<f32>(0.0));
        return;
    }
    let n = fp.counts.x;
    let enc = textureLoad(normal_tex, id.xy, 0);
    let ngp = oct_decode(enc.zw);
    let idp = textureLoad(id_tex, id.xy, 0).r;
    let tolerance = fp.params.x * fp.params.z;
    let width = split_block(size, n).x * n;
    let half = i32(n / 2u);
    var f = array<f32, 28>();
    var taps = 0.0;
    for (var dy = -half; dy < i32(n) - half; dy = dy + 1) {
        for (var dx = -half; dx < i32(n) - half; dx = dx + 1) {
            let q = vec2<u32>(clamp(vec2<i32>(id.xy) + vec2<i32>(dx, dy), vec2<i32>(0), vec2<i32>(size) - 1));
            let pq = position(q);
            let ngq = oct_decode(textureLoad(normal_tex, q, 0).zw);
            let same = textureLoad(id_tex, q, 0).r == idp;
            if pq.w < 0.5 || !same || abs(dot(pq.xyz - pp.xyz, ngp)) >= tolerance || dot(ngq, ngp) <= fp.params.y {
                continue;
            }
            let s = split_address(q, size, n);
            let base = (s.y * width + s.x) * SH_WORDS;
            for (var w = 0u; w < SH_WORDS; w = w + 1u) {
                let pair = unpack2x16float(sh_raw[base + w]);
                f[2u * w] = f[2u * w] + pair.x;
                f[2u * w + 1u] = f[2u * w + 1u] + pair.y;
            }
            taps = taps + 1.0;
        }
    }
    let inv = 1.0 / max(taps, 1.0);
    var c = array<vec3<f32>, 9>();
    for (var b = 0u; b < 9u; b = b + 1u) {
        c[b] = vec3<f32>(f[3u * b], f[3u * b + 1u], f[3u * b + 2u]) * inv;
    }
    // The projected BRDF of this pixel: its own (normal-mapped) shading normal and material.
    let ns = oct_decode(enc.xy);
    let v = normalize(frame.camera_position.xyz - pp.xyz);
    let albedo = textureLoad(albedo_tex, id.xy, 0).rgb;
    let mat = textureLoad(material_tex, id.xy, 0);
    let yd = sh9_basis(ns);
    let refl = reflect(-v, ns);
    let ys = sh9_basis(refl);
    let lambda_s = sh9_phong(phong_exponent(mat.a) * 0.25);
    var radiance = vec3<f32>(0.0);
    var band2 = 0.0;
    for (var b = 0u; b < 9u; b = b + 1u) {
        let l = sh9_band(b);
        radiance = radiance + c[b] * (albedo * SH9_LAMBERT[l] * yd[b] + mat.rgb * lambda_s[l] * ys[b]);
        if l == 2u {
            band2 = band2 + dot(c[b], c[b]);
        }
    }
    let accepted = taps / f32(n * n);
    textureStore(out_radiance, id.xy, vec4<f32>(max(radiance, vec3<f32>(0.0)), accepted));
    // Inspector views: DC as mean incident radiance, band-1 luminance direction (y, z, x order).
    textureStore(out_dc, id.xy, vec4<f32>(c[0] * 0.282095, accepted));
    let l1 = vec3<f32>(luminance(c[3]), luminance(c[1]), luminance(c[2]));
    let dir = l1 / max(length(l1), 1.0e-12);
    var total = 0.0;
    for (var b = 0u; b < 9u; b = b + 1u) {
        total = total + dot(c[b], c[b]);
    }
    textureStore(out_dir, id.xy, vec4<f32>(0.5 + 0.5 * dir, band2 / max(total, 1.0e-20)));
}
