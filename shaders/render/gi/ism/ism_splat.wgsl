// ISM pass P7: imperfect shadow maps by point splatting (Ritschel et al. 2008 as used by Knecht
// 2009). Each scene sample point belongs to one VPL (contiguous blocks of points per VPL) and is
// splatted as a small box of normalised distance into that VPL's paraboloid tile of the atlas
// with an atomic min (positive floats keep their order as u32). `clear` empties the atlas (1.0).
// Each bounce's VPL set has its own block of tiles (`sets.x` is the set's first VPL).
#import common/onb.wgsl
#import common/vpl.wgsl

struct SplatParams {
    // VPL count, points, tile side r, tiles per row C.
    counts: vec4<u32>,
    // 1 / d_max (normalised distance), splat size constant, max splat texels, unused.
    params: vec4<f32>,
    // first VPL (and atlas tile) of the set being splatted, unused x3.
    sets: vec4<u32>,
}


@group(0) @binding(0) var<uniform> sp: SplatParams;
@group(0) @binding(1) var<storage, read> points: array<vec4<f32>>;
@group(0) @binding(2) var<storage, read> vpls: array<Vpl>;
@group(0) @binding(3) var<storage, read_write> atlas: array<atomic<u32>>;

@compute @workgroup_size(8, 8, 1)
fn clear(@builtin(global_invocation_id) id: vec3<u32>) {
    let side = sp.counts.z * sp.counts.w;
    if id.x < side && id.y < side {
        atomicStore(&atlas[id.y * side + id.x], bitcast<u32>(1.0));
    }
}

@compute @workgroup_size(64, 1, 1)
fn splat(@builtin(global_invocation_id) id: vec3<u32>) {
    let n_vpl = sp.counts.x;
    let n_points = sp.counts.y;
    if id.x >= n_points {
        return;
    }
    let per = max(n_points / n_vpl, 1u);
    let k = id.x / per;
    if k >= n_vpl {
        return;
    }
    let tile = sp.sets.x + k;
    let vpl = vpls[tile];
    if vpl.position.w <= 0.0 {
        return;
    }
    let pb = paraboloid(vpl.position.xyz, vpl.normal.xyz, points[id.x].xyz);
    if pb.w <= 0.0 {
        return;
    }
    let r = sp.counts.z;
    let c = sp.counts.w;
    let side = r * c;
    let depth = min(pb.z * sp.params.x, 1.0);
    let origin = vec2<i32>(i32((tile % c) * r), i32((tile / c) * r));
    let texel = vec2<i32>(pb.xy * f32(r));
    // Closer points cover more texels: size ~ constant / distance, clamped.
    let size = i32(clamp(sp.params.y / max(pb.z * sp.params.x, 1.0e-4), 1.0, sp.params.z));
    let half = size / 2;
    for (var dy = -half; dy < size - half; dy = dy + 1) {
        for (var dx = -half; dx < size - half; dx = dx + 1) {
            let t = texel + vec2<i32>(dx, dy);
            if t.x < 0 || t.y < 0 || t.x >= i32(r) || t.y >= i32(r) {
                continue;
            }
            let a = origin + t;
            // Even bit patterns: pull-push marks the texels it fills with the lowest bit.
            atomicMin(&atlas[u32(a.y) * side + u32(a.x)], bitcast<u32>(depth) & ~1u);
        }
    }
}
