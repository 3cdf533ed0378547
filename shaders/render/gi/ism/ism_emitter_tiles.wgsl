// ISM pass P2 for the emitter tiles of the light G-buffer atlas: texel i of a tile holds
// candidate VPL `first + i` on an emissive surface or on the sky's bounding sphere
// (`render::gi::ism::emitter_points`), written
// in the light G-buffer's own terms so the importance pyramid and the warp treat it like any
// lit texel: normal (front normal, w = the area it stands for) and power (pi L A in watts,
// a = importance); albedo and the glossy lobe stay zero (an emitter's VPL is Lambertian).
// The warp reads the candidate's position from the same buffer (`vpl_generate.wgsl`).

struct EmitterPoint {
    // xyz world position, w = the area it stands for (m^2).
    position: vec4<f32>,
    // xyz unit front normal, w unused.
    normal: vec4<f32>,
    // rgb power (W), a = importance.
    power: vec4<f32>,
}

struct EmitterTile {
    // x, y of the tile's top-left atlas texel, tile side in texels, first candidate.
    origin: vec4<u32>,
}

@group(0) @binding(0) var<uniform> tile: EmitterTile;
@group(1) @binding(0) var<storage, read> points: array<EmitterPoint>;

// One triangle over the viewport (the tile).
@vertex
fn vs_main(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let uv = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4<f32>(uv * 2.0 - 1.0, 1.0, 1.0);
}

struct TileOut {
    @location(0) albedo: vec4<f32>,
    @location(1) normal: vec4<f32>,
    @location(2) power: vec4<f32>,
    @location(3) specular: vec4<f32>,
}

@fragment
fn fs_main(@builtin(position) pos: vec4<f32>) -> TileOut {
    var out: TileOut;
    let local = vec2<u32>(pos.xy) - tile.origin.xy;
    let i = tile.origin.w + local.y * tile.origin.z + local.x;
    if i < arrayLength(&points) {
        let p = points[i];
        out.normal = vec4<f32>(p.normal.xyz, p.position.w);
        out.power = p.power;
    }
    return out;
}
