// A virtual point light as the ISM passes store it (mirrors render::gi::ism::vpl_pass::GpuVpl).
struct Vpl {
    // xyz position, w = 1 when valid.
    position: vec4<f32>,
    // xyz surface normal, w = specular luminance.
    normal: vec4<f32>,
    // rgb power (W, times the interleave factor n^2), a = pdf of the chosen texel.
    power: vec4<f32>,
    // xyz unit direction towards the light it came from, w = light-G-buffer texel index.
    incident: vec4<f32>,
}

// Radiant intensity (W/sr) VPL `vpl` emits along unit direction `dir` leaving it, where
// cos_s = dot(normal, dir) > 0: the diffuse lobe power / pi cos_s.
fn vpl_intensity(vpl: Vpl, dir: vec3<f32>, cos_s: f32) -> vec3<f32> {
    return vpl.power.rgb / 3.14159265358979 * cos_s;
}
