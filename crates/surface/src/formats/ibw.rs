//! Asylum Research (Igor Pro) binary waves, version 5 (`.ibw`; WaveMetrics Technical Note 003, "Igor
//! Binary Format"). A 64-byte `BinHeader5` (version, checksum, `wfmSize`, then the sizes of the formula,
//! note, units and dimension labels), a 320-byte `WaveHeader5` (`npnts` at 12, `type` at 16, `nDim[4]` at
//! 68, `sfA[4]` at 84, `dimUnits` at 152), the data (column-major: x fastest, then y, then layer), then the
//! formula, the note and the dimension labels (32 bytes each, the first of each dimension naming the
//! dimension itself). The byte order is the one in which the version reads 5.
//!
//! An Asylum image is `x × y × channels`; the layer labels name the channels (`HeightTracee`,
//! `AmplitudeRetrace`, …) and the wave note gives the scan size (`FastScanSize`, `SlowScanSize`, m).
//! Heights are stored in metres without a data unit, so the unit is inferred from the label (Height, ZSensor,
//! Amplitude, Deflection → m; Phase → deg). Row 0 is the last stored line (y up), as AFMReader shows it.

use crate::{HeightField, SurfaceError};

use super::channel::{self, ChannelInfo};
use super::{LoadOptions, Sidecar};

const BIN: usize = 64;
const WAVE: usize = 320;
const LABEL: usize = 32;

fn bad(m: impl Into<String>) -> SurfaceError {
    SurfaceError::invalid(format!("not a valid Igor binary wave: {}", m.into()))
}

/// Version 5 in either byte order, with a plausible data type.
pub fn detect(bytes: &[u8]) -> bool {
    if bytes.len() < BIN + WAVE {
        return false;
    }
    let le = bytes[0] == 5 && bytes[1] == 0;
    let be = bytes[0] == 0 && bytes[1] == 5;
    if !(le || be) {
        return false;
    }
    let t = if le {
        u16::from_le_bytes([bytes[BIN + 16], bytes[BIN + 17]])
    } else {
        u16::from_be_bytes([bytes[BIN + 16], bytes[BIN + 17]])
    };
    matches!(t & !0x40, 2 | 4 | 8 | 0x10 | 0x20) && t & 1 == 0
}

/// Numbers at byte offsets of a wave, in the file's byte order.
// Public but hidden: not API, reachable only for the crate's tests in tests/ (Cargo.toml, `[lib] test = false`);
// a view of borrowed bytes with no invariant to keep.
#[doc(hidden)]
#[derive(Debug)]
pub struct Wave<'a> {
    /// Whether the file is little-endian.
    pub le: bool,
    /// The file's bytes.
    pub b: &'a [u8],
}

impl Wave<'_> {
    /// The `N` bytes at `at` in little-endian order (reversed from a big-endian file).
    fn le_bytes<const N: usize>(&self, at: usize) -> [u8; N] {
        let mut s: [u8; N] = self.b[at..at + N].try_into().expect("a slice of N bytes");
        if !self.le {
            s.reverse();
        }
        s
    }
    /// The `i32` at `at`.
    pub fn i32(&self, at: usize) -> i32 {
        i32::from_le_bytes(self.le_bytes(at))
    }
    /// The `u16` at `at`.
    pub fn u16(&self, at: usize) -> u16 {
        u16::from_le_bytes(self.le_bytes(at))
    }
    /// The `f64` at `at`.
    pub fn f64(&self, at: usize) -> f64 {
        f64::from_le_bytes(self.le_bytes(at))
    }
}

struct Parsed {
    list: Vec<ChannelInfo>,
    /// x (columns) and y (rows) points.
    nx: usize,
    ny: usize,
    elem: usize,
    typ: u16,
    le: bool,
    data_at: usize,
    pixel_nm: Option<(f64, f64)>,
    note_size: Option<(f64, f64)>,
}

fn cstr(b: &[u8]) -> String {
    let n = b.iter().position(|&c| c == 0).unwrap_or(b.len());
    b[..n].iter().map(|&c| c as char).collect()
}

fn unit_for_label(label: &str) -> &'static str {
    let l = label.to_ascii_lowercase();
    if ["height", "zsensor", "amplitude", "deflection"].iter().any(|k| l.contains(k)) {
        "m"
    } else if l.contains("phase") {
        "deg"
    } else {
        ""
    }
}

fn parse(bytes: &[u8]) -> Result<Parsed, SurfaceError> {
    if !detect(bytes) {
        return Err(bad("not version 5 (only Igor Pro 3+ waves, version 5, are read)"));
    }
    let w = Wave { le: bytes[0] == 5, b: bytes };
    let size = |at: usize, what: &str| -> Result<usize, SurfaceError> {
        let v = w.i32(at);
        usize::try_from(v).map_err(|_| bad(format!("negative {what} size {v}")))
    };
    let wfm = size(4, "wave")?;
    let formula = size(8, "formula")?;
    let note = size(12, "note")?;
    let data_e_units = size(16, "data units")?;
    let mut dim_e_units = 0usize;
    let mut labels = [0usize; 4];
    for k in 0..4 {
        dim_e_units = dim_e_units.saturating_add(size(20 + 4 * k, "dimension units")?);
        labels[k] = size(36 + 4 * k, "dimension labels")?;
    }
    let h = BIN;
    let typ = w.u16(h + 16);
    let elem = match typ & !0x40 {
        2 => 4,
        4 => 8,
        8 => 1,
        0x10 => 2,
        0x20 => 4,
        _ => return Err(bad(format!("data type {typ:#x} is not a real number type"))),
    };
    let mut n = [0usize; 4];
    for k in 0..4 {
        n[k] = size(h + 68 + 4 * k, "dimension")?;
    }
    let (nx, ny, nz) = (n[0], n[1], n[2].max(1));
    if n[3] > 1 {
        return Err(bad(format!("a 4-D wave ({} × {} × {} × {}) is not an image", n[0], n[1], n[2], n[3])));
    }
    crate::check_dims(ny, nx)?;
    if nz > 4096 {
        return Err(bad(format!("{nz} layers is not an image stack")));
    }
    let data_at = BIN + WAVE;
    let data_len = nx
        .checked_mul(ny)
        .and_then(|v| v.checked_mul(nz))
        .and_then(|v| v.checked_mul(elem))
        .ok_or_else(|| bad("size overflow"))?;
    if wfm < WAVE || wfm - WAVE < data_len {
        return Err(bad(format!("wave size {wfm} bytes is too small for {nx} × {ny} × {nz} values")));
    }
    let after_data = data_at + (wfm - WAVE);
    let end = |v: usize, plus: usize| v.checked_add(plus).ok_or_else(|| bad("size overflow"));
    if end(data_at, data_len)? > bytes.len() {
        return Err(bad(format!(
            "file truncated: {} bytes of data expected, {} present",
            data_len,
            bytes.len().saturating_sub(data_at)
        )));
    }
    let note_at = end(after_data, formula)?;
    let note_end = end(note_at, note)?;
    let labels_at = end(end(note_end, data_e_units)?, dim_e_units)?;
    let note_text =
        if note_end <= bytes.len() { cstr(&bytes[note_at..note_end]).replace('\r', "\n") } else { String::new() };
    // Layer labels: dimension 2's block starts after the blocks of dimensions 0 and 1.
    let l2 = end(end(labels_at, labels[0])?, labels[1])?;
    // (label up to its NUL, all its non-NUL bytes: the form igor2 returns)
    let mut names: Vec<(String, String)> = Vec::new();
    if labels[2] >= LABEL && end(l2, labels[2])? <= bytes.len() {
        for k in 1..labels[2] / LABEL {
            let raw = &bytes[l2 + k * LABEL..l2 + (k + 1) * LABEL];
            names.push((cstr(raw), raw.iter().filter(|&&c| c != 0).map(|&c| c as char).collect()));
        }
    }
    let mut list = Vec::new();
    for k in 0..nz {
        let label = names.get(k).map(|n| n.0.clone()).filter(|s| !s.is_empty()).unwrap_or_else(|| format!("layer {k}"));
        let alias = names.get(k).map(|n| n.1.clone()).filter(|a| *a != label).unwrap_or_default();
        let direction = if label.ends_with("Retrace") {
            "retrace"
        } else if label.ends_with("Trace") || label.ends_with("Tracee") {
            "trace"
        } else {
            ""
        };
        list.push(ChannelInfo {
            index: k as u32,
            z_unit: unit_for_label(&label).to_string(),
            name: label,
            rows: ny,
            cols: nx,
            direction: direction.into(),
            alias,
        });
    }
    // Scaling from the header: sfA is the x/y step in dimUnits.
    let step = |k: usize| {
        let u = cstr(&bytes[h + 152 + 4 * k..h + 156 + 4 * k]);
        super::unit_to_nm(&u).map(|s| w.f64(h + 84 + 8 * k) * s)
    };
    let pixel_nm = match (step(0), step(1)) {
        (Some(a), Some(b)) if a > 0.0 && b > 0.0 => Some((a, b)),
        _ => None,
    };
    let note_num = |key: &str| {
        note_text.lines().find_map(|l| {
            let (k, v) = l.split_once(':')?;
            (k.trim() == key).then(|| v.trim().parse::<f64>().ok()).flatten()
        })
    };
    let note_size = match (note_num("FastScanSize"), note_num("SlowScanSize")) {
        (Some(f), Some(s)) if f > 0.0 && s > 0.0 => Some((f * 1e9, s * 1e9)),
        _ => note_num("ScanSize").filter(|s| *s > 0.0).map(|s| (s * 1e9, s * 1e9)),
    };
    Ok(Parsed { list, nx, ny, elem, typ, le: w.le, data_at, pixel_nm, note_size })
}

pub fn channels(bytes: &[u8]) -> Result<Vec<ChannelInfo>, SurfaceError> {
    Ok(parse(bytes)?.list)
}

pub fn read(bytes: &[u8], side: Option<&Sidecar>, opts: &LoadOptions) -> Result<HeightField, SurfaceError> {
    let p = parse(bytes)?;
    let k = channel::pick(&p.list, opts.channel.as_ref())?;
    let (nx, ny) = (p.nx, p.ny);
    let layer = p.data_at + k * nx * ny * p.elem;
    let unsigned = p.typ & 0x40 != 0;
    let value = |i: usize| -> f64 {
        let at = layer + i * p.elem;
        let s = &bytes[at..at + p.elem];
        let mut a = [0u8; 8];
        if p.le {
            a[..p.elem].copy_from_slice(s);
        } else {
            for (j, &b) in s.iter().rev().enumerate() {
                a[j] = b;
            }
        }
        match (p.typ & !0x40, unsigned) {
            (2, _) => f64::from(f32::from_le_bytes([a[0], a[1], a[2], a[3]])),
            (4, _) => f64::from_le_bytes(a),
            (8, false) => f64::from(a[0] as i8),
            (8, true) => f64::from(a[0]),
            (0x10, false) => f64::from(i16::from_le_bytes([a[0], a[1]])),
            (0x10, true) => f64::from(u16::from_le_bytes([a[0], a[1]])),
            (_, false) => f64::from(i32::from_le_bytes([a[0], a[1], a[2], a[3]])),
            (_, true) => f64::from(u32::from_le_bytes([a[0], a[1], a[2], a[3]])),
        }
    };
    let mut values = vec![0.0; nx * ny];
    for r in 0..ny {
        let y = ny - 1 - r;
        for c in 0..nx {
            values[r * nx + c] = value(y * nx + c);
        }
    }
    // The note's scan size over the points (AFMReader's pixel), else the wave's own x/y step.
    let file_pixel = p.note_size.map(|(f, s)| (f / nx as f64, s / ny as f64)).or(p.pixel_nm);
    super::finish_channel(values, &p.list, &p.list[k], file_pixel, side, opts, "Igor binary wave")
}
