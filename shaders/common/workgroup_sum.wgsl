// A tree sum over a workgroup of 64 invocations in workgroup memory (WGSL has no float atomics):
// `workgroup_sum(lid, v)` leaves the sum of every invocation's v in `partial[0]`. Call it in
// uniform control flow. Used by MRT's pass B (`mrt_reduce.wgsl`) and sshgi's bounce tail
// (`sshgi_tail.wgsl`); a caller with fewer lanes pads v with zeros.

var<workgroup> partial: array<vec4<f32>, 64>;

fn workgroup_sum(lid: u32, v: vec4<f32>) {
    partial[lid] = v;
    workgroupBarrier();
    for (var stride = 32u; stride > 0u; stride = stride >> 1u) {
        if lid < stride {
            partial[lid] = partial[lid] + partial[lid + stride];
        }
        workgroupBarrier();
    }
}
