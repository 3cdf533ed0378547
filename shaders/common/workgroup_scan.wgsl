// An inclusive Hillis-Steele scan over a workgroup of 256 invocations in workgroup memory (WGSL
// has no float atomics): each invocation writes its value to `scan[lid]`, the workgroup passes a
// barrier, and `scan_inclusive(lid)`, called in uniform control flow, leaves in `scan[lid]` the
// sum of the values up to and with lid's. Used by `ism`'s bounce (`ism_bounce.wgsl`: the sources'
// prefix) and point selection (`ism_select.wgsl`: the clusters' weights) and `sshgi`'s sender
// power (`sshgi_sender_cdf.wgsl`).

var<workgroup> scan: array<f32, 256>;

fn scan_inclusive(lid: u32) {
    for (var off = 1u; off < 256u; off = off * 2u) {
        var v = scan[lid];
        if lid >= off {
            v = v + scan[lid - off];
        }
        workgroupBarrier();
        scan[lid] = v;
        workgroupBarrier();
    }
}
