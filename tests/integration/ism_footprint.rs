//! The splat pass's footprint (`shaders/render/gi/ism/ism_footprint.wgsl`, used by
//! `ism_splat.wgsl`): each row's column span, which the texel loop walks instead of the bounding
//! box, holds every texel the footprint test covers, and skips a good part of the box. The
//! shader's own functions run here on random and degenerate footprints.

use crate::common;

use bouncelab::render::readback::read_buffer;
use bouncelab::render::shaders::assemble;

/// Per footprint: the centre and the two tangent radii's images (texels), as the splat gets
/// them; out: texels covered but outside their row's span, box iterations, span iterations,
/// texels covered.
const KERNEL: &str = r#"
@group(0) @binding(0) var<storage, read> shapes: array<vec4<f32>>;
@group(0) @binding(1) var<storage, read_write> counts: array<vec4<u32>>;

@compute @workgroup_size(64, 1, 1)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= arrayLength(&counts) {
        return;
    }
    let a = shapes[2u * id.x];
    let b = shapes[2u * id.x + 1u];
    let centre = a.xy;
    let m = footprint_moments(a.zw, b.xy);
    let ext = min(vec2<f32>(sqrt(m.x), sqrt(m.z)), vec2<f32>(16.0));
    let lo = vec2<i32>(floor(centre - ext));
    let hi = vec2<i32>(floor(centre + ext));
    var c = vec4<u32>(0u);
    for (var y = lo.y; y <= hi.y; y = y + 1) {
        let span = row_span(centre, y, m.x, m.y, m.z, m.w);
        for (var x = lo.x; x <= hi.x; x = x + 1) {
            c.y = c.y + 1u;
            let in_span = x >= span.x && x <= span.y;
            c.z = c.z + select(0u, 1u, in_span);
            if footprint_covers(centre, x, y, m.x, m.y, m.z, m.w) {
                c.w = c.w + 1u;
                c.x = c.x + select(1u, 0u, in_span);
            }
        }
    }
    counts[id.x] = c;
}
"#;

/// A compute pipeline of `entry` in WGSL `source`, its layout derived from the shader.
fn test_pipeline(device: &wgpu::Device, label: &str, source: String, entry: &str) -> wgpu::ComputePipeline {
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(label),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some(label),
        layout: None,
        module: &module,
        entry_point: Some(entry),
        compilation_options: Default::default(),
        cache: None,
    })
}

/// A small deterministic generator (xorshift), so that a failure repeats.
struct Rng(u32);

impl Rng {
    fn next(&mut self) -> f32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 17;
        self.0 ^= self.0 << 5;
        (self.0 >> 8) as f32 / (1u32 << 24) as f32
    }
}

/// Footprints as the splat meets them: disks of 0-12 texels seen at any angle (their tangent
/// images of any length and direction, edge-on ones nearly parallel), centred anywhere in a
/// texel, plus exact edge cases (points, texel-centred and axis-aligned ones).
fn footprints(n: usize) -> Vec<[f32; 8]> {
    let mut rng = Rng(0x9e37_79b9);
    let mut out = vec![
        [64.0, 64.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [64.5, 64.5, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [10.5, 20.5, 3.0, 0.0, 0.0, 3.0, 0.0, 0.0],
        [10.0, 20.0, 2.5, 0.0, 0.0, 0.5, 0.0, 0.0],
        [33.25, 7.75, 8.0, 8.0, 0.01, -0.01, 0.0, 0.0],
    ];
    while out.len() < n {
        let (cx, cy) = (128.0 * rng.next(), 128.0 * rng.next());
        let radius = 12.0 * rng.next().powi(2);
        let angle = std::f32::consts::TAU * rng.next();
        let tilt = if rng.next() < 0.2 { 1e-3 * rng.next() } else { rng.next() };
        let (ta, tb) =
            ([radius * angle.cos(), radius * angle.sin()], [-radius * tilt * angle.sin(), radius * tilt * angle.cos()]);
        out.push([cx, cy, ta[0], ta[1], tb[0], tb[1], 0.0, 0.0]);
    }
    out
}

#[test]
fn row_spans_keep_every_covered_texel_and_skip_the_bounding_boxes_corners() {
    let Some(ctx) = common::gpu() else { return };
    let device = &ctx.device;
    let source = assemble("render/gi/ism/ism_footprint.wgsl").expect("footprint shader") + KERNEL;
    let pipeline = test_pipeline(device, "ism footprint test", source, "main");
    let shapes = footprints(20_000);
    let input = wgpu::util::DeviceExt::create_buffer_init(
        device,
        &wgpu::util::BufferInitDescriptor {
            label: Some("ism footprint test shapes"),
            contents: bytemuck::cast_slice(&shapes),
            usage: wgpu::BufferUsages::STORAGE,
        },
    );
    let output = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("ism footprint test counts"),
        size: shapes.len() as u64 * 16,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("ism footprint test"),
        layout: &pipeline.get_bind_group_layout(0),
        entries: &[
            wgpu::BindGroupEntry { binding: 0, resource: input.as_entire_binding() },
            wgpu::BindGroupEntry { binding: 1, resource: output.as_entire_binding() },
        ],
    });
    let mut encoder = device.create_command_encoder(&Default::default());
    {
        let mut pass = encoder.begin_compute_pass(&Default::default());
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &group, &[]);
        pass.dispatch_workgroups((shapes.len() as u32).div_ceil(64), 1, 1);
    }
    ctx.queue.submit([encoder.finish()]);
    let bytes = read_buffer(device, &ctx.queue, &output).expect("counts");
    let counts: &[[u32; 4]] = bytemuck::cast_slice(&bytes);
    let sum = |k: usize| counts.iter().map(|c| u64::from(c[k])).sum::<u64>();
    let (dropped, boxed, spanned, covered) = (sum(0), sum(1), sum(2), sum(3));
    eprintln!(
        "{} footprints: {covered} texels covered, {boxed} box iterations, {spanned} span iterations",
        counts.len()
    );
    let worst = counts.iter().zip(&shapes).find(|(c, _)| c[0] > 0);
    assert_eq!(dropped, 0, "row spans dropped covered texels, e.g. footprint {:?}", worst.map(|w| w.1));
    assert!(covered >= counts.len() as u64, "every footprint covers at least its own texel");
    assert!(spanned < boxed * 3 / 4, "the spans walk {spanned} of the boxes' {boxed} texels");
}

/// Slots per VPL, VPLs (tiles), tile side and tiles per row of the splat test's atlas.
const P: u32 = 512;
const VPLS: u32 = 4;
const TILE: u32 = 128;
const PER_ROW: u32 = 2;

/// The splat test's scene: four VPLs (one dead) on the floor of a 4 m box looking up, each
/// with P points of its own, some beside it (footprints of the 33 rows the half-extent allows),
/// some seen edge-on or from behind, some unchosen, about half with clip lines. Returns the
/// buffers in binding order 1..=6 (points, VPLs, normals, chosen, clips) as raw words.
fn splat_scene() -> [Vec<u32>; 5] {
    let mut rng = Rng(0x2545_f491);
    let (mut points, mut normals, mut chosen, mut clips) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let mut vpls = Vec::new();
    for k in 0..VPLS {
        let o = [0.5 + k as f32, 0.0, 1.0 + 0.3 * k as f32];
        let alive = if k == 2 { 0.0 } else { 0.01 };
        // position, normal, power, incident, gloss.
        vpls.extend([o[0], o[1], o[2], alive, 0.0, 1.0, 0.0, 0.0]);
        vpls.extend([1.0f32, 1.0, 1.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
        for i in 0..P {
            let near = rng.next() < 0.1;
            let reach = if near { 0.05 + 0.2 * rng.next() } else { 4.0 * rng.next() };
            let dir = [rng.next() * 2.0 - 1.0, rng.next(), rng.next() * 2.0 - 1.0];
            let len = (dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]).sqrt().max(1e-3);
            let p = [o[0] + reach * dir[0] / len, o[1] + reach * dir[1] / len, o[2] + reach * dir[2] / len];
            points.extend([p[0], p[1], p[2], 1.0]);
            let n = match i % 4 {
                0 => [0.0, -1.0, 0.0],
                1 => [1.0, 0.0, 0.0],
                2 => [0.0, 0.0, -1.0],
                _ => [0.0, 1.0, 0.0],
            };
            normals.extend([n[0], n[1], n[2], 1.0]);
            let area = if near { 0.02 * rng.next() } else { 0.2 * rng.next() };
            let j = k * P + i;
            chosen.extend(if rng.next() < 0.05 { [u32::MAX, 0] } else { [j, area.to_bits()] });
            for _ in 0..4 {
                let line = if rng.next() < 0.3 {
                    [rng.next() - 0.5, rng.next() - 0.5, rng.next() - 0.5, 0.2 * rng.next() - 0.1]
                } else {
                    [0.0, 0.0, 0.0, -1.0]
                };
                clips.extend(line);
            }
        }
    }
    let words = |v: Vec<f32>| v.into_iter().map(f32::to_bits).collect::<Vec<u32>>();
    [words(points), words(vpls), words(normals), chosen, words(clips)]
}

/// Runs entry point `entry` of `ism_splat.wgsl` on [`splat_scene`] into a cleared atlas.
fn splat_atlas(ctx: &bouncelab::render::GpuContext, entry: &str) -> Vec<u32> {
    use wgpu::util::DeviceExt;
    let device = &ctx.device;
    let source = assemble("render/gi/ism/ism_splat.wgsl").expect("splat shader");
    let pipeline = test_pipeline(device, "ism splat test", source, entry);
    let init = |label: &str, words: &[u32], usage: wgpu::BufferUsages| {
        device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents: bytemuck::cast_slice(words),
            usage,
        })
    };
    // counts (VPLs, P, tile side, tiles per row), params (1 / d_max, radius^2 / pi per m^2,
    // max half-extent, unused), sets (first VPL).
    let params: [u32; 12] = [
        VPLS,
        P,
        TILE,
        PER_ROW,
        (1.0f32 / 8.0).to_bits(),
        (1.35f32 * 1.35 / std::f32::consts::PI).to_bits(),
        16.0f32.to_bits(),
        0,
        0,
        0,
        0,
        0,
    ];
    let uniform = init("ism splat test params", &params, wgpu::BufferUsages::UNIFORM);
    let storage = wgpu::BufferUsages::STORAGE;
    let side = TILE * PER_ROW;
    let rows = VPLS.div_ceil(PER_ROW) * TILE;
    let atlas =
        init("ism splat test atlas", &vec![u32::MAX; (side * rows) as usize], storage | wgpu::BufferUsages::COPY_SRC);
    let [points, vpls, normals, chosen, clips] = splat_scene();
    let buffers = [
        init("points", &points, storage),
        init("vpls", &vpls, storage),
        init("normals", &normals, storage),
        init("chosen", &chosen, storage),
        init("clips", &clips, storage),
    ];
    let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("ism splat test"),
        layout: &pipeline.get_bind_group_layout(0),
        entries: &[
            wgpu::BindGroupEntry { binding: 0, resource: uniform.as_entire_binding() },
            wgpu::BindGroupEntry { binding: 1, resource: buffers[0].as_entire_binding() },
            wgpu::BindGroupEntry { binding: 2, resource: buffers[1].as_entire_binding() },
            wgpu::BindGroupEntry { binding: 3, resource: atlas.as_entire_binding() },
            wgpu::BindGroupEntry { binding: 4, resource: buffers[2].as_entire_binding() },
            wgpu::BindGroupEntry { binding: 5, resource: buffers[3].as_entire_binding() },
            wgpu::BindGroupEntry { binding: 6, resource: buffers[4].as_entire_binding() },
        ],
    });
    let mut encoder = device.create_command_encoder(&Default::default());
    {
        let mut pass = encoder.begin_compute_pass(&Default::default());
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &group, &[]);
        pass.dispatch_workgroups((VPLS * P).div_ceil(64), 1, 1);
    }
    ctx.queue.submit([encoder.finish()]);
    let bytes = read_buffer(device, &ctx.queue, &atlas).expect("atlas");
    bytemuck::cast_slice(&bytes).to_vec()
}

/// The splat pass deals each workgroup's footprint texels out among its threads (`splat` in
/// `ism_splat.wgsl`); the atlas it writes must be the one a thread per point walking its
/// whole footprint writes (`splat_per_point`), word for word: the same texels with the same
/// depths and points, whatever the order (an atomic min).
#[test]
fn the_balanced_splat_writes_exactly_the_atlas_of_a_thread_per_point() {
    let Some(ctx) = common::gpu() else { return };
    let reference = splat_atlas(&ctx, "splat_per_point");
    let balanced = splat_atlas(&ctx, "splat");
    let written = reference.iter().filter(|w| **w != u32::MAX).count();
    let differ = reference.iter().zip(&balanced).filter(|(a, b)| a != b).count();
    eprintln!("{written} texels written of {}; {differ} differ", reference.len());
    assert!(written > 20_000, "the test scene splats too little to judge ({written} texels)");
    // VPL 2 is dead: its tile (column 0, row 1 of tiles) stays empty.
    let side = (TILE * PER_ROW) as usize;
    let in_dead = (TILE as usize..2 * TILE as usize)
        .flat_map(|y| (0..TILE as usize).map(move |x| y * side + x))
        .filter(|&i| reference[i] != u32::MAX)
        .count();
    assert_eq!(in_dead, 0, "the dead VPL's tile got splats");
    assert_eq!(differ, 0, "the balanced splat differs from a thread per point in {differ} texels");
}
