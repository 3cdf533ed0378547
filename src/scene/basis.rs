//! An orthonormal basis around a direction: geometry that the path tracer's BRDF sampling, the
//! gizmo's rings and the light overlays all need, so it sits in the scene layer that every
//! other layer may use.

use glam::Vec3;

/// Two unit tangents completing `n` (a unit vector) to a right-handed orthonormal basis,
/// continuous everywhere but at n.z = 0 crossings (Duff et al. 2017, "Building an Orthonormal
/// Basis, Revisited").
pub fn basis(n: Vec3) -> (Vec3, Vec3) {
    let sign = 1.0f32.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    (Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x), Vec3::new(b, sign + n.y * n.y * a, -n.y))
}

#[cfg(test)]
mod tests {
    use super::basis;
    use glam::Vec3;

    #[test]
    fn the_basis_is_orthonormal_for_every_octant_and_the_poles() {
        for n in [
            Vec3::X,
            Vec3::Y,
            Vec3::Z,
            -Vec3::Z,
            Vec3::new(1.0, -2.0, 0.5).normalize(),
            Vec3::new(-0.3, 0.2, -0.9).normalize(),
        ] {
            let (t, b) = basis(n);
            for (u, v) in [(t, b), (t, n), (b, n)] {
                assert!(u.dot(v).abs() < 1e-5, "{n}: {u} . {v}");
            }
            assert!((t.length() - 1.0).abs() < 1e-5 && (b.length() - 1.0).abs() < 1e-5, "{n}");
        }
    }
}
