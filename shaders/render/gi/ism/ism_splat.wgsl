// ISM pass P7: imperfect shadow maps by point splatting (Ritschel et al. 2008 as used by Knecht
// 2009). Each VPL's own points (`ism_select.wgsl`: P pool points chosen by solid angle, each
// with the area it stands for) are splatted into that VPL's paraboloid tile of the atlas with
// an atomic min of their packed normalised distance (depth in the high bits), into an atlas
// `ism_clear.wgsl` emptied. Each bounce's VPL set has its own block of tiles (`sets.x` is the
// set's first VPL).
//
// A point stands for a disk of its surface (the area it was chosen to stand for), and its splat is
// that disk's footprint in the paraboloid map: the ellipse spanned by the projections of two
// tangent radii, widened by half a texel (an EWA-style footprint, so an edge-on disk still
// writes a line of texels). Screen-aligned squares of the face-on size (the earlier splat)
// were too small at the paraboloid's rim (twice the texels per radian of its centre; the atlas
// showed empty rings round every map), and squares twice that size closed the doorways (the
// wall lit through the suite's second doorway kept 2% of its one-bounce light). Each texel
// stores the depth of the disk's plane along its own ray (`disk_depth`), not the centre's, and
// which point it is (`ism_pack` in `common/vpl.wgsl`), so lookups test their own rays against
// that point's surface (`ism_lookup.wgsl`).
#import common/onb.wgsl
#import common/vpl.wgsl
#import render/gi/ism/ism_clips.wgsl
#import render/gi/ism/ism_footprint.wgsl

struct SplatParams {
    // VPL count, points per ISM P, tile side r, tiles per row C.
    counts: vec4<u32>,
    // 1 / d_max (normalised distance), splat radius^2 / pi (disk radius^2 per m^2 of area),
    // max splat half-extent in texels, unused.
    params: vec4<f32>,
    // first VPL (and atlas tile) of the set being splatted, unused x3.
    sets: vec4<u32>,
}


@group(0) @binding(0) var<uniform> sp: SplatParams;
@group(0) @binding(1) var<storage, read> points: array<vec4<f32>>;
@group(0) @binding(2) var<storage, read> vpls: array<Vpl>;
@group(0) @binding(3) var<storage, read_write> atlas: array<atomic<u32>>;
// xyz normal, w = the object's sampling weight.
@group(0) @binding(4) var<storage, read> point_normals: array<vec4<f32>>;
// Per VPL k and slot i at k P + i: pool point index (0xffffffff: none), its area's bits.
@group(0) @binding(5) var<storage, read> chosen: array<vec2<u32>>;
// CLIPS lines per pool point (`ism_clips.wgsl`).
@group(0) @binding(6) var<storage, read> clips: array<vec4<f32>>;

// The sine of the elevation, seen from a point, below which the VPL counts as on its plane.
const ON_PLANE: f32 = 2.0e-3;

// One point's splat, set up once: its VPL and tile, its disk and the footprint's ellipse, the
// rows it covers in the tile, and its clip lines.
struct Splat {
    // Whether the point splats at all (chosen, its VPL alive, in front of it, not edge-on).
    valid: bool,
    // Its slot among its VPL's points, + 1 (the texel's point, `ism_pack`).
    slot: u32,
    origin: vec2<i32>,
    side: u32,
    o: vec3<f32>,
    frame: mat3x3<f32>,
    p: vec3<f32>,
    n: vec3<f32>,
    radius: f32,
    depth: f32,
    centre: vec2<f32>,
    // The footprint's covariance (m00, m01, m11, det).
    m: vec4<f32>,
    // Its box in the tile: columns lo.x..hi.x, rows lo.y..hi.y (empty where lo.y > hi.y).
    lo: vec2<i32>,
    hi: vec2<i32>,
    edges: SplatClips,
}

// The splat of slot `i` (VPL i / P of the set, its point chosen[i]).
fn splat_setup(i: u32) -> Splat {
    var s: Splat;
    s.valid = false;
    s.lo = vec2<i32>(1);
    s.hi = vec2<i32>(0);
    let per = sp.counts.y;
    if i >= sp.counts.x * per {
        return s;
    }
    let k = i / per;
    let pick = chosen[i];
    if pick.x == 0xffffffffu {
        return s;
    }
    let j = pick.x;
    let tile = sp.sets.x + k;
    let vpl = vpls[tile];
    if vpl.position.w <= 0.0 {
        return s;
    }
    let pb = paraboloid(vpl.position.xyz, vpl.normal.xyz, points[j].xyz);
    if pb.w <= 0.0 {
        return s;
    }
    // A point whose plane runs through the VPL (the ceiling around a VPL on the ceiling) is seen
    // edge-on: no ray leaving the VPL crosses its surface, so it shadows nothing, while its
    // splat (a depth-only word where the texel's ray runs away from its plane) would fill the
    // texels at the horizon with the nearest depths and hide the walls behind them.
    if abs(dot(points[j].xyz - vpl.position.xyz, point_normals[j].xyz)) <= ON_PLANE * distance(points[j].xyz, vpl.position.xyz) {
        return s;
    }
    let r = sp.counts.z;
    let c = sp.counts.w;
    s.valid = true;
    s.slot = i % per + 1u;
    s.side = r * c;
    s.origin = vec2<i32>(i32((tile % c) * r), i32((tile / c) * r));
    // The disk's footprint: centre and the images of two orthogonal tangent radii (texels).
    let fr = f32(r);
    s.p = points[j].xyz;
    s.n = point_normals[j].xyz;
    s.radius = sqrt(sp.params.y * bitcast<f32>(pick.y));
    s.depth = pb.z;
    s.centre = pb.xy * fr;
    let ta = paraboloid(vpl.position.xyz, vpl.normal.xyz, s.p + onb_tangent(s.n) * s.radius).xy * fr - s.centre;
    let tb = paraboloid(vpl.position.xyz, vpl.normal.xyz, s.p + onb_bitangent(s.n) * s.radius).xy * fr - s.centre;
    // Its covariance plus half a texel each way; texel offsets q with q^T M^-1 q <= 1 are in.
    s.m = footprint_moments(ta, tb);
    let ext = min(vec2<f32>(sqrt(s.m.x), sqrt(s.m.z)), vec2<f32>(sp.params.z));
    s.lo = vec2<i32>(floor(s.centre - ext));
    s.hi = vec2<i32>(floor(s.centre + ext));
    s.lo.y = max(s.lo.y, 0);
    s.hi.y = min(s.hi.y, i32(r) - 1);
    s.o = vpl.position.xyz;
    s.frame = mat3x3<f32>(onb_tangent(vpl.normal.xyz), onb_bitangent(vpl.normal.xyz), vpl.normal.xyz);
    // The point's clip lines, read once for the whole footprint (rereading them from storage
    // for every texel cost lavapipe about a fifth of the maps pass: rooms 2650 -> 2100 ms).
    s.edges = splat_clips(j, 0.01 * s.radius);
    return s;
}

// The columns row `y` of splat `s` walks, x0..x1 (empty where x0 > x1): its span
// (`row_span`) within its box and the tile.
fn row_columns(s: Splat, y: i32) -> vec2<i32> {
    let span = row_span(s.centre, y, s.m.x, s.m.y, s.m.z, s.m.w);
    return vec2<i32>(max(max(s.lo.x, span.x), 0), min(min(s.hi.x, span.y), i32(sp.counts.z) - 1));
}

fn width(columns: vec2<i32>) -> u32 {
    return u32(max(columns.y - columns.x + 1, 0));
}

// The texels splat `s` walks, over all its rows.
fn splat_texels(s: Splat) -> u32 {
    var n = 0u;
    for (var y = s.lo.y; y <= s.hi.y && s.valid; y = y + 1) {
        n = n + width(row_columns(s, y));
    }
    return n;
}

// Texel (x, y) of splat `s`, if the footprint covers it and the surface holds it, gets the
// disk's depth along its ray (an atomic min, so any order of texels and points writes the same
// atlas).
fn splat_texel(s: Splat, x: i32, y: i32) {
    let m = s.m;
    if !footprint_covers(s.centre, x, y, m.x, m.y, m.z, m.w) {
        return;
    }
    let own = x == i32(s.centre.x) && y == i32(s.centre.y);
    let dir = texel_ray(s.frame, (vec2<f32>(f32(x), f32(y)) + 0.5) / f32(sp.counts.z));
    let hit = plane_hit(s.o, dir, s.p, s.n);
    // Texels whose ray meets the plane past the surface's open edges (over a doorway, past a
    // wall's end) show no surface: the disk does not hang there. (A margin of 1% of the disk
    // radius: two faces meeting at an edge leave no crack between them.)
    if !own && hit > 0.0 && s.edges.any_line && !splat_clips_admit(s.edges, s.o + dir * hit) {
        return;
    }
    let a = s.origin + vec2<i32>(x, y);
    let t = disk_depth(hit, s.depth, s.radius);
    // The point goes with the depth where its texel's ray meets its plane ahead.
    let bits = ism_pack(t * sp.params.x, select(0u, s.slot, hit > 0.0));
    atomicMin(&atlas[u32(a.y) * s.side + u32(a.x)], bits);
}

// One thread per point, walking its whole footprint: the software adapter's splat (its atomics
// run lane by lane, so idle lanes cost it little; `splat_entry` in `gather/mod.rs`), and the
// reference the balanced pass below is checked against (`tests/integration/ism_footprint.rs`).
@compute @workgroup_size(64, 1, 1)
fn splat_per_point(@builtin(global_invocation_id) id: vec3<u32>) {
    let s = splat_setup(id.x);
    for (var y = s.lo.y; y <= s.hi.y && s.valid; y = y + 1) {
        let columns = row_columns(s, y);
        for (var x = columns.x; x <= columns.y; x = x + 1) {
            splat_texel(s, x, y);
        }
    }
}

// A workgroup's 64 points, their texels dealt out among its threads in equal runs. A point's
// footprint can be 33 rows of 33 texels (one beside its VPL, or seen at a grazing angle) where
// most are a few texels, and a thread walking a whole footprint kept the other lanes of its
// group idle: over the suite's rooms, a 32-lane group spent 19% of its time walking texels
// (`bouncelab probe-ism rooms --splat-lanes`). Dealing out whole rows raised that to 42% only
// (rows run from 1 to 33 texels); texels themselves keep every lane within one texel of the
// others, at the cost of walking each point's rows' spans once more to count them.
const SPLAT_GROUP: u32 = 64u;
// Per point of the workgroup: the end of its texels in the workgroup's texel list (the
// inclusive scan of the points' texels).
var<workgroup> texel_end: array<u32, 64>;

fn texel_start(q: u32) -> u32 {
    if q == 0u {
        return 0u;
    }
    return texel_end[q - 1u];
}

@compute @workgroup_size(64, 1, 1)
fn splat(@builtin(workgroup_id) wid: vec3<u32>, @builtin(local_invocation_index) lid: u32) {
    let base = wid.x * SPLAT_GROUP;
    texel_end[lid] = splat_texels(splat_setup(base + lid));
    workgroupBarrier();
    // Inclusive scan of the texels (Hillis-Steele).
    for (var off = 1u; off < SPLAT_GROUP; off = off * 2u) {
        var v = texel_end[lid];
        if lid >= off {
            v = v + texel_end[lid - off];
        }
        workgroupBarrier();
        texel_end[lid] = v;
        workgroupBarrier();
    }
    let total = texel_end[SPLAT_GROUP - 1u];
    let run = (total + SPLAT_GROUP - 1u) / SPLAT_GROUP;
    let first = min(lid * run, total);
    let last = min(first + run, total);
    if first >= last {
        return;
    }
    // The point that holds texel `first`: the first whose texels end past it.
    var lo = 0u;
    var hi = SPLAT_GROUP - 1u;
    while lo < hi {
        let mid = (lo + hi) / 2u;
        if texel_end[mid] > first {
            hi = mid;
        } else {
            lo = mid + 1u;
        }
    }
    var q = lo;
    var s = splat_setup(base + q);
    // Its row and column: skip the rows before it.
    var k = first - texel_start(q);
    var y = s.lo.y;
    var columns = row_columns(s, y);
    // (Bounded by the point's rows and the workgroup's points: should a row's span come out
    // narrower here than where it was counted, a texel is lost, not the device.)
    while k >= width(columns) && y <= s.hi.y {
        k = k - width(columns);
        y = y + 1;
        columns = row_columns(s, y);
    }
    for (var item = first; item < last; item = item + 1u) {
        splat_texel(s, columns.x + i32(k), y);
        k = k + 1u;
        // On to the next texel: the rest of this row, the next row with columns, or the next
        // point with texels (one exists while items are left).
        while item + 1u < last && k >= width(columns) {
            k = 0u;
            y = y + 1;
            if y > s.hi.y {
                if q + 1u >= SPLAT_GROUP {
                    return;
                }
                q = q + 1u;
                while texel_end[q] == texel_start(q) && q + 1u < SPLAT_GROUP {
                    q = q + 1u;
                }
                s = splat_setup(base + q);
                y = s.lo.y;
            }
            columns = row_columns(s, y);
        }
    }
}

// The depth a splat writes: the distance `hit` from the VPL to the disk's plane along the
// texel's ray, never nearer than the disk's nearest point d - radius (a ray that meets the plane
// in front of the disk, in the footprint's half-texel margin) and the centre's distance d
// where the ray runs along the plane or away from it. Writing the plane's depth per texel
// instead of the centre's lets a wall's splats stop at the floor it stands on: a ray past the
// wall's lowest disk meets its plane beyond the floor, so the floor's receivers next to the
// wall stay lit (with the centre's depth those splats hung below the floor, nearer than the
// receivers, and shadowed them).
fn disk_depth(hit: f32, d: f32, radius: f32) -> f32 {
    var t = hit;
    if t <= 0.0 {
        t = d;
    }
    return max(t, d - radius);
}

// Distance along `dir` from `o` to the plane through `p` with normal `n`; 0 when the ray runs
// along the plane, negative when the plane is behind.
fn plane_hit(o: vec3<f32>, dir: vec3<f32>, p: vec3<f32>, n: vec3<f32>) -> f32 {
    let den = dot(dir, n);
    if abs(den) <= 1.0e-6 {
        return 0.0;
    }
    return dot(p - o, n) / den;
}

// The world direction of the paraboloid texel at `uv` (0..1) of a VPL with tangent frame `frame`.
fn texel_ray(frame: mat3x3<f32>, uv: vec2<f32>) -> vec3<f32> {
    let s = uv * 2.0 - 1.0;
    let ss = dot(s, s);
    return frame * (vec3<f32>(2.0 * s, 1.0 - ss) / (1.0 + ss));
}

// A point's clip lines prepared for one splat (`within_edges` in `ism_clips.wgsl` without seams,
// its per-line terms computed once): `rhs[k]` is the bound dot(xyz, h) / `div[k]` must reach.
struct SplatClips {
    l0: vec4<f32>,
    l1: vec4<f32>,
    l2: vec4<f32>,
    l3: vec4<f32>,
    rhs: vec4<f32>,
    div: vec4<f32>,
    // Whether line k is a seam's (divided by its length).
    seam: vec4<bool>,
    // Whether any line can reject a hit (empty slots, (0, 0, 0, -1), admit every hit).
    any_line: bool,
}

// The bound of one clip line, as `within_edges` computes it per hit: seams by their length s.
fn clip_bound(line: vec4<f32>, margin: f32) -> vec3<f32> {
    let s2 = dot(line.xyz, line.xyz);
    if s2 > 2.0 {
        let s = sqrt(s2);
        return vec3<f32>(line.w / s - (s - SEAM_SCALE) - margin, s, 1.0);
    }
    return vec3<f32>(line.w - margin, 1.0, 0.0);
}

fn splat_clips(i: u32, margin: f32) -> SplatClips {
    let l0 = clips[i * CLIPS];
    let l1 = clips[i * CLIPS + 1u];
    let l2 = clips[i * CLIPS + 2u];
    let l3 = clips[i * CLIPS + 3u];
    let b0 = clip_bound(l0, margin);
    let b1 = clip_bound(l1, margin);
    let b2 = clip_bound(l2, margin);
    let b3 = clip_bound(l3, margin);
    let empty = vec4<f32>(0.0, 0.0, 0.0, -1.0);
    let any_line = any(l0 != empty) || any(l1 != empty) || any(l2 != empty) || any(l3 != empty);
    return SplatClips(
        l0, l1, l2, l3,
        vec4<f32>(b0.x, b1.x, b2.x, b3.x),
        vec4<f32>(b0.y, b1.y, b2.y, b3.y),
        vec4<bool>(b0.z > 0.5, b1.z > 0.5, b2.z > 0.5, b3.z > 0.5),
        any_line,
    );
}

fn clip_line_admits(line: vec4<f32>, rhs: f32, div: f32, seam: bool, h: vec3<f32>) -> bool {
    if seam {
        return !(dot(line.xyz, h) / div < rhs);
    }
    return !(dot(line.xyz, h) < rhs);
}

// Whether hit `h` is on the point's surface: `on_surface` of `ism_clips.wgsl` with the lines
// prepared by `splat_clips`.
fn splat_clips_admit(c: SplatClips, h: vec3<f32>) -> bool {
    return clip_line_admits(c.l0, c.rhs.x, c.div.x, c.seam.x, h)
        && clip_line_admits(c.l1, c.rhs.y, c.div.y, c.seam.y, h)
        && clip_line_admits(c.l2, c.rhs.z, c.div.z, c.seam.z, h)
        && clip_line_admits(c.l3, c.rhs.w, c.div.w, c.seam.w, h);
}
