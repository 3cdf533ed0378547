// The scene's surface voxels in the world (`precompute/surface_voxels.rs`, which this ports:
// `SurfaceVoxels::blocked`): visibility for the segments of sshgi's hidden senders that leave
// the view, where the view's voxel columns say nothing, and for those in view where its voxels
// are finer than the columns (`world_occluded` in `sshgi_panorama_common.wgsl`). Every voxel a
// triangle overlaps is set, so no wall leaks; a segment's ends are moved 1.5 voxels along their normals, out of their own
// surface's voxels, and the voxels within half a voxel of either end are left out. The including
// shader binds `world: array<u32>` (one bit per voxel, x fastest, then y, then z; from word
// `gp.world_dims.w` on one bit per brick of 4^3 voxels), `gp.world` = (origin xyz, voxel side)
// and `gp.world_dims` = (voxels along x, y, z, the bricks' first word; x = 0: no grid). The
// segment walks the bricks and goes down to the voxels only in bricks that hold a surface.

const WORLD_OFF_SURFACE: f32 = 1.5;
const WORLD_END_SKIP: f32 = 0.5;
// Voxels along a brick's side (`BRICK`).
const WORLD_BRICK: i32 = 4;

// Whether the grid is bound.
fn world_grid_on() -> bool {
    return gp.world_dims.x != 0u;
}

// The cells along x, y, z of the voxels (brick false) or the bricks (true).
fn world_cells(brick: bool) -> vec3<i32> {
    let dims = vec3<i32>(gp.world_dims.xyz);
    return select(dims, (dims + WORLD_BRICK - 1) / WORLD_BRICK, brick);
}

// Whether cell c of the voxels or the bricks holds a surface.
fn world_cell(c: vec3<i32>, brick: bool) -> bool {
    let n = world_cells(brick);
    if any(c < vec3<i32>(0)) || any(c >= n) {
        return false;
    }
    let i = select(0u, 32u * gp.world_dims.w, brick) + u32((c.z * n.y + c.y) * n.x + c.x);
    return ((world[i >> 5u] >> (i & 31u)) & 1u) == 1u;
}

fn world_inverse(x: f32) -> f32 {
    return select(1.0 / x, 3.0e38, x == 0.0);
}

// One Amanatides-Woo walk over the cells (voxels, or bricks) that p + t d (voxel units) touches
// for t in t0..t1, from the cell clamped to lo..hi. A walk over voxels returns whether a set
// voxel lies within near..far; a walk over bricks returns, per set brick within near..far, the
// voxel walk inside it.
struct WorldWalk {
    c: vec3<i32>,
    step: vec3<i32>,
    t_max: vec3<f32>,
    t_delta: vec3<f32>,
}

fn world_walk_start(p: vec3<f32>, d: vec3<f32>, t0: f32, size: f32, lo: vec3<i32>, hi: vec3<i32>) -> WorldWalk {
    let q = p / size;
    let e = d / size;
    let c = clamp(vec3<i32>(floor(q + e * t0)), lo, hi);
    let step = vec3<i32>(sign(e));
    let next_edge = vec3<f32>(c) + vec3<f32>(max(step, vec3<i32>(0)));
    let inv = vec3<f32>(world_inverse(e.x), world_inverse(e.y), world_inverse(e.z));
    let t_max = select((next_edge - q) * inv, vec3<f32>(3.0e38), step == vec3<i32>(0));
    return WorldWalk(c, step, t_max, abs(inv));
}

fn world_walk_next(w: ptr<function, WorldWalk>) {
    let m = (*w).t_max;
    if m.x <= m.y && m.x <= m.z {
        (*w).c.x = (*w).c.x + (*w).step.x;
        (*w).t_max.x = m.x + (*w).t_delta.x;
    } else if m.y <= m.z {
        (*w).c.y = (*w).c.y + (*w).step.y;
        (*w).t_max.y = m.y + (*w).t_delta.y;
    } else {
        (*w).c.z = (*w).c.z + (*w).step.z;
        (*w).t_max.z = m.z + (*w).t_delta.z;
    }
}

// The voxels of brick b that the segment touches for t in t0..t1: whether one within near..far
// is set.
fn world_voxels_in(p: vec3<f32>, d: vec3<f32>, t0: f32, t1: f32, b: vec3<i32>, near: f32, far: f32) -> bool {
    var w = world_walk_start(p, d, t0, 1.0, b * WORLD_BRICK, b * WORLD_BRICK + (WORLD_BRICK - 1));
    var t = t0;
    for (var i = 0; i < 3 * WORLD_BRICK + 3; i = i + 1) {
        let t_next = min(min(w.t_max.x, min(w.t_max.y, w.t_max.z)), t1);
        if t_next > near && t < far && world_cell(w.c, false) {
            return true;
        }
        if t_next >= t1 {
            return false;
        }
        world_walk_next(&w);
        t = t_next;
    }
    return false;
}

// Whether the segment between surface points a and b (normals na, nb facing it; zero for a point
// in the air) crosses a set voxel: the bricks it touches are walked, and in each set brick the
// voxels it touches there.
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
    let near = skip / len;
    let far = 1.0 - skip / len;
    let bricks = world_cells(true);
    var w = world_walk_start(p, d, t0, f32(WORLD_BRICK), vec3<i32>(0), bricks - 1);
    var t = t0;
    for (var i = 0; i < bricks.x + bricks.y + bricks.z + 3; i = i + 1) {
        let t_next = min(min(w.t_max.x, min(w.t_max.y, w.t_max.z)), t1);
        if t_next > near && t < far && world_cell(w.c, true) && world_voxels_in(p, d, t, t_next, w.c, near, far) {
            return true;
        }
        if t_next >= t1 {
            return false;
        }
        world_walk_next(&w);
        t = t_next;
    }
    return false;
}
