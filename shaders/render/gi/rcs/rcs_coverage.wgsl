// rcs coverage detection, the CPU scan of Gautron et al. 2005 ("Splatting-Based Rendering") moved
// to the GPU: a pixel with geometry that no record reaches (summed weight 0) is uncovered; each
// 8 x 8 tile with uncovered pixels proposes the one nearest its centre as a new record's site.
// Candidates are appended (the CPU reads them back, orders them and computes the budget's worth).
// The mask: r = uncovered after this pass, g = the pass (1-based) that picked this pixel for a
// record (the next round makes it), b = 1 where the pixel has geometry. Passes alternate between
// two masks (the last one written holds the frame's state).
#import common/frame.wgsl
#import common/octahedral.wgsl

struct CoverageParams {
    // x = the frame's coverage pass (0: its first, which writes every pixel of the mask), yzw
    // unused.
    round: vec4<u32>,
}

struct Candidate {
    // xyz world position, w = distance to the camera.
    position: vec4<f32>,
    // xyz geometric normal, w = the tile's index as bits.
    normal: vec4<f32>,
}

struct Candidates {
    count: atomic<u32>,
    pad0: u32,
    pad1: u32,
    pad2: u32,
    items: array<Candidate>,
}

@group(0) @binding(0) var<uniform> frame: Frame;
@group(0) @binding(1) var<uniform> params: CoverageParams;
@group(0) @binding(2) var depth_tex: texture_depth_2d;
@group(0) @binding(3) var normal_tex: texture_2d<f32>;
// The splat's weighted sums (a = summed weight), row-major.
@group(0) @binding(4) var<storage, read> accum: array<vec4<f32>>;
@group(0) @binding(5) var mask_in: texture_2d<f32>;
@group(0) @binding(6) var mask_out: texture_storage_2d<rgba32float, write>;
@group(0) @binding(7) var<storage, read_write> candidates: Candidates;

var<workgroup> best: atomic<u32>;

@compute @workgroup_size(8, 8, 1)
fn cs_main(
    @builtin(global_invocation_id) id: vec3<u32>,
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(local_invocation_index) local: u32,
    @builtin(num_workgroups) groups: vec3<u32>,
) {
    if local == 0u {
        atomicStore(&best, 0xffffffffu);
    }
    workgroupBarrier();
    let size = vec2<u32>(frame.size.xy);
    let inside = id.x < size.x && id.y < size.y;
    var geometry = false;
    var uncovered = false;
    if inside {
        geometry = textureLoad(depth_tex, id.xy, 0) > 0.0;
        uncovered = geometry && accum[id.y * size.x + id.x].a <= 0.0;
    }
    if uncovered {
        let d = vec2<i32>(id.xy % 8u) * 2 - 7;
        let key = (u32(d.x * d.x + d.y * d.y) << 8u) | local;
        atomicMin(&best, key);
    }
    workgroupBarrier();
    let chosen = atomicLoad(&best);
    let picked = uncovered && (chosen & 0xffu) == local;
    if picked {
        let depth = textureLoad(depth_tex, id.xy, 0);
        let p = world_from_pixel(frame, id.xy, depth);
        let n = oct_decode(textureLoad(normal_tex, id.xy, 0).zw);
        let i = atomicAdd(&candidates.count, 1u);
        if i < arrayLength(&candidates.items) {
            let tile = group.y * groups.x + group.x;
            candidates.items[i] = Candidate(
                vec4<f32>(p, length(p - frame.camera_position.xyz)),
                vec4<f32>(n, bitcast<f32>(tile)),
            );
        }
    }
    if !inside {
        return;
    }
    var mask = vec4<f32>(0.0, 0.0, select(0.0, 1.0, geometry), 1.0);
    if params.round.x > 0u {
        mask.g = textureLoad(mask_in, id.xy, 0).g;
    }
    mask.r = select(0.0, 1.0, uncovered);
    if picked {
        mask.g = f32(params.round.x + 1u);
    }
    textureStore(mask_out, id.xy, mask);
}
