// ISM pass P3: the importance sum pyramid. `seed` copies the importance channel of the light
// G-buffer into mip 0; `seed_viewed` does the same with the first set's view weight (below);
// `reduce` writes each coarser mip as the sum of 2x2 finer texels, so the top texel is the total
// and texel / total is the probability the warp assigns it.
//
// The view weight: a texel whose surface point the camera sees is drawn as if it were (1 + s)
// times brighter, s the `first_set_seen_weight` setting; the warp divides each VPL's power by
// its texel's probability, so the set's expected light is unchanged. Knecht 2009 (section 3.3)
// draws by power alone. Where most of a light's power lands where the camera cannot see it (a
// sun on a roof), or a sky takes most of the budget (its VPLs sit on the bounding sphere, never
// in view), the few VPLs on the lit surfaces in view then change in number from frame to
// frame; the weight puts more of them there, each carrying less
// (Segovia et al. 2006 place VPLs by what the camera sees for the same reason). A VPL off
// screen carries at most 1 + s times the power it would with the weight everywhere, so light
// that reaches the view only through the bounces is never carried by a few heavy VPLs.
#import common/frame.wgsl
#import render/gi/ism/ism_light_texel.wgsl

struct SeedParams {
    // tiles per row, tile side in texels, tile count, unused.
    tiles: vec4<u32>,
    // x = the seen weight s, unused x3.
    weight: vec4<f32>,
}

@group(0) @binding(0) var source: texture_2d<f32>;
@group(0) @binding(1) var dest: texture_storage_2d<r32float, write>;

@group(1) @binding(0) var<uniform> seed_params: SeedParams;
@group(1) @binding(1) var<uniform> frame: Frame;
@group(1) @binding(2) var view_depth: texture_depth_2d;
@group(1) @binding(3) var<storage, read> tile_records: array<TileRecord>;
@group(1) @binding(4) var light_depth: texture_depth_2d;
@group(1) @binding(5) var light_normal: texture_2d<f32>;
@group(1) @binding(6) var<storage, read> emitter_points: array<EmitterPoint>;

@compute @workgroup_size(8, 8, 1)
fn seed(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(dest);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    let v = textureLoad(source, id.xy, 0).a;
    textureStore(dest, id.xy, vec4<f32>(max(v, 0.0), 0.0, 0.0, 0.0));
}

// The surface point and front normal of a VPL drawn at atlas texel `cell`.
fn texel_surface(cell: vec2<u32>) -> array<vec3<f32>, 2> {
    let ts = seed_params.tiles.y;
    let record = tile_records[tile_of(cell, seed_params.tiles.xyz)];
    if is_emitter_tile(record) {
        let e = emitter_points[candidate_of(record, cell, ts, arrayLength(&emitter_points))];
        return array<vec3<f32>, 2>(e.position.xyz, e.normal.xyz);
    }
    let x = light_texel_position(record, cell, ts, textureLoad(light_depth, cell, 0));
    return array<vec3<f32>, 2>(x, textureLoad(light_normal, cell, 0).xyz);
}

// 1 where the camera sees the surface at x with normal n, else 0: its front faces the camera
// (the top of a roof or the outside of a wall, a slab's thickness behind the ceiling or the wall
// the camera sees, does not), and x's camera distance is within 2% + 5 cm of the farthest view
// surface among its pixel's 3x3 neighbourhood (a surface seen at a grazing angle spans more
// depth across one pixel than any fixed tolerance; a point behind a wall lies beyond all nine).
fn seen(x: vec3<f32>, n: vec3<f32>) -> f32 {
    if dot(n, frame.camera_position.xyz - x) <= 0.0 {
        return 0.0;
    }
    let at = pixel_of_world(frame, x);
    if at.z == 0u {
        return 0.0;
    }
    let size = vec2<i32>(frame.size.xy);
    let centre = vec2<i32>(at.xy);
    var farthest = 0.0;
    for (var k = 0; k < 9; k = k + 1) {
        let pixel = vec2<u32>(clamp(centre + vec2<i32>(k % 3 - 1, k / 3 - 1), vec2<i32>(0), size - 1));
        let y = position_at(frame, view_depth, pixel);
        if y.w > 0.0 {
            farthest = max(farthest, length(y.xyz - frame.camera_position.xyz));
        }
    }
    let dx = length(x - frame.camera_position.xyz);
    return select(0.0, 1.0, farthest > 0.0 && dx <= farthest * 1.02 + 0.05);
}

@compute @workgroup_size(8, 8, 1)
fn seed_viewed(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(dest);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    // Texels outside every tile are never drawn and hold 0, as `seed` relies on too.
    var v = max(textureLoad(source, id.xy, 0).a, 0.0);
    if v > 0.0 {
        let surface = texel_surface(id.xy);
        v = v * (1.0 + seed_params.weight.x * seen(surface[0], surface[1]));
    }
    textureStore(dest, id.xy, vec4<f32>(v, 0.0, 0.0, 0.0));
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
