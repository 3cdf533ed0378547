// The clip lines of the pool's points (`precompute/open_edges.rs`), shared by the splats and the
// lookups: CLIPS lines per point in the point's plane, xyz inward direction, w offset; a point h
// of that plane is on the point's surface when dot(xyz, h) >= w for all of them. The including
// shader binds `clips: array<vec4<f32>>`.

const CLIPS: u32 = 4u;

// Whether `h` (on pool point `i`'s plane) lies inside all of the point's open edges' clip lines,
// less `margin`; with `seams`, inside its seams' lines too (stored with xyz of length 2, see
// `SEAM_SCALE` in `open_edges.rs`: the splats never clip at a seam, where the surface runs on
// into solid geometry).
fn within_edges(i: u32, h: vec3<f32>, margin: f32, seams: bool) -> bool {
    for (var k = 0u; k < CLIPS; k = k + 1u) {
        let line = clips[i * CLIPS + k];
        if !seams && dot(line.xyz, line.xyz) > 2.0 {
            continue;
        }
        if dot(line.xyz, h) < line.w - margin {
            return false;
        }
    }
    return true;
}

fn on_surface(i: u32, h: vec3<f32>, margin: f32) -> bool {
    return within_edges(i, h, margin, false);
}
