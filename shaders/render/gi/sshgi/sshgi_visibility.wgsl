// sshgi indirect visibility (Soler et al. 2010, Sec. 4, "Visibility computation"): the segment
// between a receiver's and a sender's voted points is marched through voxel columns. In screen
// space 1/z is affine, so the segment's view depth over each column it crosses is exact; its
// slice interval is ANDed with the column, and any common bit is an occluder. The segment runs
// between the view pixels the two points were voted from (`pyramid_pixel`), not between their
// texels' centres: on coarse levels a texel is 2^l view pixels wide and its point may lie half a
// texel from its centre, so a march between centres crossed columns of surfaces in front of the
// real segment (the Cornell box's first bounce found 0.883 of an exact screen-space gather with
// ray-cast visibility, `examples/sshgi_oracle.rs`; from the points' pixels 0.980). The columns are
// the view's OR-reduced to `gp.grid.y` view pixels (`visibility_detail` levels finer than the
// start level): an OR column starts its solid at the nearest of its pixels' surfaces, which
// near the endpoints lies in front of a segment leaving a surface at a grazing angle (quarter
// columns 0.980, half 1.001, full 1.013 of the oracle; full with one column skipped 0.998). The
// endpoints lie on solid boundaries, so two columns at each end are skipped and the interval is
// moved one slice towards the camera (a segment leaving a visible surface runs just in front of
// it). The including shader binds `voxels: array<vec4<u32>>` (the marched columns, row-major),
// `gp.vox` = (near, far, slices per metre, on) and `gp.grid` = (their width, view pixels per
// column, their height, unused).

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

// Whether the segment from the point seen at view pixel pt (view depth zt) to the point seen at
// pixel py (depth zy) passes through a solid voxel. Every level marches the same columns: the
// paper's per-level AND erodes a wall a few pixels thick away at the coarse levels, where
// long-range light is gathered (the walled floor of `tests/integration/sshgi.rs` leaked 86% of its light
// with level-k columns at three levels). Level k has 4^k fewer texels and 2^k times longer
// marches, so the marches of all levels cost at most twice the start level's.
fn voxel_occluded(pt: vec2<f32>, py: vec2<f32>, zt: f32, zy: f32) -> bool {
    // The columns of the surfaces the segment starts and ends on.
    return voxel_occluded_skipping(pt, py, zt, zy, vec2<i32>(2));
}

// `voxel_occluded` with `skip.x` columns skipped at pt's end and `skip.y` at py's (0 at an end
// that lies off any surface: a hidden sender moved off its own, or where the segment was clipped
// to the view).
fn voxel_occluded_skipping(pt: vec2<f32>, py: vec2<f32>, zt: f32, zy: f32, skip: vec2<i32>) -> bool {
    let px = f32(gp.grid.y);
    let a = pt / px - 0.5;
    let d = py / px - 0.5 - a;
    let steps = i32(ceil(max(abs(d.x), abs(d.y))));
    if steps <= skip.x + skip.y {
        return false;
    }
    let width = i32(gp.grid.x);
    let height = i32(gp.grid.z);
    let inv_t = 1.0 / zt;
    let inv_y = 1.0 / zy;
    let slice = 1.0 / gp.vox.z;
    for (var j = skip.x; j <= steps - skip.y; j = j + 1) {
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
