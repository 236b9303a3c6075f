//! Reading measured refractive indices: the refractiveindex.info YAML format (tabulated `nk`, `n`, `k` and
//! dispersion formulas 1–9) and plain CSV (`wavelength_nm, n, κ`). Only the subset of YAML that the
//! database uses is read (a `DATA:` list of entries with `type`, `wavelength_range`, `coefficients` and
//! `data: |` blocks); anything else in the file (references, comments, specs) is ignored.

use crate::error::ThinFilmError;
use crate::material::{Material, Part};
use iridis_color::spectrum::{text_rows, Separators, TextRow};

fn file_err(path: &str, line: Option<usize>, message: impl Into<String>) -> ThinFilmError {
    ThinFilmError::File { path: path.to_string(), line, message: message.into() }
}

#[derive(Debug, Default)]
struct Entry {
    kind: String,
    kind_line: usize,
    range_um: Option<(f64, f64)>,
    coefficients: Vec<f64>,
    rows: Vec<(usize, Vec<f64>)>,
}

fn numbers(s: &str, path: &str, line: usize) -> Result<Vec<f64>, ThinFilmError> {
    s.split_whitespace()
        .map(|t| match t.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            _ => Err(file_err(path, Some(line), format!("'{t}' is not a finite number"))),
        })
        .collect()
}

fn unquote(s: &str) -> &str {
    s.trim().trim_matches(|c| c == '"' || c == '\'').trim()
}

/// Parses a refractiveindex.info YAML file (wavelengths in µm in the file, nm in the result).
pub fn parse_yaml(text: &str, path: &str) -> Result<Material, ThinFilmError> {
    let lines: Vec<&str> = text.lines().collect();
    let Some(start) = lines.iter().position(|l| l.trim_end() == "DATA:") else {
        return Err(file_err(path, None, "no 'DATA:' section; is this a refractiveindex.info YAML file?"));
    };
    let mut entries: Vec<Entry> = Vec::new();
    let mut i = start + 1;
    while i < lines.len() {
        let raw = lines[i];
        let lineno = i + 1;
        let t = raw.trim();
        if t.is_empty() || t.starts_with('#') {
            i += 1;
            continue;
        }
        let indent = raw.len() - raw.trim_start().len();
        if indent == 0 {
            break; // the next top-level key (SPECS:, CONDITIONS:, …)
        }
        let (key_part, is_new) = match t.strip_prefix("- ") {
            Some(rest) => (rest.trim(), true),
            None => (t, false),
        };
        if is_new {
            entries.push(Entry::default());
        }
        let Some(entry) = entries.last_mut() else {
            return Err(file_err(path, Some(lineno), format!("expected '- type: …' in DATA, found '{t}'")));
        };
        let Some((key, value)) = key_part.split_once(':') else {
            return Err(file_err(path, Some(lineno), format!("expected 'key: value', found '{t}'")));
        };
        let value = unquote(value);
        match key.trim() {
            "type" => {
                entry.kind = value.to_string();
                entry.kind_line = lineno;
            }
            "wavelength_range" | "range" => {
                let v = numbers(value, path, lineno)?;
                if v.len() != 2 || !(v[0] > 0.0 && v[1] > v[0]) {
                    return Err(file_err(
                        path,
                        Some(lineno),
                        "wavelength_range needs two increasing positive numbers (µm)",
                    ));
                }
                entry.range_um = Some((v[0], v[1]));
            }
            "coefficients" => entry.coefficients = numbers(value, path, lineno)?,
            "data" => {
                // A literal block: the following lines indented deeper than this key.
                let key_indent = raw.len() - raw.trim_start().len() + if is_new { 2 } else { 0 };
                let inline = value.trim_start_matches('|').trim();
                if !inline.is_empty() {
                    entry.rows.push((lineno, numbers(inline, path, lineno)?));
                }
                let mut j = i + 1;
                while j < lines.len() {
                    let r = lines[j];
                    let rt = r.trim();
                    let ri = r.len() - r.trim_start().len();
                    if rt.is_empty() {
                        j += 1;
                        continue;
                    }
                    if ri <= key_indent {
                        break;
                    }
                    entry.rows.push((j + 1, numbers(rt, path, j + 1)?));
                    j += 1;
                }
                i = j;
                continue;
            }
            _ => {} // other keys (e.g. comments inside an entry) are not needed
        }
        i += 1;
    }
    if entries.is_empty() {
        return Err(file_err(path, Some(start + 1), "DATA has no entries"));
    }
    let mut n_part: Option<(Part, (f64, f64))> = None;
    let mut k_part: Option<(Part, (f64, f64))> = None;
    for e in &entries {
        let kind = e.kind.trim().to_ascii_lowercase();
        let line = Some(e.kind_line);
        if let Some(f) = kind.strip_prefix("formula") {
            let f: u8 = match f.trim().parse() {
                Ok(v @ 1..=9) => v,
                _ => {
                    return Err(file_err(path, line, format!("unsupported type '{}' (formulas 1–9 are read)", e.kind)))
                }
            };
            let Some((lo, hi)) = e.range_um else {
                return Err(file_err(path, line, format!("'{}' has no wavelength_range", e.kind)));
            };
            if e.coefficients.is_empty() {
                return Err(file_err(path, line, format!("'{}' has no coefficients", e.kind)));
            }
            n_part = Some((Part::Formula { kind: f, c: e.coefficients.clone() }, (lo * 1000.0, hi * 1000.0)));
            continue;
        }
        let cols = match kind.as_str() {
            "tabulated nk" => 3,
            "tabulated n" | "tabulated k" => 2,
            _ => {
                return Err(file_err(
                    path,
                    line,
                    format!(
                        "unsupported type '{}' (read: tabulated nk, tabulated n, tabulated k, formula 1–9)",
                        e.kind
                    ),
                ))
            }
        };
        let mut wl = Vec::with_capacity(e.rows.len());
        let mut a = Vec::with_capacity(e.rows.len());
        let mut b = Vec::with_capacity(e.rows.len());
        let k_only = kind == "tabulated k";
        for (ln, row) in &e.rows {
            if row.len() != cols {
                return Err(file_err(
                    path,
                    Some(*ln),
                    format!("'{}' rows have {cols} numbers, this one has {}", e.kind, row.len()),
                ));
            }
            let (n_val, k_val) = match (cols, k_only) {
                (3, _) => (Some(row[1]), Some(row[2])),
                (_, true) => (None, Some(row[1])),
                _ => (Some(row[1]), None),
            };
            check_row(path, *ln, row[0], n_val, k_val)?;
            wl.push(row[0] * 1000.0);
            a.push(row[1]);
            if cols == 3 {
                b.push(row[2]);
            }
        }
        let (wl, a, b) = check_table(path, line, wl, a, b, kind.ends_with('k') && cols == 2)?;
        let range = (wl[0], wl[wl.len() - 1]);
        match kind.as_str() {
            "tabulated nk" => {
                n_part = Some((Part::Table { wl_nm: wl.clone(), v: a }, range));
                k_part = Some((Part::Table { wl_nm: wl, v: b }, range));
            }
            "tabulated n" => n_part = Some((Part::Table { wl_nm: wl, v: a }, range)),
            _ => k_part = Some((Part::Table { wl_nm: wl, v: a }, range)),
        }
    }
    let Some((n, nr)) = n_part else {
        return Err(file_err(path, None, "no refractive index n (only k) in DATA"));
    };
    let (k, kr) = k_part.unwrap_or((Part::Const(0.0), (0.0, f64::INFINITY)));
    let range = (nr.0.max(kr.0), nr.1.min(kr.1));
    if range.0 >= range.1 {
        return Err(file_err(path, None, "the n and k data do not overlap in wavelength"));
    }
    Ok(Material::from_parts(path.to_string(), n, k, range))
}

type Table = (Vec<f64>, Vec<f64>, Vec<f64>);

/// Checks one table row where it is read, so that the message names its line: a positive wavelength,
/// n > 0 and κ ≥ 0. (Order is not required: [`check_table`] sorts the rows and refuses repeated wavelengths.)
fn check_row(
    path: &str,
    line: usize,
    wavelength: f64,
    n: Option<f64>,
    kappa: Option<f64>,
) -> Result<(), ThinFilmError> {
    if wavelength <= 0.0 {
        return Err(file_err(path, Some(line), format!("wavelength {wavelength} ≤ 0; wavelengths must be positive")));
    }
    if let Some(n) = n.filter(|&n| n <= 0.0) {
        return Err(file_err(path, Some(line), format!("n = {n} ≤ 0; n must be > 0")));
    }
    if let Some(k) = kappa.filter(|&k| k < 0.0) {
        return Err(file_err(path, Some(line), format!("κ = {k} < 0 (gain); κ must be ≥ 0")));
    }
    Ok(())
}

/// Sorts a table by wavelength and checks it: at least two rows, distinct wavelengths, n > 0, κ ≥ 0.
fn check_table(
    path: &str,
    line: Option<usize>,
    wl: Vec<f64>,
    a: Vec<f64>,
    b: Vec<f64>,
    a_is_k: bool,
) -> Result<Table, ThinFilmError> {
    if wl.len() < 2 {
        return Err(file_err(path, line, "a table needs at least two rows"));
    }
    let mut idx: Vec<usize> = (0..wl.len()).collect();
    idx.sort_by(|&i, &j| wl[i].total_cmp(&wl[j]));
    let wl: Vec<f64> = idx.iter().map(|&i| wl[i]).collect();
    let a: Vec<f64> = idx.iter().map(|&i| a[i]).collect();
    let b: Vec<f64> = if b.is_empty() { b } else { idx.iter().map(|&i| b[i]).collect() };
    if wl.windows(2).any(|w| w[1] <= w[0]) || wl[0] <= 0.0 {
        return Err(file_err(path, line, "wavelengths must be positive and distinct"));
    }
    if a_is_k {
        if let Some(v) = a.iter().find(|&&v| v < 0.0) {
            return Err(file_err(path, line, format!("κ = {v} < 0 (gain) in the table; κ must be ≥ 0")));
        }
    } else if let Some(v) = a.iter().find(|&&v| v <= 0.0) {
        return Err(file_err(path, line, format!("n = {v} ≤ 0 in the table; n must be > 0")));
    }
    if let Some(v) = b.iter().find(|&&v| v < 0.0) {
        return Err(file_err(path, line, format!("κ = {v} < 0 (gain) in the table; κ must be ≥ 0")));
    }
    Ok((wl, a, b))
}

/// The length unit (in nm) that a header's first column names: `wavelength_um`, `lambda (µm)`, `wl[nm]`;
/// `None` when it names none.
fn header_unit_nm(header: &str) -> Option<f64> {
    let first = if header.contains([',', ';', '\t']) {
        header.split([',', ';', '\t']).next().unwrap_or("")
    } else {
        header.split_whitespace().next().unwrap_or("")
    };
    let lower = first.to_lowercase();
    lower.split(|c: char| !(c.is_alphanumeric())).find_map(|word| match word {
        "nm" | "nanometer" | "nanometers" | "nanometre" | "nanometres" => Some(1.0),
        "um" | "µm" | "μm" | "micron" | "microns" | "micrometer" | "micrometers" | "micrometre" | "micrometres" => {
            Some(1e3)
        }
        _ => None,
    })
}

/// Whether a header row starts a κ block: refractiveindex.info's CSV writes `wl,n` rows, then `wl,k` rows.
fn names_kappa(fields: &[&str]) -> bool {
    fields.len() == 2 && matches!(fields[1].trim().to_lowercase().as_str(), "k" | "κ" | "kappa")
}

/// Parses CSV with columns `wavelength, n[, κ]` (commas, semicolons, tabs or spaces; `#` comments and one
/// header line allowed), or refractiveindex.info's CSV: a `wl,n` block, then a `wl,k` block, each on its own
/// wavelengths. Wavelengths are in nm unless the header's first column names µm (`wavelength_um`,
/// `lambda (µm)`).
pub fn parse_csv(text: &str, path: &str) -> Result<Material, ThinFilmError> {
    let (mut wl, mut n, mut k) = (Vec::new(), Vec::new(), Vec::new());
    // The κ block of a two-block file: its wavelengths and values, and the line it starts on.
    let mut kappa_block: Option<(Vec<f64>, Vec<f64>, usize)> = None;
    let mut first_line = true;
    let mut scale = 1.0;
    for TextRow { line, text: t, fields } in text_rows(text, Separators::Any) {
        let parsed: Vec<Option<f64>> = fields.iter().map(|f| f.parse::<f64>().ok().filter(|v| v.is_finite())).collect();
        let header_allowed = std::mem::replace(&mut first_line, false);
        if parsed.iter().any(Option::is_none) {
            if header_allowed {
                // The first line that is not a comment may name the columns, and the wavelength's unit.
                scale = header_unit_nm(t).unwrap_or(1.0);
                continue;
            }
            if kappa_block.is_none() && !wl.is_empty() && names_kappa(&fields) {
                scale = header_unit_nm(t).unwrap_or(scale);
                kappa_block = Some((Vec::new(), Vec::new(), line));
                continue;
            }
            let bad = fields.iter().zip(&parsed).find(|(_, p)| p.is_none()).map(|(f, _)| *f).unwrap_or("");
            return Err(file_err(path, Some(line), format!("'{bad}' is not a finite number")));
        }
        let v: Vec<f64> = parsed.into_iter().flatten().collect();
        if let Some((kw, kv, _)) = kappa_block.as_mut() {
            if v.len() != 2 {
                return Err(file_err(
                    path,
                    Some(line),
                    format!("expected 2 columns (wavelength, κ), found {}", v.len()),
                ));
            }
            check_row(path, line, v[0] * scale, None, Some(v[1]))?;
            kw.push(v[0] * scale);
            kv.push(v[1]);
            continue;
        }
        if !(v.len() == 2 || v.len() == 3) {
            return Err(file_err(
                path,
                Some(line),
                format!("expected 2 or 3 columns (wavelength_nm, n, κ), found {}", v.len()),
            ));
        }
        let kappa = v.get(2).copied().unwrap_or(0.0);
        check_row(path, line, v[0] * scale, Some(v[1]), Some(kappa))?;
        wl.push(v[0] * scale);
        n.push(v[1]);
        k.push(kappa);
    }
    if let Some((kw, kv, start)) = kappa_block {
        // Two blocks on their own wavelengths: n and κ each interpolated on its own, over both's range.
        let (wn, nv, _) = check_table(path, None, wl, n, Vec::new(), false)?;
        let (wk, kv, _) = check_table(path, Some(start), kw, kv, Vec::new(), true)?;
        let range = (wn[0].max(wk[0]), wn[wn.len() - 1].min(wk[wk.len() - 1]));
        if range.0 >= range.1 {
            return Err(file_err(
                path,
                Some(start),
                format!(
                    "its n block covers {}–{} nm and its κ block {}–{} nm: no wavelength has both",
                    wn[0],
                    wn[wn.len() - 1],
                    wk[0],
                    wk[wk.len() - 1]
                ),
            ));
        }
        return Ok(Material::from_parts(
            path.to_string(),
            Part::Table { wl_nm: wn, v: nv },
            Part::Table { wl_nm: wk, v: kv },
            range,
        ));
    }
    let (wl, n, k) = check_table(path, None, wl, n, k, false)?;
    let range = (wl[0], wl[wl.len() - 1]);
    Ok(Material::from_parts(
        path.to_string(),
        Part::Table { wl_nm: wl.clone(), v: n },
        Part::Table { wl_nm: wl, v: k },
        range,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn yaml_formula_plus_k_table() {
        let text = "DATA:\n  - type: formula 2 \n    wavelength_range: 0.3 2.5\n    coefficients: 0 1.03961212 0.00600069867 0.231792344 0.0200179144 1.01046945 103.560653\n  - type: tabulated k\n    data: |\n        0.300 2.8607E-06\n        0.700 8.9305E-09\n        2.500 8.1300E-06\nSPECS:\n    nd: 1.5168\n";
        let m = parse_yaml(text, "bk7.yml").unwrap();
        assert_eq!(m.range_nm(), (300.0, 2500.0));
        let n = m.index_at(700.0).unwrap();
        assert!((n.im - 8.9305e-9).abs() < 1e-20);
    }

    #[test]
    fn yaml_errors_name_the_line() {
        let text = "DATA:\n  - type: tabulated nk\n    data: |\n        0.4 1.5 0.0\n        0.5 1.5 x\n";
        let e = parse_yaml(text, "bad.yml").unwrap_err().to_string();
        assert!(e.contains("bad.yml, line 5") && e.contains("'x'"), "{e}");
        let text = "DATA:\n  - type: tabulated nk\n    data: |\n        0.4 1.5 0.0\n        0.5 1.5 -0.1\n";
        let e = parse_yaml(text, "gain.yml").unwrap_err().to_string();
        assert!(e.contains("κ = -0.1"), "{e}");
        let e = parse_yaml("DATA:\n  - type: tabulated eps\n", "e.yml").unwrap_err().to_string();
        assert!(e.contains("unsupported type 'tabulated eps'") && e.contains("line 2"), "{e}");
        assert!(parse_yaml("REFERENCES: x\n", "n.yml").is_err());
    }

    #[test]
    fn gas_formula_ciddor_air() {
        // Ciddor 1996 (Appl. Opt. 35, 1566), standard air, as the database writes it (formula 6):
        // n − 1 = 0.05792105/(238.0185 − λ⁻²) + 0.00167917/(57.362 − λ⁻²); n = 1.000277 at 587.6 nm.
        let text = "DATA:\n  - type: formula 6\n    wavelength_range: 0.23 1.69\n    coefficients: 0 0.05792105 238.0185 0.00167917 57.362\n";
        let m = parse_yaml(text, "air.yml").unwrap();
        assert!((m.index_at(587.6).unwrap().re - 1.000277).abs() < 1e-6);
        assert!(m.index_at(200.0).is_err());
    }

    #[test]
    fn csv_with_header() {
        let m = parse_csv("wavelength_nm,n,k\n400,1.5,0.1\n500,1.6,0.2\n", "x.csv").unwrap();
        let n = m.index_at(450.0).unwrap();
        assert!((n.re - 1.55).abs() < 1e-12 && (n.im - 0.15).abs() < 1e-12);
        assert!(m.index_at(399.0).is_err());
        let e = parse_csv("400,1.5\n500,abc\n", "y.csv").unwrap_err().to_string();
        assert!(e.contains("line 2") && e.contains("abc"), "{e}");
    }

    /// refractiveindex.info's CSV download: an n block, then a κ block under its own `wl,k` header, each on its
    /// own wavelengths (it failed with "'wl' is not a finite number"); in µm as that site writes them, said by
    /// the header's unit, or, unsaid, pointed out where the data seem to end at 0.7 nm.
    #[test]
    fn csv_of_two_blocks_n_then_kappa() {
        let text = "wl_um,n\n0.4,1.50\n0.5,1.48\n0.7,1.46\nwl,k\n0.45,0.010\n0.65,0.030\n";
        let m = parse_csv(text, "ri.csv").unwrap();
        assert_eq!(m.range_nm(), (450.0, 650.0));
        // n at 600 nm between 1.48 (500) and 1.46 (700); κ at 600 nm between 0.010 (450) and 0.030 (650).
        let i = m.index_at(600.0).unwrap();
        assert!((i.re - 1.47).abs() < 1e-12 && (i.im - 0.025).abs() < 1e-12, "{i}");
        let e = parse_csv("wl,n\n0.4,1.5\n0.7,1.5\nwl,k\n0.8,0\n0.9,0\n", "apart.csv").unwrap_err().to_string();
        assert!(e.contains("no wavelength has both"), "{e}");
        let unsaid = parse_csv("wl,n\n0.4,1.5\n0.7,1.5\n", "um.csv").unwrap();
        let e = unsaid.index_at(550.0).unwrap_err().to_string();
        assert!(
            e.contains("0.4–0.7 nm only") && e.contains("look like µm: name the first column wavelength_um"),
            "{e}"
        );
    }

    #[test]
    fn csv_header_names_the_wavelength_unit() {
        // The same gold-like table in µm and nm: read in the header's unit, so both cover 350–800 nm.
        for (text, name) in [
            ("wavelength_um,n,k\n0.35,1.5,1.9\n0.8,0.15,4.9\n", "um.csv"),
            ("wavelength (µm);n;k\n0.35;1.5;1.9\n0.8;0.15;4.9\n", "mu.csv"),
            ("lambda_nm n k\n350 1.5 1.9\n800 0.15 4.9\n", "nm.csv"),
            ("# no header: nm\n350,1.5,1.9\n800,0.15,4.9\n", "bare.csv"),
        ] {
            let m = parse_csv(text, name).unwrap();
            assert_eq!(m.range_nm(), (350.0, 800.0), "{name}");
            assert!((m.index_at(800.0).unwrap().im - 4.9).abs() < 1e-12, "{name}");
        }
        // Words that merely contain the letters are not units.
        assert_eq!(header_unit_nm("wavenumber,n,k"), None);
    }

    #[test]
    fn csv_errors_name_the_line() {
        let e = parse_csv("# nk\nwavelength_nm,n,k\n400,1.5,0.1\n500,1.6,-0.2\n600,1.6,0.1\n", "g.csv").unwrap_err();
        assert_eq!(e.to_string(), "g.csv, line 4: κ = -0.2 < 0 (gain); κ must be ≥ 0");
        let e = parse_csv("400,1.5\n500,0\n", "n.csv").unwrap_err().to_string();
        assert!(e.starts_with("n.csv, line 2: n = 0 ≤ 0"), "{e}");
        // Only the first line that is not a comment may be a header.
        let e = parse_csv("400,1.5\nwavelength_nm,n\n500,1.6\n", "h.csv").unwrap_err().to_string();
        assert!(e.starts_with("h.csv, line 2: 'wavelength_nm'"), "{e}");
        let e = parse_csv("400,1.5,0,7\n500,1.6\n", "c.csv").unwrap_err().to_string();
        assert!(e.starts_with("c.csv, line 1: expected 2 or 3 columns") && e.contains("found 4"), "{e}");
    }

    #[test]
    fn yaml_row_errors_name_the_row_line() {
        let text = "DATA:\n  - type: tabulated nk\n    data: |\n        0.4 1.5 0.0\n        0.5 1.5 -0.1\n        0.6 1.5 0.0\n";
        let e = parse_yaml(text, "gain.yml").unwrap_err().to_string();
        assert_eq!(e, "gain.yml, line 5: κ = -0.1 < 0 (gain); κ must be ≥ 0");
        let text = "DATA:\n  - type: tabulated n\n    data: |\n        0.4 1.5\n        0.5 -1.5\n";
        let e = parse_yaml(text, "n.yml").unwrap_err().to_string();
        assert!(e.starts_with("n.yml, line 5: n = -1.5 ≤ 0"), "{e}");
        let text = "DATA:\n  - type: tabulated k\n    data: |\n        0.4 0.1\n        0.5 0.2 0.3\n";
        let e = parse_yaml(text, "k.yml").unwrap_err().to_string();
        assert!(e.starts_with("k.yml, line 5: 'tabulated k' rows have 2 numbers, this one has 3"), "{e}");
        let text = "DATA:\n  - type: tabulated k\n    data: |\n        0.4 0.1\n        -0.5 0.2\n";
        let e = parse_yaml(text, "w.yml").unwrap_err().to_string();
        assert!(e.starts_with("w.yml, line 5: wavelength -0.5 ≤ 0"), "{e}");
    }
}
