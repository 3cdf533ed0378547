// sshgi's sky light (not in Soler et al. 2010, who light with the direct term alone): the
// irradiance over pi that the sky gives each start-level texel through the directions its
// voxel columns leave open. Cosine-weighted rays (stratified, rotated per pixel and frame, so the
// temporal filter averages them) are clipped to the view frustum and the voxels' depth range and
// marched through the columns like the gathers' segments (`sshgi_visibility.wgsl`). A ray is
// open when it meets no solid voxel and either leaves through the far end of the depth range
// (nothing of the scene lies beyond) or leaves the screen's side behind every solid of its last
// column (out past the walls the camera sees, or where the camera sees the sky). A ray leaving
// the screen in front of its column's solids, or through the near end, is blocked: what lies
// outside the view is unknown, and indoors it is most often a wall or the ceiling. (Open where it
// merely crossed a column showing the sky, the window room read 1.53 of the path tracer's
// energy: rays inside the room cross the window's columns in front of it.)
// With cosine sampling E / pi = the mean of L over the rays. Writes E / pi (the first bounce's
// illumination adds albedo x it to the direct term: the sky-lit surfaces send light too).
#import common/frame.wgsl
#import common/octahedral.wgsl
#import common/onb.wgsl
#import common/sky_params.wgsl
#import render/gi/sshgi/sshgi_hash.wgsl

struct SkyRayParams {
    // rays per texel, frame seed, unused x2.
    counts: vec4<u32>,
    // xyz the camera's forward axis, w unused.
    forward: vec4<f32>,
    // Voxel slices: near, far (view depth, m), slices per metre, on.
    vox: vec4<f32>,
    // Voxel columns marched: width, view pixels per column, height, unused.
    grid: vec4<u32>,
}

@group(0) @binding(0) var<uniform> frame: Frame;
@group(0) @binding(1) var<uniform> gp: SkyRayParams;
// The start level's depth/normal (`render/pyramid.wgsl`).
@group(0) @binding(2) var geometry: texture_2d<f32>;
@group(0) @binding(3) var dest: texture_storage_2d<rgba32float, write>;
@group(0) @binding(4) var<storage, read> voxels: array<vec4<u32>>;
@group(0) @binding(5) var sky_tex: texture_2d<f32>;
@group(0) @binding(6) var<uniform> sky: SkyParams;

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

// Whether the ray from view pixel pt (view depth zt) to py (depth zy) reaches the sky: no solid
// voxel on the way (the two columns of the surface it leaves are skipped, as in
// `voxel_occluded`), and an end at the far end of the depth range (`exit` 1) or at the screen's
// side (`exit` 2) behind every solid of the last column; `exit` 0 (the near end) is blocked.
fn reaches_sky(pt: vec2<f32>, py: vec2<f32>, zt: f32, zy: f32, exit: u32) -> bool {
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
    for (var j = 2; j <= steps; j = j + 1) {
        let m0 = (f32(j) - 0.5) / f32(steps);
        let m1 = min(f32(j) + 0.5, f32(steps)) / f32(steps);
        let za = 1.0 / mix(inv_t, inv_y, m0) - slice;
        let zb = 1.0 / mix(inv_t, inv_y, m1) - slice;
        let lo = i32(floor((min(za, zb) - gp.vox.x) * gp.vox.z));
        let hi = i32(floor((max(za, zb) - gp.vox.x) * gp.vox.z));
        let c = clamp(vec2<i32>(round(a + d * (f32(j) / f32(steps)))), vec2<i32>(0), vec2<i32>(width - 1, height - 1));
        last = voxels[c.y * width + c.x];
        if any((last & slice_bits(lo, hi)) != vec4<u32>(0u)) {
            return false;
        }
    }
    if exit == 1u {
        return true;
    }
    return exit == 2u && i32(floor((zy - gp.vox.x) * gp.vox.z)) > deepest_slice(last);
}

// The view pixel (pixels) of a clip-space point.
fn clip_pixel(c: vec4<f32>) -> vec2<f32> {
    let ndc = c.xy / c.w;
    return vec2<f32>(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5) * frame.size.xy;
}

// The sky's radiance along `w` from `x` (view depth zx, view pixel pixel_x) where the ray
// reaches it, else 0.
fn sky_along(x: vec3<f32>, pixel_x: vec2<f32>, zx: f32, w: vec3<f32>) -> vec3<f32> {
    // The ray clipped to the frustum's sides (clip space is linear along it) and the depth range.
    let c0 = frame.clip_from_world * vec4<f32>(x, 1.0);
    let c1 = frame.clip_from_world * vec4<f32>(w, 0.0);
    var t_end = 1.0e30;
    for (var i = 0; i < 4; i = i + 1) {
        let s = select(-1.0, 1.0, (i & 1) == 0);
        let axis = i >> 1;
        let a = c0.w + s * c0[axis];
        let b = c1.w + s * c1[axis];
        if b < 0.0 {
            t_end = min(t_end, max(-a / b, 0.0));
        }
    }
    let wf = dot(w, gp.forward.xyz);
    // 2: the screen's side, 1: the far end, 0: the near end.
    var exit = 2u;
    if wf > 0.0 {
        let t_far = (gp.vox.y - zx) / wf;
        if t_far <= t_end {
            t_end = max(t_far, 0.0);
            exit = 1u;
        }
    } else if wf < 0.0 {
        let t_near = (max(gp.vox.x, 0.05 * zx) - zx) / wf;
        if t_near <= t_end {
            t_end = t_near;
            exit = 0u;
        }
    }
    t_end = 0.999 * t_end;
    let z_end = zx + t_end * wf;
    if t_end <= 0.0 || z_end <= 0.0 {
        return vec3<f32>(0.0);
    }
    if !reaches_sky(pixel_x, clip_pixel(c0 + t_end * c1), zx, z_end, exit) {
        return vec3<f32>(0.0);
    }
    return sky_radiance(w);
}

@compute @workgroup_size(8, 8, 1)
fn sky_light(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = vec2<i32>(textureDimensions(dest));
    let t = vec2<i32>(id.xy);
    if t.x >= size.x || t.y >= size.y {
        return;
    }
    let g = textureLoad(geometry, t, 0);
    if g.a < 0.5 {
        textureStore(dest, t, vec4<f32>(0.0, 0.0, 0.0, 1.0));
        return;
    }
    let pixel_x = pyramid_pixel(frame, g);
    let x = point_on_pixel_ray(frame, pixel_x, g.r);
    let zx = dot(x - frame.camera_position.xyz, gp.forward.xyz);
    let n = oct_decode(g.gb);
    let tangent = onb_tangent(n);
    let bitangent = onb_bitangent(n);
    let count = max(gp.counts.x, 1u);
    let rotation = 2.0 * SKY_PI * hash01(id.x & 3u, id.y & 3u, gp.counts.y);
    let jitter = hash01(id.x, id.y, gp.counts.y ^ 0x85ebca6bu);
    var sum = vec3<f32>(0.0);
    for (var i = 0u; i < count; i = i + 1u) {
        let u = (f32(i) + jitter) / f32(count);
        let phi = rotation + f32(i) * GOLDEN;
        let r = sqrt(u);
        let w = normalize(tangent * (r * cos(phi)) + bitangent * (r * sin(phi)) + n * sqrt(max(1.0 - u, 0.0)));
        sum = sum + sky_along(x, pixel_x, zx, w);
    }
    textureStore(dest, t, vec4<f32>(sum / f32(count), 1.0));
}
