// What ISM's geometry-aware filters (`ism_filter.wgsl`, and `ism_upsample.wgsl` when gathering at
// half resolution) test each tap against: the pixel's world position (w = 1 where it sees
// geometry), its shading normal and its geometric normal. A tap is taken when it lies within
// `tolerance` metres of the pixel's tangent plane (along the geometric normal, so that walls seen
// at grazing angles keep their taps) and its shading normal is within a cosine `beta` of the
// pixel's. The including shader imports `common/frame.wgsl` and `common/octahedral.wgsl`.

struct FilterCentre {
    position: vec4<f32>,
    normal: vec3<f32>,
    geometric: vec3<f32>,
}

fn filter_centre(f: Frame, depth: texture_depth_2d, normals: texture_2d<f32>, pixel: vec2<u32>) -> FilterCentre {
    let enc = textureLoad(normals, pixel, 0);
    return FilterCentre(position_at(f, depth, pixel), oct_decode(enc.xy), oct_decode(enc.zw));
}

fn filter_accepts(c: FilterCentre, position: vec3<f32>, normal: vec3<f32>, tolerance: f32, beta: f32) -> bool {
    return abs(dot(position - c.position.xyz, c.geometric)) < tolerance && dot(normal, c.normal) > beta;
}
