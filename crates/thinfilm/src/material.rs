//! Materials: a complex refractive index `n̂(λ) = n(λ) + iκ(λ)` (Sussenbach eq. 3.5 uses `n̂ = n + ik`).
//!
//! A material is a constant, a dispersion formula, or a table; tables are interpolated linearly in λ, and a
//! wavelength outside the data is an error ([`ThinFilmError::OutOfRange`]), never a silent extrapolation.

use num_complex::Complex64;

use crate::error::ThinFilmError;

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

/// `s + Σ term(C_i, C_{i+1})` over the coefficient pairs from index `first` on (`i = first, first + 2, …` while
/// `C_{i+1}` exists): the sum every formula of [`formula`] but 7–9 ends with.
fn add_pairs(c: &[f64], first: usize, mut s: f64, term: impl Fn(f64, f64) -> f64) -> f64 {
    let mut i = first;
    while i + 1 < c.len() {
        s += term(c[i], c[i + 1]);
        i += 2;
    }
    s
}

/// The dispersion formulas of the refractiveindex.info database (its `formula 1` … `formula 9`), λ in µm.
/// Returns n. Coefficients missing from the file count as zero.
pub(crate) fn formula(kind: u8, c: &[f64], l: f64) -> f64 {
    let k = |i: usize| c.get(i).copied().unwrap_or(0.0);
    let l2 = l * l;
    let power = |a: f64, b: f64| a * l.powf(b);
    match kind {
        // 1 Sellmeier: n² − 1 = C1 + Σ C_i λ² / (λ² − C_{i+1}²)
        1 => add_pairs(c, 1, 1.0 + k(0), |a, b| a * l2 / (l2 - b * b)).sqrt(),
        // 2 Sellmeier-2: n² − 1 = C1 + Σ C_i λ² / (λ² − C_{i+1})
        2 => add_pairs(c, 1, 1.0 + k(0), |a, b| a * l2 / (l2 - b)).sqrt(),
        // 3 Polynomial: n² = C1 + Σ C_i λ^C_{i+1}
        3 => add_pairs(c, 1, k(0), power).sqrt(),
        // 4 RefractiveIndex.INFO: n² = C1 + C2 λ^C3/(λ² − C4^C5) + C6 λ^C7/(λ² − C8^C9) + Σ_{i≥10} C_i λ^C_{i+1}
        4 => {
            let mut s = k(0);
            if c.len() > 1 {
                s += k(1) * l.powf(k(2)) / (l2 - k(3).powf(k(4)));
            }
            if c.len() > 5 {
                s += k(5) * l.powf(k(6)) / (l2 - k(7).powf(k(8)));
            }
            add_pairs(c, 9, s, power).sqrt()
        }
        // 5 Cauchy: n = C1 + Σ C_i λ^C_{i+1}
        5 => add_pairs(c, 1, k(0), power),
        // 6 Gases: n − 1 = C1 + Σ C_i / (C_{i+1} − λ⁻²)
        6 => add_pairs(c, 1, 1.0 + k(0), |a, b| a / (b - 1.0 / l2)),
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
    pub(crate) name: String,
    pub(crate) n: Part,
    pub(crate) k: Part,
    /// The wavelengths (nm) where the data are valid, inclusive.
    range_nm: (f64, f64),
}

/// The largest |n + iκ| taken: metals in the infrared reach ~100 and nothing 10⁶; beyond ~1e150 the Fresnel
/// coefficients overflow and energy vanished (R = T = 0 for a lossless layer).
pub const MAX_INDEX: f64 = 1e6;

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
            // n = 0 with κ > 0 is a lossless metal (ε = −κ²); the models here take its limit n → 0.
            let metal = if index.re == 0.0 && index.im > 0.0 {
                format!(
                    "; for a lossless metal (ε = −κ²) give a small n, e.g. n=0.001+{}i, whose absorption is then                      negligible",
                    index.im
                )
            } else {
                String::new()
            };
            return Err(ThinFilmError::Invalid(format!("material '{name}': n = {} must be > 0{metal}", index.re)));
        }
        if index.norm() > MAX_INDEX {
            return Err(ThinFilmError::Invalid(format!(
                "material '{name}': |n + iκ| = {:e} is beyond {:e}, which no material reaches (check the number; at \
                 1e300 the Fresnel coefficients overflowed and the light vanished)",
                index.norm(),
                MAX_INDEX
            )));
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

    pub fn name(&self) -> &str {
        &self.name
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
