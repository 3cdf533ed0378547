// MRT's runtime records (mirrors render::gi::mrt::pack): per texel its real surface, per block
// its box, its faces' texel ranges and the interfaces entering it, and the frame's parameters.

const MRT_NONE: u32 = 0xffffffffu;
const MRT_PI: f32 = 3.14159265358979;

struct Texel {
    // World position, w = 1 where a real surface was found.
    position: vec4<f32>,
    // Unit normal facing into the block, w = block index.
    normal: vec4<f32>,
    // Albedo, w unused.
    albedo: vec4<f32>,
    // Radiance the texel sends on its own: an emissive front face's, or the sky through a hole
    // in the face; w unused.
    emission: vec4<f32>,
}

struct Block {
    // Minimum corner, w = quarter turns about up.
    origin: vec4<f32>,
    size: vec4<f32>,
    // First texel, texel count n, T_{d->b} offset (k_b x n), U_b offset (n x k_b).
    texels: vec4<u32>,
    // Per canonical face (-x +x -y +y -z +z): its first texel, MRT_NONE where open.
    starts_a: vec4<u32>,
    starts_b: vec4<u32>,
    // Per world side: the canonical face on it.
    local_a: vec4<u32>,
    local_b: vec4<u32>,
    // Directed interfaces entering the block (slot indices, MRT_NONE for none).
    slots: vec4<u32>,
    // Per canonical face: the block beyond it where it is open over its whole area, else
    // MRT_NONE (the lookup pads across such sides).
    across_a: vec4<u32>,
    across_b: vec4<u32>,
    // Per world side: the first of its P^2 side texels (in the indirect buffer) where it is
    // partly open (the wall around a doorway), else MRT_NONE.
    sides_a: vec4<u32>,
    sides_b: vec4<u32>,
}

struct MrtParams {
    // blocks, texels, slots, k_b.
    counts: vec4<u32>,
    // k_r, texels per face side, padding across open sides (1) or not (0), unused.
    sizes: vec4<u32>,
    // feedback gain, unused x3.
    gains: vec4<f32>,
    // opening positions per side P, partly open sides, side texels, unused.
    sides: vec4<u32>,
}

// The first texel of canonical face `face`, MRT_NONE where it is open.
fn block_start(b: Block, face: u32) -> u32 {
    if face < 4u {
        return b.starts_a[face];
    }
    return b.starts_b[face - 4u];
}

fn block_across(b: Block, face: u32) -> u32 {
    if face < 4u {
        return b.across_a[face];
    }
    return b.across_b[face - 4u];
}

// The first side texel of world side `side`, MRT_NONE where it is not partly open.
fn block_side(b: Block, side: u32) -> u32 {
    if side < 4u {
        return b.sides_a[side];
    }
    return b.sides_b[side - 4u];
}

fn block_local(b: Block, side: u32) -> u32 {
    if side < 4u {
        return b.local_a[side];
    }
    return b.local_b[side - 4u];
}

// v turned q quarter turns about up: (x, y, z) -> (z, y, -x) per turn.
fn turn_vec(v: vec3<f32>, q: u32) -> vec3<f32> {
    var r = v;
    for (var i = 0u; i < q % 4u; i = i + 1u) {
        r = vec3<f32>(r.z, r.y, -r.x);
    }
    return r;
}

// A world point in the block's canonical unit-cube frame (level::Block::local_point).
fn block_local_point(b: Block, w: vec3<f32>) -> vec3<f32> {
    let c = vec3<f32>(0.5, 0.0, 0.5);
    let q = u32(b.origin.w + 0.5);
    return c + turn_vec((w - b.origin.xyz) / b.size.xyz - c, (4u - q % 4u) % 4u);
}

// The unit normal pointing into the box from world side `side` (-x +x -y +y -z +z).
fn side_inward(side: u32) -> vec3<f32> {
    var n = vec3<f32>(0.0);
    let s = select(1.0, -1.0, side % 2u == 1u);
    n[side / 2u] = s;
    return n;
}
