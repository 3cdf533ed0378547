// The view importance of every pool point for the next frame's bounce picks (`importance` in
// `ism_bounce.wgsl`): how strongly a VPL on that point could light what the camera sees, as the
// unoccluded transfer to a grid of the view's surface points. For a VPL at x with normal n and
// a view point y at camera distance D:
//   I(x) = mean over the grid of max(n . (y - x) / |y - x|, 0) D^2 / max(|y - x|^2, (0.1 D)^2),
// i.e. its inverse-square reach relative to the camera's own (a point beside the camera facing
// the view gets about 1, one next to a lit spot up to 100, one facing away 0). Occlusion and
// the receivers' cosines are left out, so I bounds the VPL's share of the view from above up to
// the grid's sampling: no point gets a small weight for light it would actually bring. Written
// into the w of its albedo (1 at upload: every point alike until a view has been seen). Any
// positive weight keeps the picks unbiased, which divide each new VPL's power by the weight.
// Segovia et al. 2006 (bidirectional instant radiosity) and Georgiev & Slusallek 2010 place VPLs
// by their contribution to the camera for the same reason: a room lit only through doorways
// otherwise receives a handful of each set's VPLs, each carrying a large share of the light.
#import common/frame.wgsl

@group(0) @binding(0) var<uniform> frame: Frame;
@group(0) @binding(1) var depth: texture_depth_2d;
@group(0) @binding(2) var<storage, read> points: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> point_normals: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read_write> point_albedo: array<vec4<f32>>;

// View points per side of the grid.
const GRID: u32 = 8u;
// The nearest distance counted, as a fraction of the view point's camera distance.
const NEAR: f32 = 0.1;

@compute @workgroup_size(64, 1, 1)
fn view_importance(@builtin(global_invocation_id) id: vec3<u32>) {
    let j = id.x;
    if j >= arrayLength(&point_albedo) || j >= arrayLength(&points) {
        return;
    }
    let x = points[j].xyz;
    let n = point_normals[j].xyz;
    let size = vec2<u32>(frame.size.xy);
    var sum = 0.0;
    var count = 0.0;
    for (var g = 0u; g < GRID * GRID; g = g + 1u) {
        let cell = vec2<u32>(g % GRID, g / GRID);
        let pixel = min((2u * cell + 1u) * size / (2u * GRID), size - 1u);
        let y = position_at(frame, depth, pixel);
        if y.w <= 0.0 {
            continue;
        }
        count = count + 1.0;
        let to_y = y.xyz - x;
        let d2 = dot(to_y, to_y);
        let cam = y.xyz - frame.camera_position.xyz;
        let big_d2 = dot(cam, cam);
        let cos_x = dot(n, to_y) * inverseSqrt(max(d2, 1.0e-20));
        if cos_x > 0.0 {
            sum = sum + cos_x * big_d2 / max(d2, NEAR * NEAR * big_d2);
        }
    }
    var importance = 1.0;
    if count > 0.0 {
        importance = sum / count;
    }
    point_albedo[j].w = importance;
}
