// The ISM visibility test of a receiver (shading and the bounce pass). The including shader
// binds `points`, `point_normals` (pool positions and normals), `clips` (`ism_clips.wgsl`) and
// `chosen_all` (per VPL of every set and slot: the pool point, `ism_select.wgsl`), and
// `atlas_coarse` (the pull-push levels, each after the finer ones).
//
// An atlas texel holds the nearest splat along its centre ray and, in its word, which point
// made it (`ism_pack` in `common/vpl.wgsl`). A receiver whose ray passes through the texel is
// shadowed when that ray meets the point's surface before it: the point's plane, bounded by the
// open edges near it (its clip lines), nowhere else. Two errors of a depth compare at the texel
// centre go away:
// - a flat surface no longer shadows itself where the receiver's ray and the centre's meet it
//   at different depths (what a slope-scaled bias or normal offset had to cover, and such an
//   offset shifts the light falling through a doorway);
// - a texel that straddles an occluder's open edge (a door's jamb, 11 m down a corridor and
//   seen at 6 degrees narrower than a texel) no longer shadows the rays that pass the edge.
// A texel without a point (the splat's ray ran along its plane) falls back to its depth with a
// relative `margin`.
//
// A texel holds one surface, so where two meet inside it the farther is lost. At a door's jamb
// the jamb's point wins the texel, and a receiver whose ray passes the jamb's edge but meets the
// wall beside the door a centimetre further on was lit: in the held-out four-room flat this was
// 0.69 of the power wrongly lit from the lamp's room into the camera's (`bouncelab probe-ism
// --grid 4.6,3.6 --pair 0,3`). When the ray meets the stored point's plane before the receiver but
// outside its clip lines, the four neighbouring texels' points are asked too. They are tested
// against their own surfaces (within their open edges and their seams), so they add only real
// occluders. They are asked too where the texel's point is much nearer than the receiver but
// its plane is not crossed on the way (a floor at a grazing angle, or the receiver's own plane,
// holds the texel while a wall stands in the next one), and a neighbour's point covers its disk
// as the VPL sees it, stretched by 1 / cos along the ray's slope (`within_disk`): the flat's
// first set then sent 14x the true light into the camera's room, against 19.7x. Where the
// texel's own word shows the way clear (it holds the receiver's own surface) they are asked
// when the texel's 4x4 block holds a surface in front of the receiver (`ism_nearer_around`):
// the receiver's ray may run into a door's head a texel over. The including shader binds
// `atlas`.
//
// Most of what still leaked were holes: no splat of a wall's points covered the texel, which
// showed the surface behind (each ISM's points are a sample; disks of 1.35 times their share
// leave gaps). Ritschel's push fills such texels by overwriting them with the coarser level's
// depth; here the lookup asks the coarse levels instead (`ism_hole_blocks`), which also keeps
// the occluder the texel holds. The flat's first set then sent 5.3x (of a tiny true amount),
// and its later sets' lookups read within 0.3% of rays' (`probe-ism --unburied`).
//
// Every point test also asks whether the ray runs through the solid behind the point's face
// (`slab_blocks`: the depth of that solid is the point's w, found once per distribution), which
// the plane alone misses where the texel holds a face seen past its edge: over a door's head the
// flat's first set sent 5.1x the true light into the camera's room, 4.1x with the slab test.
#import render/gi/ism/ism_clips.wgsl

// What the point of atlas word `stored` says of the receiver's ray `l`: BLOCKED (its surface is
// crossed before the receiver), UNSURE (the ray meets its plane before the receiver but past
// its open edges, or the texel's own point is much nearer than the receiver and its plane is
// not crossed) or CLEAR (anything else: its plane lies beyond the receiver or contains it,
// or only a depth is stored and it is farther). `reach` > 0 (a neighbour's word): its depth
// alone never shadows, and its surface only within its seams and within reach x t of its point.
// `UNVOUCHED` and `MIN_COS` are `atlas_word.rs`'s constants of the same names (the CPU twin).
const UNVOUCHED: f32 = 0.98;
const MIN_COS: f32 = 0.05;

// Whether offset `e` (in the plane of normal `n`) from a point lies within the disk the VPL
// sees that point stand for along `dir`: `radius` across the ray, stretched by 1 / cos along
// the ray's slope over the plane (a wall seen 60 degrees off its normal covers twice the
// length per texel).
fn within_disk(e: vec3<f32>, dir: vec3<f32>, n: vec3<f32>, radius: f32) -> bool {
    let c = max(abs(dot(dir, n)), MIN_COS);
    let slope = dir - n * dot(dir, n);
    var along = 0.0;
    if dot(slope, slope) > 1.0e-12 {
        along = dot(e, normalize(slope));
    }
    let across2 = max(dot(e, e) - along * along, 0.0);
    return across2 + (along * c) * (along * c) <= radius * radius;
}

// The share of a slab's depth its test keeps clear of its faces and clip lines (a receiver on
// the slab's far face, or a ray grazing its edge, is not taken for passing through it).
// `SLAB_INSET` in `slab.rs` is the twin.
const SLAB_INSET: f32 = 0.05;

// Whether the ray from `o` along `dir` passes, before `dist`, through the solid behind pool
// point `j`'s face near it: the slab from the face to the depth of the solid behind it
// (`points[j].w`, 0 where none), bounded by the point's clip lines (open edges and seams, taken
// as faces square to its plane) and, at the middle of the ray's way through it, within
// `reach` x t of the point across its normal. A texel holds one surface: over a door's head,
// the wall's front face above the door is a strip a point or none of an ISM's sample stands
// for, and the texel shows the door's head behind it, whose plane the ray crosses past the
// wall; the slab above that head is what the ray runs through.
fn slab_blocks(j: u32, o: vec3<f32>, dir: vec3<f32>, dist: f32, reach: f32) -> bool {
    let depth = points[j].w;
    if depth <= 0.0 {
        return false;
    }
    let p = points[j].xyz;
    let n = point_normals[j].xyz;
    let inset = SLAB_INSET * depth;
    var lo = 0.0;
    var hi = dist;
    // Depth behind the face along the ray: s0 - dn t, kept within (inset, depth - inset).
    let s0 = dot(n, p - o);
    let dn = dot(n, dir);
    if abs(dn) <= 1.0e-6 {
        if s0 <= inset || s0 >= depth - inset {
            return false;
        }
    } else {
        let ta = (s0 - inset) / dn;
        let tb = (s0 - depth + inset) / dn;
        lo = max(lo, min(ta, tb));
        hi = min(hi, max(ta, tb));
    }
    for (var k = 0u; k < CLIPS; k = k + 1u) {
        let line = clips[j * CLIPS + k];
        let a = dot(line.xyz, o) - line.w - inset * length(line.xyz);
        let b = dot(line.xyz, dir);
        if abs(b) <= 1.0e-9 {
            if a < 0.0 {
                return false;
            }
        } else if b > 0.0 {
            lo = max(lo, -a / b);
        } else {
            hi = min(hi, -a / b);
        }
    }
    if lo >= hi {
        return false;
    }
    let tm = 0.5 * (lo + hi);
    let e = o + dir * tm - p;
    let across = e - n * dot(e, n);
    return dot(across, across) <= (reach * tm) * (reach * tm);
}

const CLEAR: u32 = 0u;
const BLOCKED: u32 = 1u;
const UNSURE: u32 = 2u;

fn ism_point_test(vpl: Vpl, tile: u32, l: IsmLookup, stored: u32, per_ism: u32, margin: f32, reach: f32, own: bool) -> u32 {
    if stored == ISM_EMPTY {
        return CLEAR;
    }
    let slot1 = ism_slot1(stored);
    var j = 0xffffffffu;
    if slot1 > 0u && slot1 <= per_ism {
        j = chosen_all[tile * per_ism + slot1 - 1u];
    }
    if j == 0xffffffffu || j >= arrayLength(&points) {
        if own && l.depth > ism_depth(stored) * (1.0 + margin) {
            return BLOCKED;
        }
        return CLEAR;
    }
    let n = point_normals[j].xyz;
    let o = vpl.position.xyz;
    if slab_blocks(j, o, l.dir, l.dist, reach) {
        return BLOCKED;
    }
    // The ray does not cross the point's plane before the receiver: a point much nearer than the
    // receiver still leaves the rest of the way unvouched for, and the neighbours are asked.
    var not_crossed = CLEAR;
    if own && distance(points[j].xyz, o) < l.dist * UNVOUCHED {
        not_crossed = UNSURE;
    }
    let den = dot(l.dir, n);
    if abs(den) <= 1.0e-6 {
        return not_crossed;
    }
    let t = dot(points[j].xyz - o, n) / den;
    // The receiver's own surface meets its ray at its own distance: 1e-4 of it is float noise.
    if t <= 0.0 || t >= l.dist * (1.0 - 1.0e-4) {
        return not_crossed;
    }
    let h = o + l.dir * t;
    if !on_surface(j, h, 0.0) {
        return UNSURE;
    }
    if own {
        return BLOCKED;
    }
    if within_edges(j, h, 0.0, true) && within_disk(h - points[j].xyz, l.dir, n, reach * t) {
        return BLOCKED;
    }
    return CLEAR;
}

// Whether the receiver of lookup `l` sees the VPL of atlas tile `tile` (tiles of side r, c per
// row); `bias`: x the neighbours' reach in point spacings (`NEIGHBOUR_REACH` in
// `atlas_word.rs`), w the relative depth margin of texels without a point.
fn ism_lit(vpl: Vpl, tile: u32, l: IsmLookup, r: u32, c: u32, per_ism: u32, bias: vec4<f32>) -> bool {
    let margin = bias.w;
    let stored = atlas[l.index];
    // A neighbour's point vouches for about its own disk only (the VPL's angular point spacing
    // sigma times the distance across, radius 0.75 of it).
    let reach = bias.x * vpl.normal.w;
    let own = ism_point_test(vpl, tile, l, stored, per_ism, margin, reach, true);
    if own == BLOCKED {
        return false;
    }
    let side = r * c;
    // A neighbour's point whose surface the ray crosses blocks it, even where the texel's own
    // word shows the way clear: a texel holds one surface, and at an occluder's edge (a door's
    // head, a jamb) its centre ray passes the occluder and shows the receiver's own surface
    // while the receiver's ray runs into the occluder a texel over. Where the own word shows
    // the way clear, the neighbours are read only where the texel's 4x4 block holds a surface
    // in front of the receiver, and only those that do not show the way clear are tested: a lit
    // wall away from any edge costs one more word read. With the buried jambs' clip
    // (`open_edges::buried_end`) and without this, the suite's three rooms read 1.135 of the
    // path tracer's light and the held-out four-room flat 1.141; with this 1.059 and 0.999
    // (`docs/notes/ism-tuning.md`). The block's word is pull-push's mean of the depths near its
    // nearest, and its blocks are aligned: an edge on a block's border, or a small occluder
    // among farther surfaces, can still pass unasked. Where the texel cannot decide, neither
    // the texel nor a neighbour showing the way clear blocks it too.
    if own == UNSURE || (own == CLEAR && ism_nearer_around(l, side)) {
        let around = ism_neighbours(vpl, tile, l, r, c, per_ism, margin, reach, own == CLEAR);
        if around == BLOCKED || (own == UNSURE && around == UNSURE && !ism_shows_clear(stored, l.depth)) {
            return false;
        }
    }
    return !ism_hole_blocks(vpl, tile, l, side, per_ism, reach, ism_depth(stored));
}

// Whether atlas word `w` shows the way to a receiver at normalised depth `depth` clear: empty, or
// a surface at least `SHOWN_CLEAR` of its depth. A ray the texel's own point cannot decide (it
// passes the point's open edge, or the point is much nearer and its plane is not crossed), with
// no neighbour's point on its way, may still be stopped by a surface that no texel holds (past a
// door's jamb, the wall beside the door a centimetre further on); where the nearest thing every
// texel around it shows stands well in front of the receiver, the way is not taken for clear.
// In the held-out maisonette rays past a jamb or a door's head were half of the first set's
// false light into the camera's room; with this test its lookups read 1.86x the rays' light
// there instead of 2.73x (`probe-ism`). `atlas_word.rs` holds the twin.
const SHOWN_CLEAR: f32 = 0.9;

fn ism_shows_clear(w: u32, depth: f32) -> bool {
    return w == ISM_EMPTY || ism_depth(w) >= SHOWN_CLEAR * depth;
}

// Ritschel's push, asked at lookup time: where a coarser level's depth is nearer than the
// texel's, the texel may show what lies behind a hole in a nearer surface, and the ray is tested
// against the point the coarse word names (the nearest of its block) within its open edges and
// seams, and within 2^level x `reach` of it. Unlike the push's overwrite, no occluder the texel
// holds is lost, and the point test replaces Ritschel's depth threshold: 15% of the depth
// (the pull's) let light through a 0.25 m wall 6 m away (the held-out flat's first set sent
// 10x the true light into the camera's room with it, 5.3x without).
// The coarse levels pull-push keeps (`PULL_LEVELS` in `gather.rs`).
const ISM_LEVELS: u32 = 2u;

fn ism_hole_blocks(vpl: Vpl, tile: u32, l: IsmLookup, side: u32, per_ism: u32, reach: f32, own_depth: f32) -> bool {
    let x = l.index % side;
    let y = l.index / side;
    var base = 0u;
    for (var level = 1u; level <= ISM_LEVELS; level = level + 1u) {
        let coarse = atlas_coarse[base + (y >> level) * (side >> level) + (x >> level)];
        base = base + (side >> level) * (side >> level);
        let cd = ism_depth(coarse);
        if coarse == ISM_EMPTY || cd >= own_depth {
            continue;
        }
        if ism_point_test(vpl, tile, l, coarse, per_ism, 0.0, reach * f32(1u << level), false) == BLOCKED {
            return true;
        }
    }
    return false;
}

// Whether the texel's 4x4 block (its second coarse level, which pull-push always keeps:
// `PULL_LEVELS` >= 2, asserted in `atlas_word.rs`) holds a surface well in front of the
// receiver (`ism_shows_clear` fails): one word read that spares a lit surface's lookups the
// four neighbours' reads.
fn ism_nearer_around(l: IsmLookup, side: u32) -> bool {
    let x = l.index % side;
    let y = l.index / side;
    let w = atlas_coarse[side / 2u * (side / 2u) + (y >> 2u) * (side >> 2u) + (x >> 2u)];
    return !ism_shows_clear(w, l.depth);
}

// What the four neighbouring texels say of the ray: BLOCKED where any one's point blocks it
// (their words tested with `reach`; with `nearer_only`, only words that do not show the way
// clear), CLEAR where none does and one shows the way clear (`ism_shows_clear`), UNSURE
// otherwise.
fn ism_neighbours(
    vpl: Vpl, tile: u32, l: IsmLookup, r: u32, c: u32, per_ism: u32, margin: f32, reach: f32, nearer_only: bool,
) -> u32 {
    let side = r * c;
    let x = l.index % side;
    let y = l.index / side;
    let x0 = (tile % c) * r;
    let y0 = (tile / c) * r;
    let offsets = array<vec2<i32>, 4>(vec2<i32>(-1, 0), vec2<i32>(1, 0), vec2<i32>(0, -1), vec2<i32>(0, 1));
    var shown = UNSURE;
    for (var i = 0; i < 4; i = i + 1) {
        let q = vec2<i32>(i32(x), i32(y)) + offsets[i];
        if q.x < i32(x0) || q.y < i32(y0) || q.x >= i32(x0 + r) || q.y >= i32(y0 + r) {
            continue;
        }
        let w = atlas[u32(q.y) * side + u32(q.x)];
        let clear = ism_shows_clear(w, l.depth);
        let asked = !(nearer_only && clear);
        if asked && ism_point_test(vpl, tile, l, w, per_ism, margin, reach, false) == BLOCKED {
            return BLOCKED;
        }
        if clear {
            shown = CLEAR;
        }
    }
    return shown;
}
