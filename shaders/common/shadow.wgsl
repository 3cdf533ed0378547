// Shadow-map lookup: every shadow map is a layer of one depth array (spot and directional: one
// layer; point: six, faces +X -X +Y -Y +Z -Z). Filtering is (2r+1)^2 hardware 2x2 comparison taps
// (PCF); acne is avoided with a receiver offset along the geometric normal, sized in shadow texels
// at the receiver's distance, plus the raster pass's slope-scaled depth bias.
// Requires: frame.wgsl, lights.wgsl, and bindings `shadow_maps`, `shadow_sampler`, `shadow_views`.

fn point_face(v: vec3<f32>) -> u32 {
    let a = abs(v);
    if a.x >= a.y && a.x >= a.z {
        return select(1u, 0u, v.x >= 0.0);
    }
    if a.y >= a.z {
        return select(3u, 2u, v.y >= 0.0);
    }
    return select(5u, 4u, v.z >= 0.0);
}

fn shadow_factor(frame: Frame, light: GpuLight, p: vec3<f32>, n_geo: vec3<f32>, distance: f32) -> f32 {
    let first = i32(floor(light.radiant.w + 0.5));
    if first < 0 {
        return 1.0;
    }
    var texel_world = light.cone.z;
    if light_kind(light) != LIGHT_DIRECTIONAL {
        texel_world = light.cone.z * distance;
    }
    let q = p + n_geo * (frame.shadow.x * texel_world);
    var layer = first;
    if light_kind(light) == LIGHT_POINT {
        layer = first + i32(point_face(q - light.position.xyz));
    }
    let clip = shadow_views[layer] * vec4<f32>(q, 1.0);
    let ndc = clip.xyz / clip.w;
    if clip.w <= 0.0 || any(abs(ndc.xy) > vec2<f32>(1.0)) || ndc.z > 1.0 {
        return 1.0;
    }
    let uv = ndc.xy * vec2<f32>(0.5, -0.5) + 0.5;
    let r = i32(frame.params.z);
    var sum = 0.0;
    for (var y = -r; y <= r; y = y + 1) {
        for (var x = -r; x <= r; x = x + 1) {
            let o = vec2<f32>(f32(x), f32(y)) * frame.shadow.z;
            sum = sum + textureSampleCompareLevel(shadow_maps, shadow_sampler, uv + o, layer, ndc.z);
        }
    }
    let taps = f32((2 * r + 1) * (2 * r + 1));
    return sum / taps;
}
