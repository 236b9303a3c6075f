//! Gwyddion Simple Field (`.gsf`; gwyddion.net "Gwyddion Simple Field 1.0"): the line
//! `Gwyddion Simple Field 1.0`, `Key = Value` lines (`XRes`, `YRes` required; `XReal`, `YReal` default 1;
//! `XYUnits`, `ZUnits`, `Title`), then 1–4 NUL bytes padding the header to a multiple of 4, then
//! `XRes·YRes` little-endian `f32`, row after row from the top.

use crate::{HeightField, SurfaceError};

use super::channel::ChannelInfo;
use super::{KeyValues, LeSample, LoadOptions, Sidecar};

/// The first line of every Gwyddion Simple Field file.
pub const MAGIC: &[u8] = b"Gwyddion Simple Field 1.0\n";

fn bad(m: impl Into<String>) -> SurfaceError {
    SurfaceError::invalid(format!("not a valid Gwyddion Simple Field: {}", m.into()))
}

pub fn detect(bytes: &[u8]) -> bool {
    bytes.starts_with(MAGIC)
}

struct Parsed {
    info: ChannelInfo,
    data_at: usize,
    real: (f64, f64),
    xy_unit: Option<String>,
}

fn parse(bytes: &[u8]) -> Result<Parsed, SurfaceError> {
    if !detect(bytes) {
        return Err(bad("missing the 'Gwyddion Simple Field 1.0' line"));
    }
    let nul = bytes.iter().position(|&b| b == 0).ok_or_else(|| bad("no NUL after the header (truncated?)"))?;
    let header = std::str::from_utf8(&bytes[MAGIC.len()..nul]).map_err(|_| bad("header is not UTF-8"))?;
    if let Some(line) = header.lines().find(|l| !l.trim().is_empty() && !l.contains('=')) {
        return Err(bad(format!("header line '{line}' is not Key = Value")));
    }
    let kv = KeyValues::parse(header, '=');
    let res = |key: &str| kv.count(key).ok_or_else(|| bad(format!("no valid {key} in the header")));
    let (cols, rows) = (res("XRes")?, res("YRes")?);
    crate::check_dims(rows, cols)?;
    let real = |key: &str| match kv.get(key) {
        None => Ok(1.0),
        Some(v) => v.parse::<f64>().map_err(|_| bad(format!("{key} = {v} is not a number"))),
    };
    let data_at = (nul / 4 + 1) * 4;
    let info = ChannelInfo {
        index: 0,
        name: kv.get("Title").unwrap_or("").to_string(),
        rows,
        cols,
        z_unit: kv.get("ZUnits").unwrap_or("").to_string(),
        direction: String::new(),
        alias: String::new(),
    };
    Ok(Parsed { info, data_at, real: (real("XReal")?, real("YReal")?), xy_unit: kv.get("XYUnits").map(str::to_string) })
}

pub fn channels(bytes: &[u8]) -> Result<Vec<ChannelInfo>, SurfaceError> {
    Ok(vec![parse(bytes)?.info])
}

pub fn read(bytes: &[u8], side: Option<&Sidecar>, opts: &LoadOptions) -> Result<HeightField, SurfaceError> {
    let p = parse(bytes)?;
    let (rows, cols) = (p.info.rows, p.info.cols);
    let (list, values) = super::single_channel(bytes, &p.info, p.data_at, LeSample::F32, opts, |need| {
        bad(format!("{cols} × {rows} values need {need} bytes after the header (truncated?)"))
    })?;
    let file_pixel = match p.xy_unit.as_deref().map(super::unit_to_nm) {
        Some(Some(k)) => Some((p.real.0 * k / cols as f64, p.real.1 * k / rows as f64)),
        Some(None) => {
            return Err(bad(format!("XYUnits = {} is not a length", p.xy_unit.unwrap_or_default())));
        }
        // No lateral unit: the pixel size must come from --pixel-size or a sidecar.
        None => None,
    };
    super::finish_channel(values, &list, &p.info, file_pixel, side, opts, "Gwyddion Simple Field without XYUnits")
}

/// Writes a field with `XYUnits = m` and `ZUnits = m` (Gwyddion's convention).
pub fn write(hf: &HeightField) -> Vec<u8> {
    let title = if hf.meta.source.is_empty() { "Height".to_string() } else { format!("Height ({})", hf.meta.source) };
    let mut head = String::from_utf8_lossy(MAGIC).into_owned();
    head += &format!("XRes = {}\nYRes = {}\n", hf.cols, hf.rows);
    head +=
        &format!("XReal = {:e}\nYReal = {:e}\n", hf.cols as f64 * hf.dx_nm * 1e-9, hf.rows as f64 * hf.dy_nm * 1e-9);
    head += "XYUnits = m\nZUnits = m\n";
    head += &format!("Title = {}\n", title.replace(['\n', '\r', '\0'], " "));
    let mut out = head.into_bytes();
    let pad = 4 - out.len() % 4;
    out.resize(out.len() + pad, 0);
    for h in &hf.heights_nm {
        out.extend_from_slice(&((h * 1e-9) as f32).to_le_bytes());
    }
    out
}
