//! Bruker/Veeco NanoScope files (`.spm`, `.000`–`.00n`; header versions 5–9). A text header of
//! `\Key: value` lines (CR LF) from `\*File list` to `\*File list end`; each `\*Ciao image list` section
//! describes one image: `Data offset`, `Data length`, `Bytes/pixel` (2 or 4, little-endian signed),
//! `Samps/line` (columns), `Number of lines` (rows), `Scan Size: X Y unit`, `Line Direction`, the name in
//! `\@2:Image Data: S [key] "Name"` and the scale `\@2:Z scale: V [Sens. Zsens] (hard V/LSB) soft V`.
//! A stored code becomes a value as `code · soft / 2^(8·Bytes/pixel) · sensitivity`, the sensitivity being the
//! header's `\@Sens. Zsens: V 4.27 nm/V` line (the NanoScope User Guide's "Z scale" conversion, as Gwyddion's
//! and pySPM's readers apply it). The first stored line is the bottom of the image, so rows are flipped to
//! put row 0 on top.

use crate::{HeightField, SurfaceError};

use super::channel::{self, ChannelInfo};
use super::{LoadOptions, Sidecar};

fn bad(m: impl Into<String>) -> SurfaceError {
    SurfaceError::invalid(format!("not a valid NanoScope file: {}", m.into()))
}

/// The magic: the first header line.
pub fn detect(bytes: &[u8]) -> bool {
    bytes.starts_with(b"\\*File list") || bytes.starts_with(b"?*File list")
}

#[derive(Debug, Clone)]
struct Image {
    info: ChannelInfo,
    offset: usize,
    bpp: usize,
    /// nm (or the channel's unit) per stored code.
    scale: f64,
    extent: Option<(f64, f64)>,
}

/// `"V [Sens. Zsens] (0.00195 V/LSB) 127.9392 V"` → (sensitivity key, soft value, soft unit).
// Public but hidden: not API, reachable only for the crate's tests in tests/ (Cargo.toml, `[lib] test = false`).
#[doc(hidden)]
pub fn parse_z_scale(v: &str) -> Option<(Option<String>, f64, String)> {
    let key = match (v.find('['), v.find(']')) {
        (Some(a), Some(b)) if b > a => Some(v[a + 1..b].trim().to_string()),
        _ => None,
    };
    // The soft value is the last number; its unit (which may hold parentheses, `log(Arb)`) follows it.
    let tokens: Vec<&str> = v.split_whitespace().collect();
    let at = tokens.iter().rposition(|t| t.parse::<f64>().is_ok())?;
    let soft: f64 = tokens[at].parse().ok()?;
    let unit = tokens.get(at + 1).copied().unwrap_or("").to_string();
    Some((key, soft, unit))
}

/// `"V 4.273442 nm/V"` → (4.273442, "nm").
// Public but hidden: not API, reachable only for the crate's tests in tests/ (Cargo.toml, `[lib] test = false`).
#[doc(hidden)]
pub fn parse_sens(v: &str) -> Option<(f64, String)> {
    let mut it = v.split_whitespace();
    let _ = it.next()?;
    let k: f64 = it.next()?.parse().ok()?;
    let unit = it.next().unwrap_or("");
    Some((k, unit.strip_suffix("/V").unwrap_or(unit).to_string()))
}

/// A Nanoscope length unit (`~m` is µm) in nm, `None` if it is not a length.
// Public but hidden: not API, reachable only for the crate's tests in tests/ (Cargo.toml, `[lib] test = false`).
#[doc(hidden)]
pub fn length_unit(u: &str) -> Option<f64> {
    let u = if let Some(rest) = u.strip_prefix('~') { format!("µ{rest}") } else { u.to_string() };
    super::unit_to_nm(&u)
}

fn parse(bytes: &[u8]) -> Result<Vec<Image>, SurfaceError> {
    if !detect(bytes) {
        return Err(bad("missing the \\*File list header"));
    }
    let head_len = bytes
        .windows(15)
        .position(|w| w == b"\\*File list end")
        .ok_or_else(|| bad("the header has no \\*File list end (truncated file?)"))?;
    // Latin-1: every byte is a character.
    let header: String = bytes[..head_len].iter().map(|&b| b as char).collect();
    let mut sens: Vec<(String, (f64, String))> = Vec::new();
    let mut sections: Vec<Vec<(String, String)>> = Vec::new();
    let mut in_image = false;
    for line in header.split(['\r', '\n']).filter(|l| !l.is_empty()) {
        let line = line.trim_start_matches('\\');
        if line.starts_with('*') {
            in_image = line.eq_ignore_ascii_case("*Ciao image list");
            if in_image {
                sections.push(Vec::new());
            }
            continue;
        }
        let Some((k, v)) = line.split_once(':') else { continue };
        // `@2:Z scale` has a colon in its key.
        let (k, v) = if k.starts_with('@') && k.len() <= 3 && v.contains(':') {
            let (k2, v2) = v.split_once(':').unwrap_or((v, ""));
            (format!("{k}:{k2}"), v2)
        } else {
            (k.to_string(), v)
        };
        let v = v.trim().to_string();
        if in_image {
            if let Some(s) = sections.last_mut() {
                s.push((k, v));
            }
        } else if let Some(name) = k.strip_prefix("@Sens. ") {
            if let Some(p) = parse_sens(&v) {
                sens.push((name.to_string(), p));
            }
        }
    }
    let mut images = Vec::new();
    for (i, s) in sections.iter().enumerate() {
        let get = |key: &str| s.iter().find(|(k, _)| k.eq_ignore_ascii_case(key)).map(|(_, v)| v.as_str());
        let Some(name_line) = get("@2:Image Data").or_else(|| get("Image Data")) else { continue };
        let name = match (name_line.find('"'), name_line.rfind('"')) {
            (Some(a), Some(b)) if b > a => name_line[a + 1..b].to_string(),
            _ => name_line.to_string(),
        };
        let num = |key: &str| -> Result<usize, SurfaceError> {
            get(key)
                .and_then(|v| v.split_whitespace().next())
                .and_then(|v| v.parse::<usize>().ok())
                .ok_or_else(|| bad(format!("image {i} ('{name}') has no valid '{key}'")))
        };
        let (cols, rows) = (num("Samps/line")?, num("Number of lines")?);
        crate::check_dims(rows, cols).map_err(|e| bad(format!("image {i} ('{name}'): {e}")))?;
        let offset = num("Data offset")?;
        // Stored width from `Data length`; the scale's width from `Bytes/pixel`. Version 9 files may store
        // 32-bit codes under `Bytes/pixel: 2` with a 16-bit Z scale (sample_0.spm's "Height"): pySPM, and so
        // AFMReader, read the data length's width and scale by the header's, which gives the right heights.
        let header_bpp = match get("Bytes/pixel") {
            Some(_) => Some(num("Bytes/pixel")?),
            None => None,
        };
        let bpp = match get("Data length") {
            Some(_) => num("Data length")? / (rows * cols),
            None => header_bpp.unwrap_or(2),
        };
        let scale_bpp = header_bpp.unwrap_or(bpp);
        if !matches!(bpp, 2 | 4) || !matches!(scale_bpp, 2 | 4) {
            return Err(bad(format!("image {i} ('{name}'): {bpp} bytes per pixel (2 or 4 expected)")));
        }
        let zline = get("@2:Z scale")
            .or_else(|| get("Z scale"))
            .ok_or_else(|| bad(format!("image {i} ('{name}') has no Z scale")))?;
        let (key, soft, soft_unit) =
            parse_z_scale(zline).ok_or_else(|| bad(format!("image {i} ('{name}'): unreadable Z scale '{zline}'")))?;
        let per_code = soft / 2f64.powi(8 * scale_bpp as i32);
        let (scale, unit) = match key.as_deref().and_then(|k| k.strip_prefix("Sens. ")) {
            Some(k) => match sens.iter().rev().find(|(n, _)| n == k) {
                Some((_, (s, u))) if !u.is_empty() => (per_code * s, u.clone()),
                _ => (per_code, soft_unit),
            },
            None => (per_code, soft_unit),
        };
        let extent = get("Scan Size").and_then(|v| {
            let p: Vec<&str> = v.split_whitespace().collect();
            let (sx, sy, u) = match p.as_slice() {
                [x, y, u, ..] => (x.parse::<f64>().ok()?, y.parse::<f64>().ok()?, *u),
                [x, u] => (x.parse::<f64>().ok()?, x.parse::<f64>().ok()?, *u),
                _ => return None,
            };
            let k = length_unit(u)?;
            // The second size is the nominal square side; the lines cover rows/cols of it (pySPM does the same).
            Some((sx * k, sy * k * rows as f64 / cols as f64))
        });
        let direction = get("Line Direction").unwrap_or("").to_ascii_lowercase();
        let z_unit = match unit.as_str() {
            "~m" => "µm".to_string(),
            _ => unit,
        };
        images.push(Image {
            info: ChannelInfo { index: images.len() as u32, name, rows, cols, z_unit, direction, alias: String::new() },
            offset,
            bpp,
            scale,
            extent,
        });
    }
    if images.is_empty() {
        return Err(bad("the header lists no image (\\*Ciao image list with Image Data)"));
    }
    Ok(images)
}

pub fn channels(bytes: &[u8]) -> Result<Vec<ChannelInfo>, SurfaceError> {
    Ok(parse(bytes)?.into_iter().map(|i| i.info).collect())
}

pub fn read(bytes: &[u8], side: Option<&Sidecar>, opts: &LoadOptions) -> Result<HeightField, SurfaceError> {
    let images = parse(bytes)?;
    let list: Vec<ChannelInfo> = images.iter().map(|i| i.info.clone()).collect();
    let im = &images[channel::pick(&list, opts.channel.as_ref())?];
    let (rows, cols) = (im.info.rows, im.info.cols);
    let need = rows * cols * im.bpp;
    if im.offset.checked_add(need).is_none_or(|end| end > bytes.len()) {
        return Err(bad(format!(
            "image '{}' needs {need} bytes at offset {}, the file has {} (truncated?)",
            im.info.name,
            im.offset,
            bytes.len()
        )));
    }
    let data = &bytes[im.offset..im.offset + need];
    let mut values = vec![0.0; rows * cols];
    for r in 0..rows {
        // Stored bottom line first.
        let src = (rows - 1 - r) * cols;
        for c in 0..cols {
            let at = (src + c) * im.bpp;
            let code = if im.bpp == 2 {
                f64::from(i16::from_le_bytes([data[at], data[at + 1]]))
            } else {
                f64::from(i32::from_le_bytes([data[at], data[at + 1], data[at + 2], data[at + 3]]))
            };
            values[r * cols + c] = code * im.scale;
        }
    }
    let file_pixel = im.extent.map(|(ex, ey)| (ex / cols as f64, ey / rows as f64));
    super::finish_channel(values, &list, &im.info, file_pixel, side, opts, "NanoScope")
}
