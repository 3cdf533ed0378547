// Radiance cache splatting (Gautron et al. 2005): the record layout every rcs pass
// shares (mirrors render::gi::rcs::record::GpuRecord), Ward's weight, the gradient-extrapolated
// irradiance of a record, and the world hash grid the hemisphere renders look the cache up in
// for later bounces (render::gi::rcs::grid builds it).

struct Record {
    // xyz position P_k, w = R_k, the clamped harmonic mean distance (0: free slot).
    position: vec4<f32>,
    // xyz unit normal n_k, w = the times it was computed (bounces it holds).
    normal: vec4<f32>,
    // rgb irradiance E_k (W/m^2), w = the harmonic mean distance before the clamp.
    irradiance: vec4<f32>,
    // Rotational gradient per channel (r, g, b), world space, w unused.
    grad_r: array<vec4<f32>, 3>,
    // Translational gradient per channel, world space, w unused.
    grad_t: array<vec4<f32>, 3>,
    // x = luminance of the irradiance from the directly lit surfaces the check strata saw (the
    // light check compares against it), yzw = the hemisphere camera's tangent (plane +x).
    check: vec4<f32>,
}

// Ward's weight w_k(P) = 1 / (|P - P_k| / R_k + sqrt(1 - n . n_k)), with 1e-3 in the
// denominator against the singularity at the record (it caps w at 1000), and 0 where P lies
// behind the record (Ward's (P - P_k) . (n + n_k) / 2 test at 2% of R_k): no leaks through thin
// walls.
fn ward_weight(r: Record, p: vec3<f32>, n: vec3<f32>) -> f32 {
    return ward_weight_at(r.position, r.normal.xyz, p, n);
}

// `ward_weight` of the record whose `position` (w = R_k) and normal are given.
fn ward_weight_at(position: vec4<f32>, normal: vec3<f32>, p: vec3<f32>, n: vec3<f32>) -> f32 {
    let radius = position.w;
    if radius <= 0.0 {
        return 0.0;
    }
    let d = p - position.xyz;
    if dot(d, (n + normal) * 0.5) < -0.02 * radius {
        return 0.0;
    }
    let cosine = clamp(dot(n, normal), -1.0, 1.0);
    return 1.0 / (length(d) / radius + sqrt(1.0 - cosine) + 1.0e-3);
}

// E_k + (n_k x n) . grad_r E_k + (P - P_k) . grad_t E_k per channel, each clamped at 0.
fn record_extrapolated(r: Record, p: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    let axis = cross(r.normal.xyz, n);
    let d = p - r.position.xyz;
    var e = r.irradiance.rgb;
    for (var c = 0u; c < 3u; c = c + 1u) {
        e[c] = max(e[c] + dot(axis, r.grad_r[c].xyz) + dot(d, r.grad_t[c].xyz), 0.0);
    }
    return e;
}

struct GridParams {
    // xyz origin of cell (0, 0, 0), w = cell size (m).
    origin: vec4<f32>,
    // x = table size - 1 (a power of two minus one), y = accuracy a as bits, z = records in the
    // grid (0: empty, the lookup returns nothing), w unused.
    table: vec4<u32>,
}

fn grid_hash(cell: vec3<i32>, mask: u32) -> u32 {
    let c = bitcast<vec3<u32>>(cell);
    return ((c.x * 73856093u) ^ (c.y * 19349663u) ^ (c.z * 83492791u)) & mask;
}
