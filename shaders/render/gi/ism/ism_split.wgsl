// ISM pass P9 (Knecht 2009 section 3.4.1, Fig. 3.2): rearrange the G-buffer into the split
// layout of common/interleave.wgsl, an n x n mosaic of 1/n-resolution copies of the view. The
// position is stored in world space (reconstructed once here instead of per VPL), w = 1 where
// the pixel sees geometry; the normals keep the G-buffer's octahedral encoding. With a gathering
// step s = 2 (`IsmSettings::shade_resolution`) the mosaic is of the view's every second pixel
// along each axis (pixel s q for sample q), a quarter of the texels for `ism shade`.
#import common/frame.wgsl
#import common/interleave.wgsl

struct SplitParams {
    // interleave n, gathering step s (1 or 2), unused x2.
    counts: vec4<u32>,
}

@group(0) @binding(0) var<uniform> frame: Frame;
@group(0) @binding(1) var<uniform> sp: SplitParams;
@group(0) @binding(2) var depth_tex: texture_depth_2d;
@group(0) @binding(3) var normal_tex: texture_2d<f32>;
@group(0) @binding(4) var out_position: texture_storage_2d<rgba32float, write>;
@group(0) @binding(5) var out_normal: texture_storage_2d<rgba16float, write>;

@compute @workgroup_size(8, 8, 1)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let view = vec2<u32>(frame.size.xy);
    let n = sp.counts.x;
    let step = max(sp.counts.y, 1u);
    let size = (view + vec2<u32>(step - 1u)) / step;
    if any(id.xy >= split_block(size, n) * n) {
        return;
    }
    let sample = split_pixel(id.xy, size, n).xy;
    let pixel = sample * step;
    var position = vec4<f32>(0.0);
    var normal = vec4<f32>(0.0);
    if all(sample < size) {
        let depth = textureLoad(depth_tex, pixel, 0);
        if depth > 0.0 {
            position = vec4<f32>(world_from_pixel(frame, pixel, depth), 1.0);
            normal = textureLoad(normal_tex, pixel, 0);
        }
    }
    textureStore(out_position, id.xy, position);
    textureStore(out_normal, id.xy, normal);
}
