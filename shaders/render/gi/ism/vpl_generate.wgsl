// ISM pass P5: first-bounce VPLs by hierarchical warping (Knecht 2009 section 3.3) over the
// light G-buffer of every light (one tile per spot or directional light, six per point light),
// so the VPLs spread over the lights in proportion to the power they reflect (times the first
// set's seen weight where the camera sees the surface, `seed_viewed` in `importance.wgsl`). One thread
// per VPL: a Halton point of this frame's window descends the importance pyramid from the 2x2
// level to the finest (rows first, then the column within the row), lands in texel t with
// probability p(t) = importance(t) / total, and becomes a VPL on the surface that texel sees,
// carrying the unbiased power rho I dOmega n^2 / (N p(t)); the thesis gives no normalisation
// (sections 4.4 and 4.5), and n^2 is there because a pixel shades only the N / n^2 VPLs of its
// interleave tile (section 3.4.1).
#import common/vpl.wgsl
#import render/gi/ism/ism_light_texel.wgsl

struct GenParams {
    // VPL count, frame index, interleave n, pyramid levels K (finest side = 2^K).
    counts: vec4<u32>,
    // tiles per row, tile side in texels, tile count, unused.
    tiles: vec4<u32>,
}

@group(0) @binding(0) var<uniform> params: GenParams;
@group(0) @binding(1) var importance: texture_2d<f32>;
@group(0) @binding(2) var albedo_tex: texture_2d<f32>;
@group(0) @binding(3) var normal_tex: texture_2d<f32>;
@group(0) @binding(4) var power_tex: texture_2d<f32>;
@group(0) @binding(5) var depth_tex: texture_depth_2d;
@group(0) @binding(6) var<storage, read_write> vpls: array<Vpl>;
@group(0) @binding(7) var specular_tex: texture_2d<f32>;
@group(0) @binding(8) var<storage, read> tile_records: array<TileRecord>;
@group(0) @binding(9) var<storage, read> emitter_points: array<EmitterPoint>;

const PI: f32 = 3.14159265358979;

fn radical_inverse_2(i: u32) -> f32 {
    return f32(reverseBits(i) >> 8u) / 16777216.0;
}

fn radical_inverse_3(i_in: u32) -> f32 {
    var i = i_in;
    var f = 1.0 / 3.0;
    var r = 0.0;
    while i > 0u {
        r = r + f * f32(i % 3u);
        i = i / 3u;
        f = f / 3.0;
    }
    return r;
}

fn imp(level: u32, c: vec2<u32>) -> f32 {
    return textureLoad(importance, c, i32(params.counts.w - level)).r;
}

@compute @workgroup_size(64, 1, 1)
fn cs_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let n_vpl = params.counts.x;
    let k = id.x;
    if k >= n_vpl {
        return;
    }
    let index = params.counts.y * n_vpl + k + 1u;
    var s = vec2<f32>(radical_inverse_2(index), radical_inverse_3(index));
    var lo = vec2<f32>(0.0);
    var hi = vec2<f32>(1.0);
    var cell = vec2<u32>(0u);
    for (var l = 1u; l <= params.counts.w; l = l + 1u) {
        let c = cell * 2u;
        let q00 = imp(l, c);
        let q10 = imp(l, c + vec2<u32>(1u, 0u));
        let q01 = imp(l, c + vec2<u32>(0u, 1u));
        let q11 = imp(l, c + vec2<u32>(1u, 1u));
        let sum = q00 + q10 + q01 + q11;
        var p_row0 = 0.5;
        if sum > 0.0 {
            p_row0 = (q00 + q10) / sum;
        }
        let mid = 0.5 * (lo + hi);
        var t = (s.y - lo.y) / (hi.y - lo.y);
        var dy = 0u;
        if t < p_row0 {
            t = t / p_row0;
            hi.y = mid.y;
        } else {
            t = (t - p_row0) / (1.0 - p_row0);
            lo.y = mid.y;
            dy = 1u;
        }
        s.y = lo.y + t * (hi.y - lo.y);
        var a = q00;
        var b = q10;
        if dy == 1u {
            a = q01;
            b = q11;
        }
        var p_col0 = 0.5;
        if a + b > 0.0 {
            p_col0 = a / (a + b);
        }
        var u = (s.x - lo.x) / (hi.x - lo.x);
        var dx = 0u;
        if u < p_col0 {
            u = u / p_col0;
            hi.x = mid.x;
        } else {
            u = (u - p_col0) / (1.0 - p_col0);
            lo.x = mid.x;
            dx = 1u;
        }
        s.x = lo.x + u * (hi.x - lo.x);
        cell = c + vec2<u32>(dx, dy);
    }
    let size = 1u << params.counts.w;
    let total = textureLoad(importance, vec2<u32>(0u), i32(params.counts.w)).r;
    let texel_imp = textureLoad(importance, cell, 0).r;
    var out: Vpl;
    out.incident = vec4<f32>(0.0, 0.0, 0.0, f32(cell.y * size + cell.x));
    if total <= 0.0 || texel_imp <= 0.0 {
        vpls[k] = out;
        return;
    }
    let pdf = texel_imp / total;
    let ts = params.tiles.y;
    let record = tile_records[tile_of(cell, params.tiles.xyz)];
    let interleave = f32(params.counts.z);
    let scale = interleave * interleave / (f32(n_vpl) * pdf);
    if is_emitter_tile(record) {
        // An emitter candidate: a Lambertian VPL of power pi L A on the emitter's front face.
        let e = emitter_points[candidate_of(record, cell, ts, arrayLength(&emitter_points))];
        out.position = vec4<f32>(e.position.xyz, max(e.position.w / (f32(n_vpl) * pdf) / PI, 1.0e-20));
        out.normal = vec4<f32>(e.normal.xyz, 0.0);
        out.power = vec4<f32>(e.power.rgb * scale, pdf);
        out.gloss = vec4<f32>(0.0);
        out.incident = vec4<f32>(e.normal.xyz, f32(cell.y * size + cell.x));
        vpls[k] = out;
        return;
    }
    let p = light_texel_position(record, cell, ts, textureLoad(depth_tex, cell, 0));
    let reflected = textureLoad(power_tex, cell, 0).rgb;
    let nt = textureLoad(normal_tex, cell, 0);
    // The VPL stands for a disk of the area its texel's patch covers among N draws: A / (N p).
    let disk_area = nt.w / (f32(n_vpl) * pdf);
    out.position = vec4<f32>(p, max(disk_area / PI, 1.0e-20));
    out.normal = vec4<f32>(normalize(nt.xyz), textureLoad(albedo_tex, cell, 0).a);
    out.power = vec4<f32>(reflected * scale, pdf);
    let spec = textureLoad(specular_tex, cell, 0);
    out.gloss = vec4<f32>(spec.rgb * scale, spec.a);
    var towards = normalize(record.light.xyz - p);
    if record.light.w > 0.5 {
        towards = record.light.xyz;
    }
    out.incident = vec4<f32>(towards, f32(cell.y * size + cell.x));
    vpls[k] = out;
}
