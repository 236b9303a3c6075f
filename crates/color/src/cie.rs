//! CIE standard observers and illuminants, read from the tables in `data/cie/` (see
//! `tools/gen_cie_data.py` for their provenance) and parsed once on first use.

use std::fmt;
use std::sync::OnceLock;

use crate::spectrum::Spectrum;

/// A CIE standard colorimetric observer.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub enum Observer {
    /// CIE 1931 2° standard observer.
    #[default]
    Cie1931,
    /// CIE 1964 10° supplementary standard observer.
    Cie1964,
}

/// A CIE illuminant (relative spectral power distribution).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub enum Illuminant {
    #[default]
    D65,
    D50,
    A,
    E,
}

/// The colour-matching functions x̄, ȳ, z̄ of an observer, 360–830 nm at 1 nm.
#[derive(Debug, Clone)]
pub struct Cmfs {
    pub wavelengths_nm: Vec<f64>,
    pub x: Vec<f64>,
    pub y: Vec<f64>,
    pub z: Vec<f64>,
}

impl Cmfs {
    /// (x̄, ȳ, z̄) at any wavelength, linear between the 1 nm samples and zero outside 360–830 nm.
    pub fn at(&self, wavelength_nm: f64) -> [f64; 3] {
        let (lo, hi) = (self.wavelengths_nm[0], self.wavelengths_nm[self.wavelengths_nm.len() - 1]);
        if !(lo..=hi).contains(&wavelength_nm) {
            return [0.0; 3];
        }
        let f = |v: &[f64]| crate::spectrum::interpolate_linear(&self.wavelengths_nm, v, wavelength_nm);
        [f(&self.x), f(&self.y), f(&self.z)]
    }
}

fn parse_table(text: &str, columns: usize) -> Vec<Vec<f64>> {
    // The tables are part of the build (include_str!), so a malformed one is a programming error that the
    // unit tests catch.
    let mut out = vec![Vec::new(); columns];
    for line in text.lines().filter(|l| !l.starts_with('#')).skip(1) {
        for (col, field) in out.iter_mut().zip(line.split(',')) {
            col.push(field.trim().parse::<f64>().expect("malformed built-in CIE table"));
        }
    }
    out
}

impl Observer {
    pub const ALL: [Observer; 2] = [Observer::Cie1931, Observer::Cie1964];

    /// The observer's colour-matching functions.
    pub fn cmfs(self) -> &'static Cmfs {
        static C1931: OnceLock<Cmfs> = OnceLock::new();
        static C1964: OnceLock<Cmfs> = OnceLock::new();
        let (cell, text) = match self {
            Observer::Cie1931 => (&C1931, include_str!("../../../data/cie/cie1931_2deg.csv")),
            Observer::Cie1964 => (&C1964, include_str!("../../../data/cie/cie1964_10deg.csv")),
        };
        cell.get_or_init(|| {
            let mut t = parse_table(text, 4);
            let z = t.pop().unwrap_or_default();
            let y = t.pop().unwrap_or_default();
            let x = t.pop().unwrap_or_default();
            let w = t.pop().unwrap_or_default();
            Cmfs { wavelengths_nm: w, x, y, z }
        })
    }

    /// The range the observer's colour-matching functions are tabulated over, 360–830 nm. They are zero
    /// outside it: a spectrum may start lower (at 300 nm, where the CIE tabulates D65 and animals' catches
    /// begin), but what lies below 360 nm takes no part in XYZ.
    pub fn range_nm(self) -> (f64, f64) {
        let w = &self.cmfs().wavelengths_nm;
        (w[0], w[w.len() - 1])
    }
}

impl Illuminant {
    pub const ALL: [Illuminant; 4] = [Illuminant::D65, Illuminant::D50, Illuminant::A, Illuminant::E];

    /// The relative spectral power distribution, as tabulated (5 nm for D65/D50/E, 1 nm for A, 300–830 nm).
    pub fn spd(self) -> &'static Spectrum {
        static CELLS: [OnceLock<Spectrum>; 4] = [OnceLock::new(), OnceLock::new(), OnceLock::new(), OnceLock::new()];
        let (i, text) = match self {
            Illuminant::D65 => (0, include_str!("../../../data/cie/d65.csv")),
            Illuminant::D50 => (1, include_str!("../../../data/cie/d50.csv")),
            Illuminant::A => (2, include_str!("../../../data/cie/a.csv")),
            Illuminant::E => (3, include_str!("../../../data/cie/e.csv")),
        };
        CELLS[i].get_or_init(|| {
            let mut t = parse_table(text, 2);
            let v = t.pop().unwrap_or_default();
            let w = t.pop().unwrap_or_default();
            Spectrum::new(w, v).expect("malformed built-in illuminant table")
        })
    }
}

/// An observer or illuminant name that is not known.
#[derive(Debug, Clone, thiserror::Error)]
#[error("unknown {kind} '{given}'; expected one of: {expected}")]
pub struct UnknownName {
    pub kind: &'static str,
    pub given: String,
    pub expected: &'static str,
}

crate::names! {
    Observer {
        Cie1931 => "1931" | "2" | "2deg" | "cie1931",
        Cie1964 => "1964" | "10" | "10deg" | "cie1964",
    }
    else |s| -> UnknownName { UnknownName { kind: "observer", given: s.into(), expected: "1931, 1964" } }
}

crate::names! {
    Illuminant {
        D65 => "D65",
        D50 => "D50",
        A => "A",
        E => "E",
    }
    else |s| -> UnknownName { UnknownName { kind: "illuminant", given: s.into(), expected: "d65, d50, a, e" } }
}

impl fmt::Display for Observer {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}
impl fmt::Display for Illuminant {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}
