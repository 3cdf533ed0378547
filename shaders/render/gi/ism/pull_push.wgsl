// ISM pass P8: pull-push hole filling of the ISM atlas (Grossman & Dally 1998, Marroquim et al.
// 2008; Ritschel et al. 2008's threshold times 2^level, but relative to the depth compared
// instead of their 5% of the scene extent). Every level holds atlas words (`ism_pack` in
// `common/vpl.wgsl`: 17-bit depth, all ones empty); a coarse word names the point of the
// nearest of its block, which the lookups test rays against where a texel shows a hole
// (`ism_hole_blocks` in `ism_lookup.wgsl`). Tiles are powers of two, so 2x2 reductions never mix
// two VPLs' maps. The push marks the finest-level texels it fills with the lowest bit (a depth
// without a point), so the inspector can show the atlas before and after hole filling.
#import common/vpl.wgsl
struct PullPushParams {
    // fine side (texels), level of the fine side (0 = finest), first fine row, unused.
    counts: vec4<u32>,
    // relative threshold tau (two depths more than tau x depth x 2^level apart are two
    // surfaces), unused...
    params: vec4<f32>,
}

@group(0) @binding(0) var<uniform> pp: PullPushParams;
// The finest level, and the coarse levels each after the finer ones (`level_base` in
// `gather.rs`).
@group(0) @binding(1) var<storage, read_write> atlas: array<u32>;
@group(0) @binding(2) var<storage, read_write> coarse: array<u32>;

// Where level `level` >= 1 starts in `coarse`.
fn coarse_base(level: u32) -> u32 {
    let side = pp.counts.x << pp.counts.y;
    var base = 0u;
    for (var l = 1u; l < level; l = l + 1u) {
        base = base + (side >> l) * (side >> l);
    }
    return base;
}

fn read_fine(i: u32) -> u32 {
    if pp.counts.y == 0u {
        return atlas[i];
    }
    return coarse[coarse_base(pp.counts.y) + i];
}

fn write_fine(i: u32, w: u32) {
    if pp.counts.y == 0u {
        atlas[i] = w;
    } else {
        coarse[coarse_base(pp.counts.y) + i] = w;
    }
}

fn coarse_at(i: u32) -> u32 {
    return coarse_base(pp.counts.y + 1u) + i;
}

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
    let w = array<u32, 4>(
        read_fine(b.y * fs + b.x),
        read_fine(b.y * fs + b.x + 1u),
        read_fine((b.y + 1u) * fs + b.x),
        read_fine((b.y + 1u) * fs + b.x + 1u),
    );
    // The nearest's word names the coarse texel's point, so the lookups can test a ray against
    // the surface around a hole (`ism_lookup.wgsl`); the slot survives every level.
    var nearest = 1.0;
    var named = 0u;
    for (var i = 0; i < 4; i = i + 1) {
        let v = ism_depth(w[i]);
        if v < nearest {
            nearest = v;
            named = ism_slot1(w[i]);
        }
    }
    var sum = 0.0;
    var count = 0.0;
    for (var i = 0; i < 4; i = i + 1) {
        let v = ism_depth(w[i]);
        if v < 1.0 && v - nearest <= threshold(nearest) {
            sum = sum + v;
            count = count + 1.0;
        }
    }
    var out = ISM_EMPTY;
    if count > 0.0 {
        out = ism_pack(sum / count, named);
    }
    coarse[coarse_at(id.y * cs + id.x)] = out;
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
    let c = coarse[coarse_at(id.y * cs + id.x)];
    if c == ISM_EMPTY {
        return;
    }
    // Only empty texels are filled. Ritschel's push also overwrote texels farther than the
    // coarse depth (background seen through a hole in a nearer surface), which dilated every
    // silhouette by up to a coarse texel: at doorways that was a false shadow (with it at the
    // finest level only, the three rooms read 0.59 of the reference's energy, the unlit room
    // 0.51; without it 0.66 and 0.57, at splat radius 1.25, `bouncelab probe`, mean of 16 frames).
    // Splats clipped at open edges and sized to close the surfaces do its job.
    for (var k = 0u; k < 4u; k = k + 1u) {
        let f = id * 2u + vec2<u32>(k & 1u, k >> 1u);
        let i = f.y * fs + f.x;
        if read_fine(i) == ISM_EMPTY {
            // The finest level gets a depth only (a filled texel's point may lie a few texels
            // away; the lookups ask the coarse levels' points themselves).
            write_fine(i, select(c, (c & ~0x7ffeu) | 1u, pp.counts.y == 0u));
        }
    }
}
