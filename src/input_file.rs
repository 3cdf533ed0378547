//! Reading the user's input files with bounds: only regular files (a FIFO would block forever,
//! `/dev/zero` would fill memory), and never more bytes than the kind of file can sensibly hold.
//! Every reader of a scene, project, image or buffer goes through [`read`], so a hostile or
//! mistaken path is a clear error naming the file rather than a hang or an out-of-memory kill.

use std::io::Read as _;
use std::path::Path;

/// What a file is read as, with its size cap.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// A project file (`.ron`): text, a few MB even for 100,000 objects.
    Project,
    /// A glTF scene (`.gltf` JSON or `.glb` container).
    Scene,
    /// A buffer a glTF file points to.
    Buffer,
    /// An image (a texture, or an image to compare).
    Image,
    /// A cached file this program wrote (the MRT dictionary).
    Cache,
}

impl Kind {
    /// The largest file of this kind that is read (bytes).
    pub const fn cap(self) -> u64 {
        match self {
            Self::Project => 256 << 20,
            Self::Scene | Self::Buffer => 2 << 30,
            // `compare` reads this tool's own EXRs: RGBA f32 with RLE, 16 bytes a pixel.
            Self::Image => 2 << 30,
            Self::Cache => 1 << 30,
        }
    }

    /// How errors name the kind.
    pub const fn name(self) -> &'static str {
        match self {
            Self::Project => "project file",
            Self::Scene => "scene file",
            Self::Buffer => "buffer",
            Self::Image => "image",
            Self::Cache => "cache file",
        }
    }
}

/// Reads `path` whole if it is a regular file (symlinks followed) of at most `kind.cap()` bytes.
/// The error is an `io::Error` whose text says what is wrong; callers prefix the path.
pub fn read(path: &Path, kind: Kind) -> std::io::Result<Vec<u8>> {
    let meta = std::fs::metadata(path)?;
    check_regular(&meta, kind)?;
    let cap = kind.cap();
    if meta.len() > cap {
        return Err(too_large(meta.len(), kind));
    }
    // The size can change between the check and the read (a growing log, a file being written):
    // read at most one byte past the cap and refuse if it is there.
    let file = std::fs::File::open(path)?;
    let mut bytes = Vec::with_capacity(usize::try_from(meta.len()).unwrap_or(0));
    file.take(cap + 1).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > cap {
        return Err(too_large(bytes.len() as u64, kind));
    }
    Ok(bytes)
}

/// Reads `path` as UTF-8 text with [`read`]'s checks.
pub fn read_text(path: &Path, kind: Kind) -> std::io::Result<String> {
    String::from_utf8(read(path, kind)?)
        .map_err(|e| std::io::Error::new(std::io::ErrorKind::InvalidData, format!("not UTF-8 text: {e}")))
}

/// Refuses anything but a regular file, naming what it is.
fn check_regular(meta: &std::fs::Metadata, kind: Kind) -> std::io::Result<()> {
    if meta.is_file() {
        return Ok(());
    }
    let what = if meta.is_dir() { "a folder" } else { special_kind(meta) };
    Err(std::io::Error::new(
        std::io::ErrorKind::InvalidInput,
        format!("is {what}, not a regular file; a {} is read only from a regular file", kind.name()),
    ))
}

#[cfg(unix)]
fn special_kind(meta: &std::fs::Metadata) -> &'static str {
    use std::os::unix::fs::FileTypeExt as _;
    let t = meta.file_type();
    if t.is_fifo() {
        "a FIFO (named pipe)"
    } else if t.is_char_device() || t.is_block_device() {
        "a device"
    } else if t.is_socket() {
        "a socket"
    } else {
        "not a regular file"
    }
}

#[cfg(not(unix))]
fn special_kind(_meta: &std::fs::Metadata) -> &'static str {
    "a special file"
}

fn too_large(len: u64, kind: Kind) -> std::io::Error {
    std::io::Error::new(
        std::io::ErrorKind::InvalidData,
        format!(
            "is {:.1} MB, over the {:.0} MB limit for a {}",
            len as f64 / 1e6,
            kind.cap() as f64 / 1e6,
            kind.name()
        ),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[cfg(unix)]
    #[test]
    fn devices_folders_and_fifos_are_refused_without_reading() {
        let err = read(Path::new("/dev/zero"), Kind::Scene).expect_err("a device");
        assert!(err.to_string().contains("a device"), "{err}");
        let err = read(&std::env::temp_dir(), Kind::Project).expect_err("a folder");
        assert!(err.to_string().contains("a folder"), "{err}");
        let fifo = std::env::temp_dir().join(format!("bouncelab-fifo-{}", std::process::id()));
        let _ = std::fs::remove_file(&fifo);
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        if made.is_ok_and(|s| s.success()) {
            // Opening a FIFO for reading would block until a writer comes: this must return.
            let err = read(&fifo, Kind::Project).expect_err("a fifo");
            assert!(err.to_string().contains("FIFO"), "{err}");
            let _ = std::fs::remove_file(&fifo);
        }
    }

    #[test]
    fn a_file_over_its_cap_is_refused_and_one_under_is_read() {
        let path = std::env::temp_dir().join(format!("bouncelab-cap-{}.ron", std::process::id()));
        std::fs::write(&path, b"(format_version: 1)").expect("write");
        assert_eq!(read(&path, Kind::Project).expect("small").len(), 19);
        let f = std::fs::File::create(&path).expect("create");
        f.set_len(Kind::Project.cap() + 1).expect("sparse file");
        let err = read(&path, Kind::Project).expect_err("too large");
        assert!(err.to_string().contains("limit for a project file"), "{err}");
        let _ = std::fs::remove_file(&path);
    }
}
