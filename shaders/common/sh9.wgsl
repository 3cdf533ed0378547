// Real spherical harmonics up to band 2 (9 coefficients; Ramamoorthi & Hanrahan 2001 order) and
// the zonal band factors of the radially symmetric lobes used to evaluate a projected BRDF
// from incident-radiance coefficients (Segovia & Wald, Sec. 3.3; Lambertian 3.3.1, Phong 3.3.2).

fn sh9_basis(d: vec3<f32>) -> array<f32, 9> {
    return array<f32, 9>(
        0.282095,
        0.488603 * d.y,
        0.488603 * d.z,
        0.488603 * d.x,
        1.092548 * d.x * d.y,
        1.092548 * d.y * d.z,
        0.315392 * (3.0 * d.z * d.z - 1.0),
        1.092548 * d.x * d.z,
        0.546274 * (d.x * d.x - d.y * d.y),
    );
}

// Band of coefficient i (0, 1, 1, 1, 2, 2, 2, 2, 2).
fn sh9_band(i: u32) -> u32 {
    return select(select(2u, 1u, i < 4u), 0u, i == 0u);
}

// Clamped-cosine (Lambertian) band factors divided by pi: 1, 2/3, 1/4.
const SH9_LAMBERT: vec3<f32> = vec3<f32>(1.0, 2.0 / 3.0, 0.25);

// Normalised Phong lobe (n + 1) / (2 pi) cos^n around its axis: 1, (n + 1) / (n + 2), n / (n + 3).
fn sh9_phong(n: f32) -> vec3<f32> {
    return vec3<f32>(1.0, (n + 1.0) / (n + 2.0), n / (n + 3.0));
}
