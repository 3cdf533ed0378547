// Per-frame view constants shared by every full-screen pass (mirrors render::uniforms::FrameUniforms).
struct Frame {
    clip_from_world: mat4x4<f32>,
    world_from_clip: mat4x4<f32>,
    prev_clip_from_world: mat4x4<f32>,
    // xyz camera position, w unused.
    camera_position: vec4<f32>,
    // width, height, 1/width, 1/height.
    size: vec4<f32>,
    // light count, frame index, PCF radius, shadow layer count.
    params: vec4<u32>,
    // normal bias in texels, shadow map size, 1/size, unused.
    shadow: vec4<f32>,
}

// World position of pixel `pixel` (integer coordinates) at depth `depth` (0..1).
fn world_from_pixel(frame: Frame, pixel: vec2<u32>, depth: f32) -> vec3<f32> {
    let uv = (vec2<f32>(pixel) + 0.5) * frame.size.zw;
    let ndc = vec4<f32>(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0, depth, 1.0);
    let h = frame.world_from_clip * ndc;
    return h.xyz / h.w;
}

// The pixel (integer coordinates) world point `x` projects to; w = 1 where it lies in front of
// the camera and inside the view, 0 elsewhere (xy undefined then).
fn pixel_of_world(frame: Frame, x: vec3<f32>) -> vec3<u32> {
    let c = frame.clip_from_world * vec4<f32>(x, 1.0);
    if c.w <= 0.0 {
        return vec3<u32>(0u);
    }
    let uv = vec2<f32>(c.x / c.w * 0.5 + 0.5, 0.5 - c.y / c.w * 0.5);
    if any(uv < vec2<f32>(0.0)) || any(uv >= vec2<f32>(1.0)) {
        return vec3<u32>(0u);
    }
    return vec3<u32>(vec2<u32>(uv * frame.size.xy), 1u);
}

// World position of `pixel` read from the reversed-depth buffer `depth`, w = 1 where the pixel
// sees geometry (0: far plane, nothing drawn).
fn position_at(frame: Frame, depth: texture_depth_2d, pixel: vec2<u32>) -> vec4<f32> {
    let d = textureLoad(depth, pixel, 0);
    if d <= 0.0 {
        return vec4<f32>(0.0);
    }
    return vec4<f32>(world_from_pixel(frame, pixel, d), 1.0);
}

// The view pixel (its centre, in pixels) a depth/normal pyramid texel `g` copied
// (`render/pyramid.wgsl`: g.a - 1, row-major). g.a must be >= 1.
fn pyramid_pixel(frame: Frame, g: vec4<f32>) -> vec2<f32> {
    let index = u32(g.a - 0.5);
    let width = u32(frame.size.x);
    return vec2<f32>(f32(index % width), f32(index / width)) + 0.5;
}

// The world point at distance `r` from the camera on the ray through `pixel` (pixels).
fn point_on_pixel_ray(frame: Frame, pixel: vec2<f32>, r: f32) -> vec3<f32> {
    let uv = pixel * frame.size.zw;
    let h = frame.world_from_clip * vec4<f32>(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0, 1.0, 1.0);
    return frame.camera_position.xyz + normalize(h.xyz / h.w - frame.camera_position.xyz) * r;
}

// The world point a depth/normal pyramid texel `g` stands for: on the ray of the view pixel it
// copied, at its distance g.r.
fn pyramid_point(frame: Frame, g: vec4<f32>) -> vec3<f32> {
    return point_on_pixel_ray(frame, pyramid_pixel(frame, g), g.r);
}
