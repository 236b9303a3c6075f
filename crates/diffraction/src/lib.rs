//! # iridis-diffraction
//!
//! The diffraction BRDF of a measured nanostructure, after Stam (1999) as adapted to discrete height fields by
//! Dhillon et al. (2014, "the paper") and Single (2014, "the thesis"). Conventions: `docs/PHYSICS.md`.
//!
//! Data flow:
//! ```text
//! height field ──► Patch (y up, mean removed) ──► TaylorTerms: DFT{(i h)^n}, n = 0..N      (paper eq. 5–8)
//!                        │                              │
//!                        ▼                              ├──► Reference evaluator (thesis FLSS)
//!                  GroundTruth evaluator                └──► LookupTable I_p(u, v) ──► Lookup evaluator (eq. 9–12)
//! ```
//! Every evaluator implements [`Evaluator`]: colour (XYZ) for a pair of directions, and — where the method
//! has it — the spectral reflectance at one wavelength. [`map::brdf_map`] renders any of them.

pub mod accel;
pub mod encoding;
pub mod energy;
pub mod evaluator;
pub mod geometry;
pub mod grating;
pub mod map;
pub mod patch;
pub mod point;
pub mod spectral;
pub mod table;
pub mod taylor;

pub use accel::Accelerator;
pub use evaluator::{Aperture, Evaluator, GroundTruth, Lattice, Reference};
pub use geometry::{Fresnel, FresnelConvention, Shading};
pub use patch::{Coherence, Patch};
pub use point::{point_query, PointQuery};
pub use spectral::{SpectralSetup, Units};
pub use table::{Lookup, LookupTable, TableParams};
pub use taylor::TaylorTerms;

/// Errors of the diffraction library; messages say what to change.
#[derive(Debug, thiserror::Error)]
pub enum DiffractionError {
    #[error("{0}")]
    Invalid(String),
    #[error("table {path}: {message}")]
    Table { path: String, message: String },
    #[error("{0}")]
    Io(#[from] std::io::Error),
}

/// Default coherence length `4σ_s` (nm): 65 µm, as in the paper (sec. 4.2).
pub const DEFAULT_COHERENCE_NM: f64 = 65_000.0;
