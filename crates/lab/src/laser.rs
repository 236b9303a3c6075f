//! The laser experiment of paper sec. 6.2 (Figures 8–10), simulated.
//!
//! A sample stands vertically; a horizontal supercontinuum beam falls on it at `θ_i = 45°` through a
//! diaphragm whose aperture (65–100 µm) limits the coherent area, so the aperture is the coherence length
//! `4σ_s` here. The mirror reflection leaves at 90° to the beam, and a white screen parallel to the beam, at
//! distance `D` from the sample, catches it head-on. The camera records the screen.
//!
//! Geometry in the surface frame (PHYSICS.md), the sample rotated by `azimuth` about its normal as on the test
//! bench: light `ω_i = (sin θ_i e_x', cos θ_i)`, mirror direction `s = (−sin θ_i e_x', cos θ_i)`,
//! `e_x' = (cos φ, −sin φ, 0)` for azimuth `φ`. The screen point at image coordinates `(a, b)` (mm right, up)
//! is `P = D s + a e₁ + b e₂` with `e₁ = −ω_i` (along the beam, to the right as the camera sees it from the
//! sample's side) and `e₂` the normal of the plane of incidence (up); the pixel views `ω_r = P/|P|`.
//!
//! Screen brightness: the sample sends radiant intensity `∝ ρ cos θ_r` into `ω_r` (ρ the relative reflectance
//! of PHYSICS.md, which carries the `cos θ_i` of the irradiance); the screen receives it over `r²` at the
//! angle `acos(D/r)`, so a sample of the pixel weighs `ρ · (cos θ_r / cos θ_i) · (D/r)³`, normalised to `ρ` at
//! the screen's centre. Each pixel averages `k × k` samples over its area — the average over the pixel's
//! solid angle of sec. 6.2.
//!
//! Light and coating: the beam's spectrum `S(λ)` (CSV) replaces the illuminant. A gold coating enters through
//! gold's complex index `n + iκ` (Johnson & Christy 1972, via `iridis-thinfilm`): its normal-incidence
//! reflectance `R_Au(λ)` multiplies the light (the gold mirror's colour), and the Fresnel factor of the
//! shading becomes gold's exact unpolarised Fresnel reflectance, so its angular change stays inside the
//! spectral integral (paper: "a wavelength dependent Fresnel-term as part of the integrand"). The lookup
//! method integrates over λ in advance and takes gold at normal incidence only (the paper notes the angular
//! dependence is weak, Figure 9). Exposure: 1 RU saturates white for a perfect, uncoated mirror at normal
//! incidence under the same beam, so a gold mirror is dimmer by `Σ S R_Au ȳ / Σ S ȳ`.

use std::sync::Arc;

use iridis_color::{Observer, Spectrum, Xyz};
use iridis_diffraction::geometry::{fresnel_unpolarised, FresnelSource, Vec3};
use iridis_thinfilm::Material;

use crate::image::Pixels;
use crate::methods::{spectral_with_light, Method, MethodConfig};
use crate::LabError;

/// The most pixels on a side of the screen's image.
pub const MAX_SIDE_PX: usize = 4096;
/// The most view samples a pixel side.
pub const MAX_SUBSAMPLES: usize = 16;

/// The geometry of Figure 8.
#[derive(Debug, Clone, PartialEq)]
pub struct LaserSetup {
    /// Angle between the beam and the sample normal (rad); the paper: 45°.
    pub incidence: f64,
    /// Rotation of the sample about its normal (rad).
    pub azimuth: f64,
    /// Distance from the sample to the screen (nm); the paper's simulation: 100 mm.
    pub distance_nm: f64,
    /// Screen area shown (nm).
    pub screen_width_nm: f64,
    pub screen_height_nm: f64,
    /// Image size (pixels); the paper's error analysis: 101 × 101.
    pub width_px: usize,
    pub height_px: usize,
    /// Samples per pixel side (pixel solid-angle averaging).
    pub subsamples: usize,
}

impl Default for LaserSetup {
    fn default() -> Self {
        Self {
            incidence: std::f64::consts::FRAC_PI_4,
            azimuth: 0.0,
            distance_nm: 100e6,
            screen_width_nm: 300e6,
            screen_height_nm: 300e6,
            width_px: 101,
            height_px: 101,
            subsamples: 3,
        }
    }
}

impl LaserSetup {
    fn check(&self) -> Result<(), LabError> {
        let pos = |v: f64| v.is_finite() && v > 0.0;
        if !(self.incidence.is_finite() && self.incidence > 0.0 && self.incidence < std::f64::consts::FRAC_PI_2) {
            return Err(LabError::invalid(format!(
                "beam incidence {:.2}° must be between 0° and 90° (exclusive)",
                self.incidence.to_degrees()
            )));
        }
        if !(pos(self.distance_nm) && pos(self.screen_width_nm) && pos(self.screen_height_nm)) {
            return Err(LabError::invalid(format!(
                "--distance {} nm and --screen {} × {} nm: the screen's distance and size must be positive lengths",
                self.distance_nm, self.screen_width_nm, self.screen_height_nm
            )));
        }
        if !(1..=MAX_SIDE_PX).contains(&self.width_px) || !(1..=MAX_SIDE_PX).contains(&self.height_px) {
            return Err(LabError::invalid(format!("the image must be 1–{MAX_SIDE_PX} pixels on each side")));
        }
        if !(1..=MAX_SUBSAMPLES).contains(&self.subsamples) {
            return Err(LabError::invalid(format!("subsamples per pixel side must be 1–{MAX_SUBSAMPLES}")));
        }
        Ok(())
    }

    /// The angle (rad) between neighbouring view samples where they are furthest apart, at the screen's
    /// centre (the sample's distance there; further out the same step on the screen subtends less).
    pub fn sample_spacing_rad(&self) -> f64 {
        let k = self.subsamples as f64;
        let step = (self.screen_width_nm / (self.width_px as f64 * k))
            .max(self.screen_height_nm / (self.height_px as f64 * k));
        step / self.distance_nm
    }

    /// The light direction and the screen's frame `(s, e₁, e₂)` in the surface frame.
    pub fn frame(&self) -> (Vec3, Vec3, Vec3, Vec3) {
        let (st, ct) = self.incidence.sin_cos();
        let (sp, cp) = (-self.azimuth).sin_cos();
        let wi = [st * cp, st * sp, ct];
        let s = [-st * cp, -st * sp, ct];
        let e1 = [-wi[0], -wi[1], -wi[2]];
        let e2 = [-sp, cp, 0.0];
        (wi, s, e1, e2)
    }

    /// The view direction through screen point `(a, b)` (nm right, up of the centre) and its weight.
    pub fn view(&self, a: f64, b: f64) -> Option<(Vec3, f64)> {
        let (wi, s, e1, e2) = self.frame();
        let d = self.distance_nm;
        let p = [d * s[0] + a * e1[0] + b * e2[0], d * s[1] + a * e1[1] + b * e2[1], d * s[2] + a * e1[2] + b * e2[2]];
        let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        let wr = [p[0] / r, p[1] / r, p[2] / r];
        if wr[2] <= 1e-9 {
            return None; // behind the sample's plane
        }
        Some((wr, wr[2] / wi[2] * (d / r).powi(3)))
    }

    /// The screen's pixels, each with `k × k` direction samples.
    pub fn pixels(&self) -> Result<Pixels, LabError> {
        self.check()?;
        let (wi, ..) = self.frame();
        let k = self.subsamples;
        let (w, h) = (self.width_px, self.height_px);
        let mut samples = Vec::with_capacity(w * h);
        for row in 0..h {
            for col in 0..w {
                let mut s = Vec::with_capacity(k * k);
                for sy in 0..k {
                    for sx in 0..k {
                        let a = ((col as f64 + (sx as f64 + 0.5) / k as f64) / w as f64 - 0.5) * self.screen_width_nm;
                        let b = (0.5 - (row as f64 + (sy as f64 + 0.5) / k as f64) / h as f64) * self.screen_height_nm;
                        if let Some((wr, weight)) = self.view(a, b) {
                            s.push((wi, wr, weight / (k * k) as f64));
                        }
                    }
                }
                samples.push(s);
            }
        }
        Ok(Pixels { width: w, height: h, samples })
    }
}

/// Gold (or any metal) as the Fresnel source: the exact unpolarised Fresnel reflectance of `n̂(λ)` in air.
#[derive(Debug, Clone)]
pub struct MetalFresnel {
    pub material: Arc<Material>,
}

impl MetalFresnel {
    /// Checks that the material covers `[from, to]` nm.
    pub fn new(material: Material, from_nm: f64, to_nm: f64) -> Result<Self, LabError> {
        for l in [from_nm, to_nm] {
            material.index_at(l).map_err(|e| LabError::invalid(format!("coating: {e}")))?;
        }
        Ok(Self { material: Arc::new(material) })
    }

    pub fn index(&self, wavelength_nm: f64) -> num_complex::Complex64 {
        // The range was checked at construction; outside it the nearest end is used.
        let (lo, hi) = self.material.range_nm();
        self.material.index_at(wavelength_nm.clamp(lo, hi)).unwrap_or(num_complex::Complex64::new(1.0, 0.0))
    }

    /// Normal-incidence reflectance `|(n̂ − 1)/(n̂ + 1)|²`.
    pub fn normal_reflectance(&self, wavelength_nm: f64) -> f64 {
        fresnel_unpolarised(self.index(wavelength_nm), 1.0)
    }
}

impl FresnelSource for MetalFresnel {
    fn reflectance(&self, wavelength_nm: f64, cos_theta: f64) -> f64 {
        fresnel_unpolarised(self.index(wavelength_nm), cos_theta)
    }
    fn reflectance_sp(&self, wavelength_nm: f64, cos_theta: f64) -> [f64; 2] {
        iridis_diffraction::geometry::fresnel_sp(self.index(wavelength_nm), cos_theta)
    }
    fn polarised(&self) -> bool {
        true
    }
    fn depends_on_wavelength(&self) -> bool {
        true
    }
    fn describe(&self) -> String {
        format!("{} (complex index, exact Fresnel)", self.material.name())
    }
}

/// The coating's Fresnel factor relative to its own normal incidence, `F(λ, cos θ) / F(λ, 1)`: the angular
/// shape only, because [`configure`] already carries the coating's normal-incidence colour in the light (and
/// reports its brightness as the mirror scale). With the plain [`MetalFresnel`] the shading's λ-independent
/// `F_0` would apply the coating's colour a second time.
#[derive(Debug, Clone)]
pub struct CoatingShape(pub MetalFresnel);

impl FresnelSource for CoatingShape {
    fn reflectance(&self, wavelength_nm: f64, cos_theta: f64) -> f64 {
        self.0.reflectance(wavelength_nm, cos_theta) / self.0.normal_reflectance(wavelength_nm).max(1e-300)
    }
    fn depends_on_wavelength(&self) -> bool {
        true
    }
    fn describe(&self) -> String {
        format!("{} relative to normal incidence (colour in the light)", self.0.material.name())
    }
    fn normal_reflectance(&self) -> f64 {
        1.0
    }
}

/// A Fresnel factor of 1 (the coating's colour is carried by the light instead).
#[derive(Debug, Clone, Copy)]
pub struct UnitFresnel;

impl FresnelSource for UnitFresnel {
    fn reflectance(&self, _: f64, _: f64) -> f64 {
        1.0
    }
    fn depends_on_wavelength(&self) -> bool {
        false
    }
    fn describe(&self) -> String {
        "none (coating colour in the light)".into()
    }
}

/// Sets a method configuration up for the experiment: the beam's spectrum as the light, the coating in the
/// light and in the Fresnel factor (see the module notes); without a coating the configuration's Fresnel factor
/// stays. Returns the factor that converts the resulting
/// XYZ to RU of a perfect mirror under the same beam.
pub fn configure(
    config: &mut MethodConfig,
    method: Method,
    spectrum: &Spectrum,
    coating: Option<&MetalFresnel>,
    observer: Observer,
) -> Result<f64, LabError> {
    if spectrum.values().iter().any(|v| *v < 0.0) || spectrum.values().iter().all(|v| *v == 0.0) {
        return Err(LabError::invalid("the beam spectrum must be non-negative and not all zero"));
    }
    let grid = config.spectral.wavelengths().to_vec();
    let (from, to, step) = (grid[0], grid[grid.len() - 1], config.spectral.step_nm);
    let fine: Vec<f64> = (0..=((to - from).round() as usize)).map(|i| from + i as f64).collect();
    let r0 = |l: f64| coating.map(|c| c.normal_reflectance(l)).unwrap_or(1.0);
    let effective = Spectrum::new(fine.clone(), fine.iter().map(|&l| spectrum.value_at(l) * r0(l)).collect())
        .map_err(|e| LabError::invalid(e.to_string()))?;
    let plain = iridis_color::SpectralWeights::with_light(&fine, |l| spectrum.value_at(l), observer);
    if plain.white().y <= 0.0 {
        return Err(LabError::invalid("the beam spectrum has no visible light (380–780 nm)"));
    }
    let scale = plain.integrate(&fine.iter().map(|&l| r0(l)).collect::<Vec<_>>()).y;
    config.spectral = spectral_with_light(&effective, observer, from, to, step)?;
    config.light = Some(effective);
    // Uncoated, the surface keeps the configuration's Fresnel term (`--fresnel`).
    match (coating, method.is_spectral()) {
        (Some(c), true) => config.shading.fresnel = Arc::new(CoatingShape(c.clone())),
        (Some(_), false) => config.shading.fresnel = Arc::new(UnitFresnel),
        (None, _) => {}
    }
    Ok(scale)
}

/// Scales every pixel by `factor`.
pub fn scale_image(image: &mut [Option<Xyz>], factor: f64) {
    for p in image.iter_mut().flatten() {
        *p = p.scale(factor);
    }
}
