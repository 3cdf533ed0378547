// sshgi panorama, pack (an extension of Soler et al. 2010, not in the paper): one face of a
// low-resolution cube G-buffer around the camera, lit by the same direct-light pass as the view,
// turned into senders: per texel its world point, the area ds it stands for (a cube texel's solid
// angle, (2/F)^2 / (1 + u^2 + v^2)^(3/2), times distance^2 over the tilt), its geometric normal and
// outgoing radiance (the first bounce's sender radiance, the lighting pass's `exitance`: a
// glossy lobe's share of the light sent in every direction; later bounces' come from
// `sshgi_panorama_receive.wgsl`) and reflectance (albedo + the lobe's share of diffuse light).
// A texel inside the view's frustum is left out (ds = 0): the view shows it, and the screen's
// own gathers send it.
#import common/frame.wgsl
#import common/octahedral.wgsl
#import common/brdf.wgsl

struct PackParams {
    // face index, face size F (texels), unused x2.
    face: vec4<u32>,
}

#import render/gi/sshgi/sshgi_sender.wgsl

@group(0) @binding(0) var<uniform> face_frame: Frame;
@group(0) @binding(1) var<uniform> view_frame: Frame;
@group(0) @binding(2) var<uniform> pp: PackParams;
@group(0) @binding(3) var face_depth: texture_depth_2d;
@group(0) @binding(4) var face_normal: texture_2d<f32>;
@group(0) @binding(5) var face_exitance: texture_2d<f32>;
@group(0) @binding(6) var<storage, read_write> senders: array<Sender>;
// The senders' outgoing radiance of the first bounce (rgb).
@group(0) @binding(7) var<storage, read_write> radiance: array<vec4<f32>>;
@group(0) @binding(8) var face_albedo: texture_2d<f32>;
// Every face texel's distance to its surface (1e30 where it sees none): what the camera sees
// around it, for the hidden senders' test (`sshgi_hidden_pack.wgsl`).
@group(0) @binding(9) var<storage, read_write> distances: array<f32>;
// The faces' specular colour and roughness (the G-buffer's material target).
@group(0) @binding(10) var face_material: texture_2d<f32>;

// Whether the view shows the point p: whether it lies inside the view's frustum. The faces are
// rendered from the view's own centre of projection, so what a face sees inside that frustum is
// what the view sees (up to their sampling); comparing depths instead lets silhouettes, where
// the two samplings land on different surfaces, through twice.
fn on_screen(p: vec3<f32>) -> bool {
    let clip = view_frame.clip_from_world * vec4<f32>(p, 1.0);
    if clip.w <= 0.0 {
        return false;
    }
    let ndc = clip.xyz / clip.w;
    return all(abs(ndc.xy) <= vec2<f32>(1.0)) && ndc.z >= 0.0 && ndc.z <= 1.0;
}

@compute @workgroup_size(8, 8, 1)
fn pack(@builtin(global_invocation_id) id: vec3<u32>) {
    let f = pp.face.y;
    if id.x >= f || id.y >= f {
        return;
    }
    let index = pp.face.x * f * f + id.y * f + id.x;
    var sender = Sender(vec4<f32>(0.0), vec4<f32>(0.0), vec4<f32>(0.0));
    var light = vec4<f32>(0.0);
    let p = position_at(face_frame, face_depth, id.xy);
    distances[index] = 1.0e30;
    if p.w > 0.5 {
        let cam = face_frame.camera_position.xyz;
        let dist = distance(p.xyz, cam);
        distances[index] = dist;
        let n = oct_decode(textureLoad(face_normal, id.xy, 0).zw);
        let dir = (p.xyz - cam) / max(dist, 1.0e-20);
        if !on_screen(p.xyz) && dot(n, -dir) > 0.0 {
            let uv = (vec2<f32>(id.xy) + 0.5) / f32(f) * 2.0 - 1.0;
            let solid_angle = 4.0 / f32(f * f) / pow(1.0 + dot(uv, uv), 1.5);
            let ds = solid_angle * dist * dist / max(dot(n, -dir), 0.05);
            let mat = textureLoad(face_material, id.xy, 0);
            let reflectance = sender_reflectance(textureLoad(face_albedo, id.xy, 0).rgb, mat.rgb, mat.a);
            sender = Sender(vec4<f32>(p.xyz, ds), vec4<f32>(n, 0.0), vec4<f32>(reflectance, 0.0));
            light = vec4<f32>(textureLoad(face_exitance, id.xy, 0).rgb, 0.0);
        }
    }
    senders[index] = sender;
    radiance[index] = light;
}
