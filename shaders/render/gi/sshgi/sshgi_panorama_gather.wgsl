// sshgi panorama, gather (an extension of Soler et al. 2010, not in the paper): each start-level
// texel adds to the screen's first bounce the light of N senders of the panorama
// (`sshgi_panorama_pack.wgsl`: the surfaces around the camera the view does not show), picked
// one per stratum of the sender list with a per-pixel and per-frame jitter, each with the same
// bounded disc form factor as the screen's gathers (Eq. 4, R^2 = cos(theta') ds / pi), weighted
// by the list's size over N: an unbiased estimate of the panorama's E / pi, averaged over frames
// by the temporal filter. No visibility: the view's voxels do not reach off screen, so light
// passes through whatever lies between the receiver and a panorama sender.
#import common/frame.wgsl
#import common/octahedral.wgsl

struct PanoramaParams {
    // senders in the list S, samples N, frame seed, unused.
    counts: vec4<u32>,
}

struct Sender {
    point: vec4<f32>,
    radiance: vec4<f32>,
    normal: vec4<f32>,
}

@group(0) @binding(0) var<uniform> frame: Frame;
@group(0) @binding(1) var<uniform> pg: PanoramaParams;
// The depth/normal pyramid's start level.
@group(0) @binding(2) var geometry: texture_2d<f32>;
// The screen's first bounce (E / pi) at the start level.
@group(0) @binding(3) var base: texture_2d<f32>;
@group(0) @binding(4) var dest: texture_storage_2d<rgba32float, write>;
@group(0) @binding(5) var<storage, read> senders: array<Sender>;

const PI: f32 = 3.14159265358979;

// A hash of (x, y, seed) to [0, 1) (PCG, Jarzynski & Olano 2020).
fn hash01(x: u32, y: u32, seed: u32) -> f32 {
    var v = x * 747796405u + y * 2891336453u + seed * 277803737u + 1442695041u;
    v = ((v >> ((v >> 28u) + 4u)) ^ v) * 277803737u;
    v = (v >> 22u) ^ v;
    return f32(v >> 8u) / 16777216.0;
}

@compute @workgroup_size(8, 8, 1)
fn gather(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(dest);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    let screen = textureLoad(base, id.xy, 0);
    let g = textureLoad(geometry, id.xy, 0);
    let count = pg.counts.x;
    let n = pg.counts.y;
    if g.a < 0.5 || count == 0u || n == 0u {
        textureStore(dest, id.xy, screen);
        return;
    }
    let x = pyramid_point(frame, g);
    let nx = oct_decode(g.gb);
    let jitter = hash01(id.x, id.y, pg.counts.z);
    let stratum = f32(count) / f32(n);
    var sum = vec3<f32>(0.0);
    for (var i = 0u; i < n; i = i + 1u) {
        let pick = min(u32((f32(i) + fract(jitter + f32(i) * 0.618034)) * stratum), count - 1u);
        let s = senders[pick];
        if s.point.w <= 0.0 {
            continue;
        }
        let v = s.point.xyz - x;
        let d2 = dot(v, v);
        if d2 <= 1.0e-10 {
            continue;
        }
        let vh = v * inverseSqrt(d2);
        let cos_r = dot(nx, vh);
        let cos_s = dot(s.normal.xyz, -vh);
        if cos_r <= 0.0 || cos_s <= 0.0 {
            continue;
        }
        let r2_disc = cos_s * s.point.w / PI;
        sum = sum + s.radiance.rgb * (r2_disc * cos_r / (d2 + r2_disc));
    }
    textureStore(dest, id.xy, vec4<f32>(screen.rgb + sum * stratum, screen.a));
}
