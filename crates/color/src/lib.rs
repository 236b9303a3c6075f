//! # iridis-color
//!
//! The pipeline every part of iridis ends in: sampled spectra → CIE XYZ → linear sRGB or CIELAB → pixels.
//!
//! * [`spectrum`]: sampled spectra on any wavelength grid (resampling, trapezoidal integration, CSV input);
//! * [`cie`]: the CIE 1931 2° and 1964 10° observers and the illuminants D65, D50, A and E (data in
//!   `data/cie/`, provenance in `tools/gen_cie_data.py`);
//! * [`integrate`]: spectrum → XYZ, normalised so that a perfect reflector has `Y = 1`;
//! * [`convert`]: XYZ ↔ xyY, XYZ ↔ linear sRGB (IEC 61966-2-1), the sRGB transfer curve, plain gamma;
//! * [`lab`]: XYZ ↔ CIELAB and the colour differences ΔE*ab (1976) and CIEDE2000;
//! * [`tonemap`]: exposure in relative units (RU) and encoding to 8-bit pixels;
//! * [`units`]: the one parser of lengths and angles typed by people (`65nm`, `0.43um`, `75deg`);
//! * [`names`](mod@names): [`names!`], the names of an enum's variants (canonical name and aliases) read both ways, and
//!   with an `else` clause their `FromStr`.
//!
//! All lengths are nanometres, all angles radians (see `docs/PHYSICS.md`).

pub mod cie;
pub mod convert;
pub mod integrate;
pub mod lab;
pub mod names;
pub mod spectrum;
pub mod tonemap;
pub mod units;

pub use cie::{Illuminant, Observer};
pub use convert::{Xyy, Xyz};
pub use integrate::SpectralWeights;
pub use lab::Lab;
pub use spectrum::{Spectrum, SpectrumError};
pub use tonemap::{Encoding, ToneMap};
