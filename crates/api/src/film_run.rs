//! One call per thin-film command, smooth or rough: `thinfilm spectrum`, `color`, `table` and `bench` run the
//! smooth film's model or, given a rough substrate ([`RoughLight`], [`RoughLights`]), the LSRS model; the choice
//! and what it refuses (options the rough model would ignore) are made here once, for the CLI and Python.

use anyhow::{bail, Result};
use iridis_color::Observer;
use iridis_plot::RgbImage;
use iridis_thinfilm::Stack;

use crate::film::{self, FilmColour, FilmSpectrum, FilmTable, Polarization};
pub use crate::film_chart::RoughLight;
use crate::rough::{self, Angles, RoughBench, RoughColourReport, RoughOptions, RoughSpectrum, RoughTableRun};
use crate::Report;

/// The rough substrate of a table: its model, the lights `FROM:TO:STEP` (`None`: the views) and their azimuth.
#[derive(Debug, Clone)]
pub struct RoughLights {
    pub options: RoughOptions,
    pub lights: Option<String>,
    pub azimuth: f64,
}

fn angles(view: f64, r: &RoughLight) -> Angles {
    Angles::new(view, r.light, r.azimuth)
}

/// A film's spectrum: `thinfilm spectrum`.
#[derive(Debug)]
pub enum Spectrum {
    Smooth(FilmSpectrum),
    Rough(RoughSpectrum),
}

/// The spectrum of `stack` at `angle_rad` over `grid`, for `polarization` (avg, s or p); with `rough`, over a
/// rough substrate, whose spectrum is unpolarised (its s and p are columns of the CSV and JSON).
pub fn spectrum(
    stack: &str,
    angle_rad: f64,
    grid: &[f64],
    polarization: &str,
    rough: Option<RoughLight>,
    report: &dyn Report,
) -> Result<Spectrum> {
    let unpolarised = "spectrum is unpolarised, with s and p columns in the CSV and JSON";
    let (parsed, pol) = parse(stack, polarization, rough.is_some(), unpolarised)?;
    Ok(match rough {
        Some(r) => Spectrum::Rough(rough::spectrum(parsed, stack, &r.options, angles(angle_rad, &r), grid)?),
        None => Spectrum::Smooth(film::spectrum(&parsed, stack, angle_rad, grid, pol, report)?),
    })
}

/// Refuses pavo's spectra CSV for a rough substrate (its R and T are a smooth film's), before the spectrum is
/// computed when the caller asks for the file up front.
pub fn refuse_spectra_csv(rough: bool) -> Result<()> {
    if rough {
        bail!(SPECTRA_CSV_ROUGH);
    }
    Ok(())
}

const SPECTRA_CSV_ROUGH: &str = "--spectra writes a smooth film's R and T; with --roughness use --csv";

/// The stack and polarisation as typed; with a rough substrate only unpolarised light (`rough_light`: what the
/// rough model gives instead, for the refusal).
fn parse(stack: &str, polarization: &str, rough: bool, rough_light: &str) -> Result<(Stack, Polarization)> {
    let (parsed, pol) = (film::parse_stack(stack)?, film::parse_polarization(polarization)?);
    if rough && pol != Polarization::Average {
        bail!("--polarization {polarization} would be ignored: with a rough substrate the {rough_light}");
    }
    Ok((parsed, pol))
}

impl Spectrum {
    pub fn to_json(&self) -> serde_json::Value {
        match self {
            Spectrum::Smooth(s) => s.to_json(),
            Spectrum::Rough(s) => s.to_json(),
        }
    }

    pub fn text(&self) -> String {
        match self {
            Spectrum::Smooth(s) => s.text(),
            Spectrum::Rough(s) => s.text(),
        }
    }

    pub fn csv(&self) -> String {
        match self {
            Spectrum::Smooth(s) => s.csv(),
            Spectrum::Rough(s) => s.csv(),
        }
    }

    pub fn plot(&self) -> Result<RgbImage> {
        match self {
            Spectrum::Smooth(s) => s.plot(),
            Spectrum::Rough(s) => s.plot(),
        }
    }

    /// R and T in pavo's layout (`--spectra`): a smooth film's ([`refuse_spectra_csv`]).
    pub fn spectra_csv(&self) -> Result<String> {
        match self {
            Spectrum::Smooth(s) => s.spectra_csv(),
            Spectrum::Rough(_) => bail!(SPECTRA_CSV_ROUGH),
        }
    }
}

/// A film's colours: `thinfilm color`.
#[derive(Debug)]
pub enum Colour {
    Smooth(Box<FilmColour>),
    Rough(Box<RoughColourReport>),
}

/// The colours of `stack` at `angle_rad` under `illuminant`; `visual` also shows them as an animal sees them
/// (a smooth film's). With `rough`, over a rough substrate, for unpolarised light.
#[allow(clippy::too_many_arguments)]
pub fn colour(
    stack: &str,
    angle_rad: f64,
    polarization: &str,
    grid: &[f64],
    illuminant: &str,
    observer: Observer,
    visual: Option<&str>,
    rough: Option<RoughLight>,
    report: &dyn Report,
) -> Result<Colour> {
    film::check_colour_grid(grid, film::GridGiven::Range, report)?;
    let (parsed, pol) = parse(stack, polarization, rough.is_some(), "colours are for unpolarised light")?;
    Ok(match rough {
        Some(r) => {
            if let Some(v) = visual {
                bail!("--visual {v} takes a smooth film's spectra; leave out --roughness");
            }
            let c =
                rough::colour_report(parsed, &r.options, angles(angle_rad, &r), grid, illuminant.parse()?, observer)?;
            Colour::Rough(Box::new(c))
        }
        None => {
            let c = film::colour(&parsed, angle_rad, pol, grid, illuminant, observer, visual, report)?;
            Colour::Smooth(Box::new(c))
        }
    })
}

impl Colour {
    pub fn to_json(&self) -> Result<serde_json::Value> {
        match self {
            Colour::Smooth(c) => c.to_json(),
            Colour::Rough(c) => Ok(c.to_json()),
        }
    }

    pub fn text(&self) -> String {
        match self {
            Colour::Smooth(c) => c.text(),
            Colour::Rough(c) => c.text(),
        }
    }

    /// What a reader should know of the colours as an animal sees them (a smooth film's, with `visual`).
    pub fn notes(&self) -> &[String] {
        match self {
            Colour::Smooth(c) => c.notes(),
            Colour::Rough(_) => &[],
        }
    }
}

/// A film's table: `thinfilm table`.
#[derive(Debug)]
pub enum Table {
    Smooth(FilmTable),
    Rough(RoughTableRun),
}

/// The angle × wavelength table of `stack` (`angles` `FROM:TO:STEP`); with `rough`, the view × light ×
/// wavelength table over a rough substrate.
pub fn table(
    stack: &str,
    angles: &str,
    grid: &[f64],
    rough: Option<RoughLights>,
    report: &dyn Report,
) -> Result<Table> {
    let parsed = film::parse_stack(stack)?;
    Ok(match rough {
        Some(r) => Table::Rough(rough::table(parsed, stack, &r.options, angles, r.lights.as_deref(), r.azimuth, grid)?),
        None => Table::Smooth(film::table(&parsed, stack, angles, grid, report)?),
    })
}

impl Table {
    /// The CSV (smooth: angle × wavelength; rough: view × light × wavelength).
    pub fn csv(&self) -> Result<Vec<u8>> {
        match self {
            Table::Smooth(t) => Ok(t.csv().into_bytes()),
            Table::Rough(t) => t.csv(),
        }
    }

    /// The map of R, on `scale` (auto, linear or log: [`film::table_scale`]).
    pub fn plot(&self, scale: &str, report: &dyn Report) -> Result<RgbImage> {
        match self {
            Table::Smooth(t) => t.plot(scale, report),
            Table::Rough(t) => t.plot(),
        }
    }

    /// A rough table's summary line (its size and model), for people; a smooth table has none.
    pub fn summary(&self) -> Option<String> {
        match self {
            Table::Smooth(_) => None,
            Table::Rough(t) => Some(t.summary()),
        }
    }

    /// What follows the CSV's file name in `wrote FILE…`: a smooth table's size (the rough one's is in its
    /// summary).
    pub fn written_size(&self) -> String {
        match self {
            Table::Smooth(t) => format!(" ({} angles × {} wavelengths)", t.angles_rad.len(), t.wavelength_nm.len()),
            Table::Rough(_) => String::new(),
        }
    }
}

/// The speed of the film models: `thinfilm bench`.
#[derive(Debug)]
pub enum Bench {
    Smooth(crate::film_bench::FilmBench),
    Rough(RoughBench),
}

/// Measures the smooth model against Python's tmm (unless `no_python`) or, with `rough`, the rough substrate's
/// table of Sussenbach's Listing 3.6, shared against direct (tmm has no rough model: `no_python` is refused).
pub fn bench(seconds: f64, no_python: bool, rough: Option<RoughLight>) -> Result<Bench> {
    Ok(match rough {
        Some(r) => {
            if no_python {
                bail!(
                    "--no-python would be ignored: the rough bench times iridis's table against its own direct \
                     evaluation (tmm has no rough model)"
                );
            }
            if let Some(l) = r.light {
                bail!(
                    "--light-angle {}° would be ignored: the rough bench times the whole table of Listing 3.6, \
                     every view and every light",
                    crate::film::round_deg(l)
                );
            }
            let stack = film::parse_stack(rough::LISTING_3_6_STACK)?;
            Bench::Rough(rough::bench(stack, &r.options, r.azimuth, 80, seconds)?)
        }
        None => Bench::Smooth(crate::film_bench::bench(seconds, no_python)?),
    })
}

impl Bench {
    pub fn to_json(&self) -> serde_json::Value {
        match self {
            Bench::Smooth(b) => b.to_json(),
            Bench::Rough(b) => b.to_json(),
        }
    }

    pub fn text(&self) -> String {
        match self {
            Bench::Smooth(b) => b.text(),
            Bench::Rough(b) => b.text(),
        }
    }
}
