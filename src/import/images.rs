//! Image decoding (PNG, JPEG) from URIs or buffer views, to RGBA8, within a memory budget: every
//! image's size is read from its header first, and an asset whose textures would need more than
//! [`TEXTURE_BUDGET`] bytes decoded is an error naming the images, before anything is decoded.

use std::path::Path;

use super::{ImportError, uri};
use crate::scene::Image;

/// Largest accepted image side (texels).
const MAX_IMAGE_SIDE: u32 = 8192;

/// The most decoded RGBA8 bytes one asset's textures may take (1 GiB: four 8192² textures, or
/// sixty-four 2048² ones). Six references to one 8192² file took 6.45 GB before there was one.
pub const TEXTURE_BUDGET: u64 = 1 << 30;

pub(super) fn load_images(
    doc: &gltf::Document,
    buffers: &[Vec<u8>],
    base_dir: &Path,
    path: &Path,
) -> Result<Vec<Image>, ImportError> {
    let err = |index: usize, message: String| ImportError::Image { path: path.to_owned(), index, message };
    let mut encoded = Vec::new();
    let mut total = 0u64;
    for image in doc.images() {
        let index = image.index();
        let bytes = source_bytes(&image, buffers, base_dir).map_err(|m| err(index, m))?;
        let (w, h) = dimensions(&bytes).map_err(|m| err(index, m))?;
        total += 4 * u64::from(w) * u64::from(h);
        if total > TEXTURE_BUDGET {
            return Err(err(
                index,
                format!(
                    "{w}x{h}: the asset's images 0..={index} need {:.0} MB decoded, over the {:.0} MB texture budget (use smaller textures)",
                    total as f64 / 1e6,
                    TEXTURE_BUDGET as f64 / 1e6
                ),
            ));
        }
        encoded.push(bytes);
    }
    encoded.iter().enumerate().map(|(index, bytes)| decode(bytes).map_err(|m| err(index, m))).collect()
}

/// The encoded bytes of `image`, from its URI (bounded) or its buffer view.
fn source_bytes(image: &gltf::Image<'_>, buffers: &[Vec<u8>], base_dir: &Path) -> Result<Vec<u8>, String> {
    match image.source() {
        gltf::image::Source::Uri { uri: u, .. } => {
            uri::load(u, base_dir, crate::input_file::Kind::Image).map_err(|e| e.to_string())
        }
        gltf::image::Source::View { view, .. } => {
            let buffer = buffers
                .get(view.buffer().index())
                .ok_or_else(|| format!("buffer {} is missing", view.buffer().index()))?;
            let end = view.offset().checked_add(view.length()).filter(|e| *e <= buffer.len());
            let end = end.ok_or_else(|| "bufferView reaches past its buffer".to_owned())?;
            Ok(buffer[view.offset()..end].to_vec())
        }
    }
}

/// The image's size from its header, checked against [`MAX_IMAGE_SIDE`].
fn dimensions(bytes: &[u8]) -> Result<(u32, u32), String> {
    let reader =
        image::ImageReader::new(std::io::Cursor::new(bytes)).with_guessed_format().map_err(|e| e.to_string())?;
    let (w, h) = reader.into_dimensions().map_err(|e| e.to_string())?;
    if w == 0 || h == 0 || w > MAX_IMAGE_SIDE || h > MAX_IMAGE_SIDE {
        return Err(format!("{w}x{h} is outside 1..={MAX_IMAGE_SIDE} texels per side"));
    }
    Ok((w, h))
}

fn decode(bytes: &[u8]) -> Result<Image, String> {
    dimensions(bytes)?;
    let img = image::load_from_memory(bytes).map_err(|e| e.to_string())?.to_rgba8();
    Ok(Image { width: img.width(), height: img.height(), rgba8: img.into_raw() })
}
