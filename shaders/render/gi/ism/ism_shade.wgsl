// ISM pass P10 (interleaved VPL shading, Knecht 2009 section 3.4) on the split G-buffer: one
// thread per split texel, whose tile (i, j) gathers only its contiguous block of about N / n^2 VPLs of
// every bounce's set, each tested against its imperfect shadow map. Two outputs:
// - `shade`: E / pi into the split accumulation buffer (the lighting composite multiplies by
//   albedo): sum of V I(w) cos_r / (pi max(d^2, d_min^2)), with I the VPL's radiant intensity;
// - `project_sh` (Segovia & Wald): the incident radiance projected on 9 SH coefficients per
//   colour, sum of V I(w) / max(d^2, d_min^2) Y(w_to_vpl), packed as f16 (14 u32 per texel).
// Both add, over the screen, the luminance the last and the previous set give (`tail_sums`): the
// bounce tail's ratio for the next frame (`tail` in `ism_bounce.wgsl`).
#import common/color.wgsl
#import common/interleave.wgsl
#import common/octahedral.wgsl
#import common/sh9.wgsl
#import common/vpl.wgsl
#import render/gi/ism/ism_lookup.wgsl

struct ShadeParams {
    // VPL count, tile side r, tiles per row C, interleave n.
    counts: vec4<u32>,
    // 1 / d_max, unused, d_min^2, clamp factor on the VPL's disk radius squared.
    params: vec4<f32>,
    // VPL sets (bounces), view width, view height, points per ISM.
    sets: vec4<u32>,
    // ISM lookup: neighbour reach (`ism_lit`), normal-offset constant and slope factors (`ism_offset_point`), the
    // relative depth margin of texels without a point (`ism_lit`).
    bias: vec4<f32>,
}

@group(0) @binding(0) var<uniform> sh: ShadeParams;
@group(0) @binding(1) var<storage, read> vpls: array<Vpl>;
@group(0) @binding(2) var<storage, read> atlas: array<u32>;
@group(0) @binding(3) var split_position: texture_2d<f32>;
@group(0) @binding(4) var split_normal: texture_2d<f32>;
@group(0) @binding(5) var out_indirect: texture_storage_2d<rgba32float, write>;
@group(0) @binding(6) var<storage, read_write> out_sh: array<u32>;
// For the lookups (`ism_lookup.wgsl`): pool positions, normals, clip lines, and per VPL of
// every set and slot the pool point.
@group(0) @binding(7) var<storage, read> points: array<vec4<f32>>;
@group(0) @binding(8) var<storage, read> point_normals: array<vec4<f32>>;
@group(0) @binding(9) var<storage, read> clips: array<vec4<f32>>;
@group(0) @binding(10) var<storage, read> chosen_all: array<u32>;
// From TAIL_SUMS_AT, TAIL_SLOTS pairs: the last set's and the previous set's luminance E cos / pi
// summed over the screen (f32 bits, workgroup w adding its sums to pair w mod TAIL_SLOTS by
// compare-and-swap); `tail` in `ism_bounce.wgsl` adds them up and zeroes them. One pair for the
// whole screen had 32,400 workgroups contending for each word at 1080p.
@group(0) @binding(11) var<storage, read_write> tail_sums: array<atomic<u32>>;
// The atlas's coarse levels (`ism_lookup.wgsl`).
@group(0) @binding(12) var<storage, read> atlas_coarse: array<u32>;

const PI: f32 = 3.14159265358979;
const SH_WORDS: u32 = 14u;

struct Incident {
    // Unit direction from the receiver towards the VPL.
    dir: vec3<f32>,
    // Irradiance at normal incidence, V I(w) / max(d^2, d_min^2); zero when not lit.
    e: vec3<f32>,
}

// The light VPL `k` sends to receiver `p` (geometric normal `ng`), ISM visibility included.
fn incident(k: u32, p: vec3<f32>, ng: vec3<f32>) -> Incident {
    var out = Incident(vec3<f32>(0.0, 0.0, 1.0), vec3<f32>(0.0));
    let vpl = vpls[k];
    if vpl.position.w <= 0.0 {
        return out;
    }
    let to_p = p - vpl.position.xyz;
    let d2 = max(dot(to_p, to_p), 1.0e-8);
    let dir = to_p * inverseSqrt(d2);
    let cos_s = dot(vpl.normal.xyz, dir);
    // One-sided receivers: light from behind the geometric normal adds nothing.
    if cos_s <= 0.0 || dot(ng, -dir) <= 0.0 {
        return out;
    }
    let q = ism_offset_point(sh.bias, vpl.normal.w, vpl.position.xyz, p, ng);
    let ism = ism_lookup(vpl, k, q, sh.counts.y, sh.counts.z, sh.params.x);
    if !ism_lit(vpl, k, ism, sh.counts.y, sh.counts.z, sh.sets.w, sh.bias) {
        return out;
    }
    out.dir = -dir;
    out.e = vpl_intensity(vpl, dir, cos_s) / max(max(d2, sh.params.w * vpl.position.w), sh.params.z);
    return out;
}

struct Texel {
    // World position (w = 1 when the pixel sees geometry).
    position: vec4<f32>,
    shading_normal: vec3<f32>,
    geometric_normal: vec3<f32>,
    // First VPL of this texel's block in set 0, VPLs per block.
    first: u32,
    per: u32,
}

fn texel(s: vec2<u32>) -> Texel {
    let size = sh.sets.yz;
    let ni = sh.counts.w;
    let tile = split_pixel(s, size, ni).z;
    // Tile `tile` gathers a contiguous block of each set: N / n^2 VPLs, one more for the first
    // N mod n^2 tiles, so that every VPL lights exactly one tile whatever N (each carries n^2
    // times its power). Blocks of N / n^2 alone left N mod n^2 VPLs unused: 8 of 120 at n = 4,
    // 12 of the 76 the editor's preview uses at a third of the cost, 15 of 31 (the indirect
    // light read 0.498 of 32 VPLs', `tests/integration/ism.rs`).
    // A tile with no VPL (N < n^2) starts past the set's end and gathers nothing.
    let tiles = ni * ni;
    let base = sh.counts.x / tiles;
    let extra = sh.counts.x % tiles;
    let first = tile * base + min(tile, extra);
    let per = max(base + select(0u, 1u, tile < extra), 1u);
    let enc = textureLoad(split_normal, s, 0);
    return Texel(textureLoad(split_position, s, 0), oct_decode(enc.xy), oct_decode(enc.zw), first, per);
}

// Index of the i-th VPL texel t gathers (its block of every set in turn), or -1 where the
// block runs past the set's end.
fn vpl_of(t: Texel, i: u32) -> i32 {
    let j = t.first + i % t.per;
    return select(i32((i / t.per) * sh.counts.x + j), -1, j >= sh.counts.x);
}

// The light the i-th VPL of texel t's loop sends it (none where its block runs past the set).
fn gathered(t: Texel, i: u32) -> Incident {
    let k = vpl_of(t, i);
    if k < 0 {
        return Incident(vec3<f32>(0.0, 0.0, 1.0), vec3<f32>(0.0));
    }
    return incident(u32(k), t.position.xyz, t.geometric_normal);
}

fn in_split(s: vec2<u32>) -> bool {
    return all(s < split_block(sh.sets.yz, sh.counts.w) * sh.counts.w);
}

// Which of the tail's sums VPL number i of a texel's loop adds to: 0 the last set, 1 the
// previous one, 2 neither.
fn tail_slot(t: Texel, i: u32) -> u32 {
    let set_index = i / t.per;
    if set_index + 1u == sh.sets.x {
        return 0u;
    }
    if set_index + 2u == sh.sets.x {
        return 1u;
    }
    return 2u;
}

fn atomic_add_f32(at: u32, v: f32) {
    var old = atomicLoad(&tail_sums[at]);
    loop {
        let res = atomicCompareExchangeWeak(&tail_sums[at], old, bitcast<u32>(bitcast<f32>(old) + v));
        if res.exchanged {
            break;
        }
        old = res.old_value;
    }
}

var<workgroup> group_sums: array<vec2<f32>, 64>;

// As in `ism_bounce.wgsl`'s `tail`.
const TAIL_SUMS_AT: u32 = 8u;
const TAIL_SLOTS: u32 = 1024u;

// Adds every thread's (last, previous) luminance to workgroup `group`'s pair of `tail_sums`;
// called by the whole workgroup.
fn add_tail_sums(lid: u32, group: vec3<u32>, v: vec2<f32>) {
    group_sums[lid] = v;
    workgroupBarrier();
    if lid == 0u {
        var total = vec2<f32>(0.0);
        for (var i = 0u; i < 64u; i = i + 1u) {
            total = total + group_sums[i];
        }
        let at = TAIL_SUMS_AT + 2u * ((group.y * 4099u + group.x) % TAIL_SLOTS);
        if total.x > 0.0 {
            atomic_add_f32(at, total.x);
        }
        if total.y > 0.0 {
            atomic_add_f32(at + 1u, total.y);
        }
    }
}

@compute @workgroup_size(8, 8, 1)
fn shade(
    @builtin(global_invocation_id) id: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
    @builtin(workgroup_id) group: vec3<u32>,
) {
    var sum = vec3<f32>(0.0);
    var tail = vec3<f32>(0.0);
    let inside = in_split(id.xy);
    if inside {
        let t = texel(id.xy);
        if t.position.w > 0.5 {
            for (var i = 0u; i < t.per * sh.sets.x; i = i + 1u) {
                let inc = gathered(t, i);
                let e = inc.e * max(dot(t.shading_normal, inc.dir), 0.0) / PI;
                sum = sum + e;
                tail[tail_slot(t, i)] += luminance(e);
            }
        }
        textureStore(out_indirect, id.xy, vec4<f32>(sum, 1.0));
    }
    add_tail_sums(lid, group, tail.xy);
}

@compute @workgroup_size(8, 8, 1)
fn project_sh(
    @builtin(global_invocation_id) id: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
    @builtin(workgroup_id) group: vec3<u32>,
) {
    let inside = in_split(id.xy);
    var tail = vec3<f32>(0.0);
    if inside {
        tail = write_sh(id.xy);
    }
    add_tail_sums(lid, group, tail.xy);
}

// Projects split texel `s`'s incident light on SH and stores it; returns its tail sums.
fn write_sh(s: vec2<u32>) -> vec3<f32> {
    let id = vec3<u32>(s, 0u);
    let t = texel(id.xy);
    var c = array<vec3<f32>, 9>();
    var tail = vec3<f32>(0.0);
    if t.position.w > 0.5 {
        for (var i = 0u; i < t.per * sh.sets.x; i = i + 1u) {
            let inc = gathered(t, i);
            if all(inc.e <= vec3<f32>(0.0)) {
                continue;
            }
            tail[tail_slot(t, i)] += luminance(inc.e) * max(dot(t.shading_normal, inc.dir), 0.0) / PI;
            let y = sh9_basis(inc.dir);
            for (var b = 0u; b < 9u; b = b + 1u) {
                c[b] = c[b] + inc.e * y[b];
            }
        }
    }
    let width = split_block(sh.sets.yz, sh.counts.w).x * sh.counts.w;
    let base = (id.y * width + id.x) * SH_WORDS;
    // 27 floats as 14 f16 pairs: coefficient b channel ch is float number 3 b + ch.
    var f = array<f32, 28>();
    for (var b = 0u; b < 9u; b = b + 1u) {
        f[3u * b] = c[b].x;
        f[3u * b + 1u] = c[b].y;
        f[3u * b + 2u] = c[b].z;
    }
    for (var w = 0u; w < SH_WORDS; w = w + 1u) {
        // f16 saturates at 65504: clamp so that absurd light powers cannot write infinities.
        let pair = clamp(vec2<f32>(f[2u * w], f[2u * w + 1u]), vec2<f32>(-65000.0), vec2<f32>(65000.0));
        out_sh[base + w] = pack2x16float(pair);
    }
    return tail;
}
