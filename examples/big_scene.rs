//! Big-scene measurement for the reliability issue: a level of N props (copies of four meshes
//! of about T triangles each, on a ground plane, lit by two point lights) rendered
//! headless in the named modes. Prints, per mode, the time to the first frame (upload and any
//! precompute included), the mean time of the next frames, and the process's resident memory
//! (on the software adapter this includes every GPU allocation).
//!
//! `cargo run --release --example big_scene -- 100000 100 direct,ism 320x180 4`

use std::time::Instant;

use anyhow::Context as _;
use bouncelab::render::{GpuContext, Renderer};
use bouncelab::scene::{
    Camera, Light, Material, Mesh, MeshSource, Object, ObjectRole, Resources, Scene, SceneDesc, Transform,
};
use bouncelab::settings::{GiMode, RenderSettings};
use glam::{Quat, Vec2, Vec3, Vec4};

/// A UV sphere of `stacks * slices * 2` triangles (some degenerate at the poles), radius 0.5.
fn sphere(name: &str, stacks: u32, slices: u32) -> Mesh {
    let mut mesh = Mesh { name: name.to_owned(), ..Mesh::default() };
    for i in 0..=stacks {
        let theta = std::f32::consts::PI * i as f32 / stacks as f32;
        for j in 0..=slices {
            let phi = std::f32::consts::TAU * j as f32 / slices as f32;
            let n = Vec3::new(theta.sin() * phi.cos(), theta.cos(), theta.sin() * phi.sin());
            mesh.positions.push(n * 0.5);
            mesh.normals.push(n);
            mesh.uvs.push(Vec2::new(j as f32 / slices as f32, i as f32 / stacks as f32));
            mesh.tangents.push(Vec4::new(-phi.sin(), 0.0, phi.cos(), 1.0));
        }
    }
    let row = slices + 1;
    for i in 0..stacks {
        for j in 0..slices {
            let (a, b) = (i * row + j, (i + 1) * row + j);
            mesh.indices.extend([a, a + 1, b, a + 1, b + 1, b]);
        }
    }
    mesh
}

/// Resident and peak resident memory of this process in MiB (Linux `/proc/self/status`).
fn memory_mib() -> (f64, f64) {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    let field = |key: &str| {
        status
            .lines()
            .find(|l| l.starts_with(key))
            .and_then(|l| l.split_whitespace().nth(1))
            .and_then(|v| v.parse::<f64>().ok())
            .map_or(f64::NAN, |kib| kib / 1024.0)
    };
    (field("VmRSS:"), field("VmHWM:"))
}

fn level(count: usize, triangles: u32) -> anyhow::Result<Scene> {
    // stacks * slices * 2 = triangles with slices = 2 * stacks.
    let stacks = ((triangles as f32 / 4.0).sqrt().round() as u32).max(2);
    let meshes: Vec<Mesh> = (0..4).map(|k| sphere(&format!("prop {k}"), stacks, 2 * stacks)).collect();
    let side = (count as f32).sqrt().ceil() as usize;
    let spacing = 1.5f32;
    let extent = side as f32 * spacing;
    let mut objects: Vec<Object> = (0..count)
        .map(|i| {
            let (x, z) = ((i % side) as f32, (i / side) as f32);
            let k = i % 4;
            Object {
                name: format!("prop {i}"),
                source: MeshSource::Plane { size: 1.0 },
                mesh: k,
                material: 1 + k % 2,
                transform: Transform {
                    translation: Vec3::new((x + 0.5) * spacing - 0.5 * extent, 0.5, (z + 0.5) * spacing - 0.5 * extent),
                    rotation: Quat::from_rotation_y(i as f32),
                    scale: Vec3::splat(0.6 + 0.1 * k as f32),
                },
                sampling_weight: 1.0,
                role: ObjectRole::Static,
                visible: true,
            }
        })
        .collect();
    let mut meshes = meshes;
    objects.push(Object {
        name: "ground".into(),
        source: MeshSource::Plane { size: extent + 4.0 },
        mesh: meshes.len(),
        material: 0,
        transform: Transform::default(),
        sampling_weight: 1.0,
        role: ObjectRole::Static,
        visible: true,
    });
    meshes.push(Mesh::plane("ground", extent + 4.0));
    let h = 0.5 * extent;
    let lamp = Light::point("lamp", Vec3::new(0.0, 0.3 * extent + 3.0, 0.0), 50.0 * extent * extent);
    let desc = SceneDesc {
        materials: vec![
            Material::diffuse("ground", [0.6; 3]),
            Material::diffuse("red", [0.7, 0.2, 0.1]),
            Material::diffuse("white", [0.8; 3]),
        ],
        objects,
        lights: vec![lamp, Light::point("fill", Vec3::new(h, 4.0, h), 200.0)],
        camera: Camera::look_at(Vec3::new(0.0, 0.6 * extent + 4.0, 0.9 * extent + 4.0), Vec3::ZERO, 0.9),
        light_units: bouncelab::scene::LightUnits::Radiometric,
        environment: Default::default(),
    };
    Ok(Scene::new(desc, Resources { meshes, images: vec![], sky: None })?)
}

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().collect();
    let count: usize = args.get(1).map_or(Ok(1000), |s| s.parse()).context("object count")?;
    let triangles: u32 = args.get(2).map_or(Ok(100), |s| s.parse()).context("triangles per object")?;
    let modes = args.get(3).map_or("direct,ism", String::as_str);
    let size = args.get(4).map_or("320x180", String::as_str);
    let (w, h) = size.split_once('x').context("size as WxH")?;
    let size: (u32, u32) = (w.parse()?, h.parse()?);
    let frames: usize = args.get(5).map_or(Ok(4), |s| s.parse())?;

    let t0 = Instant::now();
    let scene = level(count, triangles)?;
    let drawn: usize = scene.objects().iter().map(|o| scene.resources().meshes[o.mesh].triangle_count()).sum();
    let (rss, _) = memory_mib();
    println!(
        "{count} objects, {drawn} triangles drawn, {} meshes; scene built in {:.2} s, RSS {rss:.0} MiB",
        scene.resources().meshes.len(),
        t0.elapsed().as_secs_f64()
    );
    let ctx = GpuContext::new_headless()?;
    println!("adapter: {}", ctx.describe());
    for name in modes.split(',') {
        let mode = GiMode::from_name(name).ok_or_else(|| anyhow::anyhow!("unknown mode {name:?}"))?;
        let settings = RenderSettings { mode, ..RenderSettings::default() };
        let mut r = Renderer::new(&ctx.device, &ctx.queue)?;
        let t = Instant::now();
        r.render(&scene, &settings, size)?;
        let _ = r.read_hdr()?;
        let first = t.elapsed().as_secs_f64();
        let t = Instant::now();
        for _ in 0..frames {
            r.render(&scene, &settings, size)?;
        }
        let pixels = r.read_hdr()?;
        let per = t.elapsed().as_secs_f64() / frames.max(1) as f64;
        let finite = pixels.iter().all(|p| p.iter().all(|c| c.is_finite()));
        let lit = pixels.iter().filter(|p| p[0] + p[1] + p[2] > 0.0).count() as f64 / pixels.len() as f64;
        let (rss, peak) = memory_mib();
        println!(
            "{name:8} first frame {first:7.2} s, then {:8.1} ms/frame; RSS {rss:6.0} MiB (peak {peak:6.0}); \
             finite {finite}, lit {:.0}%",
            per * 1e3,
            lit * 100.0
        );
    }
    Ok(())
}
