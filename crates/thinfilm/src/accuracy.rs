//! Colour differences as a person sees them: CIEDE2000 between two XYZ colours after the same exposure,
//! clipped to the sRGB cube as a display shows them (the measure of the GPU tests and of the film-path
//! studies in docs/gpu.md), and the statistics reported for a set of pixels.

use iridis_color::integrate::white_point;
use iridis_color::lab::delta_e_2000;
use iridis_color::{Illuminant, Lab, Observer, Xyz};
use serde::Serialize;

/// The displayed colour of `xyz` scaled by `exposure`, clipped to the sRGB cube, in CIELAB (D65).
pub fn displayed_lab(xyz: Xyz, exposure: f64) -> Lab {
    // The white point integrates the CMFs on their 1 nm grid: once, not per colour.
    static WHITE: std::sync::OnceLock<Xyz> = std::sync::OnceLock::new();
    let white = *WHITE.get_or_init(|| white_point(Illuminant::D65, Observer::Cie1931));
    let rgb = xyz.scale(exposure).to_linear_srgb().map(|c| if c.is_nan() { 0.0 } else { c.clamp(0.0, 1.0) });
    Lab::from_xyz(Xyz::from_linear_srgb(rgb), white)
}

/// CIEDE2000 between the displayed colours of `a` and `b` at one exposure.
pub fn delta_e_displayed(a: Xyz, b: Xyz, exposure: f64) -> f64 {
    delta_e_2000(displayed_lab(a, exposure), displayed_lab(b, exposure))
}

/// Mean, 95th and 99th percentiles (nearest rank below) and maximum of a set of colour differences: the one ΔE
/// statistics of the benches (`iridis_api::bench`), the film-path studies and the GPU tests.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct DeltaEStats {
    pub mean: f64,
    pub p95: f64,
    pub p99: f64,
    pub max: f64,
    /// How many colours were compared.
    pub count: usize,
}

impl DeltaEStats {
    /// The statistics of `values` (all zero for none).
    pub fn of(mut values: Vec<f64>) -> Self {
        if values.is_empty() {
            return Self { mean: 0.0, p95: 0.0, p99: 0.0, max: 0.0, count: 0 };
        }
        values.sort_by(f64::total_cmp);
        let n = values.len();
        let rank = |q: f64| values[((n as f64 * q) as usize).min(n - 1)];
        Self {
            mean: values.iter().sum::<f64>() / n as f64,
            p95: rank(0.95),
            p99: rank(0.99),
            max: values[n - 1],
            count: n,
        }
    }

    /// Displayed ΔE00 between matching colours of `a` and `b` at one exposure (in parallel).
    pub fn between(a: &[Xyz], b: &[Xyz], exposure: f64) -> Self {
        use rayon::prelude::*;
        Self::of(a.par_iter().zip(b).map(|(p, q)| delta_e_displayed(*p, *q, exposure)).collect())
    }
}

impl std::fmt::Display for DeltaEStats {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "ΔE00 mean {:.4}, p99 {:.4}, max {:.4} ({} colours)", self.mean, self.p99, self.max, self.count)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn statistics_and_clipping() {
        let s = DeltaEStats::of((1..=200).map(|i| i as f64).collect());
        assert_eq!((s.mean, s.p95, s.p99, s.max, s.count), (100.5, 191.0, 199.0, 200.0, 200));
        // Two colours both far above white are both shown as white.
        let w = white_point(Illuminant::D65, Observer::Cie1931);
        assert!(delta_e_displayed(w.scale(3.0), w.scale(5.0), 1.0) < 1e-9);
        assert!(delta_e_displayed(w.scale(0.3), w.scale(0.5), 1.0) > 10.0);
    }
}
