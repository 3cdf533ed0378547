//! The power a VPL carries, which the thesis leaves out (Knecht 2009 §4.4 and Eq. 4.7-4.9 have no
//! 1/N, pdf or pi): a light-G-buffer texel t chosen with probability P(t) gets
//! Phi = rho_t * I_L(w_t) * dOmega_t * cos_t / (N * P(t)) * n^2, where I_L * dOmega * cos is the
//! light's power arriving on the texel's surface patch, rho_t the (blurred) albedo, N the VPL
//! count and n^2 the interleave factor (each pixel sees only N / n^2 VPLs). Summing the VPLs
//! then estimates the light reflected by the surfaces the light sees, without bias.

/// Power of one VPL (RGB watts) from its texel's reflected power `reflected` (rho x incident
/// power on the texel, watts), the texel's selection probability, the VPL count and the
/// interleave size.
pub fn vpl_power(reflected: [f32; 3], pdf: f64, vpl_count: usize, interleave: usize) -> [f32; 3] {
    if pdf <= 0.0 || vpl_count == 0 {
        return [0.0; 3];
    }
    let k = ((interleave * interleave) as f64 / (vpl_count as f64 * pdf)) as f32;
    reflected.map(|c| c * k)
}

/// Radiance a diffuse receiver sees from one VPL (no visibility): the VPL emits
/// Phi/pi * cos_s per steradian (a Lambertian patch), the receiver reflects rho/pi of the
/// irradiance; `d_min` clamps the distance (the thesis uses 1 world unit).
pub fn receiver_radiance(phi: f32, albedo: f32, cos_s: f32, cos_r: f32, d2: f32, d_min: f32) -> f32 {
    phi / std::f32::consts::PI * albedo / std::f32::consts::PI * cos_s.max(0.0) * cos_r.max(0.0) / d2.max(d_min * d_min)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::precompute::ism::halton::sample_set;
    use crate::precompute::ism::warp::ImportancePyramid;

    /// A point light above a floor: VPLs sampled by importance (any importance) carry, in sum,
    /// the floor's total reflected power, whatever the VPL count.
    #[test]
    fn vpl_powers_sum_to_the_reflected_power() {
        let (size, h, intensity, rho) = (32usize, 1.0f64, 5.0f64, 0.6f64);
        // The light looks straight down through a 90 degree frustum onto the floor [-1,1]^2.
        let texel_area = (2.0 / size as f64).powi(2);
        let reflected: Vec<f64> = (0..size * size)
            .map(|i| {
                let (x, z) = (
                    ((i % size) as f64 + 0.5) / size as f64 * 2.0 - 1.0,
                    ((i / size) as f64 + 0.5) / size as f64 * 2.0 - 1.0,
                );
                let d2 = x * x + z * z + h * h;
                let cos = h / d2.sqrt();
                rho * intensity * cos / d2 * texel_area
            })
            .collect();
        let exact: f64 = reflected.iter().sum();
        // Importance deliberately unlike the power (the thesis's (0.5 + SP) factors): unbiased anyway.
        let importance: Vec<f64> = (0..size * size).map(|i| 1.0 + (i % 7) as f64).collect();
        let pyr = ImportancePyramid::new(&importance, size).expect("pyramid");
        for n in [64usize, 256, 1024] {
            // Enough frames for 16k samples in all (the estimate is unbiased per frame).
            let frames = 16384 / n as u64;
            let mut sum = 0.0f64;
            for frame in 0..frames {
                for s in sample_set(n, frame) {
                    let w = pyr.warp([f64::from(s[0]), f64::from(s[1])]);
                    let r = reflected[w.texel[1] * size + w.texel[0]] as f32;
                    sum += f64::from(vpl_power([r; 3], w.pdf, n, 1)[0]);
                }
            }
            let estimate = sum / frames as f64;
            assert!((estimate / exact - 1.0).abs() < 0.02, "N={n}: {estimate} vs {exact}");
        }
        assert_eq!(vpl_power([1.0; 3], 0.0, 10, 4), [0.0; 3]);
        assert!((vpl_power([1.0; 3], 0.25, 4, 2)[0] - 4.0).abs() < 1e-6);
    }
}
