// The clip lines of the pool's points (`precompute/open_edges.rs`), shared by the splats and the
// lookups: CLIPS lines per point in the point's plane, xyz inward direction, w offset; a point h
// of that plane is on the point's surface when dot(xyz, h) >= w for all of them. The including
// shader binds `clips: array<vec4<f32>>`.

const CLIPS: u32 = 4u;

// Whether `h` (on pool point `i`'s plane) lies inside all of the point's clip lines, less `margin`.
fn on_surface(i: u32, h: vec3<f32>, margin: f32) -> bool {
    for (var k = 0u; k < CLIPS; k = k + 1u) {
        let line = clips[i * CLIPS + k];
        if dot(line.xyz, h) < line.w - margin {
            return false;
        }
    }
    return true;
}
