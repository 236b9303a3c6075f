//! Argument conversion shared by the bindings: sequences or arrays of numbers into Rust slices, with a
//! `TypeError` that names the argument when the type is wrong.

use num_complex::Complex64;
use numpy::{PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyFloat, PyList};

/// A library error as Python's `ValueError`, with the library's message in a Python caller's words
/// ([`in_python_terms`]).
pub fn value_error(e: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(in_python_terms(&e.to_string()))
}

/// A direction `(θ, φ)` in radians above the surface (`what` names it in the message).
pub fn above(what: &str, (theta, phi): (f64, f64)) -> PyResult<(f64, f64)> {
    if !((0.0..std::f64::consts::FRAC_PI_2).contains(&theta) && phi.is_finite()) {
        // θ between π/2 and 90 is likely degrees given for radians.
        let hint = if (std::f64::consts::FRAC_PI_2..90.0).contains(&theta) {
            format!(" ({theta} looks like degrees: give numpy.radians({theta}))")
        } else {
            String::new()
        };
        return Err(value_error(format!(
            "{what} θ = {theta} rad must be in [0, π/2) (above the surface), φ finite{hint}"
        )));
    }
    check_azimuth(what, phi)?;
    Ok((theta, phi))
}

/// An azimuth in radians within one turn either way: beyond it, degrees given for radians (`azimuth=90` read as
/// 5157°, and the test bench measured along that).
pub fn check_azimuth(what: &str, phi: f64) -> PyResult<f64> {
    // A non-finite one is refused where it is read, by name.
    if phi.is_finite() && phi.abs() > std::f64::consts::TAU + 1e-9 {
        return Err(value_error(format!(
            "{what} φ = {phi} rad is beyond one turn (±2π): if it is in degrees, give numpy.radians({phi})"
        )));
    }
    Ok(phi)
}

/// One real or complex number (a float is read without the complex conversion).
fn number(name: &str, x: &Bound<'_, PyAny>) -> PyResult<Complex64> {
    if let Ok(f) = x.downcast_exact::<PyFloat>() {
        return Ok(Complex64::new(f.value(), 0.0));
    }
    x.extract::<Complex64>()
        .map_err(|_| PyTypeError::new_err(format!("{name} must be a 1-D sequence of numbers, got an item {x:?}")))
}

/// A 1-D list or array of complex (or real) numbers.
pub fn complex_list(name: &str, obj: &Bound<'_, PyAny>) -> PyResult<Vec<Complex64>> {
    // Plain lists first: the common tmm call, and the cheapest to recognise.
    if let Ok(l) = obj.downcast::<PyList>() {
        let mut v = Vec::with_capacity(l.len());
        for x in l.iter() {
            v.push(number(name, &x)?);
        }
        return Ok(v);
    }
    if let Ok(a) = obj.extract::<PyReadonlyArray1<'_, Complex64>>() {
        return Ok(a.as_slice().map(|s| s.to_vec()).unwrap_or_else(|_| a.as_array().to_vec()));
    }
    if let Ok(a) = obj.extract::<PyReadonlyArray1<'_, f64>>() {
        return Ok(a.as_array().iter().map(|&x| Complex64::new(x, 0.0)).collect());
    }
    if let Ok(a) = obj.downcast::<numpy::PyUntypedArray>() {
        if a.ndim() != 1 {
            return Err(PyValueError::new_err(format!("{name} must be 1-D, got an array of shape {:?}", a.shape())));
        }
    }
    obj.extract::<Vec<Complex64>>()
        .map_err(|_| PyTypeError::new_err(format!("{name} must be a 1-D sequence of numbers (real or complex)")))
}

/// A 1-D list or array of real numbers.
pub fn real_list(name: &str, obj: &Bound<'_, PyAny>) -> PyResult<Vec<f64>> {
    if let Ok(l) = obj.downcast::<PyList>() {
        let mut v = Vec::with_capacity(l.len());
        for x in l.iter() {
            v.push(x.extract::<f64>().map_err(|_| {
                PyTypeError::new_err(format!("{name} must be a 1-D sequence of real numbers, got an item {x:?}"))
            })?);
        }
        return Ok(v);
    }
    if let Ok(a) = obj.extract::<PyReadonlyArray1<'_, f64>>() {
        return Ok(a.as_array().to_vec());
    }
    if let Ok(a) = obj.downcast::<numpy::PyUntypedArray>() {
        if a.ndim() != 1 {
            return Err(PyValueError::new_err(format!("{name} must be 1-D, got an array of shape {:?}", a.shape())));
        }
    }
    obj.extract::<Vec<f64>>()
        .map_err(|_| PyTypeError::new_err(format!("{name} must be a 1-D sequence of real numbers")))
}

/// Spectra as a wavelength grid and one row per spectrum, each row as long as the grid (refused, naming both
/// lengths, otherwise).
pub fn spectra_rows(
    wavelengths: &PyReadonlyArray1<'_, f64>,
    values: &PyReadonlyArray2<'_, f64>,
) -> PyResult<(Vec<f64>, Vec<Vec<f64>>)> {
    let wl = wavelengths.as_array().to_vec();
    let v = values.as_array();
    if v.ncols() != wl.len() {
        return Err(value_error(format!(
            "values have {} samples per spectrum but there are {} wavelengths",
            v.ncols(),
            wl.len()
        )));
    }
    Ok((wl, v.rows().into_iter().map(|r| r.to_vec()).collect()))
}

/// tmm's "not vectorized" `ValueError` for an array of several values where one number belongs.
fn not_vectorized(name: &str, obj: &Bound<'_, PyAny>, batch_hint: &str) -> PyResult<()> {
    if let Ok(a) = obj.downcast::<numpy::PyUntypedArray>() {
        if a.len() > 1 {
            return Err(PyValueError::new_err(format!(
                "This function is not vectorized; you need to run one calculation at a time (1 wavelength, 1 \
                 angle, etc.): {name} has {} values{batch_hint}",
                a.len()
            )));
        }
    }
    Ok(())
}

/// One real number; an array of several gives tmm's "not vectorized" `ValueError`.
pub fn scalar(name: &str, obj: &Bound<'_, PyAny>, batch_hint: &str) -> PyResult<f64> {
    if let Ok(x) = obj.extract::<f64>() {
        return Ok(x);
    }
    not_vectorized(name, obj, batch_hint)?;
    if obj.extract::<Complex64>().is_ok() {
        return Err(PyTypeError::new_err(format!(
            "{name} must be a real number (iridis needs a lossless incident medium and a real angle)"
        )));
    }
    Err(PyTypeError::new_err(format!("{name} must be a real number, got {}", obj.get_type().name()?)))
}

/// One real or complex number (tmm's angles may be complex); an array of several gives tmm's "not
/// vectorized" `ValueError`.
pub fn complex_scalar(name: &str, obj: &Bound<'_, PyAny>, batch_hint: &str) -> PyResult<Complex64> {
    // Complex first: extracting an f64 from a NumPy complex scalar calls its __float__, which drops the
    // imaginary part (with only a ComplexWarning).
    if let Ok(f) = obj.downcast_exact::<PyFloat>() {
        return Ok(Complex64::new(f.value(), 0.0));
    }
    if obj.downcast::<numpy::PyUntypedArray>().is_err() {
        if let Ok(x) = obj.extract::<Complex64>() {
            return Ok(x);
        }
    }
    not_vectorized(name, obj, batch_hint)?;
    if obj.downcast::<numpy::PyUntypedArray>().is_ok() {
        if let Ok(item) = obj.call_method0("item") {
            return complex_scalar(name, &item, batch_hint);
        }
    }
    Err(PyTypeError::new_err(format!("{name} must be a number (real or complex), got {}", obj.get_type().name()?)))
}

/// The Python keyword of a command-line flag, where it is not the flag's own name with `_` for `-`: lengths
/// carry their unit in the name (`--pixel-size` is `pixel_size_nm`), angles theirs.
const PYTHON_KEYWORDS: &[(&str, &str)] = &[
    ("pixel-size", "pixel_size_nm"),
    ("max-height", "max_height_nm"),
    ("from", "from_nm"),
    ("to", "to_nm"),
    ("step", "step_nm"),
    ("coherence", "coherence_nm"),
    ("roughness", "roughness_nm"),
    ("correlation", "correlation_nm"),
    ("aperture", "aperture_nm"),
    ("max-period", "max_period_nm"),
    ("distance", "distance_nm"),
    ("screen", "screen_nm"),
    ("wavelength", "wavelengths_nm"),
    ("angle", "angle_rad"),
    ("light-angle", "light_angle_rad"),
    ("no-shadowing", "shadowing=False"),
    ("terms auto", "terms=None"),
];

/// Commands a message points to, as a Python caller calls them (the CLI's `surface generate --help` stays: it
/// is where `iridis.surface.generate`'s docstring sends its reader too).
const PYTHON_CALLS: &[(&str, &str)] = &[
    ("`iridis surface info`", "`Surface.info()`"),
    ("`iridis surface convert`", "`Surface.reshape()`"),
    ("surface convert --crop", "Surface.reshape(crop=…)"),
    ("`iridis surface generate`", "`iridis.surface.generate()`"),
    ("`iridis precompute`", "`iridis.diffraction.precompute()`"),
    ("`iridis brdf-map`", "`iridis.diffraction.brdf_map()`"),
    ("`iridis brdf vision`", "`iridis.diffraction.vision()`"),
    ("`iridis brdf eval`", "`iridis.diffraction.brdf_eval()`"),
];

/// A message of the facade in the words of a Python caller: each `--flag` named by its keyword
/// ([`PYTHON_KEYWORDS`], else the flag with `_` for `-`), so that `give --pixel-size` reads `give pixel_size_nm`,
/// and a command it points to by its Python call ([`PYTHON_CALLS`]).
/// Left as written: a message that already gives the Python form (`(Python: from_nm=400)`), and flags inside a
/// quoted command line (`` `iridis surface convert --crop` ``), which are the CLI's.
pub fn in_python_terms(msg: &str) -> String {
    if msg.contains("Python:") || msg.contains("(Python") {
        return msg.to_string();
    }
    let msg = PYTHON_CALLS.iter().fold(msg.to_string(), |m, (cli, python)| m.replace(cli, python));
    let mut out = String::with_capacity(msg.len());
    // Inside `…` or a command line that starts `iridis ` (a report step's), up to the line's end.
    let (mut quoted, mut command_line) = (false, false);
    let mut rest = msg.as_str();
    while let Some(c) = rest.chars().next() {
        match c {
            '`' => quoted = !quoted,
            '\n' => command_line = false,
            _ if rest.starts_with("iridis ") && !out.ends_with(|ch: char| ch.is_alphanumeric()) => command_line = true,
            _ => {}
        }
        let in_command = quoted || command_line;
        let flag_start = !in_command
            && rest.starts_with("--")
            && rest[2..].starts_with(|ch: char| ch.is_ascii_lowercase())
            && !out.ends_with(|ch: char| ch.is_alphanumeric() || ch == '-');
        if flag_start {
            let name_len =
                rest[2..].find(|ch: char| !(ch.is_ascii_alphanumeric() || ch == '-')).unwrap_or(rest.len() - 2);
            let name = rest[2..2 + name_len].trim_end_matches('-');
            // `--terms auto` as one phrase: its keyword's value differs.
            let phrase = PYTHON_KEYWORDS.iter().find(|(f, _)| f.contains(' ') && rest[2..].starts_with(f));
            if let Some((f, k)) = phrase {
                out.push_str(k);
                rest = &rest[2 + f.len()..];
                continue;
            }
            let keyword = match PYTHON_KEYWORDS.iter().find(|(f, _)| *f == name) {
                Some((_, k)) => k.to_string(),
                None => name.replace('-', "_"),
            };
            out.push_str(&keyword);
            rest = &rest[2 + name.len()..];
            // An example length for a keyword in nm is a number: "give pixel_size_nm (e.g. 65)", not "65nm".
            if keyword.ends_with("_nm") {
                if let Some(after) = rest.strip_prefix(" (e.g. ") {
                    let digits = after.find(|ch: char| !(ch.is_ascii_digit() || ch == '.')).unwrap_or(after.len());
                    if digits > 0 && after[digits..].starts_with("nm") {
                        out.push_str(" (e.g. ");
                        out.push_str(&after[..digits]);
                        rest = &after[digits + 2..];
                    }
                }
            }
            continue;
        }
        out.push(c);
        rest = &rest[c.len_utf8()..];
    }
    out
}
