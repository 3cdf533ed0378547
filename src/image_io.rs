//! Image files: EXR holds linear radiance (before exposure and tonemapping), PNG the
//! tonemapped sRGB view. No GPU types.

use std::path::{Path, PathBuf};

/// Why an image could not be written or read.
#[derive(Debug, thiserror::Error)]
pub enum ImageIoError {
    /// The extension is neither `.exr` nor `.png`.
    #[error("{0}: unsupported image extension (use .exr for linear radiance or .png for the tonemapped view)")]
    Extension(PathBuf),
    /// Encoding or decoding failed.
    #[error("{path}: {message}")]
    Codec { path: PathBuf, message: String },
    /// The pixel count does not match the size.
    #[error("{path}: {got} pixels for a {width}x{height} image")]
    Size { path: PathBuf, got: usize, width: u32, height: u32 },
}

/// Linear RGBA float image.
#[derive(Clone, Debug, PartialEq)]
pub struct HdrImage {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Row-major RGBA, top row first.
    pub pixels: Vec<[f32; 4]>,
}

/// Writes linear radiance to `.exr` (32-bit float RGBA).
pub fn write_exr(path: &Path, img: &HdrImage) -> Result<(), ImageIoError> {
    let codec = |e: image::ImageError| ImageIoError::Codec { path: path.to_owned(), message: e.to_string() };
    let flat: Vec<f32> = img.pixels.iter().flatten().copied().collect();
    let buf = image::Rgba32FImage::from_raw(img.width, img.height, flat).ok_or_else(|| ImageIoError::Size {
        path: path.to_owned(),
        got: img.pixels.len(),
        width: img.width,
        height: img.height,
    })?;
    let mut bytes = std::io::Cursor::new(Vec::new());
    image::DynamicImage::ImageRgba32F(buf).write_to(&mut bytes, image::ImageFormat::OpenExr).map_err(codec)?;
    write_atomic(path, bytes.get_ref())
}

/// Every image goes through the atomic writer: a failed or killed write leaves the old file.
fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), ImageIoError> {
    crate::atomic_file::write(path, bytes)
        .map_err(|e| ImageIoError::Codec { path: path.to_owned(), message: e.to_string() })
}

/// Writes RGBA8 (already sRGB-encoded) to `.png`.
pub fn write_png(path: &Path, width: u32, height: u32, rgba8: Vec<u8>) -> Result<(), ImageIoError> {
    let got = rgba8.len() / 4;
    let buf = image::RgbaImage::from_raw(width, height, rgba8).ok_or_else(|| ImageIoError::Size {
        path: path.to_owned(),
        got,
        width,
        height,
    })?;
    let mut bytes = std::io::Cursor::new(Vec::new());
    buf.write_to(&mut bytes, image::ImageFormat::Png)
        .map_err(|e| ImageIoError::Codec { path: path.to_owned(), message: e.to_string() })?;
    write_atomic(path, bytes.get_ref())
}

/// Writes linear radiance as EXR, or the tonemapped `view` of it as PNG (creating the folder).
pub fn write_image(
    out: &Path,
    kind: OutputKind,
    img: &HdrImage,
    view: &crate::settings::ViewSettings,
) -> Result<(), ImageIoError> {
    if let Some(dir) = out.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|e| ImageIoError::Codec {
            path: out.to_owned(),
            message: format!("creating {}: {e}", dir.display()),
        })?;
    }
    match kind {
        OutputKind::Exr => write_exr(out, img),
        OutputKind::Png => write_png(out, img.width, img.height, tonemap_srgb8(img, view)),
    }
}

/// The largest image `read_linear` decodes: 16384 pixels a side and 2 GiB of decoder memory
/// (a 16k x 16k float image is 4 GiB, beyond any render this tool compares).
const MAX_SIDE: u32 = 16384;
const MAX_DECODE_BYTES: u64 = 2 << 30;

/// Reads an image as linear RGBA float: EXR and Radiance HDR as stored, PNG/JPEG decoded from
/// sRGB.
pub fn read_linear(path: &Path) -> Result<HdrImage, ImageIoError> {
    let bytes = crate::input_file::read(path, crate::input_file::Kind::Image)
        .map_err(|e| ImageIoError::Codec { path: path.to_owned(), message: e.to_string() })?;
    decode_linear(&bytes, path)
}

/// Decodes image bytes as [`read_linear`] does; `path` names the file in errors, and its
/// extension picks the format (else the bytes' signature). Bounded in size, so a header that
/// claims a huge image is an error rather than an allocation failure.
pub fn decode_linear(bytes: &[u8], path: &Path) -> Result<HdrImage, ImageIoError> {
    let codec = |e: image::ImageError| ImageIoError::Codec { path: path.to_owned(), message: e.to_string() };
    let mut reader = image::ImageReader::new(std::io::Cursor::new(bytes));
    match image::ImageFormat::from_path(path) {
        Ok(format) => reader.set_format(format),
        Err(_) => reader = reader.with_guessed_format().map_err(|e| codec(image::ImageError::IoError(e)))?,
    }
    let mut limits = image::Limits::default();
    limits.max_image_width = Some(MAX_SIDE);
    limits.max_image_height = Some(MAX_SIDE);
    limits.max_alloc = Some(MAX_DECODE_BYTES);
    reader.limits(limits);
    let img = reader.decode().map_err(codec)?;
    let is_linear = reader_is_linear(path, bytes);
    let rgba = img.to_rgba32f();
    let (width, height) = rgba.dimensions();
    let pixels = rgba
        .pixels()
        .map(|p| {
            if is_linear {
                p.0
            } else {
                [srgb_to_linear(p.0[0]), srgb_to_linear(p.0[1]), srgb_to_linear(p.0[2]), p.0[3]]
            }
        })
        .collect();
    Ok(HdrImage { width, height, pixels })
}

/// Whether the bytes are (or the path names) OpenEXR or Radiance HDR: linear data, no sRGB
/// decoding.
fn reader_is_linear(path: &Path, bytes: &[u8]) -> bool {
    path.extension().is_some_and(|e| e.eq_ignore_ascii_case("exr") || e.eq_ignore_ascii_case("hdr"))
        || bytes.starts_with(&[0x76, 0x2f, 0x31, 0x01])
        || bytes.starts_with(b"#?RADIANCE")
        || bytes.starts_with(b"#?RGBE")
}

/// The sRGB decoding curve.
pub fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 { c / 12.92 } else { ((c + 0.055) / 1.055).powf(2.4) }
}

/// What an output path asks for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OutputKind {
    /// Linear radiance.
    Exr,
    /// Tonemapped sRGB.
    Png,
}

/// Chooses the output kind from the extension.
pub fn output_kind(path: &Path) -> Result<OutputKind, ImageIoError> {
    match path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).as_deref() {
        Some("exr") => Ok(OutputKind::Exr),
        Some("png") => Ok(OutputKind::Png),
        _ => Err(ImageIoError::Extension(path.to_owned())),
    }
}

/// The first pixel (x, y) with a NaN or infinite channel, if any.
pub fn first_non_finite(img: &HdrImage) -> Option<(u32, u32)> {
    let i = img.pixels.iter().position(|p| p.iter().any(|c| !c.is_finite()))?;
    let w = img.width.max(1) as usize;
    Some(((i % w) as u32, (i / w) as u32))
}

/// The CPU twin of `shaders/render/tonemap.wgsl`: exposure, operator, sRGB encoding to RGBA8.
pub fn tonemap_srgb8(img: &HdrImage, view: &crate::settings::ViewSettings) -> Vec<u8> {
    use crate::settings::Tonemap;
    let k = view.exposure_ev.exp2();
    let encode = |c: f32| {
        let c = c.clamp(0.0, 1.0);
        let s = if c <= 0.003_130_8 { 12.92 * c } else { 1.055 * c.powf(1.0 / 2.4) - 0.055 };
        (s * 255.0 + 0.5) as u8
    };
    img.pixels
        .iter()
        .flat_map(|p| {
            let c = [p[0] * k, p[1] * k, p[2] * k].map(|v| v.max(0.0));
            let m = match view.tonemap {
                Tonemap::Clamp => c,
                Tonemap::Reinhard => {
                    let l = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
                    c.map(|v| v / (1.0 + l))
                }
                Tonemap::Aces => c.map(|v| (v * (2.51 * v + 0.03)) / (v * (2.43 * v + 0.59) + 0.14)),
            };
            [encode(m[0]), encode(m[1]), encode(m[2]), 255]
        })
        .collect()
}

/// Averages `k` x `k` blocks of a `size` image (a box pixel filter).
pub fn box_downsample(pixels: &[[f32; 4]], size: (u32, u32), k: u32) -> Vec<[f32; 4]> {
    if k <= 1 {
        return pixels.to_vec();
    }
    let (w, h) = (size.0 / k, size.1 / k);
    let inv = 1.0 / (k * k) as f32;
    let mut out = vec![[0.0f32; 4]; (w * h) as usize];
    for y in 0..size.1 {
        for x in 0..size.0 {
            let (ox, oy) = (x / k, y / k);
            if ox >= w || oy >= h {
                continue;
            }
            let src = pixels[(y * size.0 + x) as usize];
            let dst = &mut out[(oy * w + ox) as usize];
            for c in 0..4 {
                dst[c] += src[c] * inv;
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_first_non_finite_pixel_is_found_by_position() {
        let mut img = HdrImage { width: 3, height: 2, pixels: vec![[0.5; 4]; 6] };
        assert_eq!(first_non_finite(&img), None);
        img.pixels[4][1] = f32::NAN;
        img.pixels[5][0] = f32::INFINITY;
        assert_eq!(first_non_finite(&img), Some((1, 1)));
    }
}
