//! The one error type of the crate: every message names what was wrong, and where.

/// Everything that can go wrong with thin-film input or evaluation. Messages are written for people.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ThinFilmError {
    /// A stack string that cannot be read: the offending token and its 1-based character column.
    #[error("stack \"{stack}\": {message} (token '{token}' at column {column})")]
    Stack { stack: String, token: String, column: usize, message: String },
    /// A refractive-index file that cannot be read; `line` is 1-based when known.
    #[error("{path}{}: {message}", .line.map(|l| format!(", line {l}")).unwrap_or_default())]
    File { path: String, line: Option<usize>, message: String },
    /// A wavelength outside the data of a material: never extrapolated.
    #[error(
        "material '{material}' has data for {lo_nm}–{hi_nm} nm only; {wavelength_nm} nm is outside (no extrapolation)"
    )]
    OutOfRange { material: String, wavelength_nm: f64, lo_nm: f64, hi_nm: f64 },
    /// The incident medium must be lossless (Sussenbach, section 3.4, constraint 6).
    #[error("incident medium '{material}' absorbs (κ = {kappa} at {wavelength_nm} nm); the incident medium must be lossless")]
    AbsorbingIncident { material: String, kappa: f64, wavelength_nm: f64 },
    /// Any other invalid argument (a wavelength ≤ 0, an angle outside 0°–90°, …).
    #[error("{0}")]
    Invalid(String),
}
