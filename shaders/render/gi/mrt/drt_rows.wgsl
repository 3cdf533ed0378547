// DRT pass G2 (Loos 2015 §5.3.1-§5.3.3, §5.4.1-§5.4.2): the delta operators' sparse rows.
// A delta row adds to a block texel's indirect light (E / pi) the light of the clutter its rays
// meet (ΔU_c c, weights > 0) less the light the clutter hides (ΔU_b, weights < 0); a gather row
// writes a clutter texel's indirect light (C_b) from the patches its rays reach; an inpainting
// row (the second dispatch, after the deltas) replaces a texel that clutter covers with the mean
// of its valid neighbours. Rows `counts.y .. counts.z`; one thread per row.

struct DrtParams {
    // patches, first row, end row, clutter texels.
    counts: vec4<u32>,
}

@group(0) @binding(0) var<uniform> dp: DrtParams;
// Per row: target texel, first entry, entry count, kind (0 delta, 1 inpaint, 2 gather).
@group(0) @binding(1) var<storage, read> rows: array<vec4<u32>>;
// Per entry: source (patch; block texel for inpainting), weight's bits.
@group(0) @binding(2) var<storage, read> entries: array<vec2<u32>>;
@group(0) @binding(3) var<storage, read> patch_light: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read_write> indirect: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read_write> clutter_gather: array<vec4<f32>>;
// The inspector's split of a delta row: the light the clutter hides (ΔU_b b, as a positive
// amount; the scene patches' weights are the negative ones) and the light it adds (ΔU_c c).
@group(0) @binding(6) var<storage, read_write> occlusion: array<vec4<f32>>;
@group(0) @binding(7) var<storage, read_write> reflection: array<vec4<f32>>;

@compute @workgroup_size(64, 1, 1)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let r = dp.counts.y + id.x;
    if r >= dp.counts.z {
        return;
    }
    let row = rows[r];
    var sum = vec3<f32>(0.0);
    var hidden = vec3<f32>(0.0);
    for (var e = row.y; e < row.y + row.z; e = e + 1u) {
        let entry = entries[e];
        let w = bitcast<f32>(entry.y);
        if row.w == 1u {
            sum = sum + w * indirect[entry.x].rgb;
        } else {
            let v = w * patch_light[entry.x].rgb;
            sum = sum + v;
            if w < 0.0 {
                hidden = hidden - v;
            }
        }
    }
    if row.w == 0u {
        indirect[row.x] = vec4<f32>(indirect[row.x].rgb + sum, 1.0);
        occlusion[row.x] = vec4<f32>(hidden, 1.0);
        reflection[row.x] = vec4<f32>(sum + hidden, 1.0);
    } else if row.w == 1u {
        indirect[row.x] = vec4<f32>(sum, 1.0);
    } else {
        clutter_gather[row.x] = vec4<f32>(max(sum, vec3<f32>(0.0)), 1.0);
    }
}
