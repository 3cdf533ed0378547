// ISM pass P7's first step: every atlas word empty (`ISM_EMPTY`) before the splats' atomic mins
// (`ism_splat.wgsl`). Each workgroup fills a block of `BLOCK` consecutive vec4 words, its 64
// threads side by side in each row of the block, so that a GPU's stores coalesce and a CPU
// adapter's lanes write contiguous memory. (An atomic store per texel, the earlier clear,
// cost lavapipe about 0.7 s of a default frame's 26 million atlas words.)
#import common/vpl.wgsl

// The atlas as vec4 words (its size is a multiple of 16 bytes; `Buffers::new` in gather/mod.rs).
@group(0) @binding(3) var<storage, read_write> words: array<vec4<u32>>;

// vec4 words per thread.
const PER_THREAD: u32 = 16u;
// vec4 words per workgroup.
const BLOCK: u32 = 64u * PER_THREAD;
// Workgroups per row of the dispatch (`IsmGather::record_sets`).
const GROUPS_PER_ROW: u32 = 256u;

@compute @workgroup_size(64, 1, 1)
fn clear(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_index) lane: u32) {
    let n = arrayLength(&words);
    let first = (group.y * GROUPS_PER_ROW + group.x) * BLOCK + lane;
    for (var i = 0u; i < PER_THREAD; i = i + 1u) {
        let k = first + i * 64u;
        if k < n {
            words[k] = vec4<u32>(ISM_EMPTY);
        }
    }
}
