//! The evaluators: one interface, several methods (ARCHITECTURE.md). Each answers the colour (XYZ) for a pair
//! of directions and, where the method resolves wavelengths, the relative reflectance `ρ_λ = C |A|²`.

use std::any::Any;
use std::sync::Arc;

use iridis_color::{SpectralWeights, Xyz};
use num_complex::Complex64;

use crate::geometry::{uvw, Shading, Vec3};
use crate::patch::Patch;
use crate::spectral::SpectralSetup;
use crate::taylor::TaylorTerms;
use crate::DiffractionError;

/// What lets a `&dyn Evaluator` be asked for the concrete method behind it (`as_lookup`, defined next to the
/// lookup table in [`crate::table`]; `as_ground_truth`) without the trait naming its implementations, so the
/// trait sits below every module that implements it. Every `'static` type has it.
pub trait AsAny: Any {
    fn as_any(&self) -> &dyn Any;
}

impl<T: Any> AsAny for T {
    fn as_any(&self) -> &dyn Any {
        self
    }
}

/// A diffraction BRDF model.
pub trait Evaluator: AsAny + Send + Sync {
    /// Short name (`ground-truth`, `reference`, `lookup`, …).
    fn name(&self) -> &'static str;
    /// Relative reflectance `ρ_λ(ω_i, ω_r)`; `None` for methods that integrate over λ in advance.
    fn reflectance(&self, wavelength_nm: f64, wi: Vec3, wr: Vec3) -> Option<f64>;
    /// CIE XYZ of the reflected light, `X = Σ_λ w_x(λ) ρ_λ` (paper eq. 9; a normal-incidence mirror has Y = 1).
    fn xyz(&self, wi: Vec3, wr: Vec3) -> Xyz;
    /// The shading factors `C` around `|A|²`, where the method has them: with [`Evaluator::radiometric_gain`]
    /// what turns the relative `ρ` into the BRDF `f_r` (sr⁻¹) per polarisation ([`crate::point`]).
    fn shading(&self) -> Option<&Shading> {
        None
    }
    /// The gain `A_eff/λ²` that turns the relative `ρ` (a flat mirror's peak is 1) into `f_r cos θ_i / R₀`:
    /// the coherence window's effective area `A_eff = (Σg)² dx dy / Σg²` over the wavelength squared — `4πσ_s²`
    /// for a Gaussian window inside the patch or on the periodic lattice (docs/PHYSICS.md, "Units of ρ"), less
    /// where the patch edge cuts the window. `None` for methods whose lobe has no such normalisation.
    fn radiometric_gain(&self, _wavelength_nm: f64) -> Option<f64> {
        None
    }
    /// The coherence length `4σ_s` (nm) of the evaluator's window, where it has one.
    fn coherence_nm(&self) -> Option<f64> {
        None
    }
    /// How the unpolarised BRDF divides between s (TE) and p (TM) incident light, `[f_s/f, f_p/f]` (mean 1),
    /// where the method knows it itself (a rigorous BRDF's orders). `None`: the shading's Fresnel factor at
    /// the half-vector angle says ([`crate::point`]).
    fn polarisation(&self, _wavelength_nm: f64, _wi: Vec3, _wr: Vec3) -> Option<[f64; 2]> {
        None
    }
}

impl dyn Evaluator {
    /// The direct sum behind this evaluator, if it is a ground truth: what a GPU needs to evaluate the same
    /// numbers (`iridis-gpu`).
    pub fn as_ground_truth(&self) -> Option<&GroundTruth> {
        AsAny::as_any(self).downcast_ref()
    }
}

/// The thesis' reference shader (FLSS, Algorithm 3): at each λ of a uniform grid, the windowed DFT of every
/// Taylor term at `f = (−u/λ, −v/λ)` (eq. 8), the Taylor sum (eq. 6), shading, trapezoid over λ (eq. 9).
#[derive(Debug, Clone)]
pub struct Reference {
    pub terms: Arc<TaylorTerms>,
    pub shading: Shading,
    pub spectral: SpectralSetup,
}

impl Reference {
    /// `A(λ)` for the given directions (eq. 6 with eq. 8), using `scratch` of length `N + 1`.
    pub fn amplitude(&self, wavelength_nm: f64, wi: Vec3, wr: Vec3, scratch: &mut [Complex64]) -> Complex64 {
        let [u, v, w] = uvw(wi, wr);
        let k = std::f64::consts::TAU / wavelength_nm;
        self.terms.windowed(-u / wavelength_nm, -v / wavelength_nm, scratch);
        // Σ_n (k w)^n / n! F_n by Horner's rule.
        let x = k * w;
        let n = self.terms.n_max;
        let mut acc = scratch[n];
        for m in (0..n).rev() {
            acc = acc * (x / (m + 1) as f64) + scratch[m];
        }
        acc
    }
}

impl Evaluator for Reference {
    fn name(&self) -> &'static str {
        "reference"
    }
    fn shading(&self) -> Option<&Shading> {
        Some(&self.shading)
    }
    fn radiometric_gain(&self, wavelength_nm: f64) -> Option<f64> {
        Some(crate::spectral::radiometric_gain(wavelength_nm, self.terms.coherence_nm))
    }
    fn coherence_nm(&self) -> Option<f64> {
        Some(self.terms.coherence_nm)
    }
    fn reflectance(&self, wavelength_nm: f64, wi: Vec3, wr: Vec3) -> Option<f64> {
        let mut scratch = vec![Complex64::new(0.0, 0.0); self.terms.n_max + 1];
        let a = self.amplitude(wavelength_nm, wi, wr, &mut scratch);
        Some(self.shading.factor(wavelength_nm, wi, wr) * a.norm_sqr())
    }
    fn xyz(&self, wi: Vec3, wr: Vec3) -> Xyz {
        if wi[2] <= 0.0 || wr[2] <= 0.0 {
            return Xyz::default();
        }
        let mut scratch = vec![Complex64::new(0.0, 0.0); self.terms.n_max + 1];
        let lambda_independent = !self.shading.fresnel.depends_on_wavelength();
        let c0 = self.shading.factor(500.0, wi, wr);
        let mut acc = [0.0; 3];
        for (&l, wt) in self.spectral.wavelengths().iter().zip(self.spectral.weights.weights()) {
            let a2 = self.amplitude(l, wi, wr, &mut scratch).norm_sqr();
            let rho = a2 * if lambda_independent { c0 } else { self.shading.factor(l, wi, wr) };
            for c in 0..3 {
                acc[c] += wt[c] * rho;
            }
        }
        Xyz::new(acc[0], acc[1], acc[2])
    }
}

/// Which continuation of the patch the ground truth's window sees.
///
/// * `Finite`: the window is cut at the patch edge (nothing outside the measured area): a finite aperture,
///   what a sample exactly the size of the scan would reflect.
/// * `Periodic`: the patch repeated without end (images at `x + m·Lx, y + n·Ly`, `L = samples · pixel`): the
///   surface the DFT sees, so the model that the reference and lookup methods approximate (their windowed
///   Fourier-series coefficients, eq. 8, are this sum up to the 4σ_f cut and the Taylor remainder).
///
/// While the window (`4σ_s`) stays well inside the patch the two agree; once it is as wide as the patch they
/// part (spikes `1/L` apart for `Periodic`, the edge's diffraction for `Finite`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Aperture {
    Finite,
    #[default]
    Periodic,
}

iridis_color::names! {
    Aperture {
        Finite => "finite" | "patch",
        Periodic => "periodic" | "periodic-extension",
    }
    else |s| -> DiffractionError {
        DiffractionError::Invalid(format!(
            "aperture '{s}': expected finite (the window cut at the patch edge) or periodic (the patch \
             repeated, as the DFT sees it)"
        ))
    }
}

/// The most images of the patch per axis the periodic ground truth sums (a window ~2700 patches wide).
pub const MAX_IMAGES_PER_AXIS: usize = 20_001;

/// Window weights below this fraction of the peak are left out of the ground truth's sums.
const WINDOW_CUT: f64 = 1e-12;

/// The yardstick (the paper's "benchmark implementation", sec. 6.3): the coherence-windowed Fourier transform
/// of `p = exp(i k w h)` summed directly over the height samples at exactly the frequency each `(λ, ω_i, ω_r)`
/// needs — no Taylor series, no DFT grid:
/// `A(λ) = Σ_j g_j exp(i (2π/λ) D_j) / Σ_j g_j`, `D_j = w h_j + u x_j + v y_j` (PHYSICS.md's sign), with the
/// Gaussian window `g` (`4σ_s` = coherence length) centred on the patch. The sum runs over the patch alone
/// ([`Aperture::Finite`]) or over the sample lattice of the periodically continued patch
/// ([`Aperture::Periodic`]).
///
/// Speed: `D_j` does not depend on λ, so on a grid uniform in wavenumber `1/λ` the phasors of successive
/// wavelengths follow by one complex multiplication: one `sin_cos` per sample and direction pair instead of one
/// per sample and wavelength. The spectral integral uses that grid (trapezoid rule, twice as many samples as
/// the reference's 5 nm grid by default).
///
/// The periodic sum is not expanded image by image: the Gaussian is separable, `g(x, y) = g_x(x) g_y(y)`, and
/// an image of sample `(i, t)` differs from it only by `x + m·Lx`, `y + n·Ly` (same height), so
/// `A(s) = Σ_t W_y[t](s) Σ_i W_x[i](s) e^{2πi s D_ti}` with `W_x[i](s) = Σ_m g_x(x_i + m Lx) e^{2πi s u m Lx}`
/// (and `W_y` likewise): the same lattice sum, term for term, at the cost of the patch's samples plus one short
/// sum over images per column and row — no lattice in memory.
#[derive(Debug, Clone)]
pub struct GroundTruth {
    samples: Samples,
    lattice: Arc<Lattice>,
    dx: f64,
    dy: f64,
    pub shading: Shading,
    /// Wavenumbers `1/λ` (1/nm), uniform, and their XYZ weights.
    wavenumbers: Vec<f64>,
    weights: SpectralWeights,
    /// The window's effective area `(Σg)² dx dy / Σg²` (nm²): `4πσ_s²` on the periodic lattice or for a window
    /// inside the patch, less where the patch edge cuts it ([`Evaluator::radiometric_gain`]).
    effective_area_nm2: f64,
    coherence_nm: f64,
}

#[derive(Debug, Clone)]
enum Samples {
    /// Sample positions relative to the patch centre and heights (nm), and window weights normalised to Σ g = 1.
    Finite { x: Vec<f64>, y: Vec<f64>, h: Vec<f64>, g: Vec<f64> },
    /// The sample positions of the columns and rows relative to the patch centre; heights and images are the
    /// [`Lattice`]'s.
    Periodic { xs: Vec<f64>, ys: Vec<f64> },
}

/// The ground truth's sum in separable form, as a device that evaluates it elsewhere (a GPU) needs it. The
/// window is separable, `g(x, y) = g_x(x) g_y(y)`, and every term of the sum is a patch sample `(i, t)` or one
/// of its images at lattice column `I = i + m·cols` and row `T = t + n·rows` (same height), so
///
/// `A(s) = Σ_t Σ_i e^{2πi s w h_ti} · [Σ_m gx_im e^{2πi s u I dx}] · [Σ_n gy_tn e^{2πi s v T dy}]`
///
/// up to a phase common to all terms (positions are counted from the lattice's origin, not the patch centre,
/// which leaves `|A|²` unchanged). The finite aperture has one image per column and row (`m = n = 0`) with the
/// window's weights; the periodic one the images of [`Aperture::Periodic`]. Weights are normalised so that the
/// whole window sums to 1.
#[derive(Debug, Clone, PartialEq)]
pub struct Lattice {
    pub rows: usize,
    pub cols: usize,
    /// Pixel sizes (nm).
    pub dx: f64,
    pub dy: f64,
    /// Heights (nm), row-major, row `t` at `y = t·dy` (the patch's order).
    pub heights: Vec<f64>,
    /// Per column `i`, its images that carry window weight: `(m, gx)`, lattice column `i + m·cols`.
    pub column_images: Vec<Vec<(i64, f64)>>,
    /// Per row `t`, its images: `(n, gy)`, lattice row `t + n·rows`.
    pub row_images: Vec<Vec<(i64, f64)>>,
}

impl Lattice {
    /// The lattice of `patch`'s heights with the images of its columns and rows.
    fn of(patch: &Patch, column_images: Vec<Vec<(i64, f64)>>, row_images: Vec<Vec<(i64, f64)>>) -> Self {
        Lattice {
            rows: patch.rows,
            cols: patch.cols,
            dx: patch.dx,
            dy: patch.dy,
            heights: patch.heights.clone(),
            column_images,
            row_images,
        }
    }
}

/// The images along one axis: for each sample position `pos[i]` (relative to the patch centre), the shifts
/// `m·period` and weights `exp(−(pos + m·period)²/(2σ²))` at or above [`WINDOW_CUT`], normalised by the sum over
/// every sample and image (those cut included).
fn axis_images(pos: &[f64], period: f64, sigma: f64) -> Result<Vec<Vec<(i64, f64)>>, DiffractionError> {
    // exp(−r²/2σ²) ≥ 1e-12 needs |r| ≤ σ √(2 ln 1e12) ≈ 7.43 σ; one period more covers every sample; ten more
    // σ make the normalisation's left-out tail < e^{-150}.
    let reach = sigma * (2.0 * (1.0 / WINDOW_CUT).ln()).sqrt();
    let m_max = ((reach + 10.0 * sigma + period) / period).ceil();
    if 2.0 * m_max + 1.0 > MAX_IMAGES_PER_AXIS as f64 {
        return Err(DiffractionError::Invalid(format!(
            "the coherence window (4σ_s = {:.1} µm) is {:.0} times the patch side ({:.2} µm): the periodic ground \
             truth would sum {:.0} images of the patch per axis (at most {MAX_IMAGES_PER_AXIS}); lower \
             --coherence, or use the finite aperture",
            4.0 * sigma / 1000.0,
            4.0 * sigma / period,
            period / 1000.0,
            2.0 * m_max + 1.0
        )));
    }
    let m_max = m_max as i64;
    let mut total = 0.0;
    let mut out = Vec::with_capacity(pos.len());
    for &p in pos {
        let mut kept = Vec::new();
        for m in -m_max..=m_max {
            let r = p + m as f64 * period;
            let g = (-(r * r) / (2.0 * sigma * sigma)).exp();
            total += g;
            if g >= WINDOW_CUT {
                kept.push((m, g));
            }
        }
        out.push(kept);
    }
    for (_, g) in out.iter_mut().flatten() {
        *g /= total;
    }
    Ok(out)
}

/// `W[i][k] = Σ_m g_m exp(2πi (s0 + k·ds) · a · m·period)` for each position's images `(m, g_m)`, row-major
/// `[i · count + k]`, with one extra row of zeros at the end (for padding lanes).
fn image_factors(images: &[Vec<(i64, f64)>], period: f64, a: f64, s0: f64, ds: f64, count: usize) -> Vec<Complex64> {
    let tau = std::f64::consts::TAU;
    let mut out = vec![Complex64::new(0.0, 0.0); (images.len() + 1) * count];
    for (i, list) in images.iter().enumerate() {
        let row = &mut out[i * count..(i + 1) * count];
        for &(m, g) in list {
            let shift = m as f64 * period;
            let (s, c) = (tau * s0 * a * shift).sin_cos();
            let (rs, rc) = (tau * ds * a * shift).sin_cos();
            let mut z = Complex64::new(c * g, s * g);
            let r = Complex64::new(rc, rs);
            for o in row.iter_mut() {
                *o += z;
                z *= r;
            }
        }
    }
    out
}

/// Four samples at a time: four independent phasor recurrences keep the multipliers busy.
const LANES: usize = 4;

#[allow(clippy::too_many_arguments)]
/// The finite aperture's sum `Σ_j g_j e^{2πi s D_j}` at `count` wavenumbers `s0 + k·ds`.
fn finite_sum(x: &[f64], y: &[f64], h: &[f64], g: &[f64], uvw: Vec3, s0: f64, ds: f64, count: usize) -> Vec<Complex64> {
    let [u, v, w] = uvw;
    let mut acc = vec![Complex64::new(0.0, 0.0); count];
    let tau = std::f64::consts::TAU;
    let n = h.len();
    let mut j = 0;
    while j < n {
        let lanes = LANES.min(n - j);
        let mut z = [Complex64::new(0.0, 0.0); LANES];
        let mut r = [Complex64::new(1.0, 0.0); LANES];
        for l in 0..lanes {
            let k = j + l;
            let d = w * h[k] + u * x[k] + v * y[k];
            let (s, c) = (tau * s0 * d).sin_cos();
            let (rs, rc) = (tau * ds * d).sin_cos();
            z[l] = Complex64::new(c * g[k], s * g[k]);
            r[l] = Complex64::new(rc, rs);
        }
        for a in acc.iter_mut() {
            *a += (z[0] + z[1]) + (z[2] + z[3]);
            for l in 0..LANES {
                z[l] *= r[l];
            }
        }
        j += LANES;
    }
    acc
}

/// The periodic lattice's sum `Σ_t W_y[t] Σ_i W_x[i] e^{2πi s D_ti}` (see [`GroundTruth`]), `wx` and `wy` from
/// [`image_factors`].
#[allow(clippy::too_many_arguments)]
fn periodic_sum(
    xs: &[f64],
    ys: &[f64],
    h: &[f64],
    wx: &[Complex64],
    wy: &[Complex64],
    uvw: Vec3,
    s0: f64,
    ds: f64,
    count: usize,
) -> Vec<Complex64> {
    let [u, v, w] = uvw;
    let tau = std::f64::consts::TAU;
    let cols = xs.len();
    let zero_row = cols; // the padding row of wx
                         // Columns and rows whose images all fall below the window cut contribute nothing.
    let live = |f: &[Complex64], i: usize| f[i * count..(i + 1) * count].iter().any(|z| z.re != 0.0 || z.im != 0.0);
    let active: Vec<usize> = (0..cols).filter(|&i| live(wx, i)).collect();
    let mut acc = vec![Complex64::new(0.0, 0.0); count];
    let mut row_acc = vec![Complex64::new(0.0, 0.0); count];
    for (t, &y) in ys.iter().enumerate() {
        if !live(wy, t) {
            continue;
        }
        row_acc.iter_mut().for_each(|a| *a = Complex64::new(0.0, 0.0));
        for chunk in active.chunks(LANES) {
            let mut z = [Complex64::new(0.0, 0.0); LANES];
            let mut r = [Complex64::new(1.0, 0.0); LANES];
            let mut idx = [zero_row; LANES];
            for (l, &i) in chunk.iter().enumerate() {
                let d = w * h[t * cols + i] + u * xs[i] + v * y;
                let (s, c) = (tau * s0 * d).sin_cos();
                let (rs, rc) = (tau * ds * d).sin_cos();
                z[l] = Complex64::new(c, s);
                r[l] = Complex64::new(rc, rs);
                idx[l] = i;
            }
            let rows_of = idx.map(|i| &wx[i * count..(i + 1) * count]);
            for (k, a) in row_acc.iter_mut().enumerate() {
                *a += (rows_of[0][k] * z[0] + rows_of[1][k] * z[1]) + (rows_of[2][k] * z[2] + rows_of[3][k] * z[3]);
                for l in 0..LANES {
                    z[l] *= r[l];
                }
            }
        }
        for (k, a) in acc.iter_mut().enumerate() {
            *a += wy[t * count + k] * row_acc[k];
        }
    }
    acc
}

impl GroundTruth {
    /// Prepares the direct evaluation over the patch alone (the finite aperture); `spectral_samples` points
    /// uniform in `1/λ` over the setup's range.
    pub fn new(
        patch: &Patch,
        coherence_nm: f64,
        shading: Shading,
        spectral: &SpectralSetup,
        spectral_samples: usize,
    ) -> Result<Self, DiffractionError> {
        Self::with_aperture(patch, coherence_nm, shading, spectral, spectral_samples, Aperture::Finite)
    }

    /// Prepares the direct evaluation over the chosen [`Aperture`].
    pub fn with_aperture(
        patch: &Patch,
        coherence_nm: f64,
        shading: Shading,
        spectral: &SpectralSetup,
        spectral_samples: usize,
        aperture: Aperture,
    ) -> Result<Self, DiffractionError> {
        patch.check_coherence(coherence_nm)?;
        if spectral_samples < 2 {
            return Err(DiffractionError::Invalid("the ground truth needs at least two wavelengths".into()));
        }
        let sigma_s = coherence_nm / 4.0;
        let (xc, yc) = ((patch.cols - 1) as f64 * patch.dx / 2.0, (patch.rows - 1) as f64 * patch.dy / 2.0);
        let mut effective_area_nm2 = 4.0 * std::f64::consts::PI * sigma_s * sigma_s;
        let (samples, lattice) = match aperture {
            Aperture::Finite => {
                let (mut x, mut y, mut g) = (Vec::new(), Vec::new(), Vec::new());
                for j in 0..patch.rows {
                    for i in 0..patch.cols {
                        let (px, py) = (i as f64 * patch.dx - xc, j as f64 * patch.dy - yc);
                        x.push(px);
                        y.push(py);
                        g.push((-(px * px + py * py) / (2.0 * sigma_s * sigma_s)).exp());
                    }
                }
                let gs: f64 = g.iter().sum();
                g.iter_mut().for_each(|v| *v /= gs);
                effective_area_nm2 = patch.dx * patch.dy / g.iter().map(|v| v * v).sum::<f64>();
                // Samples where the window has fallen below 1e-12 of its peak (beyond 7.4 σ_s) are left out of
                // the sum: together they change A by less than 1e-12 × (their count × peak weight), far below
                // the f64 rounding of a million-term sum, and with a window smaller than the patch they are
                // most of the work (a quarter-patch coherence length keeps 67 % of the samples). The
                // normalisation above still counts them.
                let cut = WINDOW_CUT * g.iter().fold(0.0f64, |m, &v| m.max(v));
                let keep: Vec<usize> = (0..g.len()).filter(|&k| g[k] >= cut).collect();
                let pick = |v: &[f64]| keep.iter().map(|&k| v[k]).collect::<Vec<f64>>();
                let samples = Samples::Finite { x: pick(&x), y: pick(&y), h: pick(&patch.heights), g: pick(&g) };
                // The same window, separable: g = g_x g_y, normalised by S_x S_y = Σ g. Per axis the 1e-12 cut
                // keeps the square around the disk kept above; the corners it adds each weigh < 1e-12 of the peak.
                let axis = |n: usize, d: f64, c: f64| -> Vec<Vec<(i64, f64)>> {
                    let g: Vec<f64> =
                        (0..n).map(|i| (-(i as f64 * d - c).powi(2) / (2.0 * sigma_s * sigma_s)).exp()).collect();
                    let (sum, peak) = (g.iter().sum::<f64>(), g.iter().fold(0.0f64, |m, &v| m.max(v)));
                    g.iter().map(|&v| if v >= WINDOW_CUT * peak { vec![(0, v / sum)] } else { Vec::new() }).collect()
                };
                let lattice = Lattice::of(patch, axis(patch.cols, patch.dx, xc), axis(patch.rows, patch.dy, yc));
                (samples, lattice)
            }
            Aperture::Periodic => {
                let xs: Vec<f64> = (0..patch.cols).map(|i| i as f64 * patch.dx - xc).collect();
                let ys: Vec<f64> = (0..patch.rows).map(|j| j as f64 * patch.dy - yc).collect();
                let (lx, ly) = patch.extent();
                // The same 1e-12 cut, per axis (g = g_x g_y, peak 1): the lattice kept is the square around the
                // finite aperture's disk.
                let lattice = Lattice::of(patch, axis_images(&xs, lx, sigma_s)?, axis_images(&ys, ly, sigma_s)?);
                (Samples::Periodic { xs, ys }, lattice)
            }
        };
        let lam = spectral.wavelengths();
        let (s_lo, s_hi) = (1.0 / lam[lam.len() - 1], 1.0 / lam[0]);
        let wavenumbers: Vec<f64> =
            (0..spectral_samples).map(|k| s_lo + (s_hi - s_lo) * k as f64 / (spectral_samples - 1) as f64).collect();
        let mut grid: Vec<f64> = wavenumbers.iter().map(|s| 1.0 / s).collect();
        grid.reverse(); // increasing λ
        let mut weights = SpectralWeights::new(&grid, spectral.illuminant, spectral.observer);
        if spectral.units == crate::Units::Radiometric {
            spectral.check_coherence(coherence_nm)?;
            // The lobe's solid angle is the window's effective area over λ²: 4πσ_s² unless the patch edge
            // cuts the window (the finite aperture), where 4πσ_s² overstated the energy by 1.19× (window = patch)
            // to 8.3× (the paper's 65 µm window on a 20 µm patch).
            weights = weights.scaled(|l| effective_area_nm2 / (l * l));
        }
        Ok(Self {
            samples,
            lattice: Arc::new(lattice),
            dx: patch.dx,
            dy: patch.dy,
            shading,
            wavenumbers,
            weights,
            effective_area_nm2,
            coherence_nm,
        })
    }

    /// The aperture this ground truth sums over.
    pub fn aperture(&self) -> Aperture {
        match self.samples {
            Samples::Finite { .. } => Aperture::Finite,
            Samples::Periodic { .. } => Aperture::Periodic,
        }
    }

    fn nyquist_ok(&self, u: f64, v: f64, wavelength_nm: f64) -> bool {
        (u / wavelength_nm).abs() <= 0.5 / self.dx && (v / wavelength_nm).abs() <= 0.5 / self.dy
    }

    /// `A` at each of the given wavenumbers (1/nm), equally spaced, by the phasor recurrence.
    fn amplitudes(&self, wi: Vec3, wr: Vec3, s0: f64, ds: f64, count: usize) -> Vec<Complex64> {
        let uvw = uvw(wi, wr);
        let mut acc = match &self.samples {
            Samples::Finite { x, y, h, g } => finite_sum(x, y, h, g, uvw, s0, ds, count),
            Samples::Periodic { xs, ys } => {
                let l = &self.lattice;
                let (lx, ly) = (l.cols as f64 * l.dx, l.rows as f64 * l.dy);
                let wx = image_factors(&l.column_images, lx, uvw[0], s0, ds, count);
                let wy = image_factors(&l.row_images, ly, uvw[1], s0, ds, count);
                periodic_sum(xs, ys, &l.heights, &wx, &wy, uvw, s0, ds, count)
            }
        };
        for (k, a) in acc.iter_mut().enumerate() {
            let lambda = 1.0 / (s0 + ds * k as f64);
            if !self.nyquist_ok(uvw[0], uvw[1], lambda) {
                *a = Complex64::new(0.0, 0.0);
            }
        }
        acc
    }

    /// The same yardstick lit by an arbitrary light spectrum `light(λ)` (a laser, a measured lamp) instead of
    /// the setup's illuminant: the colour weights are rebuilt on the same wavelength grid with
    /// [`SpectralWeights::with_light`] (a mirror at normal incidence keeps `Y = 1`).
    pub fn with_light(mut self, light: impl Fn(f64) -> f64, observer: iridis_color::Observer) -> Self {
        let grid = self.weights.wavelengths_nm().to_vec();
        self.weights = SpectralWeights::with_light(&grid, light, observer);
        self
    }

    /// The sum in separable form, for devices that evaluate it elsewhere.
    pub fn lattice(&self) -> &Lattice {
        &self.lattice
    }

    /// The wavenumbers `1/λ` (1/nm) of the spectral integral, uniform and increasing.
    pub fn wavenumbers(&self) -> &[f64] {
        &self.wavenumbers
    }

    /// The colour (eq. 9) from `|A|²` at each of [`GroundTruth::wavenumbers`]: `X = Σ_λ w_x(λ) C(λ) |A(λ)|²`,
    /// leaving out the wavenumbers beyond Nyquist — what [`Evaluator::xyz`] does after its sums, for powers
    /// computed elsewhere (a GPU). Black below the horizon.
    pub fn xyz_from_power(&self, wi: Vec3, wr: Vec3, power: &[f64]) -> Xyz {
        let n = self.wavenumbers.len();
        if wi[2] <= 0.0 || wr[2] <= 0.0 || power.len() != n {
            return Xyz::default();
        }
        let [u, v, _] = uvw(wi, wr);
        let lambda_independent = !self.shading.fresnel.depends_on_wavelength();
        let c0 = self.shading.factor(500.0, wi, wr);
        let mut acc = [0.0; 3];
        // The weights are in increasing λ, the powers in increasing wavenumber.
        for (k, wt) in self.weights.weights().iter().enumerate() {
            let l = self.weights.wavelengths_nm()[k];
            // The wavenumber as `amplitudes` forms it, so both leave out the same ones.
            let ds = self.wavenumbers[1] - self.wavenumbers[0];
            if !self.nyquist_ok(u, v, 1.0 / (self.wavenumbers[0] + ds * (n - 1 - k) as f64)) {
                continue;
            }
            let rho = power[n - 1 - k] * if lambda_independent { c0 } else { self.shading.factor(l, wi, wr) };
            for c in 0..3 {
                acc[c] += wt[c] * rho;
            }
        }
        Xyz::new(acc[0], acc[1], acc[2])
    }

    /// `A(λ)` at one wavelength.
    pub fn amplitude(&self, wavelength_nm: f64, wi: Vec3, wr: Vec3) -> Complex64 {
        self.amplitudes(wi, wr, 1.0 / wavelength_nm, 0.0, 1)[0]
    }
}

impl Evaluator for GroundTruth {
    fn name(&self) -> &'static str {
        match self.aperture() {
            Aperture::Finite => "ground-truth",
            Aperture::Periodic => "ground-truth-periodic",
        }
    }
    fn reflectance(&self, wavelength_nm: f64, wi: Vec3, wr: Vec3) -> Option<f64> {
        Some(self.shading.factor(wavelength_nm, wi, wr) * self.amplitude(wavelength_nm, wi, wr).norm_sqr())
    }
    fn xyz(&self, wi: Vec3, wr: Vec3) -> Xyz {
        if wi[2] <= 0.0 || wr[2] <= 0.0 {
            return Xyz::default();
        }
        let n = self.wavenumbers.len();
        let ds = self.wavenumbers[1] - self.wavenumbers[0];
        let power: Vec<f64> =
            self.amplitudes(wi, wr, self.wavenumbers[0], ds, n).iter().map(|a| a.norm_sqr()).collect();
        self.xyz_from_power(wi, wr, &power)
    }
    fn shading(&self) -> Option<&Shading> {
        Some(&self.shading)
    }
    fn radiometric_gain(&self, wavelength_nm: f64) -> Option<f64> {
        Some(self.effective_area_nm2 / (wavelength_nm * wavelength_nm))
    }
    fn coherence_nm(&self) -> Option<f64> {
        Some(self.coherence_nm)
    }
}
