// One record computation (mirrors render::gi::rcs::record::GpuJob): where the record's
// hemisphere camera stands and where its plane goes in the atlas. A 256-byte uniform slot for the
// hemisphere render (dynamic offset), an array element for the reduction.
struct Job {
    // xyz P_k, w = near plane of the hemisphere camera (m).
    position: vec4<f32>,
    // xyz n_k (the camera's axis), w = the record's slot as bits.
    normal: vec4<f32>,
    // xyz tangent (plane +x), w = smallest R_k allowed (m).
    tangent: vec4<f32>,
    // xyz bitangent (plane +y), w = largest R_k allowed (m).
    bitangent: vec4<f32>,
    // x = white furnace (1: every surface and the background emit 1), y = look the cache up at
    // the surfaces seen (later bounces), z, w = the plane's first atlas texel.
    params: vec4<f32>,
    // x = the times this record has been computed before (0: new), y = 1: propose secondary
    // records where its bounce lookups found nothing, zw unused.
    extra: vec4<f32>,
    pad: array<vec4<f32>, 10>,
}
