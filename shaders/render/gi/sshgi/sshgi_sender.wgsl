// One sender of sshgi's off-screen list (`sshgi_panorama_pack.wgsl` writes the panorama's,
// `sshgi_hidden_pack.wgsl` the hidden ones after them; the gathers, receives and the sky read it).
struct Sender {
    // xyz the point, w the area ds it stands for (m^2; 0: no sender).
    point: vec4<f32>,
    // xyz geometric normal, w unused.
    normal: vec4<f32>,
    // rgb reflectance as a diffuse sender (albedo + a glossy lobe's share of diffuse light,
    // `sender_reflectance`), a unused.
    reflectance: vec4<f32>,
}
