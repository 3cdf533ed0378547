// A virtual point light as the ISM passes store it (mirrors render::gi::ism::vpl_pass::GpuVpl).
#import common/onb.wgsl
#import common/octahedral.wgsl

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
// wins): bits 31..16 the depth along the texel's centre ray, normalised by the scene diameter
// (0xffff: empty); bits 15..1 the octahedral normal of the splat's plane (8 + 7 bits; 0: no
// plane, a depth only); bit 0 set where pull-push filled a hole. With the plane, a lookup
// evaluates the occluder's depth along the receiver's own ray instead of the texel centre's, so
// a surface no longer shadows itself where the receiver's ray and the texel's meet it at
// different depths (what a slope-scaled bias or normal offset otherwise has to cover; such an
// offset shifts the light falling through a doorway, see `ism_offset_point`).
const ISM_EMPTY: u32 = 0xffffffffu;
const ISM_DEPTH_MAX: f32 = 65534.0;

fn ism_pack(depth: f32, n: vec3<f32>, with_plane: bool) -> u32 {
    let d = u32(round(clamp(depth, 0.0, 1.0) * ISM_DEPTH_MAX));
    var code = 0u;
    if with_plane {
        let e = oct_encode(n) * 0.5 + 0.5;
        let u = 1u + u32(round(clamp(e.x, 0.0, 1.0) * 254.0));
        let v = u32(round(clamp(e.y, 0.0, 1.0) * 127.0));
        code = (u << 7u) | v;
    }
    return (d << 16u) | (code << 1u);
}

// The normalised depth of an atlas word (1.0 for an empty texel).
fn ism_depth(bits: u32) -> f32 {
    if bits >> 16u == 0xffffu {
        return 1.0;
    }
    return f32(bits >> 16u) / ISM_DEPTH_MAX;
}

// The world direction of the paraboloid texel at `uv` (0..1) of a VPL with tangent frame `frame`.
fn texel_ray(frame: mat3x3<f32>, uv: vec2<f32>) -> vec3<f32> {
    let s = uv * 2.0 - 1.0;
    let ss = dot(s, s);
    return frame * (vec3<f32>(2.0 * s, 1.0 - ss) / (1.0 + ss));
}

// Where receiver `p` falls in VPL `k`'s imperfect shadow map: the atlas index (tiles of side r,
// c per row), its texel, p's unit direction from the VPL and its distance normalised by the
// scene diameter.
struct IsmLookup {
    index: u32,
    texel: vec2<u32>,
    dir: vec3<f32>,
    depth: f32,
}

fn ism_lookup(vpl: Vpl, k: u32, p: vec3<f32>, r: u32, c: u32, inv_d_max: f32) -> IsmLookup {
    let pb = paraboloid(vpl.position.xyz, vpl.normal.xyz, p);
    let texel = min(vec2<u32>(pb.xy * f32(r)), vec2<u32>(r - 1u));
    let a = vec2<u32>((k % c) * r, (k / c) * r) + texel;
    let dir = (p - vpl.position.xyz) / max(pb.z, 1.0e-20);
    return IsmLookup(a.y * r * c + a.x, texel, dir, pb.z * inv_d_max);
}

// Whether the lookup `l` into VPL `vpl`'s map (tile side r) is lit, given the atlas word
// `stored` at `l.index`. With a plane, the occluder's depth along the receiver's ray: the plane
// through the texel centre's stored point, met by the receiver's ray (the centre's depth where
// that ray runs within 3 degrees of the plane). Without one (a hole pull-push filled), the
// stored depth plus `margin` (its share of the depth). The tolerance covers the 16-bit depth
// and the normal's 8 / 7 bits over the half texel between the two rays.
fn ism_lit(vpl: Vpl, l: IsmLookup, stored: u32, r: u32, margin: f32) -> bool {
    if stored >> 16u == 0xffffu {
        return true;
    }
    let t = ism_depth(stored);
    let code = (stored >> 1u) & 0x7fffu;
    if code == 0u {
        return l.depth <= t * (1.0 + margin);
    }
    let e = vec2<f32>(f32((code >> 7u) - 1u) / 254.0, f32(code & 0x7fu) / 127.0) * 2.0 - 1.0;
    let n = oct_decode(e);
    let frame = mat3x3<f32>(onb_tangent(vpl.normal.xyz), onb_bitangent(vpl.normal.xyz), vpl.normal.xyz);
    let centre = texel_ray(frame, (vec2<f32>(l.texel) + 0.5) / f32(r));
    let den = dot(l.dir, n);
    var plane = t;
    if abs(den) > 0.05 {
        plane = t * dot(centre, n) / den;
    }
    return l.depth <= max(plane, 0.0) * 1.002 + 2.0 / ISM_DEPTH_MAX;
}

// The point a receiver is looked up at: a normal offset (an extension of the thesis's constant
// depth bias). Each ISM's points are spread by solid angle (`ism_select.wgsl`), so on a surface
// at distance d from the VPL they lie about d sigma apart, sigma = sqrt(W / P) the VPL's angular
// point spacing (its normal.w). The plane stored per texel (`ism_lit`) removes the self-shadowing
// of flat surfaces; what is left is a curved surface's, which lies behind its neighbours' tangent
// disks by a fraction of their spacing, hence delta = d sigma (c + k sin(theta)), theta the angle
// between the receiver's normal and the VPL. An offset moves the receiver's ray, though: a floor
// receiver beyond a doorway, raised by delta, is looked up through the doorway higher up and falls
// in the lintel's shadow sooner (with the texel-sized term d 2/r sin(theta) the plane replaced, the
// suite's three rooms read 0.90 of the reference's energy; with k = 0.2, 0.64). `p` and `n` are
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
