//! The height field as the diffraction model sees it: heights in nm on a regular grid, stored with `y` growing
//! with the row index (so that DFT frequencies have the sign of `docs/PHYSICS.md`), mean height removed.

use crate::DiffractionError;

/// A height-field patch ready for the diffraction model.
#[derive(Debug, Clone)]
pub struct Patch {
    /// Samples along y (rows) and x (columns).
    pub rows: usize,
    pub cols: usize,
    /// Pixel sizes (nm).
    pub dx: f64,
    pub dy: f64,
    /// Heights (nm), mean removed, index `j * cols + i` at `x = i·dx`, `y = j·dy` (y up).
    pub heights: Vec<f64>,
    /// `max |h|` after mean removal (nm); drives the number of Taylor terms.
    pub max_abs_height: f64,
}

impl Patch {
    /// Builds a patch from heights stored as in the rest of iridis: row-major, row 0 at the top of the image
    /// (`y = (rows − 1 − row)·dy`). The mean height is subtracted: a constant phase leaves |A|² unchanged and a
    /// smaller `|h|max` needs fewer Taylor terms.
    pub fn from_row_major(
        rows: usize,
        cols: usize,
        dx: f64,
        dy: f64,
        heights: &[f64],
    ) -> Result<Self, DiffractionError> {
        if rows < 2 || cols < 2 {
            return Err(DiffractionError::Invalid(format!("a {rows}×{cols} height field is too small (need ≥ 2×2)")));
        }
        if heights.len() != rows * cols {
            return Err(DiffractionError::Invalid(format!("{} heights for a {rows}×{cols} grid", heights.len())));
        }
        if !(dx.is_finite() && dy.is_finite() && dx > 0.0 && dy > 0.0) {
            return Err(DiffractionError::Invalid(format!("pixel size {dx} × {dy} nm must be positive")));
        }
        if let Some(bad) = heights.iter().position(|h| !h.is_finite()) {
            return Err(DiffractionError::Invalid(format!("height {bad} is not finite")));
        }
        let mean = heights.iter().sum::<f64>() / heights.len() as f64;
        let mut flipped = Vec::with_capacity(heights.len());
        for j in 0..rows {
            let row = rows - 1 - j;
            flipped.extend(heights[row * cols..(row + 1) * cols].iter().map(|h| h - mean));
        }
        let max_abs_height = flipped.iter().fold(0.0f64, |m, h| m.max(h.abs()));
        Ok(Self { rows, cols, dx, dy, heights: flipped, max_abs_height })
    }

    /// Physical size (nm) along x and y.
    pub fn extent(&self) -> (f64, f64) {
        (self.cols as f64 * self.dx, self.rows as f64 * self.dy)
    }

    /// A fingerprint of the height field as the model sees it (grid, pixel sizes, every height's bits): FNV-1a,
    /// 64 bit (Fowler–Noll–Vo, the published offset basis and prime), written `fnv1a64:` and 16 hex digits.
    /// Recorded in lookup tables so that a table is never applied to another surface.
    pub fn fingerprint(&self) -> String {
        let mut h: u64 = 0xcbf2_9ce4_8422_2325;
        let mut eat = |bytes: [u8; 8]| {
            for b in bytes {
                h ^= b as u64;
                h = h.wrapping_mul(0x0000_0100_0000_01b3);
            }
        };
        eat((self.rows as u64).to_le_bytes());
        eat((self.cols as u64).to_le_bytes());
        eat(self.dx.to_bits().to_le_bytes());
        eat(self.dy.to_bits().to_le_bytes());
        for v in &self.heights {
            eat(v.to_bits().to_le_bytes());
        }
        format!("fnv1a64:{h:016x}")
    }

    /// Warnings a user should see before trusting results ([`model_warnings`]).
    pub fn warnings(&self, coherence_nm: f64) -> Vec<String> {
        model_warnings(self.rows, self.cols, self.dx, self.dy, coherence_nm)
    }

    /// The shorter side of the patch (nm).
    pub fn shorter_side_nm(&self) -> f64 {
        (self.cols as f64 * self.dx).min(self.rows as f64 * self.dy)
    }

    /// The coherence length to use: the one given, or [`Coherence::fitted`] to this patch.
    pub fn coherence(&self, given_nm: Option<f64>) -> Coherence {
        match given_nm {
            Some(nm) => Coherence { nm, fitted_to_side_nm: None },
            None => Coherence::fitted(self.shorter_side_nm()),
        }
    }
}

/// The coherence length `4σ_s` a model runs with, and whether it was fitted to the patch.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Coherence {
    pub nm: f64,
    /// The patch side it was fitted to, when the user gave none and the paper's 65 µm would not fit.
    pub fitted_to_side_nm: Option<f64>,
}

impl Coherence {
    /// The paper's 65 µm ([`crate::DEFAULT_COHERENCE_NM`]) when the patch is at least that large, otherwise half
    /// the patch's shorter side `L`. Why half: the Gaussian window `exp(−r²/2σ_s²)` with `4σ_s = L/2` falls to
    /// e⁻⁸ ≈ 3e-4 at the patch's edges (±4σ_s = ±L/2), so the window sees one copy of the patch, and its
    /// spectral width `σ_f = 1/(2π σ_s) ≈ 1.27/L` blends the DFT's spikes (`1/L` apart) into a smooth spectrum.
    /// With the paper's 65 µm on a 6.4 µm scan of a 1000 nm sine the spikes stay apart and the test bench reads
    /// 1066.7 nm (6400/6, a DFT grid value); at L/2 it reads 996 nm (measured; 4.8 µm: 999, 6.4 µm: 1007,
    /// 9.6 µm: 1053 — the error grows once the window is wider than the patch).
    pub fn fitted(shorter_side_nm: f64) -> Self {
        if shorter_side_nm >= crate::DEFAULT_COHERENCE_NM {
            Coherence { nm: crate::DEFAULT_COHERENCE_NM, fitted_to_side_nm: None }
        } else {
            Coherence { nm: 0.5 * shorter_side_nm, fitted_to_side_nm: Some(shorter_side_nm) }
        }
    }

    /// A line for the user when the coherence was fitted: what was chosen and why.
    pub fn note(&self) -> Option<String> {
        self.fitted_to_side_nm.map(|side| {
            format!(
                "coherence {} µm, fitted to the patch (half its {} µm shorter side): the paper's {} µm would exceed \
                 the patch and turn its spectrum into DFT spikes; give --coherence to choose another",
                trim_um(self.nm),
                trim_um(side),
                trim_um(crate::DEFAULT_COHERENCE_NM)
            )
        })
    }
}

/// A length in µm as a person would write it: at most 3 decimals, trailing zeros dropped.
fn trim_um(nm: f64) -> String {
    let s = format!("{:.3}", nm / 1000.0);
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// Warnings about a `rows × cols` grid of `dx × dy` nm pixels under a coherence length (PHYSICS.md), each at
/// most once: pixels too coarse for the visible band at grazing geometry (one warning for both axes), or a
/// patch smaller than the coherence area (treated as periodic). Also stored in a lookup table's metadata.
pub fn model_warnings(rows: usize, cols: usize, dx: f64, dy: f64, coherence_nm: f64) -> Vec<String> {
    let mut w = Vec::new();
    let d = dx.max(dy);
    if d > 95.0 {
        w.push(format!(
            "pixel size {d:.1} nm cannot represent the whole visible band at grazing geometry: frequencies above \
             1/(2·{d:.1} nm) need |u|/λ ≤ {:.5}/nm, i.e. |u| ≤ {:.2} at 380 nm (|u| reaches 2); resample to ≤ 95 nm",
            0.5 / d,
            380.0 * 0.5 / d
        ));
    }
    let (ex, ey) = (cols as f64 * dx, rows as f64 * dy);
    if ex.min(ey) < coherence_nm {
        w.push(format!(
            "patch {:.1} × {:.1} µm is smaller than the coherence length {:.1} µm: the DFT treats it as periodic, so \
             spectra become spikes {:.3}/µm apart (narrower than the window) and a period read off them is quantised \
             to about ± d²/L; tiling does not help (the spikes stay where they are): leave --coherence out (it is \
             then fitted to the patch) or give at most half the patch's side, or scan a larger area",
            ex / 1000.0,
            ey / 1000.0,
            coherence_nm / 1000.0,
            1000.0 / ex.min(ey)
        ));
    }
    w
}
