// sshgi panorama, gather (an extension of Soler et al. 2010, not in the paper): each start-level
// texel adds to the screen's gather of a bounce the light of N senders of the panorama
// (`sshgi_panorama_pack.wgsl`: the surfaces around the camera the view does not show), picked
// one per stratum of a mixture of uniform and power-proportional picks over the sender list
// (`sshgi_sender_pick.wgsl`) with a per-pixel and per-frame jitter, each with the same bounded
// disc form factor as the screen's gathers (Eq. 4, R^2 = cos(theta') ds / pi), weighted by one
// over N times its pick's probability: an unbiased estimate of the panorama's E / pi, averaged
// over frames by the temporal filter. No visibility for the panorama's senders: the view's
// voxels do not reach off screen, so light passes through whatever lies between the receiver and
// a panorama sender.
// The hidden senders after them in the list (`sshgi_hidden_pack.wgsl`) are marched through the
// voxels, and where a segment leaves the view through the world's surface voxels.
#import common/frame.wgsl
#import common/octahedral.wgsl

#import render/gi/sshgi/sshgi_panorama_common.wgsl

@group(0) @binding(0) var<uniform> frame: Frame;
@group(0) @binding(1) var<uniform> gp: PanoramaParams;
// The depth/normal pyramid's start level.
@group(0) @binding(2) var geometry: texture_2d<f32>;
// The screen's first bounce (E / pi) at the start level.
@group(0) @binding(3) var base: texture_2d<f32>;
@group(0) @binding(4) var dest: texture_storage_2d<rgba32float, write>;
@group(0) @binding(5) var<storage, read> senders: array<Sender>;
// The senders' outgoing radiance of this bounce.
@group(0) @binding(6) var<storage, read> radiance: array<vec4<f32>>;
// The voxel columns marched (as the screen's gathers').
@group(0) @binding(7) var<storage, read> voxels: array<vec4<u32>>;
// The world's surface voxels (one word where there are none).
@group(0) @binding(8) var<storage, read> world: array<u32>;
// The prefix sums of this bounce's senders' power (`sshgi_sender_cdf.wgsl`).
@group(0) @binding(9) var<storage, read> cdf: array<f32>;

@compute @workgroup_size(64, 1, 1)
fn gather(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_index) lid: u32) {
    let size = textureDimensions(dest);
    let split = max(gp.screen.z, 1u);
    let item = split_item(group, lid, split);
    let id = item.xy;
    let inside = item.z == 1u && all(id < size);
    var screen = vec4<f32>(0.0);
    var g = vec4<f32>(0.0);
    if inside {
        screen = textureLoad(base, id, 0);
        g = textureLoad(geometry, id, 0);
    }
    let count = gp.counts.x;
    let n = gp.counts.y;
    var own = vec3<f32>(0.0);
    if g.a >= 0.5 && count > 0u && n > 0u {
        let x = pyramid_point(frame, g);
        let nx = oct_decode(g.gb);
        own = gather_senders(x, nx, hash01(id.x, id.y, gp.counts.z), false, lid % split, split);
    }
    let sum = split_sum(lid, own, split);
    if inside && lid % split == 0u {
        textureStore(dest, id, vec4<f32>(screen.rgb + sum, screen.a));
    }
}
