// sshgi solid voxelisation of the view (Soler et al. 2010, Sec. 4, "Visibility computation", after
// Eisemann & Décoret 2008): every surface is rasterised with the camera's projection, no culling
// and no depth test, and each fragment XORs "all slices from mine to the last" into its pixel's
// 128-bit column. Afterwards a slice bit is set exactly when an odd number of surfaces lie in
// front of it along the pixel's ray: inside a closed solid. wgpu has no logic-op blending, so the
// XOR is a storage atomic. Clip-space z is pinned mid-range so no surface is clipped at the near
// or far plane (a surface crossing the near plane would otherwise lose its entry and flip the
// parity of everything behind it); the slice comes from the fragment's own view depth, clamped
// into the range at the near end, and geometry beyond the range writes nothing.
#import common/frame.wgsl
#import common/object.wgsl

struct VoxelParams {
    // near, far (view depth, m), slices per metre (128 / (far - near)), the raster's width in
    // columns (the view's, or a coarser level's where the view's columns exceed a binding).
    range: vec4<f32>,
    // xyz the camera's forward axis, w unused.
    forward: vec4<f32>,
}

@group(0) @binding(0) var<uniform> frame: Frame;
@group(0) @binding(1) var<uniform> vp: VoxelParams;
// Four words per pixel, row-major: slices 0-31, 32-63, 64-95, 96-127.
@group(0) @binding(2) var<storage, read_write> voxels: array<atomic<u32>>;
@group(1) @binding(0) var<storage, read> objects: array<Object>;

struct VoxelOut {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
}

@vertex
fn vs_main(@location(0) position: vec3<f32>, @builtin(instance_index) instance: u32) -> VoxelOut {
    let world = objects[instance].world_from_local * vec4<f32>(position, 1.0);
    var clip = frame.clip_from_world * world;
    clip.z = 0.5 * clip.w;
    return VoxelOut(clip, world.xyz);
}

// The bits of word w (slices 32w..32w+31) from slice s on.
fn from_slice(w: u32, s: u32) -> u32 {
    let lo = 32u * w;
    if s <= lo {
        return 0xffffffffu;
    }
    if s >= lo + 32u {
        return 0u;
    }
    return 0xffffffffu << (s - lo);
}

@fragment
fn fs_main(in: VoxelOut) -> @location(0) vec4<f32> {
    let z = dot(in.world - frame.camera_position.xyz, vp.forward.xyz);
    if z <= vp.range.y {
        let s = u32(clamp(floor((z - vp.range.x) * vp.range.z), 0.0, 127.0));
        let pixel = vec2<u32>(in.clip.xy);
        let base = (pixel.y * u32(vp.range.w) + pixel.x) * 4u;
        for (var w = 0u; w < 4u; w = w + 1u) {
            let mask = from_slice(w, s);
            if mask != 0u {
                atomicXor(&voxels[base + w], mask);
            }
        }
    }
    return vec4<f32>(0.0);
}
