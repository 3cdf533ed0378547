//! glTF import: lights, cameras, hierarchy, GLB, computed normals, and every error case ending in
//! a typed error that names the file (never a panic).

use crate::common;

use std::path::{Path, PathBuf};

use bouncelab::import::writer::{GltfWriter, NodeDesc};
use bouncelab::import::{self, ImportError, import_gltf};
use bouncelab::scene::{LightKind, MeshSource};
use glam::{Quat, Vec3};
use serde_json::{Value, json};

fn temp_dir(name: &str) -> PathBuf {
    common::temp_dir("gltf", name)
}

fn write(dir: &Path, name: &str, doc: &Value) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, serde_json::to_vec_pretty(doc).expect("json")).expect("write");
    path
}

/// One triangle facing +Y (CCW seen from above), optionally without normals.
fn triangle_doc(normals: bool) -> GltfWriter {
    let mut w = GltfWriter::default();
    let m = w.material("grey", [0.5, 0.5, 0.5, 1.0]);
    let p = [Vec3::new(0.0, 0.0, 0.0), Vec3::new(0.0, 0.0, 1.0), Vec3::new(1.0, 0.0, 0.0)];
    let n = [Vec3::Y; 3];
    let mesh = w.mesh("tri", &p, normals.then_some(&n[..]), &[0, 1, 2], Some(m));
    w.node(NodeDesc { name: "tri".into(), mesh: Some(mesh), ..NodeDesc::default() }, true);
    w
}

fn expect_err(dir: &Path, name: &str, doc: &Value, needle: &str) -> ImportError {
    let path = write(dir, name, doc);
    let err = import_gltf(&path).expect_err("import must fail");
    let msg = err.to_string();
    assert!(msg.contains(name), "error does not name the file: {msg}");
    assert!(msg.to_lowercase().contains(&needle.to_lowercase()), "error {msg:?} does not mention {needle:?}");
    err
}

#[test]
fn lights_and_camera_follow_khr_conventions() {
    let dir = temp_dir("lights");
    let mut w = triangle_doc(true);
    let p = w.light("bulb", "point", [1.0, 0.5, 0.25], 4.0, None);
    let s = w.light("spot", "spot", [1.0, 1.0, 1.0], 8.0, Some((0.1, 0.7)));
    let d = w.light("sun", "directional", [1.0, 1.0, 1.0], 3.0, None);
    let c = w.camera(0.8, 0.1, Some(50.0));
    let down = Quat::from_rotation_x(-std::f32::consts::FRAC_PI_2);
    w.node(
        NodeDesc {
            name: "p".into(),
            light: Some(p),
            translation: Some(Vec3::new(1.0, 2.0, 3.0)),
            ..NodeDesc::default()
        },
        true,
    );
    w.node(
        NodeDesc {
            name: "s".into(),
            light: Some(s),
            translation: Some(Vec3::Y),
            rotation: Some(down),
            ..NodeDesc::default()
        },
        true,
    );
    w.node(NodeDesc { name: "d".into(), light: Some(d), rotation: Some(down), ..NodeDesc::default() }, true);
    w.node(
        NodeDesc {
            name: "cam".into(),
            camera: Some(c),
            translation: Some(Vec3::new(0.0, 1.0, 5.0)),
            ..NodeDesc::default()
        },
        true,
    );
    let asset = import_gltf(&write(&dir, "lights.gltf", &w.to_json())).expect("imports");
    let lights = &asset.scene.lights;
    assert_eq!(lights.len(), 3);
    assert_eq!(lights[0].kind, LightKind::Point);
    assert!((lights[0].position - Vec3::new(1.0, 2.0, 3.0)).length() < 1e-6);
    assert_eq!(
        lights[0].radiant(),
        Vec3::new(4.0, 2.0, 1.0),
        "colour x intensity in W/sr, no conversion (the writer records radiometric units)"
    );
    assert_eq!(lights[1].kind, LightKind::Spot { inner_cone_angle: 0.1, outer_cone_angle: 0.7 });
    assert!((lights[1].direction - Vec3::NEG_Y).length() < 1e-5, "spot points down its node's -Z");
    assert_eq!(lights[2].kind, LightKind::Directional);
    assert!((lights[2].direction - Vec3::NEG_Y).length() < 1e-5);
    assert!(asset.has_camera);
    let cam = asset.scene.camera;
    assert_eq!((cam.yfov, cam.znear, cam.zfar), (0.8, 0.1, Some(50.0)));
    assert!((cam.position - Vec3::new(0.0, 1.0, 5.0)).length() < 1e-6);
    assert!((cam.forward() - Vec3::NEG_Z).length() < 1e-6);
}

#[test]
fn hierarchy_transforms_compose() {
    let dir = temp_dir("hierarchy");
    let mut w = triangle_doc(true);
    let child = w.node(
        NodeDesc {
            name: "child".into(),
            mesh: Some(0),
            translation: Some(Vec3::new(1.0, 0.0, 0.0)),
            ..NodeDesc::default()
        },
        false,
    );
    let parent_rot = Quat::from_rotation_y(std::f32::consts::FRAC_PI_2);
    w.node(
        NodeDesc {
            name: "parent".into(),
            translation: Some(Vec3::new(0.0, 2.0, 0.0)),
            rotation: Some(parent_rot),
            scale: Some(Vec3::splat(2.0)),
            children: vec![child],
            ..NodeDesc::default()
        },
        true,
    );
    let asset = import_gltf(&write(&dir, "hier.gltf", &w.to_json())).expect("imports");
    let scene = import::scene_from_asset(&asset).expect("resolves");
    let obj = scene.objects().iter().find(|o| o.name == "child").expect("child object");
    // Child origin: parent T * R * S * (1,0,0) = (0,2,0) + R(2,0,0) = (0, 2, -2).
    let origin = obj.transform.matrix().transform_point3(Vec3::ZERO);
    assert!((origin - Vec3::new(0.0, 2.0, -2.0)).length() < 1e-5, "got {origin}");
    assert!(!asset.has_camera);
    assert!(scene.camera().validate().is_ok(), "a framing camera is made when the file has none");
}

#[test]
fn mirrored_nodes_bake_and_keep_front_faces() {
    let dir = temp_dir("mirror");
    let mut w = triangle_doc(true);
    w.node(
        NodeDesc {
            name: "mirror".into(),
            mesh: Some(0),
            scale: Some(Vec3::new(-1.0, 1.0, 1.0)),
            ..NodeDesc::default()
        },
        true,
    );
    let asset = import_gltf(&write(&dir, "mirror.gltf", &w.to_json())).expect("imports");
    let scene = import::scene_from_asset(&asset).expect("resolves");
    let obj = scene.objects().iter().find(|o| o.name == "mirror").expect("mirror object");
    assert!(matches!(obj.source, MeshSource::Asset { baked: Some(_), .. }));
    let mesh = &scene.resources().meshes[obj.mesh];
    let [a, b, c] = mesh.triangle(0);
    assert!((b - a).cross(c - a).y > 0.0, "winding flipped so the front still faces +Y");
    assert!(mesh.positions.iter().all(|p| p.x <= 0.0));
}

#[test]
fn missing_normals_are_computed_and_non_indexed_works() {
    let dir = temp_dir("normals");
    let mut doc = triangle_doc(false).to_json();
    doc["meshes"][0]["primitives"][0].as_object_mut().expect("prim").remove("indices");
    let asset = import_gltf(&write(&dir, "nonormals.gltf", &doc)).expect("imports");
    let mesh = asset.primitive(0, 0).expect("mesh");
    assert_eq!(mesh.indices, vec![0, 1, 2]);
    assert!(mesh.normals.iter().all(|n| (*n - Vec3::Y).length() < 1e-6));
}

#[test]
fn glb_container_imports() {
    let dir = temp_dir("glb");
    let mut doc = triangle_doc(true).to_json();
    // Move the embedded buffer into the GLB binary chunk.
    let uri = doc["buffers"][0]["uri"].as_str().expect("uri").to_owned();
    let data = uri.split_once(";base64,").expect("data uri").1;
    use base64::Engine as _;
    let mut bin = base64::engine::general_purpose::STANDARD.decode(data).expect("b64");
    doc["buffers"][0].as_object_mut().expect("buffer").remove("uri");
    let mut json = serde_json::to_vec(&doc).expect("json");
    while !json.len().is_multiple_of(4) {
        json.push(b' ');
    }
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let mut glb = Vec::new();
    glb.extend_from_slice(b"glTF");
    glb.extend_from_slice(&2u32.to_le_bytes());
    glb.extend_from_slice(&(total as u32).to_le_bytes());
    glb.extend_from_slice(&(json.len() as u32).to_le_bytes());
    glb.extend_from_slice(b"JSON");
    glb.extend_from_slice(&json);
    glb.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    glb.extend_from_slice(b"BIN\0");
    glb.extend_from_slice(&bin);
    let path = dir.join("tri.glb");
    std::fs::write(&path, &glb).expect("write");
    let asset = import_gltf(&path).expect("glb imports");
    assert_eq!(asset.primitive(0, 0).expect("mesh").triangle_count(), 1);
    // Truncated GLB: a named error.
    std::fs::write(&path, &glb[..glb.len() - 40]).expect("write");
    let msg = import_gltf(&path).expect_err("truncated").to_string();
    assert!(msg.contains("tri.glb"), "{msg}");
}

#[test]
fn point_and_line_primitives_are_skipped_not_fatal() {
    let dir = temp_dir("lines");
    let base = triangle_doc(true).to_json();
    // A mesh mixing triangles with lines keeps its triangles.
    let mut d = base.clone();
    let tri = d["meshes"][0]["primitives"][0].clone();
    let mut line = tri.clone();
    line["mode"] = json!(1);
    d["meshes"][0]["primitives"] = json!([tri, line]);
    let asset = import_gltf(&write(&dir, "mixed.gltf", &d)).expect("mixed mesh imports");
    assert_eq!(asset.scene.objects.len(), 1, "the triangle primitive only");
    // A file of points alone imports with nothing to render.
    let mut d = base.clone();
    d["meshes"][0]["primitives"][0]["mode"] = json!(0);
    let asset = import_gltf(&write(&dir, "points.gltf", &d)).expect("points-only file imports");
    assert!(asset.scene.objects.is_empty());
}

#[test]
fn every_error_case_is_a_named_error() {
    let dir = temp_dir("errors");
    let base = triangle_doc(true).to_json();

    let mut d = base.clone();
    d["extensionsRequired"] = json!(["KHR_draco_mesh_compression"]);
    d["extensionsUsed"] = json!(["KHR_draco_mesh_compression"]);
    expect_err(&dir, "draco.gltf", &d, "KHR_draco_mesh_compression");

    let mut d = base.clone();
    d["buffers"][0]["uri"] = json!("missing.bin");
    expect_err(&dir, "missingbuf.gltf", &d, "missing.bin");

    let mut d = base.clone();
    d["buffers"][0]["uri"] = json!("../../etc/passwd");
    expect_err(&dir, "escape.gltf", &d, "refusing");

    let mut d = base.clone();
    d["asset"]["version"] = json!("3.0");
    expect_err(&dir, "v3.gltf", &d, "version 3.0");

    let mut d = base.clone();
    d["meshes"][0]["primitives"] = json!([]);
    expect_err(&dir, "noprims.gltf", &d, "no primitives");

    let mut d = base.clone();
    d["nodes"][0]["rotation"] = json!([0.0, 0.0, 0.0, 0.0]);
    expect_err(&dir, "zeroquat.gltf", &d, "unit quaternion");

    let mut d = base.clone();
    d["accessors"][0]["count"] = json!(1_000_000);
    expect_err(&dir, "bounds.gltf", &d, "past the end");

    let mut d = base.clone();
    d["buffers"][0]["byteLength"] = json!(1 << 20);
    expect_err(&dir, "short.gltf", &d, "declares");

    // NaN position: patch the first float of the buffer.
    let mut d = base.clone();
    let uri = d["buffers"][0]["uri"].as_str().expect("uri").to_owned();
    use base64::Engine as _;
    let mut bytes =
        base64::engine::general_purpose::STANDARD.decode(uri.split_once(";base64,").expect("b64").1).expect("b64");
    bytes[0..4].copy_from_slice(&f32::NAN.to_le_bytes());
    d["buffers"][0]["uri"] = json!(format!(
        "data:application/octet-stream;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(&bytes)
    ));
    expect_err(&dir, "nan.gltf", &d, "not finite");

    // Index out of range: patch the index buffer (last 12 bytes) to 7.
    let mut d = base.clone();
    let n = bytes.len();
    let mut b2 =
        base64::engine::general_purpose::STANDARD.decode(uri.split_once(";base64,").expect("b64").1).expect("b64");
    b2[n - 4..].copy_from_slice(&7u32.to_le_bytes());
    d["buffers"][0]["uri"] = json!(format!(
        "data:application/octet-stream;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(&b2)
    ));
    expect_err(&dir, "index.gltf", &d, "out of range");

    // An attribute naming a missing accessor (gltf-json itself would panic on POSITION).
    let mut d = base.clone();
    d["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = json!(42);
    expect_err(&dir, "attr.gltf", &d, "refers to accessor 42");

    // Float indices.
    let mut d = base.clone();
    d["accessors"][2]["componentType"] = json!(5126);
    expect_err(&dir, "floatidx.gltf", &d, "unsigned");

    // NaN node transform.
    let mut d = base.clone();
    d["nodes"][0]["translation"] = json!([0.0, 1e39, 0.0]);
    expect_err(&dir, "nantransform.gltf", &d, "node 0");

    // A cycle in the node graph.
    let mut d = base.clone();
    d["nodes"] = json!([{"name": "a", "children": [1]}, {"name": "b", "children": [0], "mesh": 0}]);
    d["scenes"] = json!([{"nodes": [0]}]);
    let path = write(&dir, "cycle.gltf", &d);
    let msg = import_gltf(&path).expect_err("cycle").to_string();
    assert!(msg.contains("cycle.gltf"), "{msg}");

    // Light with a NaN intensity and a bad cone.
    let mut d = base.clone();
    d["extensionsUsed"] = json!(["KHR_lights_punctual"]);
    d["extensions"] = json!({"KHR_lights_punctual": {"lights": [{"type": "spot", "spot": {"innerConeAngle": 0.9, "outerConeAngle": 0.5}}]}});
    d["nodes"][0]["extensions"] = json!({"KHR_lights_punctual": {"light": 0}});
    let path = write(&dir, "badspot.gltf", &d);
    let msg = import_gltf(&path).expect_err("bad cone").to_string();
    assert!(msg.contains("badspot.gltf"), "{msg}");

    // Not JSON at all, and an empty file.
    std::fs::write(dir.join("garbage.gltf"), b"{ this is not json").expect("write");
    let msg = import_gltf(&dir.join("garbage.gltf")).expect_err("garbage").to_string();
    assert!(msg.contains("garbage.gltf") && msg.contains("not a valid glTF"), "{msg}");
    std::fs::write(dir.join("empty.glb"), b"").expect("write");
    assert!(import_gltf(&dir.join("empty.glb")).expect_err("empty").to_string().contains("empty.glb"));
    let msg = import_gltf(&dir.join("nope.gltf")).expect_err("missing").to_string();
    assert!(msg.contains("nope.gltf"), "{msg}");
}

/// Found by fuzzing (`tools/fuzz.sh gltf_import`): a GLB whose header declares fewer bytes than
/// the header itself made the gltf crate subtract past zero (a panic in debug builds).
#[test]
fn a_glb_header_declaring_a_bad_length_is_a_named_error() {
    let json = br#"{"asset":{"version":"2.0"}}  "#;
    for declared in [0u32, 11, 10_000] {
        let mut bytes = b"glTF".to_vec();
        bytes.extend(2u32.to_le_bytes());
        bytes.extend(declared.to_le_bytes());
        bytes.extend((json.len() as u32).to_le_bytes());
        bytes.extend(0x4E4F_534Au32.to_le_bytes());
        bytes.extend(json);
        let path = Path::new("fuzzed.glb");
        match import::import_slice(&bytes, Path::new("."), path) {
            Err(ImportError::Parse { path: p, message }) => {
                assert_eq!(p, path);
                assert!(message.contains("GLB header declares"), "{message}");
            }
            Err(other) => panic!("declared {declared}: {other}"),
            Ok(_) => panic!("declared {declared}: imported"),
        }
    }
}
