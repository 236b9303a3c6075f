//! Reading and writing height fields. The format is recognised from the file's first bytes (magic numbers),
//! and only falls back to the extension for plain text; units come from the file itself (Gwyddion), then
//! from a JSON sidecar, then from the options the user typed, the last one winning.
//!
//! | format | read | write | units |
//! |---|---|---|---|
//! | Gwyddion `.gwy` | yes | yes | in the file (`xreal`, `si_unit_xy`, `si_unit_z`) |
//! | numpy `.npy` (f32, f64, integers) | yes | f64 | sidecar or options |
//! | numpy `.npz` (`savez`, compressed or not; `--channel N` among several 2-D arrays) | yes | f64, array `heights` | sidecar or options |
//! | PNG, TIFF 8/16-bit grey | yes | PNG 16-bit | relative: `--max-height`, `--pixel-size` or sidecar |
//! | text matrix | yes | yes | Gwyddion ASCII-export header (`# Width: 5 µm`), sidecar or options |

pub mod gwy;
pub mod npy;
pub mod npz;
pub mod raster;
pub mod sidecar;
pub mod text;

use std::path::{Path, PathBuf};

use crate::{HeightField, SurfaceError};
pub use sidecar::Sidecar;

/// Largest file read (bytes): a 2²⁶-sample f64 array plus headers. Checked before reading.
pub const MAX_FILE_BYTES: u64 = (crate::MAX_SAMPLES as u64) * 8 + (1 << 20);

/// A height-field file format.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    Gwy,
    Npy,
    Npz,
    Png,
    Tiff,
    Text,
}

impl Format {
    pub fn name(self) -> &'static str {
        match self {
            Format::Gwy => "gwy",
            Format::Npy => "npy",
            Format::Npz => "npz",
            Format::Png => "png",
            Format::Tiff => "tiff",
            Format::Text => "text",
        }
    }

    /// The format an output path asks for, from its extension.
    pub fn from_extension(path: &Path) -> Option<Format> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        Some(match ext.as_str() {
            "gwy" => Format::Gwy,
            "npy" => Format::Npy,
            "npz" => Format::Npz,
            "png" => Format::Png,
            "tif" | "tiff" => Format::Tiff,
            "txt" | "asc" | "csv" | "dat" | "xyz" => Format::Text,
            _ => return None,
        })
    }
}

/// Options for [`load_surface`]; `None` means "from the file or its sidecar".
#[derive(Debug, Clone, Default, PartialEq)]
pub struct LoadOptions {
    /// Pixel size (nm), both axes. Required for formats without units; overrides the file's if given.
    pub pixel_size_nm: Option<f64>,
    /// Images: the height (nm) that full white stands for; black is 0.
    pub max_height_nm: Option<f64>,
    /// Gwyddion: the channel number (`/N/data`), default the lowest; `.npz`: the index of the 2-D array in
    /// name order, needed when the archive holds several.
    pub channel: Option<u32>,
    /// Built-in surfaces: edge length of the square patch (nm); default 65 µm.
    pub size_nm: Option<f64>,
    /// Built-in surfaces: random seed; default 1.
    pub seed: Option<u64>,
    /// Do not look for a JSON sidecar.
    pub ignore_sidecar: bool,
}

/// Recognises a format from the first bytes of a file.
pub fn detect_format(bytes: &[u8]) -> Option<Format> {
    if bytes.starts_with(b"GWYP") || bytes.starts_with(b"GWYO") {
        Some(Format::Gwy)
    } else if bytes.starts_with(b"\x93NUMPY") {
        Some(Format::Npy)
    } else if bytes.starts_with(b"PK\x03\x04") || bytes.starts_with(b"PK\x05\x06") {
        Some(Format::Npz)
    } else if bytes.starts_with(b"\x89PNG\r\n\x1a\n") {
        Some(Format::Png)
    } else if bytes.starts_with(b"II*\0") || bytes.starts_with(b"MM\0*") {
        Some(Format::Tiff)
    } else if text::looks_like_text(bytes) {
        Some(Format::Text)
    } else {
        None
    }
}

fn describe_unknown(bytes: &[u8]) -> String {
    let kind = if bytes.starts_with(b"\xff\xd8\xff") {
        "a JPEG image: lossy compression destroys heights, export the scan as 16-bit PNG/TIFF, .gwy or .npy"
    } else if bytes.starts_with(b"II+\0") || bytes.starts_with(b"MM\0+") {
        "a BigTIFF, which is not supported: save as an ordinary TIFF"
    } else if bytes.is_empty() {
        "empty"
    } else {
        "not a recognised height-field format"
    };
    format!("{kind} (recognised: Gwyddion .gwy, numpy .npy/.npz, PNG, TIFF, text matrix)")
}

/// Loads a height field from a file path or a `builtin:NAME[?key=value&…]` spec (see [`crate::builtin`]).
pub fn load_surface(spec: &str, opts: &LoadOptions) -> Result<HeightField, SurfaceError> {
    if let Some(rest) = spec.strip_prefix("builtin:") {
        return crate::builtin::builtin_surface(rest, opts);
    }
    let path = Path::new(spec);
    let io = |e: std::io::Error| SurfaceError::Io { path: spec.to_string(), err: e };
    let meta = std::fs::metadata(path).map_err(io)?;
    if meta.is_dir() {
        return Err(SurfaceError::invalid(format!("{spec} is a folder, not a height-field file")));
    }
    if meta.len() > MAX_FILE_BYTES {
        return Err(SurfaceError::invalid(format!(
            "{spec} is {} MB, more than the {} MB a height field of at most {} samples needs",
            meta.len() >> 20,
            MAX_FILE_BYTES >> 20,
            crate::MAX_SAMPLES
        )));
    }
    let bytes = std::fs::read(path).map_err(io)?;
    let side = if opts.ignore_sidecar { None } else { Sidecar::find(path)? };
    let mut hf = read_bytes(&bytes, spec, side.as_ref(), opts)?;
    if let Some(s) = &side {
        hf.meta.notes.push(format!("units from sidecar {}", s.path.display()));
    }
    Ok(hf)
}

/// Parses bytes whose format is recognised by content; `name` is used in messages.
pub fn read_bytes(
    bytes: &[u8],
    name: &str,
    side: Option<&Sidecar>,
    opts: &LoadOptions,
) -> Result<HeightField, SurfaceError> {
    let fmt = detect_format(bytes)
        .ok_or_else(|| SurfaceError::Format { path: name.into(), message: describe_unknown(bytes) })?;
    let wrap = |e: SurfaceError| match e {
        SurfaceError::Invalid(m) => SurfaceError::Format { path: name.into(), message: m },
        other => other,
    };
    let mut hf = match fmt {
        Format::Gwy => gwy::read(bytes, side, opts),
        Format::Npy => npy::read(bytes, side, opts),
        Format::Npz => npz::read(bytes, side, opts),
        Format::Png | Format::Tiff => raster::read(bytes, fmt, side, opts),
        Format::Text => text::read(bytes, side, opts),
    }
    .map_err(wrap)?;
    hf.meta.source = name.to_string();
    hf.meta.format = fmt.name().to_string();
    Ok(hf)
}

/// Encodes a height field; the second value is the JSON sidecar to write beside it (for formats that do
/// not hold units themselves).
pub fn write_bytes(hf: &HeightField, fmt: Format) -> Result<(Vec<u8>, Option<String>), SurfaceError> {
    match fmt {
        Format::Gwy => Ok((gwy::write(hf), None)),
        Format::Npy => Ok((npy::write(hf)?, Some(Sidecar::for_field(hf, false).to_json()))),
        Format::Png => Ok((raster::write_png16(hf)?, Some(Sidecar::for_field(hf, true).to_json()))),
        Format::Text => Ok((text::write(hf).into_bytes(), None)),
        Format::Npz => Ok((npz::write(hf)?, Some(Sidecar::for_field(hf, false).to_json()))),
        Format::Tiff => Err(SurfaceError::invalid(
            "writing TIFF is not supported (a 16-bit PNG holds the same data); write .png, .gwy, .npy or .txt",
        )),
    }
}

/// Where the sidecar of `path` is written: `FILE.EXT.json`.
pub fn sidecar_path(path: &Path) -> PathBuf {
    let mut s = path.as_os_str().to_owned();
    s.push(".json");
    PathBuf::from(s)
}

/// Pixel sizes from (in increasing priority) the file, the sidecar and the options.
pub(crate) fn pick_pixel(
    from_file: Option<(f64, f64)>,
    side: Option<&Sidecar>,
    opts: &LoadOptions,
    what: &str,
) -> Result<(f64, f64), SurfaceError> {
    let p = opts.pixel_size_nm.map(|p| (p, p)).or_else(|| side.and_then(|s| s.pixel_nm())).or(from_file).ok_or_else(
        || {
            SurfaceError::invalid(format!(
                "{what} has no pixel size: give --pixel-size (e.g. 65nm) or a sidecar FILE.json with \
                 {{\"pixel_size_nm\": 65}}"
            ))
        },
    )?;
    crate::check_pixel(p.0, p.1)?;
    Ok(p)
}

/// Length unit string → nanometres per unit (`m`, `mm`, `um`, `µm`, `nm`, `pm`, `Å`, `A`).
pub fn unit_to_nm(unit: &str) -> Option<f64> {
    let u = unit.trim();
    Some(match u {
        "m" => 1e9,
        "cm" => 1e7,
        "mm" => 1e6,
        "um" | "µm" | "μm" | "micron" | "microns" => 1e3,
        "nm" => 1.0,
        "pm" => 1e-3,
        "Å" | "A" | "Angstrom" | "angstrom" => 0.1,
        _ => return None,
    })
}

/// Shared test helpers.
#[cfg(test)]
pub(crate) fn sample_field() -> HeightField {
    let (rows, cols) = (7, 9);
    let h = (0..rows * cols).map(|i| ((i as f64) * 0.37).sin() * 40.0 + i as f64 * 0.01).collect();
    HeightField::new(rows, cols, 12.5, 13.25, h).unwrap()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn detection_by_content() {
        assert_eq!(detect_format(b"GWYP\0\0"), Some(Format::Gwy));
        assert_eq!(detect_format(b"\x93NUMPY\x01\x00"), Some(Format::Npy));
        assert_eq!(detect_format(b"\x89PNG\r\n\x1a\nxxxx"), Some(Format::Png));
        assert_eq!(detect_format(b"II*\0...."), Some(Format::Tiff));
        assert_eq!(detect_format(b"1 2 3\n4 5 6\n"), Some(Format::Text));
        assert_eq!(detect_format(b"\xff\xd8\xff\xe0JFIF"), None);
        let e = read_bytes(b"\xff\xd8\xff\xe0JFIF", "x.jpg", None, &LoadOptions::default()).unwrap_err();
        assert!(e.to_string().contains("JPEG"), "{e}");
    }

    #[test]
    fn units() {
        assert_eq!(unit_to_nm("m"), Some(1e9));
        assert_eq!(unit_to_nm("µm"), Some(1e3));
        assert_eq!(unit_to_nm("furlong"), None);
    }
}
