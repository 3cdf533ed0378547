// ISM pass P3: the importance sum pyramid. `seed` copies the importance channel of the light
// G-buffer into mip 0; `reduce` writes each coarser mip as the sum of 2x2 finer texels, so the
// top texel is the total and texel / total is the probability the warp assigns it.
@group(0) @binding(0) var source: texture_2d<f32>;
@group(0) @binding(1) var dest: texture_storage_2d<r32float, write>;

@compute @workgroup_size(8, 8, 1)
fn seed(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(dest);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    let v = textureLoad(source, id.xy, 0).a;
    textureStore(dest, id.xy, vec4<f32>(max(v, 0.0), 0.0, 0.0, 0.0));
}

@compute @workgroup_size(8, 8, 1)
fn reduce(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(dest);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    let c = id.xy * 2u;
    let s = textureLoad(source, c, 0).r + textureLoad(source, c + vec2<u32>(1u, 0u), 0).r
        + textureLoad(source, c + vec2<u32>(0u, 1u), 0).r + textureLoad(source, c + vec2<u32>(1u, 1u), 0).r;
    textureStore(dest, id.xy, vec4<f32>(s, 0.0, 0.0, 0.0));
}
