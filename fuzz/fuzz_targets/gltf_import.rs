//! glTF and GLB bytes: an asset or a named error. A panic inside the importer is caught and
//! reported as `ImportError::Internal`; here that counts as a crash, so the fuzzer finds the
//! inputs that reach one.
#![no_main]

use std::path::Path;

use bouncelab::import::{ImportError, import_slice};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    // An empty folder: relative URIs name files that do not exist.
    let base = Path::new("/nonexistent-bouncelab-fuzz");
    if let Err(ImportError::Internal { message, .. }) = import_slice(data, base, Path::new("fuzz.gltf")) {
        panic!("the importer panicked: {message}");
    }
});
