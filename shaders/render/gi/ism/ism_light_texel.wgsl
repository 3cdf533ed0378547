// What a texel of the light G-buffer atlas stands for, shared by the VPL warp
// (`vpl_generate.wgsl`) and the first set's view weights (`importance.wgsl`): the tile it lies
// in, and the surface point a light tile's texel sees or the emitter candidate an emitter
// tile's texel holds.

// One light-G-buffer tile (a spot light's frustum, a cube face, a sun's orthographic view, or
// candidates on the emissive surfaces).
struct TileRecord {
    world_from_clip: mat4x4<f32>,
    // xyz light position (w = 0), the unit direction towards a directional light (w = 1), or
    // x = the first emitter candidate of an emitter tile (w = 2).
    light: vec4<f32>,
}

// A candidate VPL on an emissive surface or the sky (`ism_emitter_tiles.wgsl`).
struct EmitterPoint {
    // xyz world position, w = the area it stands for (m^2).
    position: vec4<f32>,
    // xyz unit front normal, w unused.
    normal: vec4<f32>,
    // rgb power pi L A (W), a = importance.
    power: vec4<f32>,
}

// The tile of atlas texel `cell` for `tiles` = (tiles per row, tile side, tile count), clamped
// to the last tile.
fn tile_of(cell: vec2<u32>, tiles: vec3<u32>) -> u32 {
    let ts = tiles.y;
    return min((cell.y / ts) * tiles.x + cell.x / ts, tiles.z - 1u);
}

// Whether `record` is an emitter tile.
fn is_emitter_tile(record: TileRecord) -> bool {
    return record.light.w > 1.5;
}

// The index of the emitter candidate that texel `cell` of emitter tile `record` holds (tile
// side `ts`), clamped to the `count` candidates.
fn candidate_of(record: TileRecord, cell: vec2<u32>, ts: u32, count: u32) -> u32 {
    let local = cell % vec2<u32>(ts);
    return min(u32(record.light.x) + local.y * ts + local.x, max(count, 1u) - 1u);
}

// The world position that texel `cell` of light tile `record` (side `ts`) sees at light depth
// `depth`.
fn light_texel_position(record: TileRecord, cell: vec2<u32>, ts: u32, depth: f32) -> vec3<f32> {
    let uv = (vec2<f32>(cell % vec2<u32>(ts)) + 0.5) / f32(ts);
    let ndc = vec4<f32>(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0, depth, 1.0);
    let h = record.world_from_clip * ndc;
    return h.xyz / h.w;
}
