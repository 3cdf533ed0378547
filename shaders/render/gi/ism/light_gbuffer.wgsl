// ISM pass P2: the light G-buffer (an RSM without stored flux, Knecht 2009 section 4.3) of one
// tile: a spot light's frustum, one face of a point light's cube, or a directional light's
// orthographic view of the scene. Outputs per texel:
//   0 albedo     rgba8unorm   base colour x texture, a = specular luminance
//   1 normal     rgba16float  world-space shading normal, w = world area of the surface patch
//                             this texel sees (m^2; the VPL's disk radius comes from it)
//   2 power      rgba16float  rgb = power reflected by the patch this texel sees, in watts:
//                             rho * I(w) * dOmega for perspective tiles, rho * E * A_texel for
//                             orthographic ones (the cosine cancels), a = importance
//   3 specular   rgba16float  rgb = specular reflectance x I(w) dOmega (the incident power the
//                             glossy lobe reflects), a = Blinn-Phong exponent (0: no lobe)
// Back faces (the light reaches the back of a one-sided surface) reflect nothing.
#import common/color.wgsl
#import common/lights.wgsl
#import common/material.wgsl
#import common/brdf.wgsl

struct LightView {
    clip_from_world: mat4x4<f32>,
    light: GpuLight,
    // tan(half fov), texels per side, world area of a texel (orthographic tiles, else 0), unused.
    params: vec4<f32>,
    // xyz view axis of this tile (the spot direction or a cube face), w unused.
    axis: vec4<f32>,
}

@group(0) @binding(0) var<uniform> view: LightView;

struct VertexOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
}

@vertex
fn vs_main(v: MeshVertex, @builtin(instance_index) instance: u32) -> VertexOut {
    var out: VertexOut;
    let object = objects[instance];
    let world = object.world_from_local * vec4<f32>(v.position, 1.0);
    out.world = world.xyz;
    out.clip = view.clip_from_world * world;
    out.normal = (object.normal_from_local * vec4<f32>(v.normal, 0.0)).xyz;
    out.uv = v.uv;
    return out;
}

struct LightGbufferOut {
    @location(0) albedo: vec4<f32>,
    @location(1) normal: vec4<f32>,
    @location(2) power: vec4<f32>,
    @location(3) specular: vec4<f32>,
}

@fragment
fn fs_main(in: VertexOut, @builtin(front_facing) front: bool) -> LightGbufferOut {
    var out: LightGbufferOut;
    let albedo = material_albedo(in.uv);
    let spec = luminance(material.specular.rgb);
    let n = normalize(in.normal);
    out.albedo = vec4<f32>(albedo, spec);
    let inc = light_incident(view.light, in.world);
    // Solid angle of this texel seen from the light: (2 t / L)^2 cos^3 of the angle off axis.
    let cos_axis = max(dot(view.axis.xyz, -inc.dir), 0.0);
    let texel = 2.0 * view.params.x / view.params.y;
    let d_omega = texel * texel * cos_axis * cos_axis * cos_axis;
    // irradiance * d^2 = radiant intensity towards this texel (spot falloff and range included);
    // a directional light's irradiance times the texel's cross-section is the power it sends.
    var incident = inc.irradiance * inc.distance * inc.distance * d_omega;
    // The patch's area: the texel's cross-section at the surface over the cosine of incidence
    // (bounded at grazing angles, where the patch reflects little anyway).
    var cross_section = d_omega * inc.distance * inc.distance;
    if view.params.z > 0.0 {
        incident = inc.irradiance * view.params.z;
        cross_section = view.params.z;
    }
    out.normal = vec4<f32>(n, cross_section / max(abs(dot(n, inc.dir)), 0.05));
    if !front {
        incident = vec3<f32>(0.0);
    }
    let reflected = albedo * incident;
    // f16 holds exponents up to 65504; 4096 is already a mirror at light G-buffer resolution.
    let exponent = select(0.0, min(phong_exponent(material.specular.a), 4096.0), spec > 0.0);
    out.specular = vec4<f32>(material.specular.rgb * incident, exponent);
    let importance = luminance(reflected) * (0.5 + spec);
    out.power = vec4<f32>(reflected, importance);
    return out;
}
