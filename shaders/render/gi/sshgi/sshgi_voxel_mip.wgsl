// sshgi voxel levels: the start level's columns (the gathers march them, `sshgi_visibility.wgsl`)
// from the view's, 2x2 at a time. Each coarse column is the OR of its children's 128-bit columns
// (depth stays 128 slices): a voxel is solid where any of the pixels it covers is. The paper ANDs
// them (a coarse voxel solid only where all four are), which erodes a wall a pixel or two wide on
// screen away: the walled floor of `tests/integration/sshgi.rs` kept 30% of the light leaking through its
// wall at a half-resolution start level, none with OR. OR dilates occluders by up to a coarse
// texel at their silhouettes instead; the march skips two columns at each end for the surfaces
// the segment starts and ends on (one-bounce Cornell box against a one-bounce reference, 256x144
// and ¼ start, before the pyramid named its pixels and voted by Eq. 5: FLIP 0.1019 with OR, 0.1101
// with the paper's AND at every level, 0.1090 without visibility).

struct VoxelMipParams {
    // fine width, fine height, coarse width, coarse height.
    sizes: vec4<u32>,
}

@group(0) @binding(0) var<uniform> mp: VoxelMipParams;
@group(0) @binding(1) var<storage, read> fine: array<vec4<u32>>;
@group(0) @binding(2) var<storage, read_write> coarse: array<vec4<u32>>;

@compute @workgroup_size(8, 8, 1)
fn reduce(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= mp.sizes.z || id.y >= mp.sizes.w {
        return;
    }
    var column = vec4<u32>(0u);
    for (var i = 0u; i < 4u; i = i + 1u) {
        let c = min(id.xy * 2u + vec2<u32>(i & 1u, i >> 1u), mp.sizes.xy - 1u);
        column = column | fine[c.y * mp.sizes.x + c.x];
    }
    coarse[id.y * mp.sizes.z + id.x] = column;
}
