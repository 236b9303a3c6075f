//! Stacks: incident medium | layers with thicknesses | substrate, and their evaluation.
//!
//! Syntax (one string, media separated by `|`):
//! ```text
//! air | water 635nm | air
//! air | gasoline 216nm | water 220nm | asphalt
//! air | n=1.38 100nm | n=0.2+3.4i
//! air | file:data/materials/au_johnson.yml 40nm | glass
//! ```
//! A medium is a library name ([`Material::builtin`]), `n=REAL` or `n=REAL+IMAGi` (κ ≥ 0), or
//! `file:PATH` (refractiveindex.info YAML or CSV). Each layer between the two ends carries a thickness with
//! a unit (`635nm`, `0.2um`); the ends carry none. Errors name the token and its column.
//!
//! A layer written `inc:MATERIAL THICKNESS` (`air | MgF2 100nm | inc:BK7 1mm | air`) is *incoherent*: thicker
//! than the light's coherence length, it adds intensities instead of amplitudes (a 1 mm glass slide), as
//! `tmm.inc_tmm` does (Byrnes, arXiv:1603.02720, section 5); see [`crate::incoherent`].

use std::str::FromStr;

use num_complex::Complex64;

use crate::error::ThinFilmError;
use crate::material::Material;
use crate::recurrence::{compose, layer_cosine, Amplitudes, Composite, Medium, Rta};

/// A layer: a material and its thickness in nm.
#[derive(Debug, Clone, PartialEq)]
pub struct Layer {
    pub material: Material,
    pub thickness_nm: f64,
    /// Written `inc:…`: intensities, not amplitudes, add across this layer ([`crate::incoherent`]).
    pub incoherent: bool,
}

/// A thin-film stack: a lossless incident medium, `N ≥ 0` layers (top first) and a substrate.
#[derive(Debug, Clone, PartialEq)]
pub struct Stack {
    pub incident: Material,
    pub layers: Vec<Layer>,
    pub substrate: Material,
}

/// The placeholder that marks the swept layer of `iridis thinfilm chart`.
pub const SWEEP_PLACEHOLDER: &str = "{d}";

struct Token<'a> {
    text: &'a str,
    column: usize, // 1-based, in characters
}

fn tokens(s: &str, seg_start: usize, seg: &str) -> Vec<(usize, usize)> {
    // (byte offset in s, byte length) of whitespace-separated words of a segment
    let mut out = Vec::new();
    let mut start = None;
    for (i, ch) in seg.char_indices() {
        if ch.is_whitespace() {
            if let Some(st) = start.take() {
                out.push((seg_start + st, i - st));
            }
        } else if start.is_none() {
            start = Some(i);
        }
    }
    if let Some(st) = start {
        out.push((seg_start + st, seg.len() - st));
    }
    let _ = s;
    out
}

impl Stack {
    /// Parses a stack (see the module documentation).
    pub fn parse(s: &str) -> Result<Self, ThinFilmError> {
        Ok(Self::parse_inner(s, false)?.0)
    }

    /// Parses a stack in which one layer's thickness is the placeholder `{d}` (set to 0 nm here); returns the
    /// stack and the index of that layer (0 = top layer).
    pub fn parse_sweep(s: &str) -> Result<(Self, usize), ThinFilmError> {
        let (stack, swept) = Self::parse_inner(s, true)?;
        match swept {
            Some(i) => Ok((stack, i)),
            None => Err(ThinFilmError::Stack {
                stack: s.to_string(),
                token: s.trim().to_string(),
                column: 1,
                message: format!("no layer has the thickness {SWEEP_PLACEHOLDER}, which marks the swept layer"),
                unreadable: false,
            }),
        }
    }

    fn parse_inner(s: &str, allow_sweep: bool) -> Result<(Self, Option<usize>), ThinFilmError> {
        let err = |tok: &Token, message: String| ThinFilmError::Stack {
            stack: s.to_string(),
            token: tok.text.to_string(),
            column: tok.column,
            message,
            unreadable: false,
        };
        let col = |byte: usize| s[..byte].chars().count() + 1;
        // Split on '|', keeping byte offsets.
        let mut segments: Vec<(usize, &str)> = Vec::new();
        let mut start = 0;
        for (i, ch) in s.char_indices() {
            if ch == '|' {
                segments.push((start, &s[start..i]));
                start = i + 1;
            }
        }
        segments.push((start, &s[start..]));
        if segments.len() < 2 {
            let t = Token { text: s.trim(), column: 1 };
            return Err(err(
                &t,
                "a stack needs at least an incident medium and a substrate separated by '|', e.g. \"air | water 635nm | air\"".into(),
            ));
        }
        // A '|' at either end leaves nothing for the incident medium or the substrate; said so here, before the
        // medium next to it would be read as a layer without a thickness.
        for (k, what, place) in [(segments.len() - 1, "substrate", "trailing"), (0, "incident medium", "leading")] {
            let (off, seg) = segments[k];
            if seg.trim().is_empty() {
                let bar = if k == 0 { off + seg.len() } else { off - 1 };
                let t = Token { text: "|", column: col(bar) };
                return Err(err(
                    &t,
                    format!(
                        "a {place} '|' with no {what} {}; remove it, or name the {what}",
                        if k == 0 { "before it" } else { "after it" }
                    ),
                ));
            }
        }
        let last = segments.len() - 1;
        let mut media: Vec<Material> = Vec::with_capacity(segments.len());
        let mut thicknesses = Vec::new();
        let mut incoherent = Vec::new();
        let mut swept = None;
        for (k, &(off, seg)) in segments.iter().enumerate() {
            let words = tokens(s, off, seg);
            let toks: Vec<Token> = words.iter().map(|&(b, l)| Token { text: &s[b..b + l], column: col(b) }).collect();
            let role = if k == 0 {
                "the incident medium"
            } else if k == last {
                "the substrate"
            } else {
                "a layer"
            };
            if toks.is_empty() {
                let t = Token { text: "|", column: col(if off > 0 { off - 1 } else { 0 }) };
                return Err(err(&t, format!("{role} is missing (empty between separators)")));
            }
            let is_layer = k != 0 && k != last;
            if is_layer {
                if toks.len() == 1 {
                    return Err(err(
                        &toks[0],
                        format!("layer {k} has no thickness; write e.g. '{} 100nm'", toks[0].text),
                    ));
                }
                if toks.len() > 2 {
                    return Err(err(
                        &toks[2],
                        format!("layer {k}: expected 'MATERIAL THICKNESS', found an extra word"),
                    ));
                }
                let t = &toks[1];
                let d = if t.text == SWEEP_PLACEHOLDER {
                    if !allow_sweep {
                        return Err(err(
                            t,
                            format!("{SWEEP_PLACEHOLDER} marks the swept layer of 'iridis thinfilm chart' only"),
                        ));
                    }
                    if swept.is_some() {
                        return Err(err(t, format!("only one layer may have the thickness {SWEEP_PLACEHOLDER}")));
                    }
                    swept = Some(k - 1);
                    0.0
                } else {
                    let d = iridis_color::units::parse_length_nm(t.text)
                        .map_err(|e| err(t, format!("bad thickness: {}", e.0)))?;
                    if d < 0.0 {
                        return Err(err(t, "thickness must not be negative".into()));
                    }
                    d
                };
                thicknesses.push(d);
            } else if toks.len() > 1 {
                return Err(err(
                    &toks[1],
                    format!("{role} is semi-infinite and takes no thickness (a missing '|' between media?)"),
                ));
            }
            let (inc, name) = match toks[0].text.strip_prefix("inc:") {
                Some(rest) => (true, rest),
                None => (false, toks[0].text),
            };
            if inc && !is_layer {
                return Err(err(
                    &toks[0],
                    format!(
                        "{role} is semi-infinite, so already incoherent: 'inc:' marks a finite layer between \
                         the ends, e.g. \"air | MgF2 100nm | inc:BK7 1mm | air\" for a coated 1 mm slide"
                    ),
                ));
            }
            if inc && name.is_empty() {
                return Err(err(&toks[0], "inc: needs a material, e.g. inc:BK7 1mm".into()));
            }
            if is_layer {
                incoherent.push(inc);
            }
            let m = crate::library::parse_material(name).map_err(|e| {
                let io = matches!(e, ThinFilmError::Unreadable { .. });
                let message = match e {
                    ThinFilmError::Invalid(m) => m,
                    other => other.to_string(),
                };
                let mut e = err(&toks[0], message);
                if let ThinFilmError::Stack { unreadable, .. } = &mut e {
                    *unreadable = io;
                }
                e
            })?;
            if k == 0 {
                if let crate::material::Part::Const(kappa) = m.k {
                    if kappa > 0.0 {
                        return Err(err(&toks[0], format!("the incident medium must be lossless (κ = {kappa} > 0)")));
                    }
                }
            }
            media.push(m);
        }
        let substrate = media.pop().expect("at least two media");
        let mut it = media.into_iter();
        let incident = it.next().expect("at least two media");
        let layers = it
            .zip(thicknesses)
            .zip(incoherent)
            .map(|((material, thickness_nm), incoherent)| Layer { material, thickness_nm, incoherent })
            .collect();
        Ok((Self { incident, layers, substrate }, swept))
    }

    /// The media from top to bottom: incident, layers, substrate.
    pub fn materials(&self) -> impl Iterator<Item = &Material> {
        std::iter::once(&self.incident)
            .chain(self.layers.iter().map(|l| &l.material))
            .chain(std::iter::once(&self.substrate))
    }

    /// The layer thicknesses in nm, top first.
    pub fn thicknesses(&self) -> Vec<f64> {
        self.layers.iter().map(|l| l.thickness_nm).collect()
    }

    /// True when some layer is incoherent (`inc:`): R and T then come from [`crate::incoherent`].
    pub fn has_incoherent(&self) -> bool {
        self.layers.iter().any(|l| l.incoherent)
    }

    /// True when no material depends on wavelength (the chapter 4 fast path then precomputes everything).
    pub fn is_wavelength_invariant(&self) -> bool {
        self.materials().all(Material::is_constant)
    }

    /// The wavelengths (nm) at which every material has data.
    pub fn range_nm(&self) -> (f64, f64) {
        self.materials().fold((0.0f64, f64::INFINITY), |(lo, hi), m| (lo.max(m.range_nm().0), hi.min(m.range_nm().1)))
    }

    /// The `N + 2` media at one wavelength and incidence angle (checks λ, θ and the incident medium).
    pub fn media(&self, wavelength_nm: f64, angle_rad: f64) -> Result<Vec<Medium>, ThinFilmError> {
        check_angle(angle_rad)?;
        let n0 = self.incident.index_at(wavelength_nm).map_err(|e| self.place(e, 0))?;
        if n0.im > 0.0 {
            return Err(ThinFilmError::AbsorbingIncident {
                material: self.incident.name().to_string(),
                origin: self.incident.library_source().unwrap_or_default(),
                kappa: n0.im,
                wavelength_nm,
            });
        }
        let s = n0.re * angle_rad.min(std::f64::consts::FRAC_PI_2).sin();
        let mut media = Vec::with_capacity(self.layers.len() + 2);
        media.push(Medium { n: n0, cos: Complex64::new(angle_rad.min(std::f64::consts::FRAC_PI_2).cos(), 0.0) });
        for (i, l) in self.layers.iter().enumerate() {
            let n = l.material.index_at(wavelength_nm).map_err(|e| self.place(e, i + 1))?;
            media.push(Medium { n, cos: layer_cosine(s, n) });
        }
        let last = self.layers.len() + 1;
        media.push(Medium::new(self.substrate.index_at(wavelength_nm).map_err(|e| self.place(e, last))?, s));
        Ok(media)
    }

    /// Names the place of medium `i` (0 = incident, 1..=N layers, N + 1 = substrate) in an out-of-range error.
    pub(crate) fn place(&self, e: ThinFilmError, i: usize) -> ThinFilmError {
        match e {
            ThinFilmError::OutOfRange { material, wavelength_nm, lo_nm, hi_nm, .. } => {
                let n = self.layers.len();
                let place = match i {
                    0 => "incident medium".to_string(),
                    i if i > n => "substrate".to_string(),
                    i => format!("layer {i} of {n}"),
                };
                ThinFilmError::OutOfRange { material, place, wavelength_nm, lo_nm, hi_nm }
            }
            e => e,
        }
    }

    /// Complex amplitude coefficients `r_s, r_p, t_s, t_p` at one wavelength (nm) and incidence angle (rad).
    pub fn amplitudes(&self, wavelength_nm: f64, angle_rad: f64) -> Result<Amplitudes, ThinFilmError> {
        self.amplitudes_with(wavelength_nm, angle_rad, &self.thicknesses(), None)
    }

    /// Amplitudes with other layer thicknesses (nm, one per layer) and optionally a replaced bottom seed
    /// (eq. 3.3–3.4; the LSRS model's eq. 3.16).
    pub fn amplitudes_with(
        &self,
        wavelength_nm: f64,
        angle_rad: f64,
        thicknesses_nm: &[f64],
        seed: Option<Composite>,
    ) -> Result<Amplitudes, ThinFilmError> {
        if thicknesses_nm.len() != self.layers.len() {
            return Err(ThinFilmError::Invalid(format!(
                "{} thicknesses given for {} layers",
                thicknesses_nm.len(),
                self.layers.len()
            )));
        }
        if let Some(d) = thicknesses_nm.iter().find(|d| !(d.is_finite() && **d >= 0.0)) {
            return Err(ThinFilmError::Invalid(format!("thickness {d} nm must be finite and ≥ 0")));
        }
        if self.has_incoherent() {
            return Err(ThinFilmError::Invalid(format!(
                "\"{self}\" has an incoherent (inc:) layer: it has intensities, not amplitudes (no r, t, ψ, Δ)"
            )));
        }
        let media = self.media(wavelength_nm, angle_rad)?;
        let c = compose(&media, thicknesses_nm, wavelength_nm, seed);
        Ok(Amplitudes::new(c, media[0], media[media.len() - 1]))
    }

    /// Reflectance and transmittance (s, p; `r()`, `t()`, `a()` unpolarised) at one wavelength (nm) and
    /// incidence angle (rad, 0 to π/2).
    /// Stacks with incoherent (`inc:`) layers are evaluated by [`crate::incoherent::evaluate`].
    pub fn evaluate(&self, wavelength_nm: f64, angle_rad: f64) -> Result<Rta, ThinFilmError> {
        if self.has_incoherent() {
            return evaluate_incoherent(self, wavelength_nm, angle_rad, &self.thicknesses());
        }
        Ok(self.amplitudes(wavelength_nm, angle_rad)?.powers())
    }

    /// Refuses thicknesses that are not one finite value ≥ 0 per layer.
    pub(crate) fn check_thicknesses(&self, thicknesses_nm: &[f64]) -> Result<(), ThinFilmError> {
        if thicknesses_nm.len() != self.layers.len() || thicknesses_nm.iter().any(|d| !(d.is_finite() && *d >= 0.0)) {
            return Err(ThinFilmError::Invalid(format!(
                "need {} finite thicknesses ≥ 0, got {thicknesses_nm:?}",
                self.layers.len()
            )));
        }
        Ok(())
    }

    /// Spatially varying thickness (Sussenbach eq. 4.3): every layer's thickness plus `offset_nm`
    /// (`d = d_avg + d_rel Δ_rel(x)`, so `offset_nm = d_rel Δ_rel(x)`), clamped at 0.
    pub fn evaluate_offset(&self, wavelength_nm: f64, angle_rad: f64, offset_nm: f64) -> Result<Rta, ThinFilmError> {
        let d: Vec<f64> = self.layers.iter().map(|l| (l.thickness_nm + offset_nm).max(0.0)).collect();
        if self.has_incoherent() {
            return evaluate_incoherent(self, wavelength_nm, angle_rad, &d);
        }
        Ok(self.amplitudes_with(wavelength_nm, angle_rad, &d, None)?.powers())
    }

    /// A copy with one layer's thickness replaced.
    pub fn with_thickness(&self, layer: usize, thickness_nm: f64) -> Self {
        let mut s = self.clone();
        if let Some(l) = s.layers.get_mut(layer) {
            l.thickness_nm = thickness_nm;
        }
        s
    }
}

/// The SVT offset from a grey value `α ∈ [0, 1]` (Sussenbach eq. 4.4, `Δ_rel = α/0.5 − 1`, and eq. 4.3):
/// `d_rel · (2α − 1)`.
pub fn svt_offset(d_rel_nm: f64, alpha: f64) -> f64 {
    d_rel_nm * (alpha / 0.5 - 1.0)
}

pub(crate) fn check_angle(angle_rad: f64) -> Result<(), ThinFilmError> {
    if !(angle_rad.is_finite() && (-1e-12..=std::f64::consts::FRAC_PI_2 + 1e-12).contains(&angle_rad)) {
        return Err(ThinFilmError::Invalid(format!(
            "incidence angle {}° is outside 0°–90°",
            (angle_rad.to_degrees() * 1e6).round() / 1e6
        )));
    }
    Ok(())
}

impl FromStr for Stack {
    type Err = ThinFilmError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Stack::parse(s)
    }
}

impl std::fmt::Display for Stack {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}", self.incident.name())?;
        for l in &self.layers {
            let inc = if l.incoherent { "inc:" } else { "" };
            write!(f, " | {inc}{} {}nm", l.material.name(), l.thickness_nm)?;
        }
        write!(f, " | {}", self.substrate.name())
    }
}

/// Reflectance and transmittance of a stack with incoherent layers (any stack: a coherent one gives the
/// powers of [`Stack::evaluate`]), with the given layer thicknesses ([`crate::intensity`]). As everywhere in
/// iridis, T into an absorbing substrate is 0 (the light entering it is absorbed; `docs/PHYSICS.md`).
pub fn evaluate_incoherent(
    stack: &Stack,
    wavelength_nm: f64,
    angle_rad: f64,
    thicknesses_nm: &[f64],
) -> Result<Rta, ThinFilmError> {
    stack.check_thicknesses(thicknesses_nm)?;
    let media = stack.media(wavelength_nm, angle_rad)?;
    Ok(crate::intensity::rta(&media, thicknesses_nm, &incoherent_media(stack), wavelength_nm))
}

/// The indices (into the `N + 2` media) of the incoherent media: 0, every `inc:` layer, `N + 1`.
pub fn incoherent_media(stack: &Stack) -> Vec<usize> {
    let mut v = vec![0];
    v.extend(stack.layers.iter().enumerate().filter(|(_, l)| l.incoherent).map(|(i, _)| i + 1));
    v.push(stack.layers.len() + 1);
    v
}

#[cfg(test)]
mod tests {
    use super::*;

    fn column_of(e: ThinFilmError) -> (String, usize, String) {
        match e {
            ThinFilmError::Stack { token, column, message, .. } => (token, column, message),
            other => panic!("expected a stack error, got {other}"),
        }
    }

    #[test]
    fn parses_the_issue_examples() {
        let s = Stack::parse("air | water 635nm | air").unwrap();
        assert_eq!(s.layers.len(), 1);
        assert_eq!(s.layers[0].thickness_nm, 635.0);
        let s = Stack::parse("air | gasoline 216nm | water 220nm | asphalt").unwrap();
        assert_eq!(s.thicknesses(), vec![216.0, 220.0]);
        let s: Stack = "air | n=1.38 0.1um | n=0.2+3.4i".parse().unwrap();
        assert_eq!(s.substrate.index_at(500.0).unwrap(), Complex64::new(0.2, 3.4));
        assert!((s.layers[0].thickness_nm - 100.0).abs() < 1e-9);
        assert!(Stack::parse("air | Si 108nm | glass").is_ok());
        assert!(Stack::parse("glass|air").unwrap().layers.is_empty());
        // Cauchy n = A + B/λ² (λ in µm) and Sellmeier n² = 1 + B λ²/(λ² − C).
        let s = Stack::parse("air | cauchy:1.45,0.0036 100nm | sellmeier:1.2,0.01").unwrap();
        let n = s.layers[0].material.index_at(600.0).unwrap().re;
        assert!((n - (1.45 + 0.0036 / 0.36)).abs() < 1e-14);
        let n = s.substrate.index_at(500.0).unwrap().re;
        assert!((n - (1.0f64 + 1.2 * 0.25 / (0.25 - 0.01)).sqrt()).abs() < 1e-14);
        assert!(Stack::parse("air | cauchy:1.4,x 10nm | air").is_err());
        assert!(Stack::parse("air | sellmeier:1.2 10nm | air").is_err());
    }

    #[test]
    fn errors_name_token_and_column() {
        let (t, c, m) = column_of(Stack::parse("air | wter 635nm | air").unwrap_err());
        assert_eq!((t.as_str(), c), ("wter", 7));
        assert!(m.contains("unknown material"));
        let (t, c, _) = column_of(Stack::parse("air | water | air").unwrap_err());
        assert_eq!((t.as_str(), c), ("water", 7));
        let (t, c, m) = column_of(Stack::parse("air | water -5nm | air").unwrap_err());
        assert_eq!((t.as_str(), c), ("-5nm", 13));
        assert!(m.contains("negative"));
        let (t, _, m) = column_of(Stack::parse("air | water 635 | air").unwrap_err());
        assert_eq!(t, "635");
        assert!(m.contains("unit"), "{m}");
        let (t, c, m) = column_of(Stack::parse("air | n=1.5-0.1i 10nm | air").unwrap_err());
        assert_eq!((t.as_str(), c), ("n=1.5-0.1i", 7));
        assert!(m.contains("κ"), "{m}");
        let (t, c, m) = column_of(Stack::parse("n=1+0.1i | water 10nm | air").unwrap_err());
        assert_eq!((t.as_str(), c), ("n=1+0.1i", 1));
        assert!(m.contains("lossless"), "{m}");
        let (_, _, m) = column_of(Stack::parse("air | | air").unwrap_err());
        assert!(m.contains("missing"), "{m}");
        // A trailing or leading '|' is named as such, not as the medium beside it lacking a thickness.
        let (t, c, m) = column_of(Stack::parse("air | water 348nm | air |").unwrap_err());
        assert_eq!((t.as_str(), c), ("|", 25));
        assert!(m.contains("trailing '|' with no substrate") && !m.contains("thickness"), "{m}");
        let (_, c, m) = column_of(Stack::parse(" | air | water 348nm | air").unwrap_err());
        assert_eq!(c, 2);
        assert!(m.contains("leading '|' with no incident medium"), "{m}");
        let (t, _, _) = column_of(Stack::parse("air 5nm | air").unwrap_err());
        assert_eq!(t, "5nm");
        let (t, c, m) = column_of(Stack::parse("air | file:/nonexistent/x.yml 5nm | air").unwrap_err());
        assert_eq!((t.as_str(), c), ("file:/nonexistent/x.yml", 7));
        // A file that cannot be opened is marked so (Python raises OSError); a misspelt material is not.
        let unreadable = |s: &str| matches!(Stack::parse(s), Err(ThinFilmError::Stack { unreadable: true, .. }));
        assert!(unreadable("air | file:/nonexistent/x.yml 5nm | air") && !unreadable("air | wter 5nm | air"));
        assert!(m.contains("cannot read"), "{m}");
        assert!(Stack::parse("air").is_err());
        // Multi-byte characters before the token: the column counts characters.
        let (_, c, _) = column_of(Stack::parse("air | water 1µm | wäter").unwrap_err());
        assert_eq!(c, 19);
    }

    #[test]
    fn incoherent_layers() {
        let s = Stack::parse("air | MgF2 100nm | inc:BK7 1mm | air").unwrap();
        assert_eq!(s.layers.iter().map(|l| l.incoherent).collect::<Vec<_>>(), [false, true]);
        assert_eq!(s.layers[1].thickness_nm, 1e6);
        assert!(s.to_string().contains("inc:bk7 1000000nm"), "{s}");
        assert!(s.amplitudes(550.0, 0.0).is_err() && s.prepare(0.0).is_err());
        let (t, c, m) = column_of(Stack::parse("inc:air | BK7 1mm | air").unwrap_err());
        assert_eq!((t.as_str(), c), ("inc:air", 1));
        assert!(m.contains("incident medium is semi-infinite, so already incoherent"), "{m}");
        let (t, _, m) = column_of(Stack::parse("air | water 1um | inc:glass").unwrap_err());
        assert_eq!(t, "inc:glass");
        assert!(m.contains("substrate is semi-infinite"), "{m}");
        let (_, _, m) = column_of(Stack::parse("air | inc: 1mm | air").unwrap_err());
        assert!(m.contains("inc: needs a material"), "{m}");
    }

    #[test]
    fn sweep_placeholder() {
        let (s, i) = Stack::parse_sweep("air | gasoline 216nm | water {d} | asphalt").unwrap();
        assert_eq!((i, s.layers.len()), (1, 2));
        assert!(Stack::parse("air | water {d} | air").is_err());
        assert!(Stack::parse_sweep("air | water 5nm | air").is_err());
    }

    #[test]
    fn out_of_range_wavelength_is_an_error() {
        let s = Stack::parse("air | Si 108nm | glass").unwrap();
        assert!(matches!(s.evaluate(900.0, 0.0), Err(ThinFilmError::OutOfRange { .. })));
        assert!(s.evaluate(500.0, 1.7).is_err());
        assert!(s.evaluate(-1.0, 0.0).is_err());
    }

    #[test]
    fn out_of_range_names_the_layer_and_the_data_range() {
        // Aspnes & Studna Si: 206.6–826.6 nm (data/materials/si_aspnes.yml); Au (Johnson & Christy) from 187.9 nm.
        let s = Stack::parse("air | water 100nm | Si 108nm | glass").unwrap();
        let e = s.evaluate(900.0, 0.0).unwrap_err().to_string();
        assert!(e.starts_with("layer 2 of 2: material 'si' has data for 206.6–826.6 nm only; 900 nm"), "{e}");
        let e = Stack::parse("air | water 100nm | Au").unwrap().evaluate(150.0, 0.0).unwrap_err().to_string();
        assert!(e.starts_with("substrate: material 'au' has data for 187.9"), "{e}");
        let e = Stack::parse("Si | air 100nm | glass").unwrap().evaluate(150.0, 0.0).unwrap_err().to_string();
        assert!(e.starts_with("incident medium: material 'si'"), "{e}");
    }

    #[test]
    fn absorbing_library_incident_medium_says_which_and_why() {
        let e = Stack::parse("Au | water 100nm | glass").unwrap().evaluate(550.0, 0.0).unwrap_err();
        assert!(matches!(e, ThinFilmError::AbsorbingIncident { .. }));
        let e = e.to_string();
        for needle in [
            "incident medium 'au' (gold, Johnson & Christy 1972",
            "from the built-in library",
            "κ = ",
            "lossless",
            "air | au 40nm | glass",
        ] {
            assert!(e.contains(needle), "'{e}' lacks '{needle}'");
        }
        // An absorbing constant is refused when the stack is read, before any wavelength.
        let e = Stack::parse("n=1.5+0.1i | glass").unwrap_err().to_string();
        assert!(e.contains("the incident medium must be lossless (κ = 0.1 > 0)"), "{e}");
    }

    #[test]
    fn svt_offset_matches_eq_4_4() {
        assert_eq!(svt_offset(95.0, 0.0), -95.0);
        assert_eq!(svt_offset(95.0, 1.0), 95.0);
        assert_eq!(svt_offset(95.0, 0.5), 0.0);
    }
}
