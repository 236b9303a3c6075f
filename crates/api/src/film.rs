//! Thin films with smooth interfaces (`iridis thinfilm spectrum|table|color|materials`, Python's `iridis.film`):
//! spectra with the ellipsometric angles, angle × wavelength tables and their map, the reflected and
//! transmitted colour (optionally as an animal sees it), the built-in materials. Each job returns a result
//! that renders itself as the command's text, CSV and JSON, so every front end prints the same.
//! Sussenbach's smooth model (thesis eq. 3.1–3.13), evaluated by `iridis-thinfilm`.

use std::fmt::Write as _;

use anyhow::{anyhow, bail, Context, Result};
use iridis_color::units::{parse_angle_rad, parse_range};
use iridis_color::{Illuminant, Observer, Xyz};
use iridis_plot::{magma, ColorBar, ImagePlot, LinePlot, Series};
use iridis_thinfilm::color::FilmColorimeter;
use iridis_thinfilm::grid::{evaluate_grid, Path as GridPath};
use iridis_thinfilm::{Material, Rta, Stack};
use serde_json::json;

use crate::color::{colour_report, colour_text};
use crate::report::Report;

pub use iridis_plot::RgbImage;
pub use iridis_thinfilm::color::Polarization;

// ----------------------------------------------------------------------------------------------------------
// Parsing and small shared pieces

/// A stack from its text form (`air | water 635nm | air`).
pub fn parse_stack(s: &str) -> Result<Stack> {
    Stack::parse(s).map_err(|e| anyhow!("{e}"))
}

/// `avg`, `s` or `p` (the `--polarization` of spectrum, table and color).
pub fn parse_polarization(s: &str) -> Result<Polarization> {
    s.parse::<Polarization>().map_err(|e| anyhow!("--polarization: {e}"))
}

/// The wavelength grid `from..=to` in steps of `step` (nm), refused when empty, reversed or too large.
pub fn wavelength_grid(from: f64, to: f64, step: f64) -> Result<Vec<f64>> {
    if from.is_nan() || from <= 0.0 {
        bail!("--from must be a positive wavelength");
    }
    if to < from {
        bail!("--to ({to} nm) must not be below --from ({from} nm)");
    }
    // A film takes X-rays (0.154 nm for X-ray reflectivity), so only metres are refused at the short end.
    if from < 1e-4 {
        bail!("--from {from} nm looks like metres (400e-9 m is 400 nm); wavelengths are in nm");
    }
    let g = iridis_color::spectrum::range_grid(from, to, step).map_err(|e| anyhow!("{e}"))?;
    if g.len() > 100_000 {
        bail!("{} wavelengths is too many; use a larger --step", g.len());
    }
    Ok(g)
}

/// How a colour's wavelength grid was given, for the words of [`check_colour_grid`]'s messages.
#[derive(Debug, Clone, Copy)]
pub enum GridGiven {
    /// As a range and a step (`--from`, `--to`, `--step`; Python's `from_nm`, `to_nm`, `step_nm`).
    Range,
    /// As a list of wavelengths, under this name (Python's `grid_nm`).
    List(&'static str),
}

impl GridGiven {
    fn range(self) -> &'static str {
        match self {
            GridGiven::Range => "--from/--to",
            GridGiven::List(name) => name,
        }
    }

    fn finer(self) -> String {
        match self {
            GridGiven::Range => "a finer --step (≤ 10 nm keeps it within 1 %)".into(),
            GridGiven::List(name) => format!("a finer {name} (steps ≤ 10 nm keep it within 1 %)"),
        }
    }
}

/// A colour integrates a spectrum over wavelengths, normalised on its grid so that a perfect reflector is white
/// there (`iridis_color::SpectralWeights`): a band that misses a real part of the visible gives the colour of
/// that band alone, which is said; one holding under 1 % of the eye's response, or sampling it so coarsely that
/// its white is off by more than 20 %, would give a colour of nothing (`--from 300nm --to 380nm` printed a* 485,
/// `--step 400nm` #ff00ff) and is refused. "Real": more than 1 % of the CIE 1931 observer's weight
/// ∫(x̄ + ȳ + z̄) over 360–830 nm, so Sussenbach's 400–700 nm (0.27 %) and vision's 300–700 nm (0.07 %) say
/// nothing.
pub fn check_colour_grid(grid: &[f64], given: GridGiven, report: &dyn Report) -> Result<()> {
    if let [one] = grid {
        bail!(
            "a colour integrates the spectrum over wavelengths, and {} gives only {one} nm; give a range (the default \
             is 380nm to 780nm)",
            given.range()
        );
    }
    let (lo, hi) = (grid[0], grid[grid.len() - 1]);
    let nm = iridis_color::spectrum::short_number;
    let cmfs = Observer::Cie1931.cmfs();
    let response = |l: f64| {
        let [x, y, z] = cmfs.at(l);
        x + y + z
    };
    let weight = |inside: &dyn Fn(f64) -> bool| -> f64 {
        cmfs.wavelengths_nm.iter().filter(|&&l| inside(l)).map(|&l| response(l)).sum()
    };
    // `+ 0.0`: an empty band's sum is −0.0, printed "-0.00 %".
    let covered = weight(&|l| (lo..=hi).contains(&l)) / weight(&|_| true) + 0.0;
    if covered < 0.01 {
        bail!(
            "a colour needs the eye's response, and {}–{} nm ({}) holds {:.2} % of it: its colours would be of \
             nothing; give a range within 360–830 nm (the default is 380nm to 780nm)",
            nm(lo),
            nm(hi),
            given.range(),
            100.0 * covered
        );
    }
    // The grid's trapezoid integral of the response against the same rule on the observer's own 1 nm grid.
    let trapezoid = |g: &[f64]| -> f64 {
        iridis_color::spectrum::trapezoid_weights(g).iter().zip(g).map(|(w, &l)| w * response(l)).sum()
    };
    let fine: Vec<f64> = cmfs.wavelengths_nm.iter().copied().filter(|l| (lo..=hi).contains(l)).collect();
    let off = if fine.len() < 2 { 0.0 } else { (trapezoid(grid) / trapezoid(&fine) - 1.0).abs() };
    if off > 0.2 {
        bail!(
            "a grid of {} wavelengths over {}–{} nm samples the eye's response so coarsely that its white is off by \
             {:.0} %: give {}",
            grid.len(),
            nm(lo),
            nm(hi),
            100.0 * off,
            given.finer()
        );
    }
    if covered < 0.99 {
        report.warn(&format!(
            "the colours integrate over {}–{} nm only ({}): {:.0} % of the eye's response lies outside and is left \
             out, the colours normalised on this band (a perfect reflector is white on it): they are the band's, not \
             the film's in full light",
            nm(lo),
            nm(hi),
            given.range(),
            100.0 * (1.0 - covered),
        ));
    }
    Ok(())
}

/// Writes a plot as PNG, part of the run's outputs ([`crate::output`]).
pub fn write_png(path: &std::path::Path, img: &RgbImage) -> Result<()> {
    crate::output::write_png_rgb8(path, img.width, img.height, &img.data)
}

/// Degrees as printed: rounded to 1e-6, no trailing zeros (`30`, not `30.000000`).
pub fn fmt_deg(rad: f64) -> String {
    format!("{}", (rad.to_degrees() * 1e6).round() / 1e6)
}

/// Degrees rounded to 1e-9 (the angle column of the tables).
pub fn round_deg(rad: f64) -> f64 {
    (rad.to_degrees() * 1e9).round() / 1e9
}

/// `, unpolarised`, `, s-polarised` or `, p-polarised`.
pub fn pol_label(p: Polarization) -> &'static str {
    match p {
        Polarization::Average => ", unpolarised",
        Polarization::S => ", s-polarised",
        Polarization::P => ", p-polarised",
    }
}

/// The stack's text with its separators spaced evenly (titles of plots).
pub fn stack_title(s: &str) -> String {
    s.split('|').map(str::trim).collect::<Vec<_>>().join(" | ")
}

/// `1 − R − T` of a lossless stack is rounding noise (~1e-16); print it as 0.
pub fn clean(a: f64) -> f64 {
    if a.abs() < 1e-14 {
        0.0
    } else {
        a
    }
}

/// (R, T, A) of one polarisation (or their average).
pub fn pick(pol: Polarization, x: &Rta) -> (f64, f64, f64) {
    match pol {
        Polarization::Average => (x.r(), x.t(), clean(x.a())),
        Polarization::S => (x.r_s, x.t_s, clean(x.a_s())),
        Polarization::P => (x.r_p, x.t_p, clean(x.a_p())),
    }
}

/// Spectra of a stack on a grid: one `Rta` per wavelength.
pub fn spectra(stack: &Stack, angle: f64, grid: &[f64]) -> Result<Vec<Rta>> {
    Ok(evaluate_grid(stack, &[angle], grid, GridPath::Auto, false)?)
}

/// Ellipsometric (ψ, Δ) in degrees per wavelength; Δ is `None` for a stack with inc: layers (no amplitudes).
pub fn psi_delta(stack: &Stack, angle: f64, grid: &[f64]) -> Result<Vec<(f64, Option<f64>)>> {
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
    // ψ and Δ are undefined where r_s = 0 (an index-matched stack reflects nothing): empty cells, not NaN.
    let psi = if e[i].0.is_finite() { e[i].0.to_string() } else { String::new() };
    (psi, e[i].1.filter(|d| d.is_finite()).map(|d| d.to_string()).unwrap_or_default())
}

/// Warns when the grid cannot resolve the fringes of a thick layer (`iridis_thinfilm::sampling`), of a constant
/// index (water, glass, …: visible-band figures) used well outside the visible, where the real material's index
/// differs (water at 100 nm absorbs; it was taken as 1.33 in silence), and of a grid ending under 20 nm, X-rays
/// or µm by mistake (Python's `film.spectrum(from_nm=0.4, to_nm=0.7)` answered without a word).
pub fn warn_sampling(stack: &Stack, angle: f64, grid: &[f64], report: &dyn Report) {
    if let Some(w) = iridis_thinfilm::sampling::check(stack, angle, grid) {
        report.warn(&w.message);
    }
    let (lo, hi) = (grid[0], grid[grid.len() - 1]);
    let nm = iridis_color::spectrum::short_number;
    let mut constants: Vec<&str> = stack
        .materials()
        .filter(|m| m.is_constant() && !matches!(m.name(), "air" | "vacuum") && !m.name().starts_with("n="))
        .map(|m| m.name())
        .collect();
    constants.dedup();
    let constant_line = (!constants.is_empty()).then(|| {
        format!(
            "{} {} a constant index (a visible-band figure), used here at {}–{} nm, where the real material's index \
             differs; a dispersive material or file:PATH gives it there",
            constants.join(", "),
            if constants.len() == 1 { "is" } else { "are" },
            nm(lo),
            nm(hi),
        )
    });
    // A warning, not a note: the numbers are then not the material's (Python's notes go to a logger few read).
    if hi < 20.0 {
        // X-rays are taken (0.154 nm for X-ray reflectivity); 0.4–0.7 is more often µm by mistake.
        report.warn(&format!(
            "the wavelengths end at {} nm: X-rays{}; if you meant µm, the range in nm is {}–{}",
            nm(hi),
            constant_line.map_or(String::new(), |c| format!(", and {c}")),
            nm(1000.0 * lo),
            nm(1000.0 * hi)
        ));
    } else if lo < CONSTANT_BAND_NM.0 || hi > CONSTANT_BAND_NM.1 {
        if let Some(c) = constant_line {
            report.warn(&c);
        }
    }
}

/// Where the built-in constant indices stand for their materials: the visible band and a little beyond.
const CONSTANT_BAND_NM: (f64, f64) = (300.0, 1000.0);

// ----------------------------------------------------------------------------------------------------------
// Spectrum

/// R, T, A and ψ/Δ of a stack against wavelength at one angle (`iridis thinfilm spectrum`).
#[derive(Debug, Clone)]
pub struct FilmSpectrum {
    pub stack: Stack,
    /// The stack as typed, spaced evenly (plot titles).
    pub title: String,
    pub angle_rad: f64,
    pub polarization: Polarization,
    pub wavelength_nm: Vec<f64>,
    pub rta: Vec<Rta>,
    /// (ψ, Δ) in degrees per wavelength (Δ `None` through inc: layers).
    pub ellipsometry: Vec<(f64, Option<f64>)>,
}

/// The spectrum of `stack` (written `title`) at `angle_rad`; a too coarse grid is warned about.
pub fn spectrum(
    stack: &Stack,
    title: &str,
    angle_rad: f64,
    grid: &[f64],
    polarization: Polarization,
    report: &dyn Report,
) -> Result<FilmSpectrum> {
    warn_sampling(stack, angle_rad, grid, report);
    Ok(FilmSpectrum {
        stack: stack.clone(),
        title: stack_title(title),
        angle_rad,
        polarization,
        wavelength_nm: grid.to_vec(),
        rta: spectra(stack, angle_rad, grid)?,
        ellipsometry: psi_delta(stack, angle_rad, grid)?,
    })
}

impl FilmSpectrum {
    fn col(&self, f: impl Fn(&Rta) -> f64) -> Vec<f64> {
        self.rta.iter().map(f).collect()
    }
    /// R of the chosen polarisation.
    pub fn r(&self) -> Vec<f64> {
        self.col(|x| pick(self.polarization, x).0)
    }
    /// T of the chosen polarisation.
    pub fn t(&self) -> Vec<f64> {
        self.col(|x| pick(self.polarization, x).1)
    }
    /// A of the chosen polarisation.
    pub fn a(&self) -> Vec<f64> {
        self.col(|x| pick(self.polarization, x).2)
    }

    /// R and T as a spectra CSV in pavo's layout (wl, R, T), which `iridis vision` reads.
    pub fn spectra_csv(&self) -> Result<String> {
        let table = iridis_vision::SpectraTable::new(
            self.wavelength_nm.clone(),
            vec![("R".into(), self.r()), ("T".into(), self.t())],
        )?;
        Ok(table.to_csv())
    }

    /// R, T and A against wavelength.
    pub fn plot(&self) -> Result<RgbImage> {
        let grid = &self.wavelength_nm;
        let title = format!("{}  at {}°{}", self.title, fmt_deg(self.angle_rad), pol_label(self.polarization));
        let mut plot = LinePlot::new(title, "wavelength (nm)", "fraction of incident power")
            .series(Series::new("R (reflectance)", grid, &self.r()))
            .series(Series::new("T (transmittance)", grid, &self.t()))
            .series(Series::new("A (absorptance)", grid, &self.a()));
        plot.x_range = Some((grid[0], grid[grid.len() - 1].max(grid[0] + 1.0)));
        Ok(plot.render()?)
    }

    /// What `--json` prints (docs/json.md).
    pub fn to_json(&self) -> serde_json::Value {
        let e = &self.ellipsometry;
        json!({
            "stack": self.stack.to_string(), "angle_deg": self.angle_rad.to_degrees(),
            "polarization": self.polarization.name(),
            "units": "R, T, A and their s and p parts are fractions of the incident power (1 = 100 %); ψ, Δ in degrees",
            "wavelength_nm": self.wavelength_nm,
            "R": self.r(), "T": self.t(), "A": self.a(),
            "Rs": self.col(|x| x.r_s), "Rp": self.col(|x| x.r_p), "Ts": self.col(|x| x.t_s), "Tp": self.col(|x| x.t_p),
            "psi_deg": e.iter().map(|p| p.0).collect::<Vec<_>>(),
            "delta_deg": (!self.stack.has_incoherent()).then(|| e.iter().map(|p| p.1).collect::<Vec<_>>()),
        })
    }

    /// The CSV (`--csv`): wavelength_nm,R,T,A,Rs,Rp,Ts,Tp,psi_deg,delta_deg.
    pub fn csv(&self) -> String {
        let (r, t, ab) = (self.r(), self.t(), self.a());
        let mut out = String::from("wavelength_nm,R,T,A,Rs,Rp,Ts,Tp,psi_deg,delta_deg\n");
        for (i, x) in self.rta.iter().enumerate() {
            let (psi, delta) = ellips_cells(&self.ellipsometry, i);
            let _ = writeln!(
                out,
                "{},{},{},{},{},{},{},{},{psi},{delta}",
                self.wavelength_nm[i], r[i], t[i], ab[i], x.r_s, x.r_p, x.t_s, x.t_p
            );
        }
        out
    }

    /// The table for people.
    pub fn text(&self) -> String {
        let (r, t, ab) = (self.r(), self.t(), self.a());
        let mut out = String::new();
        let _ =
            writeln!(out, "stack  {}\nangle  {}°{}", self.stack, fmt_deg(self.angle_rad), pol_label(self.polarization));
        let _ = writeln!(out, "R, T, A: fractions of the incident power (reflected, transmitted, absorbed)");
        let _ = writeln!(out, "{:>10}  {:>10}  {:>10}  {:>10}", "λ (nm)", "R", "T", "A");
        for i in 0..self.wavelength_nm.len() {
            let _ = writeln!(out, "{:>10.2}  {:>10.7}  {:>10.7}  {:>10.7}", self.wavelength_nm[i], r[i], t[i], ab[i]);
        }
        out
    }
}

// ----------------------------------------------------------------------------------------------------------
// Angle × wavelength table

/// The angle × wavelength simulation table (`iridis thinfilm table`, Sussenbach Figure 3.8).
#[derive(Debug, Clone)]
pub struct FilmTable {
    pub title: String,
    pub angles_rad: Vec<f64>,
    pub wavelength_nm: Vec<f64>,
    /// Row-major: angle, then wavelength.
    pub rta: Vec<Rta>,
    /// (ψ, Δ) per angle and wavelength.
    pub ellipsometry: Vec<Vec<(f64, Option<f64>)>>,
}

/// Angles `FROM:TO:STEP` with units (radians), each within 0°–90°.
pub fn parse_angles(s: &str, flag: &str) -> Result<Vec<f64>> {
    let angles = parse_range(s, parse_angle_rad).map_err(|e| anyhow!("{flag}: {e}"))?;
    if let Some(bad) = angles.iter().find(|t| !(**t >= 0.0 && **t <= std::f64::consts::FRAC_PI_2 + 1e-12)) {
        bail!("{flag}: {}° is outside 0°–90°", fmt_deg(*bad));
    }
    Ok(angles)
}

/// The colour scale of a table's map (`--scale`) as given, `None` meaning `auto`: `linear`, `log` or `auto` (see
/// [`FilmTable::plot`]). A rough film's table draws its own map, of π·k_d, so a scale given with one is refused
/// rather than ignored.
pub fn table_scale(scale: Option<&str>, rough: bool) -> Result<&'static str> {
    match (scale, rough) {
        (None, _) => Ok("auto"),
        (Some(_), true) => {
            bail!("--scale sets the colour scale of a smooth film's R map; the rough-film table draws its own")
        }
        (Some(s), false) => ["auto", "linear", "log"]
            .into_iter()
            .find(|k| k.eq_ignore_ascii_case(s.trim()))
            .ok_or_else(|| anyhow!("--scale '{s}': expected auto, linear or log")),
    }
}

/// The table of `stack` (written `title`) over `angles` (`FROM:TO:STEP`, the `--angles` of the command).
pub fn table(stack: &Stack, title: &str, angles: &str, grid: &[f64], report: &dyn Report) -> Result<FilmTable> {
    let angles = parse_angles(angles, "--angles")?;
    if angles.len() * grid.len() > 20_000_000 {
        bail!("{} × {} samples is too many for a table", angles.len(), grid.len());
    }
    if let Some(th) = angles.first() {
        warn_sampling(stack, *th, grid, report);
    }
    let rta = evaluate_grid(stack, &angles, grid, GridPath::Auto, true)?;
    let ellipsometry = angles.iter().map(|th| psi_delta(stack, *th, grid)).collect::<Result<Vec<_>>>()?;
    Ok(FilmTable { title: stack_title(title), angles_rad: angles, wavelength_nm: grid.to_vec(), rta, ellipsometry })
}

impl FilmTable {
    /// The CSV: angle_deg, wavelength_nm, R, T, A, Rs, Rp, Ts, Tp, psi_deg, delta_deg.
    pub fn csv(&self) -> String {
        let grid = &self.wavelength_nm;
        let mut csv = String::with_capacity(self.rta.len() * 100);
        csv.push_str("angle_deg,wavelength_nm,R,T,A,Rs,Rp,Ts,Tp,psi_deg,delta_deg\n");
        for (i, th) in self.angles_rad.iter().enumerate() {
            for (j, w) in grid.iter().enumerate() {
                let x = &self.rta[i * grid.len() + j];
                let (psi, delta) = ellips_cells(&self.ellipsometry[i], j);
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
        csv
    }

    /// R as an angle × wavelength map with a colour bar; `scale` is `linear`, `log` (three decades below the
    /// largest R) or `auto` (log when most of R sits in the darkest tenth of a linear scale, said in a line).
    pub fn plot(&self, scale: &str, report: &dyn Report) -> Result<RgbImage> {
        let (angles, grid, xs) = (&self.angles_rad, &self.wavelength_nm, &self.rta);
        let (w, h) = (grid.len() as u32, angles.len() as u32);
        let rmax = xs.iter().map(|x| x.r()).fold(0.0, f64::max).max(1e-12);
        let log = match scale {
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
        if log && scale == "auto" {
            report.info("--plot: log colour scale (most of R is below a tenth of its largest value; --scale linear for a linear one)");
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
        Ok(ImagePlot {
            title: format!("Reflectance R (unpolarised): {}", self.title),
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
        .render()?)
    }
}

// ----------------------------------------------------------------------------------------------------------
// Colour

/// The JSON of `thinfilm color`, the same keys for smooth and rough films: `reflected` and `transmitted` of
/// the stack with a smooth last interface, `specular` and `diffuse` (π·k_d) parts of the reflection (for a
/// smooth film the reflection is all specular and the diffuse part black), `rough` the LSRS conditions or null.
pub fn film_colours_json(
    reflected: &serde_json::Value,
    transmitted: &serde_json::Value,
    specular: &serde_json::Value,
    diffuse: &serde_json::Value,
    rough: serde_json::Value,
    conditions: serde_json::Value,
) -> serde_json::Value {
    json!({
        "reflected": reflected, "transmitted": transmitted, "specular": specular, "diffuse": diffuse, "rough": rough,
        "conditions": conditions,
    })
}

/// What a film's colours rest on (`conditions` in `thinfilm color --json`; its text's `conditions` line): the
/// stack, the light's angle and polarisation (`None`: a rough film's, in `rough`), the illuminant, the observer
/// and the wavelength range integrated.
pub fn colour_conditions(
    stack: &Stack,
    angle_and_polarization: Option<(f64, Polarization)>,
    illuminant: Illuminant,
    observer: Observer,
    (from_nm, to_nm): (f64, f64),
) -> serde_json::Value {
    json!({
        "stack": stack.to_string(),
        "angle_deg": angle_and_polarization.map(|(a, _)| round_deg(a)),
        "polarization": angle_and_polarization.map_or("avg", |(_, p)| p.name()),
        "illuminant": illuminant.to_string(),
        "observer": observer.to_string(),
        "wavelength_range_nm": [from_nm, to_nm],
    })
}

/// The reflected and transmitted colour of a smooth film (`iridis thinfilm color`), and how an animal sees
/// them when a visual system was asked for.
#[derive(Debug, Clone)]
pub struct FilmColour {
    pub stack: Stack,
    pub angle_rad: f64,
    pub polarization: Polarization,
    pub illuminant: Illuminant,
    pub observer: Observer,
    pub wavelength_range_nm: (f64, f64),
    /// The colour reports (docs/json.md, "Shape: colour").
    pub reflected: serde_json::Value,
    pub transmitted: serde_json::Value,
    white: Xyz,
    pub vision: Option<iridis_vision::Analysis>,
}

/// The colours of `stack` at `angle_rad` under `illuminant` (its name, as `iridis vision` takes it, for
/// `visual`); `visual` names a visual system of `iridis vision` to see the reflected and transmitted light.
#[allow(clippy::too_many_arguments)]
pub fn colour(
    stack: &Stack,
    angle_rad: f64,
    polarization: Polarization,
    grid: &[f64],
    illuminant: &str,
    observer: Observer,
    visual: Option<&str>,
    report: &dyn Report,
) -> Result<FilmColour> {
    let ill: Illuminant = illuminant.parse()?;
    warn_sampling(stack, angle_rad, grid, report);
    let c = FilmColorimeter::new(grid, ill, observer).color(stack, angle_rad, polarization)?;
    let white = iridis_color::integrate::white_point(ill, observer);
    // How an animal sees the reflected and transmitted light (iridis-vision), only when asked.
    let vision = match visual {
        Some(v) => {
            let xs = spectra(stack, angle_rad, grid)?;
            let r = xs.iter().map(|x| pick(polarization, x).0).collect();
            let t = xs.iter().map(|x| pick(polarization, x).1).collect();
            let spec = iridis_vision::Spec {
                visual: Some(v.to_string()),
                illuminant: Some(illuminant.to_string()),
                ..Default::default()
            };
            let system = spec.system().context("--visual")?;
            let samples = [("reflected".to_string(), r), ("transmitted".to_string(), t)];
            Some(iridis_vision::analyse(&samples, grid, &system, &spec.options(&system)?)?)
        }
        None => None,
    };
    Ok(FilmColour {
        stack: stack.clone(),
        angle_rad,
        polarization,
        illuminant: ill,
        observer,
        wavelength_range_nm: (grid[0], grid[grid.len() - 1]),
        reflected: colour_report(c.reflected, white),
        transmitted: colour_report(c.transmitted, white),
        white,
        vision,
    })
}

impl FilmColour {
    /// What `--json` prints: one shape for smooth and rough films (a smooth film reflects specularly only).
    pub fn to_json(&self) -> Result<serde_json::Value> {
        let none = colour_report(Xyz { x: 0.0, y: 0.0, z: 0.0 }, self.white);
        let conditions = colour_conditions(
            &self.stack,
            Some((self.angle_rad, self.polarization)),
            self.illuminant,
            self.observer,
            self.wavelength_range_nm,
        );
        let mut v =
            film_colours_json(&self.reflected, &self.transmitted, &self.reflected, &none, json!(null), conditions);
        if let (Some(vision), Some(obj)) = (&self.vision, v.as_object_mut()) {
            obj.insert("vision".into(), serde_json::to_value(vision)?);
        }
        Ok(v)
    }

    /// The colours for people.
    pub fn text(&self) -> String {
        let mut o = format!("stack        {}\n", self.stack);
        let _ = writeln!(
            o,
            "conditions   {}° incidence{}, {}",
            fmt_deg(self.angle_rad),
            pol_label(self.polarization),
            crate::color::light_and_observer(self.illuminant, self.observer, self.wavelength_range_nm)
        );
        o += &colour_text("reflected", &self.reflected);
        o += &colour_text("transmitted", &self.transmitted);
        if let Some(v) = &self.vision {
            let _ = writeln!(
                o,
                "seen by      {} ({}; relative catches {})",
                v.visual.name,
                v.illuminant,
                v.receptors.join(", ")
            );
            for s in &v.samples {
                let rel: Vec<String> = s.relative_catches.iter().map(|x| format!("{x:.4}")).collect();
                let _ = writeln!(o, "  {:<11}  {}", s.name, rel.join("  "));
            }
            if let Some(d) = v.distances.first() {
                let jnd = |x: Option<f64>| x.map_or("—".to_string(), |x| format!("{x:.2} JND"));
                let _ = writeln!(o, "  reflected vs transmitted: ΔS {}, ΔL {}", jnd(d.delta_s), jnd(d.delta_l));
                let (light, noise) = crate::vision::conditions(v);
                let _ = writeln!(o, "  light  {light}\n  noise  {noise}");
            }
        }
        o
    }

    /// The vision analysis' notes (said after the text).
    pub fn notes(&self) -> &[String] {
        self.vision.as_ref().map_or(&[], |v| &v.notes)
    }
}

// ----------------------------------------------------------------------------------------------------------
// Materials

/// One built-in material: its names, description, wavelength range and (when asked) index.
pub type MaterialRow = (Vec<&'static str>, &'static str, f64, f64, Option<std::result::Result<(f64, f64), String>>);

/// The built-in materials (`iridis thinfilm materials`), each with its index at `at_nm` when given.
#[derive(Debug, Clone)]
pub struct Materials {
    pub at_nm: Option<f64>,
    pub rows: Vec<MaterialRow>,
}

/// The built-in materials and, with `at_nm`, each one's complex index there.
pub fn materials(at_nm: Option<f64>) -> Result<Materials> {
    if let Some(w) = at_nm.filter(|w| !(w.is_finite() && *w > 0.0)) {
        // Otherwise every material would answer "no data", which reads as a gap in the library.
        bail!("--at {w} nm: a wavelength must be a positive, finite length");
    }
    let mut rows = Vec::new();
    for (names, desc) in Material::library() {
        let m = Material::builtin(names[0]).context("built-in material failed to load")?;
        let (lo, hi) = m.range_nm();
        let at = at_nm.map(|w| m.index_at(w).map(|n| (n.re, n.im)).map_err(|e| e.to_string()));
        rows.push((names, desc, lo, hi, at));
    }
    Ok(Materials { at_nm, rows })
}

impl Materials {
    /// What `--json` prints.
    pub fn to_json(&self) -> serde_json::Value {
        let v: Vec<serde_json::Value> = self
            .rows
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
        json!({ "materials": v })
    }

    /// The list for people.
    pub fn text(&self) -> String {
        let mut o = String::new();
        let at = self.at_nm.unwrap_or(0.0);
        // The names' column as wide as the longest list of them, so that none runs into its description.
        let width = self.rows.iter().map(|r| r.0.join(", ").chars().count()).max().unwrap_or(0).max(36);
        for (names, desc, _, _, idx) in &self.rows {
            let idx = match idx {
                Some(Ok((n, k))) => format!("   n̂({at} nm) = {n:.5} + {k:.5}i"),
                Some(Err(_)) => format!("   (no data at {at} nm)"),
                None => String::new(),
            };
            let _ = writeln!(o, "{:<width$}   {desc}{idx}", names.join(", "));
        }
        o + "\nAlso: n=1.38, n=0.2+3.4i (constants) and file:PATH (refractiveindex.info YAML or CSV wavelength_nm,n,k).\n"
    }
}
