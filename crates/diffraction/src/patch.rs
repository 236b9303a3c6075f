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
    pub fn warnings(&self) -> Vec<String> {
        model_warnings(self.dx, self.dy)
    }

    /// The shorter side of the patch (nm).
    pub fn shorter_side_nm(&self) -> f64 {
        (self.cols as f64 * self.dx).min(self.rows as f64 * self.dy)
    }

    /// The shortest coherence length the sampling carries ([`min_coherence_nm`]).
    pub fn min_coherence_nm(&self) -> f64 {
        min_coherence_nm(self.dx, self.dy)
    }

    /// Refuses a coherence length that is not positive or is shorter than the sampling carries
    /// ([`Self::min_coherence_nm`]).
    pub fn check_coherence(&self, coherence_nm: f64) -> Result<(), DiffractionError> {
        check_coherence(coherence_nm, self.dx, self.dy)
    }

    /// The coherence length to use: the light's, as given, or the paper's 65 µm ([`Coherence`]).
    pub fn coherence(&self, given_nm: Option<f64>) -> Coherence {
        Coherence {
            nm: given_nm.unwrap_or(crate::DEFAULT_COHERENCE_NM),
            given: given_nm.is_some(),
            extent_nm: self.extent(),
        }
    }

    /// The patch's extent along the in-plane direction at azimuth `phi` (rad): the length whose DFT step
    /// `1/L` is the frequency grid's step along that direction, `1/L = √((cos φ/Lx)² + (sin φ/Ly)²)`.
    pub fn extent_along(&self, phi: f64) -> f64 {
        let (lx, ly) = self.extent();
        1.0 / ((phi.cos() / lx).powi(2) + (phi.sin() / ly).powi(2)).sqrt()
    }
}

/// The coherence length `4σ_s` a model runs with: a property of the light (paper sec. 4.2: the paper's 65 µm
/// unless the user gives another), never fitted to the patch. A patch smaller than the window is taken as one
/// unit cell of a periodic surface (the DFT's periodic extension, [`crate::Aperture::Periodic`]): it diffracts
/// into discrete orders `1/L` apart in frequency, as a grating of that period does. (An earlier default shrank
/// the window to half the patch's shorter side; on a 65 × 3.2 µm strip of a 2500 nm grating that made the
/// window 1.6 µm, narrower than one period, and the test bench read 302.8 nm.)
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Coherence {
    pub nm: f64,
    /// Whether the user gave it.
    pub given: bool,
    /// The patch's extent `(Lx, Ly)` (nm).
    pub extent_nm: (f64, f64),
}

impl Coherence {
    /// Whether the window is wider than the patch along either axis, so that the patch is taken as a unit
    /// cell of a periodic surface.
    pub fn periodic(&self) -> bool {
        self.nm > self.extent_nm.0.min(self.extent_nm.1)
    }

    /// The line a person sees: the coherence and where it came from, and, where the patch is smaller than the
    /// window, what the model makes of it and what that means for the numbers.
    pub fn note(&self) -> String {
        self.note_as(self.origin())
    }

    /// "coherence 65 µm (the paper's default; …)": the first part of [`Coherence::note`], without what the patch
    /// becomes (for a unit cell, which is meant to repeat).
    pub fn stated(&self) -> String {
        self.stated_as(self.origin())
    }

    fn stated_as(&self, origin: &str) -> String {
        format!("coherence {} µm ({origin})", trim_um(self.nm))
    }

    fn origin(&self) -> &'static str {
        if self.given {
            "as given"
        } else {
            "the paper's default; --coherence to change"
        }
    }

    /// [`Coherence::note`] with another account of where the coherence came from (`origin`: the laser's
    /// diaphragm).
    pub fn note_as(&self, origin: &str) -> String {
        let mut s = self.stated_as(origin);
        if let Some(p) = self.periodic_note() {
            s += "; ";
            s += &p;
        }
        s
    }

    /// [`Coherence::note`] for the finite aperture (the ground truth, [`crate::Aperture::Finite`]), which cuts the
    /// window at the patch's edges instead of repeating the patch: a smaller patch is seen once.
    pub fn finite_aperture_note(&self) -> String {
        let mut s = self.stated();
        if self.periodic() {
            s += &format!(
                "; the {} × {} µm patch is smaller, and the finite aperture (ground-truth) sees it once, cut at its \
                 edges: its light spreads into lobes about λ/L wide (L its extent), not the discrete orders of a \
                 periodic surface (ground-truth-periodic takes it as one unit cell)",
                trim_um(self.extent_nm.0),
                trim_um(self.extent_nm.1)
            );
        }
        s
    }

    /// [`Coherence::note`] for a grating's unit cell (the rigorous method's), which is meant to repeat.
    pub fn unit_cell_note(&self) -> String {
        format!(
            "{}; the cell repeats as the periodic surface the rigorous method solves: its orders lie exactly at the \
             cell's harmonics, read through the window's lobes",
            self.stated()
        )
    }

    /// What a patch smaller than the window becomes, where it is.
    pub fn periodic_note(&self) -> Option<String> {
        self.periodic().then(|| {
            format!(
                "the {} × {} µm patch is smaller, so it is taken as one unit cell of a periodic surface: it \
                 diffracts into discrete orders, and periods read off it are uncertain by ± d²/(2L) along their \
                 direction (L its extent there)",
                trim_um(self.extent_nm.0),
                trim_um(self.extent_nm.1)
            )
        })
    }
}

/// The shortest coherence length `dx × dy` nm pixels carry: `4·max(dx, dy)`, a window `σ_s = coherence/4` of
/// one pixel. The model's sums run over the window sampled at the pixels, whose spectrum repeats every `1/dx`
/// in frequency; the repeats overlap by `~exp(−2π²σ_s²/dx²)`, below 3·10⁻⁹ from one pixel up but 0.7 % at half
/// a pixel and 29 % at a quarter. Measured on `builtin:elaphe` at 60 nm pixels (`iridis compare`, 16² map,
/// 1 RU): the reference within ΔE00 0.015 of the ground truth at 240 nm, 0.16 at 120 nm, 100 at 1 nm.
pub fn min_coherence_nm(dx: f64, dy: f64) -> f64 {
    4.0 * dx.max(dy)
}

/// The longest coherence length taken, 1 m: a policy bound, far beyond any scan and any lobe a map or detector
/// resolves (widths ~λ/coherence, 5e-7 rad); the window's area `4πσ_s²` itself overflows f64 only near 1e150 nm.
pub const MAX_COHERENCE_NM: f64 = 1e9;

/// [`Patch::check_coherence`] for `dx × dy` nm pixels, where no patch is at hand (the scan report checks the
/// coherence it was given against the scan's pixels before its first model step).
pub fn check_coherence(coherence_nm: f64, dx: f64, dy: f64) -> Result<(), DiffractionError> {
    if !(coherence_nm.is_finite() && coherence_nm > 0.0) {
        return Err(DiffractionError::Invalid(format!("coherence length {coherence_nm} nm must be positive")));
    }
    if coherence_nm > MAX_COHERENCE_NM {
        return Err(DiffractionError::Invalid(format!(
            "a coherence length of {} nm is more than the 1 m this model takes: a window that wide makes lobes \
             narrower than any map or detector resolves (λ/1 m), and far longer ones overflow its area; give 1000mm \
             or less",
            iridis_color::spectrum::short_number(coherence_nm)
        )));
    }
    let min = min_coherence_nm(dx, dy);
    if coherence_nm < min {
        let nm = |v: f64| format!("{v:.2}").trim_end_matches('0').trim_end_matches('.').to_string();
        return Err(DiffractionError::Invalid(format!(
            "a coherence length of {} nm is shorter than this scan's {} nm pixels carry: the window (σ_s = \
             coherence/4 = {} nm) must span at least one pixel, or its sampled spectrum aliases; give at least {} \
             nm (white light's coherence length is about a micrometre or more)",
            nm(coherence_nm),
            nm(dx.max(dy)),
            nm(coherence_nm / 4.0),
            nm(min)
        )));
    }
    Ok(())
}

/// A length in µm as a person would write it: at most 3 decimals, trailing zeros dropped.
fn trim_um(nm: f64) -> String {
    let s = format!("{:.3}", nm / 1000.0);
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// Warnings about a `rows × cols` grid of `dx × dy` nm pixels (PHYSICS.md): pixels too coarse for the visible
/// band at grazing geometry (one warning for both axes). Also stored in a lookup table's metadata. A patch
/// smaller than the coherence window is no warning but the model's unit cell, said in [`Coherence::note`].
pub fn model_warnings(dx: f64, dy: f64) -> Vec<String> {
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
    w
}
