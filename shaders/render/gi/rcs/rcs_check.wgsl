// rcs light check: which records a light edit changes. Each record keeps the surfaces its 64
// check strata (4 x 16, uniform in projected solid angle) saw; this pass relights them with the
// current lights and shadow maps (albedo luminance / pi x the shadowed direct irradiance, as the
// hemisphere render lights them) and sums their irradiance. Mode 0 stores that sum in new
// records (check.x); mode 1 compares it with the stored sum for every live record and lists the
// records whose value moved by more than the tolerance of the record's irradiance: those are
// renewed in place, the rest kept.
#import common/frame.wgsl
#import common/octahedral.wgsl
#import common/lights.wgsl
#import common/color.wgsl
#import render/gi/rcs/rcs_job.wgsl
#import render/gi/rcs/rcs_common.wgsl

struct CheckParams {
    // x = mode (0 store for jobs, 1 compare all), y = records to visit (jobs or slots), zw unused.
    mode: vec4<u32>,
    // x = tolerance (fraction of the record's irradiance luminance), yzw unused.
    tolerance: vec4<f32>,
}

struct Changed {
    count: atomic<u32>,
    pad0: u32,
    pad1: u32,
    pad2: u32,
    slots: array<u32>,
}

@group(0) @binding(0) var<uniform> params: CheckParams;
@group(0) @binding(1) var<uniform> frame: Frame;
@group(0) @binding(2) var<storage, read> lights: array<GpuLight>;
@group(0) @binding(3) var<storage, read> shadow_views: array<mat4x4<f32>>;
@group(0) @binding(4) var shadow_maps: texture_depth_2d_array;
@group(0) @binding(5) var shadow_sampler: sampler_comparison;
@group(0) @binding(6) var<storage, read_write> records: array<Record>;
@group(0) @binding(7) var<storage, read> check_strata: array<vec4<f32>>;
@group(0) @binding(8) var<storage, read> jobs: array<Job>;
@group(0) @binding(9) var<storage, read_write> changed: Changed;

#import common/shadow.wgsl

const PI: f32 = 3.14159265358979;
const CHECK_ROWS: u32 = 4u;
const CHECK_COLUMNS: u32 = 16u;

var<workgroup> part: array<f32, 64>;

@compute @workgroup_size(64, 1, 1)
fn cs_main(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_index) t: u32) {
    if group.x >= params.mode.y {
        return;
    }
    var slot = group.x;
    if params.mode.x == 0u {
        slot = bitcast<u32>(jobs[group.x].normal.w);
    }
    let r = records[slot];
    if r.position.w <= 0.0 {
        return;
    }
    let n = r.normal.xyz;
    let tangent = r.check.yzw;
    let bitangent = cross(n, tangent);
    let stratum = check_strata[slot * 64u + t];
    var value = 0.0;
    if stratum.x > 0.0 && stratum.w > 0.0 {
        let j = t / CHECK_COLUMNS;
        let k = t % CHECK_COLUMNS;
        let s2 = (f32(j) + 0.5) / f32(CHECK_ROWS);
        let phi = 2.0 * PI * (f32(k) + 0.5) / f32(CHECK_COLUMNS);
        let s = sqrt(s2);
        let dir = tangent * (s * cos(phi)) + bitangent * (s * sin(phi)) + n * sqrt(1.0 - s2);
        let p = r.position.xyz + dir * stratum.x;
        let ns = oct_decode(stratum.yz);
        let e = shadowed_irradiance(frame, p, ns);
        // Each stratum holds pi / 64 of the projected solid angle: E += L pi / 64, L = rho E / pi.
        value = stratum.w * luminance(e) / 64.0;
    }
    part[t] = value;
    workgroupBarrier();
    if t != 0u {
        return;
    }
    var sum = 0.0;
    for (var i = 0u; i < 64u; i = i + 1u) {
        sum = sum + part[i];
    }
    if params.mode.x == 0u {
        records[slot].check.x = sum;
        return;
    }
    let scale = max(luminance(r.irradiance.rgb), 1.0e-6);
    if abs(sum - r.check.x) > params.tolerance.x * scale {
        let i = atomicAdd(&changed.count, 1u);
        if i < arrayLength(&changed.slots) {
            changed.slots[i] = slot;
        }
    }
}
