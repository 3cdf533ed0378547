// sshgi hidden senders, pack (an extension of Soler et al. 2010, not in the paper): points spread
// over the scene's surfaces by area (`precompute::sample_points`, one stratified block of them a
// frame) that the camera's position does not see become senders after the panorama's: the back
// of a pillar, a box's far side, the floor behind it. A point is hidden when it lies farther from
// the camera (by `hp.tolerance.x` of their distance) than every one of the 2x2 view pixels around
// its projection where it lies inside the view's frustum, else than every one of the 2x2
// panorama texels around its direction: the screen and the panorama, both seen from the camera,
// send what it sees, and a point at a silhouette is left to them (no light counted twice). The
// view's pixels, not the panorama's 90-degree texels, decide inside the frustum: there a 2x2 of
// 32-texel faces spans about 5.6 degrees, and the points just behind a pillar's edge (its sides,
// the floor at its foot) sat beside a texel of the far wall, so neither the screen nor anything
// else sent them (the pillars level read 0.77 of the path tracer's energy, 0.89 with the view's
// pixels and visibility on every bounce; `docs/notes/sshgi.md`, stop 77). A hidden point's first
// radiance is its direct light as a diffuse sender sends it (the view's lights and shadow maps,
// the lighting pass's own functions and its `exitance`: albedo + a glossy lobe's directional
// albedo per light) plus its emission; its reflectance for later bounces is albedo + the lobe's
// share of diffuse light; its area is its share of its object's surface.
#import common/frame.wgsl
#import common/lights.wgsl
#import common/brdf.wgsl

struct HiddenParams {
    // Each panorama face's clip_from_world (the cube turned this frame).
    faces: array<mat4x4<f32>, 6>,
    // points this frame, the first point of this frame's block, the list index of the first
    // hidden sender (6 F^2), face size F.
    counts: vec4<u32>,
    // x: relative distance tolerance, yzw unused.
    tolerance: vec4<f32>,
}

// One point of the scene (`hidden.rs`, `GpuSurfel`).
struct Surfel {
    // xyz the point, w the area it stands for (m^2; 0: none).
    point: vec4<f32>,
    // xyz geometric normal (front), w unused.
    normal: vec4<f32>,
    // rgb albedo, a unused.
    albedo: vec4<f32>,
    // rgb emitted radiance (W / (sr m^2)), a unused.
    emission: vec4<f32>,
    // rgb specular colour (zero: no glossy lobe), a roughness.
    specular: vec4<f32>,
}

#import render/gi/sshgi/sshgi_sender.wgsl

@group(0) @binding(0) var<uniform> hp: HiddenParams;
@group(0) @binding(1) var<storage, read> surfels: array<Surfel>;
// The panorama's distance to the surface per face texel (`sshgi_panorama_pack.wgsl`).
@group(0) @binding(2) var<storage, read> distances: array<f32>;
@group(0) @binding(3) var<storage, read_write> senders: array<Sender>;
@group(0) @binding(4) var<storage, read_write> radiance: array<vec4<f32>>;
// The view's own distances (the depth/normal pyramid's level 0: r the distance, a > 0 where a
// surface is).
@group(0) @binding(5) var view_geometry: texture_2d<f32>;

// The lighting pass's inputs, with the view's frame.
@group(1) @binding(0) var<uniform> frame: Frame;
@group(1) @binding(1) var<storage, read> lights: array<GpuLight>;
@group(1) @binding(2) var<storage, read> shadow_views: array<mat4x4<f32>>;
@group(1) @binding(3) var shadow_maps: texture_depth_2d_array;
@group(1) @binding(4) var shadow_sampler: sampler_comparison;

#import common/shadow.wgsl

// The direct light the surfel sends as a diffuse sender: (albedo + the lobe's directional albedo
// at each light's incidence) / pi x that light's shadowed irradiance, as the lighting pass's
// `exitance`.
fn direct_exitance(s: Surfel) -> vec3<f32> {
    if !has_lobe(s.specular.rgb) {
        return s.albedo.rgb / PI * shadowed_irradiance(frame, s.point.xyz, s.normal.xyz);
    }
    var sum = vec3<f32>(0.0);
    for (var i = 0u; i < frame.params.x; i = i + 1u) {
        let lit = shadowed_light(frame, i, s.point.xyz, s.normal.xyz);
        sum = sum + sender_reflectance_at(s.albedo.rgb, s.specular.rgb, s.specular.a, lit.w) / PI * lit.rgb;
    }
    return sum;
}

// Whether the view shows p, at distance d from the camera: 0 where p lies outside the view's
// frustum, else 1 where it lies no farther than the farthest of the 2x2 view pixels around its
// projection (plus the tolerance; a pixel without a surface is infinitely far), 2 where it lies
// behind all four.
fn seen_in_view(p: vec3<f32>, d: f32) -> u32 {
    let c = frame.clip_from_world * vec4<f32>(p, 1.0);
    if c.w <= 0.0 {
        return 0u;
    }
    let ndc = c.xyz / c.w;
    if any(abs(ndc.xy) > vec2<f32>(1.0)) || ndc.z < 0.0 || ndc.z > 1.0 {
        return 0u;
    }
    let size = vec2<i32>(textureDimensions(view_geometry));
    let uv = vec2<f32>(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5) * vec2<f32>(size) - 0.5;
    let base = vec2<i32>(floor(uv));
    var far = 0.0;
    for (var k = 0; k < 4; k = k + 1) {
        let t = clamp(base + vec2<i32>(k & 1, k >> 1), vec2<i32>(0), size - 1);
        let g = textureLoad(view_geometry, t, 0);
        far = max(far, select(1.0e30, g.r, g.a > 0.5));
    }
    return select(2u, 1u, d <= far * (1.0 + hp.tolerance.x));
}

// Whether the camera sees p: inside the view's frustum as the view's pixels say
// (`seen_in_view`), elsewhere when it lies no farther than the farthest of the 2x2 panorama
// texels around its direction (plus the tolerance). A point no face holds counts as seen.
fn seen_from_camera(p: vec3<f32>) -> bool {
    let d = distance(p, frame.camera_position.xyz);
    let in_view = seen_in_view(p, d);
    if in_view != 0u {
        return in_view == 1u;
    }
    let f = hp.counts.w;
    for (var face = 0u; face < 6u; face = face + 1u) {
        let c = hp.faces[face] * vec4<f32>(p, 1.0);
        if c.w <= 0.0 {
            continue;
        }
        let ndc = c.xy / c.w;
        if any(abs(ndc) > vec2<f32>(1.0)) {
            continue;
        }
        let uv = vec2<f32>(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5) * f32(f) - 0.5;
        let base = vec2<i32>(floor(uv));
        var far = 0.0;
        for (var k = 0; k < 4; k = k + 1) {
            let t = clamp(base + vec2<i32>(k & 1, k >> 1), vec2<i32>(0), vec2<i32>(i32(f) - 1));
            far = max(far, distances[face * f * f + u32(t.y) * f + u32(t.x)]);
        }
        return d <= far * (1.0 + hp.tolerance.x);
    }
    return true;
}

@compute @workgroup_size(64, 1, 1)
fn pack(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= hp.counts.x {
        return;
    }
    let s = surfels[hp.counts.y + id.x];
    let index = hp.counts.z + id.x;
    if s.point.w <= 0.0 || seen_from_camera(s.point.xyz) {
        senders[index] = Sender(vec4<f32>(0.0), vec4<f32>(0.0), vec4<f32>(0.0));
        radiance[index] = vec4<f32>(0.0);
        return;
    }
    let reflectance = sender_reflectance(s.albedo.rgb, s.specular.rgb, s.specular.a);
    senders[index] = Sender(s.point, s.normal, vec4<f32>(reflectance, 0.0));
    let light = direct_exitance(s) + s.emission.rgb;
    radiance[index] = vec4<f32>(light, 0.0);
}
