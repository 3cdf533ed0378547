// ISM pass P8: pull-push hole filling of the ISM atlas (Grossman & Dally 1998, Marroquim et al.
// 2008; Ritschel et al. 2008's threshold times 2^level, but relative to the depth compared
// instead of their 5% of the scene extent). Every level holds atlas words (`ism_pack` in
// `common/vpl.wgsl`: 17-bit depth, all ones empty); the coarse levels' name no point. Tiles are
// powers of two, so 2x2 reductions never mix two VPLs' maps. The push marks the finest-level
// texels it fills with the lowest bit (a depth without a point), so the
// inspector can show the atlas before and after hole filling from the one buffer.
#import common/vpl.wgsl
struct PullPushParams {
    // fine side (texels), level of the fine side (0 = finest), first fine row, unused.
    counts: vec4<u32>,
    // relative threshold tau (two depths more than tau x depth x 2^level apart are two
    // surfaces), unused...
    params: vec4<f32>,
}

@group(0) @binding(0) var<uniform> pp: PullPushParams;
@group(0) @binding(1) var<storage, read_write> fine: array<u32>;
@group(0) @binding(2) var<storage, read_write> coarse: array<u32>;

fn threshold(depth: f32) -> f32 {
    return pp.params.x * depth * f32(1u << pp.counts.y);
}

@compute @workgroup_size(8, 8, 1)
fn pull(@builtin(global_invocation_id) gid: vec3<u32>) {
    let fs = pp.counts.x;
    let cs = fs / 2u;
    let id = vec2<u32>(gid.x, gid.y + pp.counts.z / 2u);
    if id.x >= cs || id.y >= cs {
        return;
    }
    let b = id.xy * 2u;
    let v = array<f32, 4>(
        ism_depth(fine[b.y * fs + b.x]),
        ism_depth(fine[b.y * fs + b.x + 1u]),
        ism_depth(fine[(b.y + 1u) * fs + b.x]),
        ism_depth(fine[(b.y + 1u) * fs + b.x + 1u]),
    );
    var nearest = 1.0;
    for (var i = 0; i < 4; i = i + 1) {
        nearest = min(nearest, v[i]);
    }
    var sum = 0.0;
    var count = 0.0;
    for (var i = 0; i < 4; i = i + 1) {
        if v[i] < 1.0 && v[i] - nearest <= threshold(nearest) {
            sum = sum + v[i];
            count = count + 1.0;
        }
    }
    var out = ISM_EMPTY;
    if count > 0.0 {
        out = ism_pack(sum / count, 0u);
    }
    coarse[id.y * cs + id.x] = out;
}

// One thread per coarse texel fills its 2x2 fine texels (one coarse read for four writes).
@compute @workgroup_size(8, 8, 1)
fn push(@builtin(global_invocation_id) gid: vec3<u32>) {
    let fs = pp.counts.x;
    let cs = fs / 2u;
    let id = vec2<u32>(gid.x, gid.y + pp.counts.z / 2u);
    if id.x >= cs || id.y >= cs {
        return;
    }
    let c = coarse[id.y * cs + id.x];
    if c == ISM_EMPTY {
        return;
    }
    let mark = select(0u, 1u, pp.counts.y == 0u);
    // Only empty texels are filled. Ritschel's push also overwrote texels farther than the
    // coarse depth (background seen through a hole in a nearer surface), which dilated every
    // silhouette by up to a coarse texel: at doorways that was a false shadow (with it at the
    // finest level only, the three rooms read 0.59 of the reference's energy, the unlit room
    // 0.51; without it 0.66 and 0.57, at splat radius 1.25, `ism_probe`, mean of 16 frames).
    // Splats clipped at open edges and sized to close the surfaces do its job.
    for (var k = 0u; k < 4u; k = k + 1u) {
        let f = id * 2u + vec2<u32>(k & 1u, k >> 1u);
        let i = f.y * fs + f.x;
        if fine[i] == ISM_EMPTY {
            fine[i] = c | mark;
        }
    }
}
