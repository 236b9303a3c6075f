//! numpy `.npy` (via `npyz`): a 2-D array of heights, f32 or f64 (integers accepted too), C or Fortran
//! order. `.npy` has no units: the pixel size comes from the sidecar or `--pixel-size`, the height unit from
//! the sidecar (`height_unit`), else nanometres with a warning.

use npyz::{DType, Order, TypeChar, WriterBuilder};

use crate::{HeightField, SurfaceError};

use super::{LoadOptions, Sidecar};

fn bad(m: impl Into<String>) -> SurfaceError {
    SurfaceError::invalid(format!("not a valid .npy height field: {}", m.into()))
}

pub fn read(bytes: &[u8], side: Option<&Sidecar>, opts: &LoadOptions) -> Result<HeightField, SurfaceError> {
    check_header_length(bytes).map_err(bad)?;
    let npy = npyz::NpyFile::new(bytes).map_err(|e| bad(format!("header: {e}")))?;
    let shape = npy.shape().to_vec();
    let dims: Vec<u64> = shape.iter().copied().filter(|&d| d != 1).collect();
    let (rows, cols) = match (shape.len(), dims.len()) {
        (2, _) => (shape[0], shape[1]),
        (_, 2) => (dims[0], dims[1]),
        _ => {
            return Err(bad(format!(
                "array of shape {shape:?}; a height field is a 2-D array (rows, columns) of at least 2 × 2"
            )))
        }
    };
    if rows > crate::MAX_DIM as u64 || cols > crate::MAX_DIM as u64 {
        return Err(SurfaceError::invalid(format!(
            "array of shape {shape:?} is too large (at most {} per axis)",
            crate::MAX_DIM
        )));
    }
    let (rows, cols) = (rows as usize, cols as usize);
    crate::check_dims(rows, cols)?;
    let fortran = npy.order() == Order::Fortran;
    let ts = match npy.dtype() {
        DType::Plain(ts) => ts,
        other => return Err(bad(format!("dtype {} is not a plain number type", other.descr()))),
    };
    // The data must be present in full before we read it (npyz would otherwise stop at the end of the file).
    let need = (rows * cols) as u64 * ts.size_field();
    let have = (bytes.len().saturating_sub(header_len(bytes))) as u64;
    if need > have {
        return Err(bad(format!("file truncated: {rows} × {cols} values need {need} bytes of data")));
    }
    let io = |e: std::io::Error| bad(format!("data: {e}"));
    let values: Vec<f64> = match (ts.type_char(), ts.size_field()) {
        (TypeChar::Float, 8) => npy.into_vec::<f64>().map_err(io)?,
        (TypeChar::Float, 4) => npy.into_vec::<f32>().map_err(io)?.into_iter().map(f64::from).collect(),
        (TypeChar::Int, 1) => npy.into_vec::<i8>().map_err(io)?.into_iter().map(f64::from).collect(),
        (TypeChar::Int, 2) => npy.into_vec::<i16>().map_err(io)?.into_iter().map(f64::from).collect(),
        (TypeChar::Int, 4) => npy.into_vec::<i32>().map_err(io)?.into_iter().map(f64::from).collect(),
        (TypeChar::Int, 8) => npy.into_vec::<i64>().map_err(io)?.into_iter().map(|v| v as f64).collect(),
        (TypeChar::Uint, 1) => npy.into_vec::<u8>().map_err(io)?.into_iter().map(f64::from).collect(),
        (TypeChar::Uint, 2) => npy.into_vec::<u16>().map_err(io)?.into_iter().map(f64::from).collect(),
        (TypeChar::Uint, 4) => npy.into_vec::<u32>().map_err(io)?.into_iter().map(f64::from).collect(),
        (TypeChar::Uint, 8) => npy.into_vec::<u64>().map_err(io)?.into_iter().map(|v| v as f64).collect(),
        _ => return Err(bad(format!("dtype '{ts}' is not supported; save heights as float32 or float64"))),
    };
    if values.len() != rows * cols {
        return Err(bad(format!("{} values for shape {shape:?}", values.len())));
    }
    let mut warnings = Vec::new();
    let given = super::given_height_unit(side, opts)?;
    let scale = match &given {
        Some((k, _)) => *k,
        None => {
            warnings.push(
                "the .npy gives no height unit; values taken as nm (give --height-unit, or add \"height_unit\" to a \
                 sidecar)"
                    .into(),
            );
            super::warn_if_metres(&values, &mut warnings);
            1.0
        }
    };
    let mut heights = vec![0.0; rows * cols];
    for r in 0..rows {
        for c in 0..cols {
            let v = if fortran { values[c * rows + r] } else { values[r * cols + c] };
            heights[r * cols + c] = v * scale;
        }
    }
    // NaN lines (an aborted scan saved by a script) are filled and said, as an instrument file's are.
    super::fill_non_finite(&mut heights, rows, cols, "the .npy array", &mut warnings)?;
    let ((dx, dy), _) = super::pick_pixel(None, side, opts, "a .npy array")?;
    let hf = HeightField::new(rows, cols, dx, dy, heights)?;
    let mut meta = hf.meta.clone();
    meta.z_unit = given.map(|g| g.1).unwrap_or_else(|| "nm (assumed)".into());
    meta.warnings = warnings;
    meta.notes.push(format!("numpy {ts} array of shape {shape:?}{}", if fortran { ", Fortran order" } else { "" }));
    Ok(hf.with_meta(meta))
}

/// Refuses a header whose declared length runs past the end of `bytes` before the parser sizes a buffer from
/// it (a version-2 header may claim up to 4 GiB).
pub(crate) fn check_header_length(bytes: &[u8]) -> Result<(), String> {
    let end = header_len(bytes);
    if bytes.len() < 10 || end > bytes.len() {
        return Err(format!(
            "header truncated: it declares {} bytes, the data holds {}",
            end.saturating_sub(10),
            bytes.len().saturating_sub(10)
        ));
    }
    Ok(())
}

/// Bytes before the data: magic (6), version (2), header length (2 bytes in v1, 4 in v2/v3), header.
pub(crate) fn header_len(bytes: &[u8]) -> usize {
    match bytes.get(6) {
        Some(1) if bytes.len() >= 10 => 10 + u16::from_le_bytes([bytes[8], bytes[9]]) as usize,
        Some(_) if bytes.len() >= 12 => 12 + u32::from_le_bytes([bytes[8], bytes[9], bytes[10], bytes[11]]) as usize,
        _ => bytes.len(),
    }
}

/// Writes `<f8`, C order, shape `(rows, cols)`, heights in nm.
pub fn write(hf: &HeightField) -> Result<Vec<u8>, SurfaceError> {
    let mut out = Vec::with_capacity(hf.heights_nm.len() * 8 + 128);
    let io = |e: std::io::Error| SurfaceError::invalid(format!("cannot encode .npy: {e}"));
    {
        let mut w = npyz::WriteOptions::new()
            .default_dtype()
            .shape(&[hf.rows as u64, hf.cols as u64])
            .writer(&mut out)
            .begin_nd()
            .map_err(io)?;
        w.extend(hf.heights_nm.iter().copied()).map_err(io)?;
        w.finish().map_err(io)?;
    }
    Ok(out)
}
