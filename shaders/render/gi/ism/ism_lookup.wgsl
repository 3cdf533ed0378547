// The ISM visibility test of a receiver (shading and the bounce pass). The including shader
// binds `points`, `point_normals` (pool positions and normals), `clips` (`ism_clips.wgsl`) and
// `chosen_all` (per VPL of every set and slot: the pool point, `ism_select.wgsl`).
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
// A texel without a point (pull-push filled it, or the splat's ray ran along its plane) falls
// back to its depth with a relative `margin`.
#import render/gi/ism/ism_clips.wgsl

fn ism_lit(vpl: Vpl, tile: u32, l: IsmLookup, stored: u32, per_ism: u32, margin: f32) -> bool {
    if stored == ISM_EMPTY {
        return true;
    }
    let slot1 = ism_slot1(stored);
    var j = 0xffffffffu;
    if slot1 > 0u && slot1 <= per_ism {
        j = chosen_all[tile * per_ism + slot1 - 1u];
    }
    if j == 0xffffffffu || j >= arrayLength(&points) {
        return l.depth <= ism_depth(stored) * (1.0 + margin);
    }
    let n = point_normals[j].xyz;
    let o = vpl.position.xyz;
    let den = dot(l.dir, n);
    if abs(den) <= 1.0e-6 {
        return true;
    }
    let t = dot(points[j].xyz - o, n) / den;
    // The receiver's own surface meets its ray at its own distance: 1e-4 of it is float noise.
    if t <= 0.0 || t >= l.dist * (1.0 - 1.0e-4) {
        return true;
    }
    return !on_surface(j, o + l.dir * t, 0.0);
}
