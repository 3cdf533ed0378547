//! Big scenes: objects with one mesh source share one mesh, and the instanced draws (one per
//! run of equal mesh and material) give every object its own matrices, id and material. The
//! 100,000-object figures are in `docs/BENCHMARKS.md` (`examples/big_scene.rs`); this test keeps
//! the instancing right at a CI-friendly size.

use crate::common;

use bouncelab::render::Renderer;
use bouncelab::scene::{Camera, Light, Material, MeshSource, Transform};
use bouncelab::settings::RenderSettings;
use glam::Vec3;

const SIDE: usize = 20;
const HEIGHTS: [f32; 3] = [0.4, 0.6, 0.8];
const BOX: f32 = 0.6;

/// The box at grid cell (i, j): its height index and material (interleaved so that batches of
/// one mesh alternate materials).
fn cell(i: usize, j: usize) -> (usize, usize) {
    ((i + 2 * j) % 3, 1 + (i + j) % 2)
}

fn centre(i: usize, j: usize) -> Vec3 {
    Vec3::new(i as f32 - 0.5 * (SIDE - 1) as f32, 0.0, j as f32 - 0.5 * (SIDE - 1) as f32)
}

#[test]
fn four_hundred_boxes_share_three_meshes_and_draw_with_their_own_id_and_material() {
    let mut objects = Vec::new();
    let (floor, floor_material) = common::floor(30.0, 0.5);
    objects.push(floor);
    for j in 0..SIDE {
        for i in 0..SIDE {
            let (h, material) = cell(i, j);
            let size = Vec3::new(BOX, HEIGHTS[h], BOX);
            let transform =
                Transform { translation: centre(i, j) + Vec3::Y * 0.5 * HEIGHTS[h], ..Transform::default() };
            objects.push(common::object(
                &format!("box {i} {j}"),
                MeshSource::Cuboid { size, openings: [false; 6] },
                material,
                transform,
            ));
        }
    }
    let materials =
        vec![floor_material, Material::diffuse("red", [0.8, 0.1, 0.1]), Material::diffuse("blue", [0.1, 0.2, 0.9])];
    let camera = Camera::look_at(Vec3::new(0.0, 40.0, 0.001), Vec3::ZERO, 0.56);
    let scene = common::scene(objects, materials, vec![Light::point("lamp", Vec3::Y * 10.0, 500.0)], camera);
    assert_eq!(scene.resources().meshes.len(), 4, "the floor and one mesh per box height");

    let Some(ctx) = common::gpu() else { return };
    let size = (128, 128);
    let mut r = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    r.render(&scene, &RenderSettings::default(), size).expect("render");
    let ids = r.read_buffer("object_id").expect("ids");
    let albedo = r.read_buffer("albedo").expect("albedo");

    let (mut checked, mut wrong_id, mut wrong_material) = (0, 0, 0);
    let mut seen = std::collections::HashSet::new();
    for y in 0..size.1 {
        for x in 0..size.0 {
            let d = camera.ray_direction(x as f32 + 0.5, y as f32 + 0.5, size.0, size.1);
            // The box whose top face this pixel's ray meets well inside its footprint (tops are
            // never hidden: at this camera a ray leans at most 0.3 m per metre, the gaps are 0.4).
            let hit = (0..SIDE * SIDE).find_map(|k| {
                let (i, j) = (k % SIDE, k / SIDE);
                let (h, material) = cell(i, j);
                let t = (HEIGHTS[h] - camera.position.y) / d.y;
                let p = camera.position + d * t - centre(i, j);
                (p.x.abs() < 0.5 * BOX - 0.05 && p.z.abs() < 0.5 * BOX - 0.05).then_some((k + 2, material))
            });
            let Some((id, material)) = hit else { continue };
            let pixel = (y * size.0 + x) as usize;
            checked += 1;
            let got = ids.pixels[pixel][0] as usize;
            seen.insert(got);
            wrong_id += usize::from(got != id);
            let want = scene.materials()[material].base_color;
            let a = albedo.pixels[pixel];
            wrong_material += usize::from((0..3).any(|c| (a[c] - want[c]).abs() > 0.02));
        }
    }
    assert!(checked > 2000, "{checked} pixels on box tops");
    assert!(wrong_id * 100 <= checked, "{wrong_id} of {checked} box-top pixels carry another object's id");
    assert!(wrong_material * 100 <= checked, "{wrong_material} of {checked} box-top pixels have another material");
    assert!(seen.len() >= 390, "{} distinct boxes seen of {}", seen.len(), SIDE * SIDE);
}
