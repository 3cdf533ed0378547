// Punctual lights with the KHR_lights_punctual conventions (mirrors render::uniforms::GpuLight):
// colour x intensity is W/sr (point, spot) or W/m^2 (directional); inverse-square falloff with the
// specification's optional range window; spot falloff = saturate(cos * scale + offset)^2.
const LIGHT_POINT: u32 = 0u;
const LIGHT_SPOT: u32 = 1u;
const LIGHT_DIRECTIONAL: u32 = 2u;

struct GpuLight {
    // xyz position, w = kind.
    position: vec4<f32>,
    // xyz unit direction of travel, w = range (0 = none).
    direction: vec4<f32>,
    // rgb = colour * intensity, w = first shadow layer (< 0: no shadow).
    radiant: vec4<f32>,
    // spot scale, spot offset, shadow texel size per metre of distance (or per texel for
    // directional), unused.
    cone: vec4<f32>,
}

struct Incident {
    // Unit direction from the surface towards the light.
    dir: vec3<f32>,
    // Irradiance on a surface facing the light (W/m^2), before cosine and shadow.
    irradiance: vec3<f32>,
    // Distance to the light (large for directional).
    distance: f32,
}

fn light_kind(light: GpuLight) -> u32 {
    return u32(light.position.w + 0.5);
}

fn light_incident(light: GpuLight, p: vec3<f32>) -> Incident {
    var out: Incident;
    if light_kind(light) == LIGHT_DIRECTIONAL {
        out.dir = -light.direction.xyz;
        out.irradiance = light.radiant.rgb;
        out.distance = 1.0e30;
        return out;
    }
    let to_light = light.position.xyz - p;
    let d2 = max(dot(to_light, to_light), 1.0e-8);
    let d = sqrt(d2);
    out.dir = to_light / d;
    out.distance = d;
    var atten = 1.0 / d2;
    let range = light.direction.w;
    if range > 0.0 {
        let r = d / range;
        atten = atten * clamp(1.0 - r * r * r * r, 0.0, 1.0);
    }
    if light_kind(light) == LIGHT_SPOT {
        let cd = dot(light.direction.xyz, -out.dir);
        let a = clamp(cd * light.cone.x + light.cone.y, 0.0, 1.0);
        atten = atten * a * a;
    }
    out.irradiance = light.radiant.rgb * atten;
    return out;
}
