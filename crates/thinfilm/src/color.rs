//! Film colours: `XYZ = ∫ R(λ) S(λ) x̄(λ) dλ / ∫ S(λ) ȳ(λ) dλ` (`docs/PHYSICS.md`), through
//! `iridis_color::SpectralWeights`, for the reflected and the transmitted light.

use iridis_color::{Illuminant, Observer, SpectralWeights, Xyz};

use crate::error::ThinFilmError;
use crate::recurrence::Rta;
use crate::stack::Stack;

/// Which polarisation a quantity refers to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Polarization {
    /// Unpolarised light: the average of s and p.
    #[default]
    Average,
    S,
    P,
}

impl Polarization {
    pub fn reflectance(self, x: &Rta) -> f64 {
        match self {
            Polarization::Average => x.r(),
            Polarization::S => x.r_s,
            Polarization::P => x.r_p,
        }
    }
    pub fn transmittance(self, x: &Rta) -> f64 {
        match self {
            Polarization::Average => x.t(),
            Polarization::S => x.t_s,
            Polarization::P => x.t_p,
        }
    }
}

iridis_color::names! {
    Polarization {
        Average => "avg" | "average" | "unpolarized" | "unpolarised",
        S => "s" | "te",
        P => "p" | "tm",
    }
    else |s| -> String { format!("'{s}' is not a polarisation; use avg, s or p") }
}

/// The reflected and transmitted colour of a stack.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FilmColor {
    pub reflected: Xyz,
    pub transmitted: Xyz,
}

/// A colour calculator on a fixed wavelength grid.
#[derive(Debug, Clone)]
pub struct FilmColorimeter {
    weights: SpectralWeights,
}

impl FilmColorimeter {
    pub fn new(grid_nm: &[f64], illuminant: Illuminant, observer: Observer) -> Self {
        Self { weights: SpectralWeights::new(grid_nm, illuminant, observer) }
    }

    pub fn wavelengths_nm(&self) -> &[f64] {
        self.weights.wavelengths_nm()
    }

    /// Colours from R and T sampled on the grid.
    pub fn from_spectra(&self, r: &[f64], t: &[f64]) -> FilmColor {
        FilmColor { reflected: self.weights.integrate(r), transmitted: self.weights.integrate(t) }
    }

    /// The colours of a stack at an incidence angle (unpolarised light unless `pol` says otherwise).
    pub fn color(&self, stack: &Stack, angle_rad: f64, pol: Polarization) -> Result<FilmColor, ThinFilmError> {
        self.color_of(pol, |w| stack.evaluate(w, angle_rad))
    }

    /// The colours of the powers that `evaluate` gives at each wavelength of the grid (a stack with offset
    /// layers, a prepared stack, …), for polarisation `pol`.
    pub fn color_of(
        &self,
        pol: Polarization,
        mut evaluate: impl FnMut(f64) -> Result<Rta, ThinFilmError>,
    ) -> Result<FilmColor, ThinFilmError> {
        let mut r = Vec::with_capacity(self.wavelengths_nm().len());
        let mut t = Vec::with_capacity(r.capacity());
        for &w in self.wavelengths_nm() {
            let x = evaluate(w)?;
            r.push(pol.reflectance(&x));
            t.push(pol.transmittance(&x));
        }
        Ok(self.from_spectra(&r, &t))
    }
}
