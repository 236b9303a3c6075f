//! `iridis.film` (and `iridis.color.xyz`): the computations of the commands `iridis
//! thinfilm spectrum|table|color|chart|materials|bench|profile|fit` and `iridis color xyz|delta-e`, by the same
//! library calls (`iridis_api::film`, `film_chart`, `film_fit`, `film_bench`, `rough`, `color`); [`Answer`] is
//! also what `iridis.vision.vision` returns. Each returns what the command prints — its JSON as text, its text, its CSV — and a plot
//! as RGB bytes where the command draws one; the Python module turns them into a dict, strings and an array.
//! The library's warnings become Python warnings; its errors `ValueError` (`OSError` for files).

use std::path::Path;

use iridis_api::film::{self, RgbImage};
use iridis_api::film_run::{self, RoughLight};
use iridis_api::rough::RoughOptions;
use iridis_api::{film_chart, film_fit};
use iridis_thinfilm::rough::DiffuseTransport;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict};

use crate::facade::{run, Options};

/// What a command gives: JSON text, text, CSV, a plot.
#[derive(Default)]
pub(crate) struct Answer {
    pub(crate) json: Option<serde_json::Value>,
    pub(crate) text: Option<String>,
    pub(crate) csv: Option<String>,
    pub(crate) image: Option<RgbImage>,
    pub(crate) extra: Vec<(&'static str, String)>,
}

impl Answer {
    pub(crate) fn into_py(self, py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
        let d = PyDict::new(py);
        d.set_item("json", self.json.map(|v| v.to_string()))?;
        d.set_item("text", self.text)?;
        d.set_item("csv", self.csv)?;
        match self.image {
            Some(img) => d.set_item("image", (img.height, img.width, PyBytes::new(py, &img.data)))?,
            None => d.set_item("image", py.None())?,
        }
        for (k, v) in self.extra {
            d.set_item(k, v)?;
        }
        Ok(d)
    }
}

/// The rough-substrate keywords of spectrum, table, color, chart and bench (the CLI's `--roughness`,
/// `--correlation`, `--d-iterations`, `--diffuse-transport`, `--azimuth`): `roughness_nm`, `correlation_nm`,
/// `d_iterations`, `diffuse_transport` (default `multiple`) and `azimuth_rad` (default π).
struct RoughArgs {
    roughness_nm: Option<f64>,
    correlation_nm: Option<f64>,
    d_iterations: Option<usize>,
    diffuse_transport: Option<String>,
    azimuth_rad: Option<f64>,
}

impl RoughArgs {
    fn read(o: &mut Options) -> PyResult<Self> {
        Ok(Self {
            roughness_nm: o.f64("roughness_nm")?,
            correlation_nm: o.f64("correlation_nm")?,
            d_iterations: o.usize("d_iterations")?,
            diffuse_transport: o.string("diffuse_transport")?,
            azimuth_rad: o.f64("azimuth_rad")?,
        })
    }

    /// The light's azimuth relative to the viewer (default π, the mirror configuration).
    fn azimuth(&self) -> f64 {
        self.azimuth_rad.unwrap_or(std::f64::consts::PI)
    }

    /// The rough substrate with its light at `light_rad` (`None`: the view angle), when roughness was given.
    fn light(&self, light_rad: Option<f64>) -> anyhow::Result<Option<RoughLight>> {
        let options = self.options(light_rad.map(|_| "light_angle_rad"))?;
        Ok(options.map(|options| RoughLight { options, light: light_rad, azimuth: self.azimuth() }))
    }

    /// The rough model's options (`None` when no roughness was given, and then none of the keywords that shape
    /// its diffuse light: they would be ignored). `light`: the light's keyword, when it was given.
    fn options(&self, light: Option<&str>) -> anyhow::Result<Option<RoughOptions>> {
        match (self.roughness_nm, self.correlation_nm) {
            (None, None) => {
                let given: Vec<&str> = [
                    ("d_iterations", self.d_iterations.is_some()),
                    ("diffuse_transport", self.diffuse_transport.is_some()),
                    ("azimuth_rad", self.azimuth_rad.is_some()),
                ]
                .into_iter()
                .filter_map(|(k, given)| given.then_some(k))
                .chain(light)
                .collect();
                if !given.is_empty() {
                    anyhow::bail!(
                        "{} would be ignored: they shape the diffuse light of a rough substrate; give roughness_nm and \
                         correlation_nm",
                        given.join(", ")
                    );
                }
                Ok(None)
            }
            (Some(sigma_nm), Some(tau_nm)) => {
                // The front ends' defaults for what was not given, from the one place that holds them.
                let mut r = RoughOptions { d_iterations: self.d_iterations, ..RoughOptions::new(sigma_nm, tau_nm) };
                if let Some(t) = &self.diffuse_transport {
                    r.transport = DiffuseTransport::parse(t)?;
                }
                Ok(Some(r))
            }
            _ => anyhow::bail!("the rough model needs both roughness_nm and correlation_nm"),
        }
    }
}

/// The rough-substrate keywords with the light's direction `light_rad` (spectrum, color, chart).
struct RoughLightArgs {
    roughness: RoughArgs,
    light_rad: Option<f64>,
}

impl RoughLightArgs {
    fn read(options: Option<Bound<'_, PyDict>>) -> PyResult<Self> {
        Options::read(options, |o| Ok(Self { roughness: RoughArgs::read(o)?, light_rad: o.f64("light_rad")? }))
    }

    fn light(&self) -> anyhow::Result<Option<RoughLight>> {
        self.roughness.light(self.light_rad)
    }
}

/// `iridis thinfilm spectrum` (smooth, or rough with `roughness_nm`/`correlation_nm`).
#[pyfunction]
#[pyo3(signature = (stack, angle_rad, from_nm, to_nm, step_nm, polarization, plot, **options))]
#[allow(clippy::too_many_arguments)]
fn _film_spectrum<'py>(
    py: Python<'py>,
    stack: &str,
    angle_rad: f64,
    from_nm: f64,
    to_nm: f64,
    step_nm: f64,
    polarization: &str,
    plot: bool,
    options: Option<Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let rough = RoughLightArgs::read(options)?;
    let a = run(py, |report| {
        let grid = film::wavelength_grid(from_nm, to_nm, step_nm)?;
        let s = film_run::spectrum(stack, angle_rad, &grid, polarization, rough.light()?, report)?;
        let image = if plot { Some(s.plot()?) } else { None };
        let extra = match &s {
            film_run::Spectrum::Smooth(_) => vec![("spectra_csv", s.spectra_csv()?)],
            film_run::Spectrum::Rough(_) => Vec::new(),
        };
        Ok(Answer { json: Some(s.to_json()), text: Some(s.text()), csv: Some(s.csv()), image, extra })
    })?;
    a.into_py(py)
}

/// `iridis thinfilm table`: the CSV (smooth: angle × wavelength; rough: view × light × wavelength).
#[pyfunction]
#[pyo3(signature = (stack, angles, from_nm, to_nm, step_nm, plot, scale=None, **options))]
#[allow(clippy::too_many_arguments)]
fn _film_table<'py>(
    py: Python<'py>,
    stack: &str,
    angles: &str,
    from_nm: f64,
    to_nm: f64,
    step_nm: f64,
    plot: bool,
    scale: Option<&str>,
    options: Option<Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let (roughness, light_angles) = Options::read(options, |o| Ok((RoughArgs::read(o)?, o.string("light_angles")?)))?;
    let a = run(py, |report| {
        let grid = film::wavelength_grid(from_nm, to_nm, step_nm)?;
        if scale.is_some() && !plot {
            anyhow::bail!("scale is the colour scale of the plot: give plot=True");
        }
        let rough = roughness.options(light_angles.as_ref().map(|_| "light_angles"))?.map(|options| {
            film_run::RoughLights { options, lights: light_angles.clone(), azimuth: roughness.azimuth() }
        });
        let scale = film::table_scale(scale, rough.is_some())?;
        let t = film_run::table(stack, angles, &grid, rough, report)?;
        let image = if plot { Some(t.plot(scale, report)?) } else { None };
        let csv = Some(String::from_utf8(t.csv()?)?);
        let extra = t.summary().map(|s| vec![("summary", s)]).unwrap_or_default();
        Ok(Answer { csv, image, extra, ..Default::default() })
    })?;
    a.into_py(py)
}

/// `iridis thinfilm color`.
#[pyfunction]
#[pyo3(signature = (stack, angle_rad, polarization, from_nm, to_nm, step_nm, illuminant, observer, visual=None,
    **options))]
#[allow(clippy::too_many_arguments)]
fn _film_color<'py>(
    py: Python<'py>,
    stack: &str,
    angle_rad: f64,
    polarization: &str,
    from_nm: f64,
    to_nm: f64,
    step_nm: f64,
    illuminant: &str,
    observer: &str,
    visual: Option<String>,
    options: Option<Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let rough = RoughLightArgs::read(options)?;
    let a = run(py, |report| {
        let grid = film::wavelength_grid(from_nm, to_nm, step_nm)?;
        let c = film_run::colour(
            stack,
            angle_rad,
            polarization,
            &grid,
            illuminant,
            observer.parse()?,
            visual.as_deref(),
            rough.light()?,
            report,
        )?;
        c.notes().iter().for_each(|n| iridis_api::Report::note(report, n));
        Ok(Answer { json: Some(c.to_json()?), text: Some(c.text()), ..Default::default() })
    })?;
    a.into_py(py)
}

/// `iridis thinfilm chart`: the CSV, the picture and what was drawn.
#[pyfunction]
#[pyo3(signature = (stack, thickness, angle_rad, illuminant, exposure, from_nm, to_nm, step_nm, **options))]
#[allow(clippy::too_many_arguments)]
fn _film_chart<'py>(
    py: Python<'py>,
    stack: &str,
    thickness: &str,
    angle_rad: f64,
    illuminant: &str,
    exposure: Option<f64>,
    from_nm: f64,
    to_nm: f64,
    step_nm: f64,
    options: Option<Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let rough = RoughLightArgs::read(options)?;
    let a = run(py, |r| {
        let grid = film::wavelength_grid(from_nm, to_nm, step_nm)?;
        let c = film_chart::chart(stack, thickness, angle_rad, illuminant, exposure, &grid, rough.light()?, r)?;
        Ok(Answer {
            csv: Some(c.csv()),
            image: Some(c.image()?),
            extra: vec![("summary", c.summary()), ("exposure", c.exposure.to_string())],
            ..Default::default()
        })
    })?;
    a.into_py(py)
}

/// `iridis thinfilm materials`.
#[pyfunction]
#[pyo3(signature = (at_nm=None))]
fn _film_materials(py: Python<'_>, at_nm: Option<f64>) -> PyResult<Bound<'_, PyDict>> {
    let a = run(py, |_| {
        let m = film::materials(at_nm)?;
        Ok(Answer { json: Some(m.to_json()), text: Some(m.text()), ..Default::default() })
    })?;
    a.into_py(py)
}

/// `iridis thinfilm bench` (with `roughness_nm`/`correlation_nm`: the LSRS table of Listing 3.6).
#[pyfunction]
#[pyo3(signature = (seconds, no_python, **options))]
fn _film_bench<'py>(
    py: Python<'py>,
    seconds: f64,
    no_python: bool,
    options: Option<Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let roughness = Options::read(options, RoughArgs::read)?;
    let a = run(py, |_| {
        let b = film_run::bench(seconds, no_python, roughness.light(None)?)?;
        Ok(Answer { json: Some(b.to_json()), text: Some(b.text()), ..Default::default() })
    })?;
    a.into_py(py)
}

/// `iridis thinfilm profile`.
#[pyfunction]
#[pyo3(signature = (stack, wavelength_nm, angle_rad, polarization, points, depth, plot))]
#[allow(clippy::too_many_arguments)]
fn _film_profile<'py>(
    py: Python<'py>,
    stack: &str,
    wavelength_nm: f64,
    angle_rad: f64,
    polarization: &str,
    points: usize,
    depth: Option<String>,
    plot: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let a = run(py, |report| {
        let p = film_fit::profile(stack, wavelength_nm, angle_rad, polarization, points, depth.as_deref(), report)?;
        let image = if plot { Some(p.plot()?) } else { None };
        Ok(Answer { json: Some(p.to_json()), text: Some(p.text()), csv: Some(p.csv()), image, ..Default::default() })
    })?;
    a.into_py(py)
}

/// The request of `iridis thinfilm fit` (`iridis.film.fit`, `iridis.thinfilm.fit` of a file): `stack`,
/// `angle_rad`, `quantity`, `grid` and the keywords of reading the file and weighting it — `sigma`, `weights`,
/// `columns`, `percent`, `from_nm`, `to_nm` (the CLI's options of the same names); any other keyword is a
/// `TypeError`.
pub(crate) fn fit_request(
    stack: &str,
    angle_rad: f64,
    quantity: &str,
    grid: usize,
    options: Option<Bound<'_, PyDict>>,
) -> PyResult<film_fit::FitRequest> {
    Options::read(options, |o| {
        Ok(film_fit::FitRequest {
            stack: stack.to_string(),
            angle_rad,
            quantity: quantity.to_string(),
            sigma: o.string("sigma")?,
            weights: o.string("weights")?,
            grid,
            columns: o.string("columns")?,
            percent: o.bool("percent")?,
            from_nm: o.f64("from_nm")?,
            to_nm: o.f64("to_nm")?,
        })
    })
}

/// `iridis thinfilm fit` of the measured spectrum in a file.
#[pyfunction]
#[pyo3(signature = (path, stack, angle_rad, quantity, grid, plot, **options))]
#[allow(clippy::too_many_arguments)]
fn _film_fit<'py>(
    py: Python<'py>,
    path: &str,
    stack: &str,
    angle_rad: f64,
    quantity: &str,
    grid: usize,
    plot: bool,
    options: Option<Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let request = fit_request(stack, angle_rad, quantity, grid, options)?;
    let a = run(py, |report| {
        let f = film_fit::fit_file(Path::new(path), &request, report)?;
        let image = if plot { Some(f.plot()?) } else { None };
        Ok(Answer { json: Some(f.to_json()), text: Some(f.text()), csv: Some(f.csv()), image, ..Default::default() })
    })?;
    a.into_py(py)
}

/// `iridis color xyz`: the colour of a spectrum file.
#[pyfunction]
fn _color_xyz<'py>(
    py: Python<'py>,
    path: &str,
    illuminant: &str,
    observer: &str,
    emissive: bool,
    percent: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let a = run(py, |report| {
        let c = iridis_api::color::xyz(Path::new(path), illuminant, observer, emissive, percent, report)?;
        Ok(Answer { json: Some(c.to_json()), text: Some(c.text()), ..Default::default() })
    })?;
    a.into_py(py)
}

/// `iridis color delta-e`: the difference of two `L,a,b` texts.
#[pyfunction]
fn _color_delta_e(py: Python<'_>, first: &str, second: &str, formula: &str) -> PyResult<f64> {
    run(py, |_| iridis_api::color::delta_e(first, second, formula))
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    add_functions!(
        m,
        [
            _film_spectrum,
            _film_table,
            _film_color,
            _film_chart,
            _film_materials,
            _film_bench,
            _film_profile,
            _film_fit,
            _color_xyz,
            _color_delta_e
        ]
    );
    Ok(())
}
