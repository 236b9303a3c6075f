//! What a map's pixels show on a display: light or the round-off of cancelling sums ([`LIT_FLOOR`]), black at
//! every exposure, or clipped. Shared by the maps (`brdf_map`), the lab's comparisons and the benches.

use iridis_color::Xyz;

/// The faintest value that counts as light in a map (RU, or sr⁻¹ for f_r): below it is the round-off of sums
/// that cancel (a missed lobe leaves ~1e-35), which an exposure of 1e17 RU or more would be needed to see; a map
/// of nothing brighter is black.
pub const LIT_FLOOR: f64 = 1e-20;

/// A pixel's brightest linear sRGB channel: what reaches white first.
pub(crate) fn peak_channel(p: &Xyz) -> f64 {
    p.to_linear_srgb().iter().fold(0.0f64, |m, &c| m.max(c))
}

/// Whether a pixel's brightest channel is light ([`LIT_FLOOR`]), not round-off.
pub(crate) fn is_lit(peak: f64) -> bool {
    peak > LIT_FLOOR && peak.is_finite()
}

/// A displayed channel below this (linear sRGB) is black to CIELAB's eye: L* under 0.1.
pub const DISPLAY_FLOOR: f64 = 1e-4;

/// Whether a map shows nothing at any of `exposures` (RU): its brightest channel times the largest stays under
/// [`DISPLAY_FLOOR`], so every colour difference taken on it is 0 whatever the method.
pub fn dark_at_every_exposure(xyz: &[Xyz], exposures: &[f64]) -> bool {
    let most = exposures.iter().copied().fold(0.0f64, f64::max);
    brightest_lit(xyz).is_none_or(|p| peak_channel(&p) * most < DISPLAY_FLOOR)
}

/// The share of a map's lit pixels that are clipped at `exposure_ru` (a linear sRGB channel at 1 or above): their
/// colour, and how bright they are, is lost to the display.
pub fn clipped_share(xyz: &[Xyz], exposure_ru: f64) -> f64 {
    let lit: Vec<f64> = xyz.iter().map(peak_channel).filter(|&v| is_lit(v)).collect();
    lit.iter().filter(|&&v| v * exposure_ru >= 1.0).count() as f64 / lit.len().max(1) as f64
}

/// The map's brightest lit pixel (by its brightest channel), in one pass; `None` for a map with no light.
pub fn brightest_lit(xyz: &[Xyz]) -> Option<Xyz> {
    xyz.iter()
        .map(|p| (peak_channel(p), *p))
        .filter(|(v, _)| is_lit(*v))
        .max_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, p)| p)
}
