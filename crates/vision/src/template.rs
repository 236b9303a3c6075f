//! Photoreceptor sensitivity from a pigment's λmax: the visual-pigment templates of Govardovskii et al. (2000)
//! and the oil-droplet filters of Hart & Vorobyev (2005).

use std::fmt;

use serde::Serialize;

use crate::VisionError;

/// The chromophore of a visual pigment: vitamin A1 (rhodopsins, most land animals) or A2 (porphyropsins,
/// many freshwater fish and amphibians). Selects the template's constants.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "UPPERCASE")]
pub enum Chromophore {
    #[default]
    A1,
    A2,
}

iridis_color::names! {
    Chromophore {
        A1 => "A1",
        A2 => "A2",
    }
    else |s| -> VisionError { VisionError::invalid(format!("unknown chromophore '{s}'; expected a1 or a2")) }
}

impl fmt::Display for Chromophore {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The α band of the Govardovskii et al. (2000) template at wavelength `λ` for a pigment of peak `λmax` (nm):
/// `S_α(x) = 1 / (exp(A(a − x)) + exp(B(b − x)) + exp(C(c − x)) + D)` with `x = λmax/λ`. For A1 the constants
/// are A = 69.7, B = 28, b = 0.922, C = −14.9, c = 1.104, D = 0.674 and
/// `a = 0.8795 + 0.0459 exp(−(λmax − 300)²/11940)`; for A2 A = 62.7 + 1.834 exp((λmax − 625)/54.2),
/// `a = 0.875 + 0.0268 exp((λmax − 665)/40.7)`, B = 20.85, b = 0.9101, C = −10.37, c = 1.1123, D = 0.5343.
/// Peaks at ≈ 1 at `λ = λmax`.
pub fn alpha_band(lambda_max_nm: f64, wavelength_nm: f64, chromophore: Chromophore) -> f64 {
    let x = lambda_max_nm / wavelength_nm;
    let (big_a, a, big_b, b, big_c, c, d) = match chromophore {
        Chromophore::A1 => {
            let a = 0.8795 + 0.0459 * (-(lambda_max_nm - 300.0).powi(2) / 11940.0).exp();
            (69.7, a, 28.0, 0.922, -14.9, 1.104, 0.674)
        }
        Chromophore::A2 => {
            let big_a = 62.7 + 1.834 * ((lambda_max_nm - 625.0) / 54.2).exp();
            let a = 0.875 + 0.0268 * ((lambda_max_nm - 665.0) / 40.7).exp();
            (big_a, a, 20.85, 0.9101, -10.37, 1.1123, 0.5343)
        }
    };
    1.0 / ((big_a * (a - x)).exp() + (big_b * (b - x)).exp() + (big_c * (c - x)).exp() + d)
}

/// The β band of the Govardovskii et al. (2000) template, a Gaussian `A_β exp(−((λ − λ_mβ)/b_β)²)`: for A1
/// `A_β = 0.26`, `λ_mβ = 189 + 0.315 λmax`, `b_β = −40.5 + 0.195 λmax`; for A2 `A_β = 0.37`,
/// `λ_mβ = 216.7 + 0.287 λmax`, `b_β = 317 − 1.149 λmax + 0.00124 λmax²`.
pub fn beta_band(lambda_max_nm: f64, wavelength_nm: f64, chromophore: Chromophore) -> f64 {
    let l = lambda_max_nm;
    let (amp, centre, width) = match chromophore {
        Chromophore::A1 => (0.26, 189.0 + 0.315 * l, -40.5 + 0.195 * l),
        Chromophore::A2 => (0.37, 216.7 + 0.287 * l, 317.0 - 1.149 * l + 0.00124 * l * l),
    };
    amp * (-((wavelength_nm - centre) / width).powi(2)).exp()
}

/// The whole template: α band plus, when `beta` is set, the β band.
pub fn template(lambda_max_nm: f64, wavelength_nm: f64, chromophore: Chromophore, beta: bool) -> f64 {
    let a = alpha_band(lambda_max_nm, wavelength_nm, chromophore);
    if beta {
        a + beta_band(lambda_max_nm, wavelength_nm, chromophore)
    } else {
        a
    }
}

/// The oil-droplet types of bird cones (Hart & Vorobyev 2005): T (transparent, UVS/VS cones), C (SWS),
/// Y (MWS), R (LWS), P (principal member of the double cone).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum DropletType {
    T,
    C,
    Y,
    R,
    P,
}

iridis_color::names! {
    DropletType {
        T => "T",
        C => "C",
        Y => "Y",
        R => "R",
        P => "P",
    }
    else |s| -> VisionError {
        VisionError::invalid(format!("unknown oil-droplet type '{s}'; expected T, C, Y, R or P"))
    }
}

/// An oil-droplet filter in the model of Hart & Vorobyev (2005):
/// `T(λ) = exp(−exp(−2.89 B_mid (λ − λ_cut) + 1.08))`, where λ_cut is the wavelength at which the tangent at
/// the half-transmission wavelength λ_mid meets the maximum absorbance, and `B_mid = 0.5/(λ_mid − λ_cut)` the
/// slope there (nm⁻¹). A transparent droplet (type T) is no filter at all.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Droplet {
    pub lambda_cut_nm: f64,
    pub b_mid_per_nm: f64,
}

impl Droplet {
    /// A droplet given λ_cut and B_mid.
    pub fn new(lambda_cut_nm: f64, b_mid_per_nm: f64) -> Result<Self, VisionError> {
        if !(lambda_cut_nm.is_finite() && lambda_cut_nm > 0.0) {
            return Err(VisionError::invalid(format!("oil-droplet λcut {lambda_cut_nm} nm must be positive")));
        }
        if !(b_mid_per_nm.is_finite() && b_mid_per_nm > 0.0) {
            return Err(VisionError::invalid(format!("oil-droplet Bmid {b_mid_per_nm} nm⁻¹ must be positive")));
        }
        Ok(Self { lambda_cut_nm, b_mid_per_nm })
    }

    /// A droplet of a known type with only λ_cut measured: λ_mid from Hart & Vorobyev's (2005) regressions on
    /// λ_cut (C: 0.99 λ_cut + 24.38; Y: 0.90 λ_cut + 70.03; R: 0.99 λ_cut + 28.65; P: 0.96 λ_cut + 33.57), then
    /// `B_mid = 0.5/(λ_mid − λ_cut)`. `None` for a transparent (T) droplet.
    pub fn from_type(kind: DropletType, lambda_cut_nm: f64) -> Result<Option<Self>, VisionError> {
        let (slope, offset) = match kind {
            DropletType::T => return Ok(None),
            DropletType::C => (0.99, 24.38),
            DropletType::Y => (0.90, 70.03),
            DropletType::R => (0.99, 28.65),
            DropletType::P => (0.96, 33.57),
        };
        let lambda_mid = slope * lambda_cut_nm + offset;
        if lambda_mid <= lambda_cut_nm {
            return Err(VisionError::invalid(format!(
                "oil droplet {kind:?} with λcut {lambda_cut_nm} nm: the regression gives λmid {lambda_mid:.1} nm, not above λcut"
            )));
        }
        Self::new(lambda_cut_nm, 0.5 / (lambda_mid - lambda_cut_nm)).map(Some)
    }

    /// The droplet's transmittance at `λ`.
    pub fn transmittance(&self, wavelength_nm: f64) -> f64 {
        (-(-2.89 * self.b_mid_per_nm * (wavelength_nm - self.lambda_cut_nm) + 1.08).exp()).exp()
    }

    /// The half-transmission wavelength `λ_mid = λ_cut + 0.5/B_mid`.
    pub fn lambda_mid_nm(&self) -> f64 {
        self.lambda_cut_nm + 0.5 / self.b_mid_per_nm
    }
}
