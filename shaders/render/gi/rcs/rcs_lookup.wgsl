// The cache's irradiance at an arbitrary world point (a surface a record's hemisphere sees), for
// the bounces after the first: the weighted mean of the records whose zone holds the point,
// through the world hash grid (each record is listed in every cell its zone a R_k overlaps, so
// one cell answers). Plain records without gradients: this is the next bounce's source, not a
// pixel. Requires rcs_common.wgsl and bindings `records`, `grid`, `grid_cells`, `grid_items`.

// rgb = irradiance, a = the summed weight (0: no record listed in the point's cell faces its
// way; negative: only records whose zones miss the point, extrapolated).
fn cache_irradiance(p: vec3<f32>, n: vec3<f32>) -> vec4<f32> {
    if grid.table.z == 0u {
        return vec4<f32>(0.0);
    }
    let cell = vec3<i32>(floor((p - grid.origin.xyz) / grid.origin.w));
    let entry = grid_cells[grid_hash(cell, grid.table.x)];
    let threshold = 1.0 / bitcast<f32>(grid.table.y);
    var sum = vec4<f32>(0.0);
    // Beyond every zone: the records listed here that face the same way, by Ward's weight
    // (an extrapolation, where classical irradiance caching would make a record).
    var beyond = vec4<f32>(0.0);
    for (var i = 0u; i < entry.y; i = i + 1u) {
        let r = records[grid_items[entry.x + i]];
        let w = ward_weight(r, p, n);
        if w > threshold {
            sum = sum + vec4<f32>(r.irradiance.rgb * w, w);
        } else if w > 0.0 && dot(n, r.normal.xyz) > 0.9 {
            beyond = beyond + vec4<f32>(r.irradiance.rgb * w, w);
        }
    }
    if sum.a <= 0.0 {
        if beyond.a <= 0.0 {
            return vec4<f32>(0.0);
        }
        return vec4<f32>(beyond.rgb / beyond.a, -beyond.a);
    }
    return vec4<f32>(sum.rgb / sum.a, sum.a);
}
