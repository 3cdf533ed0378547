//! The scene on the GPU: vertex and index buffers per mesh, material bind groups (uniforms and
//! textures), and one storage array of per-object data with this and the previous frame's
//! matrices (for motion vectors). Geometry is re-uploaded only when the scene's resources change.
//!
//! Objects are drawn instanced: the array is ordered by (material, mesh), and each run of equal
//! material and mesh is one draw whose instances index the array (`instance_index`). A level of
//! 1,000 props of four meshes went from 13,000 draws and 2.5 GB resident to a handful of draws
//! on lavapipe (figures in `docs/BENCHMARKS-lavapipe.md`, `examples/big_scene.rs`).

use glam::Mat4;
use wgpu::util::DeviceExt as _;

use super::layouts::Layouts;
use super::uniforms::{MaterialUniforms, ObjectUniforms};
use crate::scene::{Image, Material, Scene};

/// Interleaved vertex: position, normal, uv, tangent (48 bytes).
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct Vertex {
    pub position: [f32; 3],
    pub normal: [f32; 3],
    pub uv: [f32; 2],
    pub tangent: [f32; 4],
}

impl Vertex {
    /// The layout matching `MeshVertex` in `common/object.wgsl`.
    pub const LAYOUT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
        array_stride: std::mem::size_of::<Vertex>() as u64,
        step_mode: wgpu::VertexStepMode::Vertex,
        attributes: &wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32x2, 3 => Float32x4],
    };

    /// The vertex stage of every pass that rasterises scene meshes: entry point `vs_main` of
    /// `module`, fed by one buffer of [`Vertex`].
    pub fn state(module: &wgpu::ShaderModule) -> wgpu::VertexState<'_> {
        wgpu::VertexState {
            module,
            entry_point: Some("vs_main"),
            compilation_options: Default::default(),
            buffers: &[Some(Self::LAYOUT)],
        }
    }
}

/// One uploaded mesh.
pub struct GpuMesh {
    pub vertices: wgpu::Buffer,
    pub indices: wgpu::Buffer,
    pub index_count: u32,
}

/// Bytes per object in the object array (the stride of `array<Object>` in `common/object.wgsl`).
pub const OBJECT_SLOT: u64 = 256;

/// One instanced draw: the objects `instances` (indices into the object array) share `mesh`
/// and `material`.
#[derive(Clone, Debug, PartialEq)]
pub struct Batch {
    /// Index into [`SceneGpu::meshes`].
    pub mesh: usize,
    /// Index into [`SceneGpu::materials`].
    pub material: usize,
    /// Slots of the object array.
    pub instances: std::ops::Range<u32>,
}

/// GPU copies of a scene's meshes, materials and objects.
pub struct SceneGpu {
    pub meshes: Vec<GpuMesh>,
    pub materials: Vec<wgpu::BindGroup>,
    material_buffers: Vec<wgpu::Buffer>,
    /// Per material: whether it emits (the emission pass draws only those).
    emissive: Vec<bool>,
    /// Per material: its emission texture (a change rebuilds the bind groups).
    emissive_textures: Vec<Option<crate::scene::TextureRef>>,
    pub object_buffer: wgpu::Buffer,
    /// Group 1 of every pass that draws objects: the object array.
    pub object_bind_group: wgpu::BindGroup,
    object_capacity: usize,
    /// This frame's draws, in object-array order.
    pub batches: Vec<Batch>,
    prev_world: Vec<Mat4>,
    resources_revision: u64,
    /// Set anew by [`Self::sync`] whenever what depth-only passes draw changed (see
    /// [`Self::geometry_generation`]).
    geometry_generation: u64,
    /// The object array's matrices in slot order as last uploaded: what the batches draw.
    drawn_worlds: Vec<Mat4>,
    textures: Vec<wgpu::TextureView>,
    white: wgpu::TextureView,
    flat_normal: wgpu::TextureView,
    sampler: wgpu::Sampler,
}

/// One counter for every [`SceneGpu`], so that no two states of two scenes' geometry share a
/// generation (a cache keyed on it never takes one scene's geometry for another's).
fn next_geometry_generation() -> u64 {
    static GENERATIONS: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(1);
    GENERATIONS.fetch_add(1, std::sync::atomic::Ordering::Relaxed)
}

fn upload_image(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    image: &Image,
    label: &str,
    srgb: bool,
) -> wgpu::TextureView {
    let format = if srgb { wgpu::TextureFormat::Rgba8UnormSrgb } else { wgpu::TextureFormat::Rgba8Unorm };
    let texture = device.create_texture_with_data(
        queue,
        &wgpu::TextureDescriptor {
            label: Some(label),
            size: wgpu::Extent3d { width: image.width, height: image.height, depth_or_array_layers: 1 },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            view_formats: &[format.remove_srgb_suffix()],
        },
        wgpu::util::TextureDataOrder::LayerMajor,
        &image.rgba8,
    );
    texture.create_view(&wgpu::TextureViewDescriptor { label: Some(label), ..Default::default() })
}

impl SceneGpu {
    /// Draws every rendered object, one instanced draw per batch, with the object array in
    /// group 1 and each batch's material in group 2; the pass's pipeline and group 0 are the
    /// caller's.
    pub fn draw_objects(&self, pass: &mut wgpu::RenderPass<'_>) {
        pass.set_bind_group(1, &self.object_bind_group, &[]);
        let mut bound = None;
        for batch in &self.batches {
            let (Some(mesh), Some(material)) = (self.meshes.get(batch.mesh), self.materials.get(batch.material)) else {
                continue;
            };
            if bound != Some(batch.material) {
                pass.set_bind_group(2, material, &[]);
                bound = Some(batch.material);
            }
            pass.set_vertex_buffer(0, mesh.vertices.slice(..));
            pass.set_index_buffer(mesh.indices.slice(..), wgpu::IndexFormat::Uint32);
            pass.draw_indexed(0..mesh.index_count, 0, batch.instances.clone());
        }
    }

    /// Draws the objects whose material emits, with their materials (the emission pass).
    pub fn draw_emissive(&self, pass: &mut wgpu::RenderPass<'_>) {
        pass.set_bind_group(1, &self.object_bind_group, &[]);
        for batch in self.batches.iter().filter(|b| self.emissive.get(b.material).copied().unwrap_or(false)) {
            let (Some(mesh), Some(material)) = (self.meshes.get(batch.mesh), self.materials.get(batch.material)) else {
                continue;
            };
            pass.set_bind_group(2, material, &[]);
            pass.set_vertex_buffer(0, mesh.vertices.slice(..));
            pass.set_index_buffer(mesh.indices.slice(..), wgpu::IndexFormat::Uint32);
            pass.draw_indexed(0..mesh.index_count, 0, batch.instances.clone());
        }
    }

    /// Whether any material emits.
    pub fn has_emissive(&self) -> bool {
        self.emissive.iter().any(|e| *e)
    }

    /// Draws every rendered object's geometry without materials (depth-only passes): adjacent
    /// batches of one mesh become one draw. The object array must be bound by the caller.
    pub fn draw_geometry(&self, pass: &mut wgpu::RenderPass<'_>) {
        let mut i = 0;
        while i < self.batches.len() {
            let mesh_index = self.batches[i].mesh;
            let start = self.batches[i].instances.start;
            let mut end = self.batches[i].instances.end;
            i += 1;
            while i < self.batches.len() && self.batches[i].mesh == mesh_index {
                end = self.batches[i].instances.end;
                i += 1;
            }
            if let Some(mesh) = self.meshes.get(mesh_index) {
                pass.set_vertex_buffer(0, mesh.vertices.slice(..));
                pass.set_index_buffer(mesh.indices.slice(..), wgpu::IndexFormat::Uint32);
                pass.draw_indexed(0..mesh.index_count, 0, start..end);
            }
        }
    }

    /// Uploads everything.
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue, layouts: &Layouts, scene: &Scene) -> Self {
        let one = |rgba: [u8; 4]| Image { width: 1, height: 1, rgba8: rgba.to_vec() };
        let white = upload_image(device, queue, &one([255; 4]), "white texture", true);
        let flat_normal = upload_image(device, queue, &one([128, 128, 255, 255]), "flat normal texture", false);
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("material sampler"),
            address_mode_u: wgpu::AddressMode::Repeat,
            address_mode_v: wgpu::AddressMode::Repeat,
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            ..Default::default()
        });
        let (object_buffer, object_bind_group) = Self::object_buffer(device, layouts, 1);
        let mut gpu = Self {
            meshes: Vec::new(),
            materials: Vec::new(),
            emissive: Vec::new(),
            emissive_textures: Vec::new(),
            material_buffers: Vec::new(),
            object_buffer,
            object_bind_group,
            object_capacity: 1,
            batches: Vec::new(),
            prev_world: Vec::new(),
            resources_revision: 0,
            geometry_generation: 0,
            drawn_worlds: Vec::new(),
            textures: Vec::new(),
            white,
            flat_normal,
            sampler,
        };
        gpu.sync(device, queue, layouts, scene);
        gpu
    }

    fn object_buffer(device: &wgpu::Device, layouts: &Layouts, capacity: usize) -> (wgpu::Buffer, wgpu::BindGroup) {
        let buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("object uniforms"),
            size: OBJECT_SLOT * capacity.max(1) as u64,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("object bind group"),
            layout: &layouts.object,
            entries: &[wgpu::BindGroupEntry { binding: 0, resource: buffer.as_entire_binding() }],
        });
        (buffer, bind_group)
    }

    /// Brings the GPU copy up to date: geometry when resources changed, materials and object
    /// matrices always (cheap). Call once per frame; it also advances the previous-frame matrices.
    pub fn sync(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, layouts: &Layouts, scene: &Scene) {
        let resources_changed = self.resources_revision != scene.resources_revision();
        if resources_changed {
            self.upload_geometry(device, queue, scene);
            self.resources_revision = scene.resources_revision();
        }
        self.upload_materials(device, queue, layouts, scene);
        let objects = scene.objects();
        let batches_before = std::mem::take(&mut self.batches);
        let order = self.draw_order(scene);
        if order.len() > self.object_capacity {
            self.object_capacity = order.len().next_power_of_two();
            (self.object_buffer, self.object_bind_group) = Self::object_buffer(device, layouts, self.object_capacity);
        }
        let worlds: Vec<Mat4> = objects.iter().map(|o| o.transform.matrix()).collect();
        // What the batches draw: each slot's matrix (one object hidden and another of the same
        // mesh and material shown leave the batches alike but move the slot's matrix).
        let drawn: Vec<Mat4> = order.iter().map(|&i| worlds[i]).collect();
        if resources_changed || self.batches != batches_before || drawn != self.drawn_worlds {
            self.geometry_generation = next_geometry_generation();
        }
        self.drawn_worlds = drawn;
        let mut data = vec![0u8; OBJECT_SLOT as usize * order.len()];
        for (slot, &i) in order.iter().enumerate() {
            let world = self.drawn_worlds[slot];
            let prev = self.prev_world.get(i).copied().unwrap_or(world);
            let u = ObjectUniforms::new(world, prev, i as u32 + 1, objects[i].material as u32);
            let start = slot * OBJECT_SLOT as usize;
            data[start..start + std::mem::size_of::<ObjectUniforms>()].copy_from_slice(bytemuck::bytes_of(&u));
        }
        if !data.is_empty() {
            queue.write_buffer(&self.object_buffer, 0, &data);
        }
        self.prev_world = worlds;
    }

    /// The drawn objects sorted by (material, mesh: each material is bound once), and [`Self::batches`] over that order.
    fn draw_order(&mut self, scene: &Scene) -> Vec<usize> {
        let mut order: Vec<usize> = scene
            .objects()
            .iter()
            .enumerate()
            .filter(|(_, o)| {
                o.is_rendered()
                    && o.material < self.materials.len()
                    && self.meshes.get(o.mesh).is_some_and(|m| m.index_count > 0)
            })
            .map(|(i, _)| i)
            .collect();
        let key = |i: usize| (scene.objects()[i].material, scene.objects()[i].mesh);
        order.sort_by_key(|&i| key(i));
        self.batches.clear();
        for (slot, &i) in order.iter().enumerate() {
            let (material, mesh) = key(i);
            match self.batches.last_mut() {
                Some(b) if b.mesh == mesh && b.material == material => b.instances.end = slot as u32 + 1,
                _ => self.batches.push(Batch { mesh, material, instances: slot as u32..slot as u32 + 1 }),
            }
        }
        order
    }

    /// A counter that changes whenever the geometry that depth-only passes draw changes: the
    /// meshes, the batches, or the matrix in any slot of the object array (an object moved,
    /// shown or hidden). Material edits that keep the batches leave it alone. Passes whose
    /// output depends on nothing else but their own view (shadow maps) key their caches on it.
    pub fn geometry_generation(&self) -> u64 {
        self.geometry_generation
    }

    /// Forgets the previous frame's matrices (no motion on the next frame).
    pub fn reset_motion(&mut self) {
        self.prev_world.clear();
    }

    fn upload_geometry(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, scene: &Scene) {
        let res = scene.resources();
        self.meshes = res
            .meshes
            .iter()
            .map(|m| {
                let vertices: Vec<Vertex> = (0..m.positions.len())
                    .map(|i| Vertex {
                        position: m.positions[i].to_array(),
                        normal: m.normals[i].to_array(),
                        uv: m.uvs[i].to_array(),
                        tangent: m.tangents[i].to_array(),
                    })
                    .collect();
                let label = format!("mesh {}", m.name);
                GpuMesh {
                    vertices: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                        label: Some(&format!("{label} vertices")),
                        contents: bytemuck::cast_slice(&vertices),
                        usage: wgpu::BufferUsages::VERTEX,
                    }),
                    indices: device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                        label: Some(&format!("{label} indices")),
                        contents: bytemuck::cast_slice(&m.indices),
                        usage: wgpu::BufferUsages::INDEX,
                    }),
                    index_count: m.indices.len() as u32,
                }
            })
            .collect();
        // Textures are sRGB for base colour; normal maps use the linear view of the same data.
        self.textures = res
            .images
            .iter()
            .enumerate()
            .map(|(i, img)| upload_image(device, queue, img, &format!("scene image {i}"), true))
            .collect();
        self.material_buffers.clear();
    }

    fn upload_materials(&mut self, device: &wgpu::Device, queue: &wgpu::Queue, layouts: &Layouts, scene: &Scene) {
        let materials = scene.materials();
        if self.material_buffers.len() != materials.len() {
            self.material_buffers = materials
                .iter()
                .map(|m| {
                    device.create_buffer(&wgpu::BufferDescriptor {
                        label: Some(&format!("material {} uniforms", m.name)),
                        size: std::mem::size_of::<MaterialUniforms>() as u64,
                        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                        mapped_at_creation: false,
                    })
                })
                .collect();
            self.materials.clear();
        }
        let rebuild = self.materials.len() != materials.len()
            || materials.iter().map(|m| m.emissive_texture).ne(self.emissive_textures.iter().copied());
        // In place: called every frame, these keep their allocation.
        self.emissive.clear();
        self.emissive.extend(materials.iter().map(Material::emits));
        self.emissive_textures.clear();
        self.emissive_textures.extend(materials.iter().map(|m| m.emissive_texture));
        let mut groups = Vec::new();
        for (m, buffer) in materials.iter().zip(&self.material_buffers) {
            queue.write_buffer(buffer, 0, bytemuck::bytes_of(&MaterialUniforms::new(m)));
            if rebuild {
                let base = m.base_color_texture.and_then(|t| self.textures.get(t.image)).unwrap_or(&self.white);
                let normal_view;
                let normal = match m.normal_texture.and_then(|t| self.textures.get(t.image)) {
                    Some(view) => {
                        normal_view = view.texture().create_view(&wgpu::TextureViewDescriptor {
                            label: Some("normal map linear view"),
                            format: Some(wgpu::TextureFormat::Rgba8Unorm),
                            ..Default::default()
                        });
                        &normal_view
                    }
                    None => &self.flat_normal,
                };
                let emissive = m.emissive_texture.and_then(|t| self.textures.get(t.image)).unwrap_or(&self.white);
                groups.push(device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some(&format!("material {} bind group", m.name)),
                    layout: &layouts.material,
                    entries: &[
                        wgpu::BindGroupEntry { binding: 0, resource: buffer.as_entire_binding() },
                        wgpu::BindGroupEntry { binding: 1, resource: wgpu::BindingResource::TextureView(base) },
                        wgpu::BindGroupEntry { binding: 2, resource: wgpu::BindingResource::TextureView(normal) },
                        wgpu::BindGroupEntry { binding: 3, resource: wgpu::BindingResource::Sampler(&self.sampler) },
                        wgpu::BindGroupEntry { binding: 4, resource: wgpu::BindingResource::TextureView(emissive) },
                    ],
                }));
            }
        }
        if rebuild {
            self.materials = groups;
        }
    }
}
