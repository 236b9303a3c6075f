//! Films on a rough substrate (the LSRS model, Sussenbach eq. 3.15–3.20, with the HTSG BRDF at the substrate;
//! `iridis_thinfilm::rough`): the options `σ, τ` (`iridis thinfilm … --roughness --correlation`, Python's
//! `iridis.thinfilm` `roughness=`), spectra, colours and the soap-film chart's bands. Specular (`k_r`, a
//! fraction of the incident power) and diffuse (`k_d`, sr⁻¹; `π k_d` is the radiance factor, relative to a
//! white Lambertian surface under the same light) are reported separately, next to the smooth model's `R`.

use std::f64::consts::PI;
use std::fmt::Write as _;

use anyhow::{anyhow, Result};
use iridis_color::units::degrees;
use iridis_color::{Illuminant, Observer, SpectralWeights, Xyz};
use iridis_thinfilm::color::{FilmColor, FilmColorimeter, Polarization};
use iridis_thinfilm::htsg::{Htsg, Roughness, Series};
use iridis_thinfilm::rough::{DiffuseTransport, Lsrs, RoughStack};
use iridis_thinfilm::Stack;

/// The rough model's options.
#[derive(Debug, Clone, Copy)]
pub struct RoughOptions {
    /// rms roughness σ of the last interface (nm).
    pub sigma_nm: f64,
    /// Autocorrelation length τ of the rough interface (nm).
    pub tau_nm: f64,
    /// Terms of the HTSG directional-diffuse series (the thesis' D-iterations); `None`: as many as needed for
    /// an error bound of 1e-6 of the lobe's peak.
    pub d_iterations: Option<usize>,
    /// How diffuse light crosses the layers.
    pub transport: DiffuseTransport,
}

impl RoughOptions {
    /// σ and τ with the defaults of the front ends (series to 1e-6, multiple scattering inside the film).
    pub fn new(sigma_nm: f64, tau_nm: f64) -> Self {
        Self { sigma_nm, tau_nm, d_iterations: None, transport: DiffuseTransport::Multiple }
    }

    /// The stack with this rough substrate.
    pub fn build(&self, stack: Stack) -> Result<RoughStack> {
        let series = match self.d_iterations {
            Some(n) => Series::Fixed(n),
            None => Series::default(),
        };
        let r = Roughness::new(self.sigma_nm, self.tau_nm).map_err(|e| anyhow!("--roughness/--correlation: {e}"))?;
        Ok(RoughStack::new(stack, Htsg::new(r, series)).with_transport(self.transport))
    }

    /// How the series is summed, in words.
    pub fn series_label(&self) -> String {
        series_label(self.d_iterations)
    }
}

/// How the HTSG series is summed, in words: `N D-iterations` or `series to 1e-6`.
pub fn series_label(d_iterations: Option<usize>) -> String {
    match d_iterations {
        Some(n) => format!("{n} D-iterations"),
        None => "series to 1e-6".into(),
    }
}

/// The directions the rough-film model is evaluated for (radians): the view and light polar angles, and the
/// light's azimuth relative to the viewer (π: light and viewer on opposite sides, the mirror configuration).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Angles {
    pub view: f64,
    pub light: f64,
    pub azimuth: f64,
}

impl Angles {
    /// At view angle `view`, with the light at `light` or, without one, at the view angle (with the default
    /// azimuth π, the mirror direction: the specular peak).
    pub fn new(view: f64, light: Option<f64>, azimuth: f64) -> Self {
        Angles { view, light: light.unwrap_or(view), azimuth }
    }

    /// `view 30°, light 30°, azimuth 180°`, as the reports print them.
    pub fn text(&self) -> String {
        format!("view {}°, light {}°, azimuth {}°", deg(self.view), deg(self.light), deg(self.azimuth))
    }

    /// The keys `view_deg`, `light_deg` and `azimuth_deg` of the reports' JSON (docs/json.md).
    fn insert_json(&self, json: &mut serde_json::Value) {
        json["view_deg"] = degrees(self.view).into();
        json["light_deg"] = degrees(self.light).into();
        json["azimuth_deg"] = degrees(self.azimuth).into();
    }
}

/// Per wavelength: the smooth model's R and the LSRS values at `angles`.
pub fn evaluate(rough: &RoughStack, grid: &[f64], angles: Angles) -> Result<Vec<(f64, Lsrs)>> {
    use rayon::prelude::*;
    let Angles { view, light, azimuth } = angles;
    // In parallel: with multiple scattering each wavelength prepares its own state.
    grid.par_iter()
        .map(|&w| Ok((rough.stack.evaluate(w, view)?.r(), rough.evaluate(w, view, light, azimuth)?)))
        .collect()
}

/// The colours of a rough film (`iridis thinfilm color --roughness`): the smooth film's (reflected and
/// transmitted), the rough film's specular part `k_r` and its diffuse part `π k_d`.
#[derive(Debug, Clone, Copy)]
pub struct RoughColours {
    pub smooth: FilmColor,
    pub specular: Xyz,
    pub diffuse: Xyz,
}

/// The colours of a rough film for one view and light.
pub fn colours(
    rough: &RoughStack,
    angles: Angles,
    grid: &[f64],
    illuminant: Illuminant,
    observer: Observer,
) -> Result<RoughColours> {
    let xs = evaluate(rough, grid, angles)?;
    let smooth =
        FilmColorimeter::new(grid, illuminant, observer).color(&rough.stack, angles.view, Polarization::Average)?;
    let (specular, diffuse) = specular_diffuse(&SpectralWeights::new(grid, illuminant, observer), &xs);
    Ok(RoughColours { smooth, specular, diffuse })
}

/// The XYZ of the specular part (`k_r`) and of the diffuse part (`π k_d`, the radiance factor) of the LSRS
/// values per wavelength of [`evaluate`].
fn specular_diffuse(weights: &SpectralWeights, xs: &[(f64, Lsrs)]) -> (Xyz, Xyz) {
    let specular = weights.integrate(&xs.iter().map(|x| x.1.k_r()).collect::<Vec<_>>());
    let diffuse = weights.integrate(&xs.iter().map(|x| PI * x.1.k_d()).collect::<Vec<_>>());
    (specular, diffuse)
}

/// For every thickness of the swept layer, the XYZ of the rough film's specular part (`k_r`, like the smooth
/// chart's reflected band) and of its diffuse part (`π k_d`, the radiance factor: Y = 1 is a white Lambertian
/// surface under the same light).
#[allow(clippy::too_many_arguments)]
pub fn chart_colours(
    stack: &Stack,
    layer: usize,
    thicknesses: &[f64],
    opts: &RoughOptions,
    angles: Angles,
    grid: &[f64],
    illuminant: Illuminant,
    observer: Observer,
) -> Result<Vec<(Xyz, Xyz)>> {
    use rayon::prelude::*;
    let weights = SpectralWeights::new(grid, illuminant, observer);
    thicknesses
        .par_iter()
        .map(|&d| {
            let rough = opts.build(stack.with_thickness(layer, d))?;
            Ok(specular_diffuse(&weights, &evaluate(&rough, grid, angles)?))
        })
        .collect()
}

// ----------------------------------------------------------------------------------------------------------
// The commands' results (`iridis thinfilm spectrum|color|table|bench --roughness σ --correlation τ`, Python's
// `iridis.film` with `roughness=`): text, CSV and JSON rendered here so every front end prints the same.

/// The LSRS spectrum at one view and light: the smooth model's R with the rough film's `k_r` and `k_d`.
#[derive(Debug, Clone)]
pub struct RoughSpectrum {
    pub rough: RoughStack,
    pub options: RoughOptions,
    /// The stack as typed, spaced evenly (plot titles).
    pub title: String,
    pub angles: Angles,
    pub wavelength_nm: Vec<f64>,
    /// Per wavelength: smooth R and the LSRS values.
    pub values: Vec<(f64, Lsrs)>,
}

/// The spectrum of `stack` (written `title`) with a rough substrate at `angles`.
pub fn spectrum(stack: Stack, title: &str, opts: &RoughOptions, angles: Angles, grid: &[f64]) -> Result<RoughSpectrum> {
    let rough = opts.build(stack)?;
    let values = evaluate(&rough, grid, angles)?;
    Ok(RoughSpectrum {
        rough,
        options: *opts,
        title: crate::film::stack_title(title),
        angles,
        wavelength_nm: grid.to_vec(),
        values,
    })
}

fn deg(rad: f64) -> String {
    crate::film::fmt_deg(rad)
}

impl RoughSpectrum {
    fn col(&self, f: impl Fn(&(f64, Lsrs)) -> f64) -> Vec<f64> {
        self.values.iter().map(f).collect()
    }

    /// R (smooth substrate), `k_r` and `π k_d` against wavelength.
    pub fn plot(&self) -> Result<iridis_plot::RgbImage> {
        use iridis_plot::{LinePlot, Series as PlotSeries};
        let grid = &self.wavelength_nm;
        let t = format!(
            "{}, σ {} nm, τ {} nm, view {}°, light {}°",
            self.title,
            self.options.sigma_nm,
            self.options.tau_nm,
            deg(self.angles.view),
            deg(self.angles.light)
        );
        let mut plot = LinePlot::new(t, "wavelength (nm)", "reflectance / radiance factor")
            .series(PlotSeries::new("R, smooth substrate", grid, &self.col(|x| x.0)))
            .series(PlotSeries::new("k_r, specular (rough)", grid, &self.col(|x| x.1.k_r())))
            .series(PlotSeries::new("π·k_d, diffuse (rough)", grid, &self.col(|x| PI * x.1.k_d())));
        plot.x_range = Some((grid[0], grid[grid.len() - 1].max(grid[0] + 1.0)));
        Ok(plot.render()?)
    }

    /// The spectrum's columns under their `--json` names (docs/json.md): the smooth model's R, the specular part
    /// `k_r` and the diffuse part `k_d` (sr⁻¹), each with its s and p halves.
    pub fn columns(&self) -> [(&'static str, Vec<f64>); 7] {
        [
            ("R_smooth", self.col(|x| x.0)),
            ("specular", self.col(|x| x.1.k_r())),
            ("specular_s", self.col(|x| x.1.specular_s)),
            ("specular_p", self.col(|x| x.1.specular_p)),
            ("diffuse_per_sr", self.col(|x| x.1.k_d())),
            ("diffuse_s_per_sr", self.col(|x| x.1.diffuse_s)),
            ("diffuse_p_per_sr", self.col(|x| x.1.diffuse_p)),
        ]
    }

    /// The diffuse part's error bound (sr⁻¹, the largest over the wavelengths) and the most series terms used.
    pub fn bound_terms(&self) -> (f64, usize) {
        (
            self.values.iter().map(|x| x.1.bound).fold(0.0, f64::max),
            self.values.iter().map(|x| x.1.terms).max().unwrap_or(0),
        )
    }

    /// What `--json` prints (docs/json.md).
    pub fn to_json(&self) -> serde_json::Value {
        let (bound, terms) = self.bound_terms();
        let mut json = serde_json::json!({
            "model": "LSRS (Sussenbach eq. 3.15-3.20) with the HTSG BRDF",
            "diffuse_transport": self.options.transport.name(),
            "roughness_nm": self.rough.htsg.roughness.sigma_nm(), "correlation_nm": self.rough.htsg.roughness.tau_nm(),
            "wavelength_nm": self.wavelength_nm,
            "series_terms_max": terms, "diffuse_error_bound_per_sr": bound,
        });
        self.angles.insert_json(&mut json);
        for (name, values) in self.columns() {
            json[name] = serde_json::json!(values);
        }
        json
    }

    /// The CSV (`--csv`).
    pub fn csv(&self) -> String {
        let mut out = String::from(
            "wavelength_nm,R_smooth,specular,diffuse_per_sr,specular_s,specular_p,diffuse_s_per_sr,diffuse_p_per_sr\n",
        );
        for (w, (r, x)) in self.wavelength_nm.iter().zip(&self.values) {
            let _ = writeln!(
                out,
                "{w},{r},{},{},{},{},{},{}",
                x.k_r(),
                x.k_d(),
                x.specular_s,
                x.specular_p,
                x.diffuse_s,
                x.diffuse_p
            );
        }
        out
    }

    /// The table for people, with the model's conditions.
    pub fn text(&self) -> String {
        let (bound, terms) = self.bound_terms();
        let (sigma, tau) = (self.rough.htsg.roughness.sigma_nm(), self.rough.htsg.roughness.tau_nm());
        let mut out = format!("stack     {}\n", self.rough.stack);
        let _ = writeln!(
            out,
            "rough     substrate interface σ = {sigma} nm, τ = {tau} nm (HTSG, {}; max {terms} terms, error ≤ {bound:.1e} sr⁻¹; {} diffuse transport)",
            self.options.series_label(),
            self.options.transport.name()
        );
        let _ = writeln!(out, "angles    {}, unpolarised", self.angles.text());
        let _ = writeln!(
            out,
            "units     R smooth, k_r specular: fractions of the incident power; k_d: BRDF of the diffuse lobe (sr⁻¹)"
        );
        let _ = writeln!(out, "{:>10}  {:>10}  {:>12}  {:>12}", "λ (nm)", "R smooth", "k_r specular", "k_d (sr⁻¹)");
        for (w, (r, x)) in self.wavelength_nm.iter().zip(&self.values) {
            let _ = writeln!(out, "{w:>10.2}  {r:>10.7}  {:>12.7}  {:>12.7}", x.k_r(), x.k_d());
        }
        out
    }
}

/// The colours of a rough film as `iridis thinfilm color --roughness` reports them.
#[derive(Debug, Clone)]
pub struct RoughColourReport {
    pub stack: Stack,
    pub options: RoughOptions,
    pub angles: Angles,
    pub illuminant: Illuminant,
    pub observer: Observer,
    pub wavelength_range_nm: (f64, f64),
    /// Colour reports (docs/json.md): smooth film reflected and transmitted, rough specular and diffuse.
    pub smooth: serde_json::Value,
    pub transmitted: serde_json::Value,
    pub specular: serde_json::Value,
    pub diffuse: serde_json::Value,
}

/// The colours of `stack` with a rough substrate, for one view and light.
#[allow(clippy::too_many_arguments)]
pub fn colour_report(
    stack: Stack,
    opts: &RoughOptions,
    angles: Angles,
    grid: &[f64],
    illuminant: Illuminant,
    observer: Observer,
) -> Result<RoughColourReport> {
    use crate::color::colour_report as report;
    let rough = opts.build(stack)?;
    let c = colours(&rough, angles, grid, illuminant, observer)?;
    let white = iridis_color::integrate::white_point(illuminant, observer);
    Ok(RoughColourReport {
        stack: rough.stack,
        options: *opts,
        angles,
        illuminant,
        observer,
        wavelength_range_nm: (grid[0], grid[grid.len() - 1]),
        smooth: report(c.smooth.reflected, white),
        transmitted: report(c.smooth.transmitted, white),
        specular: report(c.specular, white),
        diffuse: report(c.diffuse, white),
    })
}

impl RoughColourReport {
    /// What `--json` prints: the shape of `thinfilm color` ([`crate::film::film_colours_json`]).
    pub fn to_json(&self) -> serde_json::Value {
        let mut conditions = serde_json::json!({
            "roughness_nm": self.options.sigma_nm, "correlation_nm": self.options.tau_nm,
            "diffuse_transport": self.options.transport.name(),
        });
        self.angles.insert_json(&mut conditions);
        let light =
            crate::film::colour_conditions(&self.stack, None, self.illuminant, self.observer, self.wavelength_range_nm);
        crate::film::film_colours_json(
            &self.smooth,
            &self.transmitted,
            &self.specular,
            &self.diffuse,
            conditions,
            light,
        )
    }

    /// The colours for people.
    pub fn text(&self) -> String {
        use crate::color::colour_text;
        let mut o = format!("stack        {}\n", self.stack);
        let _ = writeln!(
            o,
            "rough        σ = {} nm, τ = {} nm at the substrate (HTSG, {})",
            self.options.sigma_nm,
            self.options.tau_nm,
            self.options.series_label()
        );
        let _ = writeln!(
            o,
            "conditions   {}, {}",
            self.angles.text(),
            crate::color::light_and_observer(self.illuminant, self.observer, self.wavelength_range_nm)
        );
        o += &colour_text("smooth film, reflected", &self.smooth);
        o += &colour_text("rough film, specular k_r", &self.specular);
        o += &colour_text("rough film, diffuse π·k_d", &self.diffuse);
        o
    }
}

/// Algorithm 2's view × light × wavelength table (`iridis thinfilm table --roughness`), timed.
#[derive(Debug)]
pub struct RoughTableRun {
    pub title: String,
    /// View and light angles in degrees (rounded to 1e-9).
    pub views_deg: Vec<f64>,
    pub lights_deg: Vec<f64>,
    pub wavelength_nm: Vec<f64>,
    pub table: iridis_thinfilm::rough::RoughTable,
    pub seconds: f64,
}

/// Angles `FROM:TO:STEP` with units as degrees rounded to 1e-9, each within 0°–90° (`flag` names the option).
pub fn angles_deg(s: &str, flag: &str) -> Result<Vec<f64>> {
    Ok(crate::film::parse_angles(s, flag)?.iter().map(|t| crate::film::round_deg(*t)).collect())
}

/// The table of `stack` (written `title`) for the views `views` and lights `lights` (`FROM:TO:STEP`; lights
/// default to the views) at `azimuth` (rad).
pub fn table(
    stack: Stack,
    title: &str,
    opts: &RoughOptions,
    views: &str,
    lights: Option<&str>,
    azimuth: f64,
    grid: &[f64],
) -> Result<RoughTableRun> {
    let views_deg = angles_deg(views, "--angles")?;
    let lights_deg = match lights {
        Some(s) => angles_deg(s, "--light-angles")?,
        None => views_deg.clone(),
    };
    if views_deg.len() * lights_deg.len() * grid.len() > 50_000_000 {
        anyhow::bail!("{} × {} × {} entries is too many for a table", views_deg.len(), lights_deg.len(), grid.len());
    }
    let rough = opts.build(stack)?;
    let t0 = std::time::Instant::now();
    let table = rough.table(&views_deg, &lights_deg, grid, azimuth)?;
    let seconds = t0.elapsed().as_secs_f64();
    Ok(RoughTableRun {
        title: crate::film::stack_title(title),
        views_deg,
        lights_deg,
        wavelength_nm: grid.to_vec(),
        table,
        seconds,
    })
}

impl RoughTableRun {
    /// What was computed and how fast (one line).
    pub fn summary(&self) -> String {
        let n = self.views_deg.len() * self.lights_deg.len() * self.wavelength_nm.len();
        format!(
            "LSRS table: {} views × {} lights × {} wavelengths in {:.3} s ({:.2e} entries/s), ≤ {} series terms, diffuse error ≤ {:.1e} sr⁻¹",
            self.views_deg.len(),
            self.lights_deg.len(),
            self.wavelength_nm.len(),
            self.seconds,
            n as f64 / self.seconds.max(1e-12),
            self.table.max_terms,
            self.table.max_bound
        )
    }

    /// The plot's title: the light is at the view angle where the table has that light, else at the nearest
    /// end of `--light-angles` (said, with the range: it read "light at the view angle" for every row).
    pub fn plot_title(&self) -> String {
        let (views, lights) = (&self.views_deg, &self.lights_deg);
        let (lo, hi) = (lights[0], lights[lights.len() - 1]);
        if views.iter().all(|v| (lo..=hi).contains(v)) {
            format!("Diffuse π·k_d, light at the view angle: {}", self.title)
        } else {
            format!(
                "Diffuse π·k_d, light at the view angle within the lights' {lo}°–{hi}° (else its end): {}",
                self.title
            )
        }
    }

    /// `π k_d` over view angle × wavelength with the light at the view angle (the peak of the diffuse lobe).
    pub fn plot(&self) -> Result<iridis_plot::RgbImage> {
        use iridis_plot::{magma, ColorBar, ImagePlot, RgbImage};
        let (views, lights, grid) = (&self.views_deg, &self.lights_deg, &self.wavelength_nm);
        let (w, h) = (grid.len() as u32, views.len() as u32);
        let mut vals = vec![0.0; views.len() * grid.len()];
        for (i, v) in views.iter().enumerate() {
            for (j, &wl) in grid.iter().enumerate() {
                let light = v.clamp(lights[0], lights[lights.len() - 1]);
                vals[i * grid.len() + j] = PI * self.table.lookup(v.to_radians(), light.to_radians(), wl)?.1;
            }
        }
        let max = vals.iter().copied().fold(0.0, f64::max).max(1e-12);
        let mut px = RgbImage::new(w, h);
        for i in 0..views.len() {
            for j in 0..grid.len() {
                px.put(j as u32, (views.len() - 1 - i) as u32, magma(vals[i * grid.len() + j] / max));
            }
        }
        Ok(ImagePlot {
            title: self.plot_title(),
            x_label: "wavelength (nm)".into(),
            y_label: "view angle (°)".into(),
            x_range: (grid[0], grid[grid.len() - 1].max(grid[0] + 1e-9)),
            y_range: (views[0], views[views.len() - 1].max(views[0] + 1e-9)),
            pixels: &px,
            overlays: Vec::new(),
            colorbar: Some(ColorBar { label: "π·k_d".into(), min: 0.0, max, map: magma }),
            size: (1000, 640),
        }
        .render()?)
    }

    /// The CSV: view_deg, light_deg, wavelength_nm, specular, diffuse_per_sr.
    pub fn csv(&self) -> Result<Vec<u8>> {
        let mut csv = Vec::with_capacity(self.views_deg.len() * self.lights_deg.len() * self.wavelength_nm.len() * 60);
        self.table.write_csv(&mut csv)?;
        Ok(csv)
    }
}

/// The stack of Sussenbach's Listing 3.6: a 348 nm water film on (rough) silicon, in air.
pub const LISTING_3_6_STACK: &str = "air | water 348nm | Si";

/// `iridis thinfilm bench --roughness σ --correlation τ` (Python's `iridis.film.bench(roughness=…)`): speed of
/// Algorithm 2's table for `stack` on `samples` × `samples` angles and 81 wavelengths, the shared (factorised)
/// generation against evaluating every entry directly (the algorithm as written), with the largest difference
/// between the two. Each measurement runs for at least `seconds`.
pub fn bench(stack: Stack, opts: &RoughOptions, azimuth: f64, samples: usize, seconds: f64) -> Result<RoughBench> {
    use std::time::Instant;
    if !(seconds.is_finite() && seconds > 0.0) {
        anyhow::bail!("--seconds must be positive");
    }
    let rough = opts.build(stack)?;
    let views = iridis_thinfilm::rough::angle_grid(samples)?;
    let grid: Vec<f64> = (0..81).map(|i| 380.0 + 5.0 * i as f64).collect();
    let entries = (views.len() * views.len() * grid.len()) as f64;
    // Shared generation, repeated for at least `seconds`.
    let (mut runs, t0) = (0usize, Instant::now());
    let mut table = rough.table(&views, &views, &grid, azimuth)?;
    runs += 1;
    while t0.elapsed().as_secs_f64() < seconds {
        table = rough.table(&views, &views, &grid, azimuth)?;
        runs += 1;
    }
    let shared_s = t0.elapsed().as_secs_f64() / runs as f64;
    // Direct: every entry by `evaluate` (eq. 3.15–3.19 per entry), on a sample of the (view, light) pairs, in
    // the table's order, for at least `seconds` (checked after each pair's spectrum, so that a short
    // measurement is short: a whole row of lights takes seconds).
    let t1 = Instant::now();
    let (mut n, mut max_rel) = (0usize, 0.0f64);
    'pairs: for (i, v) in views.iter().enumerate() {
        for (j, l) in views.iter().enumerate() {
            if n > 0 && t1.elapsed().as_secs_f64() >= seconds {
                break 'pairs;
            }
            for (w, &wl) in grid.iter().enumerate() {
                let x = rough.evaluate(wl, v.to_radians(), l.to_radians(), azimuth)?;
                let kd = table.diffuse[(i * views.len() + j) * grid.len() + w];
                if x.k_d() > 0.0 {
                    max_rel = max_rel.max((kd - x.k_d()).abs() / x.k_d());
                }
                n += 1;
            }
        }
    }
    let direct_per_s = n as f64 / t1.elapsed().as_secs_f64();
    let shared_per_s = entries / shared_s;
    Ok(RoughBench(serde_json::json!({
        "stack": rough.stack.to_string(),
        "roughness_nm": rough.htsg.roughness.sigma_nm(), "correlation_nm": rough.htsg.roughness.tau_nm(),
        "series": opts.series_label(),
        "views": views.len(), "lights": views.len(), "wavelengths": grid.len(), "entries": entries,
        "table_seconds": shared_s, "table_entries_per_second": shared_per_s, "table_runs": runs,
        "direct_entries_per_second": direct_per_s, "direct_entries_timed": n,
        "speedup": shared_per_s / direct_per_s, "max_relative_difference": max_rel,
        "threads": 1,
    })))
}

/// The measurements of [`fn@bench`], as `--json` prints them.
#[derive(Debug, Clone)]
pub struct RoughBench(pub serde_json::Value);

impl RoughBench {
    /// What `--json` prints.
    pub fn to_json(&self) -> serde_json::Value {
        self.0.clone()
    }

    /// The measurements for people.
    pub fn text(&self) -> String {
        let v = &self.0;
        let f = |k: &str| v[k].as_f64().unwrap_or(f64::NAN);
        let (views, lights, wl) = (&v["views"], &v["lights"], &v["wavelengths"]);
        let (shared_s, shared_per_s, direct_per_s) =
            (f("table_seconds"), f("table_entries_per_second"), f("direct_entries_per_second"));
        let entries = f("entries");
        format!(
            "LSRS table (Algorithm 2), {}, σ {} nm, τ {} nm, {}\n\
             {views} views × {lights} lights × {wl} wavelengths = {entries} entries, one thread\n  \
             shared generation  {shared_s:.3} s per table  ({shared_per_s:.3e} entries/s, {} runs)\n  \
             direct evaluation  {direct_per_s:.3e} entries/s ({} entries timed) → table {:.1} s\n  \
             speed-up ×{:.1}; largest relative difference of k_d {:.1e}\n",
            v["stack"].as_str().unwrap_or(""),
            f("roughness_nm"),
            f("correlation_nm"),
            v["series"].as_str().unwrap_or(""),
            v["table_runs"],
            v["direct_entries_timed"],
            entries / direct_per_s,
            shared_per_s / direct_per_s,
            f("max_relative_difference")
        )
    }
}
