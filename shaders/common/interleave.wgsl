// The split G-buffer layout (Knecht 2009 section 3.4.1, P9): full pixel (a n + i, b n + j)
// lives at split address (i bw + a, j bh + b) with the block bw x bh = ceil(W / n) x ceil(H / n).
// Tile (i, j) is a 1/n-resolution copy of the view that one VPL subset lights, so a compute
// workgroup in the split layout reads the same VPLs in every thread.

fn split_block(size: vec2<u32>, n: u32) -> vec2<u32> {
    return (size + vec2<u32>(n - 1u)) / n;
}

// Split-layout address of full-resolution pixel `pixel`.
fn split_address(pixel: vec2<u32>, size: vec2<u32>, n: u32) -> vec2<u32> {
    return (pixel % vec2<u32>(n)) * split_block(size, n) + pixel / vec2<u32>(n);
}

// Full-resolution pixel (xy, possibly outside the view in the padding) and tile index j n + i
// (z) of split texel `s`.
fn split_pixel(s: vec2<u32>, size: vec2<u32>, n: u32) -> vec3<u32> {
    let block = split_block(size, n);
    let tile = s / block;
    let pixel = (s % block) * n + tile;
    return vec3<u32>(pixel, tile.y * n + tile.x);
}
