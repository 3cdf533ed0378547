// The environment's uniform block (mirrors render::sky::SkyUniforms); `common/sky.wgsl`
// reads it.
struct SkyParams {
    // rgb: a constant sky's radiance; a: the intensity.
    radiance: vec4<f32>,
    // 0 none, 1 constant, 2 image; image width, height; unused.
    kind: vec4<u32>,
    // cos, sin of the rotation about +Y.
    rotation: vec4<f32>,
}
