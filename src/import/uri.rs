//! Loading buffer and image URIs without trusting the file: `data:` URIs and relative paths
//! that stay inside the model's folder only.

use std::path::{Component, Path, PathBuf};

use base64::Engine as _;

/// Why a URI could not be loaded.
#[derive(Debug, thiserror::Error)]
pub enum UriError {
    /// Absolute paths, `file:`, `http(s):` and `..` escapes are refused.
    #[error("refusing URI {0:?}: only data: URIs and relative paths inside the model's folder are allowed")]
    Refused(String),
    /// A `data:` URI that is not base64 or does not decode.
    #[error("malformed data URI: {0}")]
    BadData(String),
    /// The referenced file could not be read.
    #[error("cannot read {path}: {source}")]
    Io { path: PathBuf, source: std::io::Error },
}

fn percent_decode(s: &str) -> String {
    let bytes = s.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%'
            && i + 2 < bytes.len()
            && let Some(v) = std::str::from_utf8(&bytes[i + 1..i + 3]).ok().and_then(|h| u8::from_str_radix(h, 16).ok())
        {
            out.push(v);
            i += 3;
            continue;
        }
        out.push(bytes[i]);
        i += 1;
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// The file a URI names (`None` for `data:` URIs and refused ones).
pub fn file_path(uri: &str, base_dir: &Path) -> Option<PathBuf> {
    if uri.starts_with("data:") {
        return None;
    }
    let decoded = percent_decode(uri);
    let rel = Path::new(&decoded);
    rel.components().all(|c| matches!(c, Component::Normal(_) | Component::CurDir)).then(|| base_dir.join(rel))
}

/// Resolves and reads `uri` relative to `base_dir`; a file is read as `kind` (bounded).
pub fn load(uri: &str, base_dir: &Path, kind: crate::input_file::Kind) -> Result<Vec<u8>, UriError> {
    if let Some(rest) = uri.strip_prefix("data:") {
        let (_, payload) = rest
            .split_once(";base64,")
            .ok_or_else(|| UriError::BadData("only base64 data URIs are supported".into()))?;
        return base64::engine::general_purpose::STANDARD
            .decode(payload.trim())
            .map_err(|e| UriError::BadData(e.to_string()));
    }
    let has_scheme = uri
        .split_once(':')
        .is_some_and(|(s, _)| s.len() > 1 && s.chars().all(|c| c.is_ascii_alphanumeric() || "+-.".contains(c)));
    let decoded = percent_decode(uri);
    let rel = Path::new(&decoded);
    let escapes = rel.components().any(|c| !matches!(c, Component::Normal(_) | Component::CurDir));
    if has_scheme || decoded.is_empty() || escapes {
        return Err(UriError::Refused(uri.to_owned()));
    }
    let path = base_dir.join(rel);
    crate::input_file::read(&path, kind).map_err(|source| UriError::Io { path, source })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refuses_escapes() {
        let base = Path::new("/tmp");
        for uri in ["../x.bin", "/etc/passwd", "file:///etc/passwd", "http://example.com/a.bin", "a/../../b"] {
            assert!(matches!(load(uri, base, crate::input_file::Kind::Buffer), Err(UriError::Refused(_))), "{uri}");
        }
    }

    #[test]
    fn decodes_data_uri() {
        let bytes = load("data:application/octet-stream;base64,AAEC", Path::new("."), crate::input_file::Kind::Buffer)
            .expect("decodes");
        assert_eq!(bytes, vec![0, 1, 2]);
        assert!(load("data:text/plain,hello", Path::new("."), crate::input_file::Kind::Buffer).is_err());
    }
}
