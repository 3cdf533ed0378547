// The renderer's BRDF (mirrors scene::brdf on the CPU): Lambertian albedo/pi plus an optional
// energy-normalised Blinn-Phong lobe, specular * (e + 8) / (8 pi) * (n.h)^e with the exponent
// e = 2 / alpha^2 - 2 and alpha = roughness^2.
const PI: f32 = 3.14159265358979;

fn phong_exponent(roughness: f32) -> f32 {
    let a = max(roughness * roughness, 1.0e-3);
    return max(2.0 / (a * a) - 2.0, 0.0);
}

fn brdf_eval(albedo: vec3<f32>, specular: vec3<f32>, roughness: f32, n: vec3<f32>, v: vec3<f32>, l: vec3<f32>) -> vec3<f32> {
    var f = albedo / PI;
    if any(specular > vec3<f32>(0.0)) {
        let h = normalize(v + l);
        let e = phong_exponent(roughness);
        f = f + specular * (e + 8.0) / (8.0 * PI) * pow(max(dot(n, h), 0.0), e);
    }
    return f;
}

// The lobe's directional albedo (precompute::brdf::specular_albedo): the share of the irradiance
// arriving at cos_l that the lobe reflects over the hemisphere, fitted as g + (1 - g) cos_l^p
// with g = 1 / (1 + e / 0.9), p = 2e / (e + 4); within 0.08 of the integral for every exponent.
fn specular_albedo(specular: vec3<f32>, roughness: f32, cos_l: f32) -> vec3<f32> {
    let e = phong_exponent(roughness);
    let g = 1.0 / (1.0 + e / 0.9);
    return specular * (g + (1.0 - g) * pow(clamp(cos_l, 1.0e-6, 1.0), 2.0 * e / (e + 4.0)));
}

// Its mean under uniform incident radiance, g + (1 - g) 2 / (p + 2)
// (precompute::brdf::specular_albedo_diffuse): what the lobe reflects of diffuse light.
fn specular_albedo_diffuse(specular: vec3<f32>, roughness: f32) -> vec3<f32> {
    let e = phong_exponent(roughness);
    let g = 1.0 / (1.0 + e / 0.9);
    return specular * (g + (1.0 - g) * 2.0 / (2.0 * e / (e + 4.0) + 2.0));
}
