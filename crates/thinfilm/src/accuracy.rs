//! The statistics of colour differences over a set of pixels: displayed CIEDE2000
//! (`iridis_color::lab::delta_e_displayed`) summarised by mean, nearest-rank percentiles and maximum — the one ΔE
//! statistics of the benches, the film-path studies (docs/gpu.md), the method comparisons and the GPU tests.

use iridis_color::lab::delta_e_displayed;
use iridis_color::Xyz;
use serde::Serialize;

/// The nearest-rank `q`-quantile of `sorted` (ascending, not empty): its `⌈q n⌉`-th smallest value (the first
/// for `q = 0`).
pub fn nearest_rank(sorted: &[f64], q: f64) -> f64 {
    sorted[((q * sorted.len() as f64).ceil() as usize).clamp(1, sorted.len()) - 1]
}

/// Mean, 95th and 99th percentiles ([`nearest_rank`]) and maximum of a set of colour differences.
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
        Self {
            mean: values.iter().sum::<f64>() / n as f64,
            p95: nearest_rank(&values, 0.95),
            p99: nearest_rank(&values, 0.99),
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
    fn statistics_take_the_nearest_rank() {
        let s = DeltaEStats::of((1..=200).map(|i| i as f64).collect());
        // The 190th and 198th of 200 (⌈0.95 · 200⌉, ⌈0.99 · 200⌉).
        assert_eq!((s.mean, s.p95, s.p99, s.max, s.count), (100.5, 190.0, 198.0, 200.0, 200));
        assert_eq!(nearest_rank(&[1.0, 2.0, 3.0], 0.0), 1.0);
        assert_eq!(nearest_rank(&[1.0, 2.0, 3.0], 0.5), 2.0);
    }
}
