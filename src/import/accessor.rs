//! Bounds-checked accessor reading.
//!
//! The `gltf` crate's own readers trust the file (unchecked slicing, `count - 1` underflow,
//! `unreachable!` on float indices), so every accessor is checked here against the bytes that
//! really exist, with checked arithmetic, before anything is allocated from a declared count.

use gltf::accessor::{DataType, Dimensions};

/// Why an accessor could not be read.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum AccessorError {
    /// Sparse storage is not supported.
    #[error("accessor {0} uses sparse storage, which is not supported")]
    Sparse(usize),
    /// The accessor has no buffer view (all zeros by the spec); not supported for geometry.
    #[error("accessor {0} has no bufferView")]
    NoView(usize),
    /// Wrong element shape for its use.
    #[error("accessor {index} is {found:?}, expected {expected}")]
    WrongType { index: usize, found: String, expected: &'static str },
    /// The accessor reaches past the end of its buffer view or buffer.
    #[error("accessor {0} reads past the end of its buffer (offsets, stride or count too large)")]
    OutOfBounds(usize),
    /// The referenced buffer was not loaded.
    #[error("accessor {0} refers to buffer {1}, which is missing")]
    MissingBuffer(usize, usize),
}

fn component_size(t: DataType) -> usize {
    match t {
        DataType::I8 | DataType::U8 => 1,
        DataType::I16 | DataType::U16 => 2,
        DataType::U32 | DataType::F32 => 4,
    }
}

/// Returns the raw bytes of each element (count slices of `elem_size`).
fn element_bytes<'a>(
    accessor: &gltf::Accessor<'_>,
    buffers: &'a [Vec<u8>],
) -> Result<(Vec<&'a [u8]>, DataType), AccessorError> {
    let index = accessor.index();
    if accessor.sparse().is_some() {
        return Err(AccessorError::Sparse(index));
    }
    let view = accessor.view().ok_or(AccessorError::NoView(index))?;
    let buffer_index = view.buffer().index();
    let buffer = buffers.get(buffer_index).ok_or(AccessorError::MissingBuffer(index, buffer_index))?;
    let oob = || AccessorError::OutOfBounds(index);
    let data_type = accessor.data_type();
    let elem = component_size(data_type).checked_mul(accessor.dimensions().multiplicity()).ok_or_else(oob)?;
    let stride = view.stride().unwrap_or(elem);
    if stride < elem {
        return Err(oob());
    }
    let view_end = view.offset().checked_add(view.length()).ok_or_else(oob)?;
    if view_end > buffer.len() {
        return Err(oob());
    }
    let view_bytes = &buffer[view.offset()..view_end];
    let count = accessor.count();
    if count == 0 {
        return Ok((Vec::new(), data_type));
    }
    let last_start = stride.checked_mul(count - 1).and_then(|s| s.checked_add(accessor.offset())).ok_or_else(oob)?;
    let end = last_start.checked_add(elem).ok_or_else(oob)?;
    if end > view_bytes.len() {
        return Err(oob());
    }
    let out = (0..count)
        .map(|i| {
            let start = accessor.offset() + i * stride;
            &view_bytes[start..start + elem]
        })
        .collect();
    Ok((out, data_type))
}

fn component(bytes: &[u8], t: DataType, normalized: bool, k: usize) -> f32 {
    let at = |n: usize| &bytes[k * n..k * n + n];
    match t {
        DataType::F32 => f32::from_le_bytes([at(4)[0], at(4)[1], at(4)[2], at(4)[3]]),
        DataType::U8 if normalized => f32::from(at(1)[0]) / 255.0,
        DataType::U8 => f32::from(at(1)[0]),
        DataType::I8 => {
            let v = f32::from(at(1)[0] as i8);
            if normalized { (v / 127.0).max(-1.0) } else { v }
        }
        DataType::U16 => {
            let v = f32::from(u16::from_le_bytes([at(2)[0], at(2)[1]]));
            if normalized { v / 65535.0 } else { v }
        }
        DataType::I16 => {
            let v = f32::from(i16::from_le_bytes([at(2)[0], at(2)[1]]));
            if normalized { (v / 32767.0).max(-1.0) } else { v }
        }
        DataType::U32 => u32::from_le_bytes([at(4)[0], at(4)[1], at(4)[2], at(4)[3]]) as f32,
    }
}

/// Reads a float vector accessor of exactly `N` components (normalised integers allowed).
pub fn read_vec<const N: usize>(
    accessor: &gltf::Accessor<'_>,
    buffers: &[Vec<u8>],
    expected: &'static str,
) -> Result<Vec<[f32; N]>, AccessorError> {
    let dims = accessor.dimensions();
    let ok_dims = matches!(
        (dims, N),
        (Dimensions::Scalar, 1) | (Dimensions::Vec2, 2) | (Dimensions::Vec3, 3) | (Dimensions::Vec4, 4)
    );
    let t = accessor.data_type();
    if !ok_dims || (t != DataType::F32 && !accessor.normalized()) {
        return Err(AccessorError::WrongType {
            index: accessor.index(),
            found: format!("{dims:?} of {t:?}{}", if accessor.normalized() { " (normalized)" } else { "" }),
            expected,
        });
    }
    let (elems, t) = element_bytes(accessor, buffers)?;
    Ok(elems.into_iter().map(|b| std::array::from_fn(|k| component(b, t, accessor.normalized(), k))).collect())
}

/// Reads an index accessor (unsigned scalar of 8, 16 or 32 bits).
pub fn read_indices(accessor: &gltf::Accessor<'_>, buffers: &[Vec<u8>]) -> Result<Vec<u32>, AccessorError> {
    let t = accessor.data_type();
    if accessor.dimensions() != Dimensions::Scalar || !matches!(t, DataType::U8 | DataType::U16 | DataType::U32) {
        return Err(AccessorError::WrongType {
            index: accessor.index(),
            found: format!("{:?} of {t:?}", accessor.dimensions()),
            expected: "SCALAR of unsigned byte, short or int",
        });
    }
    let (elems, t) = element_bytes(accessor, buffers)?;
    Ok(elems
        .into_iter()
        .map(|b| match t {
            DataType::U8 => u32::from(b[0]),
            DataType::U16 => u32::from(u16::from_le_bytes([b[0], b[1]])),
            _ => u32::from_le_bytes([b[0], b[1], b[2], b[3]]),
        })
        .collect())
}
