// ISM pass P10 (interleaved VPL shading, Knecht 2009 section 3.4): pixel (x, y) belongs to
// interleave tile (x mod n, y mod n) and gathers only that tile's contiguous block of N / n^2
// VPLs of every bounce's set, each tested against its imperfect shadow map. Output is E / pi (the lighting composite
// multiplies by albedo): sum of V Phi cos_s cos_r / (pi^2 max(d^2, d_min^2)).
#import common/frame.wgsl
#import common/octahedral.wgsl
#import common/onb.wgsl
#import common/vpl.wgsl

struct ShadeParams {
    // VPL count, tile side r, tiles per row C, interleave n.
    counts: vec4<u32>,
    // 1 / d_max, depth bias (normalised), d_min^2, unused.
    params: vec4<f32>,
    // VPL sets (bounces), unused x3.
    sets: vec4<u32>,
}


@group(0) @binding(0) var<uniform> frame: Frame;
@group(0) @binding(1) var<uniform> sh: ShadeParams;
@group(0) @binding(2) var<storage, read> vpls: array<Vpl>;
@group(0) @binding(3) var<storage, read> atlas: array<u32>;
@group(0) @binding(4) var depth_tex: texture_depth_2d;
@group(0) @binding(5) var normal_tex: texture_2d<f32>;
@group(0) @binding(6) var out_indirect: texture_storage_2d<rgba32float, write>;

const PI: f32 = 3.14159265358979;

@compute @workgroup_size(8, 8, 1)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = vec2<u32>(frame.size.xy);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    let depth = textureLoad(depth_tex, id.xy, 0);
    if depth <= 0.0 {
        textureStore(out_indirect, id.xy, vec4<f32>(0.0));
        return;
    }
    let p = world_from_pixel(frame, id.xy, depth);
    let enc = textureLoad(normal_tex, id.xy, 0);
    let n = oct_decode(enc.xy);
    let ng = oct_decode(enc.zw);
    let ni = sh.counts.w;
    let tile = (id.y % ni) * ni + (id.x % ni);
    let per = max(sh.counts.x / (ni * ni), 1u);
    let r = sh.counts.y;
    let c = sh.counts.z;
    let side = r * c;
    var sum = vec3<f32>(0.0);
    for (var i = 0u; i < per * sh.sets.x; i = i + 1u) {
        let bounce = i / per;
        let j = i % per;
        if tile * per + j >= sh.counts.x {
            continue;
        }
        let k = bounce * sh.counts.x + tile * per + j;
        let vpl = vpls[k];
        if vpl.position.w < 0.5 {
            continue;
        }
        let to_p = p - vpl.position.xyz;
        let d2 = max(dot(to_p, to_p), 1.0e-8);
        let dir = to_p * inverseSqrt(d2);
        let cos_s = dot(vpl.normal.xyz, dir);
        // One-sided receivers: light from behind the geometric normal adds nothing.
        if cos_s <= 0.0 || dot(ng, -dir) <= 0.0 {
            continue;
        }
        let cos_r = max(dot(n, -dir), 0.0);
        let pb = paraboloid(vpl.position.xyz, vpl.normal.xyz, p);
        let texel = min(vec2<u32>(pb.xy * f32(r)), vec2<u32>(r - 1u));
        let a = vec2<u32>((k % c) * r, (k / c) * r) + texel;
        let stored = bitcast<f32>(atlas[a.y * side + a.x]);
        if pb.z * sh.params.x > stored + sh.params.y {
            continue;
        }
        sum = sum + vpl.power.rgb * cos_s * cos_r / (PI * PI * max(d2, sh.params.z));
    }
    textureStore(out_indirect, id.xy, vec4<f32>(sum, 1.0));
}
