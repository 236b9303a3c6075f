//! # iridis-surface
//!
//! Height fields: the measured (or generated) nanostructures that the diffraction model starts from.
//! Everything is in nanometres; the frame is `docs/PHYSICS.md`'s: row-major `h[row][col]`, `x = col·dx` to
//! the right, `y = (rows − 1 − row)·dy` upwards, so row 0 is the top of the displayed image.
//!
//! ```text
//! file (.gwy .npy .png .tif .txt) or builtin:NAME ──load_surface──► HeightField ──prep──► analysis (periods)
//!                                                                        └──formats::write──► .gwy .npy .png .txt
//! ```

pub mod analysis;
pub mod builtin;
/// The 2-D FFT every spectral computation of a height field goes through (iridis-fft).
pub use iridis_fft as fft;
pub mod formats;
pub mod fuzz;
pub mod generate;
pub mod prep;
pub mod render;
pub mod rng;
pub mod stats;

use serde::Serialize;

pub use analysis::{find_peaks, Peak, PeakOptions};
pub use builtin::{builtin_surface, BUILTIN_NAMES};
pub use formats::{detect_format, load_surface, Format, LoadOptions};

/// Largest |height| accepted, 1 m in nm: far beyond any relief a scan measures (AFM z ranges are micrometres), so
/// a larger one is a wrong height unit; and small enough that the statistics' sums of squares stay finite.
pub const MAX_HEIGHT_NM: f64 = 1e9;

/// Largest number of samples accepted (2²⁶ ≈ 67 M, 512 MiB of `f64`): checked before allocating, so a
/// corrupt header cannot make us reserve gigabytes.
pub const MAX_SAMPLES: usize = 1 << 26;
/// Largest extent of one axis in samples.
pub const MAX_DIM: usize = 1 << 16;
/// Coherence length `4σ_s` assumed when warning about small patches (nm), as in the paper: 65 µm.
pub const DEFAULT_COHERENCE_NM: f64 = 65_000.0;
/// Coarsest pixel that still represents the visible band at grazing geometry (PHYSICS.md): frequencies up to
/// `|u|/λ ≤ 2/380 nm` need `dx ≤ 95 nm`.
pub const MAX_RESOLVING_PIXEL_NM: f64 = 95.0;
/// A patch narrower than this (two wavelengths of 550 nm) taken as one unit cell has too few orders (`λ/L ≥ 0.5`)
/// to show diffraction colours, and where no period is found in it, too little of the surface to say whether
/// the surface repeats: `iridis report` then gives no verdict on its diffraction.
pub const TWO_WAVELENGTHS_NM: f64 = 2.0 * 550.0;

/// What went wrong, in words a person can act on.
#[derive(Debug, thiserror::Error)]
pub enum SurfaceError {
    /// Invalid parameters or data (sizes, pixel sizes, non-finite heights).
    #[error("{0}")]
    Invalid(String),
    /// A file that cannot be parsed as the format it claims to be.
    #[error("{path}: {message}")]
    Format { path: String, message: String },
    #[error("{path}: {err}")]
    Io { path: String, err: std::io::Error },
}

impl SurfaceError {
    pub(crate) fn invalid(msg: impl Into<String>) -> Self {
        Self::Invalid(msg.into())
    }
}

/// Where a height field came from and what happened to it; carried into tables and reports.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct Metadata {
    /// File path or `builtin:NAME…` spec.
    pub source: String,
    /// Format it was read from (`gwy`, `npy`, `png`, `tiff`, `text`, `builtin`).
    pub format: String,
    /// Unit the heights were stored in before conversion to nm (e.g. `m` for Gwyddion, `relative` for images).
    pub z_unit: String,
    /// Free-form notes: channel titles, generator parameters, preparation steps.
    pub notes: Vec<String>,
    /// Things the user should know (colour image reduced to luminance, assumed units, …).
    pub warnings: Vec<String>,
    /// Which channel of a multi-channel file was read, and why (`None` for single-image formats).
    pub channel: Option<formats::channel::ChannelChoice>,
}

/// Heights in nm on a regular grid, row-major, row 0 at the top (`docs/PHYSICS.md`).
#[derive(Debug, Clone, PartialEq)]
pub struct HeightField {
    pub rows: usize,
    pub cols: usize,
    /// Pixel size along x (columns), nm.
    pub dx_nm: f64,
    /// Pixel size along y (rows), nm.
    pub dy_nm: f64,
    /// Row-major heights in nm, `len == rows * cols`.
    pub heights_nm: Vec<f64>,
    pub meta: Metadata,
}

/// Refuses sizes that are degenerate or too large, before anything is allocated.
pub fn check_dims(rows: usize, cols: usize) -> Result<(), SurfaceError> {
    if rows < 2 || cols < 2 {
        return Err(SurfaceError::invalid(format!(
            "a height field needs at least 2×2 samples; got {rows} × {cols} (rows × columns; a single row or \
             column has no 2-D spectrum)"
        )));
    }
    if rows > MAX_DIM || cols > MAX_DIM || rows.saturating_mul(cols) > MAX_SAMPLES {
        return Err(SurfaceError::invalid(format!(
            "{rows} × {cols} samples is too large (at most {MAX_DIM} per axis and {MAX_SAMPLES} in all)"
        )));
    }
    Ok(())
}

/// Refuses pixel sizes that are not finite and positive.
pub fn check_pixel(dx_nm: f64, dy_nm: f64) -> Result<(), SurfaceError> {
    for (name, v) in [("dx", dx_nm), ("dy", dy_nm)] {
        if !(v.is_finite() && v > 0.0) {
            return Err(SurfaceError::invalid(format!(
                "pixel size {name} = {v} nm: it must be a finite positive length"
            )));
        }
    }
    Ok(())
}

impl HeightField {
    /// A validated height field: at least 2×2, within [`MAX_SAMPLES`], finite positive pixel sizes, finite
    /// heights within [`MAX_HEIGHT_NM`], `heights_nm.len() == rows * cols`.
    pub fn new(rows: usize, cols: usize, dx_nm: f64, dy_nm: f64, heights_nm: Vec<f64>) -> Result<Self, SurfaceError> {
        check_dims(rows, cols)?;
        check_pixel(dx_nm, dy_nm)?;
        if heights_nm.len() != rows * cols {
            return Err(SurfaceError::invalid(format!(
                "{} heights given for {rows} × {cols} = {} samples",
                heights_nm.len(),
                rows * cols
            )));
        }
        if let Some(i) = heights_nm.iter().position(|h| !h.is_finite()) {
            return Err(SurfaceError::invalid(format!(
                "height at row {}, column {} is {}: heights must be finite numbers",
                i / cols,
                i % cols,
                heights_nm[i]
            )));
        }
        if let Some(i) = heights_nm.iter().position(|h| h.abs() > MAX_HEIGHT_NM) {
            return Err(SurfaceError::invalid(format!(
                "height at row {}, column {} is {:e} nm, more than the 1 m any scan measures (and its square \
                 overflows the statistics): check the height unit (--height-unit, or the file's)",
                i / cols,
                i % cols,
                heights_nm[i]
            )));
        }
        Ok(Self { rows, cols, dx_nm, dy_nm, heights_nm, meta: Metadata::default() })
    }

    /// Same, with metadata.
    pub fn with_meta(mut self, meta: Metadata) -> Self {
        self.meta = meta;
        self
    }

    /// Height at `(row, col)` in nm. Panics when out of range, like slice indexing.
    #[inline]
    pub fn get(&self, row: usize, col: usize) -> f64 {
        assert!(row < self.rows && col < self.cols, "({row}, {col}) outside {}×{}", self.rows, self.cols);
        self.heights_nm[row * self.cols + col]
    }

    /// Physical size `(width along x, height along y)` in nm: `cols·dx`, `rows·dy` (the periodic patch the DFT
    /// sees, one pixel per sample).
    pub fn extent_nm(&self) -> (f64, f64) {
        (self.cols as f64 * self.dx_nm, self.rows as f64 * self.dy_nm)
    }

    /// Mean height (nm).
    pub fn mean(&self) -> f64 {
        self.heights_nm.iter().sum::<f64>() / self.heights_nm.len() as f64
    }

    /// Root-mean-square deviation from the mean height (Sq in ISO 25178), nm.
    pub fn rms(&self) -> f64 {
        let m = self.mean();
        (self.heights_nm.iter().map(|h| (h - m) * (h - m)).sum::<f64>() / self.heights_nm.len() as f64).sqrt()
    }

    /// Lowest and highest height (nm).
    pub fn min_max(&self) -> (f64, f64) {
        self.heights_nm.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &h| (lo.min(h), hi.max(h)))
    }

    /// Row `r` as a slice.
    pub fn row(&self, r: usize) -> &[f64] {
        &self.heights_nm[r * self.cols..(r + 1) * self.cols]
    }

    /// Warnings (with numbers) about what this field can represent for the diffraction model: pixels too
    /// coarse for the visible band (PHYSICS.md). A patch smaller than the coherence area is not a warning
    /// here (the diffraction commands take it as a unit cell): [`HeightField::coherence_note`] says what that means.
    pub fn physics_warnings(&self, _coherence_nm: f64) -> Vec<String> {
        let mut w = Vec::new();
        let p = self.dx_nm.max(self.dy_nm);
        if p > MAX_RESOLVING_PIXEL_NM {
            w.push(format!(
                "pixel size {p:.1} nm is coarser than {MAX_RESOLVING_PIXEL_NM} nm: spatial frequencies above \
                 1/(2·{p:.1} nm) = {:.3} µm⁻¹ are lost, so diffraction at short wavelengths and grazing angles \
                 (|u|/λ up to 2/380 nm = 5.26 µm⁻¹) is missing; resample a finer scan or expect dark blue/violet",
                1000.0 / (2.0 * p)
            ));
        }
        w
    }

    /// For a patch smaller than the light's coherence area, what it means in practice, in two sentences: the
    /// diffraction commands take the patch as one unit cell of a periodic surface (docs/PHYSICS.md), whose own
    /// period `L` puts orders every `λ/L` of viewing angle, so colours are sampled that finely. `None` for a
    /// patch at least as large as the coherence area.
    pub fn coherence_note(&self, coherence_nm: f64) -> Option<String> {
        let (ex, ey) = self.extent_nm();
        let l = ex.min(ey);
        (l < coherence_nm).then(|| {
            let lambda_over_l = 550.0 / l;
            let cost = if l > TWO_WAVELENGTHS_NM {
                format!(
                    "whose own period L sends light only into orders λ/L = {:.1}° of viewing angle apart at \
                     550 nm",
                    lambda_over_l.asin().to_degrees(),
                )
            } else {
                "and a patch under two wavelengths across (λ/L ≥ 0.5 at 550 nm) has too few orders to show \
                 diffraction colours"
                    .to_string()
            };
            // A side under a micrometre in nm (a 20 nm side read "0.0 µm").
            let size = if l < 1000.0 {
                format!("{} × {} nm", significant(ex), significant(ey))
            } else {
                format!("{:.1} × {:.1} µm", ex / 1000.0, ey / 1000.0)
            };
            format!(
                "patch {size} is smaller than the light's {:.1} µm coherence area: the diffraction commands take it \
                 as one unit cell of a periodic surface, {cost}. Scan a larger area if the structure is not \
                 periodic; periods read from this patch carry the ± given with them",
                coherence_nm / 1000.0,
            )
        })
    }
}

/// A length in nm to three significant digits, no exponent (`20`, `0.03`, `2000`).
fn significant(nm: f64) -> String {
    let digits = (2 - nm.abs().max(f64::MIN_POSITIVE).log10().floor() as i32).clamp(0, 12) as usize;
    format!("{nm:.digits$}")
}
