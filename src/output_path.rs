//! Checks on an output path before any work starts, so that a command never clobbers one of its
//! own inputs, never writes one format under another's extension, never replaces a read-only
//! file, and never finds out after a long render that the path is a folder or not writable.
//! Every command that writes a file (`render`, `compare --heatmap`, `fit-blocks`, the editor's
//! image export) calls [`check`] first; the write itself then goes through `atomic_file`.

use std::path::{Path, PathBuf};

/// Why an output path is refused. Every variant names the path.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    /// The extension does not name what the command writes.
    #[error("{path}: this writes {what}; the file name must end in {expected}")]
    Extension { path: PathBuf, what: &'static str, expected: String },
    /// The path is one of the command's inputs.
    #[error("{path}: is also an input ({input}); writing there would destroy it, choose another output path")]
    IsInput { path: PathBuf, input: PathBuf },
    /// The path is a folder.
    #[error("{path}: is a folder; give a file name")]
    Folder { path: PathBuf },
    /// The path is a device, FIFO or socket.
    #[error("{path}: is not a regular file; refusing to write to it")]
    Special { path: PathBuf },
    /// The file exists and is read-only.
    #[error("{path}: is read-only; refusing to replace it (make it writable or choose another path)")]
    ReadOnly { path: PathBuf },
    /// Its folder cannot be created or written.
    #[error("{path}: cannot create or write in the folder {folder}: {source}")]
    NotWritable { path: PathBuf, folder: PathBuf, source: std::io::Error },
}

/// What a command writes: a description and the extensions that name it (lower case, no dot).
#[derive(Clone, Copy, Debug)]
pub struct Writes {
    /// For the message (`"a RON project file"`).
    pub what: &'static str,
    /// Accepted extensions.
    pub extensions: &'static [&'static str],
}

/// A project file.
pub const PROJECT: Writes = Writes { what: "a RON project file", extensions: &["ron"] };
/// A rendered image: linear EXR or tonemapped PNG.
pub const IMAGE: Writes = Writes { what: "an EXR (linear) or PNG (tonemapped) image", extensions: &["exr", "png"] };
/// A Markdown document (`bench`'s reports).
pub const MARKDOWN: Writes = Writes { what: "a Markdown document", extensions: &["md"] };
/// A glTF scene (`bouncelab export`).
pub const GLTF: Writes = Writes { what: "a glTF scene (.gltf or .glb)", extensions: &["gltf", "glb"] };
/// A JSON document (`profile`).
pub const JSON: Writes = Writes { what: "a JSON document", extensions: &["json"] };
/// A PNG picture (heat maps).
pub const PNG: Writes = Writes { what: "a PNG image", extensions: &["png"] };

/// Refuses `out` when it does not name what `writes` says, is one of `inputs`, is a folder or
/// special file, is read-only, or lies in a folder that cannot be created or written. Creates
/// the folder if it is missing.
pub fn check(out: &Path, writes: Writes, inputs: &[&Path]) -> Result<(), OutputError> {
    check_not_input(out, inputs)?;
    check_extension(out, writes)?;
    check_existing(out)?;
    check_folder(out)
}

fn check_extension(out: &Path, writes: Writes) -> Result<(), OutputError> {
    let ext = out.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    if ext.as_deref().is_some_and(|e| writes.extensions.contains(&e)) {
        return Ok(());
    }
    let expected = writes.extensions.iter().map(|e| format!(".{e}")).collect::<Vec<_>>().join(" or ");
    Err(OutputError::Extension { path: out.to_owned(), what: writes.what, expected })
}

fn check_existing(out: &Path) -> Result<(), OutputError> {
    let Ok(meta) = std::fs::metadata(out) else { return Ok(()) };
    if meta.is_dir() {
        return Err(OutputError::Folder { path: out.to_owned() });
    }
    if !meta.is_file() {
        return Err(OutputError::Special { path: out.to_owned() });
    }
    if meta.permissions().readonly() {
        return Err(OutputError::ReadOnly { path: out.to_owned() });
    }
    Ok(())
}

/// The path `p` resolves to: canonical if it exists, else its canonical folder and its name,
/// else `p` made absolute with `.` and `..` taken lexically.
pub fn resolved(p: &Path) -> PathBuf {
    if let Ok(c) = std::fs::canonicalize(p) {
        return c;
    }
    let dir = match p.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    if let (Some(name), Ok(d)) = (p.file_name(), std::fs::canonicalize(dir)) {
        return d.join(name);
    }
    let absolute = std::path::absolute(p).unwrap_or_else(|_| p.to_owned());
    let mut out = PathBuf::new();
    for c in absolute.components() {
        match c {
            std::path::Component::ParentDir => {
                out.pop();
            }
            std::path::Component::CurDir => {}
            other => out.push(other),
        }
    }
    out
}

fn check_not_input(out: &Path, inputs: &[&Path]) -> Result<(), OutputError> {
    let target = resolved(out);
    for input in inputs {
        if resolved(input) == target || same_file(out, input) {
            return Err(OutputError::IsInput { path: out.to_owned(), input: input.to_path_buf() });
        }
    }
    Ok(())
}

/// Two names of one file (a hard link).
#[cfg(unix)]
fn same_file(a: &Path, b: &Path) -> bool {
    use std::os::unix::fs::MetadataExt as _;
    match (std::fs::metadata(a), std::fs::metadata(b)) {
        (Ok(x), Ok(y)) => x.dev() == y.dev() && x.ino() == y.ino(),
        _ => false,
    }
}

#[cfg(not(unix))]
fn same_file(_a: &Path, _b: &Path) -> bool {
    false
}

/// Creates `out`'s folder and probes that a file can be created there.
fn check_folder(out: &Path) -> Result<(), OutputError> {
    let folder = match out.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_owned(),
        _ => PathBuf::from("."),
    };
    let fail = |source| OutputError::NotWritable { path: out.to_owned(), folder: folder.clone(), source };
    std::fs::create_dir_all(&folder).map_err(fail)?;
    static NEXT: std::sync::atomic::AtomicU32 = std::sync::atomic::AtomicU32::new(0);
    let n = NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let probe = folder.join(format!(".bouncelab-write-probe-{}-{n}", std::process::id()));
    match std::fs::OpenOptions::new().write(true).create_new(true).open(&probe) {
        Ok(_) => {
            let _ = std::fs::remove_file(&probe);
            Ok(())
        }
        // A probe a killed run left behind: the folder took a file once.
        Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => Ok(()),
        Err(e) => Err(fail(e)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dir(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("bouncelab-out-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).expect("dir");
        d
    }

    #[test]
    fn an_input_under_another_spelling_is_refused() {
        let d = dir("input");
        let input = d.join("level.ron");
        std::fs::write(&input, "x").expect("write");
        std::fs::create_dir_all(d.join("sub")).expect("dir");
        let other = d.join("sub/../level.ron");
        let err = check(&other, PROJECT, &[&input]).expect_err("the input");
        assert!(matches!(err, OutputError::IsInput { .. }), "{err}");
        check(&d.join("fitted.ron"), PROJECT, &[&input]).expect("another name is fine");
    }

    #[test]
    fn extensions_folders_and_read_only_files_are_refused() {
        let d = dir("kinds");
        assert!(matches!(check(&d.join("photo.jpg"), IMAGE, &[]), Err(OutputError::Extension { .. })));
        assert!(matches!(check(&d.join("notes.txt"), PROJECT, &[]), Err(OutputError::Extension { .. })));
        assert!(matches!(check(&d.join("map.exr"), PNG, &[]), Err(OutputError::Extension { .. })));
        let folder = d.join("out.png");
        std::fs::create_dir_all(&folder).expect("dir");
        assert!(matches!(check(&folder, IMAGE, &[]), Err(OutputError::Folder { .. })));
        let ro = d.join("kept.png");
        std::fs::write(&ro, "x").expect("write");
        let mut perms = std::fs::metadata(&ro).expect("meta").permissions();
        perms.set_readonly(true);
        std::fs::set_permissions(&ro, perms).expect("chmod");
        assert!(matches!(check(&ro, IMAGE, &[]), Err(OutputError::ReadOnly { .. })));
        check(&d.join("new/deeper/x.EXR"), IMAGE, &[]).expect("a new folder and upper-case extension");
    }
}
