//! The line-sample sets of volumetric obscurance (Loos 2015 §6.3.5, Fig. 6.6): n points
//! in the unit disk spread so that each point's Voronoi cell holds about the same share of the
//! sphere's chord length 2 sqrt(1 - x^2 - y^2), and each point's weight that share exactly (its
//! cell's integral, on a 256^2 grid). The dissertation relaxes points by electrostatic repulsion
//! with Voronoi-centroid forcing; here a density-weighted Lloyd relaxation (centroidal Voronoi
//! tessellation) from a sunflower start reaches the same fixed point (every point at its cell's
//! weighted centroid). Computed once when the pass is created (a few milliseconds).

/// Grid cells per side for the Voronoi integrals.
const GRID: usize = 256;
/// Relaxation steps.
const STEPS: usize = 60;

/// A sample set: (x, y, weight) per point, weights summing to 1. `centre`: the first point is
/// fixed at the disk's centre (the 5- and 9-point sets; 12 has none).
pub fn sample_set(n: usize, centre: bool) -> Vec<[f32; 3]> {
    let n = n.max(1);
    let free = n - usize::from(centre);
    let mut points: Vec<[f64; 2]> = Vec::with_capacity(n);
    if centre {
        points.push([0.0, 0.0]);
    }
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    for i in 0..free {
        let r = 0.85 * ((i as f64 + 0.5) / free as f64).sqrt();
        let a = i as f64 * golden;
        points.push([r * a.cos(), r * a.sin()]);
    }
    let cells: Vec<([f64; 2], f64)> = (0..GRID * GRID)
        .filter_map(|k| {
            let x = ((k % GRID) as f64 + 0.5) / GRID as f64 * 2.0 - 1.0;
            let y = ((k / GRID) as f64 + 0.5) / GRID as f64 * 2.0 - 1.0;
            let rr = x * x + y * y;
            (rr < 1.0).then(|| ([x, y], (1.0 - rr).sqrt()))
        })
        .collect();
    let nearest = |points: &[[f64; 2]], p: [f64; 2]| {
        let d = |q: &[f64; 2]| (q[0] - p[0]).powi(2) + (q[1] - p[1]).powi(2);
        (0..points.len()).min_by(|a, b| d(&points[*a]).total_cmp(&d(&points[*b]))).unwrap_or(0)
    };
    let mut mass = vec![0.0; n];
    for step in 0..=STEPS {
        let mut sum = vec![[0.0f64; 2]; n];
        mass = vec![0.0; n];
        for (p, rho) in &cells {
            let i = nearest(&points, *p);
            sum[i][0] += rho * p[0];
            sum[i][1] += rho * p[1];
            mass[i] += rho;
        }
        if step == STEPS {
            break;
        }
        for i in usize::from(centre)..n {
            if mass[i] > 0.0 {
                points[i] = [sum[i][0] / mass[i], sum[i][1] / mass[i]];
            }
        }
    }
    let total: f64 = mass.iter().sum();
    points.iter().zip(&mass).map(|(p, m)| [p[0] as f32, p[1] as f32, (m / total.max(1e-12)) as f32]).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sets_lie_in_the_disk_with_weights_summing_to_one_and_near_equal_cells() {
        for (n, centre) in [(5, true), (9, true), (12, false)] {
            let s = sample_set(n, centre);
            assert_eq!(s.len(), n);
            let total: f32 = s.iter().map(|p| p[2]).sum();
            assert!((total - 1.0).abs() < 1e-4, "{n}: weights sum to {total}");
            assert!(s.iter().all(|p| p[0] * p[0] + p[1] * p[1] < 1.0), "{n}: {s:?}");
            if centre {
                assert_eq!((s[0][0], s[0][1]), (0.0, 0.0));
            }
            // The relaxed cells hold similar shares of the chord integral (the low-noise goal).
            let (lo, hi) = s.iter().fold((f32::MAX, 0.0f32), |(a, b), p| (a.min(p[2]), b.max(p[2])));
            assert!(hi / lo < 2.0, "{n}: cell shares {lo:.3} .. {hi:.3}");
        }
    }
}
