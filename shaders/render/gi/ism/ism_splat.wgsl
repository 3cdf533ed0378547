// ISM pass P7: imperfect shadow maps by point splatting (Ritschel et al. 2008 as used by Knecht
// 2009). Each scene sample point belongs to one VPL (contiguous blocks of points per VPL) and is
// splatted into that VPL's paraboloid tile of the atlas with an atomic min of its normalised
// distance (positive floats keep their order as u32). `clear` empties the atlas (1.0).
// Each bounce's VPL set has its own block of tiles (`sets.x` is the set's first VPL).
//
// A point stands for a disk of its surface (the area its ISM's points share), and its splat is
// that disk's footprint in the paraboloid map: the ellipse spanned by the projections of two
// tangent radii, widened by half a texel (an EWA-style footprint, so an edge-on disk still
// writes a line of texels). Screen-aligned squares of the face-on size (the earlier splat)
// were too small at the paraboloid's rim (twice the texels per radian of its centre; the atlas
// showed empty rings round every map), and squares twice that size closed the doorways (the
// wall lit through the suite's second doorway kept 2% of its one-bounce light).
#import common/onb.wgsl
#import common/vpl.wgsl

struct SplatParams {
    // VPL count, points, tile side r, tiles per row C.
    counts: vec4<u32>,
    // 1 / d_max (normalised distance), disk radius^2 at weight 1 (m^2), max splat half-extent
    // in texels, unused.
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

@compute @workgroup_size(8, 8, 1)
fn clear(@builtin(global_invocation_id) id: vec3<u32>) {
    let side = sp.counts.z * sp.counts.w;
    if id.x < side && id.y < side {
        atomicStore(&atlas[id.y * side + id.x], bitcast<u32>(1.0));
    }
}

@compute @workgroup_size(64, 1, 1)
fn splat(@builtin(global_invocation_id) id: vec3<u32>) {
    let n_vpl = sp.counts.x;
    let n_points = sp.counts.y;
    if id.x >= n_points {
        return;
    }
    let per = max(n_points / n_vpl, 1u);
    let k = id.x / per;
    if k >= n_vpl {
        return;
    }
    let tile = sp.sets.x + k;
    let vpl = vpls[tile];
    if vpl.position.w <= 0.0 {
        return;
    }
    let pb = paraboloid(vpl.position.xyz, vpl.normal.xyz, points[id.x].xyz);
    if pb.w <= 0.0 {
        return;
    }
    let r = sp.counts.z;
    let c = sp.counts.w;
    let side = r * c;
    let depth = min(pb.z * sp.params.x, 1.0);
    let origin = vec2<i32>(i32((tile % c) * r), i32((tile / c) * r));
    // The disk's footprint: centre and the images of two orthogonal tangent radii (texels).
    let fr = f32(r);
    let p = points[id.x].xyz;
    let nw = point_normals[id.x];
    let radius = sqrt(sp.params.y / max(nw.w, 1.0e-6));
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
    let bits = bitcast<u32>(depth) & ~1u;
    for (var y = max(lo.y, 0); y <= min(hi.y, i32(r) - 1); y = y + 1) {
        for (var x = max(lo.x, 0); x <= min(hi.x, i32(r) - 1); x = x + 1) {
            let q = vec2<f32>(f32(x), f32(y)) + 0.5 - centre;
            let inside = (m11 * q.x * q.x - 2.0 * m01 * q.x * q.y + m00 * q.y * q.y) <= det;
            let own = x == i32(centre.x) && y == i32(centre.y);
            if inside || own {
                let a = origin + vec2<i32>(x, y);
                // Even bit patterns: pull-push marks the texels it fills with the lowest bit.
                atomicMin(&atlas[u32(a.y) * side + u32(a.x)], bits);
            }
        }
    }
}
