//! Measured spectra from CSV: a header row naming the columns, one row per wavelength, `#` comments.
//! The wavelength column is `wavelength_nm` (also `wavelength`, `lambda_nm`, `wl_nm`; in nm); the measured
//! column is `R`, `T`, or `psi` and `delta` (degrees) for ellipsometry; an optional column of 1σ
//! uncertainties is named by the caller.

use crate::{FitError, Quantity};

/// A measured spectrum: wavelengths, values (one per wavelength; two — ψ, Δ — for ellipsometry, interleaved)
/// and optional 1σ uncertainties in the same layout.
#[derive(Debug, Clone, PartialEq)]
pub struct Measured {
    pub wavelength_nm: Vec<f64>,
    pub values: Vec<f64>,
    pub sigma: Option<Vec<f64>>,
}

const WAVELENGTH: &[&str] = &["wavelength_nm", "wavelength", "lambda_nm", "wl_nm", "lambda"];

impl Measured {
    /// Reads CSV text; `path` names it in messages; `sigma_column` names the 1σ column(s): for ψ/Δ two
    /// names separated by a comma (or one column used for both).
    pub fn from_csv(text: &str, path: &str, quantity: Quantity, sigma_column: Option<&str>) -> Result<Self, FitError> {
        let err = |line: usize, m: String| FitError::Data(format!("{path}, line {line}: {m}"));
        let mut rows =
            text.lines().enumerate().filter(|(_, l)| !l.trim().is_empty() && !l.trim_start().starts_with('#'));
        let (hl, header) = rows.next().ok_or_else(|| FitError::Data(format!("{path}: no header row and no data")))?;
        let names: Vec<String> = header.split(',').map(|h| h.trim().trim_matches('"').to_string()).collect();
        let find = |want: &[&str]| names.iter().position(|n| want.iter().any(|w| n.eq_ignore_ascii_case(w)));
        let wl = find(WAVELENGTH).ok_or_else(|| {
            err(
                hl + 1,
                format!("no wavelength column (wavelength_nm) among {names:?}; the header must name the columns"),
            )
        })?;
        let wanted: Vec<(&str, &[&str])> = match quantity {
            Quantity::R => vec![("R", &["R", "reflectance"])],
            Quantity::T => vec![("T", &["T", "transmittance"])],
            Quantity::PsiDelta => vec![("psi", &["psi", "psi_deg"]), ("delta", &["delta", "delta_deg"])],
        };
        let cols: Vec<usize> = wanted
            .iter()
            .map(|(label, alts)| {
                find(alts).ok_or_else(|| {
                    err(
                        hl + 1,
                        format!(
                            "no measured column '{label}' for --quantity {}; the columns are {names:?}",
                            quantity.name()
                        ),
                    )
                })
            })
            .collect::<Result<_, _>>()?;
        let sig_cols: Option<Vec<usize>> = sigma_column
            .map(|s| {
                let parts: Vec<&str> = s.split(',').map(str::trim).collect();
                let parts = if parts.len() == 1 { vec![parts[0]; cols.len()] } else { parts };
                if parts.len() != cols.len() {
                    return Err(FitError::Data(format!("--sigma: give {} column name(s), got '{s}'", cols.len())));
                }
                parts
                    .iter()
                    .map(|p| {
                        find(&[p]).ok_or_else(|| err(hl + 1, format!("no uncertainty column '{p}' among {names:?}")))
                    })
                    .collect()
            })
            .transpose()?;
        let (mut wavelength_nm, mut values, mut sigma) = (Vec::new(), Vec::new(), Vec::new());
        for (i, line) in rows {
            let cells: Vec<&str> = line.split(',').map(str::trim).collect();
            let num = |c: usize, what: &str| -> Result<f64, FitError> {
                let t = cells.get(c).copied().unwrap_or("");
                t.parse::<f64>()
                    .ok()
                    .filter(|v| v.is_finite())
                    .ok_or_else(|| err(i + 1, format!("{what} '{t}' is not a finite number")))
            };
            let w = num(wl, "wavelength")?;
            if w <= 0.0 {
                return Err(err(i + 1, format!("wavelength {w} nm must be positive")));
            }
            wavelength_nm.push(w);
            for (k, &c) in cols.iter().enumerate() {
                values.push(num(c, wanted[k].0)?);
                if let Some(sc) = &sig_cols {
                    let s = num(sc[k], "uncertainty")?;
                    if s <= 0.0 {
                        return Err(err(i + 1, format!("uncertainty {s} must be > 0")));
                    }
                    sigma.push(s);
                }
            }
        }
        if wavelength_nm.is_empty() {
            return Err(FitError::Data(format!("{path}: a header but no data rows")));
        }
        Ok(Self { wavelength_nm, values, sigma: sig_cols.map(|_| sigma) })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_and_refuses() {
        let m = Measured::from_csv(
            "# test\nwavelength_nm,R,sR\n400,0.1,0.01\n500,0.2,0.01\n",
            "x.csv",
            Quantity::R,
            Some("sR"),
        )
        .unwrap();
        assert_eq!(m.wavelength_nm, [400.0, 500.0]);
        assert_eq!(m.values, [0.1, 0.2]);
        assert_eq!(m.sigma, Some(vec![0.01, 0.01]));
        let e = Measured::from_csv("wavelength_nm,T\n400,0.1\n", "x.csv", Quantity::R, None).unwrap_err().to_string();
        assert!(e.contains("no measured column 'R' for --quantity R") && e.contains("x.csv, line 1"), "{e}");
        let e = Measured::from_csv("wavelength_nm,R\n400,abc\n", "x.csv", Quantity::R, None).unwrap_err().to_string();
        assert!(e.contains("line 2") && e.contains("'abc'"), "{e}");
        let e = Measured::from_csv("nm,R\n400,0.1\n", "x.csv", Quantity::R, None).unwrap_err().to_string();
        assert!(e.contains("no wavelength column"), "{e}");
        let m = Measured::from_csv("wavelength_nm,psi,delta\n400,30,100\n", "e.csv", Quantity::PsiDelta, None).unwrap();
        assert_eq!(m.values, [30.0, 100.0]);
    }
}
