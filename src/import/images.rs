//! Image decoding (PNG, JPEG) from URIs or buffer views, to RGBA8.

use std::path::Path;

use super::{ImportError, uri};
use crate::scene::Image;

/// Largest accepted image side (texels).
const MAX_IMAGE_SIDE: u32 = 8192;

pub(super) fn load_images(
    doc: &gltf::Document,
    buffers: &[Vec<u8>],
    base_dir: &Path,
    path: &Path,
) -> Result<Vec<Image>, ImportError> {
    doc.images()
        .map(|image| {
            let index = image.index();
            let err = |message: String| ImportError::Image { path: path.to_owned(), index, message };
            let bytes = match image.source() {
                gltf::image::Source::Uri { uri: u, .. } => uri::load(u, base_dir).map_err(|e| err(e.to_string()))?,
                gltf::image::Source::View { view, .. } => {
                    let buffer = buffers
                        .get(view.buffer().index())
                        .ok_or_else(|| err(format!("buffer {} is missing", view.buffer().index())))?;
                    let end = view.offset().checked_add(view.length()).filter(|e| *e <= buffer.len());
                    let end = end.ok_or_else(|| err("bufferView reaches past its buffer".into()))?;
                    buffer[view.offset()..end].to_vec()
                }
            };
            decode(&bytes).map_err(err)
        })
        .collect()
}

fn decode(bytes: &[u8]) -> Result<Image, String> {
    let reader =
        image::ImageReader::new(std::io::Cursor::new(bytes)).with_guessed_format().map_err(|e| e.to_string())?;
    let (w, h) = reader.into_dimensions().map_err(|e| e.to_string())?;
    if w == 0 || h == 0 || w > MAX_IMAGE_SIDE || h > MAX_IMAGE_SIDE {
        return Err(format!("{w}x{h} is outside 1..={MAX_IMAGE_SIDE} texels per side"));
    }
    let img = image::load_from_memory(bytes).map_err(|e| e.to_string())?.to_rgba8();
    Ok(Image { width: img.width(), height: img.height(), rgba8: img.into_raw() })
}
