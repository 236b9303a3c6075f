//! Measured spectra from the text files instruments and spreadsheets write ([`read`]): columns separated by
//! commas, tabs, semicolons or spaces (decimal commas with semicolons, tabs or spaces), an optional header in any
//! common form (`wavelength_nm,R`, `Wavelength (nm),Reflectance (%)`, `lambda [um]\tT`, `nm;%R`, none at all),
//! lines of instrument metadata before it, `#` and `//` comments. What was found is written into
//! [`Reading::notes`] so that front ends can say it: the separator, the columns taken, the wavelength unit,
//! whether the values were percent (from the header, from values above 1.5, or `percent`), the rows left out by a
//! wavelength window. Columns can be named or numbered ([`ReadOptions::columns`]); 1σ uncertainties or weights
//! come from a number, columns, or (weights) a separate file.

use crate::{FitError, Quantity};

/// A measured spectrum: wavelengths, values (one per wavelength; two — ψ, Δ — for ellipsometry, interleaved)
/// and optional 1σ uncertainties in the same layout.
#[derive(Debug, Clone, PartialEq)]
pub struct Measured {
    pub wavelength_nm: Vec<f64>,
    pub values: Vec<f64>,
    pub sigma: Option<Vec<f64>>,
}

/// How to read a measured spectrum.
#[derive(Debug, Clone, PartialEq)]
pub struct ReadOptions {
    pub quantity: Quantity,
    /// The columns to take, by header name or 1-based number, comma-separated: wavelength and the value (R or
    /// T), or wavelength, ψ and Δ. `None`: found from the header (or the first columns without one).
    pub columns: Option<String>,
    /// The values are percent (`Some(true)`) or fractions (`Some(false)`); `None`: a `%` or "percent" in the
    /// value column's header, or values above 1.5, mean percent. Refused (`Some`) for ψ/Δ, which are angles.
    pub percent: Option<bool>,
    /// Keep only wavelengths in this window (nm, inclusive).
    pub from_nm: Option<f64>,
    pub to_nm: Option<f64>,
    /// The `--sigma` / `--weights` argument: a number (in the file's units), column name(s), or — weights
    /// only — the path of a separate file, read through the caller's loader.
    pub spread: Option<(String, Spread)>,
}

impl ReadOptions {
    pub fn new(quantity: Quantity) -> Self {
        Self { quantity, columns: None, percent: None, from_nm: None, to_nm: None, spread: None }
    }
}

/// A spectrum read by [`read`], with what was found out on the way.
#[derive(Debug, Clone, PartialEq)]
pub struct Reading {
    pub data: Measured,
    /// One line per finding, for people ("tab-separated; header line 3", "R in percent (header 'R (%)'): divided
    /// by 100", …).
    pub notes: Vec<String>,
    /// The values were percent and are now fractions.
    pub percent: bool,
    /// The columns used (names from the header, or "column 2").
    pub columns: Vec<String>,
}

/// Names of measured quantities: a column so named is not taken for another quantity.
const OTHER_QUANTITIES: &[&str] = &[
    "r",
    "reflectance",
    "reflectivity",
    "refl",
    "reflection",
    "t",
    "transmittance",
    "transmission",
    "trans",
    "psi",
    "ψ",
    "delta",
    "δ",
    "Δ",
    "a",
    "absorptance",
    "absorbance",
];

const WAVELENGTH: &[&str] =
    &["wavelength", "wavelengths", "wl", "lambda", "λ", "wave", "nm", "um", "µm", "energy", "ev"];

/// The field separator of a file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Sep {
    Tab,
    Semicolon,
    Comma,
    Space,
}

impl Sep {
    fn name(self) -> &'static str {
        match self {
            Sep::Tab => "tab-separated",
            Sep::Semicolon => "semicolon-separated",
            Sep::Comma => "comma-separated",
            Sep::Space => "space-separated",
        }
    }
    fn split(self, line: &str) -> Vec<String> {
        let clean = |s: &str| s.trim().trim_matches('"').trim().to_string();
        match self {
            Sep::Tab => line.split('\t').map(clean).collect(),
            Sep::Semicolon => line.split(';').map(clean).collect(),
            Sep::Comma => line.split(',').map(clean).collect(),
            Sep::Space => line.split_whitespace().map(clean).collect(),
        }
    }
}

/// A number as written in a cell: `1.5`, `1,5` (decimal comma, where commas do not separate), `1e-3`.
fn number(cell: &str, sep: Sep) -> Option<f64> {
    let t = cell.trim();
    let v = t.parse::<f64>().ok().or_else(|| {
        if sep != Sep::Comma && t.matches(',').count() == 1 && !t.contains('.') {
            t.replace(',', ".").parse::<f64>().ok()
        } else {
            None
        }
    })?;
    v.is_finite().then_some(v)
}

fn numeric_row(line: &str, sep: Sep) -> Option<Vec<f64>> {
    let mut cells = sep.split(line);
    while cells.last().is_some_and(|c| c.is_empty()) {
        cells.pop(); // a trailing separator
    }
    if cells.len() < 2 {
        return None;
    }
    cells.iter().map(|c| number(c, sep)).collect()
}

fn is_comment(line: &str) -> bool {
    let t = line.trim_start();
    t.starts_with('#') || t.starts_with("//")
}

/// Normalised column name: lower case, without units in brackets or after `/`, without `_nm`.
fn base_name(name: &str) -> String {
    let mut s = name.trim().to_lowercase();
    for (open, close) in [('(', ')'), ('[', ']')] {
        while let (Some(a), Some(b)) = (s.find(open), s.find(close)) {
            if b < a {
                break;
            }
            s.replace_range(a..=b, " ");
        }
    }
    if let Some(i) = s.find('/') {
        s.truncate(i);
    }
    let s = s.replace('%', " ");
    let s = s.trim().trim_end_matches("_nm").trim_end_matches("_um").trim_end_matches("_deg").trim();
    s.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// The wavelength unit a header names: factor to nm, or `None` for energy in eV (converted separately).
fn header_unit(name: &str) -> Option<Option<f64>> {
    let s = name.to_lowercase();
    let has = |u: &str| {
        s.split(|c: char| !c.is_alphanumeric() && c != 'µ' && c != 'å').any(|w| w == u) || s.ends_with(&format!("_{u}"))
    };
    if has("ev") {
        Some(None)
    } else if has("nm") {
        Some(Some(1.0))
    } else if has("um") || has("µm") || has("micron") || has("microns") {
        Some(Some(1000.0))
    } else if has("å") || has("angstrom") || has("a") && s.contains('[') {
        Some(Some(0.1))
    } else if has("m") {
        Some(Some(1e9))
    } else {
        None
    }
}

fn says_percent(name: &str) -> bool {
    let s = name.to_lowercase();
    s.contains('%') || s.contains("percent")
}

/// What `--sigma` / `--weights` names: a number, columns of the measured file, or a file.
#[derive(Debug, Clone, PartialEq)]
pub enum SpreadSource {
    Value(f64),
    Columns(String),
    File(String),
}

impl SpreadSource {
    /// Reads the argument against the measured file's header: a number, then column names, then (weights
    /// only) a file path.
    pub fn of(arg: &str, kind: Spread, header: &[String]) -> Self {
        let arg = arg.trim();
        if let Ok(v) = arg.parse::<f64>() {
            return Self::Value(v);
        }
        let is_column = arg.split(',').all(|c| {
            let c = c.trim();
            header.iter().any(|h| h.eq_ignore_ascii_case(c))
                || c.parse::<usize>().is_ok_and(|i| i >= 1 && i <= header.len())
        });
        if kind == Spread::Weight && !is_column {
            Self::File(arg.to_string())
        } else {
            Self::Columns(arg.to_string())
        }
    }
}

/// The layout of a file: separator, header (if any), data lines.
struct Layout<'a> {
    sep: Sep,
    header: Option<(usize, Vec<String>)>,
    skipped: usize,
    rows: Vec<(usize, &'a str)>,
}

fn layout<'a>(text: &'a str, path: &str) -> Result<Layout<'a>, FitError> {
    let lines: Vec<(usize, &str)> = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim_start_matches('\u{feff}').trim_end()))
        .filter(|(_, l)| !l.trim().is_empty() && !is_comment(l))
        .collect();
    for (k, &(_, line)) in lines.iter().enumerate() {
        for sep in [Sep::Tab, Sep::Semicolon, Sep::Comma, Sep::Space] {
            let Some(first) = numeric_row(line, sep) else { continue };
            // Data from here on; the line before (if not numeric) is the header, the rest before it metadata.
            let header = if k > 0 {
                let (no, h) = lines[k - 1];
                let mut names = sep.split(h);
                if sep == Sep::Space && names.len() != first.len() {
                    // Names with spaces ("Wavelength (nm)   R (%)"): split at runs of two or more spaces.
                    names = h
                        .split("  ")
                        .map(|s| s.trim().trim_matches('"').to_string())
                        .filter(|s| !s.is_empty())
                        .collect();
                }
                while names.last().is_some_and(|c| c.is_empty()) {
                    names.pop();
                }
                Some((no, names))
            } else {
                None
            };
            return Ok(Layout { sep, header, skipped: k.saturating_sub(1), rows: lines[k..].to_vec() });
        }
    }
    Err(FitError::Data(format!(
        "{path}: no line of numbers (at least two per line, separated by commas, tabs, semicolons or spaces)"
    )))
}

/// The header names of a measured file (empty when it has none).
pub fn header(text: &str) -> Vec<String> {
    layout(text, "").ok().and_then(|l| l.header.map(|h| h.1)).unwrap_or_default()
}

/// Reads a measured spectrum (module documentation). `load` reads a separate weights file named by
/// `--weights`.
pub fn read(
    text: &str,
    path: &str,
    opts: &ReadOptions,
    load: &dyn Fn(&str) -> Result<String, String>,
) -> Result<Reading, FitError> {
    let q = opts.quantity;
    let lay = layout(text, path)?;
    let mut notes = Vec::new();
    let width = lay.rows.first().and_then(|(_, l)| numeric_row(l, lay.sep)).map_or(0, |r| r.len());
    let names: Vec<String> = match &lay.header {
        Some((_, h)) if h.len() == width => h.clone(),
        Some((no, h)) => {
            notes.push(format!(
                "line {no} ({} names) does not match the {width} columns of the data; columns are numbered",
                h.len()
            ));
            (1..=width).map(|i| format!("column {i}")).collect()
        }
        None => (1..=width).map(|i| format!("column {i}")).collect(),
    };
    let has_header = names.first().is_some_and(|n| !n.starts_with("column "));
    let mut head = lay.sep.name().to_string();
    match &lay.header {
        Some((no, _)) if has_header => head += &format!(", header on line {no}"),
        _ => head += ", no header",
    }
    if lay.skipped > 0 {
        head += &format!(", {} line(s) before it skipped", lay.skipped);
    }
    notes.push(head);
    let err = |line: usize, m: String| FitError::Data(format!("{path}, line {line}: {m}"));
    let find_by_name = |name: &str| -> Option<usize> {
        let n = name.trim();
        if let Ok(i) = n.parse::<usize>() {
            return (i >= 1 && i <= names.len()).then(|| i - 1);
        }
        names.iter().position(|h| h.eq_ignore_ascii_case(n)).or_else(|| {
            let b = base_name(n);
            names.iter().position(|h| base_name(h) == b)
        })
    };
    let labels: Vec<&str> = match q {
        Quantity::R => vec!["R"],
        Quantity::T => vec!["T"],
        Quantity::PsiDelta => vec!["psi", "delta"],
    };
    // Whether column i's name is one of `want` (the unit in brackets and the case aside).
    let is = |i: usize, want: &[&str]| {
        let b = base_name(&names[i]);
        want.iter().any(|w| b == *w || b.starts_with(&format!("{w} ")) || b.replace(' ', "_") == *w)
    };
    let wanted: Vec<&[&str]> = match q {
        Quantity::R => vec![&["r", "reflectance", "reflectivity", "refl", "reflection", "r_meas", "rmeas"]],
        Quantity::T => vec![&["t", "transmittance", "transmission", "trans", "t_meas", "tmeas"]],
        Quantity::PsiDelta => vec![&["psi", "ψ", "psi_deg"], &["delta", "δ", "Δ", "delta_deg"]],
    };
    // The columns: given, or found.
    let cols: Vec<usize> = if let Some(spec) = &opts.columns {
        let parts: Vec<&str> = spec.split(',').map(str::trim).collect();
        if parts.len() != 1 + labels.len() {
            return Err(FitError::Data(format!(
                "--columns '{spec}': give {} columns, wavelength then {} (names or numbers from 1); the columns are {names:?}",
                1 + labels.len(),
                labels.join(" and ")
            )));
        }
        let cols: Vec<usize> = parts
            .iter()
            .map(|p| {
                find_by_name(p).ok_or_else(|| FitError::Data(format!("--columns: no column '{p}' among {names:?}")))
            })
            .collect::<Result<_, _>>()?;
        // A column chosen by number whose header names another quantity (`--columns 1,3` on wl,R,T fitted T's
        // values as R without a word): fitted as asked, and said.
        for (k, &c) in cols[1..].iter().enumerate() {
            if has_header && is(c, OTHER_QUANTITIES) && !is(c, wanted[k]) {
                notes.push(format!(
                    "column '{}' is fitted as {} (--quantity {}), though its name says another quantity; \
                     --quantity chooses what the model computes",
                    names[c],
                    labels[k],
                    q.name()
                ));
            }
        }
        cols
    } else if has_header {
        let wl = (0..names.len()).find(|&i| is(i, WAVELENGTH)).ok_or_else(|| {
            err(
                lay.header.as_ref().map_or(1, |h| h.0),
                format!(
                    "no wavelength column among {names:?} (a name like 'wavelength', 'Wavelength (nm)', 'lambda', 'nm'); \
                     or name the columns with --columns WAVELENGTH,{}",
                    labels.join(",").to_uppercase()
                ),
            )
        })?;
        let mut cols = vec![wl];
        for (k, want) in wanted.iter().enumerate() {
            let found = (0..names.len()).find(|&i| i != wl && is(i, want));
            let c = match found {
                Some(c) => c,
                // A file of two columns: the other one is the value, unless its name says it is something else.
                None if names.len() == 2 && q != Quantity::PsiDelta && !is(1 - wl, OTHER_QUANTITIES) => {
                    let c = 1 - wl;
                    notes.push(format!("column '{}' taken as {} (the only other column)", names[c], labels[k]));
                    c
                }
                None => {
                    return Err(err(
                        lay.header.as_ref().map_or(1, |h| h.0),
                        format!(
                            "no measured column '{}' for --quantity {} among {names:?}; name it (e.g. '{}') or choose with \
                             --columns",
                            labels[k],
                            q.name(),
                            want[1]
                        ),
                    ))
                }
            };
            cols.push(c);
        }
        cols
    } else {
        if width < 1 + labels.len() {
            return Err(FitError::Data(format!(
                "{path}: {width} columns, but {} needs {} (wavelength, {})",
                q.name(),
                1 + labels.len(),
                labels.join(", ")
            )));
        }
        notes.push(format!(
            "no header: column 1 is the wavelength, {} the {}",
            (2..=labels.len() + 1).map(|i| format!("column {i}")).collect::<Vec<_>>().join(" and "),
            labels.join(" and ")
        ));
        (0..=labels.len()).collect()
    };
    // Uncertainties.
    let spread = opts.spread.as_ref().map(|(arg, kind)| (SpreadSource::of(arg, *kind, &names), *kind));
    let sig_cols: Option<Vec<usize>> = match &spread {
        Some((SpreadSource::Columns(s), kind)) => {
            let parts: Vec<&str> = s.split(',').map(str::trim).collect();
            let parts = if parts.len() == 1 { vec![parts[0]; labels.len()] } else { parts };
            if parts.len() != labels.len() {
                return Err(FitError::Data(format!(
                    "{}: give {} column name(s), got '{s}'",
                    kind.flag(),
                    labels.len()
                )));
            }
            Some(
                parts
                    .iter()
                    .map(|p| {
                        find_by_name(p).ok_or_else(|| {
                            FitError::Data(format!("{}: no {} column '{p}' among {names:?}", kind.flag(), kind.what()))
                        })
                    })
                    .collect::<Result<_, _>>()?,
            )
        }
        _ => None,
    };
    // Rows.
    let mut wl = Vec::new();
    let mut vals = Vec::new();
    let mut sig = Vec::new();
    let mut footer = 0usize;
    for (idx, &(no, line)) in lay.rows.iter().enumerate() {
        let Some(row) = numeric_row(line, lay.sep) else {
            // Text after the data (an instrument's footer) ends the data; text between data rows is an error.
            if lay.rows[idx + 1..].iter().all(|(_, l)| numeric_row(l, lay.sep).is_none()) {
                footer = lay.rows.len() - idx;
                break;
            }
            let cells = lay.sep.split(line);
            let bad = cells.iter().find(|c| number(c, lay.sep).is_none()).cloned().unwrap_or_default();
            return Err(err(no, format!("'{bad}' is not a number ({} columns expected)", names.len())));
        };
        let cell = |c: usize, what: &str| {
            row.get(c)
                .copied()
                .ok_or_else(|| err(no, format!("no {what} in column {} (the row has {})", c + 1, row.len())))
        };
        wl.push(cell(cols[0], "wavelength")?);
        for k in 0..labels.len() {
            vals.push(cell(cols[1 + k], labels[k])?);
            if let Some(sc) = &sig_cols {
                let v = cell(sc[k], "uncertainty")?;
                let (_, kind) = spread.as_ref().expect("columns come from a spread");
                sig.push(kind.sigma(v).map_err(|m| err(no, m))?);
            }
        }
    }
    if footer > 0 {
        notes.push(format!("{footer} line(s) of text after the data ignored"));
    }
    if wl.is_empty() {
        return Err(FitError::Data(format!("{path}: no data rows")));
    }
    let used: Vec<String> = cols.iter().map(|&c| names[c].clone()).collect();
    // Wavelength unit.
    let (lo, hi) = wl.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| (a.min(v), b.max(v)));
    match (has_header, header_unit(&names[cols[0]])) {
        (true, Some(None)) => {
            if lo <= 0.0 {
                return Err(FitError::Data(format!("{path}: photon energies must be > 0 eV, found {lo}")));
            }
            for w in &mut wl {
                *w = 1_239.841_984 / *w;
            }
            notes.push(format!("column '{}' is photon energy (eV): λ = 1239.84 nm·eV / E", names[cols[0]]));
        }
        (true, Some(Some(f))) if f != 1.0 => {
            for w in &mut wl {
                *w *= f;
            }
            notes.push(format!("wavelengths in '{}' converted to nm (×{f})", names[cols[0]]));
        }
        (_, None) | (false, _) if hi < 1e-4 && lo > 0.0 => {
            for w in &mut wl {
                *w *= 1e9;
            }
            notes.push(format!("wavelengths {lo:e}–{hi:e} read as metres (no unit given): converted to nm"));
        }
        (_, None) | (false, _) if hi < 20.0 && lo > 0.0 => {
            for w in &mut wl {
                *w *= 1000.0;
            }
            notes.push(format!("wavelengths {lo}–{hi} read as µm (no unit given; below 20): converted to nm"));
        }
        _ => {}
    }
    if let Some((i, w)) = wl.iter().enumerate().find(|(_, w)| **w <= 0.0) {
        return Err(FitError::Data(format!("{path}: wavelength {w} nm in data row {} must be positive", i + 1)));
    }
    let spread_value = match &spread {
        Some((SpreadSource::Value(v), kind)) => Some((*v, *kind)),
        _ => None,
    };
    let raw = Raw { wl, vals, sig: sig_cols.map(|_| sig) };
    let header_says_percent = (has_header && says_percent(&names[cols[1]])).then(|| names[cols[1]].as_str());
    let clue = PercentClue::File { header_says_percent };
    let (mut data, percent) = settle(raw, opts, path, clue, spread_value, &mut notes)?;
    if let Some((SpreadSource::File(f), _)) = spread {
        let wtext = load(&f).map_err(|e| {
            FitError::Data(format!(
                "--weights '{f}' is neither a number, a column of {path} (its columns: {}), nor a file ({e})",
                names.join(", ")
            ))
        })?;
        data.set_weights_from_csv(&wtext, &f, q)?;
        if percent {
            if let Some(s) = &mut data.sigma {
                for v in s.iter_mut() {
                    *v /= 100.0;
                }
            }
        }
    }
    Ok(Reading { data, notes, percent, columns: used })
}

/// A measurement's numbers as read: wavelengths (nm), values (R or T; ψ, Δ interleaved), 1σ per value.
struct Raw {
    wl: Vec<f64>,
    vals: Vec<f64>,
    sig: Option<Vec<f64>>,
}

/// Where a percent reading may come from besides [`ReadOptions::percent`].
enum PercentClue<'a> {
    /// A file: the value column's header when it says `%` or "percent", and values above 1.5.
    File { header_says_percent: Option<&'a str> },
    /// Arrays carry no header: percent must be said, values above 1.5 without it are refused.
    Arrays,
}

impl PercentClue<'_> {
    /// What the data came as, for messages.
    fn origin(&self) -> &'static str {
        match self {
            PercentClue::File { .. } => "file",
            PercentClue::Arrays => "arrays",
        }
    }
}

/// What [`read`] and [`read_arrays`] do alike once the values are numbers: percent (said, or from the clue),
/// the wavelength window, and a σ or weight given as one number. `source` names the data in messages. Returns
/// the measurement and whether its values were percent.
fn settle(
    raw: Raw,
    opts: &ReadOptions,
    source: &str,
    clue: PercentClue,
    spread_value: Option<(f64, Spread)>,
    notes: &mut Vec<String>,
) -> Result<(Measured, bool), FitError> {
    let q = opts.quantity;
    let Raw { mut wl, mut vals, mut sig } = raw;
    if let (Quantity::PsiDelta, Some(p)) = (q, opts.percent) {
        // ψ and Δ are angles: a percent (or fraction) setting would be ignored.
        let said = if p { "--percent" } else { "percent=False" };
        return Err(FitError::Data(format!(
            "{said} would be ignored: ψ and Δ are angles in degrees, read as they stand (percent applies to R and T)"
        )));
    }
    let mut percent = false;
    if q != Quantity::PsiDelta {
        let label = if q == Quantity::T { "T" } else { "R" };
        let vmax = vals.iter().fold(f64::NEG_INFINITY, |a, &b| a.max(b));
        percent = match (opts.percent, &clue) {
            (Some(p), _) => {
                if p {
                    notes.push(format!("{label} in percent (--percent): divided by 100"));
                }
                p
            }
            (None, PercentClue::File { header_says_percent: Some(name) }) => {
                notes.push(format!("{label} in percent (header '{name}'): divided by 100"));
                true
            }
            (None, PercentClue::File { .. }) if vmax > 1.5 => {
                notes.push(format!(
                    "{label} values reach {vmax} > 1: read as percent and divided by 100 (a fraction cannot exceed 1)"
                ));
                true
            }
            (None, PercentClue::Arrays) if vmax > 1.5 => {
                return Err(FitError::Data(format!(
                    "the values reach {vmax} > 1: if they are percent, say percent=True (--percent)"
                )));
            }
            // Said either way: an anti-reflection coating's R in percent stays under 1 and reads as fractions
            // (fitted with χ² 0.0008 to a wrong film, in silence).
            (None, PercentClue::File { .. }) => {
                let why = if vmax > 1.0 {
                    // Between 1 and 1.5: a fraction over 1 (a baseline off) or percent under 1.5 — both happen.
                    " — above 1, which a fraction cannot be: a baseline or calibration off, or percent under 1.5"
                } else if vmax < 0.05 {
                    " — so small a reflectance is also how a good anti-reflection coating's reads in percent"
                } else {
                    ""
                };
                notes.push(format!(
                    "{label} read as fractions (no '%' in the header, none above 1.5: the values reach {vmax:.4}){why}; \
                     --percent if they are percent"
                ));
                false
            }
            (None, PercentClue::Arrays) => false,
        };
        if percent {
            for v in vals.iter_mut().chain(sig.iter_mut().flatten()) {
                *v /= 100.0;
            }
        }
        let vmax = vals.iter().fold(f64::NEG_INFINITY, |a, &b| a.max(b));
        let vmin = vals.iter().fold(f64::INFINITY, |a, &b| a.min(b));
        if vmax > 1.05 || vmin < -0.05 {
            notes.push(format!(
                "{label} runs from {vmin:.4} to {vmax:.4}, outside 0–1: check --percent and the baseline"
            ));
        }
    }
    // The wavelength window.
    if let (Some(a), Some(b)) = (opts.from_nm, opts.to_nm) {
        if a >= b {
            return Err(FitError::Data(format!("--from {a} nm must be below --to {b} nm")));
        }
    }
    let k = q.width();
    let keep: Vec<bool> = wl
        .iter()
        .map(|&w| opts.from_nm.is_none_or(|a| w >= a - 1e-9) && opts.to_nm.is_none_or(|b| w <= b + 1e-9))
        .collect();
    let dropped = keep.iter().filter(|k| !**k).count();
    if dropped > 0 {
        let (lo, hi) = wl.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| (a.min(v), b.max(v)));
        let n = wl.len();
        let take =
            |v: &[f64]| -> Vec<f64> { v.iter().enumerate().filter(|(i, _)| keep[i / k]).map(|(_, x)| *x).collect() };
        vals = take(&vals);
        sig = sig.map(|s| take(&s));
        wl = wl.iter().zip(&keep).filter(|(_, k)| **k).map(|(w, _)| *w).collect();
        if wl.is_empty() {
            return Err(FitError::Data(format!(
                "{source}: no wavelength of the {} ({lo}–{hi} nm) lies in the window {}–{} nm",
                clue.origin(),
                opts.from_nm.map_or("…".into(), |v| v.to_string()),
                opts.to_nm.map_or("…".into(), |v| v.to_string())
            )));
        }
        notes.push(format!("{dropped} of {n} rows outside the wavelength window left out"));
    }
    let mut data = Measured { wavelength_nm: wl, values: vals, sigma: sig };
    if let Some((v, kind)) = spread_value {
        let s = kind.sigma(v).map_err(|m| FitError::Data(format!("{} {v}: {m}", kind.flag())))?;
        let s = if percent {
            let whose = match clue {
                PercentClue::File { .. } => "the file's",
                PercentClue::Arrays => "the values'",
            };
            notes.push(format!("{} {v} is in {whose} unit (percent)", kind.flag()));
            s / 100.0 // σ, or 1/√w, in percent → fraction
        } else {
            s
        };
        data.sigma = Some(vec![s; data.values.len()]);
    }
    Ok((data, percent))
}

/// A measurement given as arrays (Python's `fit((wavelengths_nm, values[, sigma]))`), read by the rules of
/// [`read`] that apply without a file: percent only when said, the wavelength window, `--sigma`/`--weights` as
/// one number. Wavelengths in nm; ψ, Δ interleaved. Column choices are refused (there are no columns).
pub fn read_arrays(
    wavelength_nm: Vec<f64>,
    values: Vec<f64>,
    sigma: Option<Vec<f64>>,
    opts: &ReadOptions,
) -> Result<Reading, FitError> {
    if let Some(c) = &opts.columns {
        return Err(FitError::Data(format!(
            "--columns '{c}' would be ignored: the measurement was given as arrays, not as a file"
        )));
    }
    let given = Measured::from_arrays(wavelength_nm, values, sigma, opts.quantity)?;
    let spread_value = match &opts.spread {
        Some((arg, kind)) => {
            if given.sigma.is_some() {
                return Err(FitError::Data(format!(
                    "{} given twice: as an array of uncertainties and as {} {arg}",
                    kind.what(),
                    kind.flag()
                )));
            }
            let v = arg.trim().parse::<f64>().map_err(|_| {
                FitError::Data(format!(
                    "{} '{arg}': with arrays give a number (column names and weight files are for a measured file)",
                    kind.flag()
                ))
            })?;
            Some((v, *kind))
        }
        None => None,
    };
    let mut notes = vec!["arrays given: wavelengths in nm".to_string()];
    let raw = Raw { wl: given.wavelength_nm, vals: given.values, sig: given.sigma };
    let (data, percent) = settle(raw, opts, "measured", PercentClue::Arrays, spread_value, &mut notes)?;
    Ok(Reading { data, notes, percent, columns: Vec::new() })
}

impl Measured {
    /// Reads CSV text; `path` names it in messages; `sigma_column` names the 1σ column(s): for ψ/Δ two
    /// names separated by a comma (or one column used for both). [`read`] with its defaults.
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
        let mut opts = ReadOptions::new(quantity);
        opts.spread = column.map(|(c, k)| (c.to_string(), k));
        let no_files = |f: &str| Err(format!("'{f}' is not a column"));
        Ok(read(text, path, &opts, &no_files)?.data)
    }

    /// Checks arrays given directly (Python): equal lengths, finite values, positive wavelengths in nm.
    pub fn from_arrays(
        wavelength_nm: Vec<f64>,
        values: Vec<f64>,
        sigma: Option<Vec<f64>>,
        quantity: Quantity,
    ) -> Result<Self, FitError> {
        let k = quantity.width();
        if values.len() != wavelength_nm.len() * k {
            return Err(FitError::Data(format!(
                "{} wavelengths need {} values for {} ({} given)",
                wavelength_nm.len(),
                wavelength_nm.len() * k,
                quantity.name(),
                values.len()
            )));
        }
        if let Some((i, w)) = wavelength_nm.iter().enumerate().find(|(_, w)| !(w.is_finite() && **w > 0.0)) {
            return Err(FitError::Data(format!("wavelength {w} at index {i} must be a finite number > 0 (nm)")));
        }
        if let Some((i, v)) = values.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Err(FitError::Data(format!("measured value {v} at index {i} is not finite")));
        }
        if let Some(s) = &sigma {
            if s.len() != values.len() {
                return Err(FitError::Data(format!("{} uncertainties for {} values", s.len(), values.len())));
            }
            if let Some((i, v)) = s.iter().enumerate().find(|(_, v)| !(v.is_finite() && **v > 0.0)) {
                return Err(FitError::Data(format!("uncertainty {v} at index {i} must be a finite number > 0")));
            }
        }
        Ok(Self { wavelength_nm, values, sigma })
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

impl Measured {
    /// Sets the uncertainties from a separate weights file (`--weights FILE`): the wavelength column and, per
    /// measured value, a weight column `w` (or `weight`); for ψ/Δ `w_psi` and `w_delta` (or one `w` for both).
    /// Its wavelengths must be those of the measurement, row by row. Any separator [`read`] knows.
    pub fn set_weights_from_csv(&mut self, text: &str, path: &str, quantity: Quantity) -> Result<(), FitError> {
        let err = |line: usize, m: String| FitError::Data(format!("{path}, line {line}: {m}"));
        let lay = layout(text, path)?;
        let names = lay.header.as_ref().map(|h| h.1.clone()).unwrap_or_default();
        let find = |want: &[&str]| names.iter().position(|n| want.iter().any(|w| base_name(n) == *w));
        let wl = find(&["wavelength", "wavelength_nm", "wl", "lambda", "lambda_nm", "wl_nm"])
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
        if lay.rows.len() != self.wavelength_nm.len() {
            return Err(FitError::Data(format!(
                "{path}: {} rows of weights for {} measured wavelengths; give one row per measured wavelength",
                lay.rows.len(),
                self.wavelength_nm.len()
            )));
        }
        let mut sigma = Vec::with_capacity(self.values.len());
        for (&(no, line), &w_meas) in lay.rows.iter().zip(&self.wavelength_nm) {
            let cells = lay.sep.split(line);
            let num = |c: usize| cells.get(c).and_then(|t| number(t, lay.sep));
            let w = num(wl).ok_or_else(|| err(no, format!("wavelength '{}' is not a number", cells[wl])))?;
            if (w - w_meas).abs() > 1e-9 * w_meas {
                return Err(err(no, format!("wavelength {w} nm, but the measurement has {w_meas} nm in this row")));
            }
            for &c in &cols {
                let v = num(c).ok_or_else(|| {
                    err(no, format!("weight '{}' is not a number", cells.get(c).map_or("", |s| s.as_str())))
                })?;
                sigma.push(Spread::Weight.sigma(v).map_err(|m| err(no, m))?);
            }
        }
        self.sigma = Some(sigma);
        Ok(())
    }
}

/// A wavelength in nm as people write it (no binary noise: 206.6, not 206.60000000000002).
fn nm(x: f64) -> String {
    format!("{}", (x * 1e4).round() / 1e4)
}

/// Checks that every material of `stack` has data over `lo`–`hi` nm; the error names the material, where it
/// sits, the range it has, the `--from/--to` that would fit the covered part, and library materials of the
/// same kind that cover the range.
pub fn check_coverage(stack: &iridis_thinfilm::Stack, lo: f64, hi: f64) -> Result<(), FitError> {
    let n = stack.layers.len();
    let media = std::iter::once(("incident medium".to_string(), &stack.incident))
        .chain(stack.layers.iter().enumerate().map(|(i, l)| (format!("layer {} of {n}", i + 1), &l.material)))
        .chain(std::iter::once(("substrate".to_string(), &stack.substrate)));
    let (mut from, mut to) = (lo, hi);
    let mut short = Vec::new();
    for (place, m) in media {
        let (a, b) = m.range_nm();
        if a > lo + 1e-9 || b < hi - 1e-9 {
            from = from.max(a);
            to = to.min(b);
            let base = m.name().to_ascii_lowercase();
            let alternatives: Vec<String> = iridis_thinfilm::Material::library()
                .into_iter()
                .filter(|(names, _)| names.iter().any(|x| x.starts_with(&format!("{base}-"))))
                .filter_map(|(names, _)| {
                    let alt = iridis_thinfilm::Material::builtin(names[0])?;
                    let (c, d) = alt.range_nm();
                    (c <= lo && d >= hi).then(|| format!("{} ({}–{} nm)", names[0], nm(c), nm(d)))
                })
                .collect();
            let alt = if alternatives.is_empty() {
                String::new()
            } else {
                format!("; {} covers it", alternatives.join(", "))
            };
            short.push(format!("{place} '{}' has data for {}–{} nm only{alt}", m.name(), nm(a), nm(b)));
        }
    }
    if short.is_empty() {
        return Ok(());
    }
    let window = if from < to {
        let (f, t) = (nm(from), nm(to));
        format!("fit the covered part with --from {f}nm --to {t}nm (Python: from_nm={f}, to_nm={t})")
    } else {
        "no wavelength is covered by all of them".into()
    };
    Err(FitError::Data(format!("the measurement spans {}–{} nm, but {}: {window}", nm(lo), nm(hi), short.join("; "))))
}
