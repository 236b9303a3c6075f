//! Plain-text matrices: one row per line, numbers separated by spaces, tabs, commas or semicolons; lines
//! starting with `#` are comments. Gwyddion's "ASCII data matrix" export header is understood
//! (`# Width: 5.000 µm`, `# Height: 5.000 µm`, `# Value units: m`), and iridis writes the same header, so
//! a text file carries its own units.

use std::fmt::Write as _;

use crate::{HeightField, SurfaceError};

use super::{LoadOptions, Sidecar};

/// UTF-8 without NUL bytes in the first 4 KiB, with at least one digit.
pub fn looks_like_text(bytes: &[u8]) -> bool {
    let head = &bytes[..bytes.len().min(4096)];
    if head.is_empty() || head.contains(&0) {
        return false;
    }
    let ok = match std::str::from_utf8(head) {
        Ok(_) => true,
        Err(e) => e.valid_up_to() + 4 > head.len() && bytes.len() > head.len(),
    };
    ok && head.iter().any(u8::is_ascii_digit)
}

/// `"5.000 µm"` → nm.
fn length(s: &str) -> Option<f64> {
    let s = s.trim();
    let split = s.find(|c: char| !(c.is_ascii_digit() || matches!(c, '.' | '-' | '+' | 'e' | 'E')))?;
    let v: f64 = s[..split].trim().parse().ok()?;
    Some(v * super::unit_to_nm(&s[split..])?)
}

pub fn read(bytes: &[u8], side: Option<&Sidecar>, opts: &LoadOptions) -> Result<HeightField, SurfaceError> {
    let text = std::str::from_utf8(bytes)
        .map_err(|e| SurfaceError::invalid(format!("not UTF-8 text (byte {}): not a text matrix", e.valid_up_to())))?;
    let (mut width, mut height, mut zunit): (Option<f64>, Option<f64>, Option<String>) = (None, None, None);
    let mut values = Vec::new();
    let mut cols = 0usize;
    let mut rows = 0usize;
    let mut header_seen = false;
    for (ln, line) in text.lines().enumerate() {
        let t = line.trim();
        if let Some(c) = t.strip_prefix('#') {
            if let Some((k, v)) = c.split_once(':') {
                match k.trim().to_ascii_lowercase().as_str() {
                    "width" => width = length(v),
                    "height" => height = length(v),
                    "value units" => zunit = Some(v.trim().to_string()),
                    _ => {}
                }
            }
            continue;
        }
        if t.is_empty() {
            continue;
        }
        let before = values.len();
        for tok in t.split(|c: char| c.is_whitespace() || c == ',' || c == ';').filter(|s| !s.is_empty()) {
            match tok.parse::<f64>() {
                Ok(v) if v.is_finite() => values.push(v),
                Ok(v) => {
                    return Err(SurfaceError::invalid(format!(
                        "line {}: value {v} is not finite; heights must be finite numbers",
                        ln + 1
                    )))
                }
                Err(_) if !header_seen && values.is_empty() => {
                    // One header line of column names; a second would make any text a matrix of no rows.
                    header_seen = true;
                    break;
                }
                Err(_) => {
                    return Err(SurfaceError::invalid(format!(
                        "line {}: '{tok}' is not a number (a text height field is rows of numbers, after at most \
                         one line of column names)",
                        ln + 1
                    )));
                }
            }
        }
        let n = values.len() - before;
        if n == 0 {
            continue;
        }
        if rows == 0 {
            cols = n;
        } else if n != cols {
            return Err(SurfaceError::invalid(format!(
                "line {}: {n} values, but the first row has {cols}: a matrix needs equal rows",
                ln + 1
            )));
        }
        rows += 1;
        if rows > crate::MAX_DIM || values.len() > crate::MAX_SAMPLES {
            return Err(SurfaceError::invalid("text matrix too large"));
        }
    }
    crate::check_dims(rows, cols)?;
    let mut warnings = Vec::new();
    let mut given = super::given_height_unit(side, opts)?;
    let scale = match (zunit.as_deref(), given.as_ref().map(|g| g.0)) {
        (Some(u), g) => {
            let k = super::unit_to_nm(u)
                .ok_or_else(|| SurfaceError::invalid(format!("value unit '{u}' is not a length: not a height map")))?;
            match (g, &given) {
                (Some(gk), Some((_, from))) if (gk / k - 1.0).abs() > 1e-9 => {
                    if opts.override_units {
                        warnings.push(format!(
                            "height unit {from} overrides the header's value unit {u} \
                             (--override-units)"
                        ));
                        gk
                    } else {
                        warnings.push(format!(
                            "height unit {from} ignored: the header gives the values in {u}; --override-units \
                             reads them in yours instead"
                        ));
                        given = None;
                        k
                    }
                }
                _ => {
                    given = None;
                    k
                }
            }
        }
        (None, Some(k)) => k,
        (None, None) => {
            warnings.push("the text gives no height unit; values taken as nm (give --height-unit)".into());
            super::warn_if_metres(&values, &mut warnings);
            1.0
        }
    };
    let file_pixel = match (width, height) {
        (Some(w), Some(h)) => Some((w / cols as f64, h / rows as f64)),
        (Some(w), None) => Some((w / cols as f64, w / cols as f64)),
        _ => None,
    };
    let ((dx, dy), pixel_warning) = super::pick_pixel(file_pixel, side, opts, "a text matrix")?;
    warnings.extend(pixel_warning);
    let hf = HeightField::new(rows, cols, dx, dy, values.into_iter().map(|v| v * scale).collect())?;
    let mut meta = hf.meta.clone();
    meta.z_unit = given.map(|g| g.1).or(zunit).unwrap_or_else(|| "nm (assumed)".into());
    meta.warnings = warnings;
    meta.notes.push(format!("text matrix {rows} × {cols}"));
    Ok(hf.with_meta(meta))
}

/// Gwyddion-style header, heights in nm with shortest round-trip formatting (exact).
pub fn write(hf: &HeightField) -> String {
    let (w, h) = hf.extent_nm();
    let mut s = String::with_capacity(hf.heights_nm.len() * 12 + 200);
    let _ = writeln!(s, "# Channel: Height (iridis-surface {})", env!("CARGO_PKG_VERSION"));
    let _ = writeln!(s, "# Width: {w} nm");
    let _ = writeln!(s, "# Height: {h} nm");
    let _ = writeln!(s, "# Value units: nm");
    for r in 0..hf.rows {
        let row = hf.row(r);
        for (i, v) in row.iter().enumerate() {
            if i > 0 {
                s.push('\t');
            }
            let _ = write!(s, "{v}");
        }
        s.push('\n');
    }
    s
}
