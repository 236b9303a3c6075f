//! The rough-substrate (LSRS) branch of `iridis thinfilm spectrum|color|table|chart|bench`: the flags
//! `--roughness σ --correlation τ` switch a command from Sussenbach's smooth model to the LSRS model
//! (`iridis_thinfilm::rough`, thesis eq. 3.15–3.20) with the HTSG BRDF at the substrate
//! (`iridis_thinfilm::htsg`). Specular (`k_r`, a fraction of the incident power) and diffuse (`k_d`, sr⁻¹;
//! `π k_d` is the radiance factor, relative to a white Lambertian surface under the same light) are reported
//! separately, next to the smooth model's `R`.

use std::f64::consts::PI;
use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

use anyhow::{bail, Result};
use clap::Args as ClapArgs;
use iridis_api::rough::{evaluate, RoughOptions};
use iridis_color::units::{degrees, parse_angle_rad, parse_range};
use iridis_color::{Illuminant, Observer, Xyz};
use iridis_plot::{magma, ColorBar, ImagePlot, LinePlot, RgbImage, Series as PlotSeries};
use iridis_thinfilm::rough::{angle_grid, DiffuseTransport, RoughStack};
use iridis_thinfilm::Stack;
use serde_json::json;

/// The stack of Sussenbach's Listing 3.6: a 348 nm water film on (rough) silicon, in air.
pub const LISTING_3_6_STACK: &str = "air | water 348nm | Si";

/// Flags of the rough model, flattened into `spectrum`, `color`, `table`, `chart` and `bench`.
#[derive(Debug, Clone, ClapArgs)]
pub struct RoughArgs {
    /// Rough substrate (LSRS model with the HTSG BRDF): rms roughness σ of the last interface, e.g. 25nm.
    /// Needs --correlation. Valid for σ > 0, 2σ/τ ≤ 1 and τ²/(2√3σ) ≥ λ in the medium above the substrate.
    #[arg(long, value_parser = crate::args::length_nm, requires = "correlation", help_heading = "Rough substrate (LSRS)")]
    pub roughness: Option<f64>,
    /// Autocorrelation length τ of the rough interface, e.g. 300nm (Sussenbach Listing 3.6).
    #[arg(long, value_parser = crate::args::length_nm, requires = "roughness", help_heading = "Rough substrate (LSRS)")]
    pub correlation: Option<f64>,
    /// Light angle θ_l of the diffuse part (spectrum, color); default: the view angle (--angle).
    #[arg(long, value_parser = crate::args::angle_rad, help_heading = "Rough substrate (LSRS)")]
    pub light_angle: Option<f64>,
    /// Light angles FROM:TO:STEP of the table's diffuse part; default: the same as --angles.
    #[arg(long, help_heading = "Rough substrate (LSRS)")]
    pub light_angles: Option<String>,
    /// Azimuth of the light relative to the viewer; 180deg puts the light on the far side of the normal in
    /// the viewer's plane (the mirror configuration).
    #[arg(long, default_value = "180deg", value_parser = crate::args::angle_rad, help_heading = "Rough substrate (LSRS)")]
    pub azimuth: f64,
    /// Terms of the HTSG directional-diffuse series (the thesis' D-iterations, 5 in Listing 3.6); default:
    /// as many as needed for an error bound of 1e-6 of the lobe's peak.
    #[arg(long, help_heading = "Rough substrate (LSRS)")]
    pub d_iterations: Option<usize>,
    /// How diffuse light crosses the layers: multiple (the default: the light the layers turn back and the
    /// light trapped beyond the escape cone is scattered again until it leaves; reciprocal, a lossless film on
    /// a mirror reflects everything), single (alias reciprocal: one scattering, power transmittances both
    /// ways; faster, loses that light; docs/rough-films.md) or thesis (eq. 3.18–3.19 as printed; creates
    /// energy, not reciprocal — for comparison with the thesis only).
    #[arg(long, default_value = "multiple", value_name = "multiple|single|thesis", value_parser = diffuse_transport, help_heading = "Rough substrate (LSRS)")]
    pub diffuse_transport: DiffuseTransport,
}

fn diffuse_transport(s: &str) -> Result<DiffuseTransport, String> {
    DiffuseTransport::parse(s).map_err(|e| e.to_string())
}

impl RoughArgs {
    /// True when the rough model was asked for.
    pub fn is_set(&self) -> bool {
        self.roughness.is_some() || self.correlation.is_some()
    }

    /// The facade's rough-model options (both σ and τ given).
    pub fn options(&self) -> Result<RoughOptions> {
        let (Some(sigma_nm), Some(tau_nm)) = (self.roughness, self.correlation) else {
            bail!("the rough model needs both --roughness and --correlation");
        };
        Ok(RoughOptions { sigma_nm, tau_nm, d_iterations: self.d_iterations, transport: self.diffuse_transport })
    }

    fn build(&self, stack: Stack) -> Result<RoughStack> {
        self.options()?.build(stack)
    }

    fn series_label(&self) -> String {
        iridis_api::rough::series_label(self.d_iterations)
    }
}

fn deg(rad: f64) -> String {
    format!("{}", (rad.to_degrees() * 1e6).round() / 1e6)
}

/// `iridis thinfilm chart … --roughness σ --correlation τ`: for every thickness of the swept layer, the XYZ of
/// the rough film's specular part (`k_r`, like the smooth chart's reflected band) and of its diffuse part
/// (`π k_d`, the radiance factor: Y = 1 is a white Lambertian surface under the same light).
#[allow(clippy::too_many_arguments)]
pub fn chart_colours(
    stack: &Stack,
    layer: usize,
    thicknesses: &[f64],
    args: &RoughArgs,
    view: f64,
    grid: &[f64],
    illuminant: Illuminant,
    observer: Observer,
) -> Result<Vec<(Xyz, Xyz)>> {
    if args.light_angles.is_some() {
        bail!("--light-angles is for 'table'; use --light-angle here");
    }
    let light = args.light_angle.unwrap_or(view);
    let opts = args.options()?;
    iridis_api::rough::chart_colours(
        stack,
        layer,
        thicknesses,
        &opts,
        view,
        light,
        args.azimuth,
        grid,
        illuminant,
        observer,
    )
}

/// `iridis thinfilm spectrum … --roughness σ --correlation τ`.
pub fn spectrum(
    stack: Stack,
    title: &str,
    args: &RoughArgs,
    view: f64,
    grid: &[f64],
    json_out: bool,
    csv: bool,
    plot: Option<&Path>,
) -> Result<()> {
    if args.light_angles.is_some() {
        bail!("--light-angles is for 'table'; use --light-angle here");
    }
    let rough = args.build(stack)?;
    let light = args.light_angle.unwrap_or(view);
    let xs = evaluate(&rough, grid, view, light, args.azimuth)?;
    let smooth: Vec<f64> = xs.iter().map(|x| x.0).collect();
    let kr: Vec<f64> = xs.iter().map(|x| x.1.k_r()).collect();
    let kd: Vec<f64> = xs.iter().map(|x| x.1.k_d()).collect();
    let (sigma, tau) = (rough.htsg.roughness.sigma_nm(), rough.htsg.roughness.tau_nm());
    if let Some(p) = plot {
        let t = format!("{title}, σ {sigma} nm, τ {tau} nm, view {}°, light {}°", deg(view), deg(light));
        let pikd: Vec<f64> = kd.iter().map(|k| PI * k).collect();
        let mut plot = LinePlot::new(t, "wavelength (nm)", "reflectance / radiance factor")
            .series(PlotSeries::new("R, smooth substrate", grid, &smooth))
            .series(PlotSeries::new("k_r, specular (rough)", grid, &kr))
            .series(PlotSeries::new("π·k_d, diffuse (rough)", grid, &pikd));
        plot.x_range = Some((grid[0], grid[grid.len() - 1].max(grid[0] + 1.0)));
        let img = plot.render()?;
        crate::output::write_png_rgb8(p, img.width, img.height, &img.data)?;
        if !json_out && !csv {
            crate::outln!("wrote {}", p.display())?;
        }
    }
    let bound = xs.iter().map(|x| x.1.bound).fold(0.0, f64::max);
    let terms = xs.iter().map(|x| x.1.terms).max().unwrap_or(0);
    if json_out {
        return crate::output::print_json(&json!({
            "model": "LSRS (Sussenbach eq. 3.15-3.20) with the HTSG BRDF",
            "diffuse_transport": args.diffuse_transport.name(),
            "roughness_nm": sigma, "correlation_nm": tau,
            "view_deg": degrees(view), "light_deg": degrees(light), "azimuth_deg": degrees(args.azimuth),
            "wavelength_nm": grid,
            "R_smooth": smooth,
            "specular": kr, "specular_s": xs.iter().map(|x| x.1.specular_s).collect::<Vec<_>>(),
            "specular_p": xs.iter().map(|x| x.1.specular_p).collect::<Vec<_>>(),
            "diffuse_per_sr": kd, "diffuse_s_per_sr": xs.iter().map(|x| x.1.diffuse_s).collect::<Vec<_>>(),
            "diffuse_p_per_sr": xs.iter().map(|x| x.1.diffuse_p).collect::<Vec<_>>(),
            "series_terms_max": terms, "diffuse_error_bound_per_sr": bound,
        }));
    }
    let mut out = String::new();
    if csv {
        out.push_str(
            "wavelength_nm,R_smooth,specular,diffuse_per_sr,specular_s,specular_p,diffuse_s_per_sr,diffuse_p_per_sr\n",
        );
        for (i, (r, x)) in xs.iter().enumerate() {
            let _ = writeln!(
                out,
                "{},{},{},{},{},{},{},{}",
                grid[i],
                r,
                x.k_r(),
                x.k_d(),
                x.specular_s,
                x.specular_p,
                x.diffuse_s,
                x.diffuse_p
            );
        }
    } else {
        let _ = writeln!(out, "stack     {}", rough.stack);
        let _ = writeln!(
            out,
            "rough     substrate interface σ = {sigma} nm, τ = {tau} nm (HTSG, {}; max {terms} terms, error ≤ {bound:.1e} sr⁻¹; {} diffuse transport)",
            args.series_label(),
            args.diffuse_transport.name()
        );
        let _ = writeln!(
            out,
            "angles    view {}°, light {}°, azimuth {}°, unpolarised",
            deg(view),
            deg(light),
            deg(args.azimuth)
        );
        let _ = writeln!(out, "{:>10}  {:>10}  {:>12}  {:>12}", "λ (nm)", "R smooth", "k_r specular", "k_d (sr⁻¹)");
        for (i, (r, x)) in xs.iter().enumerate() {
            let _ = writeln!(out, "{:>10.2}  {:>10.7}  {:>12.7}  {:>12.7}", grid[i], r, x.k_r(), x.k_d());
        }
    }
    crate::output::write_stdout_bytes(out.as_bytes())?;
    Ok(())
}

/// `iridis thinfilm color … --roughness σ --correlation τ`: the colours of the smooth film, of the rough
/// film's specular part (`k_r`) and of its diffuse part (radiance factor `π k_d`).
pub fn color(
    stack: Stack,
    args: &RoughArgs,
    view: f64,
    grid: &[f64],
    illuminant: Illuminant,
    observer: Observer,
    json_out: bool,
) -> Result<()> {
    if args.light_angles.is_some() {
        bail!("--light-angles is for 'table'; use --light-angle here");
    }
    let rough = args.build(stack)?;
    let light = args.light_angle.unwrap_or(view);
    let c = iridis_api::rough::colours(&rough, view, light, args.azimuth, grid, illuminant, observer)?;
    let (smooth_film, smooth, spec, diff) = (c.smooth, c.smooth.reflected, c.specular, c.diffuse);
    let white = iridis_color::integrate::white_point(illuminant, observer);
    let reports = [
        ("smooth", "smooth film, reflected", super::color::colour_report(smooth, white)),
        ("specular", "rough film, specular k_r", super::color::colour_report(spec, white)),
        ("diffuse", "rough film, diffuse π·k_d", super::color::colour_report(diff, white)),
    ];
    if json_out {
        let conditions = json!({
            "roughness_nm": rough.htsg.roughness.sigma_nm(), "correlation_nm": rough.htsg.roughness.tau_nm(),
            "view_deg": degrees(view), "light_deg": degrees(light), "azimuth_deg": degrees(args.azimuth),
            "diffuse_transport": args.diffuse_transport.name(),
        });
        let transmitted = super::color::colour_report(smooth_film.transmitted, white);
        return crate::output::print_json(&super::thinfilm::film_colours_json(
            &reports[0].2,
            &transmitted,
            &reports[1].2,
            &reports[2].2,
            conditions,
        ));
    }
    let f = |v: &serde_json::Value| -> String {
        v.as_array()
            .map(|v| v.iter().map(|x| format!("{:.5}", x.as_f64().unwrap_or(f64::NAN))).collect::<Vec<_>>().join("  "))
            .unwrap_or_default()
    };
    crate::outln!("stack        {}", rough.stack)?;
    crate::outln!(
        "rough        σ = {} nm, τ = {} nm at the substrate (HTSG, {})",
        rough.htsg.roughness.sigma_nm(),
        rough.htsg.roughness.tau_nm(),
        args.series_label()
    )?;
    crate::outln!(
        "conditions   view {}°, light {}°, azimuth {}°, illuminant {illuminant}, CIE {observer} observer, {}–{} nm",
        deg(view),
        deg(light),
        deg(args.azimuth),
        grid[0],
        grid[grid.len() - 1]
    )?;
    for (_, name, r) in &reports {
        crate::outln!("{name}")?;
        crate::outln!("  XYZ        {}", f(&r["XYZ"]))?;
        crate::outln!("  L*a*b*     {}", f(&r["Lab"]))?;
        crate::outln!("  sRGB       {}   {}", f(&r["srgb"]), r["hex"].as_str().unwrap_or(""))?;
    }
    Ok(())
}

/// `iridis thinfilm table … --roughness σ --correlation τ`: Algorithm 2's view × light × wavelength table
/// as CSV (`view_deg,light_deg,wavelength_nm,specular,diffuse_per_sr`); `--plot` draws `π k_d` over view
/// angle × wavelength with the light at the view angle (the peak of the diffuse lobe).
pub fn table(
    stack: Stack,
    title: &str,
    args: &RoughArgs,
    angles: &str,
    grid: &[f64],
    output: Option<&Path>,
    plot: Option<&Path>,
) -> Result<()> {
    if args.light_angle.is_some() {
        bail!("--light-angle is for 'spectrum' and 'color'; the table takes --light-angles FROM:TO:STEP");
    }
    let parse = |s: &str, flag: &str| -> Result<Vec<f64>> {
        let v = parse_range(s, parse_angle_rad).map_err(|e| anyhow::anyhow!("{flag}: {e}"))?;
        if let Some(bad) = v.iter().find(|t| !(**t >= 0.0 && **t <= PI / 2.0 + 1e-12)) {
            bail!("{flag}: {}° is outside 0°–90°", deg(*bad));
        }
        Ok(v.iter().map(|t| (t.to_degrees() * 1e9).round() / 1e9).collect())
    };
    let views = parse(angles, "--angles")?;
    let lights = match &args.light_angles {
        Some(s) => parse(s, "--light-angles")?,
        None => views.clone(),
    };
    if views.len() * lights.len() * grid.len() > 50_000_000 {
        bail!("{} × {} × {} entries is too many for a table", views.len(), lights.len(), grid.len());
    }
    let rough = args.build(stack)?;
    let t0 = Instant::now();
    let t = rough.table(&views, &lights, grid, args.azimuth)?;
    let secs = t0.elapsed().as_secs_f64();
    eprintln!(
        "LSRS table: {} views × {} lights × {} wavelengths in {secs:.3} s ({:.2e} entries/s), ≤ {} series terms, diffuse error ≤ {:.1e} sr⁻¹",
        views.len(),
        lights.len(),
        grid.len(),
        (views.len() * lights.len() * grid.len()) as f64 / secs.max(1e-12),
        t.max_terms,
        t.max_bound
    );
    if let Some(p) = plot {
        let (w, h) = (grid.len() as u32, views.len() as u32);
        let mut vals = vec![0.0; views.len() * grid.len()];
        for (i, v) in views.iter().enumerate() {
            for (j, &wl) in grid.iter().enumerate() {
                let light = v.clamp(lights[0], lights[lights.len() - 1]);
                vals[i * grid.len() + j] = PI * t.lookup(v.to_radians(), light.to_radians(), wl)?.1;
            }
        }
        let max = vals.iter().copied().fold(0.0, f64::max).max(1e-12);
        let mut px = RgbImage::new(w, h);
        for i in 0..views.len() {
            for j in 0..grid.len() {
                px.put(j as u32, (views.len() - 1 - i) as u32, magma(vals[i * grid.len() + j] / max));
            }
        }
        let img = ImagePlot {
            title: format!("Diffuse π·k_d, light at the view angle: {title}"),
            x_label: "wavelength (nm)".into(),
            y_label: "view angle (°)".into(),
            x_range: (grid[0], grid[grid.len() - 1].max(grid[0] + 1e-9)),
            y_range: (views[0], views[views.len() - 1].max(views[0] + 1e-9)),
            pixels: &px,
            overlays: Vec::new(),
            colorbar: Some(ColorBar { label: "π·k_d".into(), min: 0.0, max, map: magma }),
            size: (1000, 640),
        }
        .render()?;
        crate::output::write_png_rgb8(p, img.width, img.height, &img.data)?;
        eprintln!("wrote {}", p.display());
    }
    let mut csv = Vec::with_capacity(views.len() * lights.len() * grid.len() * 60);
    t.write_csv(&mut csv)?;
    match output {
        Some(p) => {
            crate::output::write_bytes(p, &csv)?;
            eprintln!("wrote {}", p.display());
        }
        None => crate::output::write_stdout_bytes(&csv)?,
    }
    Ok(())
}

/// `iridis thinfilm bench --roughness σ --correlation τ [--stack …]`: speed of Algorithm 2's table, the
/// shared (factorised) generation against evaluating every entry directly (the algorithm as written), with
/// the largest difference between the two.
pub fn bench(stack: Stack, args: &RoughArgs, samples: usize, seconds: f64, json_out: bool) -> Result<()> {
    let rough = args.build(stack)?;
    let views = angle_grid(samples)?;
    let grid: Vec<f64> = (0..81).map(|i| 380.0 + 5.0 * i as f64).collect();
    let entries = (views.len() * views.len() * grid.len()) as f64;
    // Shared generation, repeated for at least `seconds`.
    let (mut runs, t0) = (0usize, Instant::now());
    let mut table = rough.table(&views, &views, &grid, args.azimuth)?;
    runs += 1;
    while t0.elapsed().as_secs_f64() < seconds {
        table = rough.table(&views, &views, &grid, args.azimuth)?;
        runs += 1;
    }
    let shared_s = t0.elapsed().as_secs_f64() / runs as f64;
    // Direct: every entry by `evaluate` (eq. 3.15–3.19 per entry), on a sample of the views for time.
    let t1 = Instant::now();
    let (mut n, mut max_rel, mut i) = (0usize, 0.0f64, 0usize);
    while i < views.len() && (t1.elapsed().as_secs_f64() < seconds || n == 0) {
        for (j, l) in views.iter().enumerate() {
            for (w, &wl) in grid.iter().enumerate() {
                let x = rough.evaluate(wl, views[i].to_radians(), l.to_radians(), args.azimuth)?;
                let kd = table.diffuse[(i * views.len() + j) * grid.len() + w];
                if x.k_d() > 0.0 {
                    max_rel = max_rel.max((kd - x.k_d()).abs() / x.k_d());
                }
                n += 1;
            }
        }
        i += 1;
    }
    let direct_per_s = n as f64 / t1.elapsed().as_secs_f64();
    let shared_per_s = entries / shared_s;
    let v = json!({
        "stack": rough.stack.to_string(),
        "roughness_nm": rough.htsg.roughness.sigma_nm(), "correlation_nm": rough.htsg.roughness.tau_nm(),
        "series": args.series_label(),
        "views": views.len(), "lights": views.len(), "wavelengths": grid.len(), "entries": entries,
        "table_seconds": shared_s, "table_entries_per_second": shared_per_s, "table_runs": runs,
        "direct_entries_per_second": direct_per_s, "direct_entries_timed": n,
        "speedup": shared_per_s / direct_per_s, "max_relative_difference": max_rel,
        "threads": 1,
    });
    if json_out {
        return crate::output::print_json(&v);
    }
    crate::outln!(
        "LSRS table (Algorithm 2), {}, σ {} nm, τ {} nm, {}",
        rough.stack,
        rough.htsg.roughness.sigma_nm(),
        rough.htsg.roughness.tau_nm(),
        args.series_label()
    )?;
    crate::outln!(
        "{} views × {} lights × {} wavelengths = {entries} entries, one thread",
        views.len(),
        views.len(),
        grid.len()
    )?;
    crate::outln!("  shared generation  {shared_s:.3} s per table  ({shared_per_s:.3e} entries/s, {runs} runs)")?;
    crate::outln!(
        "  direct evaluation  {direct_per_s:.3e} entries/s ({n} entries timed) → table {:.1} s",
        entries / direct_per_s
    )?;
    crate::outln!("  speed-up ×{:.1}; largest relative difference of k_d {max_rel:.1e}", shared_per_s / direct_per_s)?;
    Ok(())
}
