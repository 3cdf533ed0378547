// ISM pass P6b: each VPL's own point set, sampled from the scene's point pool in proportion to
// the solid angle it subtends from the VPL (an extension of Ritschel et al. 2008 in the spirit
// of Hollander et al. 2011's ManyLoDs: detail where the VPL looks closely). The thesis gives
// every ISM the same share of uniformly spread points; at level scale that leaves a box next to
// a VPL with one or two points, a hole through which its light leaks (measured against BVH
// rays: 31% of the cosine-weighted directions of a cluttered room's first-bounce ISMs were
// holes at 4096 uniform points per ISM). Here every ISM gets about the same number of points
// per steradian wherever its geometry lies.
//
// The pool is grouped in clusters of nearby points (Morton order, 64 points, bounding sphere).
// One workgroup per VPL weighs every cluster by the projected solid angle it subtends (`weight`),
// scans the weights, and draws P points by systematic sampling (each thread P / 256 of them):
// P equally spaced positions on the weights' CDF with one random offset per VPL and frame, each taking
// the point at the same relative position inside its cluster (so the points are stratified in
// space too). A chosen point stands for the area a_j n_c W / (P w_c) (a_j: its own pool area,
// w_c: the cluster's weight, W: their sum), so sums over the chosen points estimate surface
// integrals without bias; the same points feed the splats (their disks) and the bounce pass
// (the power they reflect). The VPL's normal.w receives sqrt(W / P): the points' angular
// spacing, the lookup offset's unit (`ism_offset_point`).
#import common/octahedral.wgsl
#import common/vpl.wgsl
#import common/workgroup_scan.wgsl

struct SelectParams {
    // VPLs per set, points per ISM P, clusters, first VPL of the set.
    counts: vec4<u32>,
    // pool area per point at weight 1 (m^2), unused x3.
    params: vec4<f32>,
    // frame seed, unused x3.
    seed: vec4<u32>,
}

struct Cluster {
    // Bounding sphere: centre, radius.
    sphere: vec4<f32>,
    first: u32,
    count: u32,
    // Sum of its points' areas (m^2).
    area: f32,
    // The points' plane (`clusters.rs`, `plane_code`): octahedral mean normal in 2 x 12 bits, a
    // log-coded bound on the points' distance from the plane through the centre in the top 8;
    // 0: none.
    plane: u32,
}

@group(0) @binding(0) var<uniform> sp: SelectParams;
@group(0) @binding(1) var<storage, read> clusters: array<Cluster>;
// xyz normal, w = the object's sampling weight.
@group(0) @binding(2) var<storage, read> point_normals: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read_write> vpls: array<Vpl>;
// Per VPL k and slot i at k P + i: x = pool point index (0xffffffff: none), y = its area bits.
@group(0) @binding(4) var<storage, read_write> chosen: array<vec2<u32>>;
// Per VPL of every set (at its atlas tile) and slot: the pool point alone, kept for the lookups
// after later sets have overwritten `chosen` (`ism_lookup.wgsl`).
@group(0) @binding(5) var<storage, read_write> chosen_all: array<u32>;

const GROUP: u32 = 256u;
const NONE: u32 = 0xffffffffu;

// How far above the VPL's plane (normal n, the centre at v from the VPL) any of cluster c's
// points can lie: the sphere's top, or tighter, from the cluster's plane (normal m, thickness
// h): a point is c + a m + b with |a| <= h and b in the plane, |b| <= r, so it rises at most
// h |n.m| + r sqrt(1 - (n.m)^2) above the centre. The bound is computed on the CPU against the
// decoded normal; 1e-5 r covers the two decodings' rounding.
fn rise(c: Cluster, v: vec3<f32>, n: vec3<f32>) -> f32 {
    let r = c.sphere.w;
    if c.plane == 0u {
        return dot(v, n) + r;
    }
    let e = (vec2<f32>(f32(c.plane & 0xfffu), f32((c.plane >> 12u) & 0xfffu)) - 2048.0) / 2047.0;
    let m = oct_decode(e);
    let h = r * exp2((f32(c.plane >> 24u) - 255.0) / 8.0);
    let cm = min(abs(dot(n, m)), 1.0);
    return dot(v, n) + min(r, h * cm + r * sqrt(1.0 - cm * cm) + 1.0e-5 * r);
}

// Weight of cluster c seen from a VPL at o with normal n: its projected solid angle, area x
// cos / max(d^2, r^2), with the cosine of its highest point above the VPL's plane (so a
// cluster straddling that plane keeps a share) and zero when it lies wholly behind. The cosine
// matters: by solid angle alone, the VPL's own surface (all of it on the map's rim, where it
// occludes nothing) took most of the points, about log(extent / r) times any other surface's
// share. The plane matters too: with the sphere's top as the highest point, the VPL's own wall
// or floor near it kept its full weight, and 37-47% of every ISM's points lay there, behind
// the VPL, where the splat drops them and no light of the VPL reaches.
fn weight(c: Cluster, o: vec3<f32>, n: vec3<f32>) -> f32 {
    let v = c.sphere.xyz - o;
    let r = c.sphere.w;
    let up = rise(c, v, n);
    if up <= 0.0 || c.count == 0u {
        return 0.0;
    }
    let d = max(length(v), r);
    return c.area * min(up / max(d, 1.0e-6), 1.0) / max(d * d, 1.0e-12);
}

// A hash of (VPL, frame) to [0, 1) (PCG, Jarzynski & Olano 2020).
fn offset01(k: u32, seed: u32) -> f32 {
    var v = k * 747796405u + 2891336453u + seed * 277803737u;
    v = ((v >> ((v >> 28u) + 4u)) ^ v) * 277803737u;
    v = (v >> 22u) ^ v;
    return f32(v >> 8u) / 16777216.0;
}

@compute @workgroup_size(256, 1, 1)
fn select_points(@builtin(workgroup_id) wid: vec3<u32>, @builtin(local_invocation_index) lid: u32) {
    let k = wid.x;
    let p_count = sp.counts.y;
    let n_clusters = sp.counts.z;
    let vpl = vpls[sp.counts.w + k];
    let alive = vpl.position.w > 0.0;
    let o = vpl.position.xyz;
    let n = vpl.normal.xyz;
    let per = (n_clusters + GROUP - 1u) / GROUP;
    let lo = min(lid * per, n_clusters);
    let hi = min(lo + per, n_clusters);
    var own = 0.0;
    for (var c = lo; c < hi; c = c + 1u) {
        own = own + weight(clusters[c], o, n);
    }
    // The weights' inclusive prefix sums over the threads, in `scan`.
    scan[lid] = own;
    workgroupBarrier();
    scan_inclusive(lid);
    let total = scan[GROUP - 1u];
    let base = k * p_count;
    let all_base = (sp.counts.w + k) * p_count;
    if !alive || total <= 0.0 {
        for (var i = lid; i < p_count; i = i + GROUP) {
            chosen[base + i] = vec2<u32>(NONE, 0u);
            chosen_all[all_base + i] = NONE;
        }
        if lid == 0u {
            vpls[sp.counts.w + k].normal.w = 0.0;
        }
        return;
    }
    if lid == 0u {
        vpls[sp.counts.w + k].normal.w = sqrt(total / f32(p_count));
    }
    let xi = offset01(k, sp.seed.x);
    let scale = f32(p_count) / total;
    // Samples u_i = (i + xi) W / P in [start, end) of thread t's clusters are t's: slots
    // first_slot(t) .. first_slot(t + 1), the shared boundary value bit for bit, so every slot
    // is written exactly once. The slots are dealt out evenly, P / 256 consecutive ones a
    // thread: near a VPL a few clusters take most of the weight, and the thread holding them
    // wrote hundreds of slots in a row while the rest of the workgroup waited (on a GPU, a
    // serial chain per VPL). A thread finds each slot's owner by a binary search over the
    // first slots and walks the owner's clusters as the owner's own loop did, from their start
    // when the owner changes, so the choice is the same bit for bit.
    let slots = (p_count + GROUP - 1u) / GROUP;
    let s0 = min(lid * slots, p_count);
    let s1 = min(s0 + slots, p_count);
    var t = GROUP;
    var f = Found(0u, 0.0, 0.0);
    for (var i = s0; i < s1; i = i + 1u) {
        let owner_i = owner(i, scale, xi);
        let t_lo = min(owner_i * per, n_clusters);
        let t_hi = min(t_lo + per, n_clusters);
        if owner_i != t {
            t = owner_i;
            var acc = 0.0;
            if t > 0u {
                acc = scan[t - 1u];
            }
            f = start_walk(t_lo, t_hi, acc, o, n);
        }
        let u = (f32(i) + xi) / scale;
        f = walk(f, t_hi, u, o, n);
        write_slot(i, base, all_base, u, f, total);
    }
}

// The first slot of thread t's share: ceil(scan[t - 1] P / W - xi) (0 for t = 0).
fn first_slot(t: u32, scale: f32, xi: f32) -> u32 {
    if t == 0u {
        return 0u;
    }
    return u32(max(ceil(scan[t - 1u] * scale - xi), 0.0));
}

// The thread whose share holds slot i: the last t with first_slot(t) <= i.
fn owner(i: u32, scale: f32, xi: f32) -> u32 {
    var lo = 0u;
    var hi = GROUP - 1u;
    while lo < hi {
        let mid = (lo + hi + 1u) / 2u;
        if first_slot(mid, scale, xi) <= i {
            lo = mid;
        } else {
            hi = mid - 1u;
        }
    }
    return lo;
}

// Where sample u falls among clusters lo..hi whose weights start at acc: the cluster, the
// weights before it, its weight.
struct Found {
    c: u32,
    acc: f32,
    w: f32,
}

// The walk's state at the first of clusters lo..hi, whose weights start at `start`.
fn start_walk(lo: u32, hi: u32, start: f32, o: vec3<f32>, n: vec3<f32>) -> Found {
    var w = 0.0;
    if lo < hi {
        w = weight(clusters[lo], o, n);
    }
    return Found(lo, start, w);
}

// The walk from `f` on to sample u (never back: the samples of a thread's share grow).
fn walk(f: Found, hi: u32, u: f32, o: vec3<f32>, n: vec3<f32>) -> Found {
    var c = f.c;
    var acc = f.acc;
    var w = f.w;
    while c + 1u < hi && (acc + w <= u || w <= 0.0) {
        acc = acc + w;
        c = c + 1u;
        w = weight(clusters[c], o, n);
    }
    return Found(c, acc, w);
}

// Writes slot i (sample u) of a VPL whose slots start at `base` (`all_base` in `chosen_all`): the
// point at the same relative position inside the found cluster as the sample inside its weight,
// and the area it stands for.
fn write_slot(i: u32, base: u32, all_base: u32, u: f32, f: Found, total: f32) {
    let p_count = sp.counts.y;
    let cl = clusters[min(f.c, sp.counts.z - 1u)];
    if f.w <= 0.0 || cl.count == 0u {
        chosen[base + i] = vec2<u32>(NONE, 0u);
        chosen_all[all_base + i] = NONE;
        return;
    }
    let frac = clamp((u - f.acc) / f.w, 0.0, 0.99999);
    let j = cl.first + min(u32(frac * f32(cl.count)), cl.count - 1u);
    let a = sp.params.x / max(point_normals[j].w, 1.0e-6);
    let area = a * f32(cl.count) * total / (f32(p_count) * f.w);
    chosen[base + i] = vec2<u32>(j, bitcast<u32>(area));
    chosen_all[all_base + i] = j;
}
