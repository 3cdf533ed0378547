// The object and material bindings of every pass that rasterises the scene with
// render::layouts::Layouts (group 1: the object array, group 2: material), and the albedo they
// give. Objects are drawn instanced: a vertex's object is objects[instance_index].
#import common/object.wgsl

@group(1) @binding(0) var<storage, read> objects: array<Object>;
@group(2) @binding(0) var<uniform> material: MaterialParams;
@group(2) @binding(1) var base_texture: texture_2d<f32>;
@group(2) @binding(2) var normal_texture: texture_2d<f32>;
@group(2) @binding(3) var material_sampler: sampler;
@group(2) @binding(4) var emissive_texture: texture_2d<f32>;

// Linear Lambertian albedo at `uv`: the base colour factor times the base colour texture.
fn material_albedo(uv: vec2<f32>) -> vec3<f32> {
    var albedo = material.base_color.rgb;
    if material.flags.x != 0u {
        albedo = albedo * textureSample(base_texture, material_sampler, uv).rgb;
    }
    return albedo;
}

// Emitted radiance of the front face at `uv`: emission colour x strength times the emission
// texture (sRGB, decoded by the view).
fn material_emission(uv: vec2<f32>) -> vec3<f32> {
    var e = material.params.yzw;
    if material.flags.z != 0u {
        e = e * textureSample(emissive_texture, material_sampler, uv).rgb;
    }
    return e;
}
