// sshgi panorama, receive (an extension of Soler et al. 2010, not in the paper): the panorama's
// senders' outgoing radiance of the next bounce, reflectance x E / pi, where E comes from this
// bounce's senders on screen (N start-level texels, one per stratum, each with the texel area of
// the screen gathers' Eq. 2) and in the panorama (N senders, `gather_senders`, part of them
// picked by power). So light that leaves the screen, lights a surface off screen and comes back
// reaches the view in the later bounces. No visibility between the panorama's senders and the screen; a hidden sender
// (`sshgi_hidden_pack.wgsl`) marches each segment through the view's voxels, and where it leaves
// the view through the world's surface voxels.
#import common/frame.wgsl
#import common/octahedral.wgsl
#import render/gi/sshgi/sshgi_panorama_common.wgsl

@group(0) @binding(0) var<uniform> frame: Frame;
@group(0) @binding(1) var<uniform> gp: PanoramaParams;
// The depth/normal pyramid's start level.
@group(0) @binding(2) var geometry: texture_2d<f32>;
// The screen senders' outgoing radiance of this bounce, at the start level.
@group(0) @binding(3) var illumination: texture_2d<f32>;
@group(0) @binding(4) var<storage, read> senders: array<Sender>;
// The panorama senders' outgoing radiance of this bounce.
@group(0) @binding(5) var<storage, read> radiance: array<vec4<f32>>;
// Their outgoing radiance of the next bounce.
@group(0) @binding(6) var<storage, read_write> next: array<vec4<f32>>;
// The voxel columns marched (as the screen's gathers').
@group(0) @binding(7) var<storage, read> voxels: array<vec4<u32>>;
// The world's surface voxels (one word where there are none).
@group(0) @binding(8) var<storage, read> world: array<u32>;
// The prefix sums of this bounce's senders' power (`sshgi_sender_cdf.wgsl`).
@group(0) @binding(9) var<storage, read> cdf: array<f32>;

// E / pi at x (normal nx) from N start-level texels of the screen, one per stratum (with
// `march`, each segment marched through the view's voxels).
fn gather_screen(x: vec3<f32>, nx: vec3<f32>, jitter: f32, march: bool, first: u32, step: u32) -> vec3<f32> {
    let w = gp.screen.x;
    let count = w * gp.screen.y;
    let n = samples(march);
    let stratum = f32(count) / f32(n);
    let cam = frame.camera_position.xyz;
    var sum = vec3<f32>(0.0);
    for (var i = first; i < n; i = i + step) {
        let pick = min(u32((f32(i) + fract(jitter + f32(i) * 0.618034)) * stratum), count - 1u);
        let t = vec2<u32>(pick % w, pick / w);
        let g = textureLoad(geometry, t, 0);
        if g.a < 0.5 {
            continue;
        }
        let y = pyramid_point(frame, g);
        let ny = oct_decode(g.gb);
        let dir_y = (y - cam) / max(g.r, 1.0e-20);
        let cos_a = max(dot(dir_y, gp.forward.xyz), 0.0);
        let cos_b = max(dot(ny, -dir_y), 0.05);
        let ds = gp.geo.x * cos_a * cos_a * cos_a * g.r * g.r / cos_b;
        let ff = disc_form_factor(y - x, nx, ny, ds);
        if ff > 0.0 && !(march && world_occluded(off_surface(x, nx), nx, y, ny, vec2<bool>(false, true))) {
            sum = sum + textureLoad(illumination, t, 0).rgb * ff;
        }
    }
    return sum * stratum;
}

@compute @workgroup_size(64, 1, 1)
fn receive(@builtin(workgroup_id) group: vec3<u32>, @builtin(local_invocation_index) lid: u32) {
    let f = gp.counts.w;
    let split = max(gp.screen.w, 1u);
    let item = split_item(group, lid, split);
    let id = item.xy;
    let index = id.y * f + id.x;
    let inside = item.z == 1u && id.x < f && index < gp.counts.x;
    var s = Sender();
    if inside {
        s = senders[index];
    }
    let jitter = hash01(id.x, id.y, gp.counts.z ^ 0x68bc21ebu);
    let hidden = index >= hidden_from();
    var own = vec3<f32>(0.0);
    if s.point.w > 0.0 {
        let part = lid % split;
        own = gather_screen(s.point.xyz, s.normal.xyz, jitter, hidden, part, split)
            + gather_senders(s.point.xyz, s.normal.xyz, fract(jitter + 0.5), hidden, part, split);
    }
    let e = split_sum(lid, own, split);
    if inside && lid % split == 0u {
        next[index] = vec4<f32>(s.reflectance.rgb * e, 0.0);
    }
}
