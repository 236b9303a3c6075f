//! WSxM images (`.stp`, `.top`; Nanotec/WSxM "Image file" format). A text header starting
//! `WSxM file copyright …` / `SxM Image file` / `Image header size: N`, then `[Section]` blocks of
//! `    Key: value` lines up to `[Header end]`; the data follow at byte N, little-endian, row after row.
//! `Image Data Type` says how (`double`, `float`, `integer`, `short`; `.top` files without it are short).
//! Lateral size: `X Amplitude`, `Y Amplitude` (with unit). Heights: floating-point data are in the unit of
//! `Z Amplitude`; 16-bit codes span `Z Amplitude` between the header's `Minimum` and `Maximum` codes (or the
//! data's own extremes), the convention WSxM's `.top` files and their `.stp` twins share.

use crate::{HeightField, SurfaceError};

use super::channel::{self, ChannelInfo};
use super::{LoadOptions, Sidecar};

fn bad(m: impl Into<String>) -> SurfaceError {
    SurfaceError::invalid(format!("not a valid WSxM image: {}", m.into()))
}

pub fn detect(bytes: &[u8]) -> bool {
    bytes.starts_with(b"WSxM file copyright")
}

struct Parsed {
    info: ChannelInfo,
    header_size: usize,
    kind: &'static str,
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
    let mut kv: Vec<(String, String)> = Vec::new();
    for line in header.lines() {
        if let Some((k, v)) = line.split_once(':') {
            kv.push((k.trim().to_string(), v.trim().to_string()));
        }
    }
    let get = |key: &str| kv.iter().find(|(k, _)| k == key).map(|(_, v)| v.as_str());
    let count = |key: &str| {
        get(key).and_then(|v| v.parse::<usize>().ok()).ok_or_else(|| bad(format!("no valid '{key}' in the header")))
    };
    let (rows, cols) = (count("Number of rows")?, count("Number of columns")?);
    crate::check_dims(rows, cols)?;
    let kind = match get("Image Data Type").map(str::to_ascii_lowercase).as_deref() {
        Some("double") => "double",
        Some("float") => "float",
        Some("integer") => "integer",
        Some("short") | None => "short",
        Some(other) => return Err(bad(format!("image data type '{other}' is not supported"))),
    };
    let len = |key: &str| {
        // Latin-1 decoding maps WSxM's µ (0xB5) to U+00B5, which unit_to_nm knows.
        let (v, u) = quantity(get(key)?)?;
        Some(v * super::unit_to_nm(&u)?)
    };
    let extent = match (len("X Amplitude"), len("Y Amplitude")) {
        (Some(x), Some(y)) if x > 0.0 && y > 0.0 => Some((x, y)),
        _ => None,
    };
    let z_amp = get("Z Amplitude").and_then(quantity);
    let min_max = match (get("Minimum").and_then(|v| v.parse().ok()), get("Maximum").and_then(|v| v.parse().ok())) {
        (Some(a), Some(b)) => Some((a, b)),
        _ => None,
    };
    let z_unit = z_amp.as_ref().map(|z| z.1.clone()).unwrap_or_default();
    let name = get("Acquisition channel").unwrap_or("Topography").to_string();
    let direction = get("X scanning direction").unwrap_or("").to_ascii_lowercase();
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
    let list = vec![p.info.clone()];
    channel::pick(&list, opts.channel.as_ref())?;
    let (rows, cols) = (p.info.rows, p.info.cols);
    let elem = match p.kind {
        "double" => 8,
        "float" | "integer" => 4,
        _ => 2,
    };
    let need = rows * cols * elem;
    let data = bytes
        .get(p.header_size..p.header_size + need)
        .ok_or_else(|| bad(format!("{rows} × {cols} {} values need {need} bytes after the header", p.kind)))?;
    let mut values: Vec<f64> = data
        .chunks_exact(elem)
        .map(|c| match p.kind {
            "double" => f64::from_le_bytes(c.try_into().expect("8 bytes")),
            "float" => f64::from(f32::from_le_bytes(c.try_into().expect("4 bytes"))),
            "integer" => f64::from(i32::from_le_bytes(c.try_into().expect("4 bytes"))),
            _ => f64::from(i16::from_le_bytes([c[0], c[1]])),
        })
        .collect();
    let mut info = p.info.clone();
    if p.kind == "short" || p.kind == "integer" {
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
