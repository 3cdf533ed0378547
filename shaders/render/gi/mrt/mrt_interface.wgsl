// MRT pass C (Loos 2015 §3.6.3 step 4, §4.5.1): r = T_{b->r} b, the light entering each directed
// interface as k_r response coefficients, summed over every source block whose light the level's
// propagation carried there (one k_r x k_b matrix each). One thread per (interface, mode).
#import render/gi/mrt/mrt_common.wgsl

@group(0) @binding(0) var<uniform> mp: MrtParams;
@group(0) @binding(1) var<storage, read> slots: array<vec4<u32>>;
@group(0) @binding(2) var<storage, read> entries: array<vec4<u32>>;
@group(0) @binding(3) var<storage, read> transfer: array<f32>;
@group(0) @binding(4) var<storage, read> b: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read_write> r: array<vec4<f32>>;

@compute @workgroup_size(64, 1, 1)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let k_r = mp.sizes.x;
    let k_b = mp.counts.w;
    if id.x >= mp.counts.z * k_r {
        return;
    }
    let slot = slots[id.x / k_r];
    let mode = id.x % k_r;
    var sum = vec3<f32>(0.0);
    for (var e = slot.x; e < slot.x + slot.y; e = e + 1u) {
        let entry = entries[e];
        let m = entry.y + mode * k_b;
        for (var j = 0u; j < k_b; j = j + 1u) {
            // b of the block's whole direct light: the sum of its faces' shares.
            var bj = vec3<f32>(0.0);
            for (var g = 0u; g < 6u; g = g + 1u) {
                bj = bj + b[(entry.x * 6u + g) * k_b + j].rgb;
            }
            sum = sum + transfer[m + j] * bj;
        }
    }
    r[id.x] = vec4<f32>(sum, 0.0);
}
