// A virtual point light as the ISM passes store it (mirrors render::gi::ism::vpl_pass::GpuVpl).
#import common/onb.wgsl

struct Vpl {
    // xyz position, w = R^2 of the disk the VPL stands for (its patch's area / pi; the shading
    // clamps d^2 at clamp_disk x R^2 and the bounce pass at R_vpl^2 + R_point^2, so a VPL's
    // light stays bounded near it at any scene scale); 0 = no VPL.
    position: vec4<f32>,
    // xyz surface normal, w = specular luminance.
    normal: vec4<f32>,
    // rgb power (W, times the interleave factor n^2), a = pdf of the chosen texel.
    power: vec4<f32>,
    // xyz unit direction towards the light it came from, w = light-G-buffer texel index.
    incident: vec4<f32>,
    // Glossy lobe (Knecht 2009 Eq. 4.8 with the renderer's BRDF): rgb = specular reflectance x
    // incident power (scaled like `power`), w = Blinn-Phong exponent (0: no lobe).
    gloss: vec4<f32>,
}

// Radiant intensity (W/sr) VPL `vpl` emits along unit direction `dir` leaving it, where
// cos_s = dot(normal, dir) > 0: f_r(incident, dir) Phi cos_s with the renderer's BRDF, i.e. the
// diffuse lobe power / pi cos_s plus the energy-normalised Blinn-Phong lobe around the
// reflection of the incident direction, gloss (e + 8) / (8 pi) (n.h)^e cos_s.
fn vpl_intensity(vpl: Vpl, dir: vec3<f32>, cos_s: f32) -> vec3<f32> {
    let inv_pi = 0.318309886183791;
    var i = vpl.power.rgb * inv_pi;
    let e = vpl.gloss.w;
    if e > 0.0 {
        let h = normalize(vpl.incident.xyz + dir);
        i = i + vpl.gloss.rgb * (e + 8.0) * 0.125 * inv_pi * pow(max(dot(vpl.normal.xyz, h), 0.0), e);
    }
    return i * cos_s;
}

// Where receiver `p` falls in VPL `k`'s imperfect shadow map: the atlas index (tiles of side r,
// c per row) and p's distance normalised by the scene diameter, to compare with the stored
// depth (visible when depth <= stored + bias).
struct IsmLookup {
    index: u32,
    depth: f32,
}

fn ism_lookup(vpl: Vpl, k: u32, p: vec3<f32>, r: u32, c: u32, inv_d_max: f32) -> IsmLookup {
    let pb = paraboloid(vpl.position.xyz, vpl.normal.xyz, p);
    let texel = min(vec2<u32>(pb.xy * f32(r)), vec2<u32>(r - 1u));
    let a = vec2<u32>((k % c) * r, (k / c) * r) + texel;
    return IsmLookup(a.y * r * c + a.x, pb.z * inv_d_max);
}

// The point a receiver is looked up at: normal-offset ISM visibility (an extension of the
// thesis's constant depth bias). Each ISM's points are spread by solid angle
// (`ism_select.wgsl`), so on a surface at distance d from the VPL they lie about d sigma apart,
// sigma = sqrt(W / P) the VPL's angular point spacing (its normal.w). A receiver sees its own
// surface's splats up to about d sigma / 2 tan(theta) nearer along a ray at angle theta to its
// normal, and one atlas texel (angle 4 / r at the paraboloid's centre) adds d 2/r tan(theta).
// Moving the receiver along its normal by delta gives a depth margin of delta / cos(theta)
// against its own plane, so delta = d (sigma (c + k sin(theta)) + (2/r) sin(theta)) covers
// both errors, growing at grazing angles as a slope-scaled depth bias does; but the moved point
// stays on the receiver's side of every other surface, so unlike a depth bias it lets no light
// through a wall, however grazing the ray. Every term is a fraction of the VPL-receiver
// distance: the offset means the same at every scene scale. `p` and `n` are the receiver's
// position and unit geometric normal, `light` the VPL's position, `sigma` its angular spacing;
// `b` = (unused, c, k, 2 / r).
fn ism_offset_point(b: vec4<f32>, sigma: f32, light: vec3<f32>, p: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    let to_light = light - p;
    let d = length(to_light);
    let cos_r = clamp(dot(n, to_light) / max(d, 1.0e-20), 0.0, 1.0);
    let sin_r = sqrt(max(1.0 - cos_r * cos_r, 0.0));
    let delta = d * (sigma * (b.y + b.z * sin_r) + b.w * sin_r);
    return p + n * delta;
}
