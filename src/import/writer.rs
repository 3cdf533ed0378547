//! A small glTF 2.0 writer (embedded base64 buffer): generates the shipped Cornell box and the
//! test fixtures, so both are reproducible from code.

use base64::Engine as _;
use glam::{Quat, Vec3};
use serde_json::{Value, json};

/// Builds a glTF document node by node.
#[derive(Default)]
pub struct GltfWriter {
    bin: Vec<u8>,
    buffer_views: Vec<Value>,
    accessors: Vec<Value>,
    meshes: Vec<Value>,
    materials: Vec<Value>,
    nodes: Vec<Value>,
    lights: Vec<Value>,
    cameras: Vec<Value>,
    roots: Vec<usize>,
}

/// A node's transform and attachments.
#[derive(Clone, Debug, Default)]
pub struct NodeDesc {
    /// Node name.
    pub name: String,
    /// Translation.
    pub translation: Option<Vec3>,
    /// Rotation.
    pub rotation: Option<Quat>,
    /// Scale.
    pub scale: Option<Vec3>,
    /// Mesh index.
    pub mesh: Option<usize>,
    /// KHR_lights_punctual light index.
    pub light: Option<usize>,
    /// Camera index.
    pub camera: Option<usize>,
    /// Child node indices.
    pub children: Vec<usize>,
}

impl GltfWriter {
    fn push_view(&mut self, bytes: &[u8], target: Option<u32>) -> usize {
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        let mut view = json!({"buffer": 0, "byteOffset": self.bin.len(), "byteLength": bytes.len()});
        if let Some(t) = target {
            view["target"] = json!(t);
        }
        self.bin.extend_from_slice(bytes);
        self.buffer_views.push(view);
        self.buffer_views.len() - 1
    }

    fn vec3_accessor(&mut self, data: &[Vec3]) -> usize {
        let bytes: Vec<u8> = data.iter().flat_map(|v| v.to_array()).flat_map(f32::to_le_bytes).collect();
        let view = self.push_view(&bytes, Some(34962));
        let (min, max) =
            data.iter().fold((Vec3::splat(f32::MAX), Vec3::splat(f32::MIN)), |(a, b), v| (a.min(*v), b.max(*v)));
        self.accessors.push(json!({"bufferView": view, "componentType": 5126, "count": data.len(), "type": "VEC3",
            "min": min.to_array(), "max": max.to_array()}));
        self.accessors.len() - 1
    }

    /// Adds a diffuse material; returns its index.
    pub fn material(&mut self, name: &str, base_color: [f32; 4]) -> usize {
        self.materials.push(json!({"name": name, "pbrMetallicRoughness": {"baseColorFactor": base_color, "metallicFactor": 0.0, "roughnessFactor": 1.0}}));
        self.materials.len() - 1
    }

    /// Adds an indexed triangle mesh with one primitive; normals are optional.
    pub fn mesh(
        &mut self,
        name: &str,
        positions: &[Vec3],
        normals: Option<&[Vec3]>,
        indices: &[u32],
        material: Option<usize>,
    ) -> usize {
        let pos = self.vec3_accessor(positions);
        let mut attributes = json!({"POSITION": pos});
        if let Some(n) = normals {
            attributes["NORMAL"] = json!(self.vec3_accessor(n));
        }
        let bytes: Vec<u8> = indices.iter().flat_map(|i| i.to_le_bytes()).collect();
        let view = self.push_view(&bytes, Some(34963));
        self.accessors
            .push(json!({"bufferView": view, "componentType": 5125, "count": indices.len(), "type": "SCALAR"}));
        let mut prim = json!({"attributes": attributes, "indices": self.accessors.len() - 1, "mode": 4});
        if let Some(m) = material {
            prim["material"] = json!(m);
        }
        self.meshes.push(json!({"name": name, "primitives": [prim]}));
        self.meshes.len() - 1
    }

    /// Adds a KHR_lights_punctual light (`kind` = "point" | "spot" | "directional"); for spots
    /// pass `(inner, outer)` cone angles.
    pub fn light(
        &mut self,
        name: &str,
        kind: &str,
        color: [f32; 3],
        intensity: f32,
        cone: Option<(f32, f32)>,
    ) -> usize {
        let mut l = json!({"name": name, "type": kind, "color": color, "intensity": intensity});
        if let Some((inner, outer)) = cone {
            l["spot"] = json!({"innerConeAngle": inner, "outerConeAngle": outer});
        }
        self.lights.push(l);
        self.lights.len() - 1
    }

    /// Adds a perspective camera.
    pub fn camera(&mut self, yfov: f32, znear: f32, zfar: Option<f32>) -> usize {
        let mut p = json!({"yfov": yfov, "znear": znear});
        if let Some(f) = zfar {
            p["zfar"] = json!(f);
        }
        self.cameras.push(json!({"type": "perspective", "perspective": p}));
        self.cameras.len() - 1
    }

    /// Adds a node; `root` nodes are listed in the scene.
    pub fn node(&mut self, desc: NodeDesc, root: bool) -> usize {
        let mut n = json!({"name": desc.name});
        if let Some(t) = desc.translation {
            n["translation"] = json!(t.to_array());
        }
        if let Some(r) = desc.rotation {
            n["rotation"] = json!(r.to_array());
        }
        if let Some(s) = desc.scale {
            n["scale"] = json!(s.to_array());
        }
        if let Some(m) = desc.mesh {
            n["mesh"] = json!(m);
        }
        if let Some(c) = desc.camera {
            n["camera"] = json!(c);
        }
        if let Some(l) = desc.light {
            n["extensions"] = json!({"KHR_lights_punctual": {"light": l}});
        }
        if !desc.children.is_empty() {
            n["children"] = json!(desc.children);
        }
        self.nodes.push(n);
        let index = self.nodes.len() - 1;
        if root {
            self.roots.push(index);
        }
        index
    }

    /// The finished document as JSON.
    pub fn to_json(&self) -> Value {
        let data = base64::engine::general_purpose::STANDARD.encode(&self.bin);
        let mut doc = json!({
            "asset": {"version": "2.0", "generator": "bouncelab"},
            "scene": 0,
            "scenes": [{"nodes": self.roots}],
            "nodes": self.nodes,
            "meshes": self.meshes,
            "materials": self.materials,
            "accessors": self.accessors,
            "bufferViews": self.buffer_views,
            "buffers": [{"byteLength": self.bin.len(), "uri": format!("data:application/octet-stream;base64,{data}")}],
        });
        if !self.cameras.is_empty() {
            doc["cameras"] = json!(self.cameras);
        }
        if !self.lights.is_empty() {
            doc["extensionsUsed"] = json!(["KHR_lights_punctual"]);
            doc["extensions"] = json!({"KHR_lights_punctual": {"lights": self.lights}});
        }
        doc
    }

    /// Pretty JSON text with a trailing newline.
    pub fn to_string_pretty(&self) -> String {
        let mut s = serde_json::to_string_pretty(&self.to_json()).unwrap_or_default();
        s.push('\n');
        s
    }
}
