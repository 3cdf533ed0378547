//! Render sizes checked against the adapter's limits and the memory there is, before a render
//! starts: a 16384² render passed the side check and ended in an out-of-memory GPU error after
//! fifty lines of allocator warnings. The estimates are per pixel of the render (supersampled)
//! size; [`RASTER_GPU_BYTES_PER_PIXEL`] is checked against the device's own counters by a test.

use crate::render::GpuContext;

/// GPU bytes a raster frame holds per render pixel at most, over every mode's screen-sized
/// targets and buffers (G-buffer, shadowed direct, indirect, HDR, display image, the depth and
/// normal pyramid, a technique's screen buffers). `tests/integration/cli.rs` measures each mode's growth
/// with the render size against it.
pub const RASTER_GPU_BYTES_PER_PIXEL: u64 = 320;

/// Host bytes per render pixel: the RGBA32F read-back (staging copy and the image) and the
/// supersampled image's filter.
const READBACK_BYTES_PER_PIXEL: u64 = 16 * 3;

/// Host bytes per pixel of the reference path tracer: its f64 accumulator, the RGBA32F image
/// and the encoded output.
const REFERENCE_BYTES_PER_PIXEL: u64 = 24 + 16 + 8;

/// The share of available memory a render may plan to take.
const SHARE: f64 = 0.8;

/// Refuses a raster render of `size` pixels that the adapter cannot hold or this machine's
/// memory cannot read back.
pub fn check_raster(ctx: &GpuContext, size: (u32, u32)) -> anyhow::Result<()> {
    let pixels = u64::from(size.0) * u64::from(size.1);
    let limits = ctx.device.limits();
    let readback = pixels * 16;
    if readback > limits.max_buffer_size {
        anyhow::bail!(
            "a {}x{} render reads back {:.0} MB, over this adapter's {:.0} MB buffer limit: render smaller or with a lower --ssaa",
            size.0,
            size.1,
            readback as f64 / 1e6,
            limits.max_buffer_size as f64 / 1e6
        );
    }
    let gpu = pixels * RASTER_GPU_BYTES_PER_PIXEL;
    let host = pixels * READBACK_BYTES_PER_PIXEL;
    // A software adapter's "GPU" memory is this machine's memory too.
    let on_host = if ctx.info.device_type == wgpu::DeviceType::Cpu { gpu + host } else { host };
    check_host(on_host, size, "render")
}

/// Refuses a reference render of `size` pixels that this machine's memory cannot hold.
pub fn check_reference(size: (u32, u32)) -> anyhow::Result<()> {
    let pixels = u64::from(size.0) * u64::from(size.1);
    check_host(pixels * REFERENCE_BYTES_PER_PIXEL, size, "reference render")
}

fn check_host(bytes: u64, size: (u32, u32), what: &str) -> anyhow::Result<()> {
    let Some(available) = available_memory() else { return Ok(()) };
    if bytes as f64 > SHARE * available as f64 {
        anyhow::bail!(
            "a {}x{} {what} needs about {:.1} GB, and this machine has {:.1} GB available: render smaller or with a lower --ssaa",
            size.0,
            size.1,
            bytes as f64 / 1e9,
            available as f64 / 1e9
        );
    }
    Ok(())
}

/// Memory available to a new allocation (Linux: `MemAvailable`; elsewhere unknown).
fn available_memory() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_reference_larger_than_memory_is_refused_before_it_starts() {
        if available_memory().is_none() {
            return;
        }
        let err = check_reference((16384 * 8, 16384)).expect_err("over 100 GB");
        assert!(err.to_string().contains("GB available"), "{err}");
        check_reference((640, 360)).expect("a small one fits");
    }
}
