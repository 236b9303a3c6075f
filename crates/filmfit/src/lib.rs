//! # iridis-filmfit
//!
//! Fitting thin-film stacks to measured spectra: reflectance, transmittance or ellipsometric ψ/Δ against
//! wavelength, at one angle. Free parameters are written into the stack (`{d1=100nm:50nm..500nm}`, see
//! [`template`]); the fit is Levenberg–Marquardt (the `levenberg-marquardt` crate, MINPACK's algorithm)
//! started from the best points of a grid over the thickness ranges (interference makes χ²(d) periodic, so a
//! local fit from one start finds the nearest fringe order, not the best one), with the 1σ uncertainties and
//! correlations of the parameters from the covariance `(JᵀWJ)⁻¹` at the optimum. The Jacobian `J` is exact:
//! forward-mode automatic differentiation through the thin-film model ([`iridis_thinfilm::jet`]), with the
//! chain rule through Cauchy and Sellmeier formulas ([`Template::tangent`]); central finite differences
//! remain as [`Derivatives::FiniteDifferences`] (and for more than [`MAX_EXACT`] parameters).

pub mod data;
pub mod fit;
pub mod template;

pub use data::{check_coverage, read, read_arrays, Measured, ReadOptions, Reading, Spread, SpreadSource};
pub use fit::{fit, model, model_jacobian, Derivatives, FitOptions, FitResult, MAX_EXACT};
pub use template::{Param, Role, Template};

/// What was measured.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Quantity {
    /// Unpolarised reflectance.
    R,
    /// Unpolarised transmittance.
    T,
    /// Ellipsometric ψ and Δ in degrees (tmm's `ellips` convention, `tan ψ e^{iΔ} = −r_p/r_s`).
    PsiDelta,
}

iridis_color::names! {
    Quantity {
        R => "R",
        T => "T",
        PsiDelta => "psi-delta" | "psi_delta" | "ellipsometry",
    }
    else |s| -> FitError { FitError::Data(format!("--quantity '{s}': use R, T or psi-delta")) }
}

impl Quantity {
    /// Values per wavelength.
    pub fn width(self) -> usize {
        if self == Quantity::PsiDelta {
            2
        } else {
            1
        }
    }
}

/// Everything that can go wrong, with a message for people.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FitError {
    /// The stack template (parameters, ranges, the stack itself).
    #[error("--stack: {0}")]
    Template(String),
    /// The measured data.
    #[error("{0}")]
    Data(String),
    /// The model cannot be evaluated (a wavelength outside a material's data, an invalid index).
    #[error("{0}")]
    Model(String),
}
