//! The image readers behind `bouncelab compare`: EXR, PNG and JPEG bytes decode or fail with a
//! named error. The first byte picks the file extension the reader is told.
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Some((&pick, bytes)) = data.split_first() else { return };
    let name = ["fuzz.exr", "fuzz.png", "fuzz.jpg", "fuzz"][usize::from(pick % 4)];
    if let Ok(img) = bouncelab::image_io::decode_linear(bytes, Path::new(name)) {
        assert_eq!(img.pixels.len(), img.width as usize * img.height as usize);
    }
});
