//! The validity map of docs/diffraction.md ("When can I trust the scalar model?"): how far the scalar (Kirchhoff,
//! energy-normalised: what iridis' BRDFs use) order efficiencies are from Maxwell's equations (the C-method of
//! `iridis-rigorous`) over depth/period, wavelength/period, incidence and polarisation, for a sine, a blazed
//! profile and the built-in skins' profiles averaged along their ridges, on a metal and on glass; then colours
//! (CIEDE2000 of the diffracted and the mirror light over 380–780 nm) on keratin, for the same profiles scaled
//! and for the two skins at their own period and depth.
//!
//!     cargo run --release -p iridis-api --example validity_map > /tmp/validity_map.md
//!
//! Every comparison is the library's: [`iridis_api::grating::grating`] with each method on the same unit cell
//! and light, compared by [`iridis_api::grating::scalar_error`] — what `iridis grating --compare` prints. Prints
//! Markdown on stdout, progress on stderr; about 35 s on 2 cores (2026-11-29).

use std::f64::consts::TAU;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use anyhow::{Context, Result};
use iridis_api::grating::{averaged_unit_cell, grating, scalar_error, GratingMethod, GratingOptions, ScalarError};
use iridis_api::surface::{Source, SurfaceOptions};
use iridis_api::Quiet;
use iridis_diffraction::Patch;
use num_complex::Complex64;
use rayon::prelude::*;

/// The period of the dimensionless map (nm); only ratios to it matter.
const PERIOD: f64 = 1000.0;
/// Depth a/Λ: half the profile's peak-to-valley over the period (a sine `a sin Kx` has depth a/Λ).
const DEPTHS: [f64; 8] = [0.005, 0.01, 0.02, 0.05, 0.1, 0.15, 0.2, 0.3];
const LAMBDAS: [f64; 4] = [0.3, 0.5, 0.7, 0.9];
const THETAS: [f64; 4] = [0.0, 30.0, 60.0, 75.0];
/// (name, `--material`): a metal of permittivity −20 + 1i (silver-like in the visible) and glass.
const MEDIA: [(&str, &str); 2] = [("metal ε = −20 + 1i", "n=0.11178+4.47494i"), ("glass n = 1.5", "n=1.5")];
/// The bound of the stated rule (relative error of an order's efficiency).
const BOUNDS: [f64; 2] = [0.1, 0.2];
/// Depths of the colour table (keratin, Λ = 1000 nm, 380–780 nm).
const COLOUR_DEPTHS: [f64; 4] = [0.01, 0.02, 0.05, 0.1];

/// A profile over one period: zero mean, half peak-to-valley 1 (so `a · unit` has depth `a`).
struct Shape {
    name: String,
    unit: Vec<f64>,
    note: String,
}

/// Zero mean, half peak-to-valley 1.
fn normalise(v: Vec<f64>) -> Vec<f64> {
    let mean = v.iter().sum::<f64>() / v.len() as f64;
    let (lo, hi) = v.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| (a.min(x), b.max(x)));
    v.iter().map(|x| (x - mean) / (0.5 * (hi - lo))).collect()
}

fn sine() -> Shape {
    let unit = (0..256).map(|i| (TAU * i as f64 / 256.0).sin()).collect();
    Shape { name: "sine".into(), unit, note: "h = a sin(2πx/Λ)".into() }
}

/// A saw-tooth rising over 80 % of the period and falling over 20 %, its corners rounded by a Gaussian of
/// σ = Λ/50 (a Fourier series to 64 harmonics): the C-method wants a smooth profile.
fn blazed() -> Shape {
    let (fine, samples, sigma) = (2048, 256, 1.0 / 50.0);
    let saw: Vec<f64> = (0..fine)
        .map(|i| {
            let t = i as f64 / fine as f64;
            if t < 0.8 {
                t / 0.8
            } else {
                (1.0 - t) / 0.2
            }
        })
        .collect();
    let coef: Vec<Complex64> = (1..=64)
        .map(|k| {
            let c: Complex64 = saw
                .iter()
                .enumerate()
                .map(|(j, &h)| h * Complex64::from_polar(1.0, -TAU * (k * j) as f64 / fine as f64))
                .sum();
            c / fine as f64 * (-0.5 * (TAU * k as f64 * sigma).powi(2)).exp()
        })
        .collect();
    let unit = (0..samples)
        .map(|i| {
            let t = i as f64 / samples as f64;
            coef.iter()
                .enumerate()
                .map(|(k, c)| 2.0 * (c * Complex64::from_polar(1.0, TAU * (k + 1) as f64 * t)).re)
                .sum()
        })
        .collect();
    Shape {
        name: "blazed".into(),
        unit: normalise(unit),
        note: "saw-tooth, rise 80 % / fall 20 % of Λ, corners rounded (Gaussian σ = Λ/50)".into(),
    }
}

/// A built-in skin's unit cell as `--unit-cell auto` takes it ([`averaged_unit_cell`]), with its period,
/// grating-vector orientation and own depth a/Λ.
fn skin(spec: &str) -> Result<(Shape, f64, f64, f64)> {
    let patch = iridis_api::surface::load_patch(spec, &SurfaceOptions::default(), &Quiet)?;
    let (cell, d, phi) = averaged_unit_cell(&patch).with_context(|| format!("{spec}: no dominant period"))?;
    let row = cell.heights[..cell.cols].to_vec();
    let (lo, hi) = row.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| (a.min(x), b.max(x)));
    let depth = 0.5 * (hi - lo) / d;
    let note = format!(
        "`{spec}` averaged along its ridges (`--unit-cell auto`): period {d:.0} nm along {phi:.0}°, {} samples, \
         own depth a/Λ = {depth:.3}",
        cell.cols
    );
    let name = spec.trim_start_matches("builtin:").split('?').next().unwrap_or(spec).to_string();
    Ok((Shape { name, unit: normalise(row), note }, d, phi, depth))
}

fn options(method: GratingMethod, material: &str, theta_deg: f64, phi_deg: f64, wl: Vec<f64>) -> GratingOptions {
    let (t, p) = (theta_deg.to_radians(), phi_deg.to_radians());
    GratingOptions {
        method,
        light: [t.sin() * p.cos(), t.sin() * p.sin(), t.cos()],
        wavelengths_nm: wl,
        material: Some(material.into()),
        ..GratingOptions::default()
    }
}

/// Scalar against rigorous on one source; the error and whether the rigorous answer met its tolerance.
fn compare(source: &Source, opts: GratingOptions) -> Result<(ScalarError, bool)> {
    let s = SurfaceOptions::default();
    let kirchhoff = grating(source, &s, &GratingOptions { method: GratingMethod::Kirchhoff, ..opts.clone() }, &Quiet)?;
    let rigorous = grating(source, &s, &GratingOptions { method: GratingMethod::Rigorous, ..opts }, &Quiet)?;
    let met = rigorous.answers.iter().all(|a| a.convergence["met"] == serde_json::json!(true));
    Ok((scalar_error(&kirchhoff, &rigorous), met))
}

/// One case of the dimensionless map.
struct Row {
    shape: usize,
    medium: usize,
    depth: f64,
    lambda: f64,
    theta: f64,
    /// Worst relative order error TE, TM, unpolarised.
    err: [f64; 3],
    met: bool,
}

fn dimensionless(shapes: &[Shape]) -> Vec<Row> {
    let mut jobs = Vec::new();
    for s in 0..shapes.len() {
        for m in 0..MEDIA.len() {
            for &d in &DEPTHS {
                for &l in &LAMBDAS {
                    for &t in &THETAS {
                        jobs.push((s, m, d, l, t));
                    }
                }
            }
        }
    }
    let done = AtomicUsize::new(0);
    jobs.par_iter()
        .filter_map(|&(s, m, d, l, t)| {
            let h: Vec<f64> = shapes[s].unit.iter().map(|u| u * d * PERIOD).collect();
            let n = h.len();
            // Two equal rows: a 1-D grating along x, the light in the x-z plane (across the grooves).
            let rows: Vec<f64> = h.iter().chain(&h).copied().collect();
            let run = || -> Result<Row> {
                let patch = Patch::from_row_major(2, n, PERIOD / n as f64, PERIOD / n as f64, &rows)?;
                let source = Source::Patch { patch, name: shapes[s].name.clone() };
                let (e, met) =
                    compare(&source, options(GratingMethod::Kirchhoff, MEDIA[m].1, t, 0.0, vec![l * PERIOD]))?;
                Ok(Row {
                    shape: s,
                    medium: m,
                    depth: d,
                    lambda: l,
                    theta: t,
                    err: [e.worst.te, e.worst.tm, e.worst.unpolarized],
                    met,
                })
            };
            let k = done.fetch_add(1, Ordering::Relaxed) + 1;
            if k.is_multiple_of(100) {
                eprintln!("  {k}/{}", jobs.len());
            }
            run().map_err(|e| eprintln!("  {} {} a/Λ {d} λ/Λ {l} θ {t}: {e:#}", shapes[s].name, MEDIA[m].0)).ok()
        })
        .collect()
}

/// The largest error among the rows selected (NaN when none is).
fn worst<'a>(rows: impl Iterator<Item = &'a Row>, pol: usize) -> f64 {
    rows.map(|r| r.err[pol]).fold(f64::NAN, f64::max)
}

fn pct(x: f64) -> String {
    if x.is_nan() {
        "—".into()
    } else if x >= 10.0 {
        format!("{:.0}×", x + 1.0)
    } else if x >= 0.0995 {
        format!("{:.0} %", 100.0 * x)
    } else {
        format!("{:.1} %", 100.0 * x)
    }
}

/// The largest depth of the grid up to which every selected case (every λ/Λ) stays within `bound`.
fn trusted(rows: &[Row], sel: impl Fn(&Row) -> bool, pol: usize, bound: f64) -> Option<f64> {
    let mut best = None;
    for &d in &DEPTHS {
        if worst(rows.iter().filter(|r| sel(r) && r.depth <= d + 1e-12), pol) <= bound {
            best = Some(d);
        } else {
            break;
        }
    }
    best
}

fn depth_text(d: Option<f64>) -> String {
    d.map_or("< 0.005".into(), |d| format!("{d}"))
}

/// 380–780 nm every 10 nm: what the colours (CIEDE2000 under D65) need.
fn visible() -> Vec<f64> {
    (0..=40).map(|i| 380.0 + 10.0 * i as f64).collect()
}

/// Colours on keratin: every shape at Λ = [`PERIOD`] and the depths given, over the visible, at `thetas`; one
/// table line per shape and depth (ΔE00 diffracted / specular and the worst unpolarised order error, by θ_i).
fn colour_lines(shapes: &[Shape], depths: &[f64], thetas: &[f64]) -> Vec<String> {
    let mut jobs = Vec::new();
    for s in 0..shapes.len() {
        for &d in depths {
            for &t in thetas {
                jobs.push((s, d, t));
            }
        }
    }
    let answers: Vec<Option<(ScalarError, bool)>> = jobs
        .par_iter()
        .map(|&(s, d, t)| {
            let h: Vec<f64> = shapes[s].unit.iter().map(|u| u * d * PERIOD).collect();
            let n = h.len();
            let rows: Vec<f64> = h.iter().chain(&h).copied().collect();
            let run = || -> Result<(ScalarError, bool)> {
                let patch = Patch::from_row_major(2, n, PERIOD / n as f64, PERIOD / n as f64, &rows)?;
                let source = Source::Patch { patch, name: shapes[s].name.clone() };
                compare(&source, options(GratingMethod::Kirchhoff, "keratin", t, 0.0, visible()))
            };
            eprintln!("  colours: {} a/Λ {d} θ {t}° …", shapes[s].name);
            run().map_err(|e| eprintln!("  colours {} a/Λ {d} θ {t}: {e:#}", shapes[s].name)).ok()
        })
        .collect();
    let mut lines = Vec::new();
    for s in 0..shapes.len() {
        for &d in depths {
            let cells: Vec<String> = thetas
                .iter()
                .map(|&t| {
                    let k = jobs.iter().position(|&j| j == (s, d, t)).expect("a job per cell");
                    answers[k].as_ref().map_or("—".into(), |(e, met)| {
                        format!(
                            "{:.1} / {:.1} ({}){}",
                            e.delta_e_diffracted.unwrap_or(f64::NAN),
                            e.delta_e_specular.unwrap_or(f64::NAN),
                            pct(e.worst.unpolarized),
                            if *met { "" } else { "*" }
                        )
                    })
                })
                .collect();
            lines.push(format!("| {} | {d} | {} |", shapes[s].name, cells.join(" | ")));
        }
    }
    lines
}

/// The skins at their own period and depth on keratin over the visible, light across the ridges: one table
/// line per skin and incidence.
fn skin_lines(skins: &[(&str, f64, f64)]) -> Result<Vec<String>> {
    let mut lines = Vec::new();
    for &(spec, d, phi) in skins {
        let source = Source::Spec(spec.into());
        for &th in &THETAS {
            eprintln!("  {spec} at {th}° …");
            let opts = GratingOptions {
                unit_cell_auto: true,
                ..options(GratingMethod::Kirchhoff, "keratin", th, phi, visible())
            };
            let (e, met) = compare(&source, opts)?;
            lines.push(format!(
                "| {spec} (Λ = {d:.0} nm) | {th}° | {} / {} / {} | {} | {:.1} / {:.1} |{}",
                pct(e.worst.te),
                pct(e.worst.tm),
                pct(e.worst.unpolarized),
                pct(e.total),
                e.delta_e_diffracted.unwrap_or(f64::NAN),
                e.delta_e_specular.unwrap_or(f64::NAN),
                if met { "" } else { " rigorous not converged somewhere" }
            ));
        }
    }
    Ok(lines)
}

fn main() -> Result<()> {
    let start = Instant::now();
    eprintln!("profiles …");
    let (elaphe, elaphe_d, elaphe_phi, _) = skin("builtin:elaphe")?;
    let (xeno, xeno_d, xeno_phi, _) = skin("builtin:xenopeltis")?;
    let shapes = vec![sine(), blazed(), elaphe, xeno];
    eprintln!("skins on keratin …");
    let skin_lines = skin_lines(&[("builtin:elaphe", elaphe_d, elaphe_phi), ("builtin:xenopeltis", xeno_d, xeno_phi)])?;
    let t_skins = start.elapsed().as_secs_f64();
    let total = shapes.len() * MEDIA.len() * DEPTHS.len() * LAMBDAS.len() * THETAS.len();
    eprintln!("dimensionless map ({total} comparisons) …");
    let rows = dimensionless(&shapes);
    let t_map = start.elapsed().as_secs_f64() - t_skins;
    eprintln!("colours on keratin …");
    let colour_thetas = [0.0, 30.0];
    let colours = colour_lines(&shapes, &COLOUR_DEPTHS, &colour_thetas);
    let t_colour = start.elapsed().as_secs_f64() - t_skins - t_map;

    println!("Profiles (each scaled to the depths a/Λ below, Λ = {PERIOD} nm; light across the grooves):\n");
    println!("| profile | what it is |\n|---|---|");
    for s in &shapes {
        println!("| {} | {} |", s.name, s.note);
    }
    let unmet = rows.iter().filter(|r| !r.met).count();
    println!(
        "\n{} comparisons ({} failed); {} rigorous answers stopped at the solver's order limit before its tolerance \
         1e-3 (they carry their estimated error).",
        rows.len(),
        total - rows.len(),
        unmet
    );

    let names: Vec<&str> = shapes.iter().map(|s| s.name.as_str()).collect();
    for (m, (medium, _)) in MEDIA.iter().enumerate() {
        println!(
            "\n**{medium}: worst relative error of a propagating order (unpolarised; either model η > 1e-3) over λ/Λ = 0.3, 0.5, \
             0.7, 0.9, at θ_i = 0° / 30° / 60° / 75°**\n"
        );
        println!("| a/Λ | {} |\n|---|{}", names.join(" | "), "---|".repeat(names.len()));
        for &d in &DEPTHS {
            let cells: Vec<String> = (0..shapes.len())
                .map(|s| {
                    let c: Vec<String> = THETAS
                        .iter()
                        .map(|&t| {
                            pct(worst(
                                rows.iter().filter(|r| r.shape == s && r.medium == m && r.depth == d && r.theta == t),
                                2,
                            ))
                        })
                        .collect();
                    c.join(" / ")
                })
                .collect();
            println!("| {d} | {} |", cells.join(" | "));
        }
    }

    println!("\n**Polarisation: worst order error TE / TM / unpolarised over λ/Λ, θ_i ≤ 30°**\n");
    let heads: Vec<String> = MEDIA
        .iter()
        .flat_map(|(m, _)| names.iter().map(move |n| format!("{n}, {}", m.split(' ').next().unwrap_or(m))))
        .collect();
    println!("| a/Λ | {} |\n|---|{}", heads.join(" | "), "---|".repeat(heads.len()));
    for &d in &DEPTHS {
        let mut cells = Vec::new();
        for m in 0..MEDIA.len() {
            for s in 0..shapes.len() {
                let sel = || rows.iter().filter(|r| r.shape == s && r.medium == m && r.depth == d && r.theta <= 30.0);
                cells.push(format!("{} / {} / {}", pct(worst(sel(), 0)), pct(worst(sel(), 1)), pct(worst(sel(), 2))));
            }
        }
        println!("| {d} | {} |", cells.join(" | "));
    }

    println!("\n**Wavelength over period: worst unpolarised order error of the sine at θ_i = 0° / 30°**\n");
    let lheads: Vec<String> = LAMBDAS.iter().map(|l| format!("λ/Λ = {l}")).collect();
    println!("| a/Λ | medium | {} |\n|---|---|{}", lheads.join(" | "), "---|".repeat(LAMBDAS.len()));
    for &d in &[0.02, 0.05, 0.1, 0.2] {
        for (m, (medium, _)) in MEDIA.iter().enumerate() {
            let cells: Vec<String> = LAMBDAS
                .iter()
                .map(|&l| {
                    let at = |t: f64| {
                        pct(worst(
                            rows.iter().filter(|r| {
                                r.shape == 0 && r.medium == m && r.depth == d && r.lambda == l && r.theta == t
                            }),
                            2,
                        ))
                    };
                    format!("{} / {}", at(0.0), at(30.0))
                })
                .collect();
            println!("| {d} | {medium} | {} |", cells.join(" | "));
        }
    }

    println!(
        "\n**Where the scalar model holds: the largest a/Λ of the grid up to which every order of every λ/Λ \
         (0.3–0.9) is within the bound**\n"
    );
    println!(
        "| profile | medium | unpolarised ≤ 10 %: θ_i ≤ 30° / ≤ 60° / ≤ 75° | unpolarised ≤ 20 %: θ_i ≤ 30° / ≤ 60° / \
         ≤ 75° | TE ≤ 10 %, θ_i ≤ 30° | TM ≤ 10 %, θ_i ≤ 30° |\n|---|---|---|---|---|---|"
    );
    for (s, name) in names.iter().enumerate() {
        for (m, (medium, _)) in MEDIA.iter().enumerate() {
            let upto = |t: f64| move |r: &Row| r.shape == s && r.medium == m && r.theta <= t;
            let three =
                |bound: f64| [30.0, 60.0, 75.0].map(|t| depth_text(trusted(&rows, upto(t), 2, bound))).join(" / ");
            println!(
                "| {name} | {medium} | {} | {} | {} | {} |",
                three(BOUNDS[0]),
                three(BOUNDS[1]),
                depth_text(trusted(&rows, upto(30.0), 0, BOUNDS[0])),
                depth_text(trusted(&rows, upto(30.0), 1, BOUNDS[0])),
            );
        }
    }
    println!("\n**All four profiles together (the rule): the largest a/Λ within the bound, unpolarised**\n");
    println!("| medium | bound | θ_i ≤ 30° | θ_i ≤ 60° | θ_i ≤ 75° |\n|---|---|---|---|---|");
    for (m, (medium, _)) in MEDIA.iter().enumerate() {
        for b in BOUNDS {
            let c: Vec<String> = [30.0, 60.0, 75.0]
                .iter()
                .map(|&t| depth_text(trusted(&rows, |r| r.medium == m && r.theta <= t, 2, b)))
                .collect();
            println!("| {medium} | {:.0} % | {} |", 100.0 * b, c.join(" | "));
        }
    }

    println!(
        "\n**Colours on keratin (Λ = {PERIOD} nm, 380–780 nm every 10 nm, D65, CIE 1931, unpolarised): CIEDE2000 \
         between scalar and rigorous, diffracted light (all orders but the mirror one) / mirror order, and the worst \
         order error over the spectrum (* a rigorous answer at its order limit)**\n"
    );
    let heads: Vec<String> = colour_thetas.iter().map(|t| format!("θ_i = {t}°")).collect();
    println!("| profile | a/Λ | {} |\n|---|---|{}", heads.join(" | "), "---|".repeat(heads.len()));
    for line in &colours {
        println!("{line}");
    }
    println!(
        "\n**The skins as they are (own period and depth, `--unit-cell auto`) on keratin, 380–780 nm every 10 nm, \
         light across the ridges: `iridis grating SKIN --unit-cell auto --material keratin --compare --from 380nm \
         --to 780nm --light θ,φ`**\n"
    );
    println!("| skin | θ_i | worst order error TE / TM / unpolarised | total reflectance error | ΔE00 diffracted / specular |");
    println!("|---|---|---|---|---|");
    for line in &skin_lines {
        println!("{line}");
    }
    println!(
        "\nRun time: skins {t_skins:.0} s, dimensionless map {t_map:.0} s, colours {t_colour:.0} s, total {:.0} s on {} \
         threads.",
        start.elapsed().as_secs_f64(),
        rayon::current_num_threads()
    );
    Ok(())
}
