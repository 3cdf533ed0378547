//! Octahedral unit-vector encoding (Cigolle et al., JCGT 2014) on the CPU, the twin of
//! `shaders/common/octahedral.wgsl`: for data the CPU packs for a shader (the ISM clusters'
//! planes) and for oracles that decode what a shader packed (the SSHGI pyramid's normals).

use glam::{Vec2, Vec3};

/// The two signed components in [-1, 1] of unit vector `n`.
pub fn oct_encode(n: Vec3) -> Vec2 {
    let p = Vec2::new(n.x, n.y) / (n.x.abs() + n.y.abs() + n.z.abs()).max(1e-30);
    if n.z >= 0.0 {
        p
    } else {
        let sign = |c: f32| if c >= 0.0 { 1.0 } else { -1.0 };
        Vec2::new((1.0 - p.y.abs()) * sign(p.x), (1.0 - p.x.abs()) * sign(p.y))
    }
}

/// The unit vector of encoded components `e` (zero only for a degenerate input).
pub fn oct_decode(e: [f32; 2]) -> Vec3 {
    let mut n = Vec3::new(e[0], e[1], 1.0 - e[0].abs() - e[1].abs());
    let t = (-n.z).clamp(0.0, 1.0);
    n.x += if n.x >= 0.0 { -t } else { t };
    n.y += if n.y >= 0.0 { -t } else { t };
    n.normalize_or_zero()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn encoding_round_trips_axes_and_lower_hemisphere_directions() {
        let dirs =
            [Vec3::X, Vec3::NEG_X, Vec3::Y, Vec3::NEG_Y, Vec3::Z, Vec3::NEG_Z, Vec3::new(0.3, -0.5, -0.8).normalize()];
        for d in dirs {
            let e = oct_encode(d);
            assert!(e.x.abs() <= 1.0 && e.y.abs() <= 1.0, "{d}: {e}");
            let back = oct_decode(e.to_array());
            assert!(back.distance(d) < 1e-6, "{d} -> {e} -> {back}");
        }
    }
}
