// MRT pass F (Loos 2015 §3.6.2, §3.6.3 step 7): the lightmap applied to the real scene. Each pixel
// belongs to the block its surface faces into (the box nearest to the point lifted 5 cm along its
// normal; or the block an artist assigned its object to) and to that block's present face whose inward normal is closest to the pixel's normal
// (a floor to the floor, a wall to the wall behind it); its lightmap coordinate is the
// orthographic projection of the point onto that face in the block's canonical frame, read
// bilinearly between texel centres, clamped at the face's border. A surface in a partly open
// side (the wall around a doorway) reads that side's own texels (pass E); one in a side open
// over its whole area blends its neighbouring faces; near a side open over its whole area the block beyond is
// blended in (padding). A clutter object's pixel reads its own texels (DRT's gather C_b).
// Writes E / pi (the composite multiplies by the albedo);
// `assignment` holds the block and face for the inspector.
#import common/frame.wgsl
#import common/octahedral.wgsl
#import render/gi/mrt/mrt_common.wgsl

@group(0) @binding(0) var<uniform> frame: Frame;
@group(0) @binding(1) var<uniform> mp: MrtParams;
@group(0) @binding(2) var<storage, read> blocks: array<Block>;
@group(0) @binding(3) var<storage, read> indirect: array<vec4<f32>>;
@group(0) @binding(4) var depth_tex: texture_depth_2d;
@group(0) @binding(5) var normal_tex: texture_2d<f32>;
@group(0) @binding(6) var out_indirect: texture_storage_2d<rgba32float, write>;
@group(0) @binding(7) var assignment: texture_storage_2d<rgba32float, write>;
// The G-buffer's object id (scene index + 1, 0 where none) and each object's overridden block.
@group(0) @binding(8) var object_tex: texture_2d<u32>;
@group(0) @binding(9) var<storage, read> object_block: array<u32>;
// DRT (`render::gi::mrt::drt_pack`): the clutter boxes, each object's clutter record (MRT_NONE
// where it is none) and the clutter texels' gathered light (E / pi).
struct Clutter {
    lo: vec4<f32>,
    hi: vec4<f32>,
    // First texel, texels per face side, unused x2.
    texels: vec4<u32>,
}
@group(0) @binding(10) var<storage, read> clutter: array<Clutter>;
@group(0) @binding(11) var<storage, read> object_clutter: array<u32>;
@group(0) @binding(12) var<storage, read> clutter_gather: array<vec4<f32>>;

// A clutter object's light at world point `p` with normal `n`: the face of its box its normal
// points out of (dominant axis), bilinear between texel centres (`precompute::drt::clutter::taps`).
fn clutter_lookup(c: Clutter, p: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    let a = abs(n);
    var axis = 0u;
    if a.y > a.x && a.y >= a.z {
        axis = 1u;
    } else if a.z > a.x && a.z > a.y {
        axis = 2u;
    }
    let face = axis * 2u + select(0u, 1u, n[axis] > 0.0);
    let extent = max(c.hi.xyz - c.lo.xyz, vec3<f32>(1.0e-6));
    let u = clamp((p - c.lo.xyz) / extent, vec3<f32>(0.0), vec3<f32>(1.0));
    let res = c.texels.y;
    let r = f32(res);
    let st = clamp(plane_st(face, u) * r - 0.5, vec2<f32>(0.0), vec2<f32>(r - 1.0));
    let i0 = min(vec2<u32>(floor(st)), vec2<u32>(res - 1u));
    let i1 = min(i0 + 1u, vec2<u32>(res - 1u));
    let f = st - vec2<f32>(i0);
    let base = c.texels.x + face * res * res;
    let v00 = clutter_gather[base + i0.y * res + i0.x].rgb;
    let v10 = clutter_gather[base + i0.y * res + i1.x].rgb;
    let v01 = clutter_gather[base + i1.y * res + i0.x].rgb;
    let v11 = clutter_gather[base + i1.y * res + i1.x].rgb;
    return max(mix(mix(v00, v10, f.x), mix(v01, v11, f.x), f.y), vec3<f32>(0.0));
}

fn box_distance(b: Block, q: vec3<f32>) -> f32 {
    let lo = b.origin.xyz;
    let hi = lo + b.size.xyz;
    let d = max(max(lo - q, q - hi), vec3<f32>(0.0));
    return length(d);
}

fn texel_at(start: u32, s: u32, t: u32) -> vec3<f32> {
    return max(indirect[start + t * mp.sizes.y + s].rgb, vec3<f32>(0.0));
}

// In-plane coordinates (s, t) of canonical point `lp` on canonical face `face`
// (shape::Face::plane_axes: x faces (z, y), y faces (x, z), z faces (x, y)).
fn plane_st(face: u32, lp: vec3<f32>) -> vec2<f32> {
    let axis = face / 2u;
    if axis == 0u {
        return vec2<f32>(lp.z, lp.y);
    }
    if axis == 1u {
        return vec2<f32>(lp.x, lp.z);
    }
    return vec2<f32>(lp.x, lp.y);
}

// The lightmap of present face `face` at canonical point `lp`, bilinear between texel centres,
// clamped at the face's border.
fn face_lookup(start: u32, face: u32, lp: vec3<f32>) -> vec3<f32> {
    let res = f32(mp.sizes.y);
    let c = clamp(plane_st(face, lp) * res - 0.5, vec2<f32>(0.0), vec2<f32>(res - 1.0));
    let i0 = vec2<u32>(floor(c));
    let i1 = min(i0 + 1u, vec2<u32>(mp.sizes.y - 1u));
    let f = c - floor(c);
    return mix(
        mix(texel_at(start, i0.x, i0.y), texel_at(start, i1.x, i0.y), f.x),
        mix(texel_at(start, i0.x, i1.y), texel_at(start, i1.x, i1.y), f.x),
        f.y,
    );
}

// A surface in an open side (the wall around a doorway when a room's whole side is its
// opening) has no texels: blend the four neighbouring faces' light at the point's projection
// onto each, weighted towards the nearer edge (a Coons-like patch across the opening, so the
// open side continues its neighbours smoothly instead of taking whichever is nearest).
fn open_side_lookup(blk: Block, face: u32, lp: vec3<f32>) -> vec3<f32> {
    let axis = face / 2u;
    var sum = vec3<f32>(0.0);
    var weight = 0.0;
    for (var k = 0u; k < 3u; k = k + 1u) {
        if k == axis {
            continue;
        }
        for (var side = 0u; side < 2u; side = side + 1u) {
            let g = k * 2u + side;
            let start = block_start(blk, g);
            if start == MRT_NONE {
                continue;
            }
            let along = clamp(lp[k], 0.0, 1.0);
            let w = select(1.0 - along, along, side == 1u) + 1.0e-3;
            sum = sum + w * face_lookup(start, g, lp);
            weight = weight + w;
        }
    }
    return sum / max(weight, 1.0e-6);
}

// The light on the closed part of partly open world side `side` of `blk` at world point `p`:
// bilinear between the P x P side texels from `start` (u = n x up across the side, v up; the
// frame of `precompute::mrt::geometry_image::SideFrame`), clamped at the border.
fn side_lookup(blk: Block, side: u32, start: u32, p: vec3<f32>) -> vec3<f32> {
    let axis = side / 2u;
    var n = vec3<f32>(0.0);
    n[axis] = select(-1.0, 1.0, side % 2u == 1u);
    let u = cross(n, vec3<f32>(0.0, 1.0, 0.0));
    let centre = blk.origin.xyz + 0.5 * blk.size.xyz;
    let width = select(blk.size.x, blk.size.z, abs(u.z) > 0.5);
    let fu = dot(p - centre, u) / width + 0.5;
    let fv = (p.y - blk.origin.y) / blk.size.y;
    let res = f32(mp.sides.x);
    let c = clamp(vec2<f32>(fu, fv) * res - 0.5, vec2<f32>(0.0), vec2<f32>(res - 1.0));
    let i0 = vec2<u32>(floor(c));
    let i1 = min(i0 + 1u, vec2<u32>(mp.sides.x - 1u));
    let f = c - floor(c);
    let at = start + vec4<u32>(i0.y, i0.y, i1.y, i1.y) * mp.sides.x + vec4<u32>(i0.x, i1.x, i0.x, i1.x);
    let a = max(indirect[at.x].rgb, vec3<f32>(0.0));
    let b = max(indirect[at.y].rgb, vec3<f32>(0.0));
    let c0 = max(indirect[at.z].rgb, vec3<f32>(0.0));
    let d = max(indirect[at.w].rgb, vec3<f32>(0.0));
    return mix(mix(a, b, f.x), mix(c0, d, f.x), f.y);
}

// The light of block `x` at world point `p` with normal `n` (rgb) and the canonical face read (w).
fn block_light(x: u32, p: vec3<f32>, n: vec3<f32>) -> vec4<f32> {
    let blk = blocks[x];
    let lp = block_local_point(blk, p);
    // The side whose inward normal is closest to the pixel's; among sides the normal meets alike
    // (a lintel's underside, a jamb) the nearest plane, so the choice does not flicker.
    var side = 0u;
    var best_c = -1.0e9;
    for (var w = 0u; w < 6u; w = w + 1u) {
        let f = block_local(blk, w);
        let plane = select(lp[f / 2u], 1.0 - lp[f / 2u], f % 2u == 1u);
        let c = dot(n, side_inward(w)) - 0.25 * clamp(plane, 0.0, 1.0);
        if c > best_c {
            best_c = c;
            side = w;
        }
    }
    let face = block_local(blk, side);
    let start = block_start(blk, face);
    if start == MRT_NONE {
        let side_start = block_side(blk, side);
        if side_start != MRT_NONE {
            return vec4<f32>(side_lookup(blk, side, side_start, p), f32(face));
        }
        return vec4<f32>(open_side_lookup(blk, face, lp), f32(face));
    }
    return vec4<f32>(face_lookup(start, face, lp), f32(face));
}

@compute @workgroup_size(8, 8, 1)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = vec2<u32>(frame.size.xy);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    let pixel = id.xy;
    let depth = textureLoad(depth_tex, pixel, 0);
    if depth <= 0.0 || mp.counts.x == 0u {
        textureStore(out_indirect, pixel, vec4<f32>(0.0, 0.0, 0.0, 1.0));
        textureStore(assignment, pixel, vec4<f32>(-1.0, -1.0, 0.0, 1.0));
        return;
    }
    let p = world_from_pixel(frame, pixel, depth);
    let n = oct_decode(textureLoad(normal_tex, pixel, 0).zw);
    let q = p + n * 0.05;
    var best = 0u;
    var best_d = 1.0e30;
    let object = textureLoad(object_tex, pixel, 0).x;
    if object > 0u && object - 1u < arrayLength(&object_clutter) {
        let k = object_clutter[object - 1u];
        if k != MRT_NONE && k < arrayLength(&clutter) {
            // Clutter reads its own gathered light (C_b); face 6 marks it in the assignment.
            textureStore(out_indirect, pixel, vec4<f32>(clutter_lookup(clutter[k], p, n), 1.0));
            textureStore(assignment, pixel, vec4<f32>(-2.0 - f32(k), 6.0, 0.0, 1.0));
            return;
        }
    }
    var forced = MRT_NONE;
    if object > 0u && object - 1u < arrayLength(&object_block) {
        forced = object_block[object - 1u];
    }
    if forced < mp.counts.x {
        // The artist assigned this object to a block.
        best = forced;
        best_d = box_distance(blocks[forced], q);
    } else {
        for (var x = 0u; x < mp.counts.x; x = x + 1u) {
            let d = box_distance(blocks[x], q);
            if d < best_d {
                best_d = d;
                best = x;
            }
        }
    }
    let here = block_light(best, p, n);
    var e = here.rgb;
    // Padding (Loos 2015 §4.6): within half a texel of a side open over its whole area, blend
    // towards the block beyond, so both sides meet at the same value (the dissertation's padded
    // atlas, read here from the neighbour's own faces).
    if mp.sizes.z == 1u {
        let blk = blocks[best];
        let lp = block_local_point(blk, p);
        for (var f = 0u; f < 6u; f = f + 1u) {
            let nb = block_across(blk, f);
            if nb == MRT_NONE || f / 2u == 1u {
                continue;
            }
            // Texels from the side; beyond it (a point an override assigned to this block) the
            // blend stays at half and fades out within half a texel.
            let dist = select(lp[f / 2u], 1.0 - lp[f / 2u], f % 2u == 1u) * f32(mp.sizes.y);
            if dist < 0.5 && dist > -0.5 {
                e = mix(e, block_light(nb, p, n).rgb, 0.5 - max(dist, 0.0));
            }
        }
    }
    let face = u32(here.w);
    textureStore(out_indirect, pixel, vec4<f32>(e, 1.0));
    textureStore(assignment, pixel, vec4<f32>(f32(best), f32(face), best_d, 1.0));
}
