//! `iridis grating`: order efficiencies of a height field taken as one unit cell of a grating (issue 27).

use anyhow::{bail, Result};
use clap::Args as ClapArgs;
use iridis_api::grating::{grating, Detector, GratingOptions};
use iridis_diffraction::geometry::direction;

use crate::args::{angle_rad, polar_azimuth, positive_length_nm, SurfaceOpts};
use crate::progress::Cli;

#[derive(Debug, ClapArgs)]
#[command(after_help = "\
The height field is one unit cell of a periodic surface: its extent is the period along x and y (or, with
--unit-cell auto, the scan's strongest period with its profile averaged along the ridges: what a rigorous
solver needs of a real scan), and the light leaves in discrete orders (m, n), ω_r,xy = −ω_i,xy + (m λ/Lx, n λ/Ly) (in the plane of incidence
m λ/d = sin θ_i − sin θ_r, θ_r positive on the specular side). A patch whose rows are all the same is a 1-D
grating along x. Efficiencies are fractions of the incident power in each propagating order, for TE (s) and
TM (p) light and unpolarised; their sum is the hemispherical reflectance (an integrating sphere); --detector
adds what a detector of that acceptance sees (a goniometer, a fibre spectrometer).

Method kirchhoff (default): Stam's scalar model, the one behind iridis' BRDFs (docs/diffraction.md,
\"Order efficiencies\"). Its obliquity factor as printed creates energy at oblique light; by default the
channel matrix is scaled so that energy and reciprocity hold exactly (--normalisation energy; kirchhoff
keeps the printed factor). Method rigorous: Maxwell's equations by the C-method (docs/rigorous.md), TE and
TM apart, transmitted orders into a transparent substrate, the number of orders raised until every
efficiency changes by less than 1e-3 (relative; the estimate is printed). --compare runs both and says how
far the scalar model is from the rigorous one on this cell: the worst relative error of any order above
0.1 %, of the total, and CIEDE2000 of the colours of the diffracted and the mirror light.

The reflector is --material (a library name such as gold or keratin, n=1.5, n=0.2+3.4i or file:PATH; exact
Fresnel per polarisation, default n=1.5) or any --fresnel source (schlick:1.5 has no polarised form).

Examples:
  iridis grating builtin:sine --light 30deg --wavelength 550nm
  iridis grating builtin:blazed --light 0deg --from 400nm --to 700nm --step 50nm --material gold --json
  iridis grating 'builtin:sine?size=1um&pixel=10nm' --light 75deg --wavelength 500nm --normalisation kirchhoff
  iridis grating 'builtin:sine?size=1um&pixel=10nm' --light 20deg --from 400nm --to 700nm --step 10nm --detector 10deg,180deg --acceptance 2deg
  iridis grating 'builtin:sine?size=1100nm&pixel=10nm' --method rigorous --light 30deg --wavelength 550nm --material gold
  iridis grating 'builtin:sine?size=1100nm&pixel=10nm' --compare --light 0deg --from 400nm --to 700nm --step 50nm
  iridis grating 'builtin:elaphe?size=10um&pixel=50nm' --unit-cell auto --compare --light 0deg --from 380nm --to 780nm --step 20nm
  iridis grating strip.png --pixel-size 50nm --max-height 250nm --light 75deg --wavelength 600nm")]
pub struct GratingArgs {
    /// The unit cell: a height field (file or builtin:NAME) whose extent is the period.
    pub surface: String,
    /// Light direction θ[,φ] (towards the light).
    #[arg(long, default_value = "0deg")]
    pub light: String,
    /// One wavelength (instead of --from/--to/--step).
    #[arg(long, value_parser = positive_length_nm, conflicts_with_all = ["from", "to", "step"])]
    pub wavelength: Option<f64>,
    /// First wavelength of a spectrum.
    #[arg(long, value_parser = positive_length_nm)]
    pub from: Option<f64>,
    /// Last wavelength of a spectrum.
    #[arg(long, value_parser = positive_length_nm)]
    pub to: Option<f64>,
    /// Wavelength step of a spectrum.
    #[arg(long, value_parser = positive_length_nm, default_value = "10nm")]
    pub step: f64,
    /// The model: kirchhoff (Stam's scalar model) or rigorous (Maxwell's equations, the C-method).
    #[arg(long, default_value = "kirchhoff")]
    pub method: String,
    /// Run both models and report how far the scalar one is from the rigorous one on this cell.
    #[arg(long, conflicts_with = "method")]
    pub compare: bool,
    /// The medium under the relief: a library name (gold, keratin, …), n=1.5, n=0.2+3.4i or file:PATH
    /// [default: n=1.5].
    #[arg(long)]
    pub material: Option<String>,
    /// Instead of --material, any Fresnel source: schlick[:N], index:N[+Ki], gold or stack:STACK.
    #[arg(long)]
    pub fresnel: Option<String>,
    /// energy (the channel matrix scaled so that energy and reciprocity hold) or kirchhoff (as printed).
    #[arg(long, default_value = "energy")]
    pub normalisation: String,
    /// A detector's direction θ[,φ]: its reflectance is the orders inside its acceptance cone.
    #[arg(long)]
    pub detector: Option<String>,
    /// The unit cell: whole (the patch, its extent the period) or auto (the scan's strongest period, its
    /// profile averaged along the ridges: a 1-D grating at that orientation).
    #[arg(long, value_name = "whole|auto", default_value = "whole")]
    pub unit_cell: String,
    /// Half-angle of the detector's acceptance cone.
    #[arg(long, value_parser = angle_rad, default_value = "2deg")]
    pub acceptance: f64,
    /// Print JSON: every order's efficiency per wavelength, the totals, the detector's spectrum.
    #[arg(long)]
    pub json: bool,
    /// List only the orders of at least this efficiency (a fraction, or a percentage: 1e-3, 0.1%), with the
    /// mirror order and those the detector sees; the totals and colours still count every order (a large
    /// scan as one unit cell has hundreds of thousands of orders a wavelength). Default: every order.
    #[arg(long, value_name = "FRACTION", value_parser = fraction)]
    pub orders_above: Option<f64>,
    #[command(flatten)]
    pub surface_opts: SurfaceOpts,
}

pub fn run(a: GratingArgs) -> Result<()> {
    let (t, p) = polar_azimuth("light", &a.light)?;
    let wavelengths_nm = match (a.wavelength, a.from, a.to) {
        (Some(l), _, _) => vec![l],
        (None, Some(f), Some(t)) => iridis_color::spectrum::uniform_grid(f, t, a.step)?,
        (None, None, None) => vec![550.0],
        _ => bail!("give --wavelength, or --from and --to (with --step) for a spectrum"),
    };
    let detector = match &a.detector {
        Some(d) => {
            let (dt, dp) = polar_azimuth("detector", d)?;
            Some(Detector { direction: direction(dt, dp), acceptance_rad: a.acceptance })
        }
        None => None,
    };
    let opts = GratingOptions {
        method: a.method.parse()?,
        light: direction(t, p),
        wavelengths_nm,
        material: a.material.clone(),
        fresnel: a.fresnel.clone(),
        normalisation: a.normalisation.parse()?,
        detector,
        unit_cell_auto: match a.unit_cell.as_str() {
            "auto" => true,
            "whole" => false,
            other => bail!("--unit-cell '{other}': expected whole (the patch) or auto (the dominant period)"),
        },
        orders_above: a.orders_above.unwrap_or(0.0),
    };
    let source = iridis_api::surface::Source::Spec(a.surface.clone());
    if a.compare {
        return compare(&a, &source, opts);
    }
    let g = grating(&source, &a.surface_opts.options(), &opts, &Cli)?;
    if a.json {
        return crate::output::print_json(&g.to_json());
    }
    crate::outln!(
        "{} · {} · unit cell {:.1} × {:.1} nm · light θ {:.2}° φ {:.2}° · {}{}",
        g.surface,
        g.method.name(),
        g.periods_nm.0,
        g.periods_nm.1,
        t.to_degrees(),
        p.to_degrees(),
        g.reflector,
        match g.method {
            iridis_api::grating::GratingMethod::Kirchhoff => format!(" · normalisation {}", g.normalisation.name()),
            iridis_api::grating::GratingMethod::Rigorous => String::new(),
        }
    )?;
    crate::outln!("efficiencies in % of the incident power; TE = s, TM = p")?;
    if let [one] = g.answers.as_slice() {
        crate::outln!("λ = {} nm", one.wavelength_nm)?;
        crate::outln!("     m      n   θr (deg)   φr (deg)      TE (%)      TM (%)   unpol. (%)")?;
        let shown = |o: &&iridis_diffraction::grating::OrderEfficiency| o.efficiency.unpolarized >= 1e-6;
        for o in one.orders.iter().filter(shown) {
            crate::outln!(
                "{:6} {:6} {:10.3} {:10.3} {:11.4} {:11.4} {:12.4}",
                o.m,
                o.n,
                o.theta_deg,
                o.phi_deg,
                100.0 * o.efficiency.te,
                100.0 * o.efficiency.tm,
                100.0 * o.efficiency.unpolarized
            )?;
        }
        let hidden = one.orders.len() - one.orders.iter().filter(shown).count();
        if hidden > 0 {
            crate::outln!("({hidden} orders below 0.0001 % not shown; --json lists every order)")?;
        }
        let r = one.reflected_total;
        crate::outln!(
            "total reflected  TE {:.4} %  TM {:.4} %  unpolarised {:.4} %  ({} orders)",
            100.0 * r.te,
            100.0 * r.tm,
            100.0 * r.unpolarized,
            one.orders.len()
        )?;
        if let Some(t) = one.transmitted_total {
            crate::outln!(
                "total transmitted  TE {:.4} %  TM {:.4} %  unpolarised {:.4} %  ({} orders; --json lists them)",
                100.0 * t.te,
                100.0 * t.tm,
                100.0 * t.unpolarized,
                one.transmitted_orders.len()
            )?;
        }
        if let Some(err) = one.convergence["estimated_error"].as_f64() {
            crate::outln!(
                "converged: orders ±{}, estimated error {:.1e} (tolerance {:.0e}){}",
                one.convergence["orders"][0],
                err,
                one.convergence["tolerance"].as_f64().unwrap_or(f64::NAN),
                if one.convergence["met"] == serde_json::json!(true) { "" } else { " — NOT met" }
            )?;
        }
        if let Some(d) = g.detector_reflectance(one) {
            crate::outln!(
                "detector ({}, ±{:.2}°)  {:.4} %",
                a.detector.as_deref().unwrap_or(""),
                a.acceptance.to_degrees(),
                100.0 * d
            )?;
        }
        return Ok(());
    }
    let det = if g.detector.is_some() { "  detector (%)" } else { "" };
    crate::outln!("  λ (nm)   total R (%)   TE (%)    TM (%){det}   strongest orders (m,n): unpol. %")?;
    for ans in &g.answers {
        let r = ans.reflected_total;
        let mut strongest: Vec<_> = ans.orders.iter().collect();
        strongest.sort_by(|x, y| y.efficiency.unpolarized.total_cmp(&x.efficiency.unpolarized));
        let list: Vec<String> = strongest
            .iter()
            .take(4)
            .map(|o| format!("({},{}): {:.3}", o.m, o.n, 100.0 * o.efficiency.unpolarized))
            .collect();
        let d = g.detector_reflectance(ans).map(|d| format!("  {:12.4}", 100.0 * d)).unwrap_or_default();
        crate::outln!(
            "{:8.1}  {:11.4}  {:8.4}  {:8.4}{d}   {}",
            ans.wavelength_nm,
            100.0 * r.unpolarized,
            100.0 * r.te,
            100.0 * r.tm,
            list.join("  ")
        )?;
    }
    if let Some(c) = g.colours() {
        let hex = |x| iridis_api::color::colour_report(x, c.white)["hex"].as_str().unwrap_or("").to_string();
        crate::outln!(
            "colours under D65 (unpolarised): mirror order {} (Y {:.4}), diffracted orders {} (Y {:.4}, {:.2} % of the \
             reflected light), all orders {} (Y {:.4})",
            hex(c.specular),
            c.specular.y,
            hex(c.diffracted),
            c.diffracted.y,
            100.0 * c.diffracted_share(),
            hex(c.reflected),
            c.reflected.y
        )?;
    }
    Ok(())
}

/// `--compare`: both models on the same cell, and the scalar model's error.
fn compare(a: &GratingArgs, source: &iridis_api::surface::Source, opts: GratingOptions) -> Result<()> {
    use iridis_api::grating::{scalar_error, GratingMethod};
    let surface = a.surface_opts.options();
    let scalar = grating(source, &surface, &GratingOptions { method: GratingMethod::Kirchhoff, ..opts.clone() }, &Cli)?;
    let rigorous = grating(source, &surface, &GratingOptions { method: GratingMethod::Rigorous, ..opts }, &Cli)?;
    let e = scalar_error(&scalar, &rigorous);
    if a.json {
        return crate::output::print_json(&e.to_json(&scalar, &rigorous));
    }
    crate::outln!(
        "{} · unit cell {:.1} × {:.1} nm · {} · the scalar (Kirchhoff) model against the rigorous one",
        scalar.surface,
        scalar.periods_nm.0,
        scalar.periods_nm.1,
        rigorous.reflector
    )?;
    crate::outln!("     λ (nm)      m      n   scalar (%)   rigorous (%)   relative error (unpolarised)")?;
    for &(l, m, n, k, r) in &e.orders {
        if r.unpolarized < 1e-5 && k.unpolarized < 1e-5 {
            continue;
        }
        let rel = if r.unpolarized > e.floor {
            format!("{:+.1} %", 100.0 * (k.unpolarized - r.unpolarized) / r.unpolarized)
        } else {
            "(below 0.1 %)".into()
        };
        crate::outln!("{l:11.1} {m:6} {n:6} {:12.4} {:14.4}   {rel}", 100.0 * k.unpolarized, 100.0 * r.unpolarized)?;
    }
    crate::outln!(
        "worst relative error of an order above {:.1} %: TE {:.1} %, TM {:.1} %, unpolarised {:.1} %{}; of the total \
         reflectance {:.1} %",
        100.0 * e.floor,
        100.0 * e.worst.te,
        100.0 * e.worst.tm,
        100.0 * e.worst.unpolarized,
        e.worst_at.map_or(String::new(), |(l, m, n)| format!(" (order ({m},{n}) at {l:.0} nm)")),
        100.0 * e.total
    )?;
    if let (Some(d), Some(s)) = (e.delta_e_diffracted, e.delta_e_specular) {
        crate::outln!("colour difference (CIEDE2000, D65): diffracted light {d:.2}, mirror order {s:.2}")?;
    }
    Ok(())
}

/// A fraction from 0 up to 1, written as a number (`1e-3`) or a percentage (`0.1%`).
fn fraction(s: &str) -> Result<f64, String> {
    let t = s.trim();
    let v = match t.strip_suffix('%') {
        Some(p) => p.trim().parse::<f64>().map(|v| v / 100.0),
        None => t.parse::<f64>(),
    }
    .map_err(|_| format!("'{s}': expected a fraction (1e-3) or a percentage (0.1%)"))?;
    if v.is_finite() && (0.0..1.0).contains(&v) {
        Ok(v)
    } else {
        Err(format!("'{s}': the efficiency must be from 0 up to 1 (100 %)"))
    }
}
