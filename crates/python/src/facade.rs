//! Calling the facade (`iridis-api`, the functions the CLI calls) from Python: the GIL released while it
//! works, its notes and warnings kept ([`Collect`]) and given to Python afterwards — warnings as
//! `warnings.warn(…, UserWarning)` of the caller's line (`iridis._answer.warn_caller`), notes and the rest on the `logging` logger `iridis` — and its errors raised
//! with the CLI's messages: `OSError` when a file could not be read, `ValueError` otherwise.

use iridis_api::report::{Collect, Kind};
use pyo3::exceptions::{PyOSError, PyValueError};
use pyo3::prelude::*;

// A keyword argument no option of the call reads: a TypeError, as Python's own, with `keyword` (the name given)
// and `known` (the names the call reads) as attributes.
pyo3::create_exception!(_native, UnexpectedKeyword, pyo3::exceptions::PyTypeError);

/// Adds the module's exception classes (`_native.UnexpectedKeyword`).
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("UnexpectedKeyword", m.py().get_type::<UnexpectedKeyword>())
}

/// Whether an error comes from reading a file (the cause chain holds an I/O error).
fn is_io(e: &anyhow::Error) -> bool {
    e.chain().any(|c| {
        c.is::<std::io::Error>()
            || matches!(c.downcast_ref::<iridis_surface::SurfaceError>(), Some(iridis_surface::SurfaceError::Io { .. }))
            || matches!(
                c.downcast_ref::<iridis_diffraction::DiffractionError>(),
                Some(iridis_diffraction::DiffractionError::Io(_))
            )
            || matches!(c.downcast_ref::<iridis_render::RenderError>(), Some(iridis_render::RenderError::Io(_)))
            || matches!(c.downcast_ref::<iridis_color::SpectrumError>(), Some(iridis_color::SpectrumError::Io { .. }))
            || matches!(c.downcast_ref::<iridis_vision::VisionError>(), Some(iridis_vision::VisionError::Io { .. }))
            || matches!(
                c.downcast_ref::<iridis_thinfilm::ThinFilmError>(),
                Some(
                    iridis_thinfilm::ThinFilmError::Unreadable { .. }
                        | iridis_thinfilm::ThinFilmError::Stack { unreadable: true, .. }
                )
            )
    })
}

/// A facade error as a Python exception, with the message the CLI prints after `error: `, its flags named by
/// their keywords ([`crate::args::in_python_terms`]).
pub fn api_error(e: anyhow::Error) -> PyErr {
    let msg = crate::args::in_python_terms(&format!("{e:#}"));
    if is_io(&e) {
        PyOSError::new_err(msg)
    } else {
        PyValueError::new_err(msg)
    }
}

/// Gives Python what the facade said: warnings to `warnings.warn`, the rest to the `iridis` logger.
fn emit(py: Python<'_>, lines: Vec<(Kind, String)>) -> PyResult<()> {
    if lines.is_empty() {
        return Ok(());
    }
    let answer = py.import("iridis._answer")?;
    let logger = py.import("logging")?.call_method1("getLogger", ("iridis",))?;
    for (kind, text) in lines {
        let text = crate::args::in_python_terms(&text);
        match kind {
            Kind::Warning => {
                answer.call_method1("warn_caller", (text,))?;
            }
            Kind::Note => {
                logger.call_method1("info", (format!("note: {text}"),))?;
            }
            Kind::Info => {
                logger.call_method1("info", (text,))?;
            }
        }
    }
    Ok(())
}

/// Runs `f` (a facade call) with the GIL released, then reports what it said and raises its error, if any.
pub fn run<T: Send>(py: Python<'_>, f: impl FnOnce(&Collect) -> anyhow::Result<T> + Send) -> PyResult<T> {
    let report = Collect::default();
    let out = py.allow_threads(|| f(&report));
    emit(py, report.take())?;
    out.map_err(api_error)
}

/// A facade result's JSON (what the command prints with `--json`) as Python objects, as `json.loads` reads it.
pub fn json_to_py<'py>(py: Python<'py>, value: &serde_json::Value) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_string(value).map_err(crate::args::value_error)?;
    py.import("json")?.call_method1("loads", (text,))
}

/// A library value as Python objects under the names it has in the CLI's `--json` (its serde form), so that a key
/// is written in one place: the struct.
pub fn serialized<'py>(py: Python<'py>, value: &impl serde::Serialize) -> PyResult<Bound<'py, PyAny>> {
    json_to_py(py, &serde_json::to_value(value).map_err(crate::args::value_error)?)
}

/// The keyword options of a facade call (the wrapper's `**options`), read by name and type: a wrong type is a
/// `TypeError` naming the option, a name no option has is a `TypeError` as Python gives for an unexpected
/// keyword, `None` is the same as leaving the option out.
#[derive(Debug)]
pub struct Options<'py> {
    dict: Option<Bound<'py, pyo3::types::PyDict>>,
    used: Vec<&'static str>,
}

impl<'py> Options<'py> {
    pub fn new(dict: Option<Bound<'py, pyo3::types::PyDict>>) -> Self {
        Self { dict, used: Vec::new() }
    }

    /// What `read` takes from the keyword options `dict`, any keyword it did not read refused ([`Self::finish`]).
    pub fn read<T>(
        dict: Option<Bound<'py, pyo3::types::PyDict>>,
        read: impl FnOnce(&mut Self) -> PyResult<T>,
    ) -> PyResult<T> {
        let mut o = Self::new(dict);
        let value = read(&mut o)?;
        o.finish()?;
        Ok(value)
    }

    fn value(&mut self, key: &'static str) -> PyResult<Option<Bound<'py, PyAny>>> {
        self.used.push(key);
        let Some(d) = &self.dict else { return Ok(None) };
        Ok(d.get_item(key)?.filter(|v| !v.is_none()))
    }

    /// Reads the keyword `old`, an option's former name, as `new` (its name now, the CLI's flag's), with a
    /// `DeprecationWarning`; both given is a `TypeError`. Call before reading `new`.
    pub fn former_name(&mut self, old: &'static str, new: &'static str) -> PyResult<()> {
        self.used.push(old);
        let Some(d) = &self.dict else { return Ok(()) };
        let Some(v) = d.get_item(old)? else { return Ok(()) };
        if d.get_item(new)?.is_some_and(|n| !n.is_none()) {
            return Err(pyo3::exceptions::PyTypeError::new_err(format!(
                "both {new}= and its former name {old}= were given; give {new}= alone"
            )));
        }
        let py = d.py();
        py.import("iridis._answer")?.call_method1(
            "warn_caller",
            (format!("{old}= is now {new}="), py.get_type::<pyo3::exceptions::PyDeprecationWarning>()),
        )?;
        d.set_item(new, v)?;
        d.del_item(old)
    }

    fn type_error(key: &str, what: &str, v: &Bound<'_, PyAny>) -> PyErr {
        let ty = v.get_type().name().map(|n| n.to_string()).unwrap_or_else(|_| "?".into());
        pyo3::exceptions::PyTypeError::new_err(format!("{key} must be {what}, got {ty}"))
    }

    /// A real number.
    pub fn f64(&mut self, key: &'static str) -> PyResult<Option<f64>> {
        match self.value(key)? {
            None => Ok(None),
            Some(v) if v.is_instance_of::<pyo3::types::PyBool>() => Err(Self::type_error(key, "a number", &v)),
            Some(v) => v.extract::<f64>().map(Some).map_err(|_| Self::type_error(key, "a number", &v)),
        }
    }

    /// A length or other quantity that must be finite and positive.
    pub fn positive(&mut self, key: &'static str) -> PyResult<Option<f64>> {
        match self.f64(key)? {
            Some(x) if !(x.is_finite() && x > 0.0) => {
                Err(PyValueError::new_err(format!("{key} = {x}: must be a positive, finite number")))
            }
            x => Ok(x),
        }
    }

    /// A whole number ≥ 0: an int, or a float that is one (5.0), as the Python wrappers' `count` takes it.
    pub fn usize(&mut self, key: &'static str) -> PyResult<Option<usize>> {
        match self.value(key)? {
            None => Ok(None),
            Some(v) if v.is_instance_of::<pyo3::types::PyBool>() => Err(Self::type_error(key, "an integer", &v)),
            Some(v) if v.is_instance_of::<pyo3::types::PyFloat>() => match v.extract::<f64>()? {
                x if x.is_finite() && x.fract() == 0.0 && x >= 0.0 && x < 2f64.powi(53) => Ok(Some(x as usize)),
                x if x.is_finite() && x.fract() == 0.0 && x < 0.0 => {
                    Err(PyValueError::new_err(format!("{key} = {x}: must be ≥ 0")))
                }
                _ => Err(Self::type_error(key, "a whole number", &v)),
            },
            Some(v) => match v.extract::<i64>() {
                Ok(n) if n >= 0 => Ok(Some(n as usize)),
                Ok(n) => Err(PyValueError::new_err(format!("{key} = {n}: must be ≥ 0"))),
                Err(_) => Err(Self::type_error(key, "an integer", &v)),
            },
        }
    }

    pub fn string(&mut self, key: &'static str) -> PyResult<Option<String>> {
        match self.value(key)? {
            None => Ok(None),
            Some(v) => v.extract::<String>().map(Some).map_err(|_| Self::type_error(key, "a str", &v)),
        }
    }

    pub fn bool(&mut self, key: &'static str) -> PyResult<Option<bool>> {
        match self.value(key)? {
            None => Ok(None),
            Some(v) => v.extract::<bool>().map(Some).map_err(|_| Self::type_error(key, "True or False", &v)),
        }
    }

    /// A length as the CLI takes it (`"5nm"`, `"0.2um"`), in nm; positive.
    pub fn length_text_nm(&mut self, key: &'static str) -> PyResult<Option<f64>> {
        self.string(key)?
            .map(|s| {
                iridis_color::units::parse_positive_length_nm(&s)
                    .map_err(|e| PyValueError::new_err(format!("{key} '{s}': {}", e.0)))
            })
            .transpose()
    }

    /// `channel`: a channel of a multi-channel file, by index (an int) or name.
    pub fn channel(&mut self) -> PyResult<Option<iridis_surface::formats::channel::ChannelSel>> {
        match self.value("channel")? {
            None => Ok(None),
            Some(v) => {
                let s = if let Ok(i) = v.extract::<usize>() { i.to_string() } else { v.str()?.to_string() };
                Ok(Some(s.parse().map_err(|e: String| PyValueError::new_err(format!("channel: {e}")))?))
            }
        }
    }

    /// How to read a SURFACE argument: `pixel_size_nm`, `max_height_nm`, `channel`, `height_unit`, `level`,
    /// `override_units` and `as_height` (the CLI's `--override-units`, `--as-height`).
    pub fn surface(&mut self) -> PyResult<iridis_api::SurfaceOptions> {
        Ok(iridis_api::SurfaceOptions {
            pixel_size_nm: self.positive("pixel_size_nm")?,
            max_height_nm: self.positive("max_height_nm")?,
            channel: self.channel()?,
            height_unit: self.string("height_unit")?,
            level: self.string("level")?,
            units: iridis_api::surface::UnitOverrides {
                override_units: self.bool("override_units")?.unwrap_or(false),
                as_height: self.bool("as_height")?.unwrap_or(false),
            },
        })
    }

    /// The model: `terms` (None: from the remainder bound), `coherence_nm`, `illuminant`, `observer`, `step_nm`,
    /// and for `method="rigorous"` `material` and `unit_cell`.
    pub fn model(&mut self) -> PyResult<iridis_api::ModelOptions> {
        Ok(iridis_api::ModelOptions {
            terms: self.usize("terms")?.map(|n| n.to_string()).unwrap_or_else(|| "auto".into()),
            coherence_nm: self.positive("coherence_nm")?,
            illuminant: self.string("illuminant")?,
            observer: self.string("observer")?,
            step_nm: self.positive("step_nm")?,
            conserve_energy: self.bool("conserve_energy")?.unwrap_or(false),
            light: None,
            // method="rigorous": the medium under the relief and the unit cell ("whole" or "auto").
            material: self.string("material")?,
            unit_cell_auto: self.unit_cell_auto()?,
        })
    }

    /// `unit_cell`: "whole" (the default) or "auto" (`--unit-cell`), whether it is "auto".
    pub fn unit_cell_auto(&mut self) -> PyResult<bool> {
        match self.string("unit_cell")? {
            None => Ok(false),
            Some(s) => iridis_api::brdf::unit_cell_auto(&s).map_err(api_error),
        }
    }

    /// The shading factors: `fresnel` (default `schlick:1.5`), `fresnel_convention` (`physical` or `paper`),
    /// `shadowing` (default True), as text the CLI takes.
    pub fn shading_text(&mut self) -> PyResult<(String, iridis_diffraction::FresnelConvention, bool)> {
        let fresnel = self.string("fresnel")?.unwrap_or_else(|| iridis_api::fresnel::DEFAULT_FRESNEL.into());
        let convention = match self.string("fresnel_convention")? {
            None => iridis_diffraction::FresnelConvention::Physical,
            Some(c) => {
                iridis_diffraction::FresnelConvention::parse(&c).map_err(|e| PyValueError::new_err(e.to_string()))?
            }
        };
        Ok((fresnel, convention, self.bool("shadowing")?.unwrap_or(true)))
    }

    /// Refuses options no one read ([`UnexpectedKeyword`]).
    pub fn finish(self) -> PyResult<()> {
        let Some(d) = &self.dict else { return Ok(()) };
        for k in d.keys() {
            let k: String = k.extract()?;
            if !self.used.contains(&k.as_str()) {
                let mut known = self.used.clone();
                known.sort_unstable();
                let e = UnexpectedKeyword::new_err(format!(
                    "unexpected keyword argument '{k}' (this call takes: {})",
                    known.join(", ")
                ));
                // The name and the options as attributes: the Python wrapper (`_answer.keywords`) adds its own
                // parameters and a did-you-mean without reading the message.
                let value = e.value(d.py());
                value.setattr("keyword", &k)?;
                value.setattr("known", known)?;
                return Err(e);
            }
        }
        Ok(())
    }
}
