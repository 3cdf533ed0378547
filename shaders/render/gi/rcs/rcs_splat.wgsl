// rcs splatting (notes: "splat existing records") as a tiled compute pass. Gautron et al. draw
// one quad per record over the projection of its zone of influence, the sphere (P_k, a R_k), and
// blend w E^_k into the pixels the fragment test keeps. That costs every pixel of every quad
// (a whole-view quad for each record whose box reaches behind the camera), blended in the
// raster units, however few of those pixels lie in the zone. Here one workgroup owns a 16 x 16
// tile. It sorts the tile's pixels into six bins by the axis their geometric normal leans to
// (+x, -x, +y, ...), bounds each bin (a world box, and the widest angle of its normals to the
// axis), keeps for each bin the records whose sphere meets the bin's box and whose normal is
// within Ward's normal term of the bin's normals (sqrt(1 - n . n_k) < a: 20 degrees at
// a = 0.25), and each thread sums its bin's kept records' Ward weights for its own pixel, in
// record order (so every run sums alike). The sums are the paper's:
//   weighted: (sum w E^_k(P), sum w)   E^ with the gradients (rotational with the shading normal)
//   plain:    (sum w E_k, count)       the plain record value, and the records reaching the pixel
// for the resolve to divide by the summed weight. Mode 0 replaces the sums with records
// 0..count; mode 1 adds the records list[0..count] (a round's new records) to them.
#import common/frame.wgsl
#import common/octahedral.wgsl
#import render/gi/rcs/rcs_common.wgsl

struct SplatParams {
    // x = accuracy a, yzw unused.
    accuracy: vec4<f32>,
    // x = 1: add records[list[i]] to the sums; 0: replace the sums with records[i].
    // y = records, z = 1: keep every record (no bin test; the tests' check), w unused.
    mode: vec4<u32>,
}

@group(0) @binding(0) var<uniform> frame: Frame;
@group(0) @binding(1) var<uniform> params: SplatParams;
@group(0) @binding(2) var<storage, read> records: array<Record>;
@group(0) @binding(3) var<storage, read> list: array<u32>;
@group(0) @binding(4) var depth_tex: texture_depth_2d;
@group(0) @binding(5) var normal_tex: texture_2d<f32>;
@group(0) @binding(6) var<storage, read_write> weighted: array<vec4<f32>>;
@group(0) @binding(7) var<storage, read_write> plain: array<vec4<f32>>;

// The tile's threads: one per pixel, and one record each per batch.
const GROUP: u32 = 256u;
const WORDS: u32 = 8u;
// Six normal directions.
const BINS: u32 = 6u;

// Each bin's world box and the smallest cosine of its normals to its axis, as
// order-preserving integer keys (atomics on floats are not portable).
var<workgroup> bin_lo: array<atomic<u32>, 18>;
var<workgroup> bin_hi: array<atomic<u32>, 18>;
var<workgroup> bin_cos: array<atomic<u32>, 6>;
// The batch's records each bin keeps, one bit each (bin b's word k at b * WORDS + k).
var<workgroup> kept: array<atomic<u32>, 48>;
// The batch's records' slots, positions and normals (what Ward's weight reads): the pixels
// test them here and read the rest of a record only where it reaches them.
var<workgroup> batch_slot: array<u32, GROUP>;
var<workgroup> batch_position: array<vec4<f32>, GROUP>;
var<workgroup> batch_normal: array<vec4<f32>, GROUP>;

struct Bin {
    lo: vec3<f32>,
    hi: vec3<f32>,
    // cos of the widest angle of the bin's normals to its axis; 2 when the bin is empty.
    cos_half: f32,
}

// f32 -> u32 whose unsigned order is the float order.
fn order_key(x: f32) -> u32 {
    let b = bitcast<u32>(x);
    return select(b | 0x80000000u, ~b, (b & 0x80000000u) != 0u);
}

fn from_order_key(k: u32) -> f32 {
    return bitcast<f32>(select(~k, k & 0x7fffffffu, (k & 0x80000000u) != 0u));
}

// The direction of a normal: 2 x its largest axis, + 1 when that component is negative.
fn direction_of(n: vec3<f32>) -> u32 {
    let m = abs(n);
    var axis = 2u;
    if m.x >= m.y && m.x >= m.z {
        axis = 0u;
    } else if m.y >= m.z {
        axis = 1u;
    }
    return axis * 2u + select(0u, 1u, n[axis] < 0.0);
}

// The axis of bin `b`.
fn bin_axis(b: u32) -> vec3<f32> {
    var v = vec3<f32>(0.0);
    v[b / 2u] = select(1.0, -1.0, (b & 1u) == 1u);
    return v;
}

// Bins the tile's visible points; every thread gets every bin's bounds.
fn tile_bins(local: u32, geometry: bool, p: vec3<f32>, n: vec3<f32>, b: u32) -> array<Bin, 6> {
    if local < BINS * 3u {
        atomicStore(&bin_lo[local], 0xffffffffu);
        atomicStore(&bin_hi[local], 0u);
    }
    if local < BINS {
        atomicStore(&bin_cos[local], 0xffffffffu);
    }
    workgroupBarrier();
    if geometry {
        for (var c = 0u; c < 3u; c = c + 1u) {
            atomicMin(&bin_lo[b * 3u + c], order_key(p[c]));
            atomicMax(&bin_hi[b * 3u + c], order_key(p[c]));
        }
        atomicMin(&bin_cos[b], order_key(dot(n, bin_axis(b))));
    }
    workgroupBarrier();
    var bins: array<Bin, 6>;
    for (var b = 0u; b < BINS; b = b + 1u) {
        bins[b].cos_half = 2.0;
        if atomicLoad(&bin_hi[b * 3u]) != 0u {
            for (var c = 0u; c < 3u; c = c + 1u) {
                bins[b].lo[c] = from_order_key(atomicLoad(&bin_lo[b * 3u + c]));
                bins[b].hi[c] = from_order_key(atomicLoad(&bin_hi[b * 3u + c]));
            }
            bins[b].cos_half = from_order_key(atomicLoad(&bin_cos[b]));
        }
    }
    return bins;
}

// Whether record `r` can reach a pixel of bin `b`: its sphere (P_k, a R_k) meets the bin's
// box, and some normal within the bin's angle of its axis is within Ward's normal term of
// n_k (an angle below acos(1 - a^2)).
fn reaches(position: vec4<f32>, normal: vec3<f32>, bin: Bin, b: u32, a: f32) -> bool {
    if bin.cos_half > 1.5 {
        return false;
    }
    let c = position.xyz;
    let d = c - clamp(c, bin.lo, bin.hi);
    let rho = a * position.w;
    if dot(d, d) > rho * rho {
        return false;
    }
    let apart = acos(clamp(dot(bin_axis(b), normal), -1.0, 1.0));
    let spread = acos(clamp(bin.cos_half, -1.0, 1.0));
    // A little slack against the acos rounding: never drop a record a pixel would keep.
    return cos(max(apart - spread, 0.0)) > 1.0 - a * a - 1.0e-4;
}

// Loads a batch and marks the records each bin keeps: thread k takes the batch's k-th record.
fn mark(local: u32, slot: u32, valid: bool, bins: array<Bin, 6>, a: f32) {
    if local < BINS * WORDS {
        atomicStore(&kept[local], 0u);
    }
    workgroupBarrier();
    if valid {
        let position = records[slot].position;
        let normal = records[slot].normal;
        batch_slot[local] = slot;
        batch_position[local] = position;
        batch_normal[local] = normal;
        if position.w > 0.0 {
            for (var b = 0u; b < BINS; b = b + 1u) {
                if params.mode.z == 1u || reaches(position, normal.xyz, bins[b], b, a) {
                    atomicOr(&kept[b * WORDS + local / 32u], 1u << (local % 32u));
                }
            }
        }
    }
    workgroupBarrier();
}

@compute @workgroup_size(16, 16, 1)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(local_invocation_index) local: u32) {
    let size = vec2<u32>(frame.size.xy);
    let inside = id.x < size.x && id.y < size.y;
    var geometry = false;
    var p = vec3<f32>(0.0);
    var n = vec3<f32>(0.0, 0.0, 1.0);
    var n_shading = n;
    if inside {
        let depth = textureLoad(depth_tex, id.xy, 0);
        geometry = depth > 0.0;
        if geometry {
            p = world_from_pixel(frame, id.xy, depth);
            let enc = textureLoad(normal_tex, id.xy, 0);
            n_shading = oct_decode(enc.xy);
            n = oct_decode(enc.zw);
        }
    }
    let bin = direction_of(n);
    let bins = tile_bins(local, geometry, p, n, bin);
    let mine = bin * WORDS;
    let a = params.accuracy.x;
    let add = params.mode.x == 1u;
    let count = params.mode.y;
    var sum_w = vec4<f32>(0.0);
    var sum_p = vec4<f32>(0.0);
    for (var base = 0u; base < count; base = base + GROUP) {
        let i = base + local;
        var index = i;
        if add && i < count {
            index = list[i];
        }
        mark(local, index, i < count, bins, a);
        for (var word = 0u; word < WORDS && geometry; word = word + 1u) {
            var bits = atomicLoad(&kept[mine + word]);
            while bits != 0u {
                let k = word * 32u + countTrailingZeros(bits);
                bits = bits & (bits - 1u);
                let w = ward_weight_at(batch_position[k], batch_normal[k].xyz, p, n);
                if w > 1.0 / a {
                    let r = records[batch_slot[k]];
                    sum_w += vec4<f32>(record_extrapolated(r, p, n_shading) * w, w);
                    sum_p += vec4<f32>(r.irradiance.rgb * w, 1.0);
                }
            }
        }
        // The next batch's marks wait for every thread's walk.
        workgroupBarrier();
    }
    if !inside {
        return;
    }
    let pixel = id.y * size.x + id.x;
    if add {
        weighted[pixel] += sum_w;
        plain[pixel] += sum_p;
    } else {
        weighted[pixel] = sum_w;
        plain[pixel] = sum_p;
    }
}
