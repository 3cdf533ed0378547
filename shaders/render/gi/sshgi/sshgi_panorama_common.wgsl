// What the panorama's gather and receive share (`sshgi_panorama_gather.wgsl`,
// `sshgi_panorama_receive.wgsl`): the parameters, the sender list and the estimate of E / pi at a
// point from the senders. The including shader binds `pg`, `senders` and `radiance`.

#import render/gi/sshgi/sshgi_hash.wgsl

struct PanoramaParams {
    // senders in the list S, samples N, frame seed, face size F.
    counts: vec4<u32>,
    // The start level's width and height (texels), unused x2.
    screen: vec4<u32>,
    // Solid angle of one start-level texel on the optical axis (sr), unused x3.
    geo: vec4<f32>,
    // xyz the camera's forward axis, w unused.
    forward: vec4<f32>,
}

struct Sender {
    // xyz the point, w the area ds it stands for (m^2; 0: no sender).
    point: vec4<f32>,
    // xyz geometric normal, w unused.
    normal: vec4<f32>,
    // rgb albedo, a unused.
    albedo: vec4<f32>,
}

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

// E / pi at x (normal nx) from N senders picked one per stratum of the list (jittered by
// `jitter`), each weighted by the list's size over N: an unbiased estimate over frames.
fn gather_senders(x: vec3<f32>, nx: vec3<f32>, jitter: f32) -> vec3<f32> {
    let count = pg.counts.x;
    let n = pg.counts.y;
    if count == 0u || n == 0u {
        return vec3<f32>(0.0);
    }
    let stratum = f32(count) / f32(n);
    var sum = vec3<f32>(0.0);
    for (var i = 0u; i < n; i = i + 1u) {
        let pick = min(u32((f32(i) + fract(jitter + f32(i) * 0.618034)) * stratum), count - 1u);
        let s = senders[pick];
        if s.point.w > 0.0 {
            sum = sum + radiance[pick].rgb * disc_form_factor(s.point.xyz - x, nx, s.normal.xyz, s.point.w);
        }
    }
    return sum * stratum;
}
