//! `iridis thinfilm …`: multilayer thin-film interference (Sussenbach's smooth model, `iridis-thinfilm`):
//! spectra, angle × wavelength tables, film colours, the soap-film colour chart, and a benchmark against
//! the Python `tmm` package.

use std::path::{Path, PathBuf};

use anyhow::Result;
use clap::{Args as ClapArgs, Subcommand};
use iridis_api::film::{self, RgbImage};
use iridis_api::report::Report as _;
use iridis_api::{film_chart, film_fit, film_run};

use crate::output::{declare, declare_opt, print_answer, write_bytes, write_stdout_bytes};
use crate::progress::Cli;

#[derive(Debug, Subcommand)]
pub enum ThinfilmCommand {
    /// Reflectance, transmittance and absorptance spectra of a stack at one angle.
    #[command(after_help = "\
Stack syntax: media from the incident side to the substrate, separated by '|'; every layer between them has a
thickness with a unit. A medium is a library name (see 'iridis thinfilm materials'), n=1.38, n=0.2+3.4i
(κ ≥ 0 absorbs), cauchy:A,B,C (n = A + B/λ² + C/λ⁴, λ in µm), sellmeier:B1,C1,… or file:PATH
(refractiveindex.info YAML, or CSV with wavelength_nm,n,k). A layer written inc:MATERIAL is incoherent
(intensities add across it, as for a 1 mm glass slide; tmm's inc_tmm).

JSON keys: wavelength_nm, R, T, A (the chosen polarisation), Rs, Rp, Ts, Tp, psi_deg, delta_deg (ellipsometric
angles, tan ψ e^{iΔ} = −r_p/r_s as tmm.ellips; with inc: layers tan ψ = √(Rp/Rs) and Δ null: no single
phase survives an incoherent layer). CSV has the same columns. --spectra writes R and T in pavo's layout
(wl, R, T), which `iridis vision` reads.
A warning goes to stderr when the wavelength step is too coarse for the fringes of a thick layer.

Examples:
  iridis thinfilm spectrum --stack \"air | water 635nm | air\" --angle 1deg --from 400nm --to 690nm --step 10nm
  iridis thinfilm spectrum --stack \"air | gasoline 216nm | water 220nm | asphalt\" --plot oil.png
  iridis thinfilm spectrum --stack \"air | Si 108nm | glass\" --from 400nm --to 700nm --csv
  iridis thinfilm spectrum --stack \"air | n=1.38 100nm | n=0.2+3.4i\" --angle 45deg --polarization p --json
  iridis thinfilm spectrum --stack \"air | MgF2 100nm | inc:BK7 1mm | air\" --csv
  iridis thinfilm spectrum --stack \"air | water 348nm | air\" --from 300nm --to 700nm --step 1nm --spectra soap.csv")]
    Spectrum(SpectrumArgs),
    /// The angle × wavelength simulation table (Sussenbach Figure 3.8) as CSV, optionally a map image.
    #[command(after_help = "\
Columns: angle_deg, wavelength_nm, R, T, A, Rs, Rp, Ts, Tp, psi_deg, delta_deg (unpolarised R, T, A;
ellipsometric ψ, Δ as tmm.ellips; with inc: layers ψ from √(Rp/Rs) and Δ empty). Without -o the table goes to
standard output. --plot draws R as an angle × wavelength map with a colour bar, on a log scale when most of
R is small (an AR coating; --scale sets it).

Examples:
  iridis thinfilm table --stack \"air | water 635nm | air\" --angles 1deg:90deg:1deg --from 400nm --to 690nm --step 10nm -o t.csv
  iridis thinfilm table --stack \"air | MgF2 100nm | BK7\" --angles 0deg:89deg:1deg --plot ar_map.png -o ar.csv")]
    Table(TableArgs),
    /// Reflected and transmitted colour of a stack (spectrum → CIE XYZ → CIELAB, sRGB).
    #[command(after_help = "\
XYZ = ∫ R(λ) S(λ) x̄(λ) dλ / ∫ S(λ) ȳ(λ) dλ (likewise for T), so a perfect mirror has Y = 1; CIELAB is relative
to the illuminant's white; sRGB is clipped to the gamut at exposure 1.
JSON keys: docs/json.md, section `iridis thinfilm color`.
--visual adds how an animal sees the reflected and transmitted light (`iridis vision`, key vision in --json).

Examples:
  iridis thinfilm color --stack \"air | water 348nm | air\"
  iridis thinfilm color --stack \"air | gasoline 216nm | water 220nm | asphalt\" --angle 30deg --json
  iridis thinfilm color --stack \"air | TiO2 60nm | glass\" --illuminant d50
  iridis thinfilm color --stack \"air | water 348nm | air\" --visual bluetit --from 300nm --to 700nm")]
    Color(ColorArgs),
    /// The soap-film colour chart (Sussenbach Figure 5.11): colour against the thickness of one layer.
    #[command(after_help = "\
One layer's thickness is written {d}; it is swept over --thickness FROM:TO:STEP. The picture shows the
reflected colour (top band) and the transmitted colour (bottom band) with a labelled thickness axis. With
--roughness/--correlation (a rough substrate, LSRS model) the bands are the specular colour k_r (top, exposed
like the reflected band) and the diffuse colour π·k_d (bottom, at 1 RU: Y = 1 is a white matte surface). Film
reflectance is low (a soap film reflects at most ~8%), so by default the exposure is set so that the
brightest reflected colour of the chart reaches the top of the display range; --exposure fixes it instead
(in relative units, 1 RU = a perfect mirror is just white).

Examples:
  iridis thinfilm chart --stack \"air | water {d} | air\" --thickness 0nm:2000nm:2nm -o soap_chart.png
  iridis thinfilm chart --stack \"air | gasoline {d} | water 220nm | asphalt\" --thickness 0nm:1000nm:2nm --angle 30deg -o oil.png
  iridis thinfilm chart --stack \"air | water {d} | air\" --thickness 0nm:1000nm:1nm --exposure 4 --csv chart.csv -o chart.png
  iridis thinfilm chart --stack \"air | water {d} | Si\" --thickness 0nm:1000nm:2nm --roughness 25nm --correlation 300nm -o rough.png")]
    Chart(ChartArgs),
    /// The built-in materials and their sources.
    #[command(after_help = "\
Examples:
  iridis thinfilm materials
  iridis thinfilm materials --at 550nm")]
    Materials(MaterialsArgs),
    /// Speed: (λ, θ) evaluations per second for a 2-layer and a 20-layer stack, against Python's tmm.
    #[command(after_help = "\
One evaluation is R and T for s and p at one (λ, θ). Rust is timed on one thread and on all threads, on the
general path (Stack::evaluate) and on the chapter 4 fast path (Stack::prepare). The same work is timed in the
Python tmm package (two coh_tmm calls, s and p, per evaluation) by spawning python3, when it is installed.
Then a fit of 3 parameters on 401 wavelengths (the data of tools/fit_scipy_compare.py, which times scipy's
least_squares on the same problem) from one start and with the multi-start search, and a batch of 10⁶
(λ, θ) points of the 20-layer stack on all threads (fast and general path).

Examples:
  iridis thinfilm bench
  iridis thinfilm bench --seconds 0.5 --json
  iridis thinfilm bench --no-python")]
    Bench(BenchArgs),
    /// Where the light goes: absorption in each layer and |E|², absorbed power and flux against depth.
    #[command(after_help = "\
At one wavelength and angle: the fraction of the incident power reflected, absorbed in each layer (and in an
absorbing substrate) and transmitted, with the energy balance R + T + ΣA − 1 (zero up to rounding), and the
depth profile from 100 nm above the first interface to 100 nm into the substrate, or into the first inc:
layer under the films (--depth FROM:TO to choose): |E|² relative to the incident wave, absorbed power
density (fraction of the incident power per nm) and the normal Poynting flux (tmm's position_resolved;
Byrnes, arXiv:1603.02720). A layer that fewer than two samples fall in is named in a warning. With inc:
layers each coherent group is lit from both sides by incoherent intensities (tmm's inc_absorp_in_each_layer
and inc_find_absorp_analytic_fn), and inside an inc: layer the two beams decay by Beer–Lambert without
interference.
JSON keys: docs/json.md, section `iridis thinfilm profile`.

Examples:
  iridis thinfilm profile --stack \"air | Au 30nm | glass\" --wavelength 500nm
  iridis thinfilm profile --stack \"air | Si 108nm | glass\" --wavelength 450nm --angle 30deg --plot si_profile.png
  iridis thinfilm profile --stack \"air | TiO2 60nm | Si 50nm | inc:glass 1mm | air\" --wavelength 550nm --json
  iridis thinfilm profile --stack \"air | TiO2 60nm | Si 50nm | inc:glass 1mm | air\" --wavelength 550nm --depth=-20nm:200nm --csv")]
    Profile(crate::args::ProfileArgs),
    /// Fit a stack's free parameters to a measured R, T or ψ/Δ spectrum.
    #[command(after_help = "\
Free parameters are written into the stack as {NAME=START:LOW..HIGH}: a layer thickness (with a unit), a
constant index n={n1=1.45:1.3..1.7}, or a coefficient of cauchy:A,B,C / sellmeier:B1,C1,… e.g.
cauchy:{A=1.46:1.3..1.7},{B=0.004:0..0.05}. The fit is Levenberg–Marquardt (the levenberg-marquardt crate)
from the best points of a grid over the thickness ranges (fringes make χ² periodic in thickness; --grid 1 fits
from the start values only), with exact derivatives (automatic differentiation through the model). It prints
the values with 1σ uncertainties from the covariance (JᵀWJ)⁻¹, χ², and the correlation matrix. The file holds
columns of wavelength and R, T, or psi and delta (degrees), separated by commas, tabs, semicolons or spaces,
with a header in any common form (\"Wavelength (nm),Reflectance (%)\") or none; what was read is printed
(separator, columns, unit, percent detected from the header or values above 1.5); --columns, --percent and
--from/--to choose; a material without data over the range is named. --sigma gives the 1σ noise (a number or a column),
--weights the weights w = 1/σ² (a number, a column, or a CSV file with wavelength_nm,w); without either σ is
estimated from the scatter. psi-delta needs a coherent stack (Δ is undefined through an inc: layer).

Examples:
  iridis thinfilm fit measured.csv --stack \"air | SiO2 {d1=100nm:50nm..500nm} | Si\"
  iridis thinfilm fit slide.csv --stack \"air | n=2.1 {d=150nm:50nm..400nm} | inc:BK7 1mm | air\" --quantity T --sigma 0.002 --plot fit.png
  iridis thinfilm fit measured.csv --stack \"air | SiO2 {d1=100nm:50nm..500nm} | Si\" --weights 250000   # w = 1/σ², σ = 0.002; or a column name, or a file
  iridis thinfilm fit measured.csv --stack \"air | SiO2 {d1=100nm:50nm..500nm} | Si\" --columns wavelength_nm,R --from 450nm --to 650nm
  iridis thinfilm fit ellips.csv --stack \"air | n={n=1.5:1.3..1.7} {d=100nm:10nm..400nm} | Si\" --angle 70deg --quantity psi-delta --json")]
    Fit(crate::args::FitArgs),
}

#[derive(Debug, Clone, ClapArgs)]
pub struct GridArgs {
    /// First wavelength (with unit).
    #[arg(long, default_value = "380nm", value_parser = crate::args::length_nm)]
    pub from: f64,
    /// Last wavelength (with unit).
    #[arg(long, default_value = "780nm", value_parser = crate::args::length_nm)]
    pub to: f64,
    /// Wavelength step (with unit).
    #[arg(long, default_value = "5nm", value_parser = crate::args::positive_length_nm)]
    pub step: f64,
}

impl GridArgs {
    fn grid(&self) -> Result<Vec<f64>> {
        film::wavelength_grid(self.from, self.to, self.step)
    }
}

#[derive(Debug, ClapArgs)]
pub struct SpectrumArgs {
    /// The stack, e.g. "air | water 635nm | air".
    #[arg(long)]
    pub stack: String,
    /// Angle of incidence in the incident medium (0deg–90deg).
    #[arg(long, default_value = "0deg", value_parser = crate::args::angle_rad)]
    pub angle: f64,
    #[command(flatten)]
    pub grid: GridArgs,
    /// avg (unpolarised), s or p: which polarisation R, T, A refer to.
    #[arg(long, default_value = "avg")]
    pub polarization: String,
    /// Print JSON.
    #[arg(long, conflicts_with = "csv")]
    pub json: bool,
    /// Print CSV.
    #[arg(long)]
    pub csv: bool,
    /// Write a plot of R, T and A against wavelength (PNG).
    #[arg(long)]
    pub plot: Option<PathBuf>,
    /// Write R and T as a spectra CSV that pavo reads (wl, R, T), for `iridis vision` or R.
    #[arg(long)]
    pub spectra: Option<PathBuf>,
    #[command(flatten)]
    pub rough: crate::args::RoughArgs,
}

#[derive(Debug, ClapArgs)]
pub struct TableArgs {
    /// The stack, e.g. "air | water 635nm | air".
    #[arg(long)]
    pub stack: String,
    /// Angles FROM:TO:STEP with units.
    #[arg(long, default_value = "1deg:90deg:1deg")]
    pub angles: String,
    #[command(flatten)]
    pub grid: GridArgs,
    /// Output CSV file (standard output when absent).
    #[arg(short = 'o', long)]
    pub output: Option<PathBuf>,
    /// Write the angle × wavelength map of R (PNG).
    #[arg(long)]
    pub plot: Option<PathBuf>,
    /// Colour scale of --plot: linear (0 to the largest R), log (three decades below the largest R) or auto:
    /// log when most of the map would sit in the darkest tenth of a linear scale (an AR coating, whose R
    /// stays near 1 % until grazing incidence) [default: auto].
    #[arg(long, value_name = "auto|linear|log", requires = "plot")]
    pub scale: Option<String>,
    #[command(flatten)]
    pub rough: crate::args::RoughArgs,
}

#[derive(Debug, ClapArgs)]
pub struct ColorArgs {
    /// The stack, e.g. "air | water 348nm | air".
    #[arg(long)]
    pub stack: String,
    /// Angle of incidence (0deg–90deg).
    #[arg(long, default_value = "0deg", value_parser = crate::args::angle_rad)]
    pub angle: f64,
    /// Illuminant: d65, d50, a or e.
    #[arg(long, default_value = "d65")]
    pub illuminant: String,
    /// Standard observer: 1931 (2°) or 1964 (10°).
    #[arg(long, default_value = "1931")]
    pub observer: String,
    /// avg (unpolarised), s or p.
    #[arg(long, default_value = "avg")]
    pub polarization: String,
    #[command(flatten)]
    pub grid: GridArgs,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
    /// Also as an animal sees it: a visual system of `iridis vision` (bluetit, honeybee, …; under --illuminant,
    /// von Kries to grey). Use --from 300nm for animals that see ultraviolet.
    #[arg(long)]
    pub visual: Option<String>,
    #[command(flatten)]
    pub rough: crate::args::RoughArgs,
}

#[derive(Debug, ClapArgs)]
pub struct ChartArgs {
    /// The stack with one thickness written {d}, e.g. "air | water {d} | air".
    #[arg(long)]
    pub stack: String,
    /// Thicknesses FROM:TO:STEP with units.
    #[arg(long, default_value = "0nm:2000nm:2nm")]
    pub thickness: String,
    /// Angle of incidence (0deg–90deg).
    #[arg(long, default_value = "0deg", value_parser = crate::args::angle_rad)]
    pub angle: f64,
    /// Illuminant: d65, d50, a or e.
    #[arg(long, default_value = "d65")]
    pub illuminant: String,
    /// Exposure in RU; automatic when absent (brightest reflected colour at full scale).
    #[arg(long)]
    pub exposure: Option<f64>,
    #[command(flatten)]
    pub grid: GridArgs,
    /// Output PNG.
    #[arg(short = 'o', long, default_value = "thinfilm_chart.png")]
    pub output: PathBuf,
    /// Also write the numbers (thickness_nm, reflected X Y Z and hex, transmitted X Y Z and hex) as CSV;
    /// with --roughness the two parts are specular and diffuse (columns S_… and D_…).
    #[arg(long)]
    pub csv: Option<PathBuf>,
    #[command(flatten)]
    pub rough: crate::args::RoughArgs,
}

#[derive(Debug, ClapArgs)]
pub struct MaterialsArgs {
    /// Also print each material's index at this wavelength.
    #[arg(long, value_parser = crate::args::length_nm)]
    pub at: Option<f64>,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
}

#[derive(Debug, ClapArgs)]
pub struct BenchArgs {
    /// Minimum time per Rust measurement, in seconds; below 1 the batch of 10⁶ points shrinks by the same share.
    #[arg(long, default_value_t = 1.0)]
    pub seconds: f64,
    /// Do not time the Python tmm package.
    #[arg(long)]
    pub no_python: bool,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
    /// With --roughness/--correlation: time the LSRS table of Listing 3.6 (80 × 80 angles, 81 wavelengths).
    #[command(flatten)]
    pub rough: crate::args::RoughArgs,
}

pub fn run(command: ThinfilmCommand) -> Result<()> {
    match command {
        ThinfilmCommand::Spectrum(a) => spectrum(a),
        ThinfilmCommand::Table(a) => table(a),
        ThinfilmCommand::Color(a) => color(a),
        ThinfilmCommand::Chart(a) => chart(a),
        ThinfilmCommand::Materials(a) => {
            let m = film::materials(a.at)?;
            print_answer(a.json, || Ok(m.to_json()), || m.text())
        }
        ThinfilmCommand::Bench(a) => bench(a),
        ThinfilmCommand::Profile(a) => profile(a),
        ThinfilmCommand::Fit(a) => fit(a),
    }
}

/// Writes a plot when asked for, saying so on standard output unless `quiet`.
fn plot(path: Option<&Path>, quiet: bool, image: impl FnOnce() -> Result<RgbImage>) -> Result<()> {
    if let Some(p) = path {
        film::write_png(p, &image()?)?;
        if !quiet {
            crate::outln!("wrote {}", p.display())?;
        }
    }
    Ok(())
}

fn spectrum(a: SpectrumArgs) -> Result<()> {
    declare_opt("--plot", a.plot.as_deref(), &["png"])?;
    declare_opt("--spectra", a.spectra.as_deref(), &["csv"])?;
    let (quiet, rough) = (a.json || a.csv, a.rough.light()?);
    if a.spectra.is_some() {
        film_run::refuse_spectra_csv(rough.is_some())?; // before the spectrum, not after it
    }
    let s = film_run::spectrum(&a.stack, a.angle, &a.grid.grid()?, &a.polarization, rough, &Cli)?;
    if let Some(p) = &a.spectra {
        write_bytes(p, s.spectra_csv()?.as_bytes())?;
        if !quiet {
            eprintln!("wrote {} (pavo's layout: wl, R, T)", p.display());
        }
    }
    plot(a.plot.as_deref(), quiet, || s.plot())?;
    print_answer(a.json, || Ok(s.to_json()), || if a.csv { s.csv() } else { s.text() })
}

fn table(a: TableArgs) -> Result<()> {
    declare_opt("-o", a.output.as_deref(), &["csv"])?;
    declare_opt("--plot", a.plot.as_deref(), &["png"])?;
    let rough = a.rough.lights()?;
    let scale = film::table_scale(a.scale.as_deref(), rough.is_some())?;
    let t = film_run::table(&a.stack, &a.angles, &a.grid.grid()?, rough, &Cli)?;
    if let Some(summary) = t.summary() {
        Cli.info(&summary);
    }
    plot(a.plot.as_deref(), true, || t.plot(scale, &Cli))?;
    if let Some(p) = &a.plot {
        eprintln!("wrote {}", p.display());
    }
    let csv = t.csv()?;
    match &a.output {
        Some(p) => {
            write_bytes(p, &csv)?;
            eprintln!("wrote {}{}", p.display(), t.written_size());
            Ok(())
        }
        None => write_stdout_bytes(&csv),
    }
}

fn color(a: ColorArgs) -> Result<()> {
    let (observer, grid) = (a.observer.parse()?, a.grid.grid()?);
    let c = film_run::colour(
        &a.stack,
        a.angle,
        &a.polarization,
        &grid,
        &a.illuminant,
        observer,
        a.visual.as_deref(),
        a.rough.light()?,
        &Cli,
    )?;
    print_answer(a.json, || c.to_json(), || c.text())?;
    if !a.json {
        c.notes().iter().for_each(|n| Cli.note(n));
    }
    Ok(())
}

fn chart(a: ChartArgs) -> Result<()> {
    declare("-o", &a.output, &["png"])?;
    declare_opt("--csv", a.csv.as_deref(), &["csv"])?;
    let grid = a.grid.grid()?;
    let c =
        film_chart::chart(&a.stack, &a.thickness, a.angle, &a.illuminant, a.exposure, &grid, a.rough.light()?, &Cli)?;
    film::write_png(&a.output, &c.image()?)?;
    crate::outln!("wrote {} {}", a.output.display(), c.summary())?;
    if let Some(p) = &a.csv {
        write_bytes(p, c.csv().as_bytes())?;
        crate::outln!("wrote {}", p.display())?;
    }
    Ok(())
}

fn bench(a: BenchArgs) -> Result<()> {
    let b = film_run::bench(a.seconds, a.no_python, a.rough.light()?)?;
    print_answer(a.json, || Ok(b.to_json()), || b.text())
}

fn profile(a: crate::args::ProfileArgs) -> Result<()> {
    declare_opt("--plot", a.plot.as_deref(), &["png"])?;
    let p = film_fit::profile(&a.stack, a.wavelength, a.angle, &a.polarization, a.points, a.depth.as_deref(), &Cli)?;
    plot(a.plot.as_deref(), a.json || a.csv, || p.plot())?;
    print_answer(a.json, || Ok(p.to_json()), || if a.csv { p.csv() } else { p.text() })
}

fn fit(a: crate::args::FitArgs) -> Result<()> {
    declare_opt("--plot", a.plot.as_deref(), &["png"])?;
    declare_opt("-o", a.output.as_deref(), &["csv"])?;
    let f = film_fit::fit_file(&a.measured, &a.request, &Cli)?;
    if let Some(p) = &a.output {
        write_bytes(p, f.csv().as_bytes())?;
    }
    plot(a.plot.as_deref(), true, || f.plot())?;
    print_answer(a.json, || Ok(f.to_json()), || f.text())?;
    match (&a.plot, a.json) {
        (Some(p), false) => crate::outln!("wrote {}", p.display()),
        _ => Ok(()),
    }
}
