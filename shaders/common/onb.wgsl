// An orthonormal basis around a unit normal (Duff et al. 2017), identical to
// precompute::ism::paraboloid::frame on the CPU (n.z = -0.0 counts as positive on both sides):
// the ISM splat and the ISM lookup must build the same tangent basis for a VPL, or its
// paraboloid map is written in one orientation and read in another, and the visibility it
// gives is garbage.
fn onb_tangent(n: vec3<f32>) -> vec3<f32> {
    let s = select(-1.0, 1.0, n.z >= 0.0);
    let a = -1.0 / (s + n.z);
    let b = n.x * n.y * a;
    return vec3<f32>(1.0 + s * n.x * n.x * a, s * b, -s * n.x);
}

fn onb_bitangent(n: vec3<f32>) -> vec3<f32> {
    let s = select(-1.0, 1.0, n.z >= 0.0);
    let a = -1.0 / (s + n.z);
    let b = n.x * n.y * a;
    return vec3<f32>(b, s + n.y * n.y * a, -n.y);
}

// Paraboloid coordinates in [0,1]^2 (xy) and distance (z) of `p` seen from a VPL at `o` with
// normal `n`; w < 0 when p is behind the VPL's surface.
fn paraboloid(o: vec3<f32>, n: vec3<f32>, p: vec3<f32>) -> vec4<f32> {
    let q = p - o;
    let d = length(q);
    let v = vec3<f32>(dot(q, onb_tangent(n)), dot(q, onb_bitangent(n)), dot(q, n)) / max(d, 1.0e-9);
    let disk = v.xy / (1.0 + v.z);
    return vec4<f32>(disk * 0.5 + 0.5, d, v.z);
}
