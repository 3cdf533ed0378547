//! The MRT dictionary on disk: one versioned binary file per parameter set, named by a hash of
//! the parameters and the format version, written atomically. A file that is truncated, corrupt
//! (its checksum), of another version or of other parameters is never trusted: the dictionary is
//! rebuilt and the file replaced, and the caller is told why.
//!
//! Layout (little endian): magic `BLMRTDIC`, u32 format version, u64 parameter key, the
//! parameters, u32 element count; per element u8 shape, u32 res, n, k_d, k_b and seven
//! length-prefixed f64 arrays (prior, prior_sigma, data_sigma, m_sigma, u_b, t_db, l_imp); the
//! interface operators: u32 k_rlf, the light-field spectrum, u32 exit count and per exit u8
//! shape, u8 face and R_{b->rlf}, u32 turn count and per turn u8 turn and R, the response's u32
//! res, n, k_r, U_r, T_{rlf->r} and spectrum, the u32 opening positions P and the per-position
//! G_p, E_p and D_p ([`super::opening`]); then a u64 FNV-1a checksum of everything before.

use std::path::{Path, PathBuf};

use thiserror::Error;

use super::basis::Element;
use super::dictionary::{self, Dictionary, DictionaryError, DictionaryParams, Progress};
use super::interface::Exit;
use super::opening::PositionOps;
use super::operators::Interfaces;
use super::propagate::Turn;
use super::response::Response;
use super::shape::{Face, Shape};

const MAGIC: &[u8; 8] = b"BLMRTDIC";

/// Bumped whenever the file layout or the precompute's algorithm changes (old files are then
/// rebuilt, never read).
pub const FORMAT_VERSION: u32 = 4;

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
    /// corrupt); `not_cached` says why it could not be written there (the dictionary is still
    /// used for this run).
    Built { path: PathBuf, why: String, not_cached: Option<String> },
}

impl Source {
    /// One line for the user: where the dictionary came from, and where the cache lives.
    pub fn describe(&self) -> String {
        match self {
            Self::Loaded(path) => format!("loaded from {}", path.display()),
            Self::Built { path, why, not_cached: None } => format!("built ({why}) and cached in {}", path.display()),
            Self::Built { path, why, not_cached: Some(e) } => format!(
                "built ({why}) but NOT cached, so the next run builds it again: {e}; the cache belongs in {} (make it writable, or set XDG_CACHE_HOME to a writable folder)",
                path.parent().map_or_else(String::new, |d| d.display().to_string())
            ),
        }
    }
}

/// Dictionaries of other parameter sets kept besides the one in use (least recently used
/// first to go): each is 20-28 MB, and every parameter set ever tried used to stay forever.
pub const KEEP_OTHERS: usize = 3;

fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325u64, |h, b| (h ^ u64::from(*b)).wrapping_mul(0x0100_0000_01b3))
}

fn params_bytes(p: &DictionaryParams) -> Vec<u8> {
    let i = &p.interfaces;
    let mut out = Vec::new();
    for v in [
        p.res as u64,
        p.k_d as u64,
        p.k_b as u64,
        p.rays as u64,
        p.enrichment as u64,
        p.seed,
        i.positions as u64,
        i.directions as u64,
        i.supersample as u64,
        i.k_rlf as u64,
        i.k_r as u64,
        i.enrichment as u64,
        i.bands as u64,
    ] {
        out.extend_from_slice(&v.to_le_bytes());
    }
    out
}

fn put_array(out: &mut Vec<u8>, a: &[f64]) {
    out.extend_from_slice(&(a.len() as u64).to_le_bytes());
    a.iter().for_each(|x| out.extend_from_slice(&x.to_le_bytes()));
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
            put_array(&mut out, a);
        }
    }
    let i = &d.interfaces;
    out.extend_from_slice(&(i.k_rlf as u32).to_le_bytes());
    put_array(&mut out, &i.sigma);
    out.extend_from_slice(&(i.exits.len() as u32).to_le_bytes());
    for e in &i.exits {
        out.push(Shape::ALL.iter().position(|s| *s == e.shape).unwrap_or(0) as u8);
        out.push(e.face as u8);
        put_array(&mut out, &e.r_b_rlf);
    }
    out.extend_from_slice(&(i.turns.len() as u32).to_le_bytes());
    for (turn, r) in &i.turns {
        out.push(Turn::ALL.iter().position(|t| t == turn).unwrap_or(0) as u8);
        put_array(&mut out, r);
    }
    let r = &i.response;
    for v in [r.res, r.n, r.k_r] {
        out.extend_from_slice(&(v as u32).to_le_bytes());
    }
    put_array(&mut out, &r.u_r);
    put_array(&mut out, &r.t_rlf_r);
    put_array(&mut out, &r.sigma);
    let p = &i.positions;
    out.extend_from_slice(&(p.positions as u32).to_le_bytes());
    for a in [&p.gram, &p.irradiance, &p.diffuse] {
        put_array(&mut out, a);
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
    let expected = params_bytes(params);
    if r.u64()? != key(params) || r.take(expected.len())? != expected.as_slice() {
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
    let interfaces = read_interfaces(&mut r, params, &elements)?;
    if r.at != body.len() {
        return Err("trailing bytes after the interface operators".into());
    }
    Ok(Dictionary { params: *params, elements, interfaces })
}

/// The interface operators' part of the file.
fn read_interfaces(r: &mut Reader<'_>, params: &DictionaryParams, elements: &[Element]) -> Result<Interfaces, String> {
    let k_rlf = r.u32()? as usize;
    if k_rlf == 0 || k_rlf > params.interfaces.k_rlf {
        return Err(format!("k_rlf {k_rlf} is outside 1..={}", params.interfaces.k_rlf));
    }
    let cols: usize = elements.iter().map(|e| e.k_b * e.shape.open_faces().len()).sum();
    // The last enrichment pass reduces the basis, its three turns and its `bands` masked copies.
    let sigma = r.spectrum(cols.max((4 + params.interfaces.bands) * k_rlf))?;
    let count = r.u32()? as usize;
    if count != Shape::ALL.iter().map(|s| s.open_faces().len()).sum::<usize>() {
        return Err(format!("{count} openings"));
    }
    let mut exits = Vec::with_capacity(count);
    for _ in 0..count {
        let shape = *Shape::ALL.get(usize::from(r.take(1)?[0])).ok_or("an unknown shape")?;
        let face = *Face::ALL.get(usize::from(r.take(1)?[0])).ok_or("an unknown face")?;
        let k_b = elements.iter().find(|e| e.shape == shape).map_or(0, |e| e.k_b);
        if !shape.is_open(face) {
            return Err(format!("an exit through the closed {face:?} side of the {}", shape.name()));
        }
        exits.push(Exit { shape, face, r_b_rlf: r.array(k_rlf * k_b)? });
    }
    let count = r.u32()? as usize;
    if count != Turn::ALL.len() {
        return Err(format!("{count} propagation operators"));
    }
    let mut turns = Vec::with_capacity(count);
    for _ in 0..count {
        let turn = *Turn::ALL.get(usize::from(r.take(1)?[0])).ok_or("an unknown turn")?;
        turns.push((turn, r.array(k_rlf * k_rlf)?));
    }
    let (res, n, k_r) = (r.u32()? as usize, r.u32()? as usize, r.u32()? as usize);
    if res != params.res || n != super::response::layout(res).len() || k_r == 0 || k_r > params.interfaces.k_r {
        return Err("the surface response has inconsistent sizes".into());
    }
    let response = Response {
        res,
        n,
        k_r,
        u_r: r.array(n * k_r)?,
        t_rlf_r: r.array(k_r * k_rlf)?,
        sigma: r.spectrum(n.min(k_rlf))?,
    };
    let p = r.u32()? as usize;
    if p != params.interfaces.positions {
        return Err(format!("{p} opening positions where the parameters give {}", params.interfaces.positions));
    }
    let positions = PositionOps {
        positions: p,
        k: k_rlf,
        gram: r.array(p * p * k_rlf * k_rlf)?,
        irradiance: r.array(p * p * k_rlf)?,
        diffuse: r.array(p * p * k_rlf)?,
    };
    Ok(Interfaces { k_rlf, sigma, exits, turns, response, positions })
}

/// The dictionary for `params` from `dir`, or built (and written there) when the file is
/// missing, stale or damaged.
pub fn load_or_build(
    dir: &Path,
    params: &DictionaryParams,
    progress: &Progress,
) -> Result<(Dictionary, Source), CacheError> {
    let path = path_for(dir, params);
    let why = match crate::input_file::read(&path, crate::input_file::Kind::Cache) {
        Ok(bytes) => match decode(&bytes, params) {
            Ok(d) => {
                // Its modification time is its last use (the pruning's order).
                let _ = std::fs::File::options()
                    .write(true)
                    .open(&path)
                    .and_then(|f| f.set_modified(std::time::SystemTime::now()));
                return Ok((d, Source::Loaded(path)));
            }
            Err(what) => what,
        },
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => "no cached file".to_owned(),
        Err(e) => e.to_string(),
    };
    let d = dictionary::build(params, progress)?;
    let written = std::fs::create_dir_all(dir)
        .map_err(|e| format!("{}: {e}", dir.display()))
        .and_then(|()| crate::atomic_file::write(&path, &encode(&d)).map_err(|e| format!("{}: {e}", path.display())));
    let not_cached = match written {
        Ok(()) => {
            prune(dir, &path, KEEP_OTHERS);
            None
        }
        Err(e) => {
            log::warn!("the MRT dictionary was built but could not be cached: {e}");
            Some(e)
        }
    };
    Ok((d, Source::Built { path, why, not_cached }))
}

/// Removes dictionary files in `dir` other than `keep`, all but the `others` most recently
/// used; returns how many were removed.
pub fn prune(dir: &Path, keep: &Path, others: usize) -> usize {
    let Ok(entries) = std::fs::read_dir(dir) else { return 0 };
    let mut files: Vec<(std::time::SystemTime, PathBuf)> = entries
        .flatten()
        .map(|e| e.path())
        .filter(|p| {
            p.as_path() != keep
                && p.file_name()
                    .and_then(|n| n.to_str())
                    .is_some_and(|n| n.starts_with("mrt-dictionary-") && n.ends_with(".bin"))
        })
        .filter_map(|p| Some((std::fs::metadata(&p).and_then(|m| m.modified()).ok()?, p)))
        .collect();
    files.sort_by_key(|f| std::cmp::Reverse(f.0));
    files.iter().skip(others).filter(|(_, p)| std::fs::remove_file(p).is_ok()).count()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tiny() -> DictionaryParams {
        DictionaryParams { rays: 16, seed: 4, ..dictionary::test_params() }
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

    #[test]
    fn the_cache_keeps_the_recently_used_and_a_failed_write_keeps_the_dictionary() {
        let dir = std::env::temp_dir().join(format!("bouncelab-mrt-prune-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("dir");
        let old = std::time::SystemTime::now() - std::time::Duration::from_secs(3600);
        for k in 0..6u64 {
            let p = dir.join(format!("mrt-dictionary-{k:016x}.bin"));
            std::fs::write(&p, b"x").expect("write");
            let f = std::fs::File::options().write(true).open(&p).expect("open");
            f.set_modified(old + std::time::Duration::from_secs(k)).expect("mtime");
        }
        std::fs::write(dir.join("notes.txt"), b"mine").expect("write");
        let keep = dir.join("mrt-dictionary-0000000000000000.bin");
        assert_eq!(prune(&dir, &keep, 3), 2, "six files: the one in use and the three newest others stay");
        for k in [0u64, 3, 4, 5] {
            assert!(dir.join(format!("mrt-dictionary-{k:016x}.bin")).exists(), "{k} kept");
        }
        assert!(dir.join("notes.txt").exists(), "only dictionaries are pruned");
        // A cache folder that cannot be made (a file stands there): built, used, and said.
        let blocked = dir.join("notes.txt").join("cache");
        let (d, source) = load_or_build(&blocked, &tiny(), &Progress::default()).expect("still built");
        assert!(!d.elements.is_empty());
        assert!(matches!(&source, Source::Built { not_cached: Some(_), .. }), "{source:?}");
        assert!(source.describe().contains("NOT cached"), "{}", source.describe());
        let _ = std::fs::remove_dir_all(&dir);
    }
}
