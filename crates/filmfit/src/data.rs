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
        Self::from_csv_with(text, path, quantity, sigma_column.map(|c| (c, Spread::Sigma)))
    }

    /// [`Measured::from_csv`] with the column(s) of 1σ uncertainties or of weights `w = 1/σ²`.
    pub fn from_csv_with(
        text: &str,
        path: &str,
        quantity: Quantity,
        column: Option<(&str, Spread)>,
    ) -> Result<Self, FitError> {
        let (sigma_column, kind) = match column {
            Some((c, k)) => (Some(c), k),
            None => (None, Spread::Sigma),
        };
        let flag = kind.flag();
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
                    return Err(FitError::Data(format!("{flag}: give {} column name(s), got '{s}'", cols.len())));
                }
                parts
                    .iter()
                    .map(|p| {
                        find(&[p]).ok_or_else(|| {
                            err(hl + 1, format!("{flag}: no {} column '{p}' among {names:?}", kind.what()))
                        })
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
                    let v = num(sc[k], kind.what())?;
                    sigma.push(kind.sigma(v).map_err(|m| err(i + 1, m))?);
                }
            }
        }
        if wavelength_nm.is_empty() {
            return Err(FitError::Data(format!("{path}: a header but no data rows")));
        }
        Ok(Self { wavelength_nm, values, sigma: sig_cols.map(|_| sigma) })
    }
}

/// What a column (or value) of `--sigma` / `--weights` holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Spread {
    /// 1σ uncertainties.
    Sigma,
    /// Weights `w = 1/σ²` (the weights of the least-squares sum `Σ w (model − measured)²`).
    Weight,
}

impl Spread {
    fn flag(self) -> &'static str {
        match self {
            Spread::Sigma => "--sigma",
            Spread::Weight => "--weights",
        }
    }
    fn what(self) -> &'static str {
        match self {
            Spread::Sigma => "uncertainty",
            Spread::Weight => "weight",
        }
    }
    /// The 1σ of one value: itself, or `1/√w`. Zero, negative or infinite values are refused.
    pub fn sigma(self, v: f64) -> Result<f64, String> {
        if !(v.is_finite() && v > 0.0) {
            return Err(match self {
                Spread::Sigma => format!("uncertainty {v} must be a finite number > 0"),
                Spread::Weight => {
                    format!("weight {v} must be a finite number > 0 (w = 1/σ²; to leave a point out, delete its row)")
                }
            });
        }
        Ok(match self {
            Spread::Sigma => v,
            Spread::Weight => 1.0 / v.sqrt(),
        })
    }
}

/// The column names of a CSV's header row (the first line that is neither empty nor a `#` comment).
pub fn header(text: &str) -> Vec<String> {
    text.lines()
        .find(|l| !l.trim().is_empty() && !l.trim_start().starts_with('#'))
        .map(|h| h.split(',').map(|c| c.trim().trim_matches('"').to_string()).collect())
        .unwrap_or_default()
}

impl Measured {
    /// Sets the uncertainties from a separate weights file (`--weights FILE`): CSV with the wavelength
    /// column and, per measured value, a weight column `w` (or `weight`); for ψ/Δ `w_psi` and `w_delta`
    /// (or one `w` for both). Its wavelengths must be those of the measurement, row by row.
    pub fn set_weights_from_csv(&mut self, text: &str, path: &str, quantity: Quantity) -> Result<(), FitError> {
        let err = |line: usize, m: String| FitError::Data(format!("{path}, line {line}: {m}"));
        let names = header(text);
        let find = |want: &[&str]| names.iter().position(|n| want.iter().any(|w| n.eq_ignore_ascii_case(w)));
        let wl = find(WAVELENGTH)
            .ok_or_else(|| FitError::Data(format!("{path}: no wavelength column (wavelength_nm) among {names:?}")))?;
        let one = find(&["w", "weight", "weights"]);
        let cols: Vec<usize> = if quantity == Quantity::PsiDelta {
            match (find(&["w_psi", "weight_psi"]), find(&["w_delta", "weight_delta"]), one) {
                (Some(a), Some(b), _) => vec![a, b],
                (_, _, Some(w)) => vec![w, w],
                _ => {
                    return Err(FitError::Data(format!(
                        "{path}: no weight columns (w_psi and w_delta, or w) among {names:?}"
                    )))
                }
            }
        } else {
            vec![one.ok_or_else(|| FitError::Data(format!("{path}: no weight column (w) among {names:?}")))?]
        };
        let rows: Vec<(usize, &str)> = text
            .lines()
            .enumerate()
            .filter(|(_, l)| !l.trim().is_empty() && !l.trim_start().starts_with('#'))
            .skip(1)
            .collect();
        if rows.len() != self.wavelength_nm.len() {
            return Err(FitError::Data(format!(
                "{path}: {} rows of weights for {} measured wavelengths; give one row per measured wavelength",
                rows.len(),
                self.wavelength_nm.len()
            )));
        }
        let mut sigma = Vec::with_capacity(self.values.len());
        for ((i, line), &w_meas) in rows.iter().zip(&self.wavelength_nm) {
            let cells: Vec<&str> = line.split(',').map(str::trim).collect();
            let num = |c: usize| cells.get(c).and_then(|t| t.parse::<f64>().ok());
            let w = num(wl).ok_or_else(|| err(i + 1, format!("wavelength '{}' is not a number", cells[wl])))?;
            if (w - w_meas).abs() > 1e-9 * w_meas {
                return Err(err(i + 1, format!("wavelength {w} nm, but the measurement has {w_meas} nm in this row")));
            }
            for &c in &cols {
                let v = num(c).ok_or_else(|| {
                    err(i + 1, format!("weight '{}' is not a number", cells.get(c).copied().unwrap_or("")))
                })?;
                sigma.push(Spread::Weight.sigma(v).map_err(|m| err(i + 1, m))?);
            }
        }
        self.sigma = Some(sigma);
        Ok(())
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

    #[test]
    fn weights_are_inverse_variances() {
        // w = 1/σ²: w = 10⁴ is σ = 0.01, w = 2500 is σ = 0.02.
        let text = "wavelength_nm,R,w\n400,0.1,10000\n500,0.2,2500\n";
        let m = Measured::from_csv_with(text, "x.csv", Quantity::R, Some(("w", Spread::Weight))).unwrap();
        assert_eq!(m.sigma, Some(vec![0.01, 0.02]));
        let e = Measured::from_csv_with(
            "wavelength_nm,R,w\n400,0.1,0\n",
            "x.csv",
            Quantity::R,
            Some(("w", Spread::Weight)),
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("weight 0 must be") && e.contains("line 2"), "{e}");
        let e =
            Measured::from_csv_with(text, "x.csv", Quantity::R, Some(("wt", Spread::Weight))).unwrap_err().to_string();
        assert!(e.contains("--weights: no weight column 'wt'"), "{e}");
        // A separate file, row by row; ψ/Δ take two weights.
        let mut m =
            Measured::from_csv("wavelength_nm,psi,delta\n400,30,100\n450,31,101\n", "e.csv", Quantity::PsiDelta, None)
                .unwrap();
        m.set_weights_from_csv("wavelength_nm,w_psi,w_delta\n400,400,4\n450,100,1\n", "w.csv", Quantity::PsiDelta)
            .unwrap();
        assert_eq!(m.sigma, Some(vec![0.05, 0.5, 0.1, 1.0]));
        let e =
            m.set_weights_from_csv("wavelength_nm,w\n400,1\n", "w.csv", Quantity::PsiDelta).unwrap_err().to_string();
        assert!(e.contains("1 rows of weights for 2 measured wavelengths"), "{e}");
        let e = m
            .set_weights_from_csv("wavelength_nm,w\n400,1\n460,1\n", "w.csv", Quantity::PsiDelta)
            .unwrap_err()
            .to_string();
        assert!(e.contains("w.csv, line 3: wavelength 460 nm, but the measurement has 450 nm"), "{e}");
    }
}
