//! Copies a texture back to the CPU (blocking): for headless output, tests and the pixel probe.

/// Why a readback failed.
#[derive(Debug, thiserror::Error)]
pub enum ReadbackError {
    /// Mapping the staging buffer failed.
    #[error("GPU readback failed: {0}")]
    Map(String),
    /// The format has no fixed texel size.
    #[error("cannot read back texture format {0:?}")]
    Format(wgpu::TextureFormat),
}

/// Reads layer 0 of `texture` as tightly packed rows.
pub fn read_texture(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
) -> Result<Vec<u8>, ReadbackError> {
    let format = texture.format();
    let aspect =
        if format.is_depth_stencil_format() { wgpu::TextureAspect::DepthOnly } else { wgpu::TextureAspect::All };
    let bpp = format.block_copy_size(Some(aspect)).ok_or(ReadbackError::Format(format))?;
    let (w, h) = (texture.width(), texture.height());
    let row = w * bpp;
    let padded = row.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("readback staging"),
        size: u64::from(padded) * u64::from(h),
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut encoder =
        device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("readback encoder") });
    encoder.copy_texture_to_buffer(
        wgpu::TexelCopyTextureInfo { texture, mip_level: 0, origin: wgpu::Origin3d::ZERO, aspect },
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: Some(padded), rows_per_image: Some(h) },
        },
        wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 },
    );
    queue.submit([encoder.finish()]);
    let data = map_blocking(device, &buffer)?;
    let mut out = Vec::with_capacity((row * h) as usize);
    for y in 0..h as usize {
        let start = y * padded as usize;
        out.extend_from_slice(&data[start..start + row as usize]);
    }
    Ok(out)
}

/// Blocking readbacks so far in this process ([`blocking_waits`]).
static BLOCKING_WAITS: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);

/// How many times this process has waited for the GPU to map a readback: `bouncelab profile`
/// counts the waits inside a frame's `render` with it (a frame should have none: readbacks
/// land a frame or more later).
pub fn blocking_waits() -> u64 {
    BLOCKING_WAITS.load(std::sync::atomic::Ordering::Relaxed)
}

/// Maps a readback buffer, waits for the GPU and copies its bytes out.
pub(crate) fn map_blocking(device: &wgpu::Device, buffer: &wgpu::Buffer) -> Result<Vec<u8>, ReadbackError> {
    BLOCKING_WAITS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let (tx, rx) = std::sync::mpsc::channel();
    buffer.slice(..).map_async(wgpu::MapMode::Read, move |r| {
        let _ = tx.send(r);
    });
    device.poll(wgpu::PollType::wait_indefinitely()).map_err(|e| ReadbackError::Map(e.to_string()))?;
    rx.recv().map_err(|e| ReadbackError::Map(e.to_string()))?.map_err(|e| ReadbackError::Map(e.to_string()))?;
    let bytes = buffer.slice(..).get_mapped_range().map_err(|e| ReadbackError::Map(e.to_string()))?.to_vec();
    buffer.unmap();
    Ok(bytes)
}

/// Reads an `Rgba32Float` texture as RGBA texels.
pub fn read_rgba32f(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
) -> Result<Vec<[f32; 4]>, ReadbackError> {
    if texture.format() != wgpu::TextureFormat::Rgba32Float {
        return Err(ReadbackError::Format(texture.format()));
    }
    let bytes = read_texture(device, queue, texture)?;
    Ok(bytemuck::pod_collect_to_vec(&bytes))
}

/// Reads any colour or depth target as RGBA floats (integers as their value, missing channels 0,
/// alpha 1): the inspector's and `--buffer`'s common format.
pub fn read_as_rgba_f32(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
) -> Result<Vec<[f32; 4]>, ReadbackError> {
    use wgpu::TextureFormat as F;
    let bytes = read_texture(device, queue, texture)?;
    let f16 = |b: &[u8]| half::f16::from_le_bytes([b[0], b[1]]).to_f32();
    let f32le = |b: &[u8]| f32::from_le_bytes([b[0], b[1], b[2], b[3]]);
    let out = match texture.format() {
        F::Rgba32Float => {
            bytes.chunks_exact(16).map(|c| [f32le(&c[0..]), f32le(&c[4..]), f32le(&c[8..]), f32le(&c[12..])]).collect()
        }
        F::Rgba16Float => {
            bytes.chunks_exact(8).map(|c| [f16(&c[0..]), f16(&c[2..]), f16(&c[4..]), f16(&c[6..])]).collect()
        }
        F::Rg16Float => bytes.chunks_exact(4).map(|c| [f16(&c[0..]), f16(&c[2..]), 0.0, 1.0]).collect(),
        F::R32Uint => bytes
            .chunks_exact(4)
            .map(|c| [u32::from_le_bytes([c[0], c[1], c[2], c[3]]) as f32, 0.0, 0.0, 1.0])
            .collect(),
        F::R32Float | F::Depth32Float => bytes
            .chunks_exact(4)
            .map(|c| {
                let v = f32le(c);
                [v, v, v, 1.0]
            })
            .collect(),
        F::Rgba8Unorm | F::Rgba8UnormSrgb => {
            bytes.chunks_exact(4).map(|c| [0, 1, 2, 3].map(|i| f32::from(c[i]) / 255.0)).collect()
        }
        other => return Err(ReadbackError::Format(other)),
    };
    Ok(out)
}

/// Reads one texel of an `R32Uint` texture (object-id picking).
pub fn read_texel_u32(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    texture: &wgpu::Texture,
    x: u32,
    y: u32,
) -> Result<u32, ReadbackError> {
    if texture.format() != wgpu::TextureFormat::R32Uint {
        return Err(ReadbackError::Format(texture.format()));
    }
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("pick staging"),
        size: 4,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("pick encoder") });
    encoder.copy_texture_to_buffer(
        wgpu::TexelCopyTextureInfo {
            texture,
            mip_level: 0,
            origin: wgpu::Origin3d { x: x.min(texture.width() - 1), y: y.min(texture.height() - 1), z: 0 },
            aspect: wgpu::TextureAspect::All,
        },
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout { offset: 0, bytes_per_row: None, rows_per_image: None },
        },
        wgpu::Extent3d { width: 1, height: 1, depth_or_array_layers: 1 },
    );
    queue.submit([encoder.finish()]);
    let data = map_blocking(device, &buffer)?;
    Ok(u32::from_le_bytes([data[0], data[1], data[2], data[3]]))
}

/// Reads a whole buffer (it needs `COPY_SRC`).
pub fn read_buffer(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    source: &wgpu::Buffer,
) -> Result<Vec<u8>, ReadbackError> {
    let staging = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("buffer readback staging"),
        size: source.size(),
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut encoder =
        device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("buffer readback encoder") });
    encoder.copy_buffer_to_buffer(source, 0, &staging, 0, source.size());
    queue.submit([encoder.finish()]);
    map_blocking(device, &staging)
}
