// rcs record computation, step 2: one workgroup reduces one record's hemisphere plane.
// - E: sum over the plane's texels of L cos(theta) dOmega plus the border compensation, weights
//   precomputed by render::gi::rcs::hemisphere::plane_weights (they sum to pi: the white
//   furnace), i.e. the notes' Omega_p with their border band cos(theta_b) dPhi weighted for
//   irradiance: L cos^2(theta_b) dPhi / 2 (the band times cos(theta_b) would count it twice).
// - The plane resampled into M x N strata uniform in projected solid angle (2 x 2 taps each; a
//   direction beyond the aperture takes the border texel along its azimuth, as the border
//   compensation does): R_k = the harmonic mean of the strata's nearest distances, limited to
//   E / |grad_t E| (Ward and Heckbert 1992), and their rotational and translational gradients
//   (also after Ward and Heckbert 1992, over the strata).
// - 64 check strata (4 x 16, one centre tap each) keep the surface each one sees (distance,
//   normal, albedo) for the light check (`rcs_check.wgsl`).
// - Texels where the plane saw nothing (a = 0) see the sky (`common/sky.wgsl`), so a record's
//   irradiance holds the sky light that reaches it (the hemisphere render as the radiance
//   cache's authors render the environment), except in the white furnace, whose background
//   already emits 1.
// - Secondary records (classical irradiance caching's recursion): where the bounce lookup found
//   no record facing the surface's way (the camera never saw it), the texel of each plane
//   quadrant with the largest weight is proposed as a new record's site.
#import common/octahedral.wgsl
#import common/color.wgsl
#import render/gi/rcs/rcs_job.wgsl
#import render/gi/rcs/rcs_common.wgsl
#import common/sky_params.wgsl

struct ReduceParams {
    // x = plane texels per side h, y = tiles per atlas row, z = jobs, w = unused.
    sizes: vec4<u32>,
}

@group(0) @binding(0) var<uniform> params: ReduceParams;
@group(0) @binding(1) var atlas: texture_2d<f32>;
@group(0) @binding(2) var surfaces: texture_2d<f32>;
@group(0) @binding(3) var<storage, read> weights: array<f32>;
@group(0) @binding(4) var<storage, read> jobs: array<Job>;
@group(0) @binding(5) var<storage, read_write> records: array<Record>;
@group(0) @binding(6) var<storage, read_write> check_strata: array<vec4<f32>>;
@group(0) @binding(7) var<storage, read_write> results: array<vec4<f32>>;

struct Secondary {
    // xyz site, w = the proposing record's slot as bits.
    position: vec4<f32>,
    // xyz normal of the surface, w unused.
    normal: vec4<f32>,
}

struct Secondaries {
    count: atomic<u32>,
    pad0: u32,
    pad1: u32,
    pad2: u32,
    items: array<Secondary>,
}

@group(0) @binding(8) var<storage, read_write> secondaries: Secondaries;
@group(0) @binding(9) var sky_tex: texture_2d<f32>;
@group(0) @binding(10) var<uniform> sky: SkyParams;
#import common/sky.wgsl

const PI: f32 = 3.14159265358979;
const ROWS: u32 = 8u;
const COLUMNS: u32 = 32u;
const CELLS: u32 = 256u;
const CHECK_ROWS: u32 = 4u;
const CHECK_COLUMNS: u32 = 16u;
const MISS: f32 = 1.0e30;

var<workgroup> cell_l: array<vec3<f32>, CELLS>;
var<workgroup> cell_r: array<f32, CELLS>;
var<workgroup> part_e: array<vec3<f32>, 64>;
var<workgroup> part_inv: array<f32, 64>;
var<workgroup> part_rot: array<array<vec3<f32>, 3>, 64>;
var<workgroup> part_trans: array<array<vec3<f32>, 3>, 64>;
// Per invocation and plane quadrant: the best lookup miss as (weight bits, texel index + 1).
var<workgroup> part_miss: array<array<vec2<u32>, 4>, 64>;

// The plane texel (in its tile) a direction in the record's frame (z = normal) falls on; beyond
// the aperture the border texel along the same azimuth.
fn plane_texel(local: vec3<f32>, h: u32) -> vec2<u32> {
    var uv = local.xy / max(local.z, 1.0e-6);
    let s = max(abs(uv.x), abs(uv.y));
    if s > 2.0 {
        uv = uv * (2.0 / s);
    }
    let xy = vec2<f32>(uv.x * 0.25 + 0.5, 0.5 - uv.y * 0.25) * f32(h);
    return vec2<u32>(clamp(vec2<i32>(floor(xy)), vec2<i32>(0), vec2<i32>(i32(h) - 1)));
}

// The radiance and distance of plane texel `local` (in the tile) of `job`: what the hemisphere
// render stored, or the sky along the texel's direction where it saw nothing.
fn plane_radiance(job: Job, origin: vec2<u32>, local: vec2<u32>, h: u32) -> vec4<f32> {
    let stored = textureLoad(atlas, origin + local, 0);
    if stored.a > 0.0 || job.params.x > 0.5 || sky.kind.x == 0u {
        return stored;
    }
    let uv = vec2<f32>(((f32(local.x) + 0.5) / f32(h) - 0.5) * 4.0, (0.5 - (f32(local.y) + 0.5) / f32(h)) * 4.0);
    let d = normalize(job.tangent.xyz * uv.x + job.bitangent.xyz * uv.y + job.normal.xyz);
    return vec4<f32>(sky_radiance(d), 0.0);
}

// Direction of projected-solid-angle coordinates (sin^2 theta, phi) in the record's frame.
fn stratum_direction(s2: f32, phi: f32) -> vec3<f32> {
    let s = sqrt(s2);
    return vec3<f32>(s * cos(phi), s * sin(phi), sqrt(max(1.0 - s2, 0.0)));
}

@compute @workgroup_size(64, 1, 1)
fn cs_main(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_index) t: u32) {
    let index = group.x;
    if index >= params.sizes.z {
        return;
    }
    let job = jobs[index];
    let h = params.sizes.x;
    let origin = vec2<u32>(job.params.zw);
    let slot = bitcast<u32>(job.normal.w);

    // Irradiance over the plane with the border compensation; the best lookup miss per quadrant.
    var e = vec3<f32>(0.0);
    var miss = array<vec2<u32>, 4>(vec2<u32>(0u), vec2<u32>(0u), vec2<u32>(0u), vec2<u32>(0u));
    let propose = job.extra.y > 0.5;
    for (var i = t; i < h * h; i = i + 64u) {
        let texel = origin + vec2<u32>(i % h, i / h);
        e = e + plane_radiance(job, origin, vec2<u32>(i % h, i / h), h).rgb * weights[i];
        if propose && abs(textureLoad(surfaces, texel, 0).a - 0.5) < 0.1 {
            let q = u32((i % h) >= h / 2u) + 2u * u32((i / h) >= h / 2u);
            // Positive floats order like their bits.
            let key = bitcast<u32>(weights[i]);
            if key > miss[q].x {
                miss[q] = vec2<u32>(key, i + 1u);
            }
        }
    }
    part_e[t] = e;
    part_miss[t] = miss;

    // Strata: mean radiance and nearest distance of 2 x 2 taps.
    var inv = 0.0;
    for (var c = t; c < CELLS; c = c + 64u) {
        let j = c / COLUMNS;
        let k = c % COLUMNS;
        var l = vec3<f32>(0.0);
        var r = MISS;
        for (var q = 0u; q < 4u; q = q + 1u) {
            let s2 = (f32(j) + (f32(q & 1u) + 0.5) * 0.5) / f32(ROWS);
            let phi = 2.0 * PI * (f32(k) + (f32(q >> 1u) + 0.5) * 0.5) / f32(COLUMNS);
            let texel = plane_radiance(job, origin, plane_texel(stratum_direction(s2, phi), h), h);
            l = l + texel.rgb * 0.25;
            if texel.a > 0.0 {
                r = min(r, texel.a);
            }
        }
        cell_l[c] = l;
        cell_r[c] = r;
        if r < MISS {
            inv = inv + 1.0 / r;
        }
    }
    part_inv[t] = inv;

    // Check strata: the surface at each centre direction.
    {
        let j = t / CHECK_COLUMNS;
        let k = t % CHECK_COLUMNS;
        let dir = stratum_direction((f32(j) + 0.5) / f32(CHECK_ROWS), 2.0 * PI * (f32(k) + 0.5) / f32(CHECK_COLUMNS));
        let texel = origin + plane_texel(dir, h);
        let hit = textureLoad(atlas, texel, 0);
        let surface = textureLoad(surfaces, texel, 0);
        check_strata[slot * 64u + t] = vec4<f32>(hit.a, surface.xy, surface.z);
    }
    workgroupBarrier();

    // Gradients, one azimuth column per invocation.
    var rot = array<vec3<f32>, 3>(vec3<f32>(0.0), vec3<f32>(0.0), vec3<f32>(0.0));
    var trans = array<vec3<f32>, 3>(vec3<f32>(0.0), vec3<f32>(0.0), vec3<f32>(0.0));
    if t < COLUMNS {
        let k = t;
        let k_prev = (k + COLUMNS - 1u) % COLUMNS;
        let phi = 2.0 * PI * (f32(k) + 0.5) / f32(COLUMNS);
        let phi_minus = 2.0 * PI * f32(k) / f32(COLUMNS);
        let u = vec3<f32>(cos(phi), sin(phi), 0.0);
        let w = vec3<f32>(-sin(phi), cos(phi), 0.0);
        let v_minus = vec3<f32>(-sin(phi_minus), cos(phi_minus), 0.0);
        var tan_sum = vec3<f32>(0.0);
        var polar = vec3<f32>(0.0);
        var azimuthal = vec3<f32>(0.0);
        for (var j = 0u; j < ROWS; j = j + 1u) {
            let c = j * COLUMNS + k;
            let s2 = (f32(j) + 0.5) / f32(ROWS);
            tan_sum = tan_sum + sqrt(s2 / (1.0 - s2)) * cell_l[c];
            let s_minus = sqrt(f32(j) / f32(ROWS));
            let s_plus = sqrt(f32(j + 1u) / f32(ROWS));
            if j >= 1u {
                let below = (j - 1u) * COLUMNS + k;
                let cos2 = 1.0 - f32(j) / f32(ROWS);
                polar = polar + (s_minus * cos2 / min(cell_r[c], cell_r[below])) * (cell_l[c] - cell_l[below]);
            }
            let side = j * COLUMNS + k_prev;
            azimuthal = azimuthal + ((s_plus - s_minus) / min(cell_r[c], cell_r[side])) * (cell_l[c] - cell_l[side]);
        }
        polar = polar * (2.0 * PI / f32(COLUMNS));
        for (var ch = 0u; ch < 3u; ch = ch + 1u) {
            rot[ch] = w * tan_sum[ch];
            trans[ch] = u * polar[ch] + v_minus * azimuthal[ch];
        }
    }
    part_rot[t] = rot;
    part_trans[t] = trans;
    workgroupBarrier();

    if t < 4u && propose {
        var best = vec2<u32>(0u);
        for (var i = 0u; i < 64u; i = i + 1u) {
            if part_miss[i][t].x > best.x {
                best = part_miss[i][t];
            }
        }
        if best.y > 0u {
            let i = best.y - 1u;
            let texel = origin + vec2<u32>(i % h, i / h);
            let hit = textureLoad(atlas, texel, 0);
            let surface = textureLoad(surfaces, texel, 0);
            let uv = vec2<f32>((f32(i % h) + 0.5) / f32(h) * 4.0 - 2.0, 2.0 - (f32(i / h) + 0.5) / f32(h) * 4.0);
            let dir = normalize(job.tangent.xyz * uv.x + job.bitangent.xyz * uv.y + job.normal.xyz);
            let k = atomicAdd(&secondaries.count, 1u);
            if k < arrayLength(&secondaries.items) {
                secondaries.items[k] = Secondary(
                    vec4<f32>(job.position.xyz + dir * hit.a, bitcast<f32>(slot)),
                    vec4<f32>(oct_decode(surface.xy), 0.0),
                );
            }
        }
    }
    if t != 0u {
        return;
    }
    var total_e = vec3<f32>(0.0);
    var total_inv = 0.0;
    var g_rot = array<vec3<f32>, 3>(vec3<f32>(0.0), vec3<f32>(0.0), vec3<f32>(0.0));
    var g_trans = array<vec3<f32>, 3>(vec3<f32>(0.0), vec3<f32>(0.0), vec3<f32>(0.0));
    for (var i = 0u; i < 64u; i = i + 1u) {
        total_e = total_e + part_e[i];
        total_inv = total_inv + part_inv[i];
        for (var ch = 0u; ch < 3u; ch = ch + 1u) {
            g_rot[ch] = g_rot[ch] + part_rot[i][ch];
            g_trans[ch] = g_trans[ch] + part_trans[i][ch];
        }
    }
    let r_min = job.tangent.w;
    let r_max = job.bitangent.w;
    var harmonic = r_max;
    if total_inv > 0.0 {
        harmonic = f32(CELLS) / total_inv;
    }
    // Ward and Heckbert's limit: R_k <= E_k / |grad_t E_k| (of the luminance), so that the
    // translational extrapolation changes E by at most a E over the zone.
    let g_lum = g_trans[0] * 0.2126 + g_trans[1] * 0.7152 + g_trans[2] * 0.0722;
    let slope = length(g_lum);
    var limited = harmonic;
    if slope > 0.0 {
        limited = min(harmonic, luminance(total_e) / slope);
    }
    let radius = clamp(limited, r_min, r_max);
    // Where the pixel clamp keeps the zone larger than the limit, the gradient is scaled down
    // instead, to the same bound on the extrapolation.
    let trans_scale = min(limited / radius, 1.0);
    var rec: Record;
    rec.position = vec4<f32>(job.position.xyz, radius);
    rec.normal = vec4<f32>(job.normal.xyz, job.extra.x + 1.0);
    rec.irradiance = vec4<f32>(total_e, harmonic);
    let scale = PI / f32(CELLS);
    for (var ch = 0u; ch < 3u; ch = ch + 1u) {
        let gr = g_rot[ch] * scale;
        let gt = g_trans[ch] * trans_scale;
        rec.grad_r[ch] = vec4<f32>(job.tangent.xyz * gr.x + job.bitangent.xyz * gr.y + job.normal.xyz * gr.z, 0.0);
        rec.grad_t[ch] = vec4<f32>(job.tangent.xyz * gt.x + job.bitangent.xyz * gt.y + job.normal.xyz * gt.z, 0.0);
    }
    rec.check = vec4<f32>(records[slot].check.x, job.tangent.xyz);
    records[slot] = rec;
    results[index] = vec4<f32>(radius, luminance(total_e), bitcast<f32>(slot), harmonic);
}
