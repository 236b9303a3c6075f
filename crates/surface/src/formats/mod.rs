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
//! | Gwyddion Simple Field `.gsf` | yes | yes | in the file (`XReal`, `XYUnits`, `ZUnits`) |
//! | Bruker NanoScope `.spm`, `.000` (v5–9, 16/32-bit) | yes | no | in the file (`Scan Size`, `Z scale` × sensitivity) |
//! | Asylum Igor binary wave `.ibw` (v5) | yes | no | scan size from the wave note; heights in m |
//! | JPK `.jpk` (TIFF with JPK tags) | yes | no | in the file (grid lengths, per-channel linear scaling) |
//! | WSxM `.stp`, `.top` | yes | no | in the file (`X Amplitude`, `Z Amplitude`) |
//! | Nanonis `.sxm` | yes | no | in the file (`SCAN_RANGE`, `DATA_INFO` units) |
//!
//! Instrument files hold several channels; [`list_channels`] lists them and `LoadOptions::channel` picks
//! one by index or by name (see [`channel`]).

pub mod channel;
pub mod gsf;
pub mod gwy;
pub mod ibw;
pub mod jpk;
pub mod nanoscope;
pub mod npy;
pub mod npz;
pub mod raster;
pub mod sidecar;
pub mod sxm;
pub mod text;
pub mod wsxm;

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
    Gsf,
    Nanoscope,
    Ibw,
    Jpk,
    Wsxm,
    Sxm,
}

impl Format {
    /// Whether its reader reads `--channel`: an instrument format names its channels (one in a GSF or WSxM
    /// file, chosen by index 0 or its name); a bare array or image has one channel and no name for it.
    pub fn reads_channel(self) -> bool {
        !matches!(self, Format::Npy | Format::Png | Format::Tiff | Format::Text)
    }

    pub fn name(self) -> &'static str {
        match self {
            Format::Gwy => "gwy",
            Format::Npy => "npy",
            Format::Npz => "npz",
            Format::Png => "png",
            Format::Tiff => "tiff",
            Format::Text => "text",
            Format::Gsf => "gsf",
            Format::Nanoscope => "nanoscope",
            Format::Ibw => "ibw",
            Format::Jpk => "jpk",
            Format::Wsxm => "wsxm",
            Format::Sxm => "sxm",
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
            "gsf" => Format::Gsf,
            _ => return None,
        })
    }
}

/// Options for [`load_surface`]; `None` means "from the file or its sidecar".
#[derive(Debug, Clone, Default, PartialEq)]
pub struct LoadOptions {
    /// Pixel size (nm), both axes. Required for formats without units; where the file states its own, the
    /// file's wins unless `override_units`.
    pub pixel_size_nm: Option<f64>,
    /// Images: the height (nm) that full white stands for; black is 0.
    pub max_height_nm: Option<f64>,
    /// Which channel: an index or a name (`iridis surface channels` lists them). Gwyddion: the channel
    /// number (`/N/data`) or title; `.npz`: the index of the 2-D array in name order or
    /// its name, needed when the archive holds several; instrument files: the index in file order or the
    /// name. Default: the channel named Height, else the first height channel ([`channel::pick`]).
    pub channel: Option<channel::ChannelSel>,
    /// Unit of stored heights where the file has none (`.npy`, text, a unitless channel); overrides a
    /// sidecar's `height_unit`, and a file's own unit only with `override_units`.
    pub height_unit: Option<String>,
    /// Built-in surfaces: edge length of the square patch (nm); default 65 µm.
    pub size_nm: Option<f64>,
    /// Built-in surfaces: random seed; default 1.
    pub seed: Option<u64>,
    /// Do not look for a JSON sidecar.
    pub ignore_sidecar: bool,
    /// Let `pixel_size_nm` and `height_unit` (or a sidecar's) replace the pixel size and height unit a file
    /// states itself; without it the file's own win and a warning names both.
    pub override_units: bool,
    /// Read a channel that is not a height (another signal's name, a unit that is not a length) as heights.
    pub as_height: bool,
}

/// A content test: do the file's first bytes look like one format?
type Detector = fn(&[u8]) -> bool;

/// The content tests of [`detect_format`], tried in this order, the first that matches winning: JPK files are
/// TIFFs, so JPK comes before TIFF; instrument files with text headers could pass for text, so text comes last.
const DETECTORS: &[(Detector, Format)] = &[
    (|b| b.starts_with(b"GWYP") || b.starts_with(b"GWYO"), Format::Gwy),
    (|b| b.starts_with(b"\x93NUMPY"), Format::Npy),
    (|b| b.starts_with(b"PK\x03\x04") || b.starts_with(b"PK\x05\x06"), Format::Npz),
    (|b| b.starts_with(b"\x89PNG\r\n\x1a\n"), Format::Png),
    (jpk::detect, Format::Jpk),
    (|b| b.starts_with(b"II*\0") || b.starts_with(b"MM\0*"), Format::Tiff),
    (nanoscope::detect, Format::Nanoscope),
    (wsxm::detect, Format::Wsxm),
    (sxm::detect, Format::Sxm),
    (gsf::detect, Format::Gsf),
    (ibw::detect, Format::Ibw),
    (text::looks_like_text, Format::Text),
];

/// Recognises a format from the first bytes of a file.
pub fn detect_format(bytes: &[u8]) -> Option<Format> {
    DETECTORS.iter().find(|(detect, _)| detect(bytes)).map(|&(_, format)| format)
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
    format!(
        "{kind} (recognised: Gwyddion .gwy/.gsf, Bruker NanoScope .spm/.000, Asylum .ibw, JPK .jpk, WSxM \
         .stp/.top, Nanonis .sxm, numpy .npy/.npz, PNG, TIFF, text matrix)"
    )
}

/// Loads a height field from a file path or a `builtin:NAME[?key=value&…]` spec (see [`crate::builtin`]).
pub fn load_surface(spec: &str, opts: &LoadOptions) -> Result<HeightField, SurfaceError> {
    // Options that this kind of SURFACE has no use for are refused by name: each would change nothing.
    // `why` says what the options are for; `it`/`they` (with its verb) is chosen by how many were given.
    let refuse = |given: &[(&str, bool)], why: &dyn Fn(&str) -> String| {
        let named: Vec<&str> = given.iter().filter(|g| g.1).map(|g| g.0).collect();
        if named.is_empty() {
            return Ok(());
        }
        let subject = if named.len() == 1 { "it" } else { "they" };
        Err(SurfaceError::invalid(format!("{} would be ignored: {}", named.join(", "), why(subject))))
    };
    if let Some(rest) = spec.strip_prefix("builtin:") {
        let file_options = [
            ("--max-height", opts.max_height_nm.is_some()),
            ("--channel", opts.channel.is_some()),
            ("--height-unit", opts.height_unit.is_some()),
            ("--override-units", opts.override_units),
            ("--as-height", opts.as_height),
        ];
        refuse(&file_options, &|it| {
            let is = if it == "it" { "is" } else { "are" };
            format!("{it} {is} for reading files, and builtin:{rest} is generated: one channel, heights in nm")
        })?;
        return crate::builtin::builtin_surface(rest, opts);
    }
    refuse(&[("--size", opts.size_nm.is_some()), ("--seed", opts.seed.is_some())], &|it| {
        let shape = if it == "it" { "shapes" } else { "shape" };
        format!(
            "{it} {shape} built-in surfaces, and {spec} is a file (`iridis surface convert` crops and resamples one)"
        )
    })?;
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
    let fmt = detect_format(&bytes);
    if let Some(fmt) = fmt.filter(|f| !matches!(f, Format::Png | Format::Tiff)) {
        refuse(&[("--max-height", opts.max_height_nm.is_some())], &|_| {
            format!("it is the height of white in a grey image, and {spec} holds heights ({} format)", fmt.name())
        })?;
    }
    if let Some(fmt) =
        fmt.filter(|f| matches!(f, Format::Npy | Format::Npz | Format::Png | Format::Tiff | Format::Text))
    {
        refuse(&[("--as-height", opts.as_height)], &|_| {
            format!(
                "it reads an instrument's non-height channel as heights, and {spec} holds numbers without a \
                 signal's name ({} format): they are read as heights already",
                fmt.name()
            )
        })?;
    }
    let side = if opts.ignore_sidecar { None } else { Sidecar::find(path)? };
    let nothing_to_apply = opts.pixel_size_nm.is_none() && opts.height_unit.is_none() && side.is_none();
    refuse(&[("--override-units", opts.override_units && nothing_to_apply)], &|_| {
        "it lets --pixel-size or --height-unit (or a sidecar's) win over the file's own, and none is given".into()
    })?;
    let mut hf = read_bytes(&bytes, spec, side.as_ref(), opts)?;
    if let Some(s) = &side {
        hf.meta.notes.push(format!("units from sidecar {}", s.path.display()));
        // --height-unit wins over the sidecar's (given_height_unit): say so, as a file's own unit is.
        if let (Some(given), Some(theirs)) = (&opts.height_unit, &s.height_unit) {
            if unit_to_nm(given) != unit_to_nm(theirs) {
                hf.meta.warnings.push(format!(
                    "--height-unit {given} replaces the sidecar's height unit '{theirs}' ({}): heights are read in \
                     {given}",
                    s.path.display()
                ));
            }
        }
    }
    hf.meta.warnings.extend(implausible_units(&hf));
    Ok(hf)
}

/// Warnings for a file whose units, as read, give a field no microscope makes: a relief below a picometre (a
/// wrong --height-unit: a field in nm read as m gave all-zero heights and a report verdict of "too shallow to
/// diffract"), pixels above 100 µm (`--pixel-size 100mm` for 100 nm made a 6.4 m scan) or below 0.01 nm.
fn implausible_units(hf: &HeightField) -> Vec<String> {
    let mut warnings = Vec::new();
    let max = hf.heights_nm.iter().filter(|v| v.is_finite()).fold(0.0f64, |m, v| m.max(v.abs()));
    let said = hf.meta.warnings.iter().any(|w| w.contains("picometre"));
    if max > 0.0 && max < 1e-3 && !said {
        warnings.push(format!(
            "the relief is below a picometre (largest |height| {max:.3e} nm as read): the height unit is likely \
             wrong (the file's, the sidecar's or --height-unit); every model result would be of a flat surface"
        ));
    }
    let pixel = hf.dx_nm.max(hf.dy_nm);
    if pixel > 1e5 {
        warnings.push(format!(
            "pixels of {} µm as read: a scan's are nanometres to a few micrometres; check the pixel size's unit \
             (--pixel-size, the sidecar's or the file's)",
            pixel_text(pixel / 1000.0)
        ));
    }
    // Below an atom's spacing (~0.1 nm) no instrument samples: `--pixel-size 1e-30nm` printed "0.0000 nm".
    let finest = hf.dx_nm.min(hf.dy_nm);
    if finest < 0.01 {
        warnings.push(format!(
            "pixels of {finest:.3e} nm as read: finer than an atom's spacing (~0.1 nm), which no scan samples; check \
             the pixel size's unit (--pixel-size, the sidecar's or the file's)"
        ));
    }
    warnings
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
    if let (Some(sel), false) = (&opts.channel, fmt.reads_channel()) {
        return Err(SurfaceError::Format {
            path: name.into(),
            message: format!(
                "--channel {sel} would be ignored: a {} file holds one unnamed channel; leave out --channel",
                fmt.name()
            ),
        });
    }
    let mut hf = match fmt {
        Format::Gwy => gwy::read(bytes, side, opts),
        Format::Npy => npy::read(bytes, side, opts),
        Format::Npz => npz::read(bytes, side, opts),
        Format::Png | Format::Tiff => raster::read(bytes, fmt, side, opts),
        Format::Text => text::read(bytes, side, opts),
        Format::Gsf => gsf::read(bytes, side, opts),
        Format::Nanoscope => nanoscope::read(bytes, side, opts),
        Format::Ibw => ibw::read(bytes, side, opts),
        Format::Jpk => jpk::read(bytes, side, opts),
        Format::Wsxm => wsxm::read(bytes, side, opts),
        Format::Sxm => sxm::read(bytes, side, opts),
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
        Format::Gsf => Ok((gsf::write(hf), None)),
        Format::Tiff => Err(SurfaceError::invalid(
            "writing TIFF is not supported (a 16-bit PNG holds the same data); write .png, .gwy, .gsf, .npy or .txt",
        )),
        Format::Nanoscope | Format::Ibw | Format::Jpk | Format::Wsxm | Format::Sxm => Err(SurfaceError::invalid(
            format!("writing {} files is not supported; write .gwy, .gsf, .npy, .png or .txt", fmt.name()),
        )),
    }
}

/// The channels a file holds (one entry for single-image formats), recognised by content like
/// [`read_bytes`]; `name` is used in messages.
pub fn list_channels(bytes: &[u8], name: &str) -> Result<Vec<channel::ChannelInfo>, SurfaceError> {
    let fmt = detect_format(bytes)
        .ok_or_else(|| SurfaceError::Format { path: name.into(), message: describe_unknown(bytes) })?;
    let wrap = |e: SurfaceError| match e {
        SurfaceError::Invalid(m) => SurfaceError::Format { path: name.into(), message: m },
        other => other,
    };
    match fmt {
        Format::Gwy => gwy::channels(bytes),
        Format::Npz => npz::channels(bytes),
        Format::Gsf => gsf::channels(bytes),
        Format::Nanoscope => nanoscope::channels(bytes),
        Format::Ibw => ibw::channels(bytes),
        Format::Jpk => jpk::channels(bytes),
        Format::Wsxm => wsxm::channels(bytes),
        Format::Sxm => sxm::channels(bytes),
        Format::Npy | Format::Png | Format::Tiff | Format::Text => {
            // One image: read it with stand-in scales only to learn its size.
            let o = LoadOptions {
                pixel_size_nm: Some(1.0),
                max_height_nm: Some(1.0),
                ignore_sidecar: true,
                ..Default::default()
            };
            let hf = read_bytes(bytes, name, None, &o)?;
            Ok(vec![channel::ChannelInfo {
                index: 0,
                name: "heights".into(),
                rows: hf.rows,
                cols: hf.cols,
                z_unit: hf.meta.z_unit.clone(),
                direction: String::new(),
                alias: String::new(),
            }])
        }
    }
    .map_err(wrap)
}

/// The end of every instrument reader: the channel's values (in its stored unit) become nm, non-finite
/// samples (unscanned or saturated lines) are reported and filled with the mean, and the pixel size comes
/// from the file unless a sidecar or the options say otherwise.
/// Fills the samples of a row-major `rows × cols` field that are not finite (NaN lines of an aborted scan) with the
/// mean of the others, and says so as an instrument channel's are said ([`finish_channel`]); a field with no finite
/// sample is refused. `what` names it in messages.
/// What the not-finite samples `nan` (indices into `len` row-major samples) are and what was done with them.
fn non_finite_warning(nan: &[usize], len: usize, rows: usize, cols: usize) -> String {
    let mut r: Vec<usize> = nan.iter().map(|i| i / cols).collect();
    r.dedup();
    format!(
        "{} of {len} samples are not numbers (NaN/inf: an unfinished or saturated scan), in {} of {rows} rows (first \
         row {}, last row {}); they are filled with the mean height so levelling and spectra work around them — \
         crop them away (surface convert --crop) for clean results",
        nan.len(),
        r.len(),
        r[0],
        r[r.len() - 1]
    )
}

pub(crate) fn fill_non_finite(
    values: &mut [f64],
    rows: usize,
    cols: usize,
    what: &str,
    warnings: &mut Vec<String>,
) -> Result<(), SurfaceError> {
    let nan: Vec<usize> = (0..values.len()).filter(|&i| !values[i].is_finite()).collect();
    if nan.is_empty() {
        return Ok(());
    }
    if nan.len() == values.len() {
        return Err(SurfaceError::invalid(format!("{what} holds no finite value (an empty or aborted scan)")));
    }
    if 2 * nan.len() > values.len() {
        // Filled with the mean, most of the field would be flat: its roughness and periods those of the filling
        // (a scan of one measured row in 64 gave rms 8.8 nm for the row's 70.7 nm).
        // The block that holds numbers, by rows and columns (the unmeasured part may be either).
        let finite = |i: usize| values[i].is_finite();
        let rows_in: Vec<usize> = (0..rows).filter(|&r| (0..cols).any(|c| finite(r * cols + c))).collect();
        let cols_in: Vec<usize> = (0..cols).filter(|&c| (0..rows).any(|r| finite(r * cols + c))).collect();
        return Err(SurfaceError::invalid(format!(
            "{what}: {} of {} samples are not numbers (NaN/inf), more than half: filled, the field would describe the \
             filling, not the surface; crop to the measured part (surface convert --crop; rows {}–{} and columns \
             {}–{} hold numbers)",
            nan.len(),
            values.len(),
            rows_in[0],
            rows_in[rows_in.len() - 1],
            cols_in[0],
            cols_in[cols_in.len() - 1]
        )));
    }
    warnings.push(non_finite_warning(&nan, values.len(), rows, cols));
    let good: Vec<f64> = values.iter().copied().filter(|v| v.is_finite()).collect();
    let mean = good.iter().sum::<f64>() / good.len() as f64;
    for i in nan {
        values[i] = mean;
    }
    Ok(())
}

pub(crate) fn finish_channel(
    mut values: Vec<f64>,
    list: &[channel::ChannelInfo],
    ch: &channel::ChannelInfo,
    file_pixel: Option<(f64, f64)>,
    side: Option<&Sidecar>,
    opts: &LoadOptions,
    what: &str,
) -> Result<HeightField, SurfaceError> {
    let z = channel::z_scale(list, ch, opts, side, None)?;
    let (k, z_unit) = (z.nm_per_unit, z.unit);
    let mut warnings = z.warnings;
    let (rows, cols) = (ch.rows, ch.cols);
    let nan: Vec<usize> = (0..values.len()).filter(|&i| !values[i].is_finite()).collect();
    if nan.len() == values.len() {
        return Err(SurfaceError::invalid(format!(
            "channel {} '{}' holds no finite value (an empty or aborted scan)",
            ch.index, ch.name
        )));
    }
    let clipped = saturated_samples(&values, cols);
    let rows_of = |idx: &[usize]| {
        let mut r: Vec<usize> = idx.iter().map(|i| i / cols).collect();
        r.dedup();
        r
    };
    if !nan.is_empty() {
        warnings.push(non_finite_warning(&nan, values.len(), rows, cols));
    }
    if !clipped.is_empty() {
        let r = rows_of(&clipped);
        warnings.push(format!(
            "{} samples in {} of {rows} rows (first row {}, last row {}) sit at the scan's extreme height in runs \
             of {SATURATION_RUN} or more equal values: the z range saturated (the piezo hit its limit or the tip \
             lost the surface), so they are bounds, not heights; they are filled with the mean height like \
             missing samples so levelling and spectra work around them — crop them away (surface convert --crop) \
             for clean results",
            clipped.len(),
            r.len(),
            r[0],
            r[r.len() - 1]
        ));
    }
    let mut bad = nan;
    bad.extend(&clipped);
    if !bad.is_empty() {
        bad.sort_unstable();
        bad.dedup();
        let mut is_bad = vec![false; values.len()];
        for &i in &bad {
            is_bad[i] = true;
        }
        let good: Vec<f64> = values.iter().zip(&is_bad).filter(|(_, &b)| !b).map(|(&v, _)| v).collect();
        if good.is_empty() {
            return Err(SurfaceError::invalid(format!(
                "channel {} '{}' holds no height that is neither missing nor saturated",
                ch.index, ch.name
            )));
        }
        let mean = good.iter().sum::<f64>() / good.len() as f64;
        for &i in &bad {
            values[i] = mean;
        }
    }
    let ((dx, dy), pixel_warning) = pick_pixel(file_pixel, side, opts, what)?;
    warnings.extend(pixel_warning);
    let heights = values.iter().map(|v| v * k).collect();
    let hf = HeightField::new(rows, cols, dx, dy, heights)?;
    let mut meta = hf.meta.clone();
    meta.z_unit = z_unit;
    meta.warnings = warnings;
    let pos = list.iter().position(|c| c == ch).unwrap_or(0);
    let choice = channel::ChannelChoice::new(list, pos, opts.channel.as_ref());
    meta.notes.push(format!("{}: {cols} × {rows} samples", choice.describe()));
    meta.channel = Some(choice);
    Ok(hf.with_meta(meta))
}

/// How a single-image format stores its samples: little-endian numbers of one type, row after row.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum LeSample {
    F64,
    F32,
    I32,
    I16,
}

impl LeSample {
    /// Bytes per sample.
    fn size(self) -> usize {
        match self {
            LeSample::F64 => 8,
            LeSample::F32 | LeSample::I32 => 4,
            LeSample::I16 => 2,
        }
    }

    /// The type's C name, as WSxM's `Image Data Type` spells it: `double`, `float`, `integer`, `short`.
    pub(crate) fn name(self) -> &'static str {
        match self {
            LeSample::F64 => "double",
            LeSample::F32 => "float",
            LeSample::I32 => "integer",
            LeSample::I16 => "short",
        }
    }

    /// One sample from its [`size`](Self::size) bytes.
    fn value(self, c: &[u8]) -> f64 {
        match self {
            LeSample::F64 => f64::from_le_bytes(c.try_into().expect("8 bytes")),
            LeSample::F32 => f64::from(f32::from_le_bytes(c.try_into().expect("4 bytes"))),
            LeSample::I32 => f64::from(i32::from_le_bytes(c.try_into().expect("4 bytes"))),
            LeSample::I16 => f64::from(i16::from_le_bytes(c.try_into().expect("2 bytes"))),
        }
    }
}

/// The start of a single-image reader (GSF, WSxM): checks `--channel` against the file's one channel (so a
/// wrong index or name fails as it does for multi-channel files), then decodes the `rows · cols` samples at
/// byte `at`; `truncated` words the error, given the bytes needed, where the file ends before them. Returns
/// the channel list [`finish_channel`] takes and the samples in their stored unit.
pub(crate) fn single_channel(
    bytes: &[u8],
    info: &channel::ChannelInfo,
    at: usize,
    sample: LeSample,
    opts: &LoadOptions,
    truncated: impl FnOnce(usize) -> SurfaceError,
) -> Result<(Vec<channel::ChannelInfo>, Vec<f64>), SurfaceError> {
    let list = vec![info.clone()];
    channel::pick(&list, opts.channel.as_ref())?;
    let need = info.rows * info.cols * sample.size();
    let data = bytes.get(at..at + need).ok_or_else(|| truncated(need))?;
    Ok((list, data.chunks_exact(sample.size()).map(|c| sample.value(c)).collect()))
}

/// The `Key <sep> Value` lines of a text header (GSF, WSxM), both sides trimmed; the first line of a key wins.
pub(crate) struct KeyValues(Vec<(String, String)>);

impl KeyValues {
    /// The lines of `text` that hold `sep`; the others (blank lines, `[Section]` titles) are skipped.
    pub(crate) fn parse(text: &str, sep: char) -> Self {
        let pairs = text.lines().filter_map(|l| l.split_once(sep));
        Self(pairs.map(|(k, v)| (k.trim().to_string(), v.trim().to_string())).collect())
    }

    /// The value of `key`.
    pub(crate) fn get(&self, key: &str) -> Option<&str> {
        self.0.iter().find(|(k, _)| k == key).map(|(_, v)| v.as_str())
    }

    /// The value of `key` as a count (a size in samples); `None` where it is missing or not a whole number.
    pub(crate) fn count(&self, key: &str) -> Option<usize> {
        self.get(key)?.parse().ok()
    }
}

/// Shortest run of equal samples at the global extreme that counts as saturation. Measured heights carry noise,
/// so eight equal neighbours at the very top or bottom of the range are the range's limit, not the surface.
pub const SATURATION_RUN: usize = 8;

/// Indices of saturated samples: runs of at least [`SATURATION_RUN`] equal values at the global maximum or
/// minimum of the finite samples along a line, in lines where such runs cover at least a tenth of the line.
fn saturated_samples(values: &[f64], cols: usize) -> Vec<usize> {
    let (lo, hi) = values
        .iter()
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| (a.min(v), b.max(v)));
    if lo >= hi || !lo.is_finite() || cols < SATURATION_RUN {
        return Vec::new();
    }
    let mut out = Vec::new();
    for (r, line) in values.chunks(cols).enumerate() {
        let mut in_line = Vec::new();
        let mut j = 0;
        while j < line.len() {
            let v = line[j];
            let mut k = j + 1;
            while k < line.len() && line[k] == v {
                k += 1;
            }
            if (v == lo || v == hi) && k - j >= SATURATION_RUN {
                in_line.extend((j..k).map(|c| r * cols + c));
            }
            j = k;
        }
        if in_line.len() * 10 >= cols {
            out.extend(in_line);
        }
    }
    out
}

/// Where the sidecar of `path` is written: `FILE.EXT.json`.
pub fn sidecar_path(path: &Path) -> PathBuf {
    let mut s = path.as_os_str().to_owned();
    s.push(".json");
    PathBuf::from(s)
}

/// Pixel sizes: the file's where it states one, else the options' (`--pixel-size`), else the sidecar's. A
/// user's size that contradicts the file's (by more than 1e-6 relative) is ignored with a warning naming
/// both, or — with `override_units` — used, with a warning naming the file's.
// Public but hidden: not API, reachable only for the crate's tests in tests/ (Cargo.toml, `[lib] test = false`).
#[doc(hidden)]
pub fn pick_pixel(
    from_file: Option<(f64, f64)>,
    side: Option<&Sidecar>,
    opts: &LoadOptions,
    what: &str,
) -> Result<((f64, f64), Option<String>), SurfaceError> {
    let user = match opts.pixel_size_nm {
        Some(p) => Some(((p, p), format!("--pixel-size {}", crate::render::format_length(p)))),
        None => side.and_then(|s| s.pixel_nm()).map(|p| (p, format!("the sidecar's pixel_size_nm {}", p.0))),
    };
    let from_file = from_file.filter(|p| crate::check_pixel(p.0, p.1).is_ok());
    let (p, warning) = match (from_file, user) {
        (Some(f), Some((u, from))) if (u.0 / f.0 - 1.0).abs() > 1e-6 || (u.1 / f.1 - 1.0).abs() > 1e-6 => {
            let file = format!("{} × {} nm per pixel", pixel_text(f.0), pixel_text(f.1));
            if opts.override_units {
                (u, Some(format!("{from} replaces the file's own {file} (--override-units)")))
            } else {
                (f, Some(format!("{from} ignored: the file gives {file}; --override-units uses yours instead")))
            }
        }
        (Some(f), _) => (f, None),
        (None, Some((u, _))) => (u, None),
        (None, None) => {
            return Err(SurfaceError::invalid(format!(
                "{what} has no pixel size: give --pixel-size (e.g. 65nm) or a sidecar FILE.json with \
                 {{\"pixel_size_nm\": 65}}"
            )))
        }
    };
    crate::check_pixel(p.0, p.1)?;
    Ok((p, warning))
}

/// A pixel size in nm with four significant digits (0.4940, 65.00, 1563).
// Public but hidden: not API, reachable only for the crate's tests in tests/ (Cargo.toml, `[lib] test = false`).
#[doc(hidden)]
pub fn pixel_text(nm: f64) -> String {
    // Rounded to four significant digits first, so that 9.999999999 reads 10.00, not 10.000.
    let r: f64 = format!("{nm:.3e}").parse().unwrap_or(nm);
    let digits = (3 - r.abs().log10().floor() as i32).max(0) as usize;
    format!("{r:.digits$}")
}

/// The height unit the user gave (`--height-unit`, first) or the sidecar's: (nm per unit, unit).
pub(crate) fn given_height_unit(
    side: Option<&Sidecar>,
    opts: &LoadOptions,
) -> Result<Option<(f64, String)>, SurfaceError> {
    if let Some(u) = &opts.height_unit {
        let k = unit_to_nm(u).ok_or_else(|| {
            SurfaceError::invalid(format!("--height-unit '{u}' is not a length unit (m, um, µm, nm, pm, Å)"))
        })?;
        return Ok(Some((k, format!("{u} (--height-unit)"))));
    }
    Ok(side.and_then(|s| Some((s.height_scale()?, s.height_unit.clone()?))))
}

/// Warns when heights taken as nm are all below 1e-3 in magnitude: sub-picometre relief is implausible, an
/// array saved in metres is not.
pub(crate) fn warn_if_metres(values: &[f64], warnings: &mut Vec<String>) {
    let max = values.iter().filter(|v| v.is_finite()).fold(0.0f64, |m, v| m.max(v.abs()));
    if max > 0.0 && max < 1e-3 {
        warnings.push(format!(
            "the largest |height| is {max:.3e}, which as nm would be a relief below a picometre: the values look \
             like metres — if so, give --height-unit m"
        ));
    }
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
