// G-buffer pass: one draw per object. Outputs (see render::gbuffer for formats and packing):
//   0 albedo    rgba16float      linear Lambertian albedo (base colour x texture), a = 1
//   1 normal    rgba16float      xy = octahedral shading normal (normal-mapped), zw = octahedral geometric normal
//   2 material  rgba8unorm       rgb = specular colour, a = roughness
//   3 motion    rg16float        uv(current) - uv(previous frame)
//   4 object id r32uint          object index + 1 (0 = background)
#import common/frame.wgsl
#import common/octahedral.wgsl
#import common/material.wgsl

@group(0) @binding(0) var<uniform> frame: Frame;

struct VertexOut {
    // Invariant: the emission pass (`emission.wgsl`) redraws emissive objects with depth Equal.
    @builtin(position) @invariant clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
    @location(3) tangent: vec4<f32>,
    @location(4) cur_clip: vec4<f32>,
    @location(5) prev_clip: vec4<f32>,
    @location(6) @interpolate(flat) object_id: u32,
}

@vertex
fn vs_main(v: MeshVertex, @builtin(instance_index) instance: u32) -> VertexOut {
    var out: VertexOut;
    let object = objects[instance];
    out.object_id = object.ids.x;
    let world = object.world_from_local * vec4<f32>(v.position, 1.0);
    out.world = world.xyz;
    out.clip = frame.clip_from_world * world;
    out.cur_clip = out.clip;
    out.prev_clip = frame.prev_clip_from_world * (object.prev_world_from_local * vec4<f32>(v.position, 1.0));
    out.normal = (object.normal_from_local * vec4<f32>(v.normal, 0.0)).xyz;
    out.tangent = vec4<f32>((object.world_from_local * vec4<f32>(v.tangent.xyz, 0.0)).xyz, v.tangent.w);
    out.uv = v.uv;
    return out;
}

struct GbufferOut {
    @location(0) albedo: vec4<f32>,
    @location(1) normal: vec4<f32>,
    @location(2) material: vec4<f32>,
    @location(3) motion: vec2<f32>,
    @location(4) object_id: u32,
}

@fragment
fn fs_main(in: VertexOut) -> GbufferOut {
    var out: GbufferOut;
    let albedo = material_albedo(in.uv);
    var n = normalize(in.normal);
    // Flat geometric normal of the triangle, oriented like the interpolated normal.
    var ng = normalize(cross(dpdx(in.world), dpdy(in.world)));
    if dot(ng, n) < 0.0 {
        ng = -ng;
    }
    if material.flags.y != 0u {
        let t = normalize(in.tangent.xyz - n * dot(n, in.tangent.xyz));
        let b = cross(n, t) * select(-1.0, 1.0, in.tangent.w >= 0.0);
        var m = textureSample(normal_texture, material_sampler, in.uv).xyz * 2.0 - 1.0;
        m = vec3<f32>(m.xy * material.params.x, m.z);
        n = normalize(t * m.x + b * m.y + n * m.z);
    }
    out.albedo = vec4<f32>(albedo, 1.0);
    out.normal = vec4<f32>(oct_encode(n), oct_encode(ng));
    out.material = vec4<f32>(material.specular.rgb, material.specular.a);
    let cur = in.cur_clip.xy / in.cur_clip.w;
    let prev = in.prev_clip.xy / in.prev_clip.w;
    out.motion = (cur - prev) * vec2<f32>(0.5, -0.5);
    out.object_id = in.object_id;
    return out;
}
