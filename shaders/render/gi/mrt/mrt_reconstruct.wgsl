// MRT pass D (Loos 2015 §3.6.3 steps 3 and 5): each texel's indirect light, E / pi of a white
// receiver: the block's own U_b b (face by face, U_b b_g scaled by the stretch correction of
// light from face g on this texel's face) plus, for every interface entering its block, the surface
// response U_r r at the texel's row (U_r laid out for the canonical entry, the rows turned to
// this interface at level assembly), each with the stretch correction of its face
// (`precompute::mrt::warp`). `within` keeps U_b b alone for the inspector.
#import render/gi/mrt/mrt_common.wgsl

@group(0) @binding(0) var<uniform> mp: MrtParams;
@group(0) @binding(1) var<storage, read> blocks: array<Block>;
@group(0) @binding(2) var<storage, read> texels: array<Texel>;
@group(0) @binding(3) var<storage, read> matrices: array<f32>;
@group(0) @binding(4) var<storage, read> u_r: array<f32>;
@group(0) @binding(5) var<storage, read> slots: array<vec4<u32>>;
@group(0) @binding(6) var<storage, read> rows: array<u32>;
@group(0) @binding(7) var<storage, read> b: array<vec4<f32>>;
@group(0) @binding(8) var<storage, read> r: array<vec4<f32>>;
@group(0) @binding(9) var<storage, read_write> indirect: array<vec4<f32>>;
@group(0) @binding(10) var<storage, read_write> within: array<vec4<f32>>;
// Per entry of `rows`: the stretch correction of the entering light on that texel's face.
@group(0) @binding(11) var<storage, read> row_scales: array<f32>;
// Per block, 6 x 6: the stretch correction of light from face slot g on face slot f.
@group(0) @binding(12) var<storage, read> own_scales: array<f32>;

@compute @workgroup_size(64, 1, 1)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= mp.counts.y {
        return;
    }
    let x = u32(texels[i].normal.w + 0.5);
    let blk = blocks[x];
    let row = i - blk.texels.x;
    let k_b = mp.counts.w;
    let k_r = mp.sizes.x;
    var own = vec3<f32>(0.0);
    let u = blk.texels.w + row * k_b;
    let f = row / (mp.sizes.y * mp.sizes.y);
    for (var g = 0u; g < 6u; g = g + 1u) {
        var from_g = vec3<f32>(0.0);
        for (var j = 0u; j < k_b; j = j + 1u) {
            from_g = from_g + matrices[u + j] * b[(x * 6u + g) * k_b + j].rgb;
        }
        own = own + from_g * own_scales[x * 36u + g * 6u + f];
    }
    var total = own;
    for (var k = 0u; k < 4u; k = k + 1u) {
        let s = blk.slots[k];
        if s == MRT_NONE {
            continue;
        }
        let at = slots[s].w + row;
        let rr = rows[at];
        if rr == MRT_NONE {
            continue;
        }
        var entering = vec3<f32>(0.0);
        for (var j = 0u; j < k_r; j = j + 1u) {
            entering = entering + u_r[rr * k_r + j] * r[s * k_r + j].rgb;
        }
        total = total + entering * row_scales[at];
    }
    indirect[i] = vec4<f32>(total, 1.0);
    within[i] = vec4<f32>(own, 1.0);
}
