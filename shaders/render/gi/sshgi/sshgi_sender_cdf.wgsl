// sshgi's sender list sampled by power (not in Soler et al. 2010, whose senders are the screen's
// texels alone): prefix sums of every sender's power, luminance(radiance) x ds, over the list of
// this bounce (`sshgi_sender_pick.wgsl` draws from them). On levels lit through doorways most of
// the list is dark and a few senders carry the light: picked one per stratum of the list, a
// receiver's N samples met them in some frames and not in others.
//
// Two levels, so that no pass is one thread's long walk: `blocks` gives each block of 256
// senders a workgroup, which scans its powers (Hillis-Steele) into the block's own inclusive
// prefix sums at `cdf[i]` and its total at `cdf[count + block]`; `totals` (one workgroup) turns
// the blocks' totals into their inclusive prefix sums in place, and keeps the list's total power
// in the buffer's last two floats (the previous bounce's, then this one's: `HISTORY` in
// `sender_cdf.rs`), from which the bounce tail takes the world's ratio (`sshgi_tail.wgsl`). The
// list holds 6 F^2 + hidden senders: 8,192 at the defaults (32 blocks), at most 114,688 (448
// blocks, two a thread).
#import common/workgroup_scan.wgsl
#import render/gi/sshgi/sshgi_sender.wgsl

struct CdfParams {
    // x the senders in the list; yzw unused (the panorama's parameter slot, whose first word it
    // shares).
    counts: vec4<u32>,
}

@group(0) @binding(1) var<uniform> cp: CdfParams;
@group(0) @binding(2) var<storage, read> senders: array<Sender>;
// The senders' outgoing radiance of this bounce.
@group(0) @binding(3) var<storage, read> radiance: array<vec4<f32>>;
// Per sender its block's inclusive prefix sum, then per block the inclusive prefix sum of the
// blocks' totals.
@group(0) @binding(4) var<storage, read_write> cdf: array<f32>;

const BLOCK: u32 = 256u;
// Block totals a thread of `totals` takes (at most 448 blocks).
const PER_THREAD: u32 = 2u;

// Sender i's power, the luminance of its radiance times its area (its flux over pi: what it can
// send a receiver, before the form factor); 0 for an empty slot and for a radiance that is not
// finite (never drawn by power).
fn power(i: u32) -> f32 {
    let s = senders[i];
    if s.point.w <= 0.0 {
        return 0.0;
    }
    let p = dot(radiance[i].rgb, vec3<f32>(0.2126, 0.7152, 0.0722)) * s.point.w;
    return select(0.0, p, p > 0.0 && p < 3.0e38);
}

// The workgroup's inclusive prefix sums of every thread's `v`, in `scan`
// (`common/workgroup_scan.wgsl`); called by the whole workgroup.
fn scan_workgroup(lid: u32, v: f32) {
    scan[lid] = v;
    workgroupBarrier();
    scan_inclusive(lid);
}

fn sender_count() -> u32 {
    return min(cp.counts.x, arrayLength(&cdf));
}

fn block_count() -> u32 {
    return (sender_count() + BLOCK - 1u) / BLOCK;
}

@compute @workgroup_size(256, 1, 1)
fn blocks(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_index) lid: u32) {
    let count = sender_count();
    let i = group.x * BLOCK + lid;
    var p = 0.0;
    if i < count {
        p = power(i);
    }
    scan_workgroup(lid, p);
    if i < count {
        cdf[i] = scan[lid];
    }
    if lid == BLOCK - 1u && count + group.x < arrayLength(&cdf) {
        cdf[count + group.x] = scan[lid];
    }
}

@compute @workgroup_size(256, 1, 1)
fn totals(@builtin(local_invocation_index) lid: u32) {
    let count = sender_count();
    let blocks = min(block_count(), arrayLength(&cdf) - count);
    let first = lid * PER_THREAD;
    var run = array<f32, PER_THREAD>();
    var sum = 0.0;
    for (var k = 0u; k < PER_THREAD; k = k + 1u) {
        if first + k < blocks {
            sum = sum + cdf[count + first + k];
        }
        run[k] = sum;
    }
    scan_workgroup(lid, sum);
    var before = 0.0;
    if lid > 0u {
        before = scan[lid - 1u];
    }
    for (var k = 0u; k < PER_THREAD; k = k + 1u) {
        if first + k < blocks {
            cdf[count + first + k] = before + run[k];
        }
    }
    let end = arrayLength(&cdf);
    if lid == 0u && end >= count + blocks + 2u {
        cdf[end - 2u] = cdf[end - 1u];
        cdf[end - 1u] = scan[255u];
    }
}
