//! `iridis.tmm`: Byrnes' `tmm` calling convention over `iridis_thinfilm::tmm`.

use iridis_thinfilm::tmm::{self as lib, Indices, Pol};
use num_complex::Complex64;
use numpy::{IntoPyArray, PyArray1, PyArrayMethods, PyReadonlyArray1, PyReadonlyArrayDyn, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{IntoPyDict, PyDict};

use crate::args::{complex_list, complex_scalar, real_list, scalar, value_error};

const HINT: &str = "; iridis.tmm.coh_tmm_batch takes arrays";

fn pol(s: &str) -> PyResult<Pol> {
    Pol::parse(s).map_err(value_error)
}

/// Main coherent transfer-matrix calculation, as `tmm.coh_tmm`: the same arguments, the same keys, the same
/// numbers (to 1e-9 on the committed fixtures), computed by iridis.
///
/// Returns a read-only mapping (a `collections.abc.Mapping`; `dict(result)` makes a dict) with the keys `r`,
/// `t`, `R`, `T`, `power_entering`, `vw_list`, `kz_list`, `th_list`, `pol`, `n_list`, `d_list`, `th_0`,
/// `lam_vac`. The arrays are made when first read, so a call that only reads `R` pays for no array.
///
/// >>> import numpy as np, iridis.tmm as tmm
/// >>> d = tmm.coh_tmm('s', [1, 1.5], [np.inf, np.inf], 0, 500)
/// >>> round(d['R'], 6)
/// 0.04
#[pyfunction]
#[pyo3(signature = (pol, n_list, d_list, th_0, lam_vac))]
fn coh_tmm<'py>(
    py: Python<'py>,
    pol: &str,
    n_list: &Bound<'py, PyAny>,
    d_list: &Bound<'py, PyAny>,
    th_0: &Bound<'py, PyAny>,
    lam_vac: &Bound<'py, PyAny>,
) -> PyResult<CohTmmResult> {
    let p = self::pol(pol)?;
    let (n, d, th, lam) = coherent_args(n_list, d_list, th_0, lam_vac)?;
    let x = py.allow_threads(|| lib::coh_tmm_complex(p, &n, &d, th, lam)).map_err(value_error)?;
    Ok(CohTmmResult { x, pol: p, n, d, th_0: th_0.clone().unbind(), lam_vac: lam_vac.clone().unbind() })
}

const KEYS: [&str; 13] = [
    "r",
    "t",
    "R",
    "T",
    "power_entering",
    "vw_list",
    "kz_list",
    "th_list",
    "pol",
    "n_list",
    "d_list",
    "th_0",
    "lam_vac",
];

/// The result of `iridis.tmm.coh_tmm`: a read-only mapping with tmm's keys.
#[pyclass(frozen, mapping, module = "iridis.tmm")]
#[derive(Debug)]
pub struct CohTmmResult {
    x: lib::Coherent,
    pol: Pol,
    n: Vec<Complex64>,
    d: Vec<f64>,
    th_0: Py<PyAny>,
    lam_vac: Py<PyAny>,
}

impl CohTmmResult {
    fn item<'py>(&self, py: Python<'py>, key: &str) -> PyResult<Option<Bound<'py, PyAny>>> {
        let x = &self.x;
        // Small arrays: copied into numpy's own memory (cheaper than handing over a Vec).
        Ok(Some(match key {
            "r" => x.r.into_pyobject(py)?.into_any(),
            "t" => x.t.into_pyobject(py)?.into_any(),
            "R" => x.big_r.into_pyobject(py)?.into_any(),
            "T" => x.big_t.into_pyobject(py)?.into_any(),
            "power_entering" => x.power_entering.into_pyobject(py)?.into_any(),
            "vw_list" => {
                let vw: Vec<Complex64> = x.vw.iter().flatten().copied().collect();
                PyArray1::from_slice(py, &vw).reshape([x.vw.len(), 2])?.into_any()
            }
            "kz_list" => PyArray1::from_slice(py, &x.kz).into_any(),
            "th_list" => PyArray1::from_slice(py, &x.th).into_any(),
            "pol" => self.pol.name().into_pyobject(py)?.into_any(),
            "n_list" => PyArray1::from_slice(py, &self.n).into_any(),
            "d_list" => PyArray1::from_slice(py, &self.d).into_any(),
            "th_0" => self.th_0.bind(py).clone(),
            "lam_vac" => self.lam_vac.bind(py).clone(),
            _ => return Ok(None),
        }))
    }
}

#[pymethods]
impl CohTmmResult {
    fn __getitem__<'py>(&self, py: Python<'py>, key: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
        let k: Option<String> = key.extract().ok();
        match k.as_deref().map(|k| self.item(py, k)).transpose()?.flatten() {
            Some(v) => Ok(v),
            None => Err(pyo3::exceptions::PyKeyError::new_err(key.clone().unbind())),
        }
    }
    fn __len__(&self) -> usize {
        KEYS.len()
    }
    fn __contains__(&self, key: &Bound<'_, PyAny>) -> bool {
        key.extract::<String>().is_ok_and(|k| KEYS.contains(&k.as_str()))
    }
    fn __iter__<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        pyo3::types::PyList::new(py, KEYS)?.try_iter().map(|i| i.into_any())
    }
    fn keys(&self) -> Vec<&'static str> {
        KEYS.to_vec()
    }
    fn values<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyAny>>> {
        KEYS.iter().map(|k| Ok(self.item(py, k)?.expect("known key"))).collect()
    }
    fn items<'py>(&self, py: Python<'py>) -> PyResult<Vec<(&'static str, Bound<'py, PyAny>)>> {
        KEYS.iter().map(|k| Ok((*k, self.item(py, k)?.expect("known key")))).collect()
    }
    #[pyo3(signature = (key, default=None))]
    fn get<'py>(
        &self,
        py: Python<'py>,
        key: &Bound<'py, PyAny>,
        default: Option<Bound<'py, PyAny>>,
    ) -> PyResult<Option<Bound<'py, PyAny>>> {
        let k: Option<String> = key.extract().ok();
        Ok(k.as_deref().map(|k| self.item(py, k)).transpose()?.flatten().or(default))
    }
    /// A plain dict of the same items (tmm's own type).
    fn copy<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        self.items(py)?.into_py_dict(py)
    }
    fn __copy__<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        self.copy(py)
    }
    fn __deepcopy__<'py>(&self, py: Python<'py>, _memo: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyDict>> {
        self.copy(py)
    }
    /// Pickled as the plain dict tmm returns, so that results cross `multiprocessing` and caches (a frozen
    /// Rust object does not pickle).
    fn __reduce__<'py>(&self, py: Python<'py>) -> PyResult<(Bound<'py, PyAny>, (Bound<'py, PyDict>,))> {
        Ok((py.get_type::<PyDict>().into_any(), (self.copy(py)?,)))
    }
    fn __repr__(&self) -> String {
        format!(
            "CohTmmResult(pol={:?}, r={}, t={}, R={}, T={}, …)",
            self.pol.name(),
            self.x.r,
            self.x.t,
            self.x.big_r,
            self.x.big_t
        )
    }
}

/// Unpolarised reflection and transmission, as `tmm.unpolarized_RT`: `{'R': (R_s + R_p)/2, 'T': …}`.
#[pyfunction]
#[pyo3(signature = (n_list, d_list, th_0, lam_vac))]
#[pyo3(name = "unpolarized_RT")]
fn unpolarized_rt<'py>(
    py: Python<'py>,
    n_list: &Bound<'py, PyAny>,
    d_list: &Bound<'py, PyAny>,
    th_0: &Bound<'py, PyAny>,
    lam_vac: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyDict>> {
    let (n, d, th, lam) = coherent_args(n_list, d_list, th_0, lam_vac)?;
    let (s, p) = py
        .allow_threads(|| {
            Ok::<_, iridis_thinfilm::ThinFilmError>((
                lib::coh_tmm_complex(Pol::S, &n, &d, th, lam)?,
                lib::coh_tmm_complex(Pol::P, &n, &d, th, lam)?,
            ))
        })
        .map_err(value_error)?;
    [("R", 0.5 * (s.big_r + p.big_r)), ("T", 0.5 * (s.big_t + p.big_t))].into_py_dict(py)
}

/// Ellipsometric angles, as `tmm.ellips`: `{'psi': ψ, 'Delta': Δ}` in radians, `tan ψ e^{iΔ} = −r_p/r_s`.
#[pyfunction]
#[pyo3(signature = (n_list, d_list, th_0, lam_vac))]
fn ellips<'py>(
    py: Python<'py>,
    n_list: &Bound<'py, PyAny>,
    d_list: &Bound<'py, PyAny>,
    th_0: &Bound<'py, PyAny>,
    lam_vac: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyDict>> {
    let (n, d, th, lam) = coherent_args(n_list, d_list, th_0, lam_vac)?;
    let (psi, delta) = py.allow_threads(|| lib::ellips_complex(&n, &d, th, lam)).map_err(value_error)?;
    [("psi", psi), ("Delta", delta)].into_py_dict(py)
}

/// Incoherent or partly coherent stacks through the library's incoherent path (`iridis_thinfilm::tmm::inc_tmm`):
/// `R`, `T` (tmm's meaning: the flux into the last medium) and `absorp_in_each_layer` (`[R, A_1, …, A_N, T]`).
/// `iridis.tmm.inc_tmm` gives tmm's whole dictionary; the tests compare the two.
#[pyfunction]
#[pyo3(signature = (pol, n_list, d_list, c_list, th_0, lam_vac))]
fn _inc_tmm<'py>(
    py: Python<'py>,
    pol: &str,
    n_list: &Bound<'py, PyAny>,
    d_list: &Bound<'py, PyAny>,
    c_list: &Bound<'py, PyAny>,
    th_0: &Bound<'py, PyAny>,
    lam_vac: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyDict>> {
    let p = self::pol(pol)?;
    let n = complex_list("n_list", n_list)?;
    let d = real_list("d_list", d_list)?;
    let c: Vec<String> = c_list
        .extract()
        .map_err(|_| pyo3::exceptions::PyTypeError::new_err("c_list must be a sequence of 'i' and 'c'"))?;
    let chars: Vec<char> = c.iter().map(|s| if s.len() == 1 { s.chars().next().unwrap_or('?') } else { '?' }).collect();
    let th = scalar("th_0", th_0, "")?;
    let lam = scalar("lam_vac", lam_vac, "")?;
    let x = py.allow_threads(|| lib::inc_tmm(p, &n, &d, &chars, th, lam)).map_err(value_error)?;
    let out = PyDict::new(py);
    out.set_item("R", x.big_r)?;
    out.set_item("T", x.big_t)?;
    out.set_item("absorp_in_each_layer", PyArray1::from_vec(py, x.absorp))?;
    out.set_item("num_layers", n.len())?;
    out.set_item("pol", pol)?;
    Ok(out)
}

/// The checks of `coh_tmm` on a whole stack (tmm's list rules; finite indices with `Re n > 0`, no gain; finite
/// thicknesses ≥ 0; |θ₀| ≤ π/2; λ > 0), for `iridis.tmm.inc_tmm`, whose incoherent media reach no coherent
/// calculation to be checked by.
#[pyfunction]
#[pyo3(signature = (n_list, d_list, th_0, lam_vac))]
fn _check_stack(
    n_list: &Bound<'_, PyAny>,
    d_list: &Bound<'_, PyAny>,
    th_0: &Bound<'_, PyAny>,
    lam_vac: &Bound<'_, PyAny>,
) -> PyResult<()> {
    let n = complex_list("n_list", n_list)?;
    let d = real_list("d_list", d_list)?;
    let (th, lam) = (scalar("th_0", th_0, "")?, scalar("lam_vac", lam_vac, "")?);
    lib::check_lists(&n, &d).and_then(|()| lib::check_angle_wavelength(th, lam)).map_err(value_error)
}

/// The core of `iridis.tmm.coh_tmm_batch` (the Python wrapper broadcasts): `n` complex128, 1-D (media) or
/// 2-D (media × points); `d`, `th`, `lam` 1-D float64.
#[pyfunction]
#[pyo3(signature = (pol, n, d, th, lam))]
fn _coh_tmm_batch<'py>(
    py: Python<'py>,
    pol: &str,
    n: PyReadonlyArrayDyn<'py, Complex64>,
    d: PyReadonlyArray1<'py, f64>,
    th: PyReadonlyArray1<'py, f64>,
    lam: PyReadonlyArray1<'py, f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let p = self::pol(pol)?;
    let shape = n.shape().to_vec();
    let n_slice = n.as_slice().map_err(|_| PyValueError::new_err("n must be C-contiguous"))?;
    let (d, th, lam) = (d.as_slice()?, th.as_slice()?, lam.as_slice()?);
    let indices = match shape.len() {
        1 => Indices::Constant(n_slice),
        2 => Indices::PerPoint { media: shape[0], data: n_slice },
        k => return Err(PyValueError::new_err(format!("n_list must be 1-D or 2-D here, got {k}-D"))),
    };
    let b = py.allow_threads(|| lib::coh_tmm_batch(p, indices, d, th, lam)).map_err(value_error)?;
    let out = PyDict::new(py);
    out.set_item("r", b.r.into_pyarray(py))?;
    out.set_item("t", b.t.into_pyarray(py))?;
    out.set_item("R", b.big_r.into_pyarray(py))?;
    out.set_item("T", b.big_t.into_pyarray(py))?;
    out.set_item("power_entering", b.power_entering.into_pyarray(py))?;
    Ok(out)
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<CohTmmResult>()?;
    add_functions!(m, [coh_tmm, unpolarized_rt, ellips, _inc_tmm, _coh_tmm_batch, _check_stack]);
    Ok(())
}

/// tmm's four arguments of one coherent calculation: indices, thicknesses, angle and wavelength (scalars; the
/// batch takes arrays).
fn coherent_args(
    n_list: &Bound<'_, PyAny>,
    d_list: &Bound<'_, PyAny>,
    th_0: &Bound<'_, PyAny>,
    lam_vac: &Bound<'_, PyAny>,
) -> PyResult<(Vec<Complex64>, Vec<f64>, Complex64, f64)> {
    Ok((
        complex_list("n_list", n_list)?,
        real_list("d_list", d_list)?,
        complex_scalar("th_0", th_0, HINT)?,
        scalar("lam_vac", lam_vac, HINT)?,
    ))
}
