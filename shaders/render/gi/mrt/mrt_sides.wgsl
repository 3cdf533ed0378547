// MRT pass E: the light on the closed part of every partly open side (the wall around a
// doorway in a room's whole side, which has no texels of its own): per opening position, the
// irradiance / pi of the light reaching the side from inside its block, summed over every
// source block (one P^2 x k_b matrix each, `precompute::mrt::level::Transfer::sides`). One
// thread per (position, side); written after the block texels in the indirect buffer.
#import render/gi/mrt/mrt_common.wgsl

@group(0) @binding(0) var<uniform> mp: MrtParams;
@group(0) @binding(1) var<storage, read> sides: array<vec4<u32>>;
@group(0) @binding(2) var<storage, read> side_entries: array<vec4<u32>>;
@group(0) @binding(3) var<storage, read> side_matrices: array<f32>;
@group(0) @binding(4) var<storage, read> b: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read_write> indirect: array<vec4<f32>>;

@compute @workgroup_size(64, 1, 1)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let per_side = mp.sides.x * mp.sides.x;
    if id.x >= per_side || id.y >= mp.sides.y {
        return;
    }
    let side = sides[id.y];
    let k_b = mp.counts.w;
    var sum = vec3<f32>(0.0);
    for (var e = side.x; e < side.x + side.y; e = e + 1u) {
        let entry = side_entries[e];
        let m = entry.y + id.x * k_b;
        for (var j = 0u; j < k_b; j = j + 1u) {
            // b of the source's whole direct light: the sum of its faces' shares.
            var bj = vec3<f32>(0.0);
            for (var g = 0u; g < 6u; g = g + 1u) {
                bj = bj + b[(entry.x * 6u + g) * k_b + j].rgb;
            }
            sum = sum + side_matrices[m + j] * bj;
        }
    }
    indirect[side.z + id.x] = vec4<f32>(sum, 1.0);
}
