// The scene's surface voxels in the world (`precompute/surface_voxels.rs`, which this ports:
// `SurfaceVoxels::blocked`): visibility for the segments of sshgi's hidden senders that leave
// the view, where the view's voxel columns say nothing. Every voxel a triangle overlaps is set,
// so no wall leaks; a segment's ends are moved 1.5 voxels along their normals, out of their own
// surface's voxels, and the voxels within half a voxel of either end are left out. The including
// shader binds `world: array<u32>` (one bit per voxel, x fastest, then y, then z),
// `gp.world` = (origin xyz, voxel side) and `gp.world_dims` = (voxels along x, y, z; on).

const WORLD_OFF_SURFACE: f32 = 1.5;
const WORLD_END_SKIP: f32 = 0.5;

// Whether the grid is bound (`gp.world_dims.w` = 1).
fn world_grid_on() -> bool {
    return gp.world_dims.w != 0u;
}

// Whether voxel c is set.
fn world_voxel(c: vec3<i32>) -> bool {
    let dims = vec3<i32>(gp.world_dims.xyz);
    if any(c < vec3<i32>(0)) || any(c >= dims) {
        return false;
    }
    let i = u32((c.z * dims.y + c.y) * dims.x + c.x);
    return ((world[i >> 5u] >> (i & 31u)) & 1u) == 1u;
}

fn world_inverse(x: f32) -> f32 {
    return select(1.0 / x, 3.0e38, x == 0.0);
}

// Whether the segment between surface points a and b (normals na, nb facing it; zero for a point
// in the air) crosses a set voxel: an Amanatides-Woo traversal of every voxel it touches.
fn world_blocked(a_surface: vec3<f32>, na: vec3<f32>, b_surface: vec3<f32>, nb: vec3<f32>) -> bool {
    let h = gp.world.w;
    let a = a_surface + na * (WORLD_OFF_SURFACE * h);
    let b = b_surface + nb * (WORLD_OFF_SURFACE * h);
    let len = length(b - a);
    let skip = WORLD_END_SKIP * h;
    if len <= 2.0 * skip {
        return false;
    }
    let p = (a - gp.world.xyz) / h;
    let d = (b - a) / h;
    let size = vec3<f32>(gp.world_dims.xyz);
    // The part of the segment inside the grid.
    var t0 = 0.0;
    var t1 = 1.0;
    for (var k = 0; k < 3; k = k + 1) {
        if d[k] == 0.0 {
            if p[k] < 0.0 || p[k] > size[k] {
                return false;
            }
            continue;
        }
        let ta = -p[k] / d[k];
        let tb = (size[k] - p[k]) / d[k];
        t0 = max(t0, min(ta, tb));
        t1 = min(t1, max(ta, tb));
    }
    if t0 > t1 {
        return false;
    }
    let dims = vec3<i32>(gp.world_dims.xyz);
    var c = clamp(vec3<i32>(floor(p + d * t0)), vec3<i32>(0), dims - 1);
    let step = vec3<i32>(sign(d));
    let next_edge = vec3<f32>(c) + vec3<f32>(max(step, vec3<i32>(0)));
    let inv = vec3<f32>(world_inverse(d.x), world_inverse(d.y), world_inverse(d.z));
    var t_max = select((next_edge - p) * inv, vec3<f32>(3.0e38), step == vec3<i32>(0));
    let t_delta = abs(inv);
    let near = skip / len;
    let far = 1.0 - skip / len;
    var t = t0;
    let limit = dims.x + dims.y + dims.z + 3;
    for (var i = 0; i < limit; i = i + 1) {
        let t_next = min(min(t_max.x, min(t_max.y, t_max.z)), t1);
        if t_next > near && t < far && world_voxel(c) {
            return true;
        }
        if t_next >= t1 {
            return false;
        }
        if t_max.x <= t_max.y && t_max.x <= t_max.z {
            c.x = c.x + step.x;
            t_max.x = t_max.x + t_delta.x;
        } else if t_max.y <= t_max.z {
            c.y = c.y + step.y;
            t_max.y = t_max.y + t_delta.y;
        } else {
            c.z = c.z + step.z;
            t_max.z = t_max.z + t_delta.z;
        }
        t = t_next;
    }
    return false;
}
