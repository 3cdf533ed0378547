// The clip lines of the pool's points (`precompute/open_edges.rs`), shared by the splats and the
// lookups: CLIPS lines per point in the point's plane, xyz inward direction, w offset; a point h
// of that plane is on the point's surface when dot(xyz, h) >= w for all of them. The including
// shader binds `clips: array<vec4<f32>>`.

const CLIPS: u32 = 4u;
// `SEAM_SCALE` in `open_edges.rs`.
const SEAM_SCALE: f32 = 2.0;

// Whether `h` (on pool point `i`'s plane) lies inside all of the point's open edges' clip lines,
// less `margin`; past a seam (stored with xyz of length s = 2 + the seam's overhang in metres,
// see `SEAM_SCALE` in `open_edges.rs`) only beyond the overhang: where the surface runs on into
// solid geometry a disk may hang into that solid, no farther. With `seams`, inside the seams'
// own lines too.
fn within_edges(i: u32, h: vec3<f32>, margin: f32, seams: bool) -> bool {
    for (var k = 0u; k < CLIPS; k = k + 1u) {
        let line = clips[i * CLIPS + k];
        let s2 = dot(line.xyz, line.xyz);
        if !seams && s2 > 2.0 {
            let s = sqrt(s2);
            if dot(line.xyz, h) / s < line.w / s - (s - SEAM_SCALE) - margin {
                return false;
            }
        } else if dot(line.xyz, h) < line.w - margin {
            return false;
        }
    }
    return true;
}

fn on_surface(i: u32, h: vec3<f32>, margin: f32) -> bool {
    return within_edges(i, h, margin, false);
}
