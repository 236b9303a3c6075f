//! Films on a rough substrate (the LSRS model, Sussenbach eq. 3.15–3.20, with the HTSG BRDF at the substrate;
//! `iridis_thinfilm::rough`): the options `σ, τ` (`iridis thinfilm … --roughness --correlation`, Python's
//! `iridis.thinfilm` `roughness=`), spectra, colours and the soap-film chart's bands. Specular (`k_r`, a
//! fraction of the incident power) and diffuse (`k_d`, sr⁻¹; `π k_d` is the radiance factor, relative to a
//! white Lambertian surface under the same light) are reported separately, next to the smooth model's `R`.

use std::f64::consts::PI;

use anyhow::{anyhow, Result};
use iridis_color::{Illuminant, Observer, SpectralWeights, Xyz};
use iridis_thinfilm::color::{FilmColor, FilmColorimeter, Polarization};
use iridis_thinfilm::htsg::{Htsg, Roughness, Series};
use iridis_thinfilm::rough::{DiffuseTransport, Lsrs, RoughStack};
use iridis_thinfilm::Stack;

/// The rough model's options.
#[derive(Debug, Clone, Copy)]
pub struct RoughOptions {
    /// rms roughness σ of the last interface (nm).
    pub sigma_nm: f64,
    /// Autocorrelation length τ of the rough interface (nm).
    pub tau_nm: f64,
    /// Terms of the HTSG directional-diffuse series (the thesis' D-iterations); `None`: as many as needed for
    /// an error bound of 1e-6 of the lobe's peak.
    pub d_iterations: Option<usize>,
    /// How diffuse light crosses the layers.
    pub transport: DiffuseTransport,
}

impl RoughOptions {
    /// σ and τ with the defaults of the front ends (series to 1e-6, multiple scattering inside the film).
    pub fn new(sigma_nm: f64, tau_nm: f64) -> Self {
        Self { sigma_nm, tau_nm, d_iterations: None, transport: DiffuseTransport::Multiple }
    }

    /// The stack with this rough substrate.
    pub fn build(&self, stack: Stack) -> Result<RoughStack> {
        let series = match self.d_iterations {
            Some(n) => Series::Fixed(n),
            None => Series::default(),
        };
        let r = Roughness::new(self.sigma_nm, self.tau_nm).map_err(|e| anyhow!("--roughness/--correlation: {e}"))?;
        Ok(RoughStack::new(stack, Htsg::new(r, series)).with_transport(self.transport))
    }

    /// How the series is summed, in words.
    pub fn series_label(&self) -> String {
        series_label(self.d_iterations)
    }
}

/// How the HTSG series is summed, in words: `N D-iterations` or `series to 1e-6`.
pub fn series_label(d_iterations: Option<usize>) -> String {
    match d_iterations {
        Some(n) => format!("{n} D-iterations"),
        None => "series to 1e-6".into(),
    }
}

/// Per wavelength: the smooth model's R and the LSRS values (view and light polar angles, azimuth of the light
/// relative to the viewer; radians).
pub fn evaluate(rough: &RoughStack, grid: &[f64], view: f64, light: f64, azimuth: f64) -> Result<Vec<(f64, Lsrs)>> {
    use rayon::prelude::*;
    // In parallel: with multiple scattering each wavelength prepares its own state.
    grid.par_iter()
        .map(|&w| Ok((rough.stack.evaluate(w, view)?.r(), rough.evaluate(w, view, light, azimuth)?)))
        .collect()
}

/// The colours of a rough film (`iridis thinfilm color --roughness`): the smooth film's (reflected and
/// transmitted), the rough film's specular part `k_r` and its diffuse part `π k_d`.
#[derive(Debug, Clone, Copy)]
pub struct RoughColours {
    pub smooth: FilmColor,
    pub specular: Xyz,
    pub diffuse: Xyz,
}

/// The colours of a rough film for one view and light.
pub fn colours(
    rough: &RoughStack,
    view: f64,
    light: f64,
    azimuth: f64,
    grid: &[f64],
    illuminant: Illuminant,
    observer: Observer,
) -> Result<RoughColours> {
    let xs = evaluate(rough, grid, view, light, azimuth)?;
    let weights = SpectralWeights::new(grid, illuminant, observer);
    let smooth = FilmColorimeter::new(grid, illuminant, observer).color(&rough.stack, view, Polarization::Average)?;
    let specular = weights.integrate(&xs.iter().map(|x| x.1.k_r()).collect::<Vec<_>>());
    let diffuse = weights.integrate(&xs.iter().map(|x| PI * x.1.k_d()).collect::<Vec<_>>());
    Ok(RoughColours { smooth, specular, diffuse })
}

/// For every thickness of the swept layer, the XYZ of the rough film's specular part (`k_r`, like the smooth
/// chart's reflected band) and of its diffuse part (`π k_d`, the radiance factor: Y = 1 is a white Lambertian
/// surface under the same light).
#[allow(clippy::too_many_arguments)]
pub fn chart_colours(
    stack: &Stack,
    layer: usize,
    thicknesses: &[f64],
    opts: &RoughOptions,
    view: f64,
    light: f64,
    azimuth: f64,
    grid: &[f64],
    illuminant: Illuminant,
    observer: Observer,
) -> Result<Vec<(Xyz, Xyz)>> {
    use rayon::prelude::*;
    let weights = SpectralWeights::new(grid, illuminant, observer);
    thicknesses
        .par_iter()
        .map(|&d| {
            let rough = opts.build(stack.with_thickness(layer, d))?;
            let xs = evaluate(&rough, grid, view, light, azimuth)?;
            let spec = weights.integrate(&xs.iter().map(|x| x.1.k_r()).collect::<Vec<_>>());
            let diff = weights.integrate(&xs.iter().map(|x| PI * x.1.k_d()).collect::<Vec<_>>());
            Ok((spec, diff))
        })
        .collect()
}
