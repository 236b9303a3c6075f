//! Method comparisons in CIELAB (paper sec. 6.3, Table 2).
//!
//! Both images are taken as a camera would record them at an exposure `E` (RU, PHYSICS.md): XYZ × E →
//! linear sRGB (IEC 61966-2-1) → clipped to [0, 1] → back to XYZ → CIELAB relative to the sRGB/D65 white
//! (Y = 1). The per-pixel difference is CIEDE2000 (Sharma et al. 2005). Pixels that see nothing in both images
//! are left out. The clipping is why the errors depend on exposure: at 1 RU only the brightest highlights
//! reach the display range, at 7500 RU the faint diffraction bands do too (the paper's reason for three
//! exposures).

use iridis_color::lab::delta_e_displayed;
use iridis_color::Xyz;
use iridis_thinfilm::accuracy::DeltaEStats;
use serde::Serialize;

/// CIEDE2000 per pixel between `test` and `truth` at `exposure_ru` (`None` where neither sees anything).
pub fn delta_e_map(test: &[Option<Xyz>], truth: &[Option<Xyz>], exposure_ru: f64) -> Vec<Option<f64>> {
    test.iter()
        .zip(truth)
        .map(|(a, b)| match (a, b) {
            (None, None) => None,
            _ => {
                let (a, b) = (a.unwrap_or_default(), b.unwrap_or_default());
                Some(delta_e_displayed(a, b, exposure_ru))
            }
        })
        .collect()
}

/// The share (0–1) of an image's pixels, of those that have a value, that a display at `exposure_ru` shows as
/// pure white: every linear sRGB channel clipped at 1. Where most of the ground truth is, its ΔE compares white
/// with white there: small whatever the method. (Black at a low exposure is the paper's protocol: at 1 RU only
/// the highlights show, on purpose.)
pub fn clipped_white(img: &[Option<Xyz>], exposure_ru: f64) -> f64 {
    let (mut white, mut n) = (0usize, 0usize);
    for xyz in img.iter().flatten() {
        n += 1;
        white += usize::from(xyz.scale(exposure_ru).to_linear_srgb().iter().all(|&v| v >= 1.0));
    }
    if n == 0 {
        0.0
    } else {
        white as f64 / n as f64
    }
}

/// A sentence where more than half of `what` (an image's name) shows as clipped white at `exposure_ru`
/// (`share` from [`clipped_white`]).
pub fn clipping_warning(share: f64, what: &str, exposure_ru: f64) -> Option<String> {
    (share > 0.5).then(|| {
        format!(
            "at {exposure_ru} RU {what} shows as white (clipped) on {:.0} % of the map: ΔE00 there compares white \
             with white and says little of the method; a lower exposure shows its colours",
            100.0 * share
        )
    })
}

/// Statistics of a ΔE map's pixels that have a value (the percentiles are nearest-rank: the 95th is the
/// `⌈0.95 n⌉`-th smallest).
pub fn stats(map: &[Option<f64>]) -> DeltaEStats {
    DeltaEStats::of(map.iter().flatten().copied().filter(|x| x.is_finite()).collect())
}

/// One row of Table 2.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ComparisonRow {
    pub method: String,
    /// The image compared against (a ground truth's name).
    pub against: String,
    pub exposure_ru: f64,
    pub mean: f64,
    pub p95: f64,
    pub max: f64,
}

/// Table 2 for several methods' images against one ground truth (named `against`): one row per method and
/// exposure.
pub fn table(
    methods: &[(String, Vec<Option<Xyz>>)],
    truth: &[Option<Xyz>],
    against: &str,
    exposures: &[f64],
) -> Vec<ComparisonRow> {
    let mut rows = Vec::new();
    for (name, img) in methods {
        for &e in exposures {
            let s = stats(&delta_e_map(img, truth, e));
            rows.push(ComparisonRow {
                method: name.clone(),
                against: against.into(),
                exposure_ru: e,
                mean: s.mean,
                p95: s.p95,
                max: s.max,
            });
        }
    }
    rows
}

/// The periodic-extension error: the periodic ground truth's image against the finite aperture's, per exposure
/// — how far the two models of the same patch part, the floor under any comparison across them.
pub fn extension_error(periodic: &[Option<Xyz>], finite: &[Option<Xyz>], exposures: &[f64]) -> Vec<ComparisonRow> {
    table(&[("periodic-extension".into(), periodic.to_vec())], finite, "ground-truth", exposures)
}
