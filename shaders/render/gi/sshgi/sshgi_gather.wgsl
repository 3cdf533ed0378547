// sshgi gather (Soler et al. 2010, Sec. 3 and Sec. 4, "Indirect lighting shader"): one shader for
// every level. A texel of level k gathers N samples of the screen-space surface elements of its
// level: the full disc of radius r texels on the start level, the ring r/2..r on coarser ones (so
// the levels' rings tile the view without overlap), each with the bounded point-to-disc form
// factor of Eq. 4, R^2 cos(theta) / (r^2 + R^2) with R^2 = cos(theta') ds / pi, whose 1/pi makes
// the sum E / pi: the composite multiplies it by the receiver's albedo. ds is Eq. 2, the area the
// sample's share dP of the region covers at its distance and tilt. The 2^(2k) energy scale of
// coarse levels is in the texel solid angle of level k (4^k that of a view pixel), applied once.
// Samples are stratified in area with a per-pixel (4x4 interleaved) and per-frame rotation, so the
// temporal accumulation averages the pattern out. With visibility on, each sample's segment is
// marched through the view's voxel columns (`sshgi_visibility.wgsl`). A texel's samples are
// spread over S = `gp.grid.w` threads of its workgroup (`sshgi_split.wgsl`).
#import common/frame.wgsl
#import common/octahedral.wgsl
#import render/gi/sshgi/sshgi_hash.wgsl
#import render/gi/sshgi/sshgi_split.wgsl

struct GatherParams {
    // pyramid level l of this level, ring (0: full disc), samples N, frame seed.
    level: vec4<u32>,
    // ring radius r (texels of this level), solid angle of one texel of this level on the
    // optical axis (sr), 2^l (view pixels per texel), unused.
    geo: vec4<f32>,
    // xyz the camera's forward axis, w unused.
    forward: vec4<f32>,
    // Voxel slices: near, far (view depth, m), slices per metre, visibility on (1) or off (0).
    vox: vec4<f32>,
    // Voxel columns marched: width, view pixels per column, height; threads per texel S (1, 4,
    // 16 or 64: the workgroup's 64 threads cover a tile of 64 / S texels, 8 / sqrt(S) a side).
    grid: vec4<u32>,
}

@group(0) @binding(0) var<uniform> frame: Frame;
@group(0) @binding(1) var<uniform> gp: GatherParams;
// Depth/normal pyramid level l: r = distance to the camera, gb = octahedral normal, a = 1 where
// geometry.
@group(0) @binding(2) var geometry: texture_2d<f32>;
// Outgoing radiance of this level.
@group(0) @binding(3) var illumination: texture_2d<f32>;
@group(0) @binding(4) var dest: texture_storage_2d<rgba32float, write>;
// The voxel columns marched (`sshgi_voxelize.wgsl`, OR-reduced by `sshgi_voxel_mip.wgsl`).
@group(0) @binding(5) var<storage, read> voxels: array<vec4<u32>>;

#import render/gi/sshgi/sshgi_visibility.wgsl

const PI: f32 = 3.14159265358979;
const GOLDEN_ANGLE: f32 = 2.39996322972865;


@compute @workgroup_size(64, 1, 1)
fn gather(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_index) lid: u32) {
    let split = max(gp.grid.w, 1u);
    let item = split_item(group, lid, split);
    let t = vec2<i32>(item.xy);
    let inside = item.z == 1u && all(t < vec2<i32>(textureDimensions(dest)));
    var g = vec4<f32>(0.0);
    if inside {
        g = textureLoad(geometry, t, 0);
    }
    var own = vec3<f32>(0.0);
    if g.a >= 0.5 {
        own = gathered(t, g, lid % split, split);
    }
    let sum = split_sum(lid, own, split);
    if inside && lid % split == 0u {
        textureStore(dest, t, vec4<f32>(sum, 1.0));
    }
}

// Texel t's (geometry g) samples first, first + step, ... of its N.
fn gathered(t: vec2<i32>, g: vec4<f32>, first: u32, step: u32) -> vec3<f32> {
    let size = vec2<i32>(textureDimensions(dest));
    let cam = frame.camera_position.xyz;
    let pixel_x = pyramid_pixel(frame, g);
    let x = point_on_pixel_ray(frame, pixel_x, g.r);
    let zx = dot(x - cam, gp.forward.xyz);
    let nx = oct_decode(g.gb);
    let n = gp.level.z;
    let r = gp.geo.x;
    let inner = select(0.0, 0.5 * r, gp.level.y != 0u);
    let area = PI * (r * r - inner * inner);
    // Each sample stands for dP = area / N texels of this level. Its disc (Eq. 4's bound) is
    // never smaller than the texel it reads: where N exceeds the region's texels (small views,
    // coarse levels), several samples hit one texel, and discs of their small shares summed like
    // the unbounded point form factor of the whole texel (the default Cornell box at 64x36 found
    // 1.21x the one-bounce reference's indirect light). Such a sample is the texel's disc,
    // weighted by its share dP of it.
    let dp = area / f32(n);
    let dp_disc = max(dp, 1.0);
    let share = dp / dp_disc;
    // Per-pixel rotation from the 4x4 interleave cell and the frame; per-pixel radial jitter.
    let id = vec2<u32>(t);
    let cell = id & vec2<u32>(3u);
    let rotation = 2.0 * PI * hash01(cell.x, cell.y, gp.level.w);
    let jitter = hash01(id.x, id.y, gp.level.w ^ 0x9e3779b9u);
    var sum = vec3<f32>(0.0);
    for (var i = first; i < n; i = i + step) {
        let u = (f32(i) + jitter) / f32(n);
        let rho = sqrt(inner * inner + u * (r * r - inner * inner));
        let a = rotation + f32(i) * GOLDEN_ANGLE;
        let y = vec2<i32>(floor(vec2<f32>(t) + 0.5 + rho * vec2<f32>(cos(a), sin(a))));
        if all(y == t) || any(y < vec2<i32>(0)) || any(y >= size) {
            continue;
        }
        let gy = textureLoad(geometry, y, 0);
        if gy.a < 0.5 {
            continue;
        }
        let pixel_y = pyramid_pixel(frame, gy);
        let py = point_on_pixel_ray(frame, pixel_y, gy.r);
        let dir_y = (py - cam) / max(gy.r, 1.0e-20);
        let ny = oct_decode(gy.gb);
        let v = py - x;
        let d2 = dot(v, v);
        if d2 <= 1.0e-10 {
            continue;
        }
        let vh = v * inverseSqrt(d2);
        let cos_r = dot(nx, vh);
        let cos_s = dot(ny, -vh);
        if cos_r <= 0.0 || cos_s <= 0.0 {
            continue;
        }
        // Eq. 2: the texel's solid angle (cos^3 alpha off the axis) times distance^2 over the
        // tilt cos(beta) (clamped at 0.05), times the sample's share dP.
        let cos_a = max(dot(dir_y, gp.forward.xyz), 0.0);
        if gp.vox.w > 0.5 && voxel_occluded(pixel_x, pixel_y, zx, gy.r * cos_a) {
            continue;
        }
        let cos_b = max(dot(ny, -dir_y), 0.05);
        let ds = gp.geo.y * cos_a * cos_a * cos_a * gy.r * gy.r / cos_b * dp_disc;
        let r2_disc = cos_s * ds / PI;
        sum = sum + textureLoad(illumination, y, 0).rgb * (share * r2_disc * cos_r / (d2 + r2_disc));
    }
    return sum;
}
