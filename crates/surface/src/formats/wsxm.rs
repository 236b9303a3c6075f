//! WSxM images (`.stp`, `.top`; Nanotec/WSxM "Image file" format). A text header starting
//! `WSxM file copyright …` / `SxM Image file` / `Image header size: N`, then `[Section]` blocks of
//! `    Key: value` lines up to `[Header end]`; the data follow at byte N, little-endian, row after row.
//! `Image Data Type` says how (`double`, `float`, `integer`, `short`; `.top` files without it are short).
//! Lateral size: `X Amplitude`, `Y Amplitude` (with unit). Heights: floating-point data are in the unit of
//! `Z Amplitude`; 16-bit codes span `Z Amplitude` between the header's `Minimum` and `Maximum` codes (or the
//! data's own extremes), the convention WSxM's `.top` files and their `.stp` twins share.

use crate::{HeightField, SurfaceError};

use super::channel::ChannelInfo;
use super::{KeyValues, LeSample, LoadOptions, Sidecar};

fn bad(m: impl Into<String>) -> SurfaceError {
    SurfaceError::invalid(format!("not a valid WSxM image: {}", m.into()))
}

pub fn detect(bytes: &[u8]) -> bool {
    bytes.starts_with(b"WSxM file copyright")
}

struct Parsed {
    info: ChannelInfo,
    header_size: usize,
    kind: LeSample,
    extent: Option<(f64, f64)>,
    z_amp: Option<(f64, String)>,
    min_max: Option<(f64, f64)>,
}

/// `"500 nm"` → (500, "nm"); WSxM writes `µm` in Latin-1.
fn quantity(v: &str) -> Option<(f64, String)> {
    let mut it = v.split_whitespace();
    let x: f64 = it.next()?.parse().ok()?;
    Some((x, it.next().unwrap_or("").to_string()))
}

fn parse(bytes: &[u8]) -> Result<Parsed, SurfaceError> {
    if !detect(bytes) {
        return Err(bad("missing 'WSxM file copyright'"));
    }
    let head = &bytes[..bytes.len().min(200)];
    let head: String = head.iter().map(|&b| b as char).collect();
    let header_size = head
        .lines()
        .find_map(|l| l.trim().strip_prefix("Image header size:").and_then(|v| v.trim().parse::<usize>().ok()))
        .ok_or_else(|| bad("no 'Image header size' in the first lines"))?;
    if header_size > bytes.len() {
        return Err(bad(format!("header of {header_size} bytes in a file of {} (truncated?)", bytes.len())));
    }
    let header: String = bytes[..header_size].iter().map(|&b| b as char).collect();
    let kv = KeyValues::parse(&header, ':');
    let count = |key: &str| kv.count(key).ok_or_else(|| bad(format!("no valid '{key}' in the header")));
    let (rows, cols) = (count("Number of rows")?, count("Number of columns")?);
    crate::check_dims(rows, cols)?;
    let kind = match kv.get("Image Data Type").map(str::to_ascii_lowercase).as_deref() {
        Some("double") => LeSample::F64,
        Some("float") => LeSample::F32,
        Some("integer") => LeSample::I32,
        Some("short") | None => LeSample::I16,
        Some(other) => return Err(bad(format!("image data type '{other}' is not supported"))),
    };
    let len = |key: &str| {
        // Latin-1 decoding maps WSxM's µ (0xB5) to U+00B5, which unit_to_nm knows.
        let (v, u) = quantity(kv.get(key)?)?;
        Some(v * super::unit_to_nm(&u)?)
    };
    let extent = match (len("X Amplitude"), len("Y Amplitude")) {
        (Some(x), Some(y)) if x > 0.0 && y > 0.0 => Some((x, y)),
        _ => None,
    };
    let z_amp = kv.get("Z Amplitude").and_then(quantity);
    let code = |key: &str| kv.get(key)?.parse::<f64>().ok();
    let min_max = match (code("Minimum"), code("Maximum")) {
        (Some(a), Some(b)) => Some((a, b)),
        _ => None,
    };
    let z_unit = z_amp.as_ref().map(|z| z.1.clone()).unwrap_or_default();
    let name = kv.get("Acquisition channel").unwrap_or("Topography").to_string();
    let direction = kv.get("X scanning direction").unwrap_or("").to_ascii_lowercase();
    Ok(Parsed {
        info: ChannelInfo { index: 0, name, rows, cols, z_unit, direction, alias: String::new() },
        header_size,
        kind,
        extent,
        z_amp,
        min_max,
    })
}

pub fn channels(bytes: &[u8]) -> Result<Vec<ChannelInfo>, SurfaceError> {
    Ok(vec![parse(bytes)?.info])
}

pub fn read(bytes: &[u8], side: Option<&Sidecar>, opts: &LoadOptions) -> Result<HeightField, SurfaceError> {
    let p = parse(bytes)?;
    let (rows, cols) = (p.info.rows, p.info.cols);
    let (list, mut values) = super::single_channel(bytes, &p.info, p.header_size, p.kind, opts, |need| {
        bad(format!("{rows} × {cols} {} values need {need} bytes after the header", p.kind.name()))
    })?;
    let mut info = p.info.clone();
    if matches!(p.kind, LeSample::I16 | LeSample::I32) {
        let (amp, unit) = p.z_amp.clone().ok_or_else(|| bad("integer data without 'Z Amplitude' cannot be scaled"))?;
        let (lo, hi) = p.min_max.unwrap_or_else(|| {
            values.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| (a.min(v), b.max(v)))
        });
        let k = if hi > lo { amp / (hi - lo) } else { 0.0 };
        values.iter_mut().for_each(|v| *v *= k);
        info.z_unit = unit;
    }
    let file_pixel = p.extent.map(|(ex, ey)| (ex / cols as f64, ey / rows as f64));
    super::finish_channel(values, &list, &info, file_pixel, side, opts, "WSxM image")
}
