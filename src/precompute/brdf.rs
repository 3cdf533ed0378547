//! The BRDF shared with the rasteriser (`shaders/common/brdf.wgsl`): Lambertian albedo/pi plus an
//! optional energy-normalised Blinn-Phong lobe `specular * (e + 8) / (8 pi) * (n.h)^e` with
//! `e = 2 / alpha^2 - 2`, `alpha = roughness^2`; with importance sampling for the path tracer.

use std::f32::consts::PI;

use glam::Vec3;

/// Blinn-Phong exponent of a perceptual roughness (matches `phong_exponent` in WGSL).
pub fn phong_exponent(roughness: f32) -> f32 {
    let a = (roughness * roughness).max(1e-3);
    (2.0 / (a * a) - 2.0).max(0.0)
}

/// [`specular_albedo`]'s fit: its floor `g` at grazing light and the power `p` of `cos(theta_l)`
/// above it. A constant lobe (e = 0) reflects the same share at every angle (g = 1); a sharp one
/// tends to cos^2 (the half-vector's Jacobian and the outgoing cosine; g -> 0, p -> 2).
fn albedo_fit(exponent: f32) -> (f32, f32) {
    let e = exponent.max(0.0);
    (1.0 / (1.0 + e / 0.9), 2.0 * e / (e + 4.0))
}

/// The lobe's directional albedo: the share of the irradiance arriving at `cos_l` that the
/// Blinn-Phong lobe (without `specular`) reflects over the hemisphere, fitted as
/// `g + (1 - g) cos_l^p` ([`albedo_fit`]; matches `specular_albedo` in WGSL), within 0.08 of the
/// integral for roughness 0.2-1, exponents up to 1248 (`the_fitted_albedo_follows_the_lobes_integral`).
pub fn specular_albedo(exponent: f32, cos_l: f32) -> f32 {
    let (g, p) = albedo_fit(exponent);
    g + (1.0 - g) * cos_l.clamp(0.0, 1.0).powf(p)
}

/// [`specular_albedo`]'s mean under uniform incident radiance, `g + (1 - g) 2 / (p + 2)`: what
/// the lobe reflects of diffuse light, from 1 (e = 0) to 1/2 (sharp lobes).
pub fn specular_albedo_diffuse(exponent: f32) -> f32 {
    let (g, p) = albedo_fit(exponent);
    g + (1.0 - g) * 2.0 / (p + 2.0)
}

/// Surface parameters at a shading point.
#[derive(Clone, Copy, Debug)]
pub struct Surface {
    /// Lambertian albedo.
    pub albedo: Vec3,
    /// Specular colour (zero: purely diffuse).
    pub specular: Vec3,
    /// Blinn-Phong exponent.
    pub exponent: f32,
    /// Shading normal.
    pub n: Vec3,
}

impl Surface {
    /// BRDF value for view direction `v` and light direction `l` (both away from the surface).
    pub fn eval(&self, v: Vec3, l: Vec3) -> Vec3 {
        let mut f = self.albedo / PI;
        if self.specular.max_element() > 0.0 {
            let h = (v + l).normalize_or_zero();
            f += self.specular * (self.exponent + 8.0) / (8.0 * PI) * self.n.dot(h).max(0.0).powf(self.exponent);
        }
        f
    }

    fn spec_probability(&self) -> f32 {
        let (s, d) = (self.specular.max_element(), self.albedo.max_element());
        if s <= 0.0 { 0.0 } else { (s / (s + d)).clamp(0.1, 0.9) }
    }

    /// Density of [`Surface::sample`] choosing `l`.
    pub fn pdf(&self, v: Vec3, l: Vec3) -> f32 {
        let cos = self.n.dot(l);
        if cos <= 0.0 {
            return 0.0;
        }
        let ps = self.spec_probability();
        let mut pdf = (1.0 - ps) * cos / PI;
        if ps > 0.0 {
            let h = (v + l).normalize_or_zero();
            let nh = self.n.dot(h).max(0.0);
            let vh = v.dot(h).abs().max(1e-6);
            pdf += ps * (self.exponent + 1.0) / (2.0 * PI) * nh.powf(self.exponent) / (4.0 * vh);
        }
        pdf
    }

    /// Samples a light direction from the lobe mixture with two uniform numbers and a lobe choice
    /// number; returns `None` below the surface.
    pub fn sample(&self, v: Vec3, u: (f32, f32), choice: f32) -> Option<Vec3> {
        let (t, b) = basis(self.n);
        let l = if choice < self.spec_probability() {
            let cos_h = u.0.powf(1.0 / (self.exponent + 1.0));
            let sin_h = (1.0 - cos_h * cos_h).max(0.0).sqrt();
            let phi = 2.0 * PI * u.1;
            let h = t * (sin_h * phi.cos()) + b * (sin_h * phi.sin()) + self.n * cos_h;
            2.0 * v.dot(h) * h - v
        } else {
            let r = u.0.sqrt();
            let phi = 2.0 * PI * u.1;
            t * (r * phi.cos()) + b * (r * phi.sin()) + self.n * (1.0 - u.0).max(0.0).sqrt()
        };
        (self.n.dot(l) > 0.0).then(|| l.normalize())
    }
}

pub use crate::scene::basis::basis;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::precompute::rng::Pcg32;

    /// The lobe's directional albedo by quadrature over the outgoing hemisphere.
    fn lobe_albedo(exponent: f32, theta: f32) -> f32 {
        let s = Surface { albedo: Vec3::ZERO, specular: Vec3::ONE, exponent, n: Vec3::Z };
        let l = Vec3::new(theta.sin(), 0.0, theta.cos());
        let (rows, cols) = (300, 600);
        let (dt, dp) = (0.5 * PI / rows as f32, 2.0 * PI / cols as f32);
        let mut sum = 0.0f64;
        for i in 0..rows {
            let t = (i as f32 + 0.5) * dt;
            for j in 0..cols {
                let p = (j as f32 + 0.5) * dp;
                let o = Vec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos());
                sum += f64::from(s.eval(o, l).x * o.z * t.sin() * dt * dp);
            }
        }
        sum as f32
    }

    #[test]
    fn the_fitted_albedo_follows_the_lobes_integral() {
        for roughness in [1.0, 0.7, 0.5, 0.4, 0.3, 0.2] {
            let e = phong_exponent(roughness);
            let (mut mean_fit, mut mean_true) = (0.0, 0.0);
            let steps = 12;
            for k in 0..steps {
                let c = (k as f32 + 0.5) / steps as f32;
                let (fit, truth) = (specular_albedo(e, c), lobe_albedo(e, c.acos()));
                assert!((fit - truth).abs() < 0.08, "e {e} cos {c}: fit {fit} vs {truth}");
                mean_fit += 2.0 * fit * c / steps as f32;
                mean_true += 2.0 * truth * c / steps as f32;
            }
            let diffuse = specular_albedo_diffuse(e);
            assert!((diffuse - mean_fit).abs() < 0.01, "e {e}: closed form {diffuse} vs fit's mean {mean_fit}");
            assert!((diffuse - mean_true).abs() < 0.05, "e {e}: closed form {diffuse} vs integral's mean {mean_true}");
        }
    }

    /// Estimates the directional albedo with the sampler and checks it against a uniform
    /// hemisphere estimate: the sampler's weights f cos / pdf must be unbiased.
    #[test]
    fn sampling_is_unbiased() {
        let s = Surface { albedo: Vec3::splat(0.5), specular: Vec3::splat(0.3), exponent: 40.0, n: Vec3::Y };
        let v = Vec3::new(0.3, 0.8, 0.1).normalize();
        let mut rng = Pcg32::new(1, 2, 3);
        let n = 400_000;
        let (mut importance, mut uniform) = (0.0f64, 0.0f64);
        for _ in 0..n {
            if let Some(l) = s.sample(v, (rng.next_f32(), rng.next_f32()), rng.next_f32()) {
                importance += f64::from((s.eval(v, l) * s.n.dot(l)).x / s.pdf(v, l));
            }
            let (z, phi) = (rng.next_f32(), 2.0 * PI * rng.next_f32());
            let r = (1.0 - z * z).max(0.0).sqrt();
            let l = Vec3::new(r * phi.cos(), z, r * phi.sin());
            uniform += f64::from((s.eval(v, l) * z).x * 2.0 * PI);
        }
        let (a, b) = (importance / n as f64, uniform / n as f64);
        assert!((a - b).abs() < 0.01 * b, "importance {a} vs uniform {b}");
    }
}
