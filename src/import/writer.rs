//! A small glTF 2.0 writer: generates the shipped Cornell box and the test fixtures, so both are
//! reproducible from code, and writes the exports of [`crate::export`] as `.gltf` (one embedded
//! base64 buffer) or `.glb` (the binary container).

use base64::Engine as _;
use glam::{Quat, Vec2, Vec3, Vec4};
use serde_json::{Value, json};

use crate::scene::LightUnits;

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
    images: Vec<Value>,
    textures: Vec<Value>,
    roots: Vec<usize>,
    /// Root `extras` besides the unit record (`bouncelab` keys merge with it).
    extras: Option<Value>,
    /// The units the lights' intensities are given in, recorded in the root `extras` so that
    /// import reads them back as written; `None`: radiometric, the scene model's units.
    light_units: Option<LightUnits>,
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
    /// The node's `extras`.
    pub extras: Option<Value>,
}

impl GltfWriter {
    /// Records that the lights' intensities are in `units` (default: radiometric).
    pub fn set_light_units(&mut self, units: LightUnits) {
        self.light_units = Some(units);
    }

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

    fn vec2_accessor(&mut self, data: &[Vec2]) -> usize {
        let bytes: Vec<u8> = data.iter().flat_map(|v| v.to_array()).flat_map(f32::to_le_bytes).collect();
        let view = self.push_view(&bytes, Some(34962));
        self.accessors.push(json!({"bufferView": view, "componentType": 5126, "count": data.len(), "type": "VEC2"}));
        self.accessors.len() - 1
    }

    fn vec4_accessor(&mut self, data: &[Vec4]) -> usize {
        let bytes: Vec<u8> = data.iter().flat_map(|v| v.to_array()).flat_map(f32::to_le_bytes).collect();
        let view = self.push_view(&bytes, Some(34962));
        self.accessors.push(json!({"bufferView": view, "componentType": 5126, "count": data.len(), "type": "VEC4"}));
        self.accessors.len() - 1
    }

    /// Adds a material given as its glTF JSON object; returns its index.
    pub fn material_json(&mut self, material: Value) -> usize {
        self.materials.push(material);
        self.materials.len() - 1
    }

    /// Adds a PNG image stored in the buffer and a texture sampling it; returns the texture's
    /// index (equal to the image's).
    pub fn png_texture(&mut self, png: &[u8]) -> usize {
        let view = self.push_view(png, None);
        self.images.push(json!({"bufferView": view, "mimeType": "image/png"}));
        self.textures.push(json!({"source": self.images.len() - 1}));
        self.textures.len() - 1
    }

    /// Adds a light given as its KHR_lights_punctual JSON object; returns its index.
    pub fn light_json(&mut self, light: Value) -> usize {
        self.lights.push(light);
        self.lights.len() - 1
    }

    /// Sets the root `extras` (its `bouncelab` object gains the unit record).
    pub fn set_extras(&mut self, extras: Value) {
        self.extras = Some(extras);
    }

    /// Adds a triangle mesh with one primitive and every attribute given; returns its index.
    pub fn mesh_with(&mut self, name: &str, mesh: MeshAttributes<'_>, material: Option<usize>) -> usize {
        let mut attributes = json!({"POSITION": self.vec3_accessor(mesh.positions)});
        attributes["NORMAL"] = json!(self.vec3_accessor(mesh.normals));
        if let Some(uvs) = mesh.uvs {
            attributes["TEXCOORD_0"] = json!(self.vec2_accessor(uvs));
        }
        if let Some(tangents) = mesh.tangents {
            attributes["TANGENT"] = json!(self.vec4_accessor(tangents));
        }
        let bytes: Vec<u8> = mesh.indices.iter().flat_map(|i| i.to_le_bytes()).collect();
        let view = self.push_view(&bytes, Some(34963));
        self.accessors
            .push(json!({"bufferView": view, "componentType": 5125, "count": mesh.indices.len(), "type": "SCALAR"}));
        let mut prim = json!({"attributes": attributes, "indices": self.accessors.len() - 1, "mode": 4});
        if let Some(m) = material {
            prim["material"] = json!(m);
        }
        self.meshes.push(json!({"name": name, "primitives": [prim]}));
        self.meshes.len() - 1
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
        if let Some(extras) = desc.extras {
            n["extras"] = extras;
        }
        self.nodes.push(n);
        let index = self.nodes.len() - 1;
        if root {
            self.roots.push(index);
        }
        index
    }

    /// The finished document as JSON, its buffer embedded as base64.
    pub fn to_json(&self) -> Value {
        let data = base64::engine::general_purpose::STANDARD.encode(&self.bin);
        self.document(Some(format!("data:application/octet-stream;base64,{data}")))
    }

    /// The document with the buffer at `uri` (`None`: the GLB binary chunk).
    fn document(&self, uri: Option<String>) -> Value {
        let mut buffer = json!({"byteLength": self.bin.len()});
        if let Some(uri) = uri {
            buffer["uri"] = json!(uri);
        }
        let mut extras = self.extras.clone().unwrap_or_else(|| json!({}));
        let units = self.light_units.unwrap_or(LightUnits::Radiometric).name();
        if let Some(root) = extras.as_object_mut() {
            let own = root.entry("bouncelab").or_insert_with(|| json!({}));
            if let Some(own) = own.as_object_mut() {
                own.insert("light_units".into(), json!(units));
            }
        }
        let mut doc = json!({
            "asset": {"version": "2.0", "generator": "bouncelab"},
            "scene": 0,
            "scenes": [{"nodes": self.roots}],
            "nodes": self.nodes,
            "meshes": self.meshes,
            "materials": self.materials,
            "accessors": self.accessors,
            "bufferViews": self.buffer_views,
            "buffers": [buffer],
            "extras": extras,
        });
        if !self.images.is_empty() {
            doc["images"] = json!(self.images);
            doc["textures"] = json!(self.textures);
        }
        if !self.cameras.is_empty() {
            doc["cameras"] = json!(self.cameras);
        }
        let mut used = Vec::new();
        if !self.lights.is_empty() {
            used.push("KHR_lights_punctual");
            doc["extensions"] = json!({"KHR_lights_punctual": {"lights": self.lights}});
        }
        if self.materials.iter().any(|m| m.pointer("/extensions/KHR_materials_emissive_strength").is_some()) {
            used.push("KHR_materials_emissive_strength");
        }
        if !used.is_empty() {
            doc["extensionsUsed"] = json!(used);
        }
        doc
    }

    /// The document as a GLB container: a JSON chunk padded with spaces and the buffer as a
    /// binary chunk padded with zeros, each to 4 bytes (glTF 2.0, section 4.4).
    pub fn to_glb(&self) -> Vec<u8> {
        let mut json = serde_json::to_vec(&self.document(None)).unwrap_or_default();
        while !json.len().is_multiple_of(4) {
            json.push(b' ');
        }
        let mut bin = self.bin.clone();
        while !bin.len().is_multiple_of(4) {
            bin.push(0);
        }
        let total = 12 + 8 + json.len() + if bin.is_empty() { 0 } else { 8 + bin.len() };
        let mut out = Vec::with_capacity(total);
        out.extend_from_slice(b"glTF");
        out.extend_from_slice(&2u32.to_le_bytes());
        out.extend_from_slice(&(total as u32).to_le_bytes());
        out.extend_from_slice(&(json.len() as u32).to_le_bytes());
        out.extend_from_slice(b"JSON");
        out.extend_from_slice(&json);
        if !bin.is_empty() {
            out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
            out.extend_from_slice(b"BIN\0");
            out.extend_from_slice(&bin);
        }
        out
    }

    /// Pretty JSON text with a trailing newline.
    pub fn to_string_pretty(&self) -> String {
        let mut s = serde_json::to_string_pretty(&self.to_json()).unwrap_or_default();
        s.push('\n');
        s
    }
}

/// A mesh's vertex attributes and indices for [`GltfWriter::mesh_with`].
#[derive(Clone, Copy, Debug)]
pub struct MeshAttributes<'a> {
    pub positions: &'a [Vec3],
    pub normals: &'a [Vec3],
    pub uvs: Option<&'a [Vec2]>,
    pub tangents: Option<&'a [Vec4]>,
    pub indices: &'a [u32],
}
