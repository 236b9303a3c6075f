//! # iridis-lab
//!
//! The virtual lab of the paper (Dhillon et al. 2014, sec. 6–7) and the thesis (Single 2014, ch. 5), for any
//! surface and any evaluator of `iridis-diffraction`:
//!
//! * [`mod@bench`]: the virtual test bench (paper sec. 6.1, Table 1, Figure 7; thesis eq. 5.5–5.6, Table 5.1):
//!   the reflectance matrix `R(λ, θ_r)` in the plane of incidence, the peak viewing angle of one diffraction
//!   order per wavelength, the periodicity `d_λ` from the grating equation, its mean and variance, and the
//!   competing ridges of sub-structures with different periods;
//! * [`compare`]: per-pixel CIEDE2000 between any evaluator and the ground truth at given exposures (Table 2);
//! * [`stam`]: Stam's (1999) analytic models as evaluators — periodic bumps on a lattice with the paper's ε
//!   selection of wavelengths (paper eq. 14–15) and the Gaussian random surface from the height field's
//!   correlation function (Stam eq. 12 as the paper restates it);
//! * [`variants`]: the thesis' NMM (sec. 4.5.2) and PQ (sec. 3.6, 4.5.3) shading variants;
//! * [`methods`]: one place that builds any of these evaluators for a patch;
//! * [`sweep`]: convergence sweeps (terms, Δλ, coherence, u-v power and resolution; Figures 14–17);
//! * [`laser`]: the laser experiment of Figure 8 (beam at 45°, aperture as coherence window, screen parallel to
//!   the beam, supercontinuum spectrum, gold through its complex index, pixel solid-angle averaging);
//! * [`analysis`]: the dominant period of a height field along x or y from its periodogram;
//! * [`image`]: pixels of directions, rendering, tone mapping, heat maps and contact sheets.
//!
//! Frames and signs follow `docs/PHYSICS.md`: light in the x-z plane at `θ_i`, viewer in the same plane, `θ_r`
//! signed and positive on the specular side, grating equation `m λ / d = sin θ_i − sin θ_r`.

pub mod analysis;
pub mod bench;
pub mod compare;
pub mod image;
pub mod laser;
pub mod methods;
pub mod stam;
pub mod sweep;
pub mod variants;

pub use bench::{BenchResult, BenchSetup, ReflectanceMatrix};
pub use methods::{Method, MethodConfig, Workbench};

/// What went wrong, in words a person can act on.
#[derive(Debug, thiserror::Error)]
pub enum LabError {
    #[error("{0}")]
    Invalid(String),
    #[error(transparent)]
    Diffraction(#[from] iridis_diffraction::DiffractionError),
    #[error(transparent)]
    Plot(#[from] iridis_plot::PlotError),
}

impl LabError {
    pub(crate) fn invalid(msg: impl Into<String>) -> Self {
        Self::Invalid(msg.into())
    }

    /// A name (`kind`: "method", …) that is none of `names`.
    pub(crate) fn unknown_name(kind: &str, given: &str, names: impl IntoIterator<Item = &'static str>) -> Self {
        let names: Vec<_> = names.into_iter().collect();
        Self::invalid(format!("unknown {kind} '{given}'; expected one of: {}", names.join(", ")))
    }
}

/// A progress callback: called with the number of work items done so far (from any thread).
pub type Progress<'a> = &'a (dyn Fn(usize) + Sync);

/// A progress callback that does nothing.
pub fn no_progress(_: usize) {}
