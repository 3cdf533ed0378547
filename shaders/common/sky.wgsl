// The environment's radiance (mirrors crate::scene::Environment::radiance and render::sky):
// a constant colour, or an equirectangular image read at the nearest texel. The importing
// shader declares `sky_tex: texture_2d<f32>` and `sky: SkyParams` before importing this file.

const SKY_PI: f32 = 3.14159265358979;

// The sky's radiance along world direction `d` (crate::scene::Environment::radiance).
fn sky_radiance(d: vec3<f32>) -> vec3<f32> {
    if sky.kind.x == 1u {
        return sky.radiance.rgb;
    }
    if sky.kind.x != 2u {
        return vec3<f32>(0.0);
    }
    let c = sky.rotation.x;
    let s = sky.rotation.y;
    let q = vec3<f32>(d.x * c - d.z * s, d.y, d.x * s + d.z * c);
    var u = atan2(q.z, q.x) / (2.0 * SKY_PI);
    if u < 0.0 {
        u = u + 1.0;
    }
    let v = atan2(length(q.xz), q.y) / SKY_PI;
    let x = min(u32(u * f32(sky.kind.y)), sky.kind.y - 1u);
    let y = min(u32(v * f32(sky.kind.z)), sky.kind.z - 1u);
    return textureLoad(sky_tex, vec2<u32>(x, y), 0).rgb * sky.radiance.a;
}
