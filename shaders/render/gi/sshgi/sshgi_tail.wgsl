// sshgi bounce tail (not in Soler et al. 2010, who gather a fixed number of bounces): the light of
// the bounces after the last one gathered, as a geometric series of the last bounce, E_tail =
// E_last r / (1 - r). r is the screen's ratio (the last bounce's light on the start level over
// the previous bounce's) up to `SCREEN_CAP`. Past it the light on screen is still arriving (a room
// that light reaches late), and r is the geometric mean of the screen's ratio and the world's (the
// sender list's total power of the last bounce over the previous one's,
// `sshgi_sender_cdf.wgsl`), within `SCREEN_CAP` and `TAIL_CAP`: `ism`'s default tail ratio. There
// the screen's ratio alone overshoots (the light on screen grows while the level as a whole loses
// it), and the cap alone left such rooms at 0.53-0.68 of the path tracer's light. Without a
// sender list (no panorama) r is the screen's ratio up to `SCREEN_CAP`.
// Three dispatches: `sums` (each 8x8 tile's luminance of both bounces), `ratio` (one workgroup:
// the tiles' sums and the factor r / (1 - r)) and `add` (dest = total + factor x last).
#import common/workgroup_sum.wgsl

// The largest ratio taken (`ism`'s): 1 / (1 - r) is steep.
const TAIL_CAP: f32 = 0.9;
// The largest screen ratio taken alone: a room that light reaches late sees its bounces grow for a
// while (the suite's three rooms from the unlit room: 0.9 at the fourth bounce).
const SCREEN_CAP: f32 = 0.75;

// (binding 0, the steps' parameter slot, is unused.)
// The previous bounce's and the last bounce's E / pi at the start level.
@group(0) @binding(1) var previous: texture_2d<f32>;
@group(0) @binding(2) var last: texture_2d<f32>;
// The bounces' sum so far, and where the sum with the tail goes.
@group(0) @binding(3) var total: texture_2d<f32>;
@group(0) @binding(4) var dest: texture_storage_2d<rgba32float, write>;
// [0]: x the factor r / (1 - r), y r, z the screen's ratio, w the world's (0: none);
// [1 + tile]: the tile's luminance sums (previous, last).
@group(0) @binding(5) var<storage, read_write> tail: array<vec4<f32>>;
// The sender list's prefix sums, whose last two floats are its total power of the previous and
// the last bounce (two zeros without a list).
@group(0) @binding(6) var<storage, read> powers: array<f32>;

fn luminance(c: vec3<f32>) -> f32 {
    return dot(c, vec3<f32>(0.2126, 0.7152, 0.0722));
}

// The tiles across the start level.
fn tiles() -> vec2<u32> {
    return (textureDimensions(last) + vec2<u32>(7u)) / 8u;
}

@compute @workgroup_size(8, 8, 1)
fn sums(
    @builtin(global_invocation_id) id: vec3<u32>,
    @builtin(workgroup_id) group: vec3<u32>,
    @builtin(local_invocation_index) lid: u32,
) {
    let size = textureDimensions(last);
    var v = vec2<f32>(0.0);
    if id.x < size.x && id.y < size.y {
        v = vec2<f32>(luminance(textureLoad(previous, id.xy, 0).rgb), luminance(textureLoad(last, id.xy, 0).rgb));
    }
    workgroup_sum(lid, vec4<f32>(v, 0.0, 0.0));
    if lid == 0u {
        tail[1u + group.y * tiles().x + group.x] = vec4<f32>(partial[0].xy, 0.0, 0.0);
    }
}

@compute @workgroup_size(8, 8, 1)
fn ratio(@builtin(local_invocation_index) lid: u32) {
    let t = tiles();
    let count = t.x * t.y;
    var v = vec2<f32>(0.0);
    for (var i = lid; i < count; i = i + 64u) {
        v = v + tail[1u + i].xy;
    }
    workgroup_sum(lid, vec4<f32>(v, 0.0, 0.0));
    if lid == 0u {
        let s = partial[0].xy;
        let screen = select(0.0, max(s.y / s.x, 0.0), s.x > 0.0);
        let n = arrayLength(&powers);
        let previous = powers[n - 2u];
        let world = select(0.0, max(powers[n - 1u] / previous, 0.0), previous > 0.0);
        var r = min(screen, SCREEN_CAP);
        if world > 0.0 && screen > SCREEN_CAP {
            r = clamp(sqrt(screen * world), SCREEN_CAP, TAIL_CAP);
        }
        tail[0] = vec4<f32>(r / (1.0 - r), r, screen, world);
    }
}

@compute @workgroup_size(8, 8, 1)
fn add(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(dest);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    let factor = tail[0].x;
    let sum = textureLoad(total, id.xy, 0).rgb + factor * textureLoad(last, id.xy, 0).rgb;
    textureStore(dest, id.xy, vec4<f32>(sum, 1.0));
}
