// sshgi indirect visibility (Soler et al. 2010, digest C.2 "voxel visibility"): the segment from
// a receiver texel to a sample texel is marched through the level's voxel columns. In screen
// space 1/z is affine, so the segment's view depth over each column it crosses is exact; its
// slice interval is ANDed with the column, and any common bit is an occluder. The endpoints lie
// on solid boundaries, so two columns at each end are skipped (the start level's columns are
// ORed from the view's, so a surface's own column can hold its neighbour's nearer depth; one
// column read 0.894 of the one-bounce reference's indirect light on the Cornell box, two 0.923,
// three 0.938 with FLIP 0.1005 / 0.1019 / 0.1038, before the pyramid's voting and point changes) and the interval is moved one slice towards the
// camera (a segment leaving a visible surface runs just in front of it). The including shader binds `voxels: array<vec4<u32>>` (the start
// level's columns, row-major), `gp.vox` = (near, far, slices per metre, on) and `gp.grid` =
// (their width, columns per gather texel, their height, unused).

// Bits a..b (inclusive, clamped to 0..127) of a 128-bit column.
fn slice_bits(a: i32, b: i32) -> vec4<u32> {
    var m = vec4<u32>(0u);
    let lo = max(a, 0);
    let hi = min(b, 127);
    if hi < lo {
        return m;
    }
    for (var w = 0; w < 4; w = w + 1) {
        let w0 = 32 * w;
        if hi < w0 || lo > w0 + 31 {
            continue;
        }
        let from_bit = u32(max(lo, w0) - w0);
        let to_bit = u32(min(hi, w0 + 31) - w0);
        m[w] = (0xffffffffu >> (31u - to_bit)) & (0xffffffffu << from_bit);
    }
    return m;
}

// Whether the segment from texel t (view depth zt) to texel y (depth zy) of the gather level
// passes through a solid voxel. The columns marched are the start level's (`gp.grid`: their
// width, and 2^k of them per texel of gather level k), not level k's own AND-reduced ones: the
// paper's per-level AND erodes a wall a few pixels thick away at the coarse levels, where
// long-range light is gathered (the walled floor of `tests/sshgi.rs` leaked 86% of its light
// with level-k columns at three levels). Level k has 4^k fewer texels and 2^k times longer
// marches, so the marches of all levels cost at most twice the start level's.
fn voxel_occluded(t: vec2<i32>, y: vec2<i32>, zt: f32, zy: f32) -> bool {
    let scale = f32(gp.grid.y);
    let a = (vec2<f32>(t) + 0.5) * scale - 0.5;
    let d = (vec2<f32>(y) + 0.5) * scale - 0.5 - a;
    let steps = i32(ceil(max(abs(d.x), abs(d.y))));
    // The columns of the surfaces the segment starts and ends on.
    let skip = 2;
    if steps <= 2 * skip {
        return false;
    }
    let width = i32(gp.grid.x);
    let height = i32(gp.grid.z);
    let inv_t = 1.0 / zt;
    let inv_y = 1.0 / zy;
    let slice = 1.0 / gp.vox.z;
    for (var j = skip; j <= steps - skip; j = j + 1) {
        let m0 = (f32(j) - 0.5) / f32(steps);
        let m1 = (f32(j) + 0.5) / f32(steps);
        let za = 1.0 / mix(inv_t, inv_y, m0) - slice;
        let zb = 1.0 / mix(inv_t, inv_y, m1) - slice;
        let lo = i32(floor((min(za, zb) - gp.vox.x) * gp.vox.z));
        let hi = i32(floor((max(za, zb) - gp.vox.x) * gp.vox.z));
        let c = clamp(vec2<i32>(round(a + d * (f32(j) / f32(steps)))), vec2<i32>(0), vec2<i32>(width - 1, height - 1));
        let column = voxels[c.y * width + c.x];
        if any((column & slice_bits(lo, hi)) != vec4<u32>(0u)) {
            return true;
        }
    }
    return false;
}
