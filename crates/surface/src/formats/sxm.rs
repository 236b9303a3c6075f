//! Nanonis `.sxm` scans (SPECS Nanonis "SXM file format"): a text header of `:TAG:` lines each followed by
//! its value lines, ending with `:SCANIT_END:`, then the bytes `0x1A 0x04`, then big-endian `f32` images.
//! `:SCAN_PIXELS:` gives columns and rows, `:SCAN_RANGE:` the size in m, `:SCAN_DIR:` `up` or `down`,
//! and `:DATA_INFO:` a tab-separated table (`Channel Name Unit Direction Calibration Offset`) whose
//! `Direction` is `both` (a forward then a backward image) or `forward`/`backward` (one). Images are stored
//! in scan order: an upward scan starts at the bottom, so its rows are flipped; backward images are
//! stored right to left, so they are mirrored. Lines not yet scanned are NaN.

use crate::{HeightField, SurfaceError};

use super::channel::{self, ChannelInfo};
use super::{LoadOptions, Sidecar};

fn bad(m: impl Into<String>) -> SurfaceError {
    SurfaceError::invalid(format!("not a valid Nanonis .sxm file: {}", m.into()))
}

pub fn detect(bytes: &[u8]) -> bool {
    bytes.starts_with(b":NANONIS_VERSION:")
}

struct Parsed {
    list: Vec<ChannelInfo>,
    data_at: usize,
    extent: Option<(f64, f64)>,
    up: bool,
}

fn parse(bytes: &[u8]) -> Result<Parsed, SurfaceError> {
    if !detect(bytes) {
        return Err(bad("missing ':NANONIS_VERSION:'"));
    }
    let end_tag = b":SCANIT_END:";
    let end =
        bytes.windows(end_tag.len()).position(|w| w == end_tag).ok_or_else(|| bad("no :SCANIT_END: (truncated?)"))?;
    let marker = bytes[end..]
        .windows(2)
        .position(|w| w == [0x1a, 0x04])
        .ok_or_else(|| bad("no data marker 0x1A 0x04 after :SCANIT_END:"))?;
    let data_at = end + marker + 2;
    let header: String = bytes[..end].iter().map(|&b| b as char).collect();
    // Tag → value lines.
    let mut tags: Vec<(String, Vec<String>)> = Vec::new();
    for line in header.lines() {
        let t = line.trim_end();
        if t.starts_with(':') && t.ends_with(':') && t.len() > 2 {
            tags.push((t.trim_matches(':').to_string(), Vec::new()));
        } else if let Some(last) = tags.last_mut() {
            last.1.push(t.to_string());
        }
    }
    let get = |key: &str| tags.iter().find(|(k, _)| k == key).map(|(_, v)| v.as_slice());
    let first =
        |key: &str| get(key).and_then(|v| v.iter().find(|l| !l.trim().is_empty())).map(|s| s.trim().to_string());
    let pixels: Vec<usize> = first("SCAN_PIXELS")
        .ok_or_else(|| bad("no :SCAN_PIXELS:"))?
        .split_whitespace()
        .map(|v| v.parse::<usize>().map_err(|_| bad(format!("SCAN_PIXELS '{v}' is not a count"))))
        .collect::<Result<_, _>>()?;
    let [cols, rows] = pixels[..] else { return Err(bad("SCAN_PIXELS needs two counts")) };
    crate::check_dims(rows, cols)?;
    let extent = first("SCAN_RANGE").and_then(|v| {
        let r: Vec<f64> = v.split_whitespace().filter_map(|x| x.parse().ok()).collect();
        (r.len() == 2 && r[0] > 0.0 && r[1] > 0.0).then(|| (r[0] * 1e9, r[1] * 1e9))
    });
    let up = first("SCAN_DIR").is_none_or(|d| d.eq_ignore_ascii_case("up"));
    let info = get("DATA_INFO").ok_or_else(|| bad("no :DATA_INFO: table of channels"))?;
    let mut list = Vec::new();
    for line in info.iter().skip(1).filter(|l| !l.trim().is_empty()) {
        let f: Vec<&str> = line.split('\t').map(str::trim).filter(|s| !s.is_empty()).collect();
        if f.len() < 4 {
            return Err(bad(format!("DATA_INFO line '{}' has fewer than 4 fields", line.trim())));
        }
        let dirs: &[&str] = match f[3] {
            "both" => &["forward", "backward"],
            "forward" => &["forward"],
            "backward" => &["backward"],
            other => return Err(bad(format!("channel direction '{other}' (both, forward or backward expected)"))),
        };
        for d in dirs {
            list.push(ChannelInfo {
                index: list.len() as u32,
                name: f[1].to_string(),
                rows,
                cols,
                z_unit: f[2].to_string(),
                direction: d.to_string(),
                alias: String::new(),
            });
        }
        if list.len() > 1024 {
            return Err(bad("more than 1024 images"));
        }
    }
    if list.is_empty() {
        return Err(bad("DATA_INFO lists no channel"));
    }
    Ok(Parsed { list, data_at, extent, up })
}

pub fn channels(bytes: &[u8]) -> Result<Vec<ChannelInfo>, SurfaceError> {
    Ok(parse(bytes)?.list)
}

pub fn read(bytes: &[u8], side: Option<&Sidecar>, opts: &LoadOptions) -> Result<HeightField, SurfaceError> {
    let p = parse(bytes)?;
    let k = channel::pick(&p.list, opts.channel.as_ref())?;
    let ch = &p.list[k];
    let (rows, cols) = (ch.rows, ch.cols);
    let n = rows * cols;
    let at = p.data_at + k * n * 4;
    let data = bytes.get(at..at + n * 4).ok_or_else(|| {
        bad(format!(
            "image {k} ('{}', {}) needs {} bytes at offset {at}; the file has {} (truncated?)",
            ch.name,
            ch.direction,
            n * 4,
            bytes.len()
        ))
    })?;
    let backward = ch.direction == "backward";
    let mut values = vec![0.0; n];
    for (i, c) in data.chunks_exact(4).enumerate() {
        let (sr, sc) = (i / cols, i % cols);
        let r = if p.up { rows - 1 - sr } else { sr };
        let col = if backward { cols - 1 - sc } else { sc };
        values[r * cols + col] = f64::from(f32::from_be_bytes(c.try_into().expect("4 bytes")));
    }
    let file_pixel = p.extent.map(|(ex, ey)| (ex / cols as f64, ey / rows as f64));
    super::finish_channel(values, &p.list, ch, file_pixel, side, opts, "Nanonis scan")
}
