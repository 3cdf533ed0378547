// ISM pass P7: imperfect shadow maps by point splatting (Ritschel et al. 2008 as used by Knecht
// 2009). Each VPL's own points (`ism_select.wgsl`: P pool points chosen by solid angle, each
// with the area it stands for) are splatted into that VPL's paraboloid tile of the atlas with
// an atomic min of their packed normalised distance (depth in the high bits). `clear` empties
// the atlas. Each bounce's VPL set has its own block of tiles (`sets.x` is the
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

@compute @workgroup_size(8, 8, 1)
fn clear(@builtin(global_invocation_id) id: vec3<u32>) {
    let side = sp.counts.z * sp.counts.w;
    if id.x < side && id.y < side {
        atomicStore(&atlas[id.y * side + id.x], ISM_EMPTY);
    }
}

@compute @workgroup_size(64, 1, 1)
fn splat(@builtin(global_invocation_id) id: vec3<u32>) {
    let per = sp.counts.y;
    if id.x >= sp.counts.x * per {
        return;
    }
    let k = id.x / per;
    let pick = chosen[id.x];
    if pick.x == 0xffffffffu {
        return;
    }
    let j = pick.x;
    let tile = sp.sets.x + k;
    let vpl = vpls[tile];
    if vpl.position.w <= 0.0 {
        return;
    }
    let pb = paraboloid(vpl.position.xyz, vpl.normal.xyz, points[j].xyz);
    if pb.w <= 0.0 {
        return;
    }
    // A point whose plane runs through the VPL (the ceiling around a VPL on the ceiling) is seen
    // edge-on: no ray leaving the VPL crosses its surface, so it shadows nothing, while its
    // splat (a depth-only word where the texel's ray runs away from its plane) would fill the
    // texels at the horizon with the nearest depths and hide the walls behind them.
    if abs(dot(points[j].xyz - vpl.position.xyz, point_normals[j].xyz)) <= ON_PLANE * distance(points[j].xyz, vpl.position.xyz) {
        return;
    }
    let r = sp.counts.z;
    let c = sp.counts.w;
    let side = r * c;
    let origin = vec2<i32>(i32((tile % c) * r), i32((tile / c) * r));
    // The disk's footprint: centre and the images of two orthogonal tangent radii (texels).
    let fr = f32(r);
    let p = points[j].xyz;
    let nw = point_normals[j];
    let radius = sqrt(sp.params.y * bitcast<f32>(pick.y));
    let centre = pb.xy * fr;
    let ta = paraboloid(vpl.position.xyz, vpl.normal.xyz, p + onb_tangent(nw.xyz) * radius).xy * fr - centre;
    let tb = paraboloid(vpl.position.xyz, vpl.normal.xyz, p + onb_bitangent(nw.xyz) * radius).xy * fr - centre;
    // Its covariance plus half a texel each way; texel offsets q with q^T M^-1 q <= 1 are in.
    let m00 = ta.x * ta.x + tb.x * tb.x + 0.25;
    let m01 = ta.x * ta.y + tb.x * tb.y;
    let m11 = ta.y * ta.y + tb.y * tb.y + 0.25;
    let det = m00 * m11 - m01 * m01;
    let ext = min(vec2<f32>(sqrt(m00), sqrt(m11)), vec2<f32>(sp.params.z));
    let lo = vec2<i32>(floor(centre - ext));
    let hi = vec2<i32>(floor(centre + ext));
    let o = vpl.position.xyz;
    let frame = mat3x3<f32>(onb_tangent(vpl.normal.xyz), onb_bitangent(vpl.normal.xyz), vpl.normal.xyz);
    for (var y = max(lo.y, 0); y <= min(hi.y, i32(r) - 1); y = y + 1) {
        for (var x = max(lo.x, 0); x <= min(hi.x, i32(r) - 1); x = x + 1) {
            let q = vec2<f32>(f32(x), f32(y)) + 0.5 - centre;
            let inside = (m11 * q.x * q.x - 2.0 * m01 * q.x * q.y + m00 * q.y * q.y) <= det;
            let own = x == i32(centre.x) && y == i32(centre.y);
            if inside || own {
                let dir = texel_ray(frame, (vec2<f32>(f32(x), f32(y)) + 0.5) / fr);
                let hit = plane_hit(o, dir, p, nw.xyz);
                // Texels whose ray meets the plane past the surface's open edges (over a
                // doorway, past a wall's end) show no surface: the disk does not hang there.
                // (A margin of 1% of the disk radius: two faces meeting at an edge leave no
                // crack between them.)
                if !own && hit > 0.0 && !on_surface(j, o + dir * hit, 0.01 * radius) {
                    continue;
                }
                let a = origin + vec2<i32>(x, y);
                let t = disk_depth(hit, pb.z, radius);
                // The point goes with the depth where its texel's ray meets its plane ahead.
                let bits = ism_pack(t * sp.params.x, select(0u, id.x % per + 1u, hit > 0.0));
                atomicMin(&atlas[u32(a.y) * side + u32(a.x)], bits);
            }
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
