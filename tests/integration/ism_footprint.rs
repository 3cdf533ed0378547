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
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("ism footprint test"),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("ism footprint test"),
        layout: None,
        module: &module,
        entry_point: Some("main"),
        compilation_options: Default::default(),
        cache: None,
    });
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
