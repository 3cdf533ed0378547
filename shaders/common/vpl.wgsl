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

// The ISM atlas word (`ism_splat.wgsl` writes it with an atomic min, so the nearest surface
// wins): bits 31..15 the depth along the texel's centre ray, normalised by the scene diameter
// (all ones: empty); bits 14..1 the slot + 1 of the VPL's point whose splat it is (0: none, a
// depth only); bit 0 set where pull-push filled a hole. With the point, a lookup tests the
// receiver's own ray against that point's surface (`ism_lookup.wgsl`) instead of comparing
// depths at the texel centre.
const ISM_EMPTY: u32 = 0xffffffffu;
const ISM_DEPTH_MAX: f32 = 131070.0;

fn ism_pack(depth: f32, slot1: u32) -> u32 {
    let d = u32(round(clamp(depth, 0.0, 1.0) * ISM_DEPTH_MAX));
    return (d << 15u) | ((slot1 & 0x3fffu) << 1u);
}

// The normalised depth of an atlas word (1.0 for an empty texel).
fn ism_depth(bits: u32) -> f32 {
    if bits >> 15u == 0x1ffffu {
        return 1.0;
    }
    return f32(bits >> 15u) / ISM_DEPTH_MAX;
}

// The slot + 1 of the point whose splat an atlas word holds (0: none).
fn ism_slot1(bits: u32) -> u32 {
    return (bits >> 1u) & 0x3fffu;
}

// Where receiver `p` falls in VPL `k`'s imperfect shadow map: the atlas index (tiles of side r,
// c per row), p's unit direction from the VPL, its distance and that distance normalised by
// the scene diameter.
struct IsmLookup {
    index: u32,
    dir: vec3<f32>,
    dist: f32,
    depth: f32,
}

fn ism_lookup(vpl: Vpl, k: u32, p: vec3<f32>, r: u32, c: u32, inv_d_max: f32) -> IsmLookup {
    let pb = paraboloid(vpl.position.xyz, vpl.normal.xyz, p);
    let texel = min(vec2<u32>(pb.xy * f32(r)), vec2<u32>(r - 1u));
    let a = vec2<u32>((k % c) * r, (k / c) * r) + texel;
    let dir = (p - vpl.position.xyz) / max(pb.z, 1.0e-20);
    return IsmLookup(a.y * r * c + a.x, dir, pb.z, pb.z * inv_d_max);
}

// The point a receiver is looked up at: a normal offset (an extension of the thesis's constant
// depth bias). Each ISM's points are spread by solid angle (`ism_select.wgsl`), so on a surface
// at distance d from the VPL they lie about d sigma apart, sigma = sqrt(W / P) the VPL's angular
// point spacing (its normal.w). The surface lookup (`ism_lit`) removes the self-shadowing of
// flat surfaces; what is left is a curved surface's, which lies behind its neighbours' tangent
// disks by a fraction of their spacing, hence delta = d sigma (c + k sin(theta)), theta the angle
// between the receiver's normal and the VPL. An offset moves the receiver's ray, though: a floor
// receiver beyond a doorway, raised by delta, is looked up through the doorway higher up and falls
// in the lintel's shadow sooner (with the texel-sized term d 2/r sin(theta) that the surface
// lookups replaced, the suite's three rooms read 0.90 of the reference's energy; with k = 0.2,
// 0.64). `p` and `n` are
// the receiver's position and unit geometric normal, `light` the VPL's position, `sigma` its
// angular spacing; `b` = (unused, c, k, unused).
fn ism_offset_point(b: vec4<f32>, sigma: f32, light: vec3<f32>, p: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    let to_light = light - p;
    let d = length(to_light);
    let cos_r = clamp(dot(n, to_light) / max(d, 1.0e-20), 0.0, 1.0);
    let sin_r = sqrt(max(1.0 - cos_r * cos_r, 0.0));
    let delta = d * sigma * (b.y + b.z * sin_r);
    return p + n * delta;
}
