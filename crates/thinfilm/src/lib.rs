//! # iridis-thinfilm
//!
//! Multilayer thin-film interference: the smooth illumination model of Hirayama et al. as Sussenbach's
//! thesis describes it (section 3.1, equations 3.1–3.13), with the real-time variant of chapter 4 as a fast
//! path and spatially varying thickness (section 4.2).
//!
//! * [`material`]: complex refractive indices `n̂ = n + iκ` that may vary with wavelength — constants
//!   (`n=1.33`, `n=0.2+3.4i`), a built-in library (`air`, `water`, `BK7`, `Au`, …) and measured data from
//!   files (CSV and the refractiveindex.info YAML format, [`nkfile`]), interpolated in λ and never
//!   extrapolated; [`library`] the built-in library and the medium syntax of stacks;
//! * [`stack`]: incident medium | layers with thicknesses | substrate, parsed from
//!   `"air | gasoline 216nm | water 220nm | asphalt"`;
//! * [`recurrence`]: the physics — complex cosines from Snell's law (eq. 3.6), Fresnel amplitudes
//!   (eq. 3.7–3.10), the recurrence (eq. 3.1–3.4) with a replaceable bottom seed (so the LSRS model's rough
//!   seed, eq. 3.16, plugs in), and the amplitude → power conversion (eq. 3.12–3.13);
//! * [`fast`]: the chapter 4 variant — per-interface values computed once for a fixed angle, real arithmetic
//!   for dielectric stacks, the same numbers as the general path;
//! * [`grid`]: angle × wavelength tables (Figure 3.8), in parallel;
//! * [`incoherent`]: stacks with incoherent layers (`inc:BK7 1mm`), as `tmm.inc_tmm`, and the depth
//!   profile of any stack ([`incoherent::Profile`]); [`intensity`] the incoherent sum of intensities below
//!   [`stack`];
//! * [`field`]: amplitudes inside the stack, position-resolved flux / absorption / |E|², absorption per
//!   layer, ellipsometric ψ and Δ;
//! * [`jet`]: exact derivatives of R, T, ψ, Δ with respect to thicknesses and indices (forward-mode
//!   automatic differentiation through the same equations), for fitting;
//! * [`tmm`]: the calling convention of Byrnes' `tmm` package (index and thickness lists, `r`, `t`, `R`, `T`,
//!   `vw_list`, … with its conventions), for the Python drop-in `iridis.tmm`;
//! * [`sampling`]: warnings when a wavelength grid cannot resolve the fringes of a thick layer;
//! * [`color`]: film colours (reflected / transmitted spectrum → XYZ through `iridis-color`).
//! * [`htsg`]: the He–Torrance–Sillion–Greenberg BRDF of a rough interface (rms height σ, correlation
//!   length τ): specular and directional-diffuse terms, Smith shadowing, effective roughness, the bounded
//!   series of `D` (the thesis' "D-iterations");
//! * [`rough`]: the LSRS model (section 3.2, eq. 3.15–3.20, Algorithm 2) — a stack whose bottom interface is
//!   rough: composite specular `k_r` and diffuse `k_d` reflectances, tables with interpolation, eq. 3.20;
//!   [`rough_stack`] the rough stack and the optics above its rough interface, [`rough_multiple`] the light
//!   scattered more than once inside the film;
//! * [`table`] and [`rough_table`]: colour tables for rendering — a smooth film's reflected and transmitted
//!   XYZ over `cos θ` × thickness offset, a rough film's `k_r` and `π k_d` XYZ over angles, azimuth and offset —
//!   integrated over the spectrum in advance (the GPU's fast film path);
//! * [`spectral`]: wavelength grids with fewer samples and Sussenbach's sparse-sampling experiment
//!   (section 5.2.2); [`accuracy`]: CIEDE2000 between displayed colours and its statistics.
//!
//! Conventions (`docs/PHYSICS.md`): lengths in nanometres, angles in radians, `κ ≥ 0` absorbs, the incident
//! medium is lossless, and the transmittance into an absorbing substrate is zero.
//!
//! ```
//! use iridis_thinfilm::Stack;
//! let stack: Stack = "air | water 635nm | air".parse().unwrap();
//! let rta = stack.evaluate(400.0, 1f64.to_radians()).unwrap();
//! assert!((rta.r() - 0.0334109).abs() < 1e-6); // Sussenbach, Figure 3.8
//! assert!((rta.r() + rta.t() - 1.0).abs() < 1e-12);
//! ```

pub mod accuracy;
pub mod color;
pub mod depth;
pub mod error;
pub mod fast;
pub mod field;
pub mod grid;
pub mod htsg;
pub mod incoherent;
pub mod intensity;
pub mod jet;
pub mod library;
pub mod material;
pub mod nkfile;
pub mod recurrence;
pub mod rough;
pub mod rough_multiple;
pub mod rough_stack;
pub mod rough_table;
pub mod sampling;
pub mod spectral;
pub mod stack;
pub mod table;
pub mod tmm;

pub use error::ThinFilmError;
pub use fast::Prepared;
pub use material::Material;
pub use num_complex::Complex64;
pub use recurrence::{Amplitudes, Rta};
pub use stack::{Layer, Stack};
