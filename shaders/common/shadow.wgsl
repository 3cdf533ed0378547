// Shadow-map lookup: every shadow map is a layer of one depth array (spot and directional: one
// layer; point: six, faces +X -X +Y -Y +Z -Z). Filtering is (2r+1)^2 hardware 2x2 comparison taps
// (PCF); acne is avoided with receiver-plane depth bias plus a small receiver offset along the
// geometric normal, sized in shadow texels at the receiver's distance.
// Requires: frame.wgsl, lights.wgsl, and bindings `lights`, `shadow_maps`, `shadow_sampler`,
// `shadow_views`.

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

// Shadow-clip projection of `p` for `layer`: (uv, depth) and whether it is in front of the light.
fn shadow_project(layer: i32, p: vec3<f32>) -> vec4<f32> {
    let clip = shadow_views[layer] * vec4<f32>(p, 1.0);
    let ndc = clip.xyz / clip.w;
    return vec4<f32>(ndc.xy * vec2<f32>(0.5, -0.5) + 0.5, ndc.z, clip.w);
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
    let c = shadow_project(layer, q);
    if c.w <= 0.0 || any(abs(c.xy - 0.5) > vec2<f32>(0.5)) || c.z > 1.0 {
        return 1.0;
    }
    // Receiver-plane depth bias (Isidoro 2006): the receiver's depth gradient in shadow-map uv,
    // from two tangent directions of its plane, predicts its depth under every PCF tap, so the
    // bias follows the receiver's own slope instead of pushing occluders away (no leaks at
    // corners, no acne at grazing angles).
    var t1 = cross(n_geo, vec3<f32>(0.0, 1.0, 0.0));
    if dot(t1, t1) < 1.0e-4 {
        t1 = cross(n_geo, vec3<f32>(1.0, 0.0, 0.0));
    }
    t1 = normalize(t1);
    let t2 = cross(n_geo, t1);
    let a = shadow_project(layer, q + t1 * texel_world).xyz - c.xyz;
    let b = shadow_project(layer, q + t2 * texel_world).xyz - c.xyz;
    let det = a.x * b.y - b.x * a.y;
    var grad = vec2<f32>(0.0);
    if abs(det) > 1.0e-12 {
        grad = vec2<f32>(a.z * b.y - b.z * a.y, a.x * b.z - b.x * a.z) / det;
    }
    let texel = frame.shadow.z;
    // The 2x2 comparison reads texels up to one texel away from the tap centre.
    let slack = (abs(grad.x) + abs(grad.y)) * texel + 2.0e-6;
    let r = i32(frame.params.z);
    var sum = 0.0;
    for (var y = -r; y <= r; y = y + 1) {
        for (var x = -r; x <= r; x = x + 1) {
            let o = vec2<f32>(f32(x), f32(y)) * texel;
            let depth = c.z + dot(grad, o) - slack;
            sum = sum + textureSampleCompareLevel(shadow_maps, shadow_sampler, c.xy + o, layer, depth);
        }
    }
    let taps = f32((2 * r + 1) * (2 * r + 1));
    return sum / taps;
}

// Light i's shadowed irradiance (rgb) at p on the front of a surface with geometric normal n,
// and the cosine of its incidence there (w); zero where it adds nothing (one-sided: a light
// behind n, or no light).
fn shadowed_light(frame: Frame, i: u32, p: vec3<f32>, n: vec3<f32>) -> vec4<f32> {
    let light = lights[i];
    let inc = light_incident(light, p);
    let cos_s = dot(n, inc.dir);
    if cos_s <= 0.0 || all(inc.irradiance <= vec3<f32>(0.0)) {
        return vec4<f32>(0.0);
    }
    return vec4<f32>(inc.irradiance * cos_s * shadow_factor(frame, light, p, n, inc.distance), cos_s);
}

// The shadowed irradiance at p on the front of a surface with geometric normal n from every light
// of the frame: what a diffuse point there receives.
fn shadowed_irradiance(frame: Frame, p: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    var e = vec3<f32>(0.0);
    for (var i = 0u; i < frame.params.x; i = i + 1u) {
        e = e + shadowed_light(frame, i, p, n).rgb;
    }
    return e;
}
