// Deferred direct lighting into its own target: shadowed punctual lights on the Lambertian +
// glossy BRDF, plus what the camera sees of emitters: the front faces of emissive surfaces
// (`emission.wgsl`'s target) and, where no surface is, the sky (render::sky; the same mapping
// and nearest texel as the path tracer). The GI technique may read it; `composite.wgsl` adds
// the indirect term. One-sided surfaces: a light behind the geometric normal adds nothing.
// Beside it, the same light as a diffuse sender sends it (`exitance`): the emission plus
// (albedo + specular x the lobe's directional albedo) / pi x each light's irradiance, the
// surface's radiant exitance over pi. A GI technique that treats the surfaces it sees as
// diffuse senders (`sshgi`) reads it: the direct term's glossy lobe points at the camera only,
// while a glossy floor under a lamp sends up to its specular colour more upwards. Without a lobe
// the two are equal.
#import common/frame.wgsl
#import common/octahedral.wgsl
#import common/lights.wgsl
#import common/brdf.wgsl
#import common/sky_params.wgsl

@group(0) @binding(0) var<uniform> frame: Frame;
@group(0) @binding(1) var<storage, read> lights: array<GpuLight>;
@group(0) @binding(2) var<storage, read> shadow_views: array<mat4x4<f32>>;
@group(0) @binding(3) var shadow_maps: texture_depth_2d_array;
@group(0) @binding(4) var shadow_sampler: sampler_comparison;
@group(0) @binding(5) var sky_tex: texture_2d<f32>;
@group(0) @binding(6) var<uniform> sky: SkyParams;
#import common/sky.wgsl

@group(1) @binding(0) var depth_tex: texture_depth_2d;
@group(1) @binding(1) var albedo_tex: texture_2d<f32>;
@group(1) @binding(2) var normal_tex: texture_2d<f32>;
@group(1) @binding(3) var material_tex: texture_2d<f32>;
@group(1) @binding(4) var out_radiance: texture_storage_2d<rgba32float, write>;
@group(1) @binding(5) var emission_tex: texture_2d<f32>;
@group(1) @binding(6) var out_exitance: texture_storage_2d<rgba32float, write>;

#import common/shadow.wgsl

@compute @workgroup_size(8, 8, 1)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = vec2<u32>(frame.size.xy);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    let pixel = id.xy;
    let depth = textureLoad(depth_tex, pixel, 0);
    // Reversed depth: 0 is the far plane (nothing drawn).
    if depth <= 0.0 {
        let dir = normalize(world_from_pixel(frame, pixel, 0.5) - frame.camera_position.xyz);
        let sky_light = vec4<f32>(sky_radiance(dir), 1.0);
        textureStore(out_radiance, pixel, sky_light);
        textureStore(out_exitance, pixel, sky_light);
        return;
    }
    let p = world_from_pixel(frame, pixel, depth);
    let albedo = textureLoad(albedo_tex, pixel, 0).rgb;
    let enc = textureLoad(normal_tex, pixel, 0);
    let n = oct_decode(enc.xy);
    let ng = oct_decode(enc.zw);
    let mat = textureLoad(material_tex, pixel, 0);
    let v = normalize(frame.camera_position.xyz - p);
    var radiance = textureLoad(emission_tex, pixel, 0).rgb;
    var exitance = radiance;
    for (var i = 0u; i < frame.params.x; i = i + 1u) {
        let light = lights[i];
        let inc = light_incident(light, p);
        if dot(ng, inc.dir) <= 0.0 {
            continue;
        }
        let cos_s = max(dot(n, inc.dir), 0.0);
        if cos_s <= 0.0 || all(inc.irradiance <= vec3<f32>(0.0)) {
            continue;
        }
        let vis = shadow_factor(frame, light, p, ng, inc.distance);
        let f = brdf_eval(albedo, mat.rgb, mat.a, n, v, inc.dir);
        let e = inc.irradiance * cos_s * vis;
        radiance = radiance + f * e;
        exitance = exitance + sender_reflectance_at(albedo, mat.rgb, mat.a, cos_s) / PI * e;
    }
    textureStore(out_radiance, pixel, vec4<f32>(radiance, 1.0));
    textureStore(out_exitance, pixel, vec4<f32>(exitance, 1.0));
}
