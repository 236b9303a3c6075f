//! # iridis-vision
//!
//! Colours as animals see them: from reflectance spectra to what a bird, a bee, a snake or a person can tell
//! apart, with the models biologists use (those of R's `pavo` and `colourvision`):
//!
//! * [`template`]: photoreceptor sensitivities from λmax (Govardovskii et al. 2000, A1/A2, α and β bands)
//!   and oil-droplet filters (Hart & Vorobyev 2005);
//! * [`system`]: visual systems as data with provenance (`data/vision/`, sources in its README): human
//!   cones, the average avian UV and V systems, the blue tit, the honeybee, the ball python; custom systems
//!   from λmax values or a table of sensitivities;
//! * [`light`]: illuminants in photon flux (CIE D65, D50, A, E; Endler's 1993 blue sky and forest shade) and
//!   backgrounds for von Kries adaptation;
//! * [`noise`]: the receptor noise of a visual system (Weber fractions, receptor densities);
//! * [`model`]: quantum catches, von Kries adaptation, the receptor-noise-limited colour distance ΔS and the
//!   achromatic distance ΔL in JND (Vorobyev & Osorio 1998), colour-space coordinates ([`space`]);
//!   [`analyse`] is the one call from spectra to a serialisable [`Analysis`];
//! * [`table`]: sampled curves and the spectra CSV that pavo reads and writes (a wavelength column, one
//!   column per sample).
//!
//! Wavelengths are in nm; photon flux and sensitivities are relative (see `docs/vision.md`).

pub mod light;
pub mod model;
pub mod noise;
pub mod space;
pub mod spec;
pub mod system;
pub mod table;
pub mod template;

pub use light::{Background, Light, LightUnits};
pub use model::{
    analyse, analyse_table, AchromaticChoice, Analysis, Distance, NoiseModel, Options, ReceptorNoise, Sample,
};
pub use space::Space;
pub use spec::Spec;
pub use system::{Achromatic, Receptor, VisualSystem};
pub use table::{Curve, SpectraTable};
pub use template::{Chromophore, Droplet, DropletType};

/// Why a visual model could not be built or evaluated. The messages name the value and what was expected.
#[derive(Debug, thiserror::Error)]
pub enum VisionError {
    #[error("{0}")]
    Invalid(String),
    #[error("{source_name}: cannot read: {message}")]
    Io { source_name: String, message: String },
    #[error("{source_name}:{line}: {message}")]
    Parse { source_name: String, line: usize, message: String },
}

impl VisionError {
    pub(crate) fn invalid(message: impl Into<String>) -> Self {
        VisionError::Invalid(message.into())
    }
}
