// Per-object data and per-material uniforms shared by every pass that rasterises the scene
// (mirrors render::uniforms::ObjectUniforms and MaterialUniforms).
struct Object {
    world_from_local: mat4x4<f32>,
    normal_from_local: mat4x4<f32>,
    prev_world_from_local: mat4x4<f32>,
    // object id + 1, material index, unused, unused.
    ids: vec4<u32>,
    // Pads the array stride to 256 bytes (render::scene_gpu::OBJECT_SLOT).
    pad: array<vec4<u32>, 3>,
}

struct MaterialParams {
    base_color: vec4<f32>,
    // rgb specular, a roughness.
    specular: vec4<f32>,
    // has base texture, has normal texture, has emission texture, unused.
    flags: vec4<u32>,
    // normal scale, emitted radiance (rgb: emission colour x strength).
    params: vec4<f32>,
}

// One scene-mesh vertex as every rasterising pass reads it (mirrors render::scene_gpu::Vertex).
struct MeshVertex {
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
    @location(3) tangent: vec4<f32>,
}
