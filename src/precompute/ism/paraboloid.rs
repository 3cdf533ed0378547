//! The VPL frame and the paraboloid map (Brabec et al. 2002) shared by the ISM splat and the
//! lookup: one orthonormal basis function, so both sides agree (a VPL frame that differs between
//! the splat and the lookup turns the visibility into garbage).

use glam::{Vec2, Vec3};

/// The VPL's local frame: tangent, bitangent, normal (Duff et al. 2017), with the sign rule of
/// `onb_tangent` in `common/onb.wgsl` (n.z >= 0 counts as positive, so a normal whose z is -0.0,
/// as negated axis vectors have, gets the same frame on both sides; `f32::copysign`, which
/// `scene::basis` uses, would mirror it).
pub fn frame(n: Vec3) -> (Vec3, Vec3, Vec3) {
    let s = if n.z >= 0.0 { 1.0 } else { -1.0 };
    let a = -1.0 / (s + n.z);
    let b = n.x * n.y * a;
    (Vec3::new(1.0 + s * n.x * n.x * a, s * b, -s * n.x), Vec3::new(b, s + n.y * n.y * a, -n.y), n)
}

/// Paraboloid coordinates in [0, 1]^2 and distance of `p` seen from a VPL at `origin` with
/// normal `n`; `None` behind the VPL's surface (v_z <= 0).
pub fn project(origin: Vec3, n: Vec3, p: Vec3) -> Option<(Vec2, f32)> {
    let (t, b, n) = frame(n);
    let q = p - origin;
    let d = q.length();
    if d <= 0.0 {
        return None;
    }
    let v = Vec3::new(q.dot(t), q.dot(b), q.dot(n)) / d;
    if v.z <= 0.0 {
        return None;
    }
    let disk = Vec2::new(v.x, v.y) / (1.0 + v.z);
    Some((disk * 0.5 + Vec2::splat(0.5), d))
}

/// The unit direction (world space) of paraboloid coordinates `uv` for a VPL with normal `n`.
pub fn direction(n: Vec3, uv: Vec2) -> Option<Vec3> {
    let disk = uv * 2.0 - Vec2::ONE;
    let r2 = disk.length_squared();
    if r2 > 1.0 {
        return None;
    }
    // Inverse of disk = v.xy / (1 + v.z) on the unit hemisphere.
    let vz = (1.0 - r2) / (1.0 + r2);
    let vxy = disk * (1.0 + vz);
    let (t, b, n) = frame(n);
    Some((t * vxy.x + b * vxy.y + n * vz).normalize())
}

/// The atlas tile origin (in texels) of VPL `k` in a C x C grid of `r`-texel tiles.
pub fn tile_origin(k: usize, vpl_count: usize, r: usize) -> (usize, usize) {
    let c = (vpl_count as f64).sqrt().ceil() as usize;
    ((k % c.max(1)) * r, (k / c.max(1)) * r)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_negative_zero_z_gets_the_frame_of_positive_zero_as_on_the_gpu() {
        let n = -Vec3::new(-1.0, 0.0, 0.0);
        assert!(n.z.is_sign_negative(), "the case under test: z = -0.0");
        let (t, b, _) = frame(n);
        let (t0, b0, _) = frame(Vec3::new(1.0, 0.0, 0.0));
        assert_eq!((t, b), (t0, b0));
    }

    #[test]
    fn project_and_direction_round_trip() {
        let n = Vec3::new(0.3, 0.9, -0.2).normalize();
        let origin = Vec3::new(1.0, 2.0, 3.0);
        for dir in [n, (n + Vec3::X).normalize(), (n + Vec3::new(0.0, -0.3, 0.8)).normalize()] {
            if dir.dot(n) <= 0.0 {
                continue;
            }
            let (uv, d) = project(origin, n, origin + dir * 2.5).expect("in front");
            assert!((d - 2.5).abs() < 1e-5 && uv.cmpge(Vec2::ZERO).all() && uv.cmple(Vec2::ONE).all());
            let back = direction(n, uv).expect("inside the disk");
            assert!((back - dir).length() < 1e-4, "{back} vs {dir}");
        }
        assert!(project(origin, n, origin - n).is_none(), "behind the surface");
        assert_eq!(project(origin, n, origin + n).map(|(uv, _)| uv), Some(Vec2::splat(0.5)));
        assert_eq!(tile_origin(5, 16, 128), (128, 128));
    }
}
