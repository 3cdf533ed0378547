// rcs record computation, step 1 (notes: "GPU hemisphere sampling"): the scene rasterised by a
// square-plane camera at the record, looking along its normal with tan(half aperture) = 2 (126.87
// degrees), into the record's tile of the atlas. Outputs per texel:
//   0 rgba32float  rgb = outgoing radiance of the surface seen as a diffuse sender: albedo / pi
//                  x the shadowed direct irradiance of every light and the cache's irradiance
//                  for later bounces, a glossy lobe's share of both too (its directional albedo
//                  per light, its mean under the cache's light: `sender_reflectance`; spread
//                  over the hemisphere instead of along the lobe), plus the emission of an
//                  emissive front face), a = its distance
//                  from the record (0: nothing, the background, where the reduce takes the sky)
//   1 rgba16float  xy = octahedral normal of the surface seen, z = its albedo's luminance (0 on
//                  back faces), for the light check's strata; a = 0 nothing or a back face, 1 a
//                  front face, 2 one where the cache answered the bounce lookup, 3 where it
//                  extrapolated, 0.5 where it had nothing (the inspector's lookup misses)
// Back faces (the inside of a closed object seen through a crack) send nothing.
#import common/frame.wgsl
#import common/octahedral.wgsl
#import common/lights.wgsl
#import common/color.wgsl
#import common/material.wgsl
#import common/brdf.wgsl
#import render/gi/rcs/rcs_job.wgsl
#import render/gi/rcs/rcs_common.wgsl

@group(0) @binding(0) var<uniform> job: Job;
@group(0) @binding(1) var<uniform> frame: Frame;
@group(0) @binding(2) var<storage, read> lights: array<GpuLight>;
@group(0) @binding(3) var<storage, read> shadow_views: array<mat4x4<f32>>;
@group(0) @binding(4) var shadow_maps: texture_depth_2d_array;
@group(0) @binding(5) var shadow_sampler: sampler_comparison;
@group(0) @binding(6) var<storage, read> records: array<Record>;
@group(0) @binding(7) var<uniform> grid: GridParams;
@group(0) @binding(8) var<storage, read> grid_cells: array<vec2<u32>>;
@group(0) @binding(9) var<storage, read> grid_items: array<u32>;

#import common/shadow.wgsl
#import render/gi/rcs/rcs_lookup.wgsl


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
    let world = (object.world_from_local * vec4<f32>(v.position, 1.0)).xyz;
    let d = world - job.position.xyz;
    let local = vec3<f32>(dot(d, job.tangent.xyz), dot(d, job.bitangent.xyz), dot(d, job.normal.xyz));
    // x / z and y / z span [-2, 2] on the plane; reversed depth near / z (clipped below near).
    out.clip = vec4<f32>(local.x * 0.5, local.y * 0.5, job.position.w, local.z);
    out.world = world;
    out.normal = (object.normal_from_local * vec4<f32>(v.normal, 0.0)).xyz;
    out.uv = v.uv;
    return out;
}

struct HemisphereOut {
    @location(0) radiance: vec4<f32>,
    @location(1) surface: vec4<f32>,
}

@fragment
fn fs_main(in: VertexOut) -> HemisphereOut {
    var out: HemisphereOut;
    let to_record = job.position.xyz - in.world;
    let distance = max(length(to_record), 1.0e-6);
    let n = normalize(in.normal);
    if job.params.x > 0.5 {
        out.radiance = vec4<f32>(1.0, 1.0, 1.0, distance);
        out.surface = vec4<f32>(oct_encode(n), 1.0, 1.0);
        return out;
    }
    if dot(n, to_record) <= 0.0 {
        out.radiance = vec4<f32>(0.0, 0.0, 0.0, distance);
        out.surface = vec4<f32>(oct_encode(n), 0.0, 0.0);
        return out;
    }
    let albedo = material_albedo(in.uv);
    let lobe = material.specular;
    // The direct light sent (x pi): each light's shadowed irradiance times the reflectance at its
    // incidence.
    var sent = vec3<f32>(0.0);
    for (var i = 0u; i < frame.params.x; i = i + 1u) {
        let lit = shadowed_light(frame, i, in.world, n);
        sent = sent + sender_reflectance_at(albedo, lobe.rgb, lobe.a, lit.w) * lit.rgb;
    }
    // The cache's irradiance (later bounces).
    var e = vec3<f32>(0.0);
    // a = 1: a lit front face; 2: and the cache answered the lookup; 0.5: it did not.
    var found = 1.0;
    if job.params.y > 0.5 {
        let cached = cache_irradiance(in.world, n);
        found = select(0.5, 2.0, cached.a > 0.0);
        if cached.a < 0.0 {
            found = 3.0;
        }
        if cached.a == 0.0 && job.extra.x > 0.0 {
            // No record faces this way near the surface (one the camera never saw): Radiance's
            // ambient value, made adaptive: the renewed record's own previous irradiance.
            e = e + records[bitcast<u32>(job.normal.w)].irradiance.rgb;
        } else {
            e = e + cached.rgb;
        }
    }
    sent = sent + sender_reflectance(albedo, lobe.rgb, lobe.a) * e;
    out.radiance = vec4<f32>(sent / PI + material_emission(in.uv), distance);
    out.surface = vec4<f32>(oct_encode(n), luminance(albedo), found);
    return out;
}
