//! `iridis.color`: spectra to XYZ through `iridis_color` (the integration the CLI's `iridis color xyz` does),
//! colour-space conversions and colour differences, on arrays of colours.

use iridis_api::Report as _;
use iridis_color::integrate::{observer_grid, white_point};
use iridis_color::lab::DeltaEFormula;
use iridis_color::{Illuminant, Lab, Observer, SpectralWeights, Spectrum, ToneMap, Xyz};
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray2, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;

use crate::args::value_error;

pub fn illuminant(s: &str) -> PyResult<Illuminant> {
    s.parse().map_err(value_error)
}

pub fn observer(s: &str) -> PyResult<Observer> {
    s.parse().map_err(value_error)
}

fn rows3<'py>(
    py: Python<'py>,
    a: &PyReadonlyArray2<'py, f64>,
    f: impl Fn([f64; 3]) -> [f64; 3] + Sync,
) -> Bound<'py, PyArray2<f64>> {
    let a = a.as_array();
    let n = a.nrows();
    let input: Vec<[f64; 3]> = a.rows().into_iter().map(|r| [r[0], r[1], r[2]]).collect();
    let out: Vec<f64> = py.allow_threads(|| input.iter().flat_map(|r| f(*r)).collect());
    Array2::from_shape_vec((n, 3), out).expect("n × 3").into_pyarray(py)
}

/// XYZ (reflectance under `illuminant`, `Y = 1` for a perfect reflector) of spectra sampled at
/// `wavelengths` (strictly increasing, nm), one spectrum per row: interpolated onto the observer's 1 nm grid,
/// end values held outside their range (and a warning where that range is short of 380–780 nm).
#[pyfunction]
fn _spectrum_to_xyz<'py>(
    py: Python<'py>,
    wavelengths: PyReadonlyArray1<'py, f64>,
    values: PyReadonlyArray2<'py, f64>,
    illuminant: &str,
    observer: &str,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let (ill, obs) = (self::illuminant(illuminant)?, self::observer(observer)?);
    let (wl, rows) = crate::args::spectra_rows(&wavelengths, &values)?;
    let out = crate::facade::run(py, |report| {
        let grid = observer_grid(obs);
        let w = SpectralWeights::new(grid, ill, obs);
        let mut out = Vec::with_capacity(rows.len() * 3);
        for r in rows {
            let s = Spectrum::new(wl.clone(), r).map_err(anyhow::Error::from)?;
            let samples: Vec<f64> = grid.iter().map(|&l| s.value_at(l)).collect();
            out.extend(w.integrate(&samples).to_array());
        }
        // (Said once the spectra are known to be valid: a refused one is not warned about as well.)
        if let (Some(&lo), Some(&hi)) = (wl.first(), wl.last()) {
            if let Some(w) = iridis_api::color::short_range("the spectrum", lo, hi) {
                report.warn(&w);
            }
        }
        Ok(out)
    })?;
    let n = out.len() / 3;
    Ok(Array2::from_shape_vec((n, 3), out).expect("n × 3").into_pyarray(py))
}

/// The white point (XYZ of a perfect reflector, `Y = 1`).
#[pyfunction]
fn white_point_xyz(illuminant: &str, observer: &str) -> PyResult<[f64; 3]> {
    Ok(white_point(self::illuminant(illuminant)?, self::observer(observer)?).to_array())
}

#[pyfunction]
fn _xyz_to_lab<'py>(py: Python<'py>, xyz: PyReadonlyArray2<'py, f64>, white: [f64; 3]) -> Bound<'py, PyArray2<f64>> {
    let w = Xyz::new(white[0], white[1], white[2]);
    rows3(py, &xyz, |c| Lab::from_xyz(Xyz::new(c[0], c[1], c[2]), w).to_array())
}

#[pyfunction]
fn _lab_to_xyz<'py>(py: Python<'py>, lab: PyReadonlyArray2<'py, f64>, white: [f64; 3]) -> Bound<'py, PyArray2<f64>> {
    let w = Xyz::new(white[0], white[1], white[2]);
    rows3(py, &lab, |c| Lab::new(c[0], c[1], c[2]).to_xyz(w).to_array())
}

#[pyfunction]
fn _xyz_to_xyy<'py>(py: Python<'py>, xyz: PyReadonlyArray2<'py, f64>) -> Bound<'py, PyArray2<f64>> {
    rows3(py, &xyz, |c| {
        let v = Xyz::new(c[0], c[1], c[2]).to_xyy();
        [v.x, v.y, v.big_y]
    })
}

#[pyfunction]
fn _xyz_to_linear_srgb<'py>(py: Python<'py>, xyz: PyReadonlyArray2<'py, f64>) -> Bound<'py, PyArray2<f64>> {
    rows3(py, &xyz, |c| Xyz::new(c[0], c[1], c[2]).to_linear_srgb())
}

/// Display sRGB in [0, 1] (scaled by `exposure`, clipped, encoded), as the CLI's `srgb` and `hex`.
#[pyfunction]
fn _xyz_to_srgb<'py>(py: Python<'py>, xyz: PyReadonlyArray2<'py, f64>, exposure: f64) -> Bound<'py, PyArray2<f64>> {
    let tone = ToneMap { exposure_ru: exposure, ..ToneMap::default() };
    rows3(py, &xyz, move |c| tone.to_display(Xyz::new(c[0], c[1], c[2])))
}

/// `#rrggbb` of each XYZ, as the CLI prints it.
#[pyfunction]
fn _xyz_to_hex(xyz: PyReadonlyArray2<'_, f64>, exposure: f64) -> Vec<String> {
    let tone = ToneMap { exposure_ru: exposure, ..ToneMap::default() };
    xyz.as_array()
        .rows()
        .into_iter()
        .map(|r| iridis_color::tonemap::hex(tone.to_rgb8(Xyz::new(r[0], r[1], r[2]))))
        .collect()
}

/// CIEDE2000 (`formula = "2000"`) or ΔE*ab (`"1976"`) between rows of two Lab arrays.
#[pyfunction]
fn _delta_e(a: PyReadonlyArray2<'_, f64>, b: PyReadonlyArray2<'_, f64>, formula: &str) -> PyResult<Vec<f64>> {
    let formula: DeltaEFormula = formula.parse().map_err(value_error)?;
    let (a, b) = (a.as_array(), b.as_array());
    a.rows()
        .into_iter()
        .zip(b.rows())
        .enumerate()
        .map(|(i, (p, q))| {
            formula
                .delta_e_checked(Lab::new(p[0], p[1], p[2]), Lab::new(q[0], q[1], q[2]))
                .map_err(|e| value_error(format!("colour pair {i}: {e}")))
        })
        .collect()
}

/// The built-in illuminants and observers.
#[pyfunction]
fn names() -> (Vec<&'static str>, Vec<&'static str>) {
    (Illuminant::ALL.iter().map(|i| i.name()).collect(), Observer::ALL.iter().map(|o| o.name()).collect())
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    add_functions!(
        m,
        [
            _spectrum_to_xyz,
            white_point_xyz,
            _xyz_to_lab,
            _lab_to_xyz,
            _xyz_to_xyy,
            _xyz_to_linear_srgb,
            _xyz_to_srgb,
            _xyz_to_hex,
            _delta_e,
            names
        ]
    );
    Ok(())
}
