//! NumPy arrays in and out. Each input's dtype, shape and byte order is checked and the message
//! names what was expected; an array in the other byte order is read by value, and one that is
//! not contiguous (a slice, a transposed view) is read through its strides. No input is
//! converted from another dtype: a float64 height field is refused, not rounded silently.

use bumpmap::maps::Chain;
use bumpmap_math::levels::LevelSizeError;
use bumpmap_math::{HeightField, HeightSamples, Image, MipChain};
use numpy::ndarray::{Array2, Array3};
use numpy::{
    Element, IntoPyArray, PyArrayDescrMethods, PyArrayDyn, PyArrayMethods, PyReadonlyArrayDyn, PyUntypedArray,
    PyUntypedArrayMethods,
};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;

/// `value` as a NumPy array in native byte order (an array in the other order is converted by
/// value, the one conversion made), or a `TypeError` naming what `what` should be.
pub fn native<'py>(value: &Bound<'py, PyAny>, what: &str, expected: &str) -> PyResult<Bound<'py, PyUntypedArray>> {
    let array = value.cast::<PyUntypedArray>().map_err(|_| {
        PyTypeError::new_err(format!(
            "{what} must be a numpy array ({expected}), got {}",
            value.get_type().name().map(|n| n.to_string()).unwrap_or_default()
        ))
    })?;
    if array.dtype().is_native_byteorder() == Some(false) {
        let dtype = array.dtype().call_method1("newbyteorder", ("=",))?;
        let converted = array.call_method1("astype", (dtype,))?;
        return Ok(converted.cast_into::<PyUntypedArray>()?);
    }
    Ok(array.clone())
}

/// Whether `array`'s dtype is `T`'s.
pub fn is<T: Element>(array: &Bound<'_, PyUntypedArray>) -> bool {
    array.dtype().is_equiv_to(&numpy::dtype::<T>(array.py()))
}

/// The dtype's name, for messages: `float64`, `int32`, …
pub fn dtype_name(array: &Bound<'_, PyUntypedArray>) -> String {
    array.dtype().getattr("name").and_then(|n| n.extract::<String>()).unwrap_or_else(|_| "?".into())
}

/// `array`'s elements in row-major order, whatever its strides or memory order (a Fortran-
/// ordered array's memory is column-major: it is read element by element, not as its bytes lie).
pub fn elements<T: Element + Copy>(array: &Bound<'_, PyUntypedArray>) -> PyResult<Vec<T>> {
    let typed: PyReadonlyArrayDyn<'_, T> = array.cast::<PyArrayDyn<T>>()?.readonly();
    Ok(match typed.as_slice() {
        Ok(s) if typed.is_c_contiguous() => s.to_vec(),
        _ => typed.as_array().iter().copied().collect(),
    })
}

/// A height field from a 2-D array of uint8 (`h = b/255`), uint16 (`h = v/65535`) or float32
/// (`h` as it is), as `read_height_field` returns them and the command line reads images.
pub fn height_field(value: &Bound<'_, PyAny>) -> PyResult<HeightField> {
    const EXPECTED: &str = "(H, W) of uint8, uint16 or float32";
    let array = native(value, "heights", EXPECTED)?;
    let [h, w] = array.shape() else {
        return Err(PyValueError::new_err(format!(
            "heights must be a 2-D array {EXPECTED}, got shape {:?}",
            array.shape()
        )));
    };
    let (h, w) = (*h, *w);
    let field = if is::<u8>(&array) {
        HeightField::from_u8_vec(w, h, elements(&array)?)
    } else if is::<u16>(&array) {
        HeightField::from_u16(w, h, &elements::<u16>(&array)?)
    } else if is::<f32>(&array) {
        HeightField::new(w, h, elements(&array)?)
    } else {
        return Err(PyTypeError::new_err(format!(
            "heights must be uint8, uint16 or float32 (heights in [0, 1]), got {}{}",
            dtype_name(&array),
            if is::<f64>(&array) { ": use heights.astype(numpy.float32)" } else { "" }
        )));
    };
    let field =
        field.ok_or_else(|| PyValueError::new_err(format!("heights of {w}x{h}: both sides must be at least 1")))?;
    if let Some((x, y, v)) = field.first_unusable() {
        return Err(PyValueError::new_err(format!(
            "heights[{y}, {x}] is {v}: heights must be finite and within ±{:e}",
            bumpmap_math::height::MAX_FLOAT_HEIGHT
        )));
    }
    Ok(field)
}

/// A height field's samples as stored: (H, W) uint8, uint16 or float32.
pub fn from_height_field<'py>(py: Python<'py>, field: &HeightField) -> PyResult<Bound<'py, PyAny>> {
    let shape = (field.height(), field.width());
    let array = match field.samples() {
        HeightSamples::U8(s) => Array2::from_shape_vec(shape, s.to_vec()).map(|a| a.into_pyarray(py).into_any()),
        HeightSamples::U16(s) => Array2::from_shape_vec(shape, s.to_vec()).map(|a| a.into_pyarray(py).into_any()),
        HeightSamples::F32(s) => Array2::from_shape_vec(shape, s.to_vec()).map(|a| a.into_pyarray(py).into_any()),
    };
    array.map_err(|e| PyValueError::new_err(e.to_string()))
}

/// An (H, W) float32 array of `texels`, row 0 first.
pub fn from_plane<'py>(py: Python<'py>, height: usize, width: usize, texels: &[f32]) -> PyResult<Bound<'py, PyAny>> {
    Array2::from_shape_vec((height, width), texels.to_vec())
        .map(|a| a.into_pyarray(py).into_any())
        .map_err(|e| PyValueError::new_err(e.to_string()))
}

/// An (H, W, 2) float32 array of `texels`, row 0 first.
pub fn from_pairs<'py>(
    py: Python<'py>,
    height: usize,
    width: usize,
    texels: &[[f32; 2]],
) -> PyResult<Bound<'py, PyAny>> {
    Array3::from_shape_vec((height, width, 2), texels.as_flattened().to_vec())
        .map(|a| a.into_pyarray(py).into_any())
        .map_err(|e| PyValueError::new_err(e.to_string()))
}

/// An (H, W, `channels`) float32 array of `texels`, row 0 first.
pub fn from_plane_channels<'py>(
    py: Python<'py>,
    height: usize,
    width: usize,
    texels: &[f32],
    channels: usize,
) -> PyResult<Bound<'py, PyAny>> {
    Array3::from_shape_vec((height, width, channels), texels.to_vec())
        .map(|a| a.into_pyarray(py).into_any())
        .map_err(|e| PyValueError::new_err(e.to_string()))
}

/// One level as an (H, W, 4) array.
fn level_array<'py, T: Element + Copy>(py: Python<'py>, level: Image<[T; 4]>) -> PyResult<Bound<'py, PyAny>> {
    let shape = (level.height, level.width, 4);
    let flat: Vec<T> = level.texels.into_flattened();
    Ok(Array3::from_shape_vec(shape, flat)
        .map_err(|e| PyValueError::new_err(e.to_string()))?
        .into_pyarray(py)
        .into_any())
}

/// A chain's levels as (H, W, 4) arrays of uint8 or uint16, level 0 first.
pub fn from_chain(py: Python<'_>, chain: Chain) -> PyResult<Vec<Bound<'_, PyAny>>> {
    match chain {
        Chain::Rgba8(c) => c.levels.into_iter().map(|l| level_array(py, l)).collect(),
        Chain::Rgba16(c) => c.levels.into_iter().map(|l| level_array(py, l)).collect(),
    }
}

/// The texels of an (H, W, 4) array.
fn texels<T: Element + Copy + Default>(array: &Bound<'_, PyUntypedArray>) -> PyResult<Image<[T; 4]>> {
    let (h, w) = (array.shape()[0], array.shape()[1]);
    let flat: Vec<T> = elements(array)?;
    let texels = flat.chunks_exact(4).map(|c| [c[0], c[1], c[2], c[3]]).collect();
    Ok(Image::new(w, h, texels))
}

/// A chain from one (H, W, 4) array or a list of them, uint8 or uint16 alike, each level half
/// the one before (rounded down, at least 1), as a mip chain has them.
pub fn to_chain(value: &Bound<'_, PyAny>) -> PyResult<Chain> {
    const EXPECTED: &str = "(H, W, 4) of uint8 or uint16";
    let items: Vec<Bound<'_, PyAny>> = if value.cast::<PyUntypedArray>().is_ok() {
        vec![value.clone()]
    } else if value.is_instance_of::<pyo3::types::PyList>() || value.is_instance_of::<pyo3::types::PyTuple>() {
        value.try_iter()?.collect::<PyResult<_>>()?
    } else {
        return Err(PyTypeError::new_err(format!(
            "levels must be a numpy array {EXPECTED} or a list of them (level 0 first), got {}",
            value.get_type().name()?
        )));
    };
    if items.is_empty() {
        return Err(PyValueError::new_err("levels is empty: give at least level 0"));
    }
    let arrays: Vec<Bound<'_, PyUntypedArray>> =
        items.iter().enumerate().map(|(k, a)| native(a, &format!("level {k}"), EXPECTED)).collect::<PyResult<_>>()?;
    let sixteen = is::<u16>(&arrays[0]);
    let (h0, w0) = match arrays[0].shape() {
        [h, w, 4] => (*h, *w),
        other => return Err(PyValueError::new_err(format!("level 0 must be {EXPECTED}, got shape {other:?}"))),
    };
    // A chain ends at 1×1 (a DDS or KTX2 file cannot hold more levels) and each level is half
    // the one before: the library's one check of a chain's sizes, worded as arrays' shapes.
    let sizes = arrays.iter().map(|a| match a.shape() {
        [h, w, 4] => (*w, *h),
        _ => (0, 0),
    });
    match bumpmap_math::levels::check_chain(sizes) {
        Ok(()) => {}
        Err(LevelSizeError::TooMany { levels, most, .. }) => {
            return Err(PyValueError::new_err(format!(
                "{levels} levels for a {h0}x{w0} level 0: its chain ends at 1x1 after {most} levels"
            )));
        }
        Err(LevelSizeError::Size { level, want, .. }) => {
            return Err(PyValueError::new_err(format!(
                "level {level} must have shape ({}, {}, 4) (half of the level before, rounded down), got {:?}",
                want.1,
                want.0,
                arrays[level].shape()
            )));
        }
        Err(LevelSizeError::Empty) => return Err(PyValueError::new_err("levels is empty: give at least level 0")),
    }
    for (k, a) in arrays.iter().enumerate() {
        if !(is::<u8>(a) || is::<u16>(a)) || is::<u16>(a) != sixteen {
            return Err(PyTypeError::new_err(format!(
                "level {k} is {}: every level must be uint8, or every level uint16 (level 0 is {})",
                dtype_name(a),
                dtype_name(&arrays[0])
            )));
        }
    }
    let encoding = bumpmap_math::Encoding::Unorm;
    Ok(if sixteen {
        Chain::Rgba16(MipChain { levels: arrays.iter().map(texels).collect::<PyResult<_>>()?, encoding })
    } else {
        Chain::Rgba8(MipChain { levels: arrays.iter().map(texels).collect::<PyResult<_>>()?, encoding })
    })
}

/// A float32 array of shape (N, `columns`), as rows.
pub fn rows<const C: usize>(value: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<[f32; C]>> {
    let expected = format!("(N, {C}) of float32");
    let array = native(value, what, &expected)?;
    match array.shape() {
        [_, c] if *c == C => {}
        other => return Err(PyValueError::new_err(format!("{what} must have shape {expected}, got {other:?}"))),
    }
    if !is::<f32>(&array) {
        return Err(PyTypeError::new_err(format!(
            "{what} must be float32, got {}: use {what}.astype(numpy.float32)",
            dtype_name(&array)
        )));
    }
    let flat: Vec<f32> = elements(&array)?;
    Ok(flat.chunks_exact(C).map(|c| std::array::from_fn(|i| c[i])).collect())
}

/// Triangle indices: uint32 of shape (T, 3) or (3T,).
pub fn triangles(value: &Bound<'_, PyAny>) -> PyResult<Vec<[u32; 3]>> {
    const EXPECTED: &str = "(T, 3) or (3T,) of uint32";
    let array = native(value, "indices", EXPECTED)?;
    let ok_shape = match array.shape() {
        [_, 3] => true,
        [n] => n % 3 == 0,
        _ => false,
    };
    if !ok_shape {
        return Err(PyValueError::new_err(format!("indices must have shape {EXPECTED}, got {:?}", array.shape())));
    }
    if !is::<u32>(&array) {
        return Err(PyTypeError::new_err(format!(
            "indices must be uint32, got {}: use indices.astype(numpy.uint32)",
            dtype_name(&array)
        )));
    }
    let flat: Vec<u32> = elements(&array)?;
    Ok(flat.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect())
}

/// Rows as an (N, C) float32 array.
pub fn from_rows<const C: usize>(py: Python<'_>, rows: Vec<[f32; C]>) -> PyResult<Bound<'_, PyAny>> {
    let n = rows.len();
    let array =
        Array2::from_shape_vec((n, C), rows.into_flattened()).map_err(|e| PyValueError::new_err(e.to_string()))?;
    Ok(array.into_pyarray(py).into_any())
}

/// A normal map from an (H, W, 3) or (H, W, 4) array: uint8 or uint16 unorm, or float32 (signed
/// where any of RGB is below −0.01, else 0..1), as `bumpmap inspect` reads files. Three
/// channels get alpha at its largest.
pub fn normal_texels(value: &Bound<'_, PyAny>) -> PyResult<bumpmap::inspect::DecodedMap> {
    use bumpmap::inspect::{DecodedMap, StoredAs};
    const EXPECTED: &str = "(H, W, 3) or (H, W, 4) of uint8, uint16 or float32";
    let array = native(value, "normals", EXPECTED)?;
    let (h, w, c) = match array.shape() {
        [h, w, c @ (3 | 4)] => (*h, *w, *c),
        other => return Err(PyValueError::new_err(format!("normals must be {EXPECTED}, got shape {other:?}"))),
    };
    DecodedMap::check_memory("normals", w.saturating_mul(h))
        .map_err(|e| pyo3::exceptions::PyMemoryError::new_err(e.to_string()))?;
    fn rgba<T: Element + Copy>(
        array: &Bound<'_, PyUntypedArray>,
        w: usize,
        h: usize,
        c: usize,
        one: T,
    ) -> PyResult<Image<[T; 4]>> {
        let flat: Vec<T> = elements(array)?;
        let texels = flat.chunks_exact(c).map(|t| [t[0], t[1], t[2], if c == 4 { t[3] } else { one }]).collect();
        Ok(Image::new(w, h, texels))
    }
    if is::<u8>(&array) {
        Ok(DecodedMap::from_unorm(&[rgba(&array, w, h, c, u8::MAX)?], StoredAs::Unorm8))
    } else if is::<u16>(&array) {
        Ok(DecodedMap::from_unorm(&[rgba(&array, w, h, c, u16::MAX)?], StoredAs::Unorm16))
    } else if is::<f32>(&array) {
        Ok(DecodedMap::from_float(&rgba(&array, w, h, c, 1.0f32)?))
    } else {
        Err(PyTypeError::new_err(format!("normals must be {EXPECTED}, got {}", dtype_name(&array))))
    }
}

/// A mesh from its arrays (float32 positions (N, 3), normals (N, 3) or None, uvs (N, 2),
/// tangents (N, 4) or None, uint32 indices), `function` naming it in errors; normals normalized
/// as a glTF reader normalizes them. Not yet validated (the indices' range, finite values): that
/// runs on the work's threads. Returns it and whether it came with normals and tangents.
pub fn mesh(
    function: &str,
    positions: &Bound<'_, PyAny>,
    normals: &Bound<'_, PyAny>,
    uvs: &Bound<'_, PyAny>,
    tangents: Option<&Bound<'_, PyAny>>,
    indices: &Bound<'_, PyAny>,
) -> PyResult<(bumpmap_math::mesh::Mesh, bool, bool)> {
    use glam::{Vec2, Vec3, Vec4};
    let positions: Vec<Vec3> = rows::<3>(positions, "positions")?.into_iter().map(Vec3::from).collect();
    let n = positions.len();
    let normals: Vec<Vec3> = if normals.is_none() {
        Vec::new()
    } else {
        rows::<3>(normals, "normals")?.into_iter().map(|n| Vec3::from(n).normalize_or_zero()).collect()
    };
    let texcoords: Vec<Vec2> = rows::<2>(uvs, "uvs")?.into_iter().map(Vec2::from).collect();
    let tangents: Vec<Vec4> = match tangents {
        Some(t) if !t.is_none() => rows::<4>(t, "tangents")?.into_iter().map(Vec4::from).collect(),
        _ => Vec::new(),
    };
    for (what, len, optional) in
        [("normals", normals.len(), true), ("uvs", texcoords.len(), false), ("tangents", tangents.len(), true)]
    {
        if len != n && !(optional && len == 0) {
            return Err(PyValueError::new_err(format!(
                "{function}(): {what} has {len} rows, positions {n}: one per vertex"
            )));
        }
    }
    let (had_normals, had_tangents) = (!normals.is_empty(), !tangents.is_empty());
    let mesh = bumpmap_math::mesh::Mesh {
        positions,
        normals,
        texcoords,
        tangents,
        colors: Vec::new(),
        indices: triangles(indices)?,
    };
    Ok((mesh, had_normals, had_tangents))
}
