//! The MRT dictionary on disk: one versioned binary file per parameter set, named by a hash of
//! the parameters and the format version, written atomically. A file that is truncated, corrupt
//! (its checksum), of another version or of other parameters is never trusted: the dictionary is
//! rebuilt and the file replaced, and the caller is told why.
//!
//! Layout (little endian): magic `BLMRTDIC`, u32 format version, u64 parameter key, the
//! parameters, u32 element count; per element u8 shape, u32 res, n, k_d, k_b and seven
//! length-prefixed f64 arrays (prior, prior_sigma, data_sigma, m_sigma, u_b, t_db, l_imp); then
//! a u64 FNV-1a checksum of everything before it.

use std::path::{Path, PathBuf};

use thiserror::Error;

use super::basis::Element;
use super::dictionary::{self, Dictionary, DictionaryError, DictionaryParams, Progress};
use super::shape::Shape;

const MAGIC: &[u8; 8] = b"BLMRTDIC";

/// Bumped whenever the file layout or the precompute's algorithm changes (old files are then
/// rebuilt, never read).
pub const FORMAT_VERSION: u32 = 1;

/// Why a cache file was not used, or could not be written.
#[derive(Debug, Error)]
pub enum CacheError {
    /// Reading or writing failed.
    #[error("{path}: {source}")]
    Io {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    /// The file is not a dictionary of this version and these parameters, or is damaged.
    #[error("{path}: {what}")]
    Invalid { path: PathBuf, what: String },
    /// Building failed.
    #[error(transparent)]
    Build(#[from] DictionaryError),
}

/// Where the dictionary came from.
#[derive(Debug)]
pub enum Source {
    /// Read from this file.
    Loaded(PathBuf),
    /// Built and written to this file; `why` says why the file was not used (missing, stale,
    /// corrupt).
    Built { path: PathBuf, why: String },
}

fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325u64, |h, b| (h ^ u64::from(*b)).wrapping_mul(0x0100_0000_01b3))
}

fn params_bytes(p: &DictionaryParams) -> Vec<u8> {
    let mut out = Vec::new();
    for v in [p.res as u64, p.k_d as u64, p.k_b as u64, p.rays as u64, p.enrichment as u64, p.seed] {
        out.extend_from_slice(&v.to_le_bytes());
    }
    out
}

/// The key of a parameter set (with the format version).
pub fn key(p: &DictionaryParams) -> u64 {
    let mut bytes = FORMAT_VERSION.to_le_bytes().to_vec();
    bytes.extend(params_bytes(p));
    fnv1a(&bytes)
}

/// The cache file for `params` in `dir`.
pub fn path_for(dir: &Path, params: &DictionaryParams) -> PathBuf {
    dir.join(format!("mrt-dictionary-{:016x}.bin", key(params)))
}

/// The default cache folder: `$XDG_CACHE_HOME/bouncelab`, else `~/.cache/bouncelab`, else the
/// temp folder's `bouncelab`.
pub fn default_dir() -> PathBuf {
    let base = std::env::var_os("XDG_CACHE_HOME")
        .map(PathBuf::from)
        .or_else(|| std::env::var_os("HOME").map(|h| PathBuf::from(h).join(".cache")))
        .unwrap_or_else(std::env::temp_dir);
    base.join("bouncelab")
}

/// Serialises a dictionary.
pub fn encode(d: &Dictionary) -> Vec<u8> {
    let mut out = MAGIC.to_vec();
    out.extend_from_slice(&FORMAT_VERSION.to_le_bytes());
    out.extend_from_slice(&key(&d.params).to_le_bytes());
    out.extend(params_bytes(&d.params));
    out.extend_from_slice(&(d.elements.len() as u32).to_le_bytes());
    for e in &d.elements {
        let shape = Shape::ALL.iter().position(|s| *s == e.shape).unwrap_or(0) as u8;
        out.push(shape);
        for v in [e.res, e.n, e.k_d, e.k_b] {
            out.extend_from_slice(&(v as u32).to_le_bytes());
        }
        for a in [&e.prior, &e.prior_sigma, &e.data_sigma, &e.m_sigma, &e.u_b, &e.t_db, &e.l_imp] {
            out.extend_from_slice(&(a.len() as u64).to_le_bytes());
            a.iter().for_each(|x| out.extend_from_slice(&x.to_le_bytes()));
        }
    }
    let sum = fnv1a(&out);
    out.extend_from_slice(&sum.to_le_bytes());
    out
}

/// A cursor over the file's bytes.
struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl Reader<'_> {
    fn take(&mut self, n: usize) -> Result<&[u8], String> {
        let end = self.at.checked_add(n).filter(|e| *e <= self.bytes.len()).ok_or("the file is truncated")?;
        let s = &self.bytes[self.at..end];
        self.at = end;
        Ok(s)
    }
    fn u32(&mut self) -> Result<u32, String> {
        let b = self.take(4)?;
        Ok(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
    }
    fn u64(&mut self) -> Result<u64, String> {
        let b = self.take(8)?;
        let mut a = [0u8; 8];
        a.copy_from_slice(b);
        Ok(u64::from_le_bytes(a))
    }
    fn array(&mut self, want: usize) -> Result<Vec<f64>, String> {
        let len = self.u64()? as usize;
        if len != want {
            return Err(format!("an array holds {len} values where {want} belong"));
        }
        self.values(len)
    }
    /// Singular values: at most `most` of them.
    fn spectrum(&mut self, most: usize) -> Result<Vec<f64>, String> {
        let len = self.u64()? as usize;
        if len > most {
            return Err(format!("a spectrum holds {len} values, at most {most} belong"));
        }
        self.values(len)
    }
    fn values(&mut self, len: usize) -> Result<Vec<f64>, String> {
        let b = self.take(len.checked_mul(8).ok_or("an array is too long")?)?;
        let values: Vec<f64> = b
            .chunks_exact(8)
            .map(|c| {
                let mut a = [0u8; 8];
                a.copy_from_slice(c);
                f64::from_le_bytes(a)
            })
            .collect();
        if values.iter().any(|v| !v.is_finite()) {
            return Err("an array holds a NaN or infinite value".into());
        }
        Ok(values)
    }
}

/// Reads a dictionary built with `params`; the error says what is wrong with the bytes.
pub fn decode(bytes: &[u8], params: &DictionaryParams) -> Result<Dictionary, String> {
    if bytes.len() < MAGIC.len() + 8 || &bytes[..8] != MAGIC {
        return Err("not an MRT dictionary file".into());
    }
    let (body, sum) = bytes.split_at(bytes.len() - 8);
    let mut a = [0u8; 8];
    a.copy_from_slice(sum);
    if fnv1a(body) != u64::from_le_bytes(a) {
        return Err("its checksum does not match (damaged or truncated)".into());
    }
    let mut r = Reader { bytes: body, at: 8 };
    let version = r.u32()?;
    if version != FORMAT_VERSION {
        return Err(format!("format version {version}, this build reads {FORMAT_VERSION}"));
    }
    if r.u64()? != key(params) || r.take(48)? != params_bytes(params).as_slice() {
        return Err("built with other parameters".into());
    }
    let count = r.u32()? as usize;
    if count != Shape::ALL.len() {
        return Err(format!("{count} elements, the dictionary has {}", Shape::ALL.len()));
    }
    let mut elements = Vec::with_capacity(count);
    for _ in 0..count {
        let shape = *Shape::ALL.get(usize::from(r.take(1)?[0])).ok_or("an unknown shape")?;
        let (res, n, k_d, k_b) = (r.u32()? as usize, r.u32()? as usize, r.u32()? as usize, r.u32()? as usize);
        let expected_n = super::shape::Layout::new(shape, params.res).len();
        if res != params.res || n != expected_n || k_d > params.k_d || k_b > k_d.min(params.k_b) {
            return Err(format!("element {} has inconsistent sizes", shape.name()));
        }
        elements.push(Element {
            shape,
            res,
            n,
            k_d,
            k_b,
            prior: r.array(n * k_d)?,
            prior_sigma: r.array(k_d)?,
            data_sigma: r.spectrum(n)?,
            m_sigma: r.spectrum(k_d)?,
            u_b: r.array(n * k_b)?,
            t_db: r.array(k_b * n)?,
            l_imp: r.array(n * k_b)?,
        });
    }
    if r.at != body.len() {
        return Err("trailing bytes after the last element".into());
    }
    Ok(Dictionary { params: *params, elements })
}

/// The dictionary for `params` from `dir`, or built (and written there) when the file is
/// missing, stale or damaged.
pub fn load_or_build(
    dir: &Path,
    params: &DictionaryParams,
    progress: &Progress,
) -> Result<(Dictionary, Source), CacheError> {
    let path = path_for(dir, params);
    let why = match std::fs::read(&path) {
        Ok(bytes) => match decode(&bytes, params) {
            Ok(d) => return Ok((d, Source::Loaded(path))),
            Err(what) => what,
        },
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => "no cached file".to_owned(),
        Err(e) => e.to_string(),
    };
    let d = dictionary::build(params, progress)?;
    std::fs::create_dir_all(dir).map_err(|source| CacheError::Io { path: dir.to_owned(), source })?;
    crate::atomic_file::write(&path, &encode(&d)).map_err(|source| CacheError::Io { path: path.clone(), source })?;
    Ok((d, Source::Built { path, why }))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tiny() -> DictionaryParams {
        DictionaryParams { res: 3, k_d: 12, k_b: 6, rays: 16, enrichment: 1, seed: 4 }
    }

    #[test]
    fn a_cached_dictionary_loads_identical_to_a_fresh_build() {
        let dir = std::env::temp_dir().join(format!("bouncelab-mrt-cache-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let (built, source) = load_or_build(&dir, &tiny(), &Progress::default()).expect("build");
        assert!(matches!(source, Source::Built { .. }), "{source:?}");
        let (loaded, source) = load_or_build(&dir, &tiny(), &Progress::default()).expect("load");
        assert!(matches!(source, Source::Loaded(_)), "{source:?}");
        assert_eq!(built, loaded, "bit-identical");
        // A damaged file is rebuilt, never trusted, and the caller hears why.
        let path = path_for(&dir, &tiny());
        let mut bytes = std::fs::read(&path).expect("file");
        let mid = bytes.len() / 2;
        bytes[mid] ^= 0x40;
        std::fs::write(&path, &bytes).expect("write");
        let (rebuilt, source) = load_or_build(&dir, &tiny(), &Progress::default()).expect("rebuild");
        assert!(matches!(&source, Source::Built { why, .. } if why.contains("checksum")), "{source:?}");
        assert_eq!(rebuilt, built);
        std::fs::write(&path, &bytes[..bytes.len() / 3]).expect("write");
        assert!(decode(&std::fs::read(&path).expect("file"), &tiny()).is_err(), "truncated");
        let other = DictionaryParams { rays: 25, ..tiny() };
        assert_ne!(path_for(&dir, &other), path, "other parameters, other file");
        assert!(decode(&encode(&built), &other).is_err_and(|e| e.contains("other parameters")));
        let _ = std::fs::remove_dir_all(&dir);
    }
}
