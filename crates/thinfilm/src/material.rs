//! Materials: a complex refractive index `n̂(λ) = n(λ) + iκ(λ)` (Sussenbach eq. 3.5 uses `n̂ = n + ik`).
//!
//! A material is a constant, a dispersion formula, or a table; tables are interpolated linearly in λ, and a
//! wavelength outside the data is an error ([`ThinFilmError::OutOfRange`]), never a silent extrapolation.

use num_complex::Complex64;

use crate::error::ThinFilmError;
use crate::nkfile;

/// One part (n or κ) of a refractive index.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Part {
    /// The same value at every wavelength.
    Const(f64),
    /// Linear interpolation in a table (wavelengths in nm, strictly increasing).
    Table { wl_nm: Vec<f64>, v: Vec<f64> },
    /// A refractiveindex.info dispersion formula (`kind` 1–9, coefficients for λ in µm).
    Formula { kind: u8, c: Vec<f64> },
}

impl Part {
    fn eval(&self, wavelength_nm: f64) -> f64 {
        match self {
            Part::Const(v) => *v,
            Part::Table { wl_nm, v } => interpolate(wl_nm, v, wavelength_nm),
            Part::Formula { kind, c } => formula(*kind, c, wavelength_nm / 1000.0),
        }
    }
}

/// Linear interpolation; `x` is inside `[xs[0], xs[last]]` (checked by the caller).
fn interpolate(xs: &[f64], ys: &[f64], x: f64) -> f64 {
    if xs.len() == 1 {
        return ys[0];
    }
    let i = xs.partition_point(|&w| w <= x).clamp(1, xs.len() - 1);
    let (x0, x1, y0, y1) = (xs[i - 1], xs[i], ys[i - 1], ys[i]);
    let t = ((x - x0) / (x1 - x0)).clamp(0.0, 1.0);
    y0 + t * (y1 - y0)
}

/// The dispersion formulas of the refractiveindex.info database (its `formula 1` … `formula 9`), λ in µm.
/// Returns n. Coefficients missing from the file count as zero.
pub(crate) fn formula(kind: u8, c: &[f64], l: f64) -> f64 {
    let k = |i: usize| c.get(i).copied().unwrap_or(0.0);
    let l2 = l * l;
    match kind {
        // 1 Sellmeier: n² − 1 = C1 + Σ C_i λ² / (λ² − C_{i+1}²)
        1 => {
            let mut s = 1.0 + k(0);
            let mut i = 1;
            while i + 1 < c.len() {
                s += k(i) * l2 / (l2 - k(i + 1) * k(i + 1));
                i += 2;
            }
            s.sqrt()
        }
        // 2 Sellmeier-2: n² − 1 = C1 + Σ C_i λ² / (λ² − C_{i+1})
        2 => {
            let mut s = 1.0 + k(0);
            let mut i = 1;
            while i + 1 < c.len() {
                s += k(i) * l2 / (l2 - k(i + 1));
                i += 2;
            }
            s.sqrt()
        }
        // 3 Polynomial: n² = C1 + Σ C_i λ^C_{i+1}
        3 => {
            let mut s = k(0);
            let mut i = 1;
            while i + 1 < c.len() {
                s += k(i) * l.powf(k(i + 1));
                i += 2;
            }
            s.sqrt()
        }
        // 4 RefractiveIndex.INFO: n² = C1 + C2 λ^C3/(λ² − C4^C5) + C6 λ^C7/(λ² − C8^C9) + Σ_{i≥10} C_i λ^C_{i+1}
        4 => {
            let mut s = k(0);
            if c.len() > 1 {
                s += k(1) * l.powf(k(2)) / (l2 - k(3).powf(k(4)));
            }
            if c.len() > 5 {
                s += k(5) * l.powf(k(6)) / (l2 - k(7).powf(k(8)));
            }
            let mut i = 9;
            while i + 1 < c.len() {
                s += k(i) * l.powf(k(i + 1));
                i += 2;
            }
            s.sqrt()
        }
        // 5 Cauchy: n = C1 + Σ C_i λ^C_{i+1}
        5 => {
            let mut s = k(0);
            let mut i = 1;
            while i + 1 < c.len() {
                s += k(i) * l.powf(k(i + 1));
                i += 2;
            }
            s
        }
        // 6 Gases: n − 1 = C1 + Σ C_i / (C_{i+1} − λ⁻²)
        6 => {
            let mut s = 1.0 + k(0);
            let mut i = 1;
            while i + 1 < c.len() {
                s += k(i) / (k(i + 1) - 1.0 / l2);
                i += 2;
            }
            s
        }
        // 7 Herzberger: n = C1 + C2/(λ² − 0.028) + C3/(λ² − 0.028)² + C4 λ² + C5 λ⁴ + C6 λ⁶
        7 => {
            let d = 1.0 / (l2 - 0.028);
            k(0) + k(1) * d + k(2) * d * d + k(3) * l2 + k(4) * l2 * l2 + k(5) * l2 * l2 * l2
        }
        // 8 Retro: (n² − 1)/(n² + 2) = C1 + C2 λ²/(λ² − C3) + C4 λ²
        8 => {
            let q = k(0) + k(1) * l2 / (l2 - k(2)) + k(3) * l2;
            ((1.0 + 2.0 * q) / (1.0 - q)).sqrt()
        }
        // 9 Exotic: n² = C1 + C2/(λ² − C3) + C4 (λ − C5) / ((λ − C5)² + C6)
        9 => {
            let d = l - k(4);
            (k(0) + k(1) / (l2 - k(2)) + k(3) * d / (d * d + k(5))).sqrt()
        }
        _ => f64::NAN,
    }
}

/// A material with a (possibly wavelength-dependent) complex refractive index.
#[derive(Debug, Clone, PartialEq)]
pub struct Material {
    name: String,
    pub(crate) n: Part,
    pub(crate) k: Part,
    /// The wavelengths (nm) where the data are valid, inclusive.
    range_nm: (f64, f64),
}

/// The built-in library: `(names, description, source)`. Constants are the values of Sussenbach's thesis
/// (water 1.33, gasoline 1.4, asphalt 1.635, glass 1.5); measured data are in `data/materials/`
/// (provenance in `data/materials/README.md`).
const LIBRARY: &[(&[&str], &str, Builtin)] = &[
    (&["air", "vacuum"], "n = 1 (vacuum; air's 1.0003 is below the model's accuracy)", Builtin::Const(1.0)),
    (&["water"], "n = 1.33, constant (Sussenbach's soap film, Figure 3.8)", Builtin::Const(1.33)),
    (&["glass"], "n = 1.5, constant (Sussenbach section 5.1)", Builtin::Const(1.5)),
    (&["gasoline", "oil"], "n = 1.4, constant (Sussenbach section 5.1)", Builtin::Const(1.4)),
    (&["asphalt"], "n = 1.635, constant (Sussenbach section 5.1)", Builtin::Const(1.635)),
    (
        &["bk7", "n-bk7"],
        "SCHOTT N-BK7 Sellmeier, 300–2500 nm",
        Builtin::File("bk7_schott.yml", include_str!("../../../data/materials/bk7_schott.yml")),
    ),
    (
        &["fused-silica", "fused_silica", "silica", "sio2"],
        "fused silica, Malitson 1965 Sellmeier, 210–6700 nm",
        Builtin::File("sio2_malitson.yml", include_str!("../../../data/materials/sio2_malitson.yml")),
    ),
    (
        &["keratin"],
        "bird keratin, Leertouwer et al. 2011 Cauchy, 380–780 nm",
        Builtin::File("keratin_leertouwer.yml", include_str!("../../../data/materials/keratin_leertouwer.yml")),
    ),
    (
        &["chitin"],
        "butterfly chitin, Leertouwer et al. 2011 Cauchy, 380–780 nm",
        Builtin::File("chitin_leertouwer.yml", include_str!("../../../data/materials/chitin_leertouwer.yml")),
    ),
    (
        &["mgf2"],
        "MgF2 ordinary ray, Dodge 1984 Sellmeier, 200–7000 nm",
        Builtin::File("mgf2_dodge_o.yml", include_str!("../../../data/materials/mgf2_dodge_o.yml")),
    ),
    (
        // A deposited film covers the whole visible band (and is what coatings are made of); bulk rutile
        // starts at 430 nm, so it is not the default.
        &["tio2"],
        "TiO2 thin film (200 nm on glass), Sarkar et al. 2019, 300–1690 nm",
        Builtin::File("tio2_sarkar.yml", include_str!("../../../data/materials/tio2_sarkar.yml")),
    ),
    (
        &["rutile", "tio2-rutile"],
        "TiO2 (rutile) ordinary ray, Devore 1951, 430–1530 nm",
        Builtin::File("tio2_devore_o.yml", include_str!("../../../data/materials/tio2_devore_o.yml")),
    ),
    (
        &["si", "silicon"],
        "crystalline Si, Aspnes & Studna 1983, 207–827 nm",
        Builtin::File("si_aspnes.yml", include_str!("../../../data/materials/si_aspnes.yml")),
    ),
    (
        &["au", "gold"],
        "gold, Johnson & Christy 1972, 188–1937 nm",
        Builtin::File("au_johnson.yml", include_str!("../../../data/materials/au_johnson.yml")),
    ),
    (
        &["ag", "silver"],
        "silver, Johnson & Christy 1972, 188–1937 nm",
        Builtin::File("ag_johnson.yml", include_str!("../../../data/materials/ag_johnson.yml")),
    ),
    (
        &["cu", "copper"],
        "copper, Johnson & Christy 1972, 188–1937 nm",
        Builtin::File("cu_johnson.yml", include_str!("../../../data/materials/cu_johnson.yml")),
    ),
    (
        &["al", "aluminium", "aluminum"],
        "aluminium, Rakić 1995, 207–2066 nm",
        Builtin::File("al_rakic.yml", include_str!("../../../data/materials/al_rakic.yml")),
    ),
    (
        &["al2o3", "alumina"],
        "Al2O3 film (amorphous, pulsed-laser deposited), Boidin et al. 2016, 300–2498 nm",
        Builtin::File("al2o3_boidin.yml", include_str!("../../../data/materials/al2o3_boidin.yml")),
    ),
    (
        &["si3n4", "silicon-nitride"],
        "Si3N4 (CVD film), Philipp 1973 Sellmeier, 207–1240 nm",
        Builtin::File("si3n4_philipp.yml", include_str!("../../../data/materials/si3n4_philipp.yml")),
    ),
    (
        &["sio2-film"],
        "SiO2 film (ion-assisted e-beam), Gao et al. 2013, 252–1250 nm",
        Builtin::File("sio2_gao.yml", include_str!("../../../data/materials/sio2_gao.yml")),
    ),
    (
        &["ito", "in2o3-sno2"],
        "ITO film (72 nm on BK7), König et al. 2014, 252–1000 nm",
        Builtin::File("ito_konig.yml", include_str!("../../../data/materials/ito_konig.yml")),
    ),
    (
        &["hfo2", "hafnia"],
        "HfO2 film (e-beam), Franta et al. 2015, 250–2497 nm",
        Builtin::File("hfo2_franta.yml", include_str!("../../../data/materials/hfo2_franta.yml")),
    ),
    (
        &["ta2o5"],
        "Ta2O5 film (e-beam), Franta et al. 2015, 253–2497 nm",
        Builtin::File("ta2o5_franta.yml", include_str!("../../../data/materials/ta2o5_franta.yml")),
    ),
    (
        &["zno"],
        "ZnO film, Aguilar et al. 2019, 300–2500 nm",
        Builtin::File("zno_aguilar.yml", include_str!("../../../data/materials/zno_aguilar.yml")),
    ),
    (
        &["zns"],
        "ZnS (cubic), Ozaki & Adachi 1993, 221–1033 nm",
        Builtin::File("zns_ozaki.yml", include_str!("../../../data/materials/zns_ozaki.yml")),
    ),
    (
        &["cr", "chromium"],
        "chromium, Johnson & Christy 1974, 188–1937 nm",
        Builtin::File("cr_johnson.yml", include_str!("../../../data/materials/cr_johnson.yml")),
    ),
    (
        &["ti", "titanium"],
        "titanium, Johnson & Christy 1974, 188–1937 nm",
        Builtin::File("ti_johnson.yml", include_str!("../../../data/materials/ti_johnson.yml")),
    ),
    (
        &["ni", "nickel"],
        "nickel, Johnson & Christy 1974, 188–1937 nm",
        Builtin::File("ni_johnson.yml", include_str!("../../../data/materials/ni_johnson.yml")),
    ),
    (
        &["pt", "platinum"],
        "platinum, Rakić et al. 1998 (Lorentz–Drude fit), 248–2499 nm",
        Builtin::File("pt_rakic.yml", include_str!("../../../data/materials/pt_rakic.yml")),
    ),
    (
        &["w", "tungsten"],
        "tungsten, Rakić et al. 1998 (Lorentz–Drude fit), 248–2499 nm",
        Builtin::File("w_rakic.yml", include_str!("../../../data/materials/w_rakic.yml")),
    ),
    (
        &["ge", "germanium"],
        "germanium, Nunley et al. 2016, 188–2480 nm",
        Builtin::File("ge_nunley.yml", include_str!("../../../data/materials/ge_nunley.yml")),
    ),
    (
        &["inp"],
        "InP, Adachi 1989 (model dielectric function), 207–2407 nm",
        Builtin::File("inp_adachi.yml", include_str!("../../../data/materials/inp_adachi.yml")),
    ),
    (
        &["gaas"],
        "GaAs, Papatryfonos et al. 2021, 260–1879 nm",
        Builtin::File("gaas_papatryfonos.yml", include_str!("../../../data/materials/gaas_papatryfonos.yml")),
    ),
    (
        &["si-green", "si-green2008"],
        "crystalline Si, Green 2008, 250–1450 nm",
        Builtin::File("si_green.yml", include_str!("../../../data/materials/si_green.yml")),
    ),
    (
        &["pmma"],
        "PMMA, Szczurowski 2013 Sellmeier, 405–1083 nm",
        Builtin::File("pmma_szczurowski.yml", include_str!("../../../data/materials/pmma_szczurowski.yml")),
    ),
    (
        &["pdms"],
        "PDMS (Sylgard 184, 10:1), Gupta et al. 2019, 300–1690 nm",
        Builtin::File("pdms_gupta.yml", include_str!("../../../data/materials/pdms_gupta.yml")),
    ),
    (
        &["melanin", "eumelanin"],
        "eumelanin, Stavenga et al. 2015 Cauchy + exponential κ, 380–780 nm",
        Builtin::File("melanin_stavenga.yml", include_str!("../../../data/materials/melanin_stavenga.yml")),
    ),
    (
        // Birefringent: 1.83 in the plane of the biogenic plates, 1.46 normal to them; no dispersion data.
        &["guanine"],
        "guanine crystal plates, n = 1.83 in-plane (Land 1972; Jordan et al. 2012), constant",
        Builtin::Const(1.83),
    ),
];

#[derive(Debug, Clone, Copy)]
enum Builtin {
    Const(f64),
    File(&'static str, &'static str),
}

impl Material {
    /// A wavelength-independent index `n + iκ`. `κ < 0` (gain) and `n ≤ 0` are refused.
    pub fn constant(name: impl Into<String>, index: Complex64) -> Result<Self, ThinFilmError> {
        let name = name.into();
        if !index.re.is_finite() || !index.im.is_finite() {
            return Err(ThinFilmError::Invalid(format!("material '{name}': the index must be finite")));
        }
        if index.im < 0.0 {
            return Err(ThinFilmError::Invalid(format!(
                "material '{name}': κ = {} < 0 would be gain; write κ ≥ 0 (κ > 0 absorbs)",
                index.im
            )));
        }
        if index.re <= 0.0 {
            return Err(ThinFilmError::Invalid(format!("material '{name}': n = {} must be > 0", index.re)));
        }
        Ok(Self { name, n: Part::Const(index.re), k: Part::Const(index.im), range_nm: (0.0, f64::INFINITY) })
    }

    /// Cauchy's formula `n = A + B/λ² + C/λ⁴` (λ in µm; refractiveindex.info formula 5), lossless. Stack
    /// syntax `cauchy:A,B,C` (fewer coefficients: the rest are 0).
    pub fn cauchy(name: impl Into<String>, coefficients: &[f64]) -> Result<Self, ThinFilmError> {
        let name = name.into();
        if coefficients.is_empty() || coefficients.len() > 3 || coefficients.iter().any(|c| !c.is_finite()) {
            return Err(ThinFilmError::Invalid(format!(
                "material '{name}': Cauchy takes 1 to 3 finite coefficients A,B,C (n = A + B/λ² + C/λ⁴, λ in µm)"
            )));
        }
        let mut c = vec![coefficients[0]];
        for (i, &v) in coefficients.iter().enumerate().skip(1) {
            c.extend([v, -2.0 * i as f64]);
        }
        Ok(Self { name, n: Part::Formula { kind: 5, c }, k: Part::Const(0.0), range_nm: (0.0, f64::INFINITY) })
    }

    /// Sellmeier's formula `n² = 1 + Σ B_i λ² / (λ² − C_i)` (λ in µm, C_i in µm²; refractiveindex.info
    /// formula 2), lossless. Stack syntax `sellmeier:B1,C1,B2,C2,…`.
    pub fn sellmeier(name: impl Into<String>, coefficients: &[f64]) -> Result<Self, ThinFilmError> {
        let name = name.into();
        if coefficients.is_empty()
            || !coefficients.len().is_multiple_of(2)
            || coefficients.iter().any(|c| !c.is_finite())
        {
            return Err(ThinFilmError::Invalid(format!(
                "material '{name}': Sellmeier takes pairs B1,C1,B2,C2,… (n² = 1 + Σ B λ²/(λ² − C), λ in µm)"
            )));
        }
        let mut c = vec![0.0];
        c.extend_from_slice(coefficients);
        Ok(Self { name, n: Part::Formula { kind: 2, c }, k: Part::Const(0.0), range_nm: (0.0, f64::INFINITY) })
    }

    /// `∂n/∂c_i` of [`Material::cauchy`] at one wavelength: `n = A + B/λ² + C/λ⁴` (λ in µm) is linear in
    /// its coefficients, so the gradient is `(1, λ⁻², λ⁻⁴)` (as many entries as coefficients).
    pub fn cauchy_gradient(coefficients: &[f64], wavelength_nm: f64) -> Vec<f64> {
        let l2 = (wavelength_nm / 1000.0).powi(2);
        (0..coefficients.len()).map(|i| l2.powi(-(i as i32))).collect()
    }

    /// `∂n/∂c` of [`Material::sellmeier`] at one wavelength, for `B1, C1, B2, C2, …`: with
    /// `n² = 1 + Σ B_i λ²/(λ² − C_i)`, `∂n/∂B_i = λ²/((λ² − C_i) 2n)` and `∂n/∂C_i = B_i λ²/((λ² − C_i)² 2n)`.
    pub fn sellmeier_gradient(coefficients: &[f64], wavelength_nm: f64) -> Vec<f64> {
        let l2 = (wavelength_nm / 1000.0).powi(2);
        let n2: f64 = 1.0 + coefficients.chunks(2).map(|p| p[0] * l2 / (l2 - p[1])).sum::<f64>();
        let two_n = 2.0 * n2.sqrt();
        coefficients
            .chunks(2)
            .flat_map(|p| {
                let q = l2 - p[1];
                [l2 / (q * two_n), p[0] * l2 / (q * q * two_n)]
            })
            .collect()
    }

    /// A material tabulated at the given wavelengths (nm, strictly increasing), interpolated linearly in
    /// between and refused outside (as the measured data of files): Python's per-wavelength index arrays.
    /// One wavelength: a constant at that wavelength only.
    pub fn tabulated(
        name: impl Into<String>,
        wavelengths_nm: &[f64],
        index: &[Complex64],
    ) -> Result<Self, ThinFilmError> {
        let name = name.into();
        if wavelengths_nm.is_empty() || wavelengths_nm.len() != index.len() {
            return Err(ThinFilmError::Invalid(format!(
                "material '{name}': {} wavelengths for {} indices (give one index per wavelength)",
                wavelengths_nm.len(),
                index.len()
            )));
        }
        if let Some(w) = wavelengths_nm.iter().find(|w| !(w.is_finite() && **w > 0.0)) {
            return Err(ThinFilmError::Invalid(format!("material '{name}': wavelength {w} nm must be finite and > 0")));
        }
        if wavelengths_nm.windows(2).any(|w| w[1] <= w[0]) {
            return Err(ThinFilmError::Invalid(format!(
                "material '{name}': the wavelengths must increase strictly (sort them, one index per wavelength)"
            )));
        }
        for (w, x) in wavelengths_nm.iter().zip(index) {
            Material::constant(format!("{name} at {w} nm"), *x)?;
        }
        let (lo, hi) = (wavelengths_nm[0], wavelengths_nm[wavelengths_nm.len() - 1]);
        let n = Part::Table { wl_nm: wavelengths_nm.to_vec(), v: index.iter().map(|x| x.re).collect() };
        let k = Part::Table { wl_nm: wavelengths_nm.to_vec(), v: index.iter().map(|x| x.im).collect() };
        Ok(Self { name, n, k, range_nm: (lo, hi) })
    }

    pub(crate) fn from_parts(name: String, n: Part, k: Part, range_nm: (f64, f64)) -> Self {
        Self { name, n, k, range_nm }
    }

    /// A material of the built-in library by name (case-insensitive), e.g. `water`, `BK7`, `Au`.
    pub fn builtin(name: &str) -> Option<Self> {
        let key = name.trim().to_ascii_lowercase();
        let (names, _, b) = LIBRARY.iter().find(|(names, _, _)| names.contains(&key.as_str()))?;
        let m = match *b {
            Builtin::Const(v) => Material::constant(names[0], Complex64::new(v, 0.0)).ok()?,
            // The built-in files are part of the build and covered by the tests; a parse failure here
            // would be caught there.
            Builtin::File(file, text) => {
                let mut m = nkfile::parse_yaml(text, &format!("data/materials/{file}")).ok()?;
                m.name = names[0].to_string();
                m
            }
        };
        Some(m)
    }

    /// The library: each entry's names and a one-line description with its source.
    pub fn library() -> Vec<(Vec<&'static str>, &'static str)> {
        LIBRARY.iter().map(|(n, d, _)| (n.to_vec(), *d)).collect()
    }

    /// Reads a file: `.yml`/`.yaml` in the refractiveindex.info format, anything else as CSV
    /// (`wavelength_nm, n, κ`).
    pub fn from_file(path: &std::path::Path) -> Result<Self, ThinFilmError> {
        let shown = path.display().to_string();
        let text = std::fs::read_to_string(path).map_err(|e| ThinFilmError::File {
            path: shown.clone(),
            line: None,
            message: format!("cannot read: {e}"),
        })?;
        let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase();
        if ext == "yml" || ext == "yaml" {
            nkfile::parse_yaml(&text, &shown)
        } else {
            nkfile::parse_csv(&text, &shown)
        }
    }

    pub fn name(&self) -> &str {
        &self.name
    }

    /// The library's description of this material ("gold, Johnson & Christy 1972, 188–1937 nm, from the
    /// built-in library") when it came from [`Material::builtin`]; `None` for constants and files.
    pub fn library_source(&self) -> Option<String> {
        LIBRARY
            .iter()
            .find(|(names, _, b)| names[0] == self.name && matches!(b, Builtin::File(..)))
            .map(|(_, d, _)| format!("{d}, from the built-in library"))
    }

    /// The wavelengths (nm) where the index is defined, inclusive; `(0, ∞)` for constants.
    pub fn range_nm(&self) -> (f64, f64) {
        self.range_nm
    }

    /// True when the index does not depend on wavelength.
    pub fn is_constant(&self) -> bool {
        matches!((&self.n, &self.k), (Part::Const(_), Part::Const(_)))
    }

    /// The complex index `n + iκ` at a wavelength in nm.
    pub fn index_at(&self, wavelength_nm: f64) -> Result<Complex64, ThinFilmError> {
        if !(wavelength_nm.is_finite() && wavelength_nm > 0.0) {
            return Err(ThinFilmError::Invalid(format!("wavelength {wavelength_nm} nm must be positive")));
        }
        let (lo, hi) = self.range_nm;
        let tol = 1e-9 * wavelength_nm;
        if wavelength_nm < lo - tol || wavelength_nm > hi + tol {
            return Err(ThinFilmError::OutOfRange {
                material: self.name.clone(),
                place: String::new(),
                wavelength_nm,
                lo_nm: lo,
                hi_nm: hi,
            });
        }
        let w = wavelength_nm.clamp(lo, hi);
        let n = self.n.eval(w);
        let k = self.k.eval(w);
        if !(n.is_finite() && n > 0.0 && k.is_finite() && k >= 0.0) {
            return Err(ThinFilmError::Invalid(format!(
                "material '{}' gives the invalid index {n} + {k}i at {wavelength_nm} nm",
                self.name
            )));
        }
        Ok(Complex64::new(n, k))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_builtin_loads_and_covers_its_range() {
        for (names, _) in Material::library() {
            let m = Material::builtin(names[0]).unwrap_or_else(|| panic!("{} does not load", names[0]));
            let (lo, hi) = m.range_nm();
            let mid = if hi.is_finite() { 0.5 * (lo + hi) } else { 550.0 };
            let n = m.index_at(mid).unwrap();
            assert!(n.re > 0.0 && n.im >= 0.0, "{}: {n}", names[0]);
        }
    }

    #[test]
    fn published_values() {
        // N-BK7: nd = 1.5168 at 587.56 nm (SCHOTT data sheet).
        let bk7 = Material::builtin("BK7").unwrap();
        assert!((bk7.index_at(587.56).unwrap().re - 1.5168).abs() < 5e-5);
        // Fused silica (Malitson): n = 1.4585 at 587.6 nm.
        let sio2 = Material::builtin("fused silica".replace(' ', "-").as_str()).unwrap();
        assert!((sio2.index_at(587.6).unwrap().re - 1.4585).abs() < 1e-4);
        // Gold, Johnson & Christy: the tabulated row 0.6595 µm → 0.14 + 3.697i exactly.
        let au = Material::builtin("Au").unwrap();
        let n = au.index_at(659.5).unwrap();
        assert!((n.re - 0.14).abs() < 1e-12 && (n.im - 3.697).abs() < 1e-12);
        // Halfway between rows 0.6168 (0.21, 3.272) and 0.6595 (0.14, 3.697): linear interpolation.
        let n = au.index_at(0.5 * (616.8 + 659.5)).unwrap();
        assert!((n.re - 0.175).abs() < 1e-12 && (n.im - 3.4845).abs() < 1e-12);
        // Rutile (Devore): n² = 5.913 + 0.2441/(λ² − 0.0803) at 0.5 µm.
        let rutile = Material::builtin("rutile").unwrap();
        let expect = (5.913f64 + 0.2441 / (0.25 - 0.0803)).sqrt();
        assert!((rutile.index_at(500.0).unwrap().re - expect).abs() < 1e-12);
        // TiO2 film (Sarkar et al.): the table's rows at 550 nm and 330 nm (absorbing below ~365 nm).
        let tio2 = Material::builtin("TiO2").unwrap();
        assert!((tio2.index_at(550.0).unwrap() - Complex64::new(2.164358, 0.0)).norm() < 1e-12);
        assert!((tio2.index_at(330.0).unwrap() - Complex64::new(2.747194, 0.179225)).norm() < 1e-12);
        // The database's tabulated rows, read back exactly: ITO (König et al.) 0.25157 µm, Cr (Johnson &
        // Christy) 0.582 µm; Si3N4 (Philipp) Sellmeier at 0.6328 µm.
        for (name, wl, want) in
            [("ITO", 251.57, Complex64::new(2.31717213, 0.57780161)), ("Cr", 582.0, Complex64::new(3.22, 3.30))]
        {
            let n = Material::builtin(name).unwrap().index_at(wl).unwrap();
            assert!((n - want).norm() < 1e-12, "{name} at {wl} nm: {n}");
        }
        let si3n4 = Material::builtin("Si3N4").unwrap().index_at(632.8).unwrap().re;
        let l2 = 0.6328f64.powi(2);
        assert!((si3n4 - (1.0 + 2.8939 * l2 / (l2 - 0.13967f64.powi(2))).sqrt()).abs() < 1e-12, "{si3n4}");
        // Melanin (Stavenga et al. 2015): 1.648 + 23 700/λ², κ = 0.56 e^{−λ/270}; n 1.7–1.8 in the visible.
        let mel = Material::builtin("melanin").unwrap();
        let n = mel.index_at(500.0).unwrap();
        assert!(
            (n.re - (1.648 + 23700.0 / 250000.0)).abs() < 1e-12
                && (n.im - 0.56 * (-500.0f64 / 270.0).exp()).abs() < 1e-6
        );
        // Chitin (Leertouwer et al.): 1.517 + 8800/λ² with λ in nm.
        let chitin = Material::builtin("chitin").unwrap();
        assert!((chitin.index_at(500.0).unwrap().re - (1.517 + 8800.0 / 250000.0)).abs() < 1e-12);
    }

    #[test]
    fn coating_materials_cover_300_to_1000_nm_where_the_source_does() {
        // Issue 29: what people coat with, from 300 nm (UV that birds and insects see) to 1000 nm.
        for name in [
            "Al2O3", "Si3N4", "ITO", "HfO2", "Ta2O5", "ZnO", "ZnS", "Cr", "Ti", "Ni", "Pt", "W", "Ge", "InP", "PDMS",
            "si-green",
        ] {
            let m = Material::builtin(name).unwrap();
            let (lo, hi) = m.range_nm();
            assert!(lo <= 300.0 + 1e-9 && hi >= 1000.0 - 1e-9, "{name}: {lo}–{hi} nm");
            for wl in [300.0, 450.0, 650.0, 1000.0] {
                let n = m.index_at(wl).unwrap();
                assert!(n.re > 0.0 && n.im >= 0.0, "{name} at {wl} nm: {n}");
            }
        }
        // Where the source starts later, the range says so: GaAs from 260 nm (covers), PMMA from 405 nm.
        assert!(Material::builtin("GaAs").unwrap().range_nm().0 <= 300.0);
        assert!(Material::builtin("PMMA").unwrap().index_at(350.0).is_err());
    }

    #[test]
    fn no_extrapolation() {
        let si = Material::builtin("Si").unwrap();
        let e = si.index_at(900.0).unwrap_err();
        assert!(matches!(e, ThinFilmError::OutOfRange { .. }), "{e}");
        assert!(e.to_string().contains("Si") || e.to_string().contains("si"), "{e}");
        let rutile = Material::builtin("rutile").unwrap();
        assert!(rutile.index_at(400.0).is_err());
    }

    #[test]
    fn tables_from_arrays_interpolate_and_refuse_outside() {
        let (w, n) =
            ([400.0, 500.0, 700.0], [Complex64::new(2.0, 0.1), Complex64::new(1.8, 0.0), Complex64::new(1.6, 0.0)]);
        let m = Material::tabulated("t", &w, &n).unwrap();
        assert_eq!(m.index_at(500.0).unwrap(), n[1]);
        assert!((m.index_at(450.0).unwrap() - Complex64::new(1.9, 0.05)).norm() < 1e-15);
        assert!(matches!(m.index_at(750.0), Err(ThinFilmError::OutOfRange { .. })));
        assert!(Material::tabulated("t", &[500.0, 400.0], &n[..2]).is_err());
        assert!(Material::tabulated("t", &w, &n[..2]).is_err());
        assert!(Material::tabulated("t", &w, &[n[0], n[1], Complex64::new(1.5, -0.1)]).is_err());
    }

    #[test]
    fn constants_are_checked() {
        assert!(Material::constant("x", Complex64::new(1.5, -0.1)).is_err());
        assert!(Material::constant("x", Complex64::new(0.0, 0.0)).is_err());
        assert!(Material::constant("x", Complex64::new(0.2, 3.4)).is_ok());
    }
}
