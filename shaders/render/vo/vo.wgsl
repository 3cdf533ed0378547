// Volumetric obscurance by line sampling (Loos & Sloan 2010; Loos 2015 §6.3.1, §6.3.3 and
// §6.3.4). Around each pixel's point P a sphere of radius R (metres) with z along the view ray
// through P: every disk sample (x, y) is a chord of the sphere, -z_s .. z_s with
// z_s = sqrt(1 - x^2 - y^2), and the depth buffer at the chord's pixel says where matter starts
// (d_r, in sphere units, from the plane through P). The free length of the chord is integrated
// analytically: [-z_s, min(z_s, d_r)]; with the thickness model also the space behind a slab of
// thickness t, [max(-z_s, d_r + t), z_s]; with the normal clamp both end at the tangent plane
// z_pl = -(n_x x + n_y y) / n_z. V = sum w_i free_i / sum w_i hemi_i (hemi: the chord above the
// plane, or 2 z_s without the clamp, where an open plane reads 0.5 and the factor is 2V).
// The disk pattern is reflected about a direction that changes over a 4 x 4 pixel tile (the
// blur pass removes the pattern). Writes (factor, V, 0, 1).
#import common/frame.wgsl
#import common/octahedral.wgsl
#import common/onb.wgsl

struct VoParams {
    // Per sample: x, y in the unit disk, weight (its Voronoi cell's chord integral), unused.
    samples: array<vec4<f32>, 12>,
    // Sample count, normal clamp (1) or not, thickness model (1) or not, unused.
    counts: vec4<u32>,
    // Radius R (m), thickness t (m), unused x2.
    params: vec4<f32>,
}

@group(0) @binding(0) var<uniform> frame: Frame;
@group(0) @binding(1) var<uniform> vp: VoParams;
@group(0) @binding(2) var depth_tex: texture_depth_2d;
@group(0) @binding(3) var normal_tex: texture_2d<f32>;
@group(0) @binding(4) var out_vo: texture_storage_2d<rgba32float, write>;

const FAR: f32 = 1.0e6;

// The depth-buffer surface behind world point q along the view (in sphere units from q's plane),
// FAR where the chord's pixel is off screen or sees nothing, or (with the normal clamp, where the
// half below the plane does not count) where that surface does not rise above P's tangent plane
// (p, n) by a margin: the chord's pixel centre is up to half a pixel
// beside the chord, and on a plane seen at a grazing angle that offset alone put the plane's own
// next pixel in front of the chord (every grazing floor darkened itself).
fn surface_behind(q: vec3<f32>, z: vec3<f32>, radius: f32, p: vec3<f32>, n: vec3<f32>) -> f32 {
    let at = pixel_of_world(frame, q);
    if at.z == 0u {
        return FAR;
    }
    let pixel = at.xy;
    let d = textureLoad(depth_tex, pixel, 0);
    if d <= 0.0 {
        return FAR;
    }
    let b = world_from_pixel(frame, pixel, d);
    if vp.counts.y == 1u && dot(b - p, n) < 0.05 * radius {
        return FAR;
    }
    return dot(b - q, z) / radius;
}

@compute @workgroup_size(8, 8, 1)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = vec2<u32>(frame.size.xy);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    let pixel = id.xy;
    let depth = textureLoad(depth_tex, pixel, 0);
    if depth <= 0.0 {
        textureStore(out_vo, pixel, vec4<f32>(1.0, 1.0, 0.0, 1.0));
        return;
    }
    let p = world_from_pixel(frame, pixel, depth);
    let n = oct_decode(textureLoad(normal_tex, pixel, 0).zw);
    let z = normalize(p - frame.camera_position.xyz);
    let ex = onb_tangent(z);
    let ey = onb_bitangent(z);
    let nx = dot(n, ex);
    let ny = dot(n, ey);
    // The visible side faces the camera (n_z < 0); a grazing or flipped normal is kept just so.
    let nz = min(dot(n, z), -0.05);
    let radius = vp.params.x;
    let t = vp.params.y / radius;
    let clamp_on = vp.counts.y == 1u;
    let thick = vp.counts.z == 1u && t > 0.0;
    // Reflection about a direction at one of 16 angles over a 4 x 4 tile.
    let k = (pixel.y % 4u) * 4u + pixel.x % 4u;
    let phi = (f32((k * 7u) % 16u) + 0.5) * 3.14159265 / 16.0;
    let c2 = cos(2.0 * phi);
    let s2 = sin(2.0 * phi);
    var free_sum = 0.0;
    var whole_sum = 0.0;
    for (var i = 0u; i < vp.counts.x; i = i + 1u) {
        let smp = vp.samples[i];
        let s = vec2<f32>(c2 * smp.x + s2 * smp.y, s2 * smp.x - c2 * smp.y);
        let zs = sqrt(max(1.0 - dot(s, s), 0.0));
        var top = zs;
        if clamp_on {
            top = min(zs, -(s.x * nx + s.y * ny) / nz);
        }
        let whole = select(2.0 * zs, max(top + zs, 0.0), clamp_on);
        if whole <= 0.0 {
            continue;
        }
        let q = p + radius * (s.x * ex + s.y * ey);
        let d_r = surface_behind(q, z, radius, p, n);
        var free = max(min(top, d_r) + zs, 0.0);
        if thick {
            free = free + max(top - max(-zs, d_r + t), 0.0);
        }
        free_sum = free_sum + smp.z * min(free, whole);
        whole_sum = whole_sum + smp.z * whole;
    }
    let v = free_sum / max(whole_sum, 1.0e-6);
    var factor = v;
    if !clamp_on {
        factor = min(2.0 * v, 1.0);
    }
    textureStore(out_vo, pixel, vec4<f32>(clamp(factor, 0.0, 1.0), v, 0.0, 1.0));
}
