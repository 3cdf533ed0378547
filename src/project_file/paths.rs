//! Relative asset paths, written with forward slashes so project files diff the same on every
//! platform.

use std::path::{Component, Path, PathBuf};

fn absolute(p: &Path) -> PathBuf {
    let p = if p.is_absolute() { p.to_owned() } else { std::env::current_dir().unwrap_or_default().join(p) };
    let mut out = PathBuf::new();
    for c in p.components() {
        match c {
            Component::ParentDir => {
                out.pop();
            }
            Component::CurDir => {}
            other => out.push(other),
        }
    }
    out
}

/// `target` relative to the folder `base`, with `/` separators.
pub fn relative_to(target: &Path, base: &Path) -> String {
    let (t, b) = (absolute(target), absolute(base));
    let tc: Vec<_> = t.components().collect();
    let bc: Vec<_> = b.components().collect();
    let common = tc.iter().zip(&bc).take_while(|(a, b)| a == b).count();
    let mut parts: Vec<String> = std::iter::repeat_n("..".to_owned(), bc.len() - common).collect();
    parts.extend(tc[common..].iter().map(|c| c.as_os_str().to_string_lossy().into_owned()));
    parts.join("/")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn relative_paths() {
        assert_eq!(relative_to(Path::new("/a/assets/x.gltf"), Path::new("/a/projects")), "../assets/x.gltf");
        assert_eq!(relative_to(Path::new("/a/x.gltf"), Path::new("/a")), "x.gltf");
        assert_eq!(
            relative_to(Path::new("/a/projects/../assets/x.gltf"), Path::new("/a/projects")),
            "../assets/x.gltf"
        );
    }
}
