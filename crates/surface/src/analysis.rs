//! Dominant spatial periods from the power spectrum.
//!
//! The plane-levelled field is multiplied by a 2-D Hann window (so a period that does not fit the patch a
//! whole number of times does not leak over the whole spectrum), transformed with an FFT, and local maxima
//! of the power are picked on the half plane. Each maximum is then refined off the FFT grid by evaluating
//! the windowed Fourier transform directly at arbitrary frequencies and taking Newton steps on its log power
//! until they vanish, which for a sinusoid converges to the true frequency wherever it lies between bins
//! (tested to 1e-3 bin for lines 0.05–0.5 bin off the grid), not the bin centre.
//!
//! Each period carries its uncertainty ([`period_uncertainty_nm`]): half a DFT step, `d²/(2L)`, where it is
//! read off the grid, the refinement's resolution otherwise.
//!
//! Orientation is the direction of the grating vector (the direction in which the height varies), measured
//! counter-clockwise from `+x` with `y` up, in `[0°, 180°)`: a grating whose ridges run along `y` has
//! orientation 0°; nanofingers running along `x`, repeating in `y`, give 90°.

use iridis_fft::Complex;
use serde::Serialize;

pub use crate::fft::fft2;
use crate::HeightField;

/// One dominant period.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Peak {
    pub period_nm: f64,
    /// How well the period is known, ± nm: see [`period_uncertainty_nm`].
    pub period_uncertainty_nm: f64,
    /// Where the period was read: `"refined"` off the FFT grid, or `"grid"` (the refinement strayed from the
    /// grid maximum, which is kept).
    pub read_off: &'static str,
    /// Direction of the grating vector, degrees in `[0, 180)`.
    pub orientation_deg: f64,
    /// Share of the (windowed, levelled) height variance in this peak's neighbourhood, `0..1`.
    pub power: f64,
}

impl Peak {
    /// The period as a person reads it: rounded to its uncertainty, `1100.19 ± 0.03 nm`.
    pub fn period_text(&self) -> String {
        format!("{} nm", with_uncertainty(self.period_nm, self.period_uncertainty_nm))
    }
}

/// What the off-grid refinement resolves, in DFT bins: a sinusoid's frequency is found to 1e-3 bin wherever it
/// lies between bins (`refinement_finds_off_grid_periods`).
pub const REFINED_BIN_FRACTION: f64 = 1e-3;

/// The extent of a `size_x × size_y` patch along the direction `angle_deg` (counter-clockwise from +x) as
/// the DFT sees it: the frequency step along that direction is `1/L`, with `1/L² = cos²/Lx² + sin²/Ly²` —
/// `Lx` along x, `Ly` along y.
pub fn extent_along_nm(size_x_nm: f64, size_y_nm: f64, angle_deg: f64) -> f64 {
    let (s, c) = angle_deg.to_radians().sin_cos();
    1.0 / ((c / size_x_nm).powi(2) + (s / size_y_nm).powi(2)).sqrt()
}

/// The uncertainty (± nm) of a period `d` found in the spectrum of a patch `L` long along its grating vector
/// ([`extent_along_nm`]): read off the DFT grid (bins `1/L` apart) it is half a step, `δd = d²·δf =
/// d²/(2L)`; refined off the grid, the refinement's resolution, [`REFINED_BIN_FRACTION`] of a bin,
/// `d²·10⁻³/L`.
pub fn period_uncertainty_nm(period_nm: f64, extent_along_nm: f64, refined: bool) -> f64 {
    let bins = if refined { REFINED_BIN_FRACTION } else { 0.5 };
    period_nm * period_nm * bins / extent_along_nm
}

/// `value ± uncertainty` rounded to the uncertainty's first significant digit (two when it starts with a 1:
/// `0.014` stays `0.014`), the value to the same decimal place: `1100.19 ± 0.03`, `2500 ± 40`.
pub fn with_uncertainty(value: f64, uncertainty: f64) -> String {
    if !(uncertainty.is_finite() && uncertainty > 0.0 && value.is_finite()) {
        return format!("{value}");
    }
    let exp = uncertainty.log10().floor() as i32;
    let lead = uncertainty / 10f64.powi(exp);
    let place = if lead < 1.95 { exp - 1 } else { exp };
    let step = 10f64.powi(place);
    let (v, u) = ((value / step).round() * step, (uncertainty / step).round() * step);
    let decimals = (-place).max(0) as usize;
    format!("{v:.decimals$} ± {u:.decimals$}")
}

/// How many peaks to report and how weak they may be.
#[derive(Debug, Clone, PartialEq)]
pub struct PeakOptions {
    pub max_peaks: usize,
    /// Peaks weaker than this fraction of the strongest are dropped.
    pub min_relative_power: f64,
    /// Periods longer than this fraction of the patch's extent along their direction are ignored (levelling
    /// residue, not structure).
    pub max_period_fraction: f64,
    /// Peaks holding less than this share of the height variance are dropped: where all the structure lies in
    /// longer periods, what is left is rounding noise (a 2 µm sine on a 6 µm patch listed "151 nm" at a share
    /// of 1e-32). The weakest real peaks seen (instrument scans, random roughness) hold ~1e-3.
    pub min_share: f64,
}

impl Default for PeakOptions {
    fn default() -> Self {
        Self { max_peaks: 5, min_relative_power: 0.05, max_period_fraction: 0.25, min_share: 1e-6 }
    }
}

fn hann(n: usize) -> Vec<f64> {
    (0..n).map(|i| 0.5 - 0.5 * (std::f64::consts::TAU * (i as f64 + 0.5) / n as f64).cos()).collect()
}

/// Windowed, levelled field in `(x, y)` order ready for direct Fourier evaluation.
struct Windowed {
    rows: usize,
    cols: usize,
    dx: f64,
    dy: f64,
    w: Vec<f64>,
}

impl Windowed {
    /// `|Σ w(r,c) e^{−2πi (fx·x + fy·y)}|²` with `x = c·dx`, `y = (rows−1−r)·dy`.
    fn power(&self, fx: f64, fy: f64) -> f64 {
        let ex: Vec<Complex<f64>> = (0..self.cols)
            .map(|c| Complex::from_polar(1.0, -std::f64::consts::TAU * fx * c as f64 * self.dx))
            .collect();
        let mut total = Complex::new(0.0, 0.0);
        for r in 0..self.rows {
            let row = &self.w[r * self.cols..(r + 1) * self.cols];
            let s: Complex<f64> = row.iter().zip(&ex).map(|(&h, &e)| e * h).sum();
            let y = (self.rows - 1 - r) as f64 * self.dy;
            total += s * Complex::from_polar(1.0, -std::f64::consts::TAU * fy * y);
        }
        total.norm_sqr()
    }

    /// Refines a maximum by Newton steps on the log power, alternating axes: a parabola through the points
    /// at `f − d`, `f`, `f + d` (d = 0.1 bin) gives the step to its vertex, at most one bin at a time, repeated
    /// until the step is below 1e-6 bin. The finite-difference slope `ln P(f+d) − ln P(f−d)` vanishes where
    /// the (symmetric) main lobe peaks, so the iteration converges to the line's frequency wherever it lies
    /// between bins: a grid maximum can be up to half a bin from it (plus the Hann lobe's asymmetry), which
    /// a fixed set of shrinking steps could not always cover.
    /// Returns the frequency and whether it is the refined one (`false`: the grid estimate kept).
    fn refine(&self, mut fx: f64, mut fy: f64) -> (f64, f64, bool) {
        let (bx, by) = (1.0 / (self.cols as f64 * self.dx), 1.0 / (self.rows as f64 * self.dy));
        let (fx0, fy0) = (fx, fy);
        for _ in 0..12 {
            let mut moved = 0.0f64;
            for axis in 0..2 {
                let bin = if axis == 0 { bx } else { by };
                for _ in 0..20 {
                    let d = 0.1 * bin;
                    let at = |t: f64| {
                        let p = if axis == 0 { self.power(fx + t, fy) } else { self.power(fx, fy + t) };
                        p.max(1e-300).ln()
                    };
                    let (m, c, p) = (at(-d), at(0.0), at(d));
                    let denom = m - 2.0 * c + p;
                    // Not concave here: step uphill by one bin fraction instead of to a minimum.
                    let step =
                        if denom < 0.0 { (0.5 * (m - p) / denom * d).clamp(-bin, bin) } else { (p - m).signum() * d };
                    if axis == 0 {
                        fx += step
                    } else {
                        fy += step
                    }
                    moved = moved.max((step / bin).abs());
                    if (step / bin).abs() < 1e-6 {
                        break;
                    }
                }
            }
            if moved < 1e-6 {
                break;
            }
        }
        // A line more than 1.5 bins from its grid maximum is not this maximum's: keep the grid estimate.
        if ((fx - fx0) / bx).abs() > 1.5 || ((fy - fy0) / by).abs() > 1.5 {
            return (fx0, fy0, false);
        }
        (fx, fy, true)
    }
}

/// The plane-levelled, Hann-windowed field and its power spectrum (unshifted bins) with the total power.
fn windowed_power(hf: &HeightField) -> (Windowed, Vec<f64>, f64) {
    let (rows, cols) = (hf.rows, hf.cols);
    let levelled = crate::prep::level_plane(hf);
    let (wr, wc) = (hann(rows), hann(cols));
    let w: Vec<f64> = (0..rows * cols).map(|i| levelled.heights_nm[i] * wr[i / cols] * wc[i % cols]).collect();
    let mut spec: Vec<Complex<f64>> = w.iter().map(|&h| Complex::new(h, 0.0)).collect();
    fft2(&mut spec, rows, cols, false);
    let power: Vec<f64> = spec.iter().map(|z| z.norm_sqr()).collect();
    let total: f64 = power.iter().sum::<f64>().max(1e-300);
    (Windowed { rows, cols, dx: hf.dx_nm, dy: hf.dy_nm, w }, power, total)
}

/// Bin index `k` of `n` as a signed frequency index.
fn signed(k: usize, n: usize) -> i64 {
    if k <= n / 2 {
        k as i64
    } else {
        k as i64 - n as i64
    }
}

/// The share of the height variance (after plane levelling, DC excluded) in structure longer than
/// [`PeakOptions::max_period_fraction`] of the patch — fewer cycles across it than [`find_peaks`] counts as a
/// period: where it is most of the variance and no period is found, the patch is too small for its structure.
pub fn long_period_share(hf: &HeightField, opts: &PeakOptions) -> f64 {
    let (_, power, total) = windowed_power(hf);
    let min_cycles = 1.0 / opts.max_period_fraction;
    let long: f64 = power
        .iter()
        .enumerate()
        .filter(|&(i, _)| {
            let (kr, kc) = (signed(i / hf.cols, hf.rows), signed(i % hf.cols, hf.cols));
            (kr, kc) != (0, 0) && (kc as f64).hypot(kr as f64) < min_cycles
        })
        .map(|(_, p)| p)
        .sum();
    (long / (total - power[0]).max(1e-300)).min(1.0)
}

/// Dominant periods, strongest first.
pub fn find_peaks(hf: &HeightField, opts: &PeakOptions) -> Vec<Peak> {
    let (rows, cols) = (hf.rows, hf.cols);
    let (win, power, total) = windowed_power(hf);
    let (ex, ey) = hf.extent_nm();
    // Bin (kr, kc) ↔ fx = kc/(cols·dx), fy = −kr/(rows·dy) (rows run downwards, y upwards).
    // A period counts when the patch holds at least 1/max_period_fraction of it along its own direction: at
    // least that many cycles across the patch there, i.e. |(kc, kr)| in bins. (Against the shorter side, a
    // 2500 nm grating on a 65 × 3.2 µm strip was ignored and its 4th harmonic reported.)
    let min_cycles = 1.0 / opts.max_period_fraction;
    let at =
        |kr: i64, kc: i64| power[(kr.rem_euclid(rows as i64) as usize) * cols + kc.rem_euclid(cols as i64) as usize];
    let mut cands: Vec<(f64, i64, i64)> = Vec::new();
    for r in 0..rows {
        let kr = signed(r, rows);
        for c in 0..cols {
            let kc = signed(c, cols);
            // Half plane: fx > 0, or fx = 0 and fy > 0 (the other half mirrors it for a real field).
            let fy = -(kr as f64) / (rows as f64 * hf.dy_nm);
            if kc < 0 || (kc == 0 && fy <= 0.0) || (kc as f64).hypot(kr as f64) < min_cycles {
                continue;
            }
            let p = power[r * cols + c];
            let mut is_max = p > 0.0;
            'n: for dr in -1..=1 {
                for dc in -1..=1 {
                    if (dr, dc) != (0, 0) && at(kr + dr, kc + dc) > p {
                        is_max = false;
                        break 'n;
                    }
                }
            }
            if is_max {
                // Neighbourhood power: the Hann main lobe spreads a line over 3×3 bins.
                let mut s = 0.0;
                for dr in -1..=1 {
                    for dc in -1..=1 {
                        s += at(kr + dr, kc + dc);
                    }
                }
                cands.push((s, kr, kc));
            }
        }
    }
    cands.sort_by(|a, b| b.0.total_cmp(&a.0));
    let strongest = cands.first().map_or(0.0, |c| c.0);
    let mut peaks: Vec<Peak> = Vec::new();
    for &(s, kr, kc) in cands.iter().take(opts.max_peaks) {
        // Both half-plane copies count: the share of variance is twice the half-plane share.
        let share = (2.0 * s / total).min(1.0);
        if s < opts.min_relative_power * strongest || share < opts.min_share {
            break;
        }
        let fx0 = kc as f64 / (cols as f64 * hf.dx_nm);
        let fy0 = -(kr as f64) / (rows as f64 * hf.dy_nm);
        let (fx, fy, refined) = win.refine(fx0, fy0);
        let f = fx.hypot(fy);
        // Fold into [0°, 180°): a grating vector and its opposite are the same grating. Within 0.005° of 180°
        // (what prints as 180.00°) is 0°: a grating along x read 0.00° from one file and 180.00° from another.
        let mut ang = fy.atan2(fx).to_degrees().rem_euclid(180.0);
        if ang > 180.0 - 5e-3 {
            ang = 0.0;
        }
        ang += 0.0; // no −0
        let period = 1.0 / f;
        let along = extent_along_nm(ex, ey, ang);
        peaks.push(Peak {
            period_nm: period,
            period_uncertainty_nm: period_uncertainty_nm(period, along, refined),
            read_off: if refined { "refined" } else { "grid" },
            orientation_deg: ang,
            power: share,
        });
    }
    peaks
}
