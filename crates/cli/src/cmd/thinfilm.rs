//! `iridis thinfilm …`: multilayer thin-film interference (Sussenbach's smooth model, `iridis-thinfilm`):
//! spectra, angle × wavelength tables, film colours, the soap-film colour chart, and a benchmark against
//! the Python `tmm` package.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{bail, Context, Result};
use clap::{Args as ClapArgs, Subcommand};
use iridis_color::spectrum::uniform_grid;
use iridis_color::units::{parse_angle_rad, parse_length_nm, parse_range};
use iridis_color::{Illuminant, Observer, ToneMap, Xyz};
use iridis_plot::{magma, ColorBar, ImagePlot, LinePlot, RgbImage, Series};
use iridis_thinfilm::color::{FilmColorimeter, Polarization};
use iridis_thinfilm::grid::{evaluate_grid, Path as GridPath};
use iridis_thinfilm::{Material, Rta, Stack};
use serde_json::json;

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
JSON: reflected, transmitted, specular, diffuse (each XYZ, xyY, Lab, linear_srgb, srgb, hex), rough (docs/json.md).
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
depth profile from 100 nm above the first interface to 100 nm into the substrate (--depth FROM:TO to choose):
|E|² relative to the incident wave, absorbed power density (fraction of the incident power per nm) and the
normal Poynting flux (tmm's position_resolved; Byrnes, arXiv:1603.02720). With inc: layers each coherent
group is lit from both sides by incoherent intensities (tmm's inc_absorp_in_each_layer and
inc_find_absorp_analytic_fn), and inside an inc: layer the two beams decay by Beer–Lambert without
interference.
JSON keys: R, T, layers, A_layers, A_substrate, balance, profile {z_nm, medium, E2, absorption_per_nm, flux}.

Examples:
  iridis thinfilm profile --stack \"air | Au 30nm | glass\" --wavelength 500nm
  iridis thinfilm profile --stack \"air | Si 108nm | glass\" --wavelength 450nm --angle 30deg --plot si_profile.png
  iridis thinfilm profile --stack \"air | TiO2 60nm | Si 50nm | inc:glass 1mm | air\" --wavelength 550nm --json
  iridis thinfilm profile --stack \"air | TiO2 60nm | Si 50nm | inc:glass 1mm | air\" --wavelength 550nm --depth=-20nm:200nm --csv")]
    Profile(super::filmfit::ProfileArgs),
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
(separator, columns, unit, percent detected from the header or values above 1); --columns, --percent and
--from/--to choose; a material without data over the range is named. --sigma gives the 1σ noise (a number or a column),
--weights the weights w = 1/σ² (a number, a column, or a CSV file with wavelength_nm,w); without either σ is
estimated from the scatter. psi-delta needs a coherent stack (Δ is undefined through an inc: layer).

Examples:
  iridis thinfilm fit measured.csv --stack \"air | SiO2 {d1=100nm:50nm..500nm} | Si\"
  iridis thinfilm fit slide.csv --stack \"air | n=2.1 {d=150nm:50nm..400nm} | inc:BK7 1mm | air\" --quantity T --sigma 0.002 --plot fit.png
  iridis thinfilm fit measured.csv --stack \"air | SiO2 {d1=100nm:50nm..500nm} | Si\" --weights 250000   # w = 1/σ², σ = 0.002; or a column name, or a file
  iridis thinfilm fit measured.csv --stack \"air | SiO2 {d1=100nm:50nm..500nm} | Si\" --columns wavelength_nm,R --from 450nm --to 650nm
  iridis thinfilm fit ellips.csv --stack \"air | n={n=1.5:1.3..1.7} {d=100nm:10nm..400nm} | Si\" --angle 70deg --quantity psi-delta --json")]
    Fit(super::filmfit::FitArgs),
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
        if self.from.is_nan() || self.from <= 0.0 {
            bail!("--from must be a positive wavelength");
        }
        if self.to < self.from {
            bail!("--to ({} nm) must not be below --from ({} nm)", self.to, self.from);
        }
        let g = uniform_grid(self.from, self.to, self.step).map_err(|e| anyhow::anyhow!("{e}"))?;
        if g.len() > 100_000 {
            bail!("{} wavelengths is too many; use a larger --step", g.len());
        }
        Ok(g)
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
    pub rough: super::rough::RoughArgs,
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
    /// stays near 1 % until grazing incidence).
    #[arg(long, value_name = "auto|linear|log", default_value = "auto", value_parser = ["auto", "linear", "log"])]
    pub scale: String,
    #[command(flatten)]
    pub rough: super::rough::RoughArgs,
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
    pub rough: super::rough::RoughArgs,
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
    pub rough: super::rough::RoughArgs,
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
    /// Minimum time per Rust measurement, in seconds.
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
    pub rough: super::rough::RoughArgs,
}

pub fn run(command: ThinfilmCommand) -> Result<()> {
    match command {
        ThinfilmCommand::Spectrum(a) => spectrum(a),
        ThinfilmCommand::Table(a) => table(a),
        ThinfilmCommand::Color(a) => color(a),
        ThinfilmCommand::Chart(a) => chart(a),
        ThinfilmCommand::Materials(a) => materials(a),
        ThinfilmCommand::Bench(a) => bench(a),
        ThinfilmCommand::Profile(a) => super::filmfit::profile(a),
        ThinfilmCommand::Fit(a) => super::filmfit::fit_cmd(a),
    }
}

fn parse_stack(s: &str) -> Result<Stack> {
    Stack::parse(s).map_err(|e| anyhow::anyhow!("{e}"))
}

fn parse_pol(s: &str) -> Result<Polarization> {
    s.parse::<Polarization>().map_err(|e| anyhow::anyhow!("--polarization: {e}"))
}

/// Spectra of a stack on a grid: one `Rta` per wavelength.
fn spectra(stack: &Stack, angle: f64, grid: &[f64]) -> Result<Vec<Rta>> {
    Ok(evaluate_grid(stack, &[angle], grid, GridPath::Auto, false)?)
}

fn pick(pol: Polarization, x: &Rta) -> (f64, f64, f64) {
    match pol {
        Polarization::Average => (x.r(), x.t(), clean(x.a())),
        Polarization::S => (x.r_s, x.t_s, clean(x.a_s())),
        Polarization::P => (x.r_p, x.t_p, clean(x.a_p())),
    }
}

/// Ellipsometric (ψ, Δ) in degrees per wavelength; `None` for a stack with inc: layers (no amplitudes).
fn psi_delta(stack: &Stack, angle: f64, grid: &[f64]) -> Result<Vec<(f64, Option<f64>)>> {
    let v = grid
        .iter()
        .map(|&w| {
            if stack.has_incoherent() {
                // Δ is undefined through an incoherent layer; ψ from the intensity ratio (field.rs).
                stack.psi(w, angle).map(|p| (p.to_degrees(), None))
            } else {
                stack.ellipsometry(w, angle).map(|(p, d)| (p.to_degrees(), Some(d.to_degrees())))
            }
        })
        .collect::<std::result::Result<Vec<_>, _>>()?;
    Ok(v)
}

fn ellips_cells(e: &[(f64, Option<f64>)], i: usize) -> (String, String) {
    (e[i].0.to_string(), e[i].1.map(|d| d.to_string()).unwrap_or_default())
}

/// Says on stderr when the grid cannot resolve the fringes of a thick layer (`iridis_thinfilm::sampling`).
fn warn_sampling(stack: &Stack, angle: f64, grid: &[f64]) {
    if let Some(w) = iridis_thinfilm::sampling::check(stack, angle, grid) {
        eprintln!("warning: {}", w.message);
    }
}

/// `1 − R − T` of a lossless stack is rounding noise (~1e-16); print it as 0.
fn clean(a: f64) -> f64 {
    if a.abs() < 1e-14 {
        0.0
    } else {
        a
    }
}

fn spectrum(a: SpectrumArgs) -> Result<()> {
    crate::output::declare_opt("--plot", a.plot.as_deref(), &["png"])?;
    crate::output::declare_opt("--spectra", a.spectra.as_deref(), &["csv"])?;
    let stack = parse_stack(&a.stack)?;
    let pol = parse_pol(&a.polarization)?;
    if a.rough.is_set() && a.spectra.is_some() {
        bail!("--spectra writes a smooth film's R and T; with --roughness use --csv");
    }
    if a.rough.is_set() {
        if pol != Polarization::Average {
            bail!("with --roughness the spectrum is unpolarised, with s and p columns in --csv/--json");
        }
        let grid = a.grid.grid()?;
        return super::rough::spectrum(
            stack,
            &stack_title(&a.stack),
            &a.rough,
            a.angle,
            &grid,
            a.json,
            a.csv,
            a.plot.as_deref(),
        );
    }
    let grid = a.grid.grid()?;
    warn_sampling(&stack, a.angle, &grid);
    let xs = spectra(&stack, a.angle, &grid)?;
    let ellips = psi_delta(&stack, a.angle, &grid)?;
    let col = |f: &dyn Fn(&Rta) -> f64| xs.iter().map(f).collect::<Vec<f64>>();
    let (r, t, ab) = (col(&|x| pick(pol, x).0), col(&|x| pick(pol, x).1), col(&|x| pick(pol, x).2));
    if let Some(p) = &a.spectra {
        let table =
            iridis_vision::SpectraTable::new(grid.clone(), vec![("R".into(), r.clone()), ("T".into(), t.clone())])?;
        crate::output::write_bytes(p, table.to_csv().as_bytes())?;
        if !a.json && !a.csv {
            eprintln!("wrote {} (pavo's layout: wl, R, T)", p.display());
        }
    }
    if let Some(p) = &a.plot {
        let title = format!("{}  at {}°{}", stack_title(&a.stack), fmt_deg(a.angle), pol_label(pol));
        let mut plot = LinePlot::new(title, "wavelength (nm)", "fraction of incident power")
            .series(Series::new("R (reflectance)", &grid, &r))
            .series(Series::new("T (transmittance)", &grid, &t))
            .series(Series::new("A (absorptance)", &grid, &ab));
        plot.x_range = Some((grid[0], grid[grid.len() - 1].max(grid[0] + 1.0)));
        let img = plot.render()?;
        write_png(p, &img)?;
        if !a.json && !a.csv {
            crate::outln!("wrote {}", p.display())?;
        }
    }
    if a.json {
        return crate::output::print_json(&json!({
            "wavelength_nm": grid,
            "R": r, "T": t, "A": ab,
            "Rs": col(&|x| x.r_s), "Rp": col(&|x| x.r_p), "Ts": col(&|x| x.t_s), "Tp": col(&|x| x.t_p),
            "psi_deg": ellips.iter().map(|p| p.0).collect::<Vec<_>>(),
            "delta_deg": (!stack.has_incoherent()).then(|| ellips.iter().map(|p| p.1).collect::<Vec<_>>()),
        }));
    }
    let mut out = String::new();
    if a.csv {
        out.push_str("wavelength_nm,R,T,A,Rs,Rp,Ts,Tp,psi_deg,delta_deg\n");
        for (i, x) in xs.iter().enumerate() {
            let (psi, delta) = ellips_cells(&ellips, i);
            let _ = writeln!(
                out,
                "{},{},{},{},{},{},{},{},{psi},{delta}",
                grid[i], r[i], t[i], ab[i], x.r_s, x.r_p, x.t_s, x.t_p
            );
        }
    } else {
        let _ = writeln!(out, "stack  {stack}\nangle  {}°{}", fmt_deg(a.angle), pol_label(pol));
        let _ = writeln!(out, "{:>10}  {:>10}  {:>10}  {:>10}", "λ (nm)", "R", "T", "A");
        for i in 0..grid.len() {
            let _ = writeln!(out, "{:>10.2}  {:>10.7}  {:>10.7}  {:>10.7}", grid[i], r[i], t[i], ab[i]);
        }
    }
    crate::output::write_stdout_bytes(out.as_bytes())?;
    Ok(())
}

fn table(a: TableArgs) -> Result<()> {
    crate::output::declare_opt("-o", a.output.as_deref(), &["csv"])?;
    crate::output::declare_opt("--plot", a.plot.as_deref(), &["png"])?;
    let stack = parse_stack(&a.stack)?;
    if a.rough.is_set() {
        if a.scale != "auto" {
            bail!("--scale sets the colour scale of a smooth film's R map; the rough-film table draws its own");
        }
        let grid = a.grid.grid()?;
        return super::rough::table(
            stack,
            &stack_title(&a.stack),
            &a.rough,
            &a.angles,
            &grid,
            a.output.as_deref(),
            a.plot.as_deref(),
        );
    }
    let angles = parse_range(&a.angles, parse_angle_rad).map_err(|e| anyhow::anyhow!("--angles: {e}"))?;
    if let Some(bad) = angles.iter().find(|t| !(**t >= 0.0 && **t <= std::f64::consts::FRAC_PI_2 + 1e-12)) {
        bail!("--angles: {}° is outside 0°–90°", fmt_deg(*bad));
    }
    let grid = a.grid.grid()?;
    if angles.len() * grid.len() > 20_000_000 {
        bail!("{} × {} samples is too many for a table", angles.len(), grid.len());
    }
    if let Some(th) = angles.first() {
        warn_sampling(&stack, *th, &grid);
    }
    let xs = evaluate_grid(&stack, &angles, &grid, GridPath::Auto, true)?;
    let mut csv = String::with_capacity(xs.len() * 100);
    csv.push_str("angle_deg,wavelength_nm,R,T,A,Rs,Rp,Ts,Tp,psi_deg,delta_deg\n");
    for (i, th) in angles.iter().enumerate() {
        let ellips = psi_delta(&stack, *th, &grid)?;
        for (j, w) in grid.iter().enumerate() {
            let x = &xs[i * grid.len() + j];
            let (psi, delta) = ellips_cells(&ellips, j);
            let _ = writeln!(
                csv,
                "{},{},{},{},{},{},{},{},{},{psi},{delta}",
                round_deg(*th),
                w,
                x.r(),
                x.t(),
                clean(x.a()),
                x.r_s,
                x.r_p,
                x.t_s,
                x.t_p
            );
        }
    }
    if let Some(p) = &a.plot {
        let (w, h) = (grid.len() as u32, angles.len() as u32);
        let rmax = xs.iter().map(|x| x.r()).fold(0.0, f64::max).max(1e-12);
        let log = match a.scale.as_str() {
            "log" => true,
            "linear" => false,
            _ => {
                let mut r: Vec<f64> = xs.iter().map(|x| x.r()).collect();
                r.sort_by(f64::total_cmp);
                r[r.len() / 2] < 0.1 * rmax
            }
        };
        // Log: three decades below the largest R, so a 1 % reflectance on a map that reaches 90 % is visible.
        let (lo, hi) = if log { (rmax.log10() - 3.0, rmax.log10()) } else { (0.0, rmax) };
        let level = |r: f64| if log { (r.max(1e-300).log10() - lo) / (hi - lo) } else { r / rmax };
        if log && a.scale == "auto" {
            eprintln!("--plot: log colour scale (most of R is below a tenth of its largest value; --scale linear for a linear one)");
        }
        let mut px = RgbImage::new(w, h);
        for i in 0..angles.len() {
            for j in 0..grid.len() {
                // Row 0 of the picture is the top = the largest angle.
                px.put(
                    j as u32,
                    (angles.len() - 1 - i) as u32,
                    magma(level(xs[i * grid.len() + j].r()).clamp(0.0, 1.0)),
                );
            }
        }
        let img = ImagePlot {
            title: format!("Reflectance R (unpolarised): {}", stack_title(&a.stack)),
            x_label: "wavelength (nm)".into(),
            y_label: "angle of incidence (°)".into(),
            x_range: (grid[0], grid[grid.len() - 1].max(grid[0] + 1e-9)),
            y_range: (angles[0].to_degrees(), angles[angles.len() - 1].to_degrees().max(angles[0].to_degrees() + 1e-9)),
            pixels: &px,
            overlays: Vec::new(),
            colorbar: Some(ColorBar {
                label: if log { "log₁₀ R".into() } else { "R".into() },
                min: lo,
                max: hi,
                map: magma,
            }),
            size: (1000, 640),
        }
        .render()?;
        write_png(p, &img)?;
        eprintln!("wrote {}", p.display());
    }
    match &a.output {
        Some(p) => {
            crate::output::write_bytes(p, csv.as_bytes())?;
            eprintln!("wrote {} ({} angles × {} wavelengths)", p.display(), angles.len(), grid.len());
        }
        None => crate::output::write_stdout_bytes(csv.as_bytes())?,
    }
    Ok(())
}

fn color(a: ColorArgs) -> Result<()> {
    let stack = parse_stack(&a.stack)?;
    let illuminant: Illuminant = a.illuminant.parse()?;
    let observer: Observer = a.observer.parse()?;
    let pol = parse_pol(&a.polarization)?;
    let grid = a.grid.grid()?;
    if a.rough.is_set() {
        if pol != Polarization::Average {
            bail!("with --roughness the colours are for unpolarised light");
        }
        if a.visual.is_some() {
            bail!("--visual takes a smooth film's spectra; leave out --roughness");
        }
        return super::rough::color(stack, &a.rough, a.angle, &grid, illuminant, observer, a.json);
    }
    warn_sampling(&stack, a.angle, &grid);
    let meter = FilmColorimeter::new(&grid, illuminant, observer);
    let c = meter.color(&stack, a.angle, pol)?;
    let white = iridis_color::integrate::white_point(illuminant, observer);
    let refl = super::color::colour_report(c.reflected, white);
    let trans = super::color::colour_report(c.transmitted, white);
    // How an animal sees the reflected and transmitted light (iridis-vision), only when asked.
    let vision = match &a.visual {
        Some(v) => {
            let xs = spectra(&stack, a.angle, &grid)?;
            let (r, t) = (xs.iter().map(|x| pick(pol, x).0).collect(), xs.iter().map(|x| pick(pol, x).1).collect());
            let spec = iridis_vision::Spec {
                visual: Some(v.clone()),
                illuminant: Some(a.illuminant.clone()),
                ..Default::default()
            };
            let system = spec.system().context("--visual")?;
            let samples = [("reflected".to_string(), r), ("transmitted".to_string(), t)];
            Some(iridis_vision::analyse(&samples, &grid, &system, &spec.options(&system)?)?)
        }
        None => None,
    };
    if a.json {
        // One shape for smooth and rough films (see rough::color): a smooth film reflects specularly only.
        let none = super::color::colour_report(Xyz { x: 0.0, y: 0.0, z: 0.0 }, white);
        let mut v = film_colours_json(&refl, &trans, &refl, &none, json!(null));
        if let (Some(vision), Some(obj)) = (&vision, v.as_object_mut()) {
            obj.insert("vision".into(), serde_json::to_value(vision)?);
        }
        return crate::output::print_json(&v);
    }
    let f = |v: &serde_json::Value| -> String {
        v.as_array()
            .map(|v| v.iter().map(|x| format!("{:.5}", x.as_f64().unwrap_or(f64::NAN))).collect::<Vec<_>>().join("  "))
            .unwrap_or_default()
    };
    crate::outln!("stack        {stack}")?;
    crate::outln!(
        "conditions   {}° incidence{}, illuminant {illuminant}, CIE {observer} observer, {}–{} nm",
        fmt_deg(a.angle),
        pol_label(pol),
        grid[0],
        grid[grid.len() - 1]
    )?;
    for (name, r) in [("reflected", &refl), ("transmitted", &trans)] {
        crate::outln!("{name}")?;
        crate::outln!("  XYZ        {}", f(&r["XYZ"]))?;
        crate::outln!("  L*a*b*     {}", f(&r["Lab"]))?;
        crate::outln!("  sRGB       {}   {}", f(&r["srgb"]), r["hex"].as_str().unwrap_or(""))?;
    }
    if let Some(v) = &vision {
        crate::outln!(
            "seen by      {} ({}; relative catches {})",
            v.visual.name,
            v.illuminant,
            v.receptors.join(", ")
        )?;
        for s in &v.samples {
            let rel: Vec<String> = s.relative_catches.iter().map(|x| format!("{x:.4}")).collect();
            crate::outln!("  {:<11}  {}", s.name, rel.join("  "))?;
        }
        if let Some(d) = v.distances.first() {
            let jnd = |x: Option<f64>| x.map_or("—".to_string(), |x| format!("{x:.2} JND"));
            crate::outln!("  reflected vs transmitted: ΔS {}, ΔL {}", jnd(d.delta_s), jnd(d.delta_l))?;
        }
        for n in &v.notes {
            eprintln!("note: {n}");
        }
    }
    Ok(())
}

/// The JSON of `thinfilm color`, the same keys for smooth and rough films: `reflected` and `transmitted` of
/// the stack with a smooth last interface, `specular` and `diffuse` (π·k_d) parts of the reflection (for a
/// smooth film the reflection is all specular and the diffuse part black), `rough` the LSRS conditions or null.
pub(crate) fn film_colours_json(
    reflected: &serde_json::Value,
    transmitted: &serde_json::Value,
    specular: &serde_json::Value,
    diffuse: &serde_json::Value,
    rough: serde_json::Value,
) -> serde_json::Value {
    json!({
        "reflected": reflected, "transmitted": transmitted, "specular": specular, "diffuse": diffuse, "rough": rough,
    })
}

/// Colours of a thickness sweep: (reflected, transmitted) XYZ per thickness.
fn sweep(
    stack: &Stack,
    layer: usize,
    thicknesses: &[f64],
    angle: f64,
    meter: &FilmColorimeter,
) -> Result<Vec<(Xyz, Xyz)>> {
    thicknesses
        .iter()
        .map(|&d| {
            let c = meter.color(&stack.with_thickness(layer, d), angle, Polarization::Average)?;
            Ok((c.reflected, c.transmitted))
        })
        .collect()
}

fn chart(a: ChartArgs) -> Result<()> {
    crate::output::declare("-o", &a.output, &["png"])?;
    crate::output::declare_opt("--csv", a.csv.as_deref(), &["csv"])?;
    let (stack, layer) = Stack::parse_sweep(&a.stack)?;
    let ds = parse_range(&a.thickness, parse_length_nm).map_err(|e| anyhow::anyhow!("--thickness: {e}"))?;
    if ds[0] < 0.0 {
        bail!("--thickness: thicknesses must not be negative (got {} nm)", ds[0]);
    }
    if ds.len() > 20_000 {
        bail!("--thickness gives {} thicknesses; at most 20000", ds.len());
    }
    let illuminant: Illuminant = a.illuminant.parse()?;
    let grid = a.grid.grid()?;
    let cols = if a.rough.is_set() {
        super::rough::chart_colours(&stack, layer, &ds, &a.rough, a.angle, &grid, illuminant, Observer::Cie1931)?
    } else {
        sweep(&stack, layer, &ds, a.angle, &FilmColorimeter::new(&grid, illuminant, Observer::Cie1931))?
    };
    let (top, bottom, prefix) = if a.rough.is_set() {
        ("specular k_r", "diffuse π·k_d", ["S", "D"])
    } else {
        ("reflected", "transmitted", ["R", "T"])
    };
    let exposure = match a.exposure {
        Some(e) if e.is_finite() && e > 0.0 => e,
        Some(e) => bail!("--exposure {e} must be a positive number (RU)"),
        None => {
            let ymax = cols.iter().map(|c| c.0.y).fold(0.0, f64::max);
            if ymax > 0.0 {
                1.0 / ymax
            } else {
                1.0
            }
        }
    };
    let tone = ToneMap { exposure_ru: exposure, ..ToneMap::default() };
    let trans_tone = ToneMap::default();
    let title = match (a.rough.roughness, a.rough.correlation) {
        (Some(sigma), Some(tau)) => format!("{}, rough σ {sigma} nm, τ {tau} nm", stack_title(&a.stack)),
        _ => stack_title(&a.stack),
    };
    let bands = ChartBands { title: &title, top, bottom };
    let img = chart_image(&bands, &ds, &cols, &tone, &trans_tone, a.angle, illuminant, exposure)?;
    write_png(&a.output, &img)?;
    crate::outln!(
        "wrote {} ({} thicknesses, {}–{} nm; {top} at exposure {exposure:.3} RU, {bottom} at 1 RU)",
        a.output.display(),
        ds.len(),
        ds[0],
        ds[ds.len() - 1]
    )?;
    if let Some(p) = &a.csv {
        let [t, b] = prefix;
        let mut csv = format!("thickness_nm,{t}_X,{t}_Y,{t}_Z,{t}_hex,{b}_X,{b}_Y,{b}_Z,{b}_hex\n");
        for (d, (r, t)) in ds.iter().zip(&cols) {
            let _ = writeln!(
                csv,
                "{d},{},{},{},{},{},{},{},{}",
                r.x,
                r.y,
                r.z,
                iridis_color::tonemap::hex(tone.to_rgb8(*r)),
                t.x,
                t.y,
                t.z,
                iridis_color::tonemap::hex(trans_tone.to_rgb8(*t))
            );
        }
        crate::output::write_bytes(p, csv.as_bytes())?;
        crate::outln!("wrote {}", p.display())?;
    }
    Ok(())
}

#[allow(clippy::too_many_arguments)]
/// What a chart's two bands show, and its title's stack part.
struct ChartBands<'a> {
    title: &'a str,
    top: &'a str,
    bottom: &'a str,
}

fn chart_image(
    bands: &ChartBands,
    ds: &[f64],
    cols: &[(Xyz, Xyz)],
    tone: &ToneMap,
    trans_tone: &ToneMap,
    angle: f64,
    illuminant: Illuminant,
    exposure: f64,
) -> Result<RgbImage> {
    let w = ds.len().max(2) as u32;
    let h = 100u32;
    let mut px = RgbImage::new(w, h);
    for x in 0..w {
        let k = (x as usize).min(cols.len() - 1);
        let (r, t) = (tone.to_rgb8(cols[k].0), trans_tone.to_rgb8(cols[k].1));
        for y in 0..h {
            // Top half: reflected or specular (y from 1 down to 0.5), bottom half: transmitted or diffuse;
            // a thin white gap.
            let c = if y < h / 2 - 1 {
                r
            } else if y > h / 2 {
                t
            } else {
                [255, 255, 255]
            };
            px.put(x, y, c);
        }
    }
    let x_range = (ds[0], ds[ds.len() - 1].max(ds[0] + 1e-9));
    let img = ImagePlot {
        title: format!(
            "Film colours: {}  ({}°, {}, {} ×{:.2} RU)",
            bands.title,
            fmt_deg(angle),
            illuminant,
            bands.top,
            exposure
        ),
        x_label: "thickness of the {d} layer (nm)".into(),
        y_label: format!("{} | {}", bands.bottom, bands.top),
        x_range,
        y_range: (0.0, 1.0),
        pixels: &px,
        overlays: Vec::new(),
        colorbar: None,
        size: (1200, 360),
    }
    .render_without_y_ticks()?;
    Ok(img)
}

fn materials(a: MaterialsArgs) -> Result<()> {
    let mut rows = Vec::new();
    for (names, desc) in Material::library() {
        let m = Material::builtin(names[0]).context("built-in material failed to load")?;
        let (lo, hi) = m.range_nm();
        let at = a.at.map(|w| m.index_at(w).map(|n| (n.re, n.im)).map_err(|e| e.to_string()));
        rows.push((names, desc, lo, hi, at));
    }
    if a.json {
        let v: Vec<serde_json::Value> = rows
            .iter()
            .map(|(names, desc, lo, hi, at)| {
                let mut o = json!({
                    "names": names, "description": desc,
                    "range_nm": [lo, if hi.is_finite() { json!(hi) } else { json!(null) }],
                });
                if let Some(at) = at {
                    o["index"] = match at {
                        Ok((n, k)) => json!([n, k]),
                        Err(e) => json!(e),
                    };
                }
                o
            })
            .collect();
        return crate::output::print_json(&json!({ "materials": v }));
    }
    for (names, desc, _, _, at) in rows {
        let idx = match at {
            Some(Ok((n, k))) => format!("   n̂({} nm) = {n:.5} + {k:.5}i", a.at.unwrap_or(0.0)),
            Some(Err(_)) => format!("   (no data at {} nm)", a.at.unwrap_or(0.0)),
            None => String::new(),
        };
        crate::outln!("{:<36} {desc}{idx}", names.join(", "))?;
    }
    crate::outln!(
        "\nAlso: n=1.38, n=0.2+3.4i (constants) and file:PATH (refractiveindex.info YAML or CSV wavelength_nm,n,k)."
    )?;
    Ok(())
}

// ----------------------------------------------------------------------------------------------------------
// Benchmark

const BENCH_2: &str = "air | gasoline 216nm | water 220nm | asphalt";

fn bench_20() -> String {
    // A 10-pair quarter-wave mirror for 550 nm: TiO2-like n = 2.35 and MgF2-like n = 1.38 on glass.
    let mut s = String::from("air");
    for _ in 0..10 {
        s += &format!(" | n=2.35 {}nm | n=1.38 {}nm", 550.0 / (4.0 * 2.35), 550.0 / (4.0 * 1.38));
    }
    s + " | n=1.5"
}

/// The Python side: the same stack and grid through tmm.coh_tmm (s and p per evaluation).
const TMM_SCRIPT: &str = r#"
import json, sys, time, math
try:
    import numpy as np, tmm
except Exception as e:
    print(json.dumps({"error": "python3 has no tmm/numpy: %s" % e})); sys.exit(0)
spec = json.loads(sys.argv[1])
ns = [complex(a, b) for a, b in spec["n"]]
ds = [float("inf")] + spec["d"] + [float("inf")]
lams = spec["wavelengths"]; ths = spec["angles"]
count = 0; t0 = time.perf_counter(); acc = 0.0
while True:
    for th in ths:
        for lam in lams:
            s = tmm.coh_tmm("s", ns, ds, th, lam); p = tmm.coh_tmm("p", ns, ds, th, lam)
            acc += s["R"] + p["R"] + s["T"] + p["T"]; count += 1
    if time.perf_counter() - t0 > spec["seconds"]:
        break
dt = time.perf_counter() - t0
print(json.dumps({"evals": count, "seconds": dt, "per_second": count / dt, "check": acc,
                  "tmm": __import__("importlib.metadata").metadata.version("tmm"), "python": sys.version.split()[0]}))
"#;

fn time_rust(stack: &Stack, angles: &[f64], wl: &[f64], path: GridPath, threads: bool, seconds: f64) -> Result<f64> {
    let mut n = 0usize;
    let t0 = Instant::now();
    let mut sink = 0.0;
    loop {
        let xs = evaluate_grid(stack, angles, wl, path, threads)?;
        sink += xs.iter().map(|x| x.r() + x.t()).sum::<f64>();
        n += xs.len();
        if t0.elapsed().as_secs_f64() >= seconds {
            break;
        }
    }
    std::hint::black_box(sink);
    Ok(n as f64 / t0.elapsed().as_secs_f64())
}

fn time_tmm(stack: &Stack, angles: &[f64], wl: &[f64], seconds: f64) -> std::result::Result<serde_json::Value, String> {
    let n: Vec<[f64; 2]> = stack
        .materials()
        .map(|m| m.index_at(550.0).map(|z| [z.re, z.im]).map_err(|e| e.to_string()))
        .collect::<std::result::Result<_, _>>()?;
    let spec = json!({ "n": n, "d": stack.thicknesses(), "wavelengths": wl, "angles": angles, "seconds": seconds });
    let out = std::process::Command::new("python3")
        .arg("-c")
        .arg(TMM_SCRIPT)
        .arg(spec.to_string())
        .output()
        .map_err(|e| format!("python3 not found ({e}); tmm not timed"))?;
    let text = String::from_utf8_lossy(&out.stdout);
    let v: serde_json::Value = serde_json::from_str(text.trim())
        .map_err(|_| format!("python3 failed: {}", String::from_utf8_lossy(&out.stderr).trim()))?;
    if let Some(e) = v.get("error") {
        return Err(e.as_str().unwrap_or("tmm failed").to_string());
    }
    Ok(v)
}

fn bench(a: BenchArgs) -> Result<()> {
    if !(a.seconds.is_finite() && a.seconds > 0.0) {
        bail!("--seconds must be positive");
    }
    if a.rough.is_set() {
        return super::rough::bench(parse_stack(super::rough::LISTING_3_6_STACK)?, &a.rough, 80, a.seconds, a.json);
    }
    let threads = iridis_thinfilm::grid::threads();
    let wl: Vec<f64> = (0..81).map(|i| 380.0 + 5.0 * i as f64).collect();
    let angles: Vec<f64> = (0..90).map(|d| f64::to_radians(d as f64)).collect();
    // tmm is slow: give it a sub-grid (the per-evaluation cost does not depend on the grid).
    let wl_py: Vec<f64> = wl.iter().step_by(8).copied().collect();
    let angles_py: Vec<f64> = angles.iter().step_by(9).copied().collect();
    let mut results = Vec::new();
    for (label, text) in
        [("2 layers (oil slick)", BENCH_2.to_string()), ("20 layers (quarter-wave mirror)", bench_20())]
    {
        let stack = parse_stack(&text)?;
        let g1 = time_rust(&stack, &angles, &wl, GridPath::General, false, a.seconds)?;
        let gn = time_rust(&stack, &angles, &wl, GridPath::General, true, a.seconds)?;
        let f1 = time_rust(&stack, &angles, &wl, GridPath::Auto, false, a.seconds)?;
        let fnn = time_rust(&stack, &angles, &wl, GridPath::Auto, true, a.seconds)?;
        let py = if a.no_python {
            Err("not run (--no-python)".to_string())
        } else {
            time_tmm(&stack, &angles_py, &wl_py, a.seconds.max(1.0))
        };
        results.push(json!({
            "stack": label,
            "layers": stack.layers.len(),
            "rust_general_1_thread": g1,
            "rust_general_all_threads": gn,
            "rust_fast_1_thread": f1,
            "rust_fast_all_threads": fnn,
            "tmm_1_thread": py.as_ref().ok().and_then(|v| v["per_second"].as_f64()),
            "tmm_note": match &py { Ok(v) => format!("tmm {} on Python {}", v["tmm"].as_str().unwrap_or("?"), v["python"].as_str().unwrap_or("?")), Err(e) => e.clone() },
            "speedup_general_1_thread": py.as_ref().ok().and_then(|v| v["per_second"].as_f64()).map(|t| g1 / t),
            "speedup_fast_1_thread": py.as_ref().ok().and_then(|v| v["per_second"].as_f64()).map(|t| f1 / t),
        }));
    }
    let fit = bench_fit(a.seconds)?;
    let batch = bench_batch()?;
    if a.json {
        return crate::output::print_json(&json!({
            "threads": threads, "unit": "(λ, θ) evaluations per second, R and T for s and p", "results": results,
            "fit": fit, "batch": batch,
        }));
    }
    crate::outln!("(λ, θ) evaluations per second (R and T, s and p); all threads = {threads}")?;
    crate::outln!(
        "{:<34} {:>14} {:>14} {:>14} {:>14} {:>12} {:>9}",
        "stack",
        "general 1 thr",
        "general all",
        "fast 1 thr",
        "fast all",
        "tmm (Python)",
        "× tmm"
    )?;
    for r in &results {
        let tm = r["tmm_1_thread"].as_f64();
        crate::outln!(
            "{:<34} {:>14.0} {:>14.0} {:>14.0} {:>14.0} {:>12} {:>9}",
            r["stack"].as_str().unwrap_or(""),
            r["rust_general_1_thread"].as_f64().unwrap_or(0.0),
            r["rust_general_all_threads"].as_f64().unwrap_or(0.0),
            r["rust_fast_1_thread"].as_f64().unwrap_or(0.0),
            r["rust_fast_all_threads"].as_f64().unwrap_or(0.0),
            tm.map(|v| format!("{v:.0}")).unwrap_or_else(|| "—".into()),
            r["speedup_general_1_thread"].as_f64().map(|v| format!("{v:.0}")).unwrap_or_else(|| "—".into()),
        )?;
    }
    if let Some(note) = results.first().and_then(|r| r["tmm_note"].as_str()) {
        crate::outln!("tmm: {note}")?;
    }
    crate::outln!("× tmm compares the general path on one thread with tmm on one thread.")?;
    crate::outln!(
        "fit, 3 parameters on 401 wavelengths (tools/fit_scipy_compare.py's data): {:.2} ms from one start, \
         {:.2} ms with the multi-start search ({} starts), exact derivatives; with finite differences {:.2} ms \
         and {:.2} ms; scipy least_squares + tmm: see docs/thinfilm.md",
        1e3 * fit["single_start_seconds"].as_f64().unwrap_or(f64::NAN),
        1e3 * fit["multi_start_seconds"].as_f64().unwrap_or(f64::NAN),
        fit["multi_start_starts"],
        1e3 * fit["single_start_fd_seconds"].as_f64().unwrap_or(f64::NAN),
        1e3 * fit["multi_start_fd_seconds"].as_f64().unwrap_or(f64::NAN),
    )?;
    crate::outln!(
        "batch of 10⁶ (λ, θ) points, 20 layers, all threads: fast path {:.3} s, general path {:.3} s",
        batch["fast_seconds"].as_f64().unwrap_or(f64::NAN),
        batch["general_seconds"].as_f64().unwrap_or(f64::NAN)
    )?;
    Ok(())
}

/// The fit of tools/fit_scipy_compare.py (the same CSV), timed from one start and with the search.
fn bench_fit(seconds: f64) -> Result<serde_json::Value> {
    use iridis_filmfit::{fit, Derivatives, FitOptions, Measured, Quantity, Template};
    const CSV: &str = include_str!("../../../filmfit/tests/fixtures/scipy_fit.csv");
    const STACK: &str = "air | cauchy:{A=1.5:1.3..1.7},{B=0.004:0..0.02} {d=330nm:100nm..600nm} | n=3.88+0.02i";
    let t = Template::parse(STACK)?;
    let mut data = Measured::from_csv(CSV, "scipy_fit.csv", Quantity::R, None)?;
    data.sigma = Some(vec![0.002; data.values.len()]);
    let mut out = json!({ "stack": STACK, "wavelengths": data.values.len(), "parameters": 3 });
    // Exact derivatives (the default) and the finite-difference fallback, for comparison.
    let runs = [
        ("single_start", 1, Derivatives::Exact),
        ("multi_start", 0, Derivatives::Exact),
        ("single_start_fd", 1, Derivatives::FiniteDifferences),
        ("multi_start_fd", 0, Derivatives::FiniteDifferences),
    ];
    for (key, grid, derivatives) in runs {
        let opt = FitOptions { grid, derivatives, ..FitOptions::default() };
        let (mut n, t0) = (0usize, Instant::now());
        let mut last = None;
        while n == 0 || t0.elapsed().as_secs_f64() < seconds {
            last = Some(fit(&t, &data, &opt)?);
            n += 1;
        }
        let r = last.expect("ran at least once");
        out[format!("{key}_seconds")] = json!(t0.elapsed().as_secs_f64() / n as f64);
        out[format!("{key}_starts")] = json!(r.starts_tried);
        out[format!("{key}_values")] = json!(r.values);
        out[format!("{key}_evaluations")] = json!(r.evaluations);
    }
    Ok(out)
}

/// 10⁶ (λ, θ) evaluations of the 20-layer stack: 1000 angles × 1000 wavelengths, all threads.
fn bench_batch() -> Result<serde_json::Value> {
    let stack = parse_stack(&bench_20())?;
    let angles: Vec<f64> = (0..1000).map(|i| f64::to_radians(89.0 * i as f64 / 999.0)).collect();
    let wl: Vec<f64> = (0..1000).map(|i| 380.0 + 0.4 * i as f64).collect();
    let mut out = json!({ "points": angles.len() * wl.len(), "layers": stack.layers.len(), "threads": iridis_thinfilm::grid::threads() });
    for (key, path) in [("fast_seconds", GridPath::Auto), ("general_seconds", GridPath::General)] {
        let t0 = Instant::now();
        let xs = evaluate_grid(&stack, &angles, &wl, path, true)?;
        std::hint::black_box(xs.iter().map(|x| x.r()).sum::<f64>());
        out[key] = json!(t0.elapsed().as_secs_f64());
    }
    Ok(out)
}

// ----------------------------------------------------------------------------------------------------------
// Helpers

fn write_png(path: &Path, img: &RgbImage) -> Result<()> {
    crate::output::write_png_rgb8(path, img.width, img.height, &img.data)
}

fn fmt_deg(rad: f64) -> String {
    let d = rad.to_degrees();
    let r = (d * 1e6).round() / 1e6;
    format!("{r}")
}

fn round_deg(rad: f64) -> f64 {
    (rad.to_degrees() * 1e9).round() / 1e9
}

fn pol_label(p: Polarization) -> &'static str {
    match p {
        Polarization::Average => ", unpolarised",
        Polarization::S => ", s-polarised",
        Polarization::P => ", p-polarised",
    }
}

pub(crate) fn stack_title(s: &str) -> String {
    s.split('|').map(str::trim).collect::<Vec<_>>().join(" | ")
}

/// The exposure that brings the largest linear sRGB channel of a colour to 1 (shows its hue).
fn hue_exposure(xyz: Xyz) -> f64 {
    let m = xyz.to_linear_srgb().into_iter().fold(0.0, f64::max);
    if m > 0.0 {
        1.0 / m
    } else {
        1.0
    }
}

/// The demo's thin-film section: the soap-film chart, the oil-slick and coated-glass spectra and colours.
pub fn demo(g: &mut iridis_api::gallery::Gallery) -> Result<()> {
    g.section(
        "Thin-film interference",
        "Soap films, oil slicks and lens coatings colour light by interference between the reflections at their \
         interfaces. iridis-thinfilm evaluates the multilayer recurrence of Hirayama et al. (Sussenbach's thesis, \
         eq. 3.1–3.13; checked against the thesis' Figure 3.8 and the Python tmm package). The chart is the \
         soap-film colour chart of Sussenbach's Figure 5.11 (water n = 1.33 in air, normal incidence, D65).",
    );
    // Soap-film chart.
    let (stack, layer) = Stack::parse_sweep("air | water {d} | air")?;
    let ds: Vec<f64> = (0..=1000).map(|i| 2.0 * i as f64).collect();
    let grid = uniform_grid(380.0, 780.0, 5.0).map_err(|e| anyhow::anyhow!("{e}"))?;
    let meter = FilmColorimeter::new(&grid, Illuminant::D65, Observer::Cie1931);
    let cols = sweep(&stack, layer, &ds, 0.0, &meter)?;
    let ymax = cols.iter().map(|c| c.0.y).fold(0.0, f64::max).max(1e-12);
    let tone = ToneMap { exposure_ru: 1.0 / ymax, ..ToneMap::default() };
    let soap = ChartBands { title: "air | water {d} | air", top: "reflected", bottom: "transmitted" };
    let img = chart_image(&soap, &ds, &cols, &tone, &ToneMap::default(), 0.0, Illuminant::D65, 1.0 / ymax)?;
    write_png(&g.path("thinfilm_soap_chart.png"), &img)?;
    g.image(
        "thinfilm_soap_chart.png",
        "Soap-film colours, 0–2000 nm of water in air at normal incidence (Sussenbach Fig. 5.11): \
         iridis thinfilm chart --stack \"air | water {d} | air\" --thickness 0nm:2000nm:2nm",
    );
    // Spectra.
    let mut rows = Vec::new();
    let white = iridis_color::integrate::white_point(Illuminant::D65, Observer::Cie1931);
    for (file, text, what, angle_deg) in [
        (
            "thinfilm_oil_slick.png",
            "air | gasoline 216nm | water 220nm | asphalt",
            "oil slick (Sussenbach section 5.1)",
            1.0,
        ),
        ("thinfilm_soap_348nm.png", "air | water 348nm | air", "soap film 348 nm (Sussenbach Fig. 5.1)", 1.0),
        ("thinfilm_coated_glass.png", "air | MgF2 100nm | BK7", "MgF2 anti-reflection coating on BK7", 0.0),
        ("thinfilm_si_on_glass.png", "air | Si 108nm | glass", "Si 108 nm on glass (Sussenbach Fig. 5.7)", 1.0),
    ] {
        let stack = parse_stack(text)?;
        let angle = f64::to_radians(angle_deg);
        let wl = uniform_grid(400.0, 780.0, 2.0).map_err(|e| anyhow::anyhow!("{e}"))?;
        let xs = spectra(&stack, angle, &wl)?;
        let r: Vec<f64> = xs.iter().map(|x| x.r()).collect();
        let t: Vec<f64> = xs.iter().map(|x| x.t()).collect();
        let ab: Vec<f64> = xs.iter().map(|x| x.a()).collect();
        let mut plot =
            LinePlot::new(format!("{what}: {text}, {angle_deg}°"), "wavelength (nm)", "fraction of incident power")
                .series(Series::new("R (reflectance)", &wl, &r));
        if text.contains("Si") {
            plot =
                plot.series(Series::new("T (transmittance)", &wl, &t)).series(Series::new("A (absorptance)", &wl, &ab));
        }
        plot.x_range = Some((400.0, 780.0));
        write_png(&g.path(file), &plot.render()?)?;
        g.image(
            file,
            &format!(
                "{what}: iridis thinfilm spectrum --stack \"{text}\" --angle {angle_deg}deg --from 400nm --plot {file}"
            ),
        );
        // Colours need 380–780 nm; Si's data end at 827 nm, everything here covers it.
        let c = FilmColorimeter::new(&grid, Illuminant::D65, Observer::Cie1931).color(
            &stack,
            angle,
            Polarization::Average,
        )?;
        let lab_r = iridis_color::Lab::from_xyz(c.reflected, white);
        rows.push(vec![
            text.to_string(),
            format!("{:.4}", c.reflected.y),
            format!("{:.1}, {:.1}, {:.1}", lab_r.l, lab_r.a, lab_r.b),
            format!("swatch:{}", iridis_color::tonemap::hex(ToneMap::default().to_rgb8(c.reflected))),
            format!(
                "swatch:{}",
                iridis_color::tonemap::hex(
                    ToneMap { exposure_ru: hue_exposure(c.reflected), ..ToneMap::default() }.to_rgb8(c.reflected)
                )
            ),
            format!("swatch:{}", iridis_color::tonemap::hex(ToneMap::default().to_rgb8(c.transmitted))),
        ]);
    }
    g.table(
        &[
            "stack",
            "reflected Y",
            "reflected L*a*b*",
            "reflected sRGB (1 RU)",
            "reflected hue (brightest channel at 1)",
            "transmitted sRGB",
        ],
        &rows,
    );
    Ok(())
}
