//! Textured glTF materials: base colour textures (sRGB) and normal maps import, and the raster
//! G-buffer and the path tracer read the same texels.

use crate::common;

use std::sync::atomic::AtomicBool;

use base64::Engine as _;
use bouncelab::import::{import_gltf, scene_from_asset};
use bouncelab::precompute::pathtracer::PathTracer;
use bouncelab::render::Renderer;
use bouncelab::scene::{Camera, Light};
use bouncelab::settings::{ReferenceSettings, RenderSettings};
use glam::Vec3;
use serde_json::json;

fn png_data_uri(w: u32, h: u32, f: impl Fn(u32, u32) -> [u8; 4]) -> String {
    let img = image::RgbaImage::from_fn(w, h, |x, y| image::Rgba(f(x, y)));
    let mut bytes = Vec::new();
    img.write_to(&mut std::io::Cursor::new(&mut bytes), image::ImageFormat::Png).expect("png");
    format!("data:image/png;base64,{}", base64::engine::general_purpose::STANDARD.encode(bytes))
}

/// A 2x2 m floor quad facing +Y with UVs, a checker base colour and a tilted normal map.
pub(crate) fn textured_floor(path: &std::path::Path) {
    let pos: [[f32; 3]; 4] = [[-1.0, 0.0, 1.0], [1.0, 0.0, 1.0], [1.0, 0.0, -1.0], [-1.0, 0.0, -1.0]];
    let uv: [[f32; 2]; 4] = [[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]];
    let idx: [u32; 6] = [0, 1, 2, 0, 2, 3];
    let mut bin: Vec<u8> = pos.iter().flatten().flat_map(|v| v.to_le_bytes()).collect();
    let uv_off = bin.len();
    bin.extend(uv.iter().flatten().flat_map(|v| v.to_le_bytes()));
    let idx_off = bin.len();
    bin.extend(idx.iter().flat_map(|v| v.to_le_bytes()));
    // 2x2 quadrants of 2x2 texels each, so bilinear filtering inside a quadrant is exact.
    let checker = png_data_uri(4, 4, |x, y| if (x / 2 + y / 2) % 2 == 0 { [255, 0, 0, 255] } else { [0, 0, 255, 255] });
    // Normal map tilted towards +u: (0.5, 0, 0.866) encoded.
    let normal = png_data_uri(1, 1, |_, _| [191, 128, 238, 255]);
    let doc = json!({
        "asset": {"version": "2.0"},
        "scene": 0, "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2, "material": 0}]}],
        "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}, "normalTexture": {"index": 1}}],
        "textures": [{"source": 0}, {"source": 1}],
        "images": [{"uri": checker}, {"uri": normal}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1.0, 0.0, -1.0], "max": [1.0, 0.0, 1.0]},
            {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"},
            {"bufferView": 2, "componentType": 5125, "count": 6, "type": "SCALAR"}
        ],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": uv_off},
            {"buffer": 0, "byteOffset": uv_off, "byteLength": idx_off - uv_off},
            {"buffer": 0, "byteOffset": idx_off, "byteLength": bin.len() - idx_off}
        ],
        "buffers": [{"byteLength": bin.len(), "uri": format!("data:application/octet-stream;base64,{}", base64::engine::general_purpose::STANDARD.encode(&bin))}]
    });
    std::fs::write(path, serde_json::to_vec(&doc).expect("json")).expect("write");
}

#[test]
fn textures_import_and_render_alike() {
    let dir = std::env::temp_dir().join(format!("bouncelab-tex-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("dir");
    let path = dir.join("textured.gltf");
    textured_floor(&path);
    let asset = import_gltf(&path).expect("imports");
    assert_eq!(asset.images.len(), 2);
    assert_eq!((asset.images[0].width, asset.images[0].height), (4, 4));
    let mat = &asset.materials[0];
    assert!(mat.base_color_texture.is_some() && mat.normal_texture.is_some());
    let mut scene = scene_from_asset(&asset).expect("scene");
    let mesh = &scene.resources().meshes[0];
    assert!(mesh.tangents.iter().all(|t| (t.truncate() - Vec3::X).length() < 1e-5), "tangents follow +u");
    scene.desc_mut().lights = vec![Light::directional("sun", Vec3::new(0.0, -1.0, 0.0), 2.0)];
    scene.set_camera(Camera::look_at(Vec3::new(0.0, 2.07, 0.001), Vec3::ZERO, 0.9));

    // Path tracer at the centre of each checker quadrant.
    let size = (32, 32);
    let mut tracer = PathTracer::new(&scene, size, ReferenceSettings { spp: 4, max_bounces: 1, ..Default::default() });
    tracer.render(4, &AtomicBool::new(false), |_| {});
    let reference = tracer.image();
    let Some(ctx) = common::gpu() else { return };
    let mut renderer = Renderer::new(&ctx.device, &ctx.queue).expect("renderer");
    renderer.render(&scene, &RenderSettings::default(), size).expect("render");
    let albedo = renderer.read_buffer("albedo").expect("albedo");
    let raster = renderer.read_hdr().expect("hdr");
    // Quadrant centres: red and blue texels (checker), sRGB 255 -> linear 1.
    let (a, b) = (albedo.pixels[(8 * 32 + 8) as usize], albedo.pixels[(8 * 32 + 24) as usize]);
    assert!(
        (a[0] - 1.0).abs() < 0.01 && a[2] < 0.01 || (a[2] - 1.0).abs() < 0.01 && a[0] < 0.01,
        "checker texel {a:?}"
    );
    assert!((a[0] - b[2]).abs() < 0.01, "neighbouring quadrants alternate: {a:?} {b:?}");
    // The normal map tilts the shading normal by 30 degrees: radiance = albedo/pi * E * cos 30.
    let want = 1.0 / std::f32::consts::PI * 2.0 * (30f32).to_radians().cos();
    for (x, y) in [(8u32, 8u32), (24, 8), (8, 24), (24, 24)] {
        let i = (y * 32 + x) as usize;
        let (r, p) = (raster[i], reference[i]);
        let (rv, pv) = (r[0].max(r[2]), p[0].max(p[2]));
        assert!((rv - want).abs() < 0.02 * want, "raster ({x},{y}) {r:?}, want {want}");
        assert!((pv - want).abs() < 0.02 * want, "path tracer ({x},{y}) {p:?}, want {want}");
    }
}
