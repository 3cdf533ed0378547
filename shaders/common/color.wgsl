// Colour helpers: luminance, sRGB transfer, tonemapping operators (mirrors settings::Tonemap).
const TONEMAP_CLAMP: u32 = 0u;
const TONEMAP_REINHARD: u32 = 1u;
const TONEMAP_ACES: u32 = 2u;

fn luminance(c: vec3<f32>) -> f32 {
    return dot(c, vec3<f32>(0.2126, 0.7152, 0.0722));
}

fn srgb_from_linear(c: vec3<f32>) -> vec3<f32> {
    let x = clamp(c, vec3<f32>(0.0), vec3<f32>(1.0));
    let lo = x * 12.92;
    let hi = 1.055 * pow(x, vec3<f32>(1.0 / 2.4)) - 0.055;
    return select(hi, lo, x <= vec3<f32>(0.0031308));
}

fn tonemap(c: vec3<f32>, op: u32) -> vec3<f32> {
    if op == TONEMAP_REINHARD {
        let l = luminance(c);
        return c / (1.0 + l);
    }
    if op == TONEMAP_ACES {
        // Narkowicz 2015 fit of the ACES RRT+ODT.
        let a = 2.51;
        let b = 0.03;
        let cc = 2.43;
        let d = 0.59;
        let e = 0.14;
        return clamp((c * (a * c + b)) / (c * (cc * c + d) + e), vec3<f32>(0.0), vec3<f32>(1.0));
    }
    return clamp(c, vec3<f32>(0.0), vec3<f32>(1.0));
}
