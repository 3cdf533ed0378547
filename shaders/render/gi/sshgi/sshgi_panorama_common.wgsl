// What the panorama's gather and receive share (`sshgi_panorama_gather.wgsl`,
// `sshgi_panorama_receive.wgsl`): the parameters, the sender list and the estimate of E / pi at a
// point from the senders. The list holds the panorama's 6 F^2 senders, then the hidden senders
// (`sshgi_hidden_pack.wgsl`); a segment with a hidden sender at either end is marched through the
// view's voxels, and one that leaves the view, or whose columns are coarser than the world's
// voxels, through the scene's surface voxels in the world (`world_occluded`; blocked without
// them where it leaves the view). The including shader binds `frame`, `gp`, `senders`,
// `radiance`, `cdf` (`sshgi_sender_pick.wgsl`), `voxels` and `world`.

#import render/gi/sshgi/sshgi_hash.wgsl
#import render/gi/sshgi/sshgi_split.wgsl
#import render/gi/sshgi/sshgi_visibility.wgsl
#import render/gi/sshgi/sshgi_world_grid.wgsl

struct PanoramaParams {
    // senders in the list S, samples N, frame seed, face size F.
    counts: vec4<u32>,
    // The start level's width and height (texels); threads per texel of the gather and per
    // sender of the receive (`split_item`).
    screen: vec4<u32>,
    // Solid angle of one start-level texel on the optical axis (sr); a voxel column's width per
    // metre of view depth (0: segments in view never walk the world grid); the share m of the
    // sender picks drawn by power (`sshgi_sender_pick.wgsl`); unused.
    geo: vec4<f32>,
    // xyz the camera's forward axis, w unused.
    forward: vec4<f32>,
    // Voxel slices: near, far (view depth, m), slices per metre, visibility on (1) or off (0).
    vox: vec4<f32>,
    // Voxel columns marched: width, view pixels per column, height, unused.
    grid: vec4<u32>,
    // The world's surface voxels (`sshgi_world_grid.wgsl`): origin xyz, voxel side (m).
    world: vec4<f32>,
    // Voxels along x, y, z (0: no grid, a segment leaving the view is blocked); the bricks' first
    // word.
    world_dims: vec4<u32>,
}

#import render/gi/sshgi/sshgi_sender.wgsl
#import render/gi/sshgi/sshgi_sender_pick.wgsl

const PI: f32 = 3.14159265358979;


// The bounded disc form factor of a sender of area ds at offset v from a receiver of normal nx
// with sender normal ns (Eq. 4; R^2 = cos(theta') ds / pi): E / pi per unit radiance.
fn disc_form_factor(v: vec3<f32>, nx: vec3<f32>, ns: vec3<f32>, ds: f32) -> f32 {
    let d2 = dot(v, v);
    if d2 <= 1.0e-10 {
        return 0.0;
    }
    let vh = v * inverseSqrt(d2);
    let cos_r = dot(nx, vh);
    let cos_s = dot(ns, -vh);
    if cos_r <= 0.0 || cos_s <= 0.0 {
        return 0.0;
    }
    let r2_disc = cos_s * ds / PI;
    return r2_disc * cos_r / (d2 + r2_disc);
}

// The list index of the first hidden sender: after the panorama's six faces of F^2.
fn hidden_from() -> u32 {
    return 6u * gp.counts.w * gp.counts.w;
}

// The view pixel (pixels) of a clip-space point.
fn clip_to_pixel(c: vec4<f32>) -> vec2<f32> {
    let ndc = c.xy / c.w;
    return vec2<f32>(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5) * frame.size.xy;
}

// Whether the segment from x to y (normals nx, ny) passes through a solid voxel of the view
// (`voxel_occluded_skipping`; through the world's surface voxels instead where they are finer
// than a column at the segment's middle depth, `SshgiSettings::world_grid_in_view`), or, where
// it leaves the view's frustum or the voxels' near end (clip space is linear along it), through a surface voxel of the world (`world_blocked`; without them
// it counts as blocked: what lies outside the view is unknown). `on_surface.x` (y): x (y) lies on
// a surface the view shows, whose own columns are skipped; a hidden point moved off its surface
// (`off_surface`) and an end clipped to the view skip none. Off without visibility.
fn world_occluded(x: vec3<f32>, nx: vec3<f32>, y: vec3<f32>, ny: vec3<f32>, on_surface: vec2<bool>) -> bool {
    if gp.vox.w < 0.5 {
        return false;
    }
    let c0 = frame.clip_from_world * vec4<f32>(x, 1.0);
    let dc = frame.clip_from_world * vec4<f32>(y, 1.0) - c0;
    let near = max(gp.vox.x, 0.01 * gp.vox.y);
    var t0 = 0.0;
    var t1 = 1.0;
    // The four side planes (w +- x >= 0, w +- y >= 0) and the voxels' near end (w >= near).
    for (var i = 0; i < 5; i = i + 1) {
        var a = c0.w - near;
        var b = dc.w;
        if i < 4 {
            let s = select(-1.0, 1.0, (i & 1) == 0);
            a = c0.w + s * c0[i >> 1];
            b = dc.w + s * dc[i >> 1];
        }
        if b > 0.0 {
            t0 = max(t0, -a / b);
        } else if b < 0.0 {
            t1 = min(t1, -a / b);
        } else if a < 0.0 {
            return false;
        }
    }
    // What runs outside the view is the world grid's to answer; without it the segment is taken
    // as blocked (a wall behind the camera between a lit hall and the room in view).
    if t1 <= t0 || t0 > 0.0 || t1 < 1.0 {
        return !world_grid_on() || world_blocked(x, nx, y, ny);
    }
    let ca = c0 + dc * t0;
    let cb = c0 + dc * t1;
    // Where the world's voxel is finer than a column at the segment's middle depth, the world
    // answers (a corridor seen down its length spans few columns, wide and deep at its far end).
    if world_grid_on() && gp.world.w < gp.geo.y * 0.5 * (ca.w + cb.w) {
        return world_blocked(x, nx, y, ny);
    }
    let skip = vec2<i32>(select(1, 2, on_surface.x && t0 <= 0.0), select(1, 2, on_surface.y && t1 >= 1.0));
    return voxel_occluded_skipping(clip_to_pixel(ca), clip_to_pixel(cb), ca.w, cb.w, skip);
}

// A hidden point moved off its surface by two voxel slices along its normal, for the march: a
// point behind its own object (a box's far side) lies in the slice of the object's back, and its
// segment, moved a slice towards the camera by `voxel_occluded`, would start inside the object.
fn off_surface(p: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    return p + n * (2.0 / max(gp.vox.z, 1.0e-6));
}

// Samples a receiver gathers from each source: N, or N / 4 for a hidden sender receiving (each
// of its samples is marched; its light is averaged over frames like every sender's: the quarter
// cut the clutter room's receives from 35 to 22 ms on the software adapter; its energy moved 0.002).
fn samples(march: bool) -> u32 {
    return select(gp.counts.y, max(gp.counts.y / 4u, 1u), march);
}

// E / pi at x (normal nx) from N senders picked one per stratum (jittered by `jitter`) of the
// list's mixture of uniform and power-proportional picks (`pick_sender`, share `gp.geo.z` by
// power), each weighted by one over N times its pick's probability: an unbiased estimate over
// frames. With `march`, every sender's segment is marched; otherwise only a hidden sender's.
// This thread's share: samples first, first + step, ... (`split_item`: threads share a
// receiver).
fn gather_senders(x: vec3<f32>, nx: vec3<f32>, jitter: f32, march: bool, first: u32, step: u32) -> vec3<f32> {
    let count = gp.counts.x;
    let n = samples(march);
    if count == 0u || n == 0u {
        return vec3<f32>(0.0);
    }
    // A marching receiver is a hidden sender itself.
    let xm = select(x, off_surface(x, nx), march);
    var sum = vec3<f32>(0.0);
    for (var i = first; i < n; i = i + step) {
        let drawn = pick_sender((f32(i) + fract(jitter + f32(i) * 0.618034)) / f32(n), count, gp.geo.z);
        let pick = drawn.index;
        let s = senders[pick];
        if s.point.w <= 0.0 {
            continue;
        }
        let ff = disc_form_factor(s.point.xyz - x, nx, s.normal.xyz, s.point.w);
        let hidden = pick >= hidden_from();
        let y = select(s.point.xyz, off_surface(s.point.xyz, s.normal.xyz), hidden);
        // A receiver on screen skips its columns; a hidden receiver and sender do not. A dark
        // sender sends nothing, and its segment is not marched.
        let light = radiance[pick].rgb;
        let lit = any(light > vec3<f32>(0.0));
        if ff > 0.0 && lit && !((march || hidden) && world_occluded(xm, nx, y, s.normal.xyz, vec2<bool>(!march, !hidden))) {
            sum = sum + light * (ff / drawn.pdf);
        }
    }
    return sum / f32(n);
}
