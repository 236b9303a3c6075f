//! The one error type of the crate: every message names what was wrong, and where.

/// Everything that can go wrong with thin-film input or evaluation. Messages are written for people.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ThinFilmError {
    /// A stack string that cannot be read: the offending token and its 1-based character column; `unreadable`
    /// where the token is a `file:` material whose file cannot be opened (an I/O error, not the stack's syntax).
    #[error("stack \"{stack}\": {message} (token '{token}' at column {column})")]
    Stack { stack: String, token: String, column: usize, message: String, unreadable: bool },
    /// A file that cannot be opened or read at all (missing, a directory, no permission): an I/O error.
    #[error("{path}: cannot read: {message}")]
    Unreadable { path: String, message: String },
    /// A refractive-index file whose content cannot be read; `line` is 1-based when known.
    #[error("{path}{}: {message}", .line.map(|l| format!(", line {l}")).unwrap_or_default())]
    File { path: String, line: Option<usize>, message: String },
    /// A wavelength outside the data of a material: never extrapolated. `place` says where the material is
    /// in a stack ("layer 2 of 3", "incident medium", "substrate"); it is empty for a material on its own.
    #[error(
        "{}material '{material}' has data for {lo_nm}–{hi_nm} nm only; {wavelength_nm} nm is outside (no extrapolation){}",
        prefix(place),
        micrometre_hint(*hi_nm, *wavelength_nm)
    )]
    OutOfRange { material: String, place: String, wavelength_nm: f64, lo_nm: f64, hi_nm: f64 },
    /// The incident medium must be lossless (Sussenbach, section 3.4, constraint 6): in an absorbing medium
    /// the incident wave decays, so neither its angle nor the reflectance relative to it is defined.
    /// `origin` describes a library material ("gold, Johnson & Christy 1972, …"), else it is empty.
    #[error(
        "incident medium '{material}'{} absorbs (κ = {kappa:.4} at {wavelength_nm} nm), but light must arrive \
         through a lossless medium: in an absorbing one the incident wave decays, so its angle and the \
         reflectance are not defined (Sussenbach 3.4, constraint 6). Put '{material}' below a lossless \
         medium, e.g. \"air | {material} 40nm | glass\"",
        in_parens(origin)
    )]
    AbsorbingIncident { material: String, origin: String, kappa: f64, wavelength_nm: f64 },
    /// Any other invalid argument (a wavelength ≤ 0, an angle outside 0°–90°, …).
    #[error("{0}")]
    Invalid(String),
}

/// Data ending under 20 nm asked at 100 nm or more: a table in µm read as nm (refractiveindex.info's CSV `wl`
/// is in µm), said with the remedy.
fn micrometre_hint(hi_nm: f64, wavelength_nm: f64) -> &'static str {
    if hi_nm < 20.0 && wavelength_nm >= 100.0 {
        "; its wavelengths look like µm: name the first column wavelength_um (or write them in nm)"
    } else {
        ""
    }
}

fn prefix(place: &str) -> String {
    if place.is_empty() {
        String::new()
    } else {
        format!("{place}: ")
    }
}

fn in_parens(source: &str) -> String {
    if source.is_empty() {
        String::new()
    } else {
        format!(" ({source})")
    }
}
