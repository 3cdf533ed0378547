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

// Whether a material has a glossy lobe.
fn has_lobe(specular: vec3<f32>) -> bool {
    return any(specular > vec3<f32>(0.0));
}

// The fit of the lobe's directional albedo (precompute::brdf::albedo_fit): its floor g at
// grazing light and the power p of cos_l above it, for roughness `roughness`.
fn albedo_fit(roughness: f32) -> vec2<f32> {
    let e = phong_exponent(roughness);
    return vec2<f32>(1.0 / (1.0 + e / 0.9), 2.0 * e / (e + 4.0));
}

// The lobe's directional albedo (precompute::brdf::specular_albedo): the share of the irradiance
// arriving at cos_l that the lobe reflects over the hemisphere, g + (1 - g) cos_l^p; within 0.08
// of the integral for roughness 0.2-1 (exponents up to 1248).
fn specular_albedo(specular: vec3<f32>, roughness: f32, cos_l: f32) -> vec3<f32> {
    let f = albedo_fit(roughness);
    return specular * (f.x + (1.0 - f.x) * pow(clamp(cos_l, 1.0e-6, 1.0), f.y));
}

// A surface's reflectance as a diffuse sender of light arriving at cos_l: albedo + the lobe's
// directional albedo there.
fn sender_reflectance_at(albedo: vec3<f32>, specular: vec3<f32>, roughness: f32, cos_l: f32) -> vec3<f32> {
    if !has_lobe(specular) {
        return albedo;
    }
    return albedo + specular_albedo(specular, roughness, cos_l);
}

// A surface's reflectance as a diffuse sender under uniform incident light: albedo + the lobe's
// mean directional albedo, g + (1 - g) 2 / (p + 2) (precompute::brdf::specular_albedo_diffuse).
fn sender_reflectance(albedo: vec3<f32>, specular: vec3<f32>, roughness: f32) -> vec3<f32> {
    if !has_lobe(specular) {
        return albedo;
    }
    let f = albedo_fit(roughness);
    return albedo + specular * (f.x + (1.0 - f.x) * 2.0 / (f.y + 2.0));
}
