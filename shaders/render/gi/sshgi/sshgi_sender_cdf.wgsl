// sshgi's sender list sampled by power (not in Soler et al. 2010, whose senders are the screen's
// texels alone): the inclusive prefix sums of every sender's power, luminance(radiance) x ds,
// over the list of this bounce (`sshgi_sender_pick.wgsl` draws from them). On levels lit through
// doorways most of the list is dark and a few senders carry the light: picked one per stratum of
// the list, a receiver's N samples met them in some frames and not in others. One workgroup: each
// thread sums a contiguous run of the list, the workgroup scans the 256 runs (Hillis-Steele), and
// each thread writes its run's prefix sums. The list holds 6 F^2 + hidden senders (8,192 at the
// defaults, at most 114,688): a run of at most 448 senders a thread.
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
// Inclusive prefix sums of the senders' power.
@group(0) @binding(4) var<storage, read_write> cdf: array<f32>;

const THREADS: u32 = 256u;

var<workgroup> runs: array<f32, 256>;

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

@compute @workgroup_size(256, 1, 1)
fn prefix(@builtin(local_invocation_index) lid: u32) {
    let count = min(cp.counts.x, arrayLength(&cdf));
    let per = (count + THREADS - 1u) / THREADS;
    let begin = min(lid * per, count);
    let end = min(begin + per, count);
    var sum = 0.0;
    for (var i = begin; i < end; i = i + 1u) {
        sum = sum + power(i);
    }
    runs[lid] = sum;
    workgroupBarrier();
    for (var offset = 1u; offset < THREADS; offset = offset << 1u) {
        var before = 0.0;
        if lid >= offset {
            before = runs[lid - offset];
        }
        workgroupBarrier();
        runs[lid] = runs[lid] + before;
        workgroupBarrier();
    }
    var running = 0.0;
    if lid > 0u {
        running = runs[lid - 1u];
    }
    for (var i = begin; i < end; i = i + 1u) {
        running = running + power(i);
        cdf[i] = running;
    }
}
