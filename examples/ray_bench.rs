//! Rays a second through the reference tracer's BVH, apart from shading: the surfaces its own
//! paths meet in a suite scene (or a glTF file), each sending a cosine-distributed bounce ray
//! (closest hit) and a shadow ray to every punctual light (any hit). One thread, so the figure
//! is a core's; the tracer's own rays/s (`render --mode reference`) adds shading and sampling.
//!
//! `cargo run --release --example ray_bench -- rooms --rays 1000000`

use std::path::Path;
use std::time::Instant;

use bouncelab::precompute::brdf::Surface;
use bouncelab::precompute::pathtracer::PathTracer;
use bouncelab::precompute::rng::Pcg32;
use bouncelab::precompute::sampler::PathSampler;
use bouncelab::settings::ReferenceSettings;
use bouncelab::suite;
use glam::Vec3;

/// Rays a second through the reference tracer's BVH.
#[derive(clap::Parser)]
struct Args {
    /// Suite scene name or glTF path.
    #[arg(default_value = "rooms")]
    scene: String,
    /// Bounce rays (and as many shadow rays per light) to time.
    #[arg(long, default_value_t = 1_000_000)]
    rays: usize,
}

fn main() -> anyhow::Result<()> {
    let args = <Args as clap::Parser>::parse();
    let project = if args.scene.ends_with(".gltf") || args.scene.ends_with(".glb") {
        bouncelab::project_file::Project::from_gltf(Path::new(&args.scene))?.scene
    } else {
        suite::scene(&args.scene)?.load(Path::new("."))?.scene
    };
    let size = (160, 90);
    let tracer = PathTracer::new(&project, size, ReferenceSettings::default());
    let lights: Vec<Vec3> = project.lights().iter().map(|l| l.position).collect();
    // The surfaces the tracer's own paths meet.
    let mut vertices = Vec::new();
    let mut pixel = 0u64;
    while vertices.len() < args.rays {
        let (x, y) = ((pixel % 160) as f32, ((pixel / 160) % 90) as f32);
        let mut s = PathSampler::new(7, pixel, (pixel / 14_400) as u32);
        let dir = tracer.camera_ray(x, y, &mut s);
        tracer.walk(tracer.camera().position, dir, &mut s, |v| vertices.push((v.p, v.ng)));
        pixel += 1;
    }
    let bvh = tracer.bvh();
    let eps = 1e-4 * bvh.scale;
    let mut rng = Pcg32::new(3, 0, 0);
    let rays: Vec<(Vec3, Vec3)> = vertices
        .iter()
        .filter_map(|&(p, n)| {
            // A white Lambertian surface: the tracer's own cosine-distributed bounce.
            let diffuse = Surface { albedo: Vec3::ONE, specular: Vec3::ZERO, exponent: 1.0, n };
            let d = diffuse.sample(n, (rng.next_f32(), rng.next_f32()), 1.0)?;
            Some((p + n * eps, d))
        })
        .collect();
    let start = Instant::now();
    let hits = rays.iter().filter(|(o, d)| bvh.trace(*o, *d, f32::INFINITY).is_some()).count();
    let closest = start.elapsed().as_secs_f64();
    let start = Instant::now();
    let mut blocked = 0usize;
    for light in &lights {
        for (o, _) in &rays {
            let to = *light - *o;
            let dist = to.length();
            blocked += usize::from(bvh.trace_occluded(*o, to / dist, dist));
        }
    }
    let any = start.elapsed().as_secs_f64();
    let shadow = rays.len() * lights.len();
    println!(
        "{}: {} triangles; closest {:.1} ns a ray ({:.2} Mrays/s, {hits} hit); \
         shadow {:.1} ns a ray ({:.2} Mrays/s, {blocked} of {shadow} blocked)",
        args.scene,
        bvh.tris.len(),
        closest * 1e9 / rays.len() as f64,
        rays.len() as f64 / closest / 1e6,
        any * 1e9 / shadow.max(1) as f64,
        shadow as f64 / any.max(1e-9) / 1e6,
    );
    Ok(())
}
