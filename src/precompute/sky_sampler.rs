//! Importance sampling of an equirectangular sky image for the reference path tracer: a
//! piecewise-constant distribution over the texels, each weighted by its luminance times the
//! solid angle its row covers (Pharr, Jakob & Humphreys, PBRT 3rd ed., 13.6.7 and 14.2.4), so
//! that a bright sun of a few texels is found by next-event estimation instead of by chance.

use std::f32::consts::PI;

use glam::Vec3;

use crate::scene::{Environment, SkyImage, equirect_direction, equirect_uv};

/// The sampling tables of one sky image.
pub struct SkyDistribution {
    width: u32,
    height: u32,
    /// Per row: the cumulative weights of its columns (last = the row's sum), row-major.
    columns: Vec<f32>,
    /// The cumulative row sums (last = the total).
    rows: Vec<f32>,
}

/// Rec. 709 luminance ([`crate::metrics::luminance`]) of an RGB radiance.
pub fn luminance(c: Vec3) -> f32 {
    crate::metrics::luminance(&c.extend(1.0).to_array())
}

/// The index of the first entry of the ascending `cdf` above `x` (clamped to the last).
fn find(cdf: &[f32], x: f32) -> usize {
    cdf.partition_point(|c| *c <= x).min(cdf.len() - 1)
}

impl SkyDistribution {
    /// The tables of `img`, or `None` if it is black.
    pub fn new(img: &SkyImage) -> Option<Self> {
        let (w, h) = (img.width, img.height);
        let mut columns = Vec::with_capacity((w * h) as usize);
        let mut rows = Vec::with_capacity(h as usize);
        let mut total = 0.0f64;
        for y in 0..h {
            let sin = (PI * (y as f32 + 0.5) / h as f32).sin();
            let mut row = 0.0f32;
            for x in 0..w {
                row += luminance(img.texel(x, y)).max(0.0) * sin;
                columns.push(row);
            }
            total += f64::from(row);
            rows.push(total as f32);
        }
        (total > 0.0).then_some(Self { width: w, height: h, columns, rows })
    }

    fn weight(&self, x: u32, y: u32) -> f32 {
        let row = &self.columns[(y * self.width) as usize..((y + 1) * self.width) as usize];
        row[x as usize] - if x == 0 { 0.0 } else { row[x as usize - 1] }
    }

    /// A direction in the sky's own frame (rotate with [`Environment::to_world`]) and its density
    /// per steradian, from two uniform numbers.
    pub fn sample(&self, u: (f32, f32)) -> (Vec3, f32) {
        let total = *self.rows.last().unwrap_or(&1.0);
        let y = find(&self.rows, u.0 * total) as u32;
        let row = &self.columns[(y * self.width) as usize..((y + 1) * self.width) as usize];
        let row_sum = row[row.len() - 1];
        let x = find(row, u.1 * row_sum) as u32;
        // Jitter within the texel with the leftover of the numbers (stratified enough for a
        // reference that averages thousands of samples).
        let below_y = if y == 0 { 0.0 } else { self.rows[y as usize - 1] };
        let fy = ((u.0 * total - below_y) / (self.rows[y as usize] - below_y).max(1e-30)).clamp(0.0, 0.999_999);
        let below_x = if x == 0 { 0.0 } else { row[x as usize - 1] };
        let fx = ((u.1 * row_sum - below_x) / (row[x as usize] - below_x).max(1e-30)).clamp(0.0, 0.999_999);
        let uv = ((x as f32 + fx) / self.width as f32, (y as f32 + fy) / self.height as f32);
        let d = equirect_direction(uv.0, uv.1);
        (d, self.pdf_texel(x, y, uv.1))
    }

    /// The density per steradian of [`Self::sample`] choosing sky-frame direction `d`.
    pub fn pdf(&self, d: Vec3) -> f32 {
        let (u, v) = equirect_uv(d);
        let x = ((u * self.width as f32) as u32).min(self.width - 1);
        let y = ((v * self.height as f32) as u32).min(self.height - 1);
        self.pdf_texel(x, y, v)
    }

    /// Density per steradian at latitude `v` in texel (x, y): the texel's probability over its
    /// (u, v) area, over the Jacobian 2π² sin θ of the equirectangular map.
    fn pdf_texel(&self, x: u32, y: u32, v: f32) -> f32 {
        let total = *self.rows.last().unwrap_or(&1.0);
        let p = self.weight(x, y) / total;
        let sin = (PI * v).sin();
        if sin <= 1e-6 {
            return 0.0;
        }
        p * (self.width * self.height) as f32 / (2.0 * PI * PI * sin)
    }
}

/// What next-event estimation samples of an environment: an image's (or the baked analytic
/// sky's) texels by luminance, or
/// nothing for a constant sky (the BRDF's own sampling is already proportional to what a
/// constant sky gives, and MIS then gives it the whole weight).
pub fn sky_distribution(env: &Environment, image: Option<&SkyImage>) -> Option<SkyDistribution> {
    match (&env.sky, image) {
        (crate::scene::Sky::Image(_) | crate::scene::Sky::Preetham { .. }, Some(img)) if env.intensity > 0.0 => {
            SkyDistribution::new(img)
        }
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::precompute::rng::Pcg32;

    /// A sky with one bright texel and a dim rest: the sampler's estimate of the irradiance on an
    /// upward surface (E = ∫ L cos) matches the exact sum over the texels, and most samples land
    /// on the bright texel.
    #[test]
    fn importance_sampling_is_unbiased_and_finds_the_sun() {
        let (w, h) = (32u32, 16u32);
        let mut texels = vec![[0.2, 0.3, 0.5]; (w * h) as usize];
        texels[(4 * w + 9) as usize] = [500.0, 450.0, 400.0];
        let img = SkyImage { width: w, height: h, texels };
        let dist = SkyDistribution::new(&img).expect("not black");
        let radiance = |d: Vec3| {
            let (x, y) = img.texel_of(d);
            luminance(img.texel(x, y))
        };
        // Exact: each upper texel gives L dφ (sin² θ1 - sin² θ0) / 2.
        let mut exact = 0.0f64;
        for y in 0..h / 2 {
            let (t0, t1) = (PI * y as f32 / h as f32, PI * (y + 1) as f32 / h as f32);
            let band = f64::from(2.0 * PI / w as f32 * (t1.sin().powi(2) - t0.sin().powi(2)) / 2.0);
            exact += (0..w).map(|x| f64::from(luminance(img.texel(x, y))) * band).sum::<f64>();
        }
        let mut rng = Pcg32::new(7, 1, 2);
        let n = 100_000;
        let (mut importance, mut on_sun) = (0.0f64, 0);
        for _ in 0..n {
            let (d, pdf) = dist.sample((rng.next_f32(), rng.next_f32()));
            // Equal but where rounding moves a point on a texel's edge into its neighbour.
            assert!((pdf - dist.pdf(d)).abs() <= 0.02 * pdf.max(1.0), "{pdf} vs {}", dist.pdf(d));
            if img.texel_of(d) == (9, 4) {
                on_sun += 1;
            }
            importance += f64::from(radiance(d) * d.y.max(0.0) / pdf);
        }
        let a = importance / f64::from(n);
        assert!((a - exact).abs() < 0.01 * exact, "importance {a} vs exact {exact}");
        assert!(on_sun > n / 2, "{on_sun} of {n} samples on the sun");
    }
}
