// MRT pass B (Loos 2015 §4.4): b = T_{d->b} l_d per block, the most expensive indirect stage,
// kept per emitting face (b_g over face slot g's texels; b = the sum of the six), so that the
// block's own light gets each face's stretch correction (`precompute::mrt::warp`). One workgroup
// per (mode, block, face slot): 64 threads each sum a strided share of the face's products, then
// a tree reduction in workgroup memory (WGSL has no float atomics).
#import render/gi/mrt/mrt_common.wgsl
#import common/workgroup_sum.wgsl

@group(0) @binding(0) var<uniform> mp: MrtParams;
@group(0) @binding(1) var<storage, read> blocks: array<Block>;
@group(0) @binding(2) var<storage, read> matrices: array<f32>;
@group(0) @binding(3) var<storage, read> l_d: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read_write> b: array<vec4<f32>>;

@compute @workgroup_size(64, 1, 1)
fn cs_main(@builtin(workgroup_id) wg: vec3<u32>, @builtin(local_invocation_index) li: u32) {
    let mode = wg.x;
    let x = wg.y;
    let g = wg.z;
    let blk = blocks[x];
    let n = blk.texels.y;
    let per = mp.sizes.y * mp.sizes.y;
    let row = blk.texels.z + mode * n;
    // Face slots past the shape's present faces sum nothing.
    let first = min(g * per, n);
    let last = min(first + per, n);
    var sum = vec3<f32>(0.0);
    for (var i = first + li; i < last; i = i + 64u) {
        sum = sum + matrices[row + i] * l_d[blk.texels.x + i].rgb;
    }
    workgroup_sum(li, vec4<f32>(sum, 0.0));
    if li == 0u {
        b[(x * 6u + g) * mp.counts.w + mode] = vec4<f32>(partial[0].xyz, 0.0);
    }
}
