//! `iridis.thinfilm`: stacks in the CLI's syntax or from lists, R/T over arrays of (λ, θ, thickness offset),
//! film colours — the same library calls as `iridis thinfilm spectrum|color`.

use iridis_api::rough::{Angles, RoughOptions};
use iridis_thinfilm::color::{FilmColor, FilmColorimeter, Polarization};
use iridis_thinfilm::rough::DiffuseTransport;
use iridis_thinfilm::tmm::stack_from_lists;
use iridis_thinfilm::{Stack, ThinFilmError};
use num_complex::Complex64;
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1, PyArray2, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rayon::prelude::*;

use crate::args::{complex_list, real_list, value_error};
use crate::color::{illuminant, observer};
use crate::facade::run;

/// A thin-film stack (the native half of `iridis.thinfilm.Stack`).
#[pyclass(frozen, module = "iridis._native", name = "_Stack")]
#[derive(Debug)]
pub struct PyStack {
    pub(crate) stack: Stack,
}

fn pol(s: &str) -> PyResult<Polarization> {
    s.parse().map_err(value_error)
}

/// The rough model's options from Python: σ, τ (nm), the series' terms, the diffuse transport.
fn rough_options(sigma: f64, tau: f64, d_iterations: Option<usize>, transport: &str) -> PyResult<RoughOptions> {
    let transport = DiffuseTransport::parse(transport).map_err(value_error)?;
    Ok(RoughOptions { sigma_nm: sigma, tau_nm: tau, d_iterations, transport })
}

#[pymethods]
impl PyStack {
    /// Parses the CLI's syntax, e.g. `"air | water 348nm | air"`, `"air | inc:BK7 1mm | n=1.38+0.01i 90nm | Si"`.
    #[new]
    fn new(spec: &str) -> PyResult<Self> {
        Ok(Self { stack: Stack::parse(spec).map_err(|e| crate::facade::api_error(e.into()))? })
    }

    /// From indices (incident, layers…, substrate) and the layers' thicknesses in nm.
    #[staticmethod]
    #[pyo3(signature = (indices, thicknesses_nm, incoherent=None))]
    fn from_lists(
        indices: &Bound<'_, PyAny>,
        thicknesses_nm: &Bound<'_, PyAny>,
        incoherent: Option<Vec<bool>>,
    ) -> PyResult<Self> {
        let n = complex_list("indices", indices)?;
        let t = real_list("thicknesses_nm", thicknesses_nm)?;
        if n.len() < 2 {
            return Err(value_error(format!(
                "{} indices: a stack needs at least two media (the incident medium and the substrate)",
                n.len()
            )));
        }
        if t.len() + 2 != n.len() {
            return Err(value_error(format!(
                "{} indices need {} thicknesses (one per layer between the incident medium and the substrate), got {}",
                n.len(),
                n.len().saturating_sub(2),
                t.len()
            )));
        }
        let mut d = vec![f64::INFINITY];
        d.extend(t);
        d.push(f64::INFINITY);
        let inc = match incoherent {
            None => None,
            Some(v) if v.len() == n.len() - 2 => Some([vec![true], v, vec![true]].concat()),
            Some(v) => {
                return Err(value_error(format!("incoherent has {} entries for {} layers", v.len(), n.len() - 2)))
            }
        };
        Ok(Self { stack: stack_from_lists(&n, &d, inc.as_deref()).map_err(value_error)? })
    }

    /// From per-wavelength indices: `table` (media × wavelengths, complex) at `wavelengths` (nm, increasing);
    /// `constant[j]`: medium `j` is the same at every wavelength (a constant material, not a table).
    #[staticmethod]
    #[pyo3(signature = (table, constant, wavelengths, thicknesses_nm, incoherent=None))]
    fn _from_tables(
        table: numpy::PyReadonlyArray2<'_, Complex64>,
        constant: Vec<bool>,
        wavelengths: PyReadonlyArray1<'_, f64>,
        thicknesses_nm: &Bound<'_, PyAny>,
        incoherent: Option<Vec<bool>>,
    ) -> PyResult<Self> {
        let (t, w) = (table.as_array(), wavelengths.as_slice()?);
        let t_nm = real_list("thicknesses_nm", thicknesses_nm)?;
        let media = t.nrows();
        if media < 2 || t_nm.len() + 2 != media || constant.len() != media || t.ncols() != w.len() {
            return Err(value_error(format!(
                "{media} media need {} thicknesses (got {}) and one index per wavelength ({} wavelengths, {} columns)",
                media.saturating_sub(2),
                t_nm.len(),
                w.len(),
                t.ncols()
            )));
        }
        let material = |j: usize| -> PyResult<iridis_thinfilm::Material> {
            let row: Vec<Complex64> = t.row(j).to_vec();
            if constant[j] {
                iridis_thinfilm::Material::constant(format!("n={}", row[0]), row[0]).map_err(value_error)
            } else {
                iridis_thinfilm::Material::tabulated(format!("indices[{j}]"), w, &row).map_err(value_error)
            }
        };
        let inc = incoherent.unwrap_or_else(|| vec![false; media - 2]);
        if inc.len() != media - 2 {
            return Err(value_error(format!("incoherent has {} entries for {} layers", inc.len(), media - 2)));
        }
        let mut layers = Vec::with_capacity(media - 2);
        for j in 1..media - 1 {
            let d = t_nm[j - 1];
            if !(d.is_finite() && d >= 0.0) {
                return Err(value_error(format!(
                    "thicknesses_nm[{}] = {d}: a layer thickness must be finite and ≥ 0 (nm)",
                    j - 1
                )));
            }
            layers.push(iridis_thinfilm::Layer { material: material(j)?, thickness_nm: d, incoherent: inc[j - 1] });
        }
        let stack = Stack { incident: material(0)?, layers, substrate: material(media - 1)? };
        Ok(Self { stack })
    }

    fn __str__(&self) -> String {
        self.stack.to_string()
    }

    #[getter]
    fn layers(&self) -> usize {
        self.stack.layers.len()
    }

    /// The layers' thicknesses (nm), top first.
    #[getter]
    fn thicknesses(&self) -> Vec<f64> {
        self.stack.layers.iter().map(|l| l.thickness_nm).collect()
    }

    /// The index of each medium (incident first) at each wavelength: shape (media, wavelengths).
    fn indices<'py>(
        &self,
        py: Python<'py>,
        wavelengths: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Bound<'py, PyArray2<Complex64>>> {
        let wl = wavelengths.as_array();
        let media: Vec<_> = self.stack.materials().collect();
        let mut out = Vec::with_capacity(media.len() * wl.len());
        for m in &media {
            for &w in wl.iter() {
                out.push(m.index_at(w).map_err(value_error)?);
            }
        }
        Ok(Array2::from_shape_vec((media.len(), wl.len()), out).expect("shape").into_pyarray(py))
    }

    /// `[R_s, R_p, T_s, T_p]` at each point `(λ_i, θ_i, offset_i)` (1-D arrays of one length): shape (4, P).
    fn _rta<'py>(
        &self,
        py: Python<'py>,
        wavelengths: PyReadonlyArray1<'py, f64>,
        angles: PyReadonlyArray1<'py, f64>,
        offsets: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let (w, a, o) = (wavelengths.as_slice()?, angles.as_slice()?, offsets.as_slice()?);
        let stack = &self.stack;
        let rows = each_point(py, w.len(), |i| stack.evaluate_offset(w[i], a[i], o[i]))?;
        let mut out = Array2::zeros((4, rows.len()));
        for (i, x) in rows.iter().enumerate() {
            out[[0, i]] = x.r_s;
            out[[1, i]] = x.r_p;
            out[[2, i]] = x.t_s;
            out[[3, i]] = x.t_p;
        }
        Ok(out.into_pyarray(py))
    }

    /// Reflected and transmitted XYZ at each `(θ_i, offset_i)`: shape (P, 2, 3) flattened to (P, 6), on the
    /// wavelength `grid` (nm), as `iridis thinfilm color`.
    fn _colors<'py>(
        &self,
        py: Python<'py>,
        angles: PyReadonlyArray1<'py, f64>,
        offsets: PyReadonlyArray1<'py, f64>,
        grid: PyReadonlyArray1<'py, f64>,
        illuminant: &str,
        observer: &str,
        polarization: &str,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let (ill, obs, pol) = (self::illuminant(illuminant)?, self::observer(observer)?, self::pol(polarization)?);
        let (a, o, g) = (angles.as_slice()?, offsets.as_slice()?, grid.as_slice()?);
        check_grid(g)?;
        // As `iridis thinfilm color`: a grid too coarse for a thick layer's fringes is said, for the point whose
        // fringes are closest: the angle nearest the normal and the largest thickness offset.
        let nearest_normal = a.iter().map(|x| x.abs()).fold(f64::INFINITY, f64::min);
        let thickest = o.iter().copied().fold(0.0, f64::max);
        if nearest_normal.is_finite() {
            let stack = (0..self.stack.layers.len()).fold(self.stack.clone(), |s, i| {
                let t = s.layers[i].thickness_nm + thickest;
                s.with_thickness(i, t)
            });
            crate::facade::run(py, |r| {
                iridis_api::film::warn_sampling(&stack, nearest_normal, g, r);
                Ok(())
            })?;
        }
        let (stack, meter) = (&self.stack, FilmColorimeter::new(g, ill, obs));
        color_rows(py, a.len(), |i| meter.color_of(pol, |w| stack.evaluate_offset(w, a[i], o[i])))
    }

    /// The rough film's spectrum (LSRS, as `iridis thinfilm spectrum --roughness --json`): a dict of arrays
    /// over `wavelengths` and the series' figures.
    #[pyo3(signature = (sigma_nm, tau_nm, d_iterations, transport, wavelengths, view, light, azimuth))]
    fn _rough_spectrum<'py>(
        &self,
        py: Python<'py>,
        sigma_nm: f64,
        tau_nm: f64,
        d_iterations: Option<usize>,
        transport: &str,
        wavelengths: PyReadonlyArray1<'py, f64>,
        view: f64,
        light: f64,
        azimuth: f64,
    ) -> PyResult<Bound<'py, PyDict>> {
        let opts = rough_options(sigma_nm, tau_nm, d_iterations, transport)?;
        let grid = wavelengths.as_slice()?.to_vec();
        let stack = self.stack.clone();
        let s = run(py, |_| iridis_api::rough::spectrum(stack, "", &opts, Angles { view, light, azimuth }, &grid))?;
        let (bound, terms) = s.bound_terms();
        let d = PyDict::new(py);
        d.set_item("wavelength_nm", PyArray1::from_vec(py, grid))?;
        for (name, values) in s.columns() {
            d.set_item(name, PyArray1::from_vec(py, values))?;
        }
        d.set_item("series_terms_max", terms)?;
        d.set_item("diffuse_error_bound_per_sr", bound)?;
        d.set_item("diffuse_transport", opts.transport.name())?;
        d.set_item("series", opts.series_label())?;
        Ok(d)
    }

    /// The rough film's colours (as `iridis thinfilm color --roughness`): XYZ rows of the smooth film's
    /// reflected and transmitted light, the rough film's specular part `k_r` and its diffuse part `π k_d`;
    /// shape (4, 3).
    #[pyo3(signature = (sigma_nm, tau_nm, d_iterations, transport, view, light, azimuth, grid, illuminant, observer))]
    fn _rough_color<'py>(
        &self,
        py: Python<'py>,
        sigma_nm: f64,
        tau_nm: f64,
        d_iterations: Option<usize>,
        transport: &str,
        view: f64,
        light: f64,
        azimuth: f64,
        grid: PyReadonlyArray1<'py, f64>,
        illuminant: &str,
        observer: &str,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let opts = rough_options(sigma_nm, tau_nm, d_iterations, transport)?;
        let (ill, obs) = (self::illuminant(illuminant)?, self::observer(observer)?);
        let g = grid.as_slice()?.to_vec();
        check_grid(&g)?;
        let stack = self.stack.clone();
        let c = run(py, |_| {
            let rough = opts.build(stack)?;
            iridis_api::rough::colours(&rough, Angles { view, light, azimuth }, &g, ill, obs)
        })?;
        let rows = [c.smooth.reflected, c.smooth.transmitted, c.specular, c.diffuse];
        let flat: Vec<f64> = rows.iter().flat_map(|x| x.to_array()).collect();
        Ok(Array2::from_shape_vec((4, 3), flat).expect("shape").into_pyarray(py))
    }
}

/// Reflected and transmitted XYZ of many stacks of constant indices: `n` (stacks × media, complex), `d`
/// (stacks × layers, nm), one angle; shape (stacks, 6). Each row is one stack, as `Stack.color`.
#[pyfunction]
fn _stack_colors<'py>(
    py: Python<'py>,
    n: numpy::PyReadonlyArray2<'py, Complex64>,
    d: numpy::PyReadonlyArray2<'py, f64>,
    angle: f64,
    grid: PyReadonlyArray1<'py, f64>,
    illuminant: &str,
    observer: &str,
    polarization: &str,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let (ill, obs, pol) = (self::illuminant(illuminant)?, self::observer(observer)?, self::pol(polarization)?);
    let (n, d, g) = (n.as_array(), d.as_array(), grid.as_slice()?);
    if n.nrows() != d.nrows() || n.ncols() != d.ncols() + 2 {
        return Err(value_error(format!(
            "indices of shape {:?} need thicknesses of shape ({}, {}), got {:?}",
            n.shape(),
            n.nrows(),
            n.ncols().saturating_sub(2),
            d.shape()
        )));
    }
    check_grid(g)?;
    let rows: Vec<(Vec<Complex64>, Vec<f64>)> = n
        .rows()
        .into_iter()
        .zip(d.rows())
        .map(|(a, b)| {
            let mut dl = vec![f64::INFINITY];
            dl.extend(b.iter());
            dl.push(f64::INFINITY);
            (a.to_vec(), dl)
        })
        .collect();
    let meter = FilmColorimeter::new(g, ill, obs);
    color_rows(py, rows.len(), |i| {
        let (n, d) = &rows[i];
        let stack = stack_from_lists(n, d, None).map_err(|e| ThinFilmError::Invalid(format!("stack {i}: {e}")))?;
        // Constant indices: the chapter 4 fast path (per-interface values once per stack).
        let prepared = stack.prepare(angle)?;
        meter.color_of(pol, |w| prepared.evaluate(w))
    })
}

/// The complex index `n + iκ` of a material (library name, `n=…`, `file:PATH`) at each wavelength (nm).
#[pyfunction]
fn material_index<'py>(
    py: Python<'py>,
    name: &str,
    wavelengths: PyReadonlyArray1<'py, f64>,
) -> PyResult<Bound<'py, PyArray1<Complex64>>> {
    if name.trim().is_empty() || name.contains('|') {
        return Err(value_error(format!(
            "material '{name}': give one material (a library name, n=…, or file:PATH), not a stack"
        )));
    }
    // Read as a stack's substrate, the one syntax for a material; its errors name the stack "air | NAME".
    let stack = Stack::parse(&format!("air | {name}")).map_err(|e| value_error(format!("material '{name}': {e}")))?;
    let out = wavelengths
        .as_array()
        .iter()
        .map(|&w| stack.substrate.index_at(w))
        .collect::<Result<Vec<_>, _>>()
        .map_err(value_error)?;
    Ok(out.into_pyarray(py))
}

/// The built-in material library: `(names, description)` pairs.
#[pyfunction]
fn materials() -> Vec<(Vec<&'static str>, &'static str)> {
    iridis_thinfilm::Material::library()
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyStack>()?;
    add_functions!(m, [material_index, materials, _stack_colors]);
    Ok(())
}

/// A colour integral's wavelength grid: at least two strictly increasing values.
fn check_grid(g: &[f64]) -> PyResult<()> {
    if g.len() < 2 || g.windows(2).any(|x| x[1] <= x[0]) {
        return Err(value_error("the wavelength grid must have ≥ 2 strictly increasing values"));
    }
    Ok(())
}

/// `point(i)` for each point `i` in `0..n`, computed in parallel with the GIL released; the first library
/// error raised as `ValueError`.
fn each_point<T: Send>(
    py: Python<'_>,
    n: usize,
    point: impl Fn(usize) -> Result<T, ThinFilmError> + Sync + Send,
) -> PyResult<Vec<T>> {
    py.allow_threads(|| (0..n).into_par_iter().map(point).collect::<Result<Vec<_>, _>>()).map_err(value_error)
}

/// The colours of `n` points ([`each_point`]) as the colour arrays give them: one row of reflected then
/// transmitted XYZ per point, shape (n, 6).
fn color_rows<'py>(
    py: Python<'py>,
    n: usize,
    color: impl Fn(usize) -> Result<FilmColor, ThinFilmError> + Sync + Send,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let rows = each_point(py, n, |i| color(i).map(|c| [c.reflected.to_array(), c.transmitted.to_array()]))?;
    let flat: Vec<f64> = rows.into_iter().flatten().flatten().collect();
    Ok(Array2::from_shape_vec((n, 6), flat).expect("shape").into_pyarray(py))
}
