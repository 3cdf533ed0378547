// ISM pass P11: one-pass multi-bounce VPL generation (Knecht 2009 section 3.6). Each VPL of the
// source set owns the points of its ISM (`ism_select.wgsl`, each with the area it stands for);
// a point is lit by that VPL (ISM-tested), and per source VPL one lit point becomes the new VPL, carrying the
// source VPL's whole reflected power in the winner's colour (section 3.6.1 leaves the power open):
// - the thesis's pick: the brightest lit point (its >= depth test, here an atomic max on the
//   luminance). The total power is right in expectation, but its position is not: the
//   brightest point is nearly always the one nearest the source, so light never travels far
//   (the suite's unlit room, two doorways from the spot, got 5% of its light);
// - `proportional`: a point picked with probability proportional to its reflected luminance
//   (an exponential race, max of y / E with E ~ Exp(1), same atomic max), which makes both the
//   power and its spatial distribution unbiased;
// - the default, `resampled` (`resample` below): the whole new set drawn at once from every
//   source's lit points, with the view importance (`importance`), each new VPL carrying an
//   equal share of the set's light divided by its point's weight.
#import common/color.wgsl
#import common/workgroup_scan.wgsl
#import common/vpl.wgsl
#import render/gi/ism/ism_lookup.wgsl

struct BounceParams {
    // VPLs per set, points per ISM P, tile side r, tiles per row C.
    counts: vec4<u32>,
    // source set's first VPL, destination set's first VPL, frame seed, pick (0: brightest,
    // 1: proportional to luminance, 2: the whole set resampled, `resample`).
    sets: vec4<u32>,
    // 1 / d_max, unused, d_min^2, interleave n^2.
    params: vec4<f32>,
    // sum over the scene of area x weight, the tail's ratio (0: the sets' power, 1: the
    // screen's, 2: their geometric mean, `TailRatio`), the view importance (`importance`),
    // unused.
    area: vec4<f32>,
    // ISM lookup: neighbour reach (`ism_lit`), normal-offset constant and slope factors (`ism_offset_point`), the
    // relative depth margin of texels without a point (`ism_lit`).
    bias: vec4<f32>,
}


const PI: f32 = 3.14159265358979;

@group(0) @binding(0) var<uniform> bp: BounceParams;
@group(0) @binding(1) var<storage, read> points: array<vec4<f32>>;
// xyz normal, w = the object's sampling weight.
@group(0) @binding(2) var<storage, read> point_normals: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> point_albedo: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read_write> vpls: array<Vpl>;
@group(0) @binding(5) var<storage, read> atlas: array<u32>;
// Per source VPL k: [2k] = the winning key's bits, [2k + 1] = the luminance sum.
@group(0) @binding(6) var<storage, read_write> selection: array<atomic<u32>>;
// Per slot i, written by `pick` and read by `write_winner` (so the winner test
// compares the very bits the atomic max saw, and each point does one ISM lookup):
// [2i] = diffusely reflected power rgb, w = source VPL index (-1: none); [2i + 1] = incident power.
@group(0) @binding(7) var<storage, read_write> lit: array<vec4<f32>>;
// rgb specular reflectance, w = Blinn-Phong exponent (0: no lobe).
@group(0) @binding(8) var<storage, read> point_specular: array<vec4<f32>>;
// Per source VPL k and slot i at k P + i: pool point index (0xffffffff: none), its area's bits.
@group(0) @binding(9) var<storage, read> chosen: array<vec2<u32>>;
// For the lookups (`ism_lookup.wgsl`): clip lines, and per VPL of every set and slot the pool point.
@group(0) @binding(10) var<storage, read> clips: array<vec4<f32>>;
@group(0) @binding(11) var<storage, read> chosen_all: array<u32>;


// A hash of (point, frame) to a uniform number in (0, 1] (PCG, Jarzynski & Olano 2020).
fn uniform01(j: u32, seed: u32) -> f32 {
    var v = j * 747796405u + 2891336453u + seed * 277803737u;
    v = ((v >> ((v >> 28u) + 4u)) ^ v) * 277803737u;
    v = (v >> 22u) ^ v;
    return (f32(v >> 8u) + 1.0) / 16777216.0;
}

// The weight of pool point j in the proportional and resampled picks: 1 + `IsmSettings::
// view_importance` x its reach into the last frame's view (`ism_view_importance.wgsl` writes it
// into the albedo's w). The pick's probability is proportional to luminance x weight and the new
// VPL's power is divided by the same, so each set's expected light is unchanged while more of
// its VPLs, each carrying less, land where they light what the camera sees.
fn importance(j: u32) -> f32 {
    if bp.sets.w == 0u {
        return 1.0;
    }
    return 1.0 + bp.area.z * max(point_albedo[j].w, 0.0);
}

// The key point j of luminance y competes with for its source VPL (largest wins).
fn pick_key(j: u32, y: f32) -> f32 {
    if bp.sets.w == 0u {
        return y;
    }
    return y / max(-log(uniform01(j, bp.sets.z)), 1.0e-30);
}

// Power arriving at slot i's point's patch from its source VPL (rgb) and that VPL's index (w).
fn incident_power(i: u32) -> vec4<f32> {
    let k = i / bp.counts.y;
    let pick = chosen[i];
    if k >= bp.counts.x || pick.x == 0xffffffffu {
        return vec4<f32>(0.0, 0.0, 0.0, -1.0);
    }
    let j = pick.x;
    let src = bp.sets.x + k;
    let vpl = vpls[src];
    if vpl.position.w <= 0.0 {
        return vec4<f32>(0.0, 0.0, 0.0, f32(k));
    }
    let p = points[j].xyz;
    let n = point_normals[j].xyz;
    let to_p = p - vpl.position.xyz;
    let d2 = max(dot(to_p, to_p), 1.0e-8);
    let dir = to_p * inverseSqrt(d2);
    let cos_s = dot(vpl.normal.xyz, dir);
    let cos_r = dot(n, -dir);
    if cos_s <= 0.0 || cos_r <= 0.0 {
        return vec4<f32>(0.0, 0.0, 0.0, f32(k));
    }
    let q = ism_offset_point(bp.bias, vpl.normal.w, vpl.position.xyz, p, n);
    let ism = ism_lookup(vpl, src, q, bp.counts.z, bp.counts.w, bp.params.x);
    if !ism_lit(vpl, src, ism, bp.counts.z, bp.counts.w, bp.counts.y, bp.bias) {
        return vec4<f32>(0.0, 0.0, 0.0, f32(k));
    }
    // The area A this point stands for among its VPL's points.
    let area = bitcast<f32>(pick.y);
    // Physical power of the source VPL (its shading power carries the interleave factor n^2)
    // reaching the point's patch, taken as a disk of area A: d^2 + A / pi is the exact
    // point-to-coaxial-disk form factor's, so a patch next to the VPL receives at most the
    // VPL's power and no light farther off is lost. The clamp at the VPL's and the point's
    // disks used before (d^2 >= R_vpl^2 + R_point^2) lost 9% of the light at every bounce: in
    // the held-out offices with every surface 0.7 grey (closed, so each set must reflect 0.7 of
    // the last) the sets' ratio was 0.634, with this 0.687, with no clamp at all 0.698, but
    // then one frame in 40 of the offices read 24x the reference's energy (the unbounded
    // 1 / d^2, presumably at a point next to a VPL).
    let e = vpl_intensity(vpl, dir, cos_s) / bp.params.w * cos_r / max(d2 + area / PI, bp.params.z);
    return vec4<f32>(e * area, f32(k));
}

@compute @workgroup_size(64, 1, 1)
fn clear(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= bp.counts.x {
        return;
    }
    atomicStore(&selection[2u * id.x], 0u);
    atomicStore(&selection[2u * id.x + 1u], bitcast<u32>(0.0));
    vpls[bp.sets.y + id.x] = Vpl(vec4<f32>(0.0), vec4<f32>(0.0, 0.0, 1.0, 0.0), vec4<f32>(0.0), vec4<f32>(0.0), vec4<f32>(0.0));
}

@compute @workgroup_size(64, 1, 1)
fn pick(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= bp.counts.x * bp.counts.y {
        return;
    }
    let incident = incident_power(id.x);
    let j = min(chosen[id.x].x, arrayLength(&point_albedo) - 1u);
    let r = vec4<f32>(point_albedo[j].rgb * incident.rgb, incident.w);
    lit[2u * id.x] = r;
    lit[2u * id.x + 1u] = incident;
    let y = luminance(r.rgb) * importance(j);
    if r.w < 0.0 || !(y > 0.0) {
        return;
    }
    let k = u32(r.w);
    if bp.sets.w != 2u {
        atomicMax(&selection[2u * k], bitcast<u32>(pick_key(id.x, y)));
    }
}

// Per source VPL k (one workgroup each): the sum of its P slots' weights (`slot_weight`) into
// selection[2k + 1], which `write_winner` and `scan_sources` read. A tree reduction in
// workgroup memory: `pick` used to add every slot by a compare-and-swap loop on that one word,
// P = 1024 threads contending for each address, the pass's one contended step; the H200
// profile read `ism bounce` at 12-34 ms of a 1080p frame (five bounces), whatever the view's
// size (`docs/BENCHMARKS.md`).
@compute @workgroup_size(256, 1, 1)
fn source_sums(@builtin(workgroup_id) wid: vec3<u32>, @builtin(local_invocation_index) lid: u32) {
    let k = wid.x;
    let first = k * bp.counts.y;
    var own = 0.0;
    for (var i = lid; i < bp.counts.y; i = i + 256u) {
        own = own + slot_weight(first + i);
    }
    scan[lid] = own;
    workgroupBarrier();
    for (var half = 128u; half > 0u; half = half / 2u) {
        if lid < half {
            scan[lid] = scan[lid] + scan[lid + half];
        }
        workgroupBarrier();
    }
    if lid == 0u && k < bp.counts.x {
        atomicStore(&selection[2u * k + 1u], bitcast<u32>(scan[0]));
    }
}

@compute @workgroup_size(64, 1, 1)
fn write_winner(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= bp.counts.x * bp.counts.y {
        return;
    }
    let r = lit[2u * id.x];
    let j = min(chosen[id.x].x, arrayLength(&point_albedo) - 1u);
    let y = luminance(r.rgb) * importance(j);
    if r.w < 0.0 || y <= 0.0 {
        return;
    }
    let k = u32(r.w);
    if bitcast<u32>(pick_key(id.x, y)) != atomicLoad(&selection[2u * k]) {
        return;
    }
    let total = bitcast<f32>(atomicLoad(&selection[2u * k + 1u]));
    let src = vpls[bp.sets.x + k];
    let p = points[j].xyz;
    var out: Vpl;
    // The new VPL stands for every point its source lit: the area of one ISM's points.
    out.position = vec4<f32>(p, max(bp.area.x / (f32(bp.counts.x) * PI), 1.0e-20));
    out.normal = vec4<f32>(point_normals[j].xyz, 0.0);
    let scale = (total / y) * bp.params.w;
    out.power = vec4<f32>(r.rgb * scale, 1.0);
    out.incident = vec4<f32>(normalize(src.position.xyz - p), 0.0);
    let spec = point_specular[j];
    out.gloss = vec4<f32>(spec.rgb * lit[2u * id.x + 1u].rgb * scale, spec.w);
    vpls[bp.sets.y + k] = out;
}

// The resampled pick (`BouncePick::Resampled`, sets.w = 2): the new set is drawn from every lit
// point of every source VPL at once, N positions spaced W / N apart on the cumulative luminance
// of all N x P slots (W their sum; one random offset per set), and each new VPL carries
// r W / (N y): equal luminance for every VPL of the set. This is systematic resampling as
// particle filters use it (Kitagawa 1996; Douc et al. 2005 for its variance): unbiased like the
// per-chain pick (slot i is drawn N y_i / W times in expectation and carries r_i W / (N y_i)),
// but the number of VPLs landing in a region no longer adds one coin flip per chain, and a chain
// that reaches a room through a doorway no longer carries its source's whole power alone. The
// slots are ordered by source VPL and then by its points' cluster order (`ism_select.wgsl`), so
// the draws are stratified over the sources and, within each, over space.
// `scan_sources` turns the per-source sums (`source_sums`) into their exclusive prefix
// (selection[2k] = the bits of the prefix before source k, [2k + 1] = the source's sum), with
// `scan_inclusive` (`common/workgroup_scan.wgsl`).
var<workgroup> last_thread: atomic<u32>;

fn source_sum(k: u32) -> f32 {
    let v = bitcast<f32>(atomicLoad(&selection[2u * k + 1u]));
    return select(0.0, v, v > 0.0);
}

@compute @workgroup_size(256, 1, 1)
fn scan_sources(@builtin(local_invocation_index) lid: u32) {
    let n = bp.counts.x;
    let per = (n + 255u) / 256u;
    let lo = min(lid * per, n);
    let hi = min(lo + per, n);
    var own = 0.0;
    for (var k = lo; k < hi; k = k + 1u) {
        own = own + source_sum(k);
    }
    scan[lid] = own;
    workgroupBarrier();
    scan_inclusive(lid);
    var base = 0.0;
    if lid > 0u {
        base = scan[lid - 1u];
    }
    for (var k = lo; k < hi; k = k + 1u) {
        atomicStore(&selection[2u * k], bitcast<u32>(base));
        base = base + source_sum(k);
    }
}

// The resampling weight of slot g: its reflected luminance times its point's view importance
// (0 where unlit).
fn slot_weight(g: u32) -> f32 {
    let r = lit[2u * g];
    let y = luminance(r.rgb) * importance(min(chosen[g].x, arrayLength(&point_albedo) - 1u));
    return select(0.0, y, r.w >= 0.0 && y > 0.0);
}

// One workgroup per source VPL k: scans its P slots' weights and writes the new VPLs whose draw
// positions fall in its share [base_k, base_k+1) of the cumulative sum. Which draws a source
// (and, inside it, a thread) owns is computed from the same stored bits by both neighbours, so
// every draw is written exactly once; inside a thread's range the walk clamps to its last
// lit slot. (A draw can land on a source with nothing lit only where the two sums' float
// rounding disagree at its boundary; it is then left dark, which costs one VPL in a
// set on the rare frame where it happens.)
@compute @workgroup_size(256, 1, 1)
fn resample(@builtin(workgroup_id) wid: vec3<u32>, @builtin(local_invocation_index) lid: u32) {
    let k = wid.x;
    let n = bp.counts.x;
    let p_count = bp.counts.y;
    let per = (p_count + 255u) / 256u;
    let lo = min(lid * per, p_count);
    let hi = min(lo + per, p_count);
    let first = k * p_count;
    var own = 0.0;
    var last_lit = lo;
    for (var i = lo; i < hi; i = i + 1u) {
        let w = slot_weight(first + i);
        own = own + w;
        if w > 0.0 {
            last_lit = i;
        }
    }
    if lid == 0u {
        atomicStore(&last_thread, 0u);
    }
    scan[lid] = own;
    workgroupBarrier();
    if own > 0.0 {
        atomicMax(&last_thread, lid);
    }
    scan_inclusive(lid);
    let last = atomicLoad(&last_thread);
    let total = bitcast<f32>(atomicLoad(&selection[2u * (n - 1u)])) + source_sum(n - 1u);
    if !(total > 0.0) || k >= n || lid > last || own <= 0.0 {
        return;
    }
    let base = bitcast<f32>(atomicLoad(&selection[2u * k]));
    // One offset in [0, 1) for the whole set.
    let xi = 1.0 - uniform01(0xffffffffu, bp.sets.z);
    let scale = f32(n) / total;
    let s0 = draw_at(base, scale, xi, n);
    var s1 = n;
    if k + 1u < n {
        s1 = draw_at(bitcast<f32>(atomicLoad(&selection[2u * (k + 1u)])), scale, xi, n);
    }
    s1 = max(s1, s0);
    var start = 0.0;
    var i0 = s0;
    if lid > 0u {
        start = scan[lid - 1u];
        i0 = clamp(draw_at(base + start, scale, xi, n), s0, s1);
    }
    var i1 = s1;
    if lid < last {
        i1 = clamp(draw_at(base + scan[lid], scale, xi, n), s0, s1);
    }
    var i = lo;
    var acc = start;
    var w = slot_weight(first + i);
    for (var s = i0; s < i1; s = s + 1u) {
        let u = (f32(s) + xi) / scale - base;
        while i < last_lit && (acc + w <= u || w <= 0.0) {
            acc = acc + w;
            i = i + 1u;
            w = slot_weight(first + i);
        }
        if w > 0.0 {
            write_vpl(first + i, k, s, total / (f32(n) * w));
        }
    }
}

// The index of the first draw at or after cumulative position x (draws at (s + xi) W / N).
fn draw_at(x: f32, scale: f32, xi: f32, n: u32) -> u32 {
    return u32(clamp(ceil(x * scale - xi), 0.0, f32(n)));
}

// Writes VPL `s` of the new set at slot g's point, lit by source VPL k, its reflected power
// times `weight` (the draw's 1 / (N probability) in luminance units).
fn write_vpl(g: u32, k: u32, s: u32, weight: f32) {
    let r = lit[2u * g];
    let src = vpls[bp.sets.x + k];
    let j = chosen[g].x;
    let p = points[j].xyz;
    var out: Vpl;
    out.position = vec4<f32>(p, max(bp.area.x / (f32(bp.counts.x) * PI), 1.0e-20));
    out.normal = vec4<f32>(point_normals[j].xyz, 0.0);
    let scale = weight * bp.params.w;
    out.power = vec4<f32>(r.rgb * scale, 1.0);
    out.incident = vec4<f32>(normalize(src.position.xyz - p), 0.0);
    let spec = point_specular[j];
    out.gloss = vec4<f32>(spec.rgb * lit[2u * g + 1u].rgb * scale, spec.w);
    vpls[bp.sets.y + s] = out;
}

var<workgroup> set_power: array<vec2<f32>, 64>;
var<workgroup> screen_power: array<vec2<f32>, 64>;

// Screen sums of the tail (`ism_shade.wgsl`) and their running means, f32: [2], [3] the running
// means, [4] the scale the last set was given last frame; from [TAIL_SUMS_AT], TAIL_SLOTS pairs
// of the last set's and the previous set's luminance on screen last frame (read and zeroed here).
@group(0) @binding(12) var<storage, read_write> tail_state: array<f32>;

// Where the shading's partial screen sums start, and how many pairs (`ism_shade.wgsl`, which
// adds workgroup w's sums to pair w mod TAIL_SLOTS). Rust: `gather::resources::TAIL_BYTES`.
const TAIL_SUMS_AT: u32 = 8u;
const TAIL_SLOTS: u32 = 1024u;
// The atlas's coarse levels (`ism_lookup.wgsl`).
@group(0) @binding(13) var<storage, read> atlas_coarse: array<u32>;

// Weight of a frame's screen sums in their running mean (they move with the VPLs' resampling).
const TAIL_BLEND: f32 = 0.25;

// The bounces beyond the last set, as a geometric series (an extension of the thesis, which
// stops at its last set): with r the ratio of the last set's light to the previous set's, later
// bounces carry r + r^2 + ... of the last set's, so the last set is scaled by 1 / (1 - r), r
// clamped to 0.9. r is the ratio of the two sets' total power, or (`TailRatio::Screen`) of what
// the screen saw of them (last frame's shading, a running mean): in a level lit from another
// room the light on screen grows for more bounces than the light in the scene as a whole
// (held-out offices: 24% of the light on screen arrives after the sixth bounce). The default
// (`TailRatio::Mean`) is the geometric mean of the two: the screen's growth slows as the light's
// spread settles, and the power ratio is where it ends. Before the screen has seen both sets, r
// is their power ratio, and the screen sums' running mean starts from it: the first frame the
// screen sees (the least settled VPLs) weighs TAIL_BLEND like every later one. Started from that
// frame alone, one realization of the suite's three rooms (seed 0) read its unlit room at 1.194
// of the path tracer (frames 17-48, 128x72; r at the 0.9 cap in frame 3), 1.126 seeded. One
// workgroup; runs after `write_winner` of the last set, which no later pass reads as a source.
@compute @workgroup_size(64, 1, 1)
fn tail(@builtin(local_invocation_index) lid: u32) {
    let n = bp.counts.x;
    var sums = vec2<f32>(0.0);
    for (var i = lid; i < n; i = i + 64u) {
        sums.x = sums.x + luminance(vpls[bp.sets.x + i].power.rgb);
        sums.y = sums.y + luminance(vpls[bp.sets.y + i].power.rgb);
    }
    set_power[lid] = sums;
    var screen = vec2<f32>(0.0);
    for (var i = lid; i < TAIL_SLOTS; i = i + 64u) {
        let at = TAIL_SUMS_AT + 2u * i;
        screen = screen + vec2<f32>(tail_state[at], tail_state[at + 1u]);
        tail_state[at] = 0.0;
        tail_state[at + 1u] = 0.0;
    }
    screen_power[lid] = screen;
    var mean = vec2<f32>(tail_state[2], tail_state[3]);
    workgroupBarrier();
    storageBarrier();
    var total = vec2<f32>(0.0);
    var last_screen = vec2<f32>(0.0);
    for (var i = 0u; i < 64u; i = i + 1u) {
        total = total + set_power[i];
        last_screen = last_screen + screen_power[i];
    }
    // The last frame's screen sums, the last set's without the scale it was given.
    let fresh = vec2<f32>(last_screen.x / max(tail_state[4], 1.0), last_screen.y);
    if fresh.y > 0.0 && all(fresh == fresh) {
        // An empty mean starts from the power ratio at the screen's scale.
        let seed = vec2<f32>(fresh.y * select(0.0, total.y / total.x, total.x > 0.0), fresh.y);
        mean = mix(select(seed, mean, mean.y > 0.0), fresh, TAIL_BLEND);
    }
    var r = 0.0;
    if mean.y > 0.0 && bp.area.y > 1.5 && total.x > 0.0 {
        r = sqrt(max(mean.x / mean.y, 0.0) * total.y / total.x);
    } else if mean.y > 0.0 && bp.area.y > 0.5 {
        r = mean.x / mean.y;
    } else if total.x > 0.0 {
        r = total.y / total.x;
    }
    r = clamp(r, 0.0, 0.9);
    let scale = 1.0 / (1.0 - r);
    if lid == 0u {
        tail_state[2] = mean.x;
        tail_state[3] = mean.y;
        tail_state[4] = scale;
    }
    for (var i = lid; i < n; i = i + 64u) {
        let k = bp.sets.y + i;
        vpls[k].power = vec4<f32>(vpls[k].power.rgb * scale, vpls[k].power.a);
        vpls[k].gloss = vec4<f32>(vpls[k].gloss.rgb * scale, vpls[k].gloss.a);
    }
}
