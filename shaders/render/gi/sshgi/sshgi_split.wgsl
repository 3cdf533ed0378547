// How `sshgi`'s marching passes (the screen's gathers, the panorama's gather and receive, the
// sky) share an item's (texel's or sender's) samples over the threads of a 64-thread workgroup:
// each item takes `split` threads (1, 4, 16 or 64), each thread every split-th sample, and the
// workgroup adds them up. A thread per item made each a serial chain of N marched samples, and
// the coarse levels, which march the farthest, have the fewest texels (the H200 profile, commit
// e48fc51: level 3's 2,040 texels 21 ms, level 0's 130,000 5.5 ms at 1080p; the receive 5 ms,
// the sky 12.6 ms). `passes::steps::split` chooses `split`; a software adapter keeps 1. A
// workgroup covers a tile of 8 / sqrt(split) items a side.

var<workgroup> split_partial: array<vec3<f32>, 64>;

// The item thread `lid` of workgroup `group` works on; z = 1 where the thread has one.
fn split_item(group: vec3<u32>, lid: u32, split: u32) -> vec3<u32> {
    let side = max(8u / u32(round(sqrt(f32(split)))), 1u);
    let slot = lid / split;
    let item = group.xy * side + vec2<u32>(slot % side, slot / side);
    return vec3<u32>(item, u32(slot < side * side));
}

// The sum of the split threads' `own` of item `lid / split`, valid in its first thread (lid a
// multiple of split); the whole workgroup calls it.
fn split_sum(lid: u32, own: vec3<f32>, split: u32) -> vec3<f32> {
    split_partial[lid] = own;
    workgroupBarrier();
    var sum = own;
    if lid % split == 0u {
        for (var i = 1u; i < split; i = i + 1u) {
            sum = sum + split_partial[lid + i];
        }
    }
    return sum;
}
