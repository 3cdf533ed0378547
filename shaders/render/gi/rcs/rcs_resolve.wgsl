// rcs normalisation (notes: "normalize / compose"): E(P) = sum w E^ / sum w at every pixel some
// record reaches, written as E / pi for the composite to multiply by the albedo (Lambertian
// convention; the white-furnace test checks the pi). Uncovered pixels (the cache still filling,
// or full) get no indirect light.

struct ResolveParams {
    // x = 1: with gradients (target 0's sum), 0: plain record values (target 1's); yzw unused.
    mode: vec4<u32>,
}

@group(0) @binding(0) var<uniform> params: ResolveParams;
// The splat's sums, row-major, one per pixel of the view.
@group(0) @binding(1) var<storage, read> weighted: array<vec4<f32>>;
@group(0) @binding(2) var<storage, read> plain: array<vec4<f32>>;
@group(0) @binding(3) var out_indirect: texture_storage_2d<rgba32float, write>;

const PI: f32 = 3.14159265358979;

@compute @workgroup_size(8, 8, 1)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = textureDimensions(out_indirect);
    if id.x >= size.x || id.y >= size.y {
        return;
    }
    let pixel = id.y * size.x + id.x;
    let w = weighted[pixel];
    var e = vec3<f32>(0.0);
    if w.a > 0.0 {
        if params.mode.x == 1u {
            e = w.rgb / w.a;
        } else {
            e = plain[pixel].rgb / w.a;
        }
    }
    textureStore(out_indirect, id.xy, vec4<f32>(e / PI, 1.0));
}
