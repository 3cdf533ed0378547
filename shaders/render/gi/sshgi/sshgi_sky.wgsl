// sshgi's sky light (not in Soler et al. 2010, who light with the direct term alone): the
// irradiance over pi that the sky gives each start-level texel through the directions its
// voxel columns leave open. Cosine-weighted rays (stratified, rotated per pixel and frame, so the
// temporal filter averages them) are clipped to the view frustum and the voxels' depth range and
// marched through the columns like the gathers' segments (`sshgi_visibility.wgsl`). A ray is
// open when it meets no solid voxel and either leaves through the far end of the depth range
// (nothing of the scene lies beyond) or leaves the screen's side behind every solid of its last
// column (out past the walls the camera sees, or where the camera sees the sky). A ray leaving
// the screen in front of its column's solids, or through the near end, leaves the view where
// what lies beyond is unknown: with the world grid (`sshgi_world_grid.wgsl`) it walks on through
// the scene's surface voxels to the grid's border (the courtyard: 0.979 -> 0.990 of the path
// tracer's energy), without it it is blocked (indoors it is most often a wall or the ceiling).
// (Open where it merely crossed a column showing the sky, the window room read 1.53 of the path
// tracer's energy: rays inside the room cross the window's columns in front of it.)
// With cosine sampling E / pi = the mean of L over the rays. `sky_light` writes E / pi of the
// start level (the first bounce's illumination adds reflectance x it to the direct term: the
// sky-lit surfaces send light too); `sender_sky` adds reflectance x E / pi to the panorama's
// senders' first radiance (a wall behind the camera lit by the sky through a window in view):
// their rays are marched from where they enter the view, the way there taken as free.
#import common/frame.wgsl
#import common/octahedral.wgsl
#import common/onb.wgsl
#import common/sky_params.wgsl
#import render/gi/sshgi/sshgi_hash.wgsl
#import render/gi/sshgi/sshgi_split.wgsl

struct SkyRayParams {
    // rays per texel (and sender), frame seed, panorama face size F (0: no senders), senders in
    // the list (the panorama's and the hidden ones).
    counts: vec4<u32>,
    // xyz the camera's forward axis, w unused.
    forward: vec4<f32>,
    // Voxel slices: near, far (view depth, m), slices per metre, on.
    vox: vec4<f32>,
    // Voxel columns marched: width, view pixels per column, height; threads per texel or sender
    // (`sshgi_split.wgsl`).
    grid: vec4<u32>,
    // The world's surface voxels (`sshgi_world_grid.wgsl`, the senders' rays): origin xyz, voxel
    // side (m).
    world: vec4<f32>,
    // Voxels along x, y, z (0: none); the bricks' first word.
    world_dims: vec4<u32>,
}

@group(0) @binding(0) var<uniform> frame: Frame;
@group(0) @binding(1) var<uniform> gp: SkyRayParams;
// The start level's depth/normal (`render/pyramid.wgsl`).
@group(0) @binding(2) var geometry: texture_2d<f32>;
@group(0) @binding(3) var dest: texture_storage_2d<rgba32float, write>;
@group(0) @binding(4) var<storage, read> voxels: array<vec4<u32>>;
@group(0) @binding(5) var sky_tex: texture_2d<f32>;
@group(0) @binding(6) var<uniform> sky: SkyParams;

// The panorama's senders (`sshgi_panorama_pack.wgsl`) and their first radiance (`sender_sky`).
#import render/gi/sshgi/sshgi_sender.wgsl
@group(0) @binding(7) var<storage, read> senders: array<Sender>;
@group(0) @binding(8) var<storage, read_write> sender_radiance: array<vec4<f32>>;
// The world's surface voxels (`sender_sky` only).
@group(0) @binding(9) var<storage, read> world: array<u32>;
#import render/gi/sshgi/sshgi_world_grid.wgsl

#import common/sky.wgsl
#import render/gi/sshgi/sshgi_visibility.wgsl

const GOLDEN: f32 = 2.39996322972865;

// The deepest solid slice of a column (-1: none).
fn deepest_slice(column: vec4<u32>) -> i32 {
    for (var w = 3; w >= 0; w = w - 1) {
        if column[w] != 0u {
            return 32 * w + i32(firstLeadingBit(column[w]));
        }
    }
    return -1;
}

// What the march of the ray from view pixel pt (view depth zt) to py (depth zy) says of the
// sky: SKY_BLOCKED where a solid voxel lies on the way (the first `skip` columns are skipped: 2
// where the ray leaves a surface on screen, as in `voxel_occluded`), SKY_OPEN where it then ends
// at the far end of the depth range (`exit` 1) or at the screen's side (`exit` 2) behind every
// solid of the last column, and SKY_UNKNOWN where it leaves through the near end (`exit` 0) or
// the screen's side in front of its last column's solids: what lies beyond is not in view.
const SKY_BLOCKED: u32 = 0u;
const SKY_OPEN: u32 = 1u;
const SKY_UNKNOWN: u32 = 2u;

fn screen_sky(pt: vec2<f32>, py: vec2<f32>, zt: f32, zy: f32, exit: u32, skip: i32) -> u32 {
    let px = f32(gp.grid.y);
    let a = pt / px - 0.5;
    let d = py / px - 0.5 - a;
    let steps = max(i32(ceil(max(abs(d.x), abs(d.y)))), 1);
    let width = i32(gp.grid.x);
    let height = i32(gp.grid.z);
    let inv_t = 1.0 / zt;
    let inv_y = 1.0 / zy;
    let slice = 1.0 / gp.vox.z;
    var last = vec4<u32>(0u);
    for (var j = skip; j <= steps; j = j + 1) {
        let m0 = (f32(j) - 0.5) / f32(steps);
        let m1 = min(f32(j) + 0.5, f32(steps)) / f32(steps);
        let za = 1.0 / mix(inv_t, inv_y, m0) - slice;
        let zb = 1.0 / mix(inv_t, inv_y, m1) - slice;
        let lo = i32(floor((min(za, zb) - gp.vox.x) * gp.vox.z));
        let hi = i32(floor((max(za, zb) - gp.vox.x) * gp.vox.z));
        let c = clamp(vec2<i32>(round(a + d * (f32(j) / f32(steps)))), vec2<i32>(0), vec2<i32>(width - 1, height - 1));
        last = voxels[c.y * width + c.x];
        if any((last & slice_bits(lo, hi)) != vec4<u32>(0u)) {
            return SKY_BLOCKED;
        }
    }
    if exit == 1u || (exit == 2u && i32(floor((zy - gp.vox.x) * gp.vox.z)) > deepest_slice(last)) {
        return SKY_OPEN;
    }
    return SKY_UNKNOWN;
}

// Whether the ray from x (normal n) along `w`, which leaves the view at distance t, meets no
// surface voxel of the world grid from two voxels before that point to the grid's border (the
// march answered the way there; a start close to x is moved off x's surface along n, as the
// senders' rays are); false without a grid (unknown counts as blocked).
fn sky_past_view(x: vec3<f32>, n: vec3<f32>, w: vec3<f32>, t: f32) -> bool {
    if !world_grid_on() {
        return false;
    }
    // Past the grid's far corner from anywhere inside it.
    let reach = length(vec3<f32>(gp.world_dims.xyz)) * gp.world.w + 1.0;
    let start = x + w * max(t - 2.0 * gp.world.w, 0.0);
    return !world_blocked(start, n, start + w * reach, vec3<f32>(0.0));
}

// The view pixel (pixels) of a clip-space point.
fn clip_pixel(c: vec4<f32>) -> vec2<f32> {
    let ndc = c.xy / c.w;
    return vec2<f32>(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5) * frame.size.xy;
}

// The sky's radiance along `w` from `x` where the ray reaches it, else 0. The ray is clipped to
// the view's frustum (clip space is linear along it) and the voxels' depth range; a ray that never
// enters them is blocked (unknown), and the way from an off-screen `x` to where it enters is taken
// as free. `skip`: columns skipped at the start (2 for a point on screen, 0 off it).
fn sky_along(x: vec3<f32>, n: vec3<f32>, w: vec3<f32>, skip: i32) -> vec3<f32> {
    let c0 = frame.clip_from_world * vec4<f32>(x, 1.0);
    let c1 = frame.clip_from_world * vec4<f32>(w, 0.0);
    var t_in = 0.0;
    var t_out = 1.0e30;
    for (var i = 0; i < 4; i = i + 1) {
        let s = select(-1.0, 1.0, (i & 1) == 0);
        let axis = i >> 1;
        let a = c0.w + s * c0[axis];
        let b = c1.w + s * c1[axis];
        if b > 0.0 {
            t_in = max(t_in, -a / b);
        } else if b < 0.0 {
            t_out = min(t_out, -a / b);
        } else if a < 0.0 {
            return vec3<f32>(0.0);
        }
    }
    let zx = dot(x - frame.camera_position.xyz, gp.forward.xyz);
    let wf = dot(w, gp.forward.xyz);
    let near = max(gp.vox.x, 0.01 * gp.vox.y);
    // 2: the screen's side, 1: the far end, 0: the near end.
    var exit = 2u;
    if wf > 0.0 {
        let t_far = (gp.vox.y - zx) / wf;
        if t_far <= t_out {
            t_out = t_far;
            exit = 1u;
        }
        t_in = max(t_in, (near - zx) / wf);
    } else if wf < 0.0 {
        let t_near = (near - zx) / wf;
        if t_near <= t_out {
            t_out = t_near;
            exit = 0u;
        }
        t_in = max(t_in, (gp.vox.y - zx) / wf);
    } else if zx < near || zx > gp.vox.y {
        return vec3<f32>(0.0);
    }
    if t_out <= t_in {
        return vec3<f32>(0.0);
    }
    let span = t_out - t_in;
    let ta = t_in + 0.0005 * span;
    let tb = t_out - 0.0005 * span;
    let za = zx + ta * wf;
    let zb = zx + tb * wf;
    if za <= 0.0 || zb <= 0.0 {
        return vec3<f32>(0.0);
    }
    let seen = screen_sky(clip_pixel(c0 + ta * c1), clip_pixel(c0 + tb * c1), za, zb, exit, skip);
    if seen == SKY_OPEN || (seen == SKY_UNKNOWN && sky_past_view(x, n, w, tb)) {
        return sky_radiance(w);
    }
    return vec3<f32>(0.0);
}

// Ray i of `count` cosine-distributed about n (stratified, rotated by `rotation`, jittered by
// `jitter`).
fn cosine_ray(n: vec3<f32>, tangent: vec3<f32>, bitangent: vec3<f32>, i: u32, count: u32, rotation: f32, jitter: f32) -> vec3<f32> {
    let u = (f32(i) + jitter) / f32(count);
    let phi = rotation + f32(i) * GOLDEN;
    let r = sqrt(u);
    return normalize(tangent * (r * cos(phi)) + bitangent * (r * sin(phi)) + n * sqrt(max(1.0 - u, 0.0)));
}

// E / pi from `count` cosine-distributed rays about `n` from `x` (stratified, rotated by
// `rotation`, jittered by `jitter`): this thread's share, rays `first`, first + split, ...
fn sky_irradiance(x: vec3<f32>, n: vec3<f32>, count: u32, rotation: f32, jitter: f32, skip: i32, first: u32) -> vec3<f32> {
    let tangent = onb_tangent(n);
    let bitangent = onb_bitangent(n);
    var sum = vec3<f32>(0.0);
    for (var i = first; i < count; i = i + sky_split()) {
        let w = cosine_ray(n, tangent, bitangent, i, count, rotation, jitter);
        sum = sum + sky_along(x, n, w, skip);
    }
    return sum / f32(max(count, 1u));
}

// Each texel or sender takes `gp.grid.w` threads of a 64-thread workgroup, each tracing every
// split-th ray (`sshgi_split.wgsl`).
fn sky_split() -> u32 {
    return max(gp.grid.w, 1u);
}

@compute @workgroup_size(64, 1, 1)
fn sky_light(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_index) lid: u32) {
    let item = split_item(group, lid, sky_split());
    let id = item.xy;
    let inside = item.z == 1u && all(id < textureDimensions(dest));
    var g = vec4<f32>(0.0);
    if inside {
        g = textureLoad(geometry, id, 0);
    }
    var own = vec3<f32>(0.0);
    if g.a >= 0.5 {
        let x = pyramid_point(frame, g);
        let rotation = 2.0 * SKY_PI * hash01(id.x & 3u, id.y & 3u, gp.counts.y);
        let jitter = hash01(id.x, id.y, gp.counts.y ^ 0x85ebca6bu);
        own = sky_irradiance(x, oct_decode(g.gb), max(gp.counts.x, 1u), rotation, jitter, 2, lid % sky_split());
    }
    let e = split_sum(lid, own, sky_split());
    if inside && lid % sky_split() == 0u {
        textureStore(dest, id, vec4<f32>(e, 1.0));
    }
}

// Whether the view's frustum holds p (a hidden sender behind what the camera sees).
fn in_view(p: vec3<f32>) -> bool {
    let c = frame.clip_from_world * vec4<f32>(p, 1.0);
    return c.w > 0.0 && all(abs(c.xy) <= vec2<f32>(c.w));
}

// E / pi at a sender x (normal n) from `count` cosine-distributed rays walked through the world
// grid to its border: a ray that meets no surface voxel leaves the scene and sees the sky.
fn sky_through_world(x: vec3<f32>, n: vec3<f32>, count: u32, rotation: f32, jitter: f32, first: u32) -> vec3<f32> {
    let tangent = onb_tangent(n);
    let bitangent = onb_bitangent(n);
    // Past the grid's far corner from anywhere inside it.
    let reach = length(vec3<f32>(gp.world_dims.xyz)) * gp.world.w + 1.0;
    var sum = vec3<f32>(0.0);
    for (var i = first; i < count; i = i + sky_split()) {
        let w = cosine_ray(n, tangent, bitangent, i, count, rotation, jitter);
        if !world_blocked(x, n, x + w * reach, vec3<f32>(0.0)) {
            sum = sum + sky_radiance(w);
        }
    }
    return sum / f32(max(count, 1u));
}

// The panorama's and the hidden senders (F per row, one per thread): their first radiance gains
// reflectance x E / pi, from rays walked through the world grid where there is one; otherwise through
// the view's voxels from where they enter the view (a hidden sender inside the view skips its own
// columns, as a point on screen).
@compute @workgroup_size(64, 1, 1)
fn sender_sky(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_index) lid: u32) {
    let f = gp.counts.z;
    let item = split_item(group, lid, sky_split());
    let id = item.xy;
    let index = id.y * f + id.x;
    var s = Sender();
    if item.z == 1u && id.x < f && index < gp.counts.w {
        s = senders[index];
    }
    var own = vec3<f32>(0.0);
    if s.point.w > 0.0 {
        let rotation = 2.0 * SKY_PI * hash01(id.x, id.y, gp.counts.y ^ 0x27d4eb2fu);
        let jitter = hash01(id.y, id.x, gp.counts.y ^ 0x165667b1u);
        let skip = select(0, 2, in_view(s.point.xyz));
        let part = lid % sky_split();
        if world_grid_on() {
            own = sky_through_world(s.point.xyz, s.normal.xyz, max(gp.counts.x / 4u, 1u), rotation, jitter, part);
        } else {
            own = sky_irradiance(s.point.xyz, s.normal.xyz, max(gp.counts.x, 1u), rotation, jitter, skip, part);
        }
    }
    let e = split_sum(lid, own, sky_split());
    if s.point.w > 0.0 && lid % sky_split() == 0u {
        sender_radiance[index] = sender_radiance[index] + vec4<f32>(s.reflectance.rgb * e, 0.0);
    }
}
