//! Argument conversion shared by the bindings: sequences or arrays of numbers into Rust slices, with a
//! `TypeError` that names the argument when the type is wrong.

use num_complex::Complex64;
use numpy::{PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyFloat, PyList};

/// A library error as Python's `ValueError`, with the library's message in a Python caller's words
/// ([`crate::facade::in_python_terms`]).
pub fn value_error(e: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(crate::facade::in_python_terms(&e.to_string()))
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
    Ok((theta, phi))
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
