// DRT pass G1 (Loos 2015 §5.4.1): the light of every patch the delta
// operators read, the mean outgoing radiance of a side x side square of texels of one block face
// (l_d, direct plus the feedback's bounces) or one clutter face (its radiance this frame).
// `precompute::drt::operators` says why patches and not the dissertation's L_imp rows.

struct DrtParams {
    // patches, first row, end row, clutter texels.
    counts: vec4<u32>,
}

@group(0) @binding(0) var<uniform> dp: DrtParams;
// Per patch: first texel, buffer (0 block l_d, 1 clutter radiance), row stride, side.
@group(0) @binding(1) var<storage, read> patches: array<vec4<u32>>;
@group(0) @binding(2) var<storage, read> l_d: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> clutter_radiance: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read_write> patch_light: array<vec4<f32>>;

@compute @workgroup_size(64, 1, 1)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let k = id.x;
    if k >= dp.counts.x {
        return;
    }
    let rec = patches[k];
    var sum = vec3<f32>(0.0);
    for (var j = 0u; j < rec.w; j = j + 1u) {
        for (var i = 0u; i < rec.w; i = i + 1u) {
            let at = rec.x + j * rec.z + i;
            if rec.y == 0u {
                sum = sum + max(l_d[at].rgb, vec3<f32>(0.0));
            } else {
                sum = sum + max(clutter_radiance[at].rgb, vec3<f32>(0.0));
            }
        }
    }
    patch_light[k] = vec4<f32>(sum / f32(max(rec.w * rec.w, 1u)), 1.0);
}
