//! Project files: any text either parses (and then resolves and validates with a clear error
//! or a scene) or is a named error; never a panic, hang or unbounded allocation.
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    let path = Path::new("fuzz.ron");
    if let Ok(file) = bouncelab::project_file::parse(text, path) {
        let _ = file.render.validate();
        // No assets: objects that name one fail by name; generated meshes resolve and validate.
        let _ = bouncelab::import::resolve(file.scene, &[]);
    }
});
