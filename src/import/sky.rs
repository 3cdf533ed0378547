//! Loads an environment's equirectangular sky image ([`crate::scene::Sky::Image`]).
//!
//! Exists so that a project file, a recovery file and the command line's `--sky FILE` all turn
//! a path into the same [`SkyImage`]: HDR only (an 8-bit PNG cannot hold a sky whose sun is
//! thousands of times its zenith), box-filtered down to at most [`MAX_SKY_WIDTH`] texels a row
//! (a 16k panorama would cost 1.5 GB and the importance sampler's tables with it, for detail no
//! indirect light resolves), every texel checked finite and non-negative.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use crate::image_io;
use crate::scene::{Environment, Sky, SkyImage};

/// The widest sky image kept (texels a row); wider ones are box-filtered by a power of two.
pub const MAX_SKY_WIDTH: u32 = 2048;

/// Why a sky image could not be loaded. Names the file.
#[derive(Debug, thiserror::Error)]
pub enum SkyError {
    /// Not an HDR format.
    #[error("{0}: a sky image must be HDR (.hdr or .exr): 8-bit images cannot hold the sky's range")]
    NotHdr(PathBuf),
    /// Reading or decoding failed.
    #[error(transparent)]
    Read(#[from] image_io::ImageIoError),
    /// The decoded texels are unusable.
    #[error("{path}: {message}")]
    Bad { path: PathBuf, message: String },
}

/// The image of `env`'s sky, if it is an image (`base`: the folder relative paths start from).
pub fn load_sky(env: &Environment, base: &Path) -> Result<Option<Arc<SkyImage>>, SkyError> {
    let Sky::Image(name) = &env.sky else { return Ok(None) };
    let path = base.join(name);
    load_sky_file(&path).map(|img| Some(Arc::new(img)))
}

/// Decodes one `.hdr` or `.exr` file as a sky image.
pub fn load_sky_file(path: &Path) -> Result<SkyImage, SkyError> {
    let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    if !matches!(ext.as_deref(), Some("hdr" | "exr")) {
        return Err(SkyError::NotHdr(path.to_owned()));
    }
    let hdr = image_io::read_linear(path)?;
    let mut k = 1;
    while hdr.width / k > MAX_SKY_WIDTH && hdr.height / (2 * k) > 0 {
        k *= 2;
    }
    let pixels = image_io::box_downsample(&hdr.pixels, (hdr.width, hdr.height), k);
    let img = SkyImage {
        width: hdr.width / k,
        height: hdr.height / k,
        texels: pixels.iter().map(|p| [p[0], p[1], p[2]]).collect(),
    };
    img.validate().map_err(|e| SkyError::Bad { path: path.to_owned(), message: e.to_string() })?;
    if k > 1 {
        log::info!("{}: sky image box-filtered by {k} to {}x{}", path.display(), img.width, img.height);
    }
    Ok(img)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_ldr_sky_is_refused_by_name_and_an_exr_sky_loads_linear() {
        let dir = std::env::temp_dir().join(format!("bouncelab-sky-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("dir");
        let png = dir.join("sky.png");
        let err = load_sky_file(&png).expect_err("a PNG sky").to_string();
        assert!(err.contains("sky.png") && err.contains("HDR"), "{err}");
        let exr = dir.join("sky.exr");
        let pixels = vec![[0.25, 0.5, 4.0, 1.0]; 8 * 4];
        image_io::write_exr(&exr, &image_io::HdrImage { width: 8, height: 4, pixels }).expect("write");
        let img = load_sky_file(&exr).expect("load");
        assert_eq!((img.width, img.height), (8, 4));
        assert_eq!(img.texels[5], [0.25, 0.5, 4.0]);
        // A panorama wider than MAX_SKY_WIDTH is box-filtered by a power of two.
        let wide = dir.join("wide.exr");
        let pixels = (0..4096 * 4).map(|i| if i % 2 == 0 { [1.0, 1.0, 1.0, 1.0] } else { [3.0; 4] }).collect();
        image_io::write_exr(&wide, &image_io::HdrImage { width: 4096, height: 4, pixels }).expect("write");
        let img = load_sky_file(&wide).expect("load");
        assert_eq!((img.width, img.height), (MAX_SKY_WIDTH, 2));
        assert_eq!(img.texels[0], [2.0; 3], "each texel the mean of the 2 x 2 it stands for");
        let _ = std::fs::remove_dir_all(&dir);
    }
}
