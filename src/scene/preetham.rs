//! The analytic clear sky of Preetham, Shirley and Smits, "A Practical Analytic Model for
//! Daylight" (SIGGRAPH 1999): the Perez et al. distribution of luminance and chromaticity over
//! the sky, driven by the sun's direction and the atmosphere's turbidity (2: very clear, 3: clear,
//! 6: hazy, 10: thin overcast), with the paper's zenith formulas (its appendix A.2).
//!
//! The model gives luminance in kcd/m²; the scene model's radiance is radiometric, so it is
//! divided by 683 lm/W like every photometric value ([`super::LUMENS_PER_WATT`]): a clear sky's
//! zenith (turbidity 3, the sun 45 degrees up: 7.3 kcd/m², measured by this file's test) has a
//! luminance of 10.7 W/(sr m²). Chromaticity (x, y) with Y gives CIE XYZ,
//! then linear sRGB. The model covers the sky above the horizon only; below it the sky is black
//! (the ground of a level is geometry). The sun's disc is not part of it: the sun is the scene's
//! directional light.

use std::f32::consts::PI;

use glam::Vec3;

use super::{SkyImage, equirect_direction};

/// The turbidities the model was fitted for.
pub const TURBIDITY_RANGE: (f32, f32) = (1.7, 10.0);

/// Perez et al.'s distribution: (1 + A e^(B / cos θ)) (1 + C e^(D γ) + E cos² γ).
fn perez(c: [f32; 5], cos_theta: f32, gamma: f32, cos_gamma: f32) -> f32 {
    (1.0 + c[0] * (c[1] / cos_theta.max(0.01)).exp())
        * (1.0 + c[2] * (c[3] * gamma).exp() + c[4] * cos_gamma * cos_gamma)
}

/// The sky of one sun direction and turbidity, ready to evaluate.
pub struct Preetham {
    sun: Vec3,
    coefficients: [[f32; 5]; 3],
    /// Zenith Y (kcd/m²), x, y, each divided by its distribution at the zenith.
    zenith: [f32; 3],
}

impl Preetham {
    /// The sky for unit direction `sun` (towards the sun) and `turbidity`.
    pub fn new(sun: Vec3, turbidity: f32) -> Self {
        let t = turbidity.clamp(TURBIDITY_RANGE.0, TURBIDITY_RANGE.1);
        let sun = sun.normalize_or(Vec3::Y);
        // The zenith angle of a sun below the horizon is held at the horizon.
        let theta_s = sun.y.clamp(0.0, 1.0).acos();
        let coefficients = [
            [
                0.1787 * t - 1.4630,
                -0.3554 * t + 0.4275,
                -0.0227 * t + 5.3251,
                0.1206 * t - 2.5771,
                -0.0670 * t + 0.3703,
            ],
            [
                -0.0193 * t - 0.2592,
                -0.0665 * t + 0.0008,
                -0.0004 * t + 0.2125,
                -0.0641 * t - 0.8989,
                -0.0033 * t + 0.0452,
            ],
            [
                -0.0167 * t - 0.2608,
                -0.0950 * t + 0.0092,
                -0.0079 * t + 0.2102,
                -0.0441 * t - 1.6537,
                -0.0109 * t + 0.0529,
            ],
        ];
        let chi = (4.0 / 9.0 - t / 120.0) * (PI - 2.0 * theta_s);
        let y_zenith = ((4.0453 * t - 4.9710) * chi.tan() - 0.2155 * t + 2.4192).max(0.0);
        let th = [theta_s.powi(3), theta_s.powi(2), theta_s, 1.0];
        let poly = |m: [[f32; 4]; 3]| {
            let row = |r: [f32; 4]| r.iter().zip(th).map(|(a, b)| a * b).sum::<f32>();
            t * t * row(m[0]) + t * row(m[1]) + row(m[2])
        };
        let x_zenith = poly([
            [0.00166, -0.00375, 0.00209, 0.0],
            [-0.02903, 0.06377, -0.03202, 0.00394],
            [0.11693, -0.21196, 0.06052, 0.25886],
        ]);
        let yc_zenith = poly([
            [0.00275, -0.00610, 0.00317, 0.0],
            [-0.04214, 0.08970, -0.04153, 0.00516],
            [0.15346, -0.26756, 0.06670, 0.26688],
        ]);
        let at_zenith = |c: [f32; 5]| perez(c, 1.0, theta_s, theta_s.cos());
        let zenith = [
            y_zenith / at_zenith(coefficients[0]),
            x_zenith / at_zenith(coefficients[1]),
            yc_zenith / at_zenith(coefficients[2]),
        ];
        Self { sun, coefficients, zenith }
    }

    /// The radiance (linear sRGB, W/(sr m²)) arriving from unit direction `d`.
    pub fn radiance(&self, d: Vec3) -> Vec3 {
        if d.y <= 0.0 {
            return Vec3::ZERO;
        }
        let cos_gamma = d.dot(self.sun).clamp(-1.0, 1.0);
        let gamma = cos_gamma.acos();
        let f = |i: usize| self.zenith[i] * perez(self.coefficients[i], d.y, gamma, cos_gamma);
        let (luminance, x, y) = (f(0) * 1000.0, f(1), f(2));
        if y <= 1e-4 || luminance <= 0.0 {
            return Vec3::ZERO;
        }
        let xyz = Vec3::new(x * luminance / y, luminance, (1.0 - x - y) * luminance / y);
        let rgb = Vec3::new(
            3.2406 * xyz.x - 1.5372 * xyz.y - 0.4986 * xyz.z,
            -0.9689 * xyz.x + 1.8758 * xyz.y + 0.0415 * xyz.z,
            0.0557 * xyz.x - 0.2040 * xyz.y + 1.0570 * xyz.z,
        );
        rgb.max(Vec3::ZERO) / super::LUMENS_PER_WATT
    }

    /// The sky as an equirectangular image of `width` x `height` texels (each its centre's
    /// radiance), in the sky's own frame.
    pub fn image(&self, width: u32, height: u32) -> SkyImage {
        let texels = (0..width * height)
            .map(|i| {
                let (x, y) = (i % width, i / width);
                let d = equirect_direction((x as f32 + 0.5) / width as f32, (y as f32 + 0.5) / height as f32);
                self.radiance(d).to_array()
            })
            .collect();
        SkyImage { width, height, texels }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The paper's clear sky (turbidity 3, sun 45 degrees up): a zenith of a few kcd/m², blue
    /// (more blue than red), brighter towards the sun than away from it at the same elevation,
    /// and black below the horizon.
    #[test]
    fn a_clear_sky_is_blue_brightest_around_the_sun_and_black_below_the_horizon() {
        let sun = Vec3::new(0.0, 1.0, 1.0).normalize();
        let sky = Preetham::new(sun, 3.0);
        let zenith = sky.radiance(Vec3::Y);
        // Rec. 709 luminance (the scene layer does not import metrics).
        let kcd = zenith.dot(Vec3::new(0.2126, 0.7152, 0.0722)) * super::super::LUMENS_PER_WATT / 1000.0;
        eprintln!("turbidity 3, sun 45 degrees up: zenith {kcd:.2} kcd/m², {zenith} W/(sr m²)");
        assert!((1.0..12.0).contains(&kcd), "zenith {kcd} kcd/m²");
        assert!(zenith.z > zenith.x, "blue: {zenith}");
        let toward = sky.radiance(Vec3::new(0.0, 0.3, 1.0).normalize());
        let away = sky.radiance(Vec3::new(0.0, 0.3, -1.0).normalize());
        assert!(toward.y > 1.5 * away.y, "{toward} vs {away}");
        assert_eq!(sky.radiance(Vec3::new(0.2, -0.1, 0.5).normalize()), Vec3::ZERO);
        assert!(sky.image(32, 16).texels.iter().flatten().all(|v| v.is_finite() && *v >= 0.0));
    }
}
