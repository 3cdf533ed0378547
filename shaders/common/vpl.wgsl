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
