//! `iridis thinfilm profile` (where the light goes: absorption per layer, |E|² and absorption against depth)
//! and `iridis thinfilm fit` (fitting a stack to a measured spectrum), thin shells over
//! `iridis_thinfilm::field` and `iridis-filmfit`.

use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::Instant;

use anyhow::{bail, Context, Result};
use clap::Args as ClapArgs;
use iridis_filmfit::{fit, FitOptions, Quantity, ReadOptions, Spread, Template};
use iridis_plot::{LinePlot, Series};
use iridis_thinfilm::color::Polarization;
use iridis_thinfilm::depth::depth_profile;
use iridis_thinfilm::Stack;
use serde_json::json;

#[derive(Debug, ClapArgs)]
pub struct ProfileArgs {
    /// The stack, e.g. "air | Au 30nm | glass" (inc: layers: incoherent intensities, no interference, in them).
    #[arg(long)]
    pub stack: String,
    /// Vacuum wavelength (with unit).
    #[arg(long, value_parser = crate::args::length_nm)]
    pub wavelength: f64,
    /// Angle of incidence (0deg–90deg).
    #[arg(long, default_value = "0deg", value_parser = crate::args::angle_rad)]
    pub angle: f64,
    /// avg (unpolarised), s or p.
    #[arg(long, default_value = "avg")]
    pub polarization: String,
    /// Number of depth samples of the profile (from 100 nm above the stack to 100 nm into the substrate).
    #[arg(long, default_value_t = 400)]
    pub points: usize,
    /// The depth window of the profile, FROM:TO below the first interface (e.g. --depth=-20nm:200nm to see
    /// the films on a 1 mm slide); default 100 nm above the stack to 100 nm into the substrate.
    #[arg(long, value_name = "FROM:TO", allow_hyphen_values = true)]
    pub depth: Option<String>,
    /// Print JSON (absorption per layer and the profile).
    #[arg(long, conflicts_with = "csv")]
    pub json: bool,
    /// Print the profile as CSV (z_nm, medium, E2, absorption_per_nm, flux).
    #[arg(long)]
    pub csv: bool,
    /// Plot |E|² and the absorbed power density against depth (PNG).
    #[arg(long)]
    pub plot: Option<PathBuf>,
}

#[derive(Debug, ClapArgs)]
pub struct FitArgs {
    /// The measured spectrum: columns of wavelength and R, T, or psi and delta (degrees), separated by
    /// commas, tabs, semicolons or spaces, with or without a header ("Wavelength (nm),Reflectance (%)", …);
    /// what was read is printed (separator, columns, unit, percent).
    pub measured: PathBuf,
    /// The stack with free parameters {NAME=START:LOW..HIGH}, e.g. "air | SiO2 {d1=100nm:50nm..500nm} | Si".
    #[arg(long)]
    pub stack: String,
    /// Angle of incidence (0deg–90deg).
    #[arg(long, default_value = "0deg", value_parser = crate::args::angle_rad)]
    pub angle: f64,
    /// What was measured: R, T (unpolarised) or psi-delta (ellipsometry, degrees).
    #[arg(long, default_value = "R")]
    pub quantity: String,
    /// 1σ measurement uncertainty: a number (same for every point) or the name of a CSV column (for
    /// psi-delta two names, "spsi,sdelta"). The weights are 1/σ². Without it σ is estimated from the scatter.
    #[arg(long, conflicts_with = "weights")]
    pub sigma: Option<String>,
    /// Weights w = 1/σ² of the measured values: a number (the same for every point), the name of a CSV
    /// column ("w_psi,w_delta" for psi-delta), or a separate CSV file with wavelength_nm and w (w_psi and
    /// w_delta) in the measurement's rows. Equivalent to --sigma 1/√w.
    #[arg(long)]
    pub weights: Option<String>,
    /// Grid points per thickness range for the multi-start search (0: automatic, about one per 10 nm;
    /// 1: a single local fit from the start values).
    #[arg(long, default_value_t = 0)]
    pub grid: usize,
    /// The columns to fit, by header name or number from 1: wavelength then R (or T), or wavelength, psi,
    /// delta, e.g. --columns "Wavelength (nm),R sample" or --columns 1,3. Default: found from the header.
    #[arg(long, value_name = "WL,VALUE[,VALUE]")]
    pub columns: Option<String>,
    /// The values are in percent (default: detected from a "%" in the header or values above 1.5, and said).
    #[arg(long)]
    pub percent: bool,
    /// Fit only wavelengths from this one on (with unit, e.g. 400nm).
    #[arg(long, value_parser = crate::args::length_nm)]
    pub from: Option<f64>,
    /// Fit only wavelengths up to this one (with unit, e.g. 826nm).
    #[arg(long, value_parser = crate::args::length_nm)]
    pub to: Option<f64>,
    /// Plot measured against fitted (PNG).
    #[arg(long)]
    pub plot: Option<PathBuf>,
    /// Write the fitted curve as CSV (wavelength_nm, measured, fitted, residual).
    #[arg(long)]
    pub output: Option<PathBuf>,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
}

pub fn profile(a: ProfileArgs) -> Result<()> {
    crate::output::declare_opt("--plot", a.plot.as_deref(), &["png"])?;
    let stack = Stack::parse(&a.stack).map_err(|e| anyhow::anyhow!("{e}"))?;
    let pol = a.polarization.to_ascii_lowercase();
    let polarization = match pol.as_str() {
        "avg" => Polarization::Average,
        "s" => Polarization::S,
        "p" => Polarization::P,
        _ => bail!("--polarization '{}': use avg, s or p", a.polarization),
    };
    let window = match &a.depth {
        None => None,
        Some(w) => {
            let bad = || anyhow::anyhow!("--depth '{w}': write FROM:TO with units, e.g. --depth=-20nm:200nm");
            let (from, to) = w.split_once(':').ok_or_else(bad)?;
            match (crate::args::length_nm(from.trim()), crate::args::length_nm(to.trim())) {
                (Ok(f), Ok(t)) if f < t => Some((f, t)),
                (Ok(f), Ok(t)) => bail!("--depth {f} nm:{t} nm is empty: FROM must be above (less than) TO"),
                (Err(e), _) | (_, Err(e)) => bail!("--depth '{w}': {e}"),
            }
        }
    };
    if !(2..=1_000_000).contains(&a.points) {
        bail!("--points must be between 2 and 1000000");
    }
    // Coherent and mixed stacks alike (in inc: layers: incoherent Beer–Lambert beams, no interference).
    let d = depth_profile(&stack, a.wavelength, a.angle, polarization, a.points, window)?;
    // The energy balance is an identity of the flux formulas; more than rounding means a bug, not bad input.
    if d.balance.abs() > 1e-9 {
        bail!("internal error: R + T + ΣA − 1 = {:e} (please report with the stack)", d.balance);
    }
    let (r, t, sub, balance, depth) = (d.r, d.t, d.substrate, d.balance, d.depth_nm);
    let (layers, names) = (&d.layers, &d.layer_names);
    if let Some(path) = &a.plot {
        let ab: Vec<f64> = d.absorption_per_nm.iter().map(|v| 1000.0 * v).collect();
        let mut plot = LinePlot::new(
            format!("{}  at {} nm, {}°", super::thinfilm::stack_title(&a.stack), a.wavelength, deg(a.angle)),
            format!("depth below the first interface (nm); layers end at 0 and {depth} nm"),
            "|E|² (incident = 1); absorbed power (fraction per µm)",
        )
        .series(Series::new("|E|²", &d.z_nm, &d.e2))
        .series(Series::new("absorbed power density (1/µm)", &d.z_nm, &ab));
        plot.x_range = Some((d.z_nm[0], d.z_nm[d.z_nm.len() - 1]));
        let img = plot.render()?;
        crate::output::write_png_rgb8(path, img.width, img.height, &img.data)?;
        if !a.json && !a.csv {
            crate::outln!("wrote {}", path.display())?;
        }
    }
    if a.json {
        let prof = json!({
                "z_nm": d.z_nm, "medium": d.medium, "E2": d.e2, "absorption_per_nm": d.absorption_per_nm, "flux": d.flux,
        });
        return crate::output::print_json(&json!({
            "stack": stack.to_string(), "wavelength_nm": a.wavelength, "angle_deg": a.angle.to_degrees(),
            "polarization": pol, "R": r, "T": t, "layers": names, "A_layers": layers, "A_substrate": sub,
            "balance": balance, "profile": prof,
        }));
    }
    if a.csv {
        let mut out = String::from("z_nm,medium,E2,absorption_per_nm,flux\n");
        for i in 0..d.z_nm.len() {
            let _ = writeln!(out, "{},{},{},{},{}", d.z_nm[i], d.medium[i], d.e2[i], d.absorption_per_nm[i], d.flux[i]);
        }
        return crate::output::write_stdout_bytes(out.as_bytes());
    }
    crate::outln!("stack  {stack}")?;
    crate::outln!("{} nm at {}°, {}", a.wavelength, deg(a.angle), pol)?;
    crate::outln!("{:<40} {:>12}", "where the light goes", "fraction")?;
    crate::outln!("{:<40} {:>12.7}", "reflected (R)", r)?;
    for (i, (n, v)) in names.iter().zip(layers.iter()).enumerate() {
        crate::outln!("{:<40} {:>12.7}", format!("absorbed in layer {} ({n})", i + 1), v)?;
    }
    if sub > 0.0 {
        crate::outln!("{:<40} {:>12.7}", "absorbed in the substrate", sub)?;
    }
    crate::outln!("{:<40} {:>12.7}", "transmitted (T)", t)?;
    crate::outln!("{:<40} {:>12.1e}", "R + T + ΣA − 1", balance)?;
    Ok(())
}

pub fn fit_cmd(a: FitArgs) -> Result<()> {
    crate::output::declare_opt("--plot", a.plot.as_deref(), &["png"])?;
    crate::output::declare_opt("-o", a.output.as_deref(), &["csv"])?;
    let quantity: Quantity = a.quantity.parse()?;
    let template = Template::parse(&a.stack)?;
    let text = std::fs::read_to_string(&a.measured).with_context(|| format!("cannot read {}", a.measured.display()))?;
    let shown = a.measured.display().to_string();
    let reading = iridis_filmfit::read(&text, &shown, &read_options(&a, quantity), &|p| {
        std::fs::read_to_string(p).map_err(|e| e.to_string())
    })?;
    let data = &reading.data;
    if let Some(w) = iridis_thinfilm::sampling::check(&template.base, a.angle, &sorted(&data.wavelength_nm)) {
        eprintln!("warning: the measured wavelengths: {}", w.message);
    }
    let opt = FitOptions { angle_rad: a.angle, quantity, grid: a.grid, ..FitOptions::default() };
    let t0 = Instant::now();
    let r = fit(&template, data, &opt)?;
    let seconds = t0.elapsed().as_secs_f64();
    let params = &template.params;
    if let Some(path) = &a.output {
        let mut out = String::from("wavelength_nm,measured,fitted,residual\n");
        let k = quantity.width();
        for (i, w) in data.wavelength_nm.iter().enumerate() {
            for j in 0..k {
                let (m, f) = (data.values[i * k + j], r.fitted[i * k + j]);
                let _ = writeln!(out, "{w},{m},{f},{}", m - f);
            }
        }
        crate::output::write_bytes(path, out.as_bytes())?;
    }
    if let Some(path) = &a.plot {
        let k = quantity.width();
        let labels: &[&str] = if k == 2 { &["ψ (°)", "Δ (°)"] } else { &[quantity.name()] };
        let mut plot = LinePlot::new(
            format!("measured and fitted {}, χ²/dof = {:.3}", quantity.name(), r.reduced_chi2),
            "wavelength (nm)",
            if k == 2 { "ψ, Δ (degrees)" } else { "fraction of incident power" },
        );
        for (j, label) in labels.iter().enumerate() {
            let m: Vec<f64> = (0..data.wavelength_nm.len()).map(|i| data.values[i * k + j]).collect();
            let f: Vec<f64> = (0..data.wavelength_nm.len()).map(|i| r.fitted[i * k + j]).collect();
            let mut meas = Series::new(format!("measured {label}"), &data.wavelength_nm, &m);
            meas.emphasis = false;
            plot = plot.series(meas).series(Series::new(format!("fitted {label}"), &data.wavelength_nm, &f));
        }
        let img = plot.render()?;
        crate::output::write_png_rgb8(path, img.width, img.height, &img.data)?;
    }
    for (p, at) in params.iter().zip(&r.at_bound) {
        if *at {
            eprintln!(
                "warning: {} ended on a bound of its range {}..{}: widen the range; its uncertainty is not meaningful",
                p.name, p.lo, p.hi
            );
        }
    }
    if a.json {
        return crate::output::print_json(&json!({
            "stack": a.stack, "quantity": quantity.name(), "angle_deg": a.angle.to_degrees(),
            "names": r.names, "units": params.iter().map(|p| p.unit()).collect::<Vec<_>>(),
            "values": r.values, "sigma": r.sigma, "correlation": r.correlation,
            "chi2": r.chi2, "dof": r.dof, "reduced_chi2": r.reduced_chi2, "sigma_given": r.sigma_given,
            "at_bound": r.at_bound, "starts": r.starts_tried, "evaluations": r.evaluations, "jacobian": r.jacobian, "seconds": seconds,
            "fitted": r.fitted, "wavelength_nm": data.wavelength_nm, "measured": data.values,
            "read": { "columns": reading.columns, "percent": reading.percent, "notes": reading.notes },
        }));
    }
    crate::outln!("stack     {}", a.stack)?;
    crate::outln!(
        "data      {} ({} wavelengths, {} at {}°)",
        shown,
        data.wavelength_nm.len(),
        quantity.name(),
        deg(a.angle)
    )?;
    for note in &reading.notes {
        crate::outln!("read      {note}")?;
    }
    crate::outln!("{:<12} {:>16} {:>14}", "parameter", "value", "1σ")?;
    for (k, p) in params.iter().enumerate() {
        crate::outln!("{:<12} {:>16.6} {:>14.3e} {}", p.name, r.values[k], r.sigma[k], p.unit())?;
    }
    crate::outln!("χ² = {:.4} for {} degrees of freedom (χ²/dof = {:.4})", r.chi2, r.dof, r.reduced_chi2)?;
    if !r.sigma_given {
        crate::outln!(
            "no --sigma or --weights: χ² uses σ = 1 and the uncertainties are scaled by √(χ²/dof), i.e. σ is estimated from the scatter"
        )?;
    }
    if params.len() > 1 {
        crate::outln!("correlation")?;
        let mut head = format!("{:<12}", "");
        for p in params {
            let _ = write!(head, " {:>8}", p.name);
        }
        crate::outln!("{head}")?;
        for (k, p) in params.iter().enumerate() {
            let mut row = format!("{:<12}", p.name);
            for v in &r.correlation[k] {
                let _ = write!(row, " {v:>8.3}");
            }
            crate::outln!("{row}")?;
        }
    }
    crate::outln!(
        "{} starts searched, {} spectra evaluated, {} derivatives, {:.3} s",
        r.starts_tried,
        r.evaluations,
        r.jacobian,
        seconds
    )?;
    if let Some(p) = &a.plot {
        crate::outln!("wrote {}", p.display())?;
    }
    Ok(())
}

/// The reading options of the measured file, from the command line.
fn read_options(a: &FitArgs, quantity: Quantity) -> ReadOptions {
    let mut o = ReadOptions::new(quantity);
    o.columns = a.columns.clone();
    o.percent = a.percent.then_some(true);
    o.from_nm = a.from;
    o.to_nm = a.to;
    o.spread = match (&a.sigma, &a.weights) {
        (Some(s), _) => Some((s.clone(), Spread::Sigma)),
        (None, Some(w)) => Some((w.clone(), Spread::Weight)),
        (None, None) => None,
    };
    o
}

/// Degrees, rounded to 1e-6 (prints `30`, not `30.000000`).
fn deg(rad: f64) -> f64 {
    (rad.to_degrees() * 1e6).round() / 1e6
}

fn sorted(v: &[f64]) -> Vec<f64> {
    let mut v = v.to_vec();
    v.sort_by(f64::total_cmp);
    v
}
