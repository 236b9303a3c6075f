//! What `iridis grating` prints: the order efficiencies of a unit cell as a table (one wavelength: every order;
//! a spectrum: totals and the strongest orders a wavelength, and the colours), and `--compare`'s run of both
//! models with the scalar model's error. The numbers are [`crate::grating`]'s.

use std::fmt::Write as _;

use anyhow::{bail, Result};
use serde_json::Value;

use crate::grating::{grating, scalar_error, Grating, GratingMethod, GratingOptions, ScalarError};
use crate::report::Report;
use crate::surface::{Source, SurfaceOptions};

/// The table `iridis grating` prints; `light` is θ, φ (radians), `detector` the `--detector` text as given.
pub fn grating_text(g: &Grating, light: (f64, f64), detector: Option<&str>, acceptance_rad: f64) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{} · {} · unit cell {:.1} × {:.1} nm · light θ {:.2}° φ {:.2}° · {}{}",
        g.surface,
        g.method.name(),
        g.periods_nm.0,
        g.periods_nm.1,
        light.0.to_degrees(),
        light.1.to_degrees(),
        g.reflector,
        match g.method {
            GratingMethod::Kirchhoff => format!(" · normalisation {}", g.normalisation.name()),
            GratingMethod::Rigorous => String::new(),
        }
    );
    s += "efficiencies in % of the incident power; TE = s, TM = p\n";
    if let [one] = g.answers.as_slice() {
        let _ = writeln!(s, "λ = {} nm", one.wavelength_nm);
        s += "     m      n   θr (deg)   φr (deg)      TE (%)      TM (%)   unpol. (%)\n";
        let shown = |o: &&iridis_diffraction::grating::OrderEfficiency| o.efficiency.unpolarized >= 1e-6;
        for o in one.orders.iter().filter(shown) {
            let _ = writeln!(
                s,
                "{:6} {:6} {:10.3} {:10.3} {:11.4} {:11.4} {:12.4}",
                o.m,
                o.n,
                o.theta_deg,
                // An order in the plane of incidence beyond the normal has φ = ±1e-15 or so: 0.000, not −0.000.
                if o.phi_deg.abs() < 5e-4 { 0.0 } else { o.phi_deg },
                100.0 * o.efficiency.te,
                100.0 * o.efficiency.tm,
                100.0 * o.efficiency.unpolarized
            );
        }
        let hidden = one.orders.len() - one.orders.iter().filter(shown).count();
        let plural = |n: usize| if n == 1 { "order" } else { "orders" };
        if hidden > 0 {
            let _ = writeln!(s, "({hidden} {} below 0.0001 % not shown; --json lists every order)", plural(hidden));
        }
        if one.unlisted > 0 {
            // --orders-above: the totals count them, no list holds them (an audit found them missing in silence).
            let _ = writeln!(
                s,
                "({} {} below --orders-above {} not listed, in the totals)",
                one.unlisted,
                plural(one.unlisted),
                g.orders_above
            );
        }
        let r = one.reflected_total;
        let counted = one.orders.len() + one.unlisted;
        let _ = writeln!(
            s,
            "total reflected  TE {:.4} %  TM {:.4} %  unpolarised {:.4} %  ({counted} {})",
            100.0 * r.te,
            100.0 * r.tm,
            100.0 * r.unpolarized,
            plural(counted)
        );
        if let Some(t) = one.transmitted_total {
            let _ = writeln!(
                s,
                "total transmitted  TE {:.4} %  TM {:.4} %  unpolarised {:.4} %  ({} {}; --json lists them)",
                100.0 * t.te,
                100.0 * t.tm,
                100.0 * t.unpolarized,
                one.transmitted_orders.len(),
                plural(one.transmitted_orders.len())
            );
        }
        if one.convergence.get("met").is_some() {
            let c = &one.convergence;
            let err = c["estimated_error"].as_f64().unwrap_or(f64::NAN);
            let repeats = |k: usize| c["cell_repeats"][k].as_u64().unwrap_or(1);
            let on = match (repeats(0), repeats(1)) {
                (1, 1) => String::new(),
                (kx, ky) => format!(" on one of the cell's {kx} × {ky} exact repeats (orders numbered in the cell's)"),
            };
            let energy = c["energy_error"].as_f64().map_or(String::new(), |e| format!(", |R + T − 1| {e:.1e}"));
            // A truncation that could not grow past the propagating orders was compared with itself: no estimate.
            let untested = crate::grating::error_not_estimated(c);
            let tolerance = c["tolerance"].as_f64().unwrap_or(f64::NAN);
            let orders = &c["orders"][0];
            if untested {
                // Its "estimate" is a comparison of one truncation with itself (5.6e-16): not printed.
                let _ = writeln!(
                    s,
                    "convergence NOT met: orders ±{orders}{on}, the truncation could not grow beyond the propagating \
                     orders, so the error is not estimated{energy} (tolerance {tolerance:.0e})"
                );
            } else {
                let head = if c["met"] == Value::Bool(true) { "converged" } else { "convergence NOT met" };
                let _ = writeln!(
                    s,
                    "{head}: orders ±{orders}{on}, estimated error {err:.1e}{energy} (tolerance {tolerance:.0e})"
                );
            }
        }
        if let Some(d) = g.detector_reflectance(one) {
            let _ = writeln!(
                s,
                "detector ({}, ±{:.2}°)  {:.4} %",
                detector.unwrap_or(""),
                acceptance_rad.to_degrees(),
                100.0 * d
            );
        }
        return s;
    }
    let det = if g.detector.is_some() { "  detector (%)" } else { "" };
    if g.detector.is_some() {
        // Where the detector column's detector is (it was said with one wavelength only).
        let _ = writeln!(
            s,
            "detector at {}, acceptance ±{:.2}°: the orders inside its cone",
            detector.unwrap_or(""),
            acceptance_rad.to_degrees()
        );
    }
    let _ = writeln!(s, "  λ (nm)   total R (%)   TE (%)    TM (%){det}   strongest orders (m,n): unpol. %");
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
        let _ = writeln!(
            s,
            "{:8.1}  {:11.4}  {:8.4}  {:8.4}{d}   {}",
            ans.wavelength_nm,
            100.0 * r.unpolarized,
            100.0 * r.te,
            100.0 * r.tm,
            list.join("  ")
        );
    }
    if let Some(c) = g.colours() {
        let hex = |x| crate::color::colour_report(x, c.white)["hex"].as_str().unwrap_or("").to_string();
        let _ = writeln!(
            s,
            "colours under D65, CIE 1931 (unpolarised; Y = 1 a perfect white): mirror order {} (Y {:.4}), diffracted \
             orders {} (Y {:.4}, {:.2} % of the reflected light), all orders {} (Y {:.4})",
            hex(c.specular),
            c.specular.y,
            hex(c.diffracted),
            c.diffracted.y,
            100.0 * c.diffracted_share(),
            hex(c.reflected),
            c.reflected.y
        );
    }
    s
}

/// The longest 1-D period, in shortest wavelengths, on which [`grating_checked`] solves Maxwell's equations
/// unasked: ~60 orders each side over n = 1.5, milliseconds a wavelength.
pub const CHECKED_PERIOD_IN_WAVELENGTHS: f64 = 24.0;
/// How many of the wavelengths [`grating_checked`] solves Maxwell's equations at.
pub const CHECKED_WAVELENGTHS: usize = 5;

/// `iridis grating`: [`grating`], and for the scalar model on a 1-D cell whose rigorous solve is cheap
/// ([`CHECKED_PERIOD_IN_WAVELENGTHS`]), its error against Maxwell's equations on the same cell, warned where above
/// the threshold at which its numbers are not to be trusted (a 1 µm sine at 89.9° light: 8.5 % reflected
/// where Maxwell's equations give 98.9 %, in silence). A crossed or longer cell, or a `--fresnel` the rigorous
/// method has no equivalent of, is not checked (`--compare` measures it).
pub fn grating_checked(
    source: &Source,
    surface: &SurfaceOptions,
    opts: &GratingOptions,
    report: &dyn Report,
) -> Result<Grating> {
    let g = grating(source, surface, opts, report)?;
    let lambda_min = opts.wavelengths_nm.iter().copied().fold(f64::INFINITY, f64::min);
    let period = match g.lines {
        iridis_diffraction::grating::Lines::AlongX => g.periods_nm.0,
        iridis_diffraction::grating::Lines::AlongY => g.periods_nm.1,
        iridis_diffraction::grating::Lines::Crossed => return Ok(g),
    };
    if opts.method != GratingMethod::Kirchhoff
        || opts.fresnel.is_some()
        || period > CHECKED_PERIOD_IN_WAVELENGTHS * lambda_min
    {
        return Ok(g);
    }
    // At most five wavelengths, spread over the range with its ends (a deep cell's solve takes ~0.5 s each).
    let all = &opts.wavelengths_nm;
    let checked: Vec<f64> = if all.len() <= CHECKED_WAVELENGTHS {
        all.clone()
    } else {
        let last = (all.len() - 1) as f64;
        let k = (CHECKED_WAVELENGTHS - 1) as f64;
        (0..CHECKED_WAVELENGTHS).map(|i| all[(i as f64 * last / k).round() as usize]).collect()
    };
    // `--compare` on those wavelengths, quietly; its orders judged where either model would list them. A
    // rigorous solve that fails (a Rayleigh anomaly's truncation, …) leaves the scalar answer as it was. Five
    // wavelengths make no colour: the orders' efficiencies only.
    let subset = GratingOptions { wavelengths_nm: checked.clone(), detector: None, ..opts.clone() };
    let Ok(GratingComparison { error: e, .. }) = compare(source, surface, &subset, &crate::report::Quiet) else {
        return Ok(g);
    };
    if e.worst.unpolarized > crate::grating::SCALAR_WARN_RELATIVE {
        report.warn(&format!(
            "the scalar (Kirchhoff) model is off by up to {:.0} % in an order's efficiency{} and {:.1} % in the total \
             reflectance against Maxwell's equations on this cell (the C-method, same light and material{}): above \
             the {:.0} % at which its numbers are not to be trusted; --method rigorous gives Maxwell's, --compare \
             lists both",
            100.0 * e.worst.unpolarized,
            e.worst_at.map_or(String::new(), |(l, m, n)| format!(" (order ({m},{n}) at {l:.0} nm)")),
            100.0 * e.total,
            if checked.len() < all.len() {
                format!(", at {} of the {} wavelengths", checked.len(), all.len())
            } else {
                String::new()
            },
            100.0 * crate::grating::SCALAR_WARN_RELATIVE
        ));
    }
    Ok(g)
}

/// `iridis grating --compare`: both models on the same cell, and the scalar model's error.
#[derive(Debug)]
pub struct GratingComparison {
    pub scalar: Grating,
    pub rigorous: Grating,
    pub error: ScalarError,
}

/// Runs the scalar (Kirchhoff) and the rigorous model on the cell of `opts` (its method is ignored).
pub fn compare(
    source: &Source,
    surface: &SurfaceOptions,
    opts: &GratingOptions,
    report: &dyn Report,
) -> Result<GratingComparison> {
    if opts.detector.is_some() {
        bail!(
            "--detector would be ignored: --compare sets the two models' orders side by side; for what a detector \
             sees, run without --compare, once with each --method"
        );
    }
    // The CLI's parser refuses the pair as well; Python's keywords reach here.
    if opts.method != GratingMethod::Kirchhoff {
        bail!("--method would be ignored: --compare runs both the scalar and the rigorous method");
    }
    // Every order of both models, then judged where either would list it under --orders-above: the lists alone
    // paired only the orders both listed, and missed one listed by the scalar model at 2 % (Maxwell: 0.5 %).
    let every = GratingOptions { orders_above: 0.0, ..opts.clone() };
    let scalar =
        grating(source, surface, &GratingOptions { method: GratingMethod::Kirchhoff, ..every.clone() }, report)?;
    let rigorous = grating(
        source,
        surface,
        &GratingOptions { method: GratingMethod::Rigorous, normalisation: None, ..every },
        report,
    )?;
    let error = scalar_error(&scalar, &rigorous).judged_above(opts.orders_above);
    Ok(GratingComparison { scalar, rigorous, error })
}

impl GratingComparison {
    /// As `iridis grating --compare --json` prints it (keys in docs/json.md).
    pub fn to_json(&self) -> Value {
        self.error.to_json(&self.scalar, &self.rigorous)
    }

    /// The table `iridis grating --compare` prints.
    pub fn text(&self) -> String {
        let (e, scalar, rigorous) = (&self.error, &self.scalar, &self.rigorous);
        let mut s = String::new();
        let _ = writeln!(
            s,
            "{} · unit cell {:.1} × {:.1} nm · {} · the scalar (Kirchhoff) model against the rigorous one",
            scalar.surface, scalar.periods_nm.0, scalar.periods_nm.1, rigorous.reflector
        );
        s += "     λ (nm)      m      n   scalar (%)   rigorous (%)   relative error (unpolarised)\n";
        for &(l, m, n, k, r) in &e.orders {
            if r.unpolarized < 1e-5 && k.unpolarized < 1e-5 {
                continue;
            }
            let rel = match crate::grating::relative_error(k.unpolarized, r.unpolarized, e.floor) {
                Some(x) if r.unpolarized < e.floor => {
                    format!("{:+.1} % (of the {} % floor: Maxwell's is below it)", 100.0 * x, 100.0 * e.floor)
                }
                Some(x) => format!("{:+.1} %", 100.0 * x),
                None => format!("(both below {} %)", 100.0 * e.floor),
            };
            let _ = writeln!(
                s,
                "{l:11.1} {m:6} {n:6} {:12.4} {:14.4}   {rel}",
                100.0 * k.unpolarized,
                100.0 * r.unpolarized
            );
        }
        let _ = writeln!(
            s,
            "worst relative error of an order either model puts above {:.1} %: unpolarised {:.1} %{}, TE {:.1} %, TM \
             {:.1} % (each at its own worst order); of the total reflectance {:.1} %",
            100.0 * e.floor,
            100.0 * e.worst.unpolarized,
            e.worst_at.map_or(String::new(), |(l, m, n)| format!(" (order ({m},{n}) at {l:.0} nm)")),
            100.0 * e.worst.te,
            100.0 * e.worst.tm,
            100.0 * e.total
        );
        match (e.delta_e_diffracted, e.delta_e_specular) {
            (Some(d), Some(sp)) => {
                let _ =
                    writeln!(s, "colour difference (CIEDE2000, D65): diffracted light {d:.2}, mirror order {sp:.2}");
            }
            // Said, not left out: at --step 20nm the line vanished without a word.
            _ => {
                let _ = writeln!(
                    s,
                    "colour difference: not computed (the wavelengths must span 380–780 nm in steps of at most {} nm)",
                    crate::grating::COLOUR_STEP_NM
                );
            }
        }
        s
    }
}
