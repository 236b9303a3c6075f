//! The validity map of docs/diffraction.md ("When to trust the scalar model"): how far the scalar (Kirchhoff)
//! order efficiencies of iridis are from the rigorous ones (the C-method of `iridis-rigorous`), over
//! depth/period, wavelength/period, incidence and polarisation, for sine, blazed and the built-in skins'
//! averaged profiles, on a metal and on glass; and the colour difference (CIEDE2000, D65, CIE 1931) of the
//! diffracted and the specular light over 380–780 nm on gold and keratin.
//!
//!     cargo run --release -p iridis-api --example validity_map [-- --csv docs/validity_map.csv --plot docs/img/validity_map.png]
//!
//! Prints Markdown tables on stdout (progress on stderr) and writes every case to the CSV.

use std::f64::consts::TAU;
use std::io::Write;
use std::time::Instant;

use anyhow::{Context, Result};
use iridis_api::unit_cell::averaged_profile;
use iridis_color::{Illuminant, Lab, Observer, SpectralWeights, Xyz};
use iridis_diffraction::geometry::{direction, Fresnel, FresnelSource};
use iridis_diffraction::grating::{Efficiency as SEff, GratingAnswer, Normalisation, UnitCell};
use iridis_diffraction::Patch;
use iridis_lab::laser::MetalFresnel;
use iridis_rigorous::{Efficiency as REff, Options, Problem, Profile1d, Solution};
use num_complex::Complex64;
use rayon::prelude::*;

/// Samples per period handed to both models (the rigorous solver interpolates them trigonometrically; the
/// scalar model's DFT reads them as they are: both see the same smooth, band-limited profile).
const SAMPLES: usize = 256;
/// Depths (half the peak-to-valley over the period) of the dimensionless map.
const DEPTHS: [f64; 8] = [0.005, 0.01, 0.02, 0.05, 0.1, 0.15, 0.2, 0.3];
const LAMBDAS: [f64; 4] = [0.3, 0.5, 0.7, 0.9];
const THETAS: [f64; 4] = [0.0, 30.0, 60.0, 75.0];
/// Depths of the colour map (the skins' own depth is added).
const COLOUR_DEPTHS: [f64; 4] = [0.01, 0.02, 0.05, 0.1];
/// Orders below this efficiency (in both models) are not compared; the error is relative to max(η, floor).
const FLOOR: f64 = 1e-3;

/// A profile shape over one period: zero mean, half peak-to-valley 1 (so `a · shape` has depth `a`).
#[derive(Debug, Clone)]
struct Shape {
    name: String,
    /// The period the shape was measured at (the skins) or is shown at in the colour map (nm).
    period_nm: f64,
    /// The skin's own depth over period (half its averaged peak-to-valley over the period), if it has one.
    natural_depth: Option<f64>,
    unit: Vec<f64>,
    note: String,
}

/// A periodic function's trigonometric interpolant (of its `v.len()` samples) at `n` points.
fn resample(v: &[f64], n: usize) -> Vec<f64> {
    let m = v.len();
    let half = m / 2;
    let coef: Vec<Complex64> = (0..=half)
        .map(|k| {
            let c: Complex64 = v
                .iter()
                .enumerate()
                .map(|(j, &h)| h * Complex64::from_polar(1.0, -TAU * (k * j) as f64 / m as f64))
                .sum();
            // Positive and negative frequency together; the Nyquist bin of an even count once.
            let w = if k == 0 || (m % 2 == 0 && k == half) { 1.0 } else { 2.0 };
            c * w / m as f64
        })
        .collect();
    (0..n)
        .map(|i| {
            let t = i as f64 / n as f64;
            coef.iter().enumerate().map(|(k, c)| (c * Complex64::from_polar(1.0, TAU * k as f64 * t)).re).sum()
        })
        .collect()
}

/// Zero mean, half peak-to-valley 1.
fn normalise(mut v: Vec<f64>) -> Vec<f64> {
    let mean = v.iter().sum::<f64>() / v.len() as f64;
    let (lo, hi) = v.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| (a.min(x), b.max(x)));
    let half = 0.5 * (hi - lo);
    for x in v.iter_mut() {
        *x = (*x - mean) / half;
    }
    v
}

fn sine() -> Shape {
    Shape {
        name: "sine".into(),
        period_nm: 1000.0,
        natural_depth: None,
        unit: (0..SAMPLES).map(|i| (TAU * i as f64 / SAMPLES as f64).sin()).collect(),
        note: "h = a sin(2πx/Λ)".into(),
    }
}

/// A saw-tooth that rises over 80 % of the period and falls over 20 %, its corners rounded by a Gaussian of
/// σ = Λ/50 (the C-method needs a smooth profile; a sharp corner is outside what it does well).
fn blazed() -> Shape {
    let fine = 4096;
    let tri: Vec<f64> = (0..fine)
        .map(|i| {
            let t = i as f64 / fine as f64;
            if t < 0.8 {
                t / 0.8
            } else {
                (1.0 - t) / 0.2
            }
        })
        .collect();
    let sigma = 1.0 / 50.0;
    let unit = (0..SAMPLES)
        .map(|i| {
            let t = i as f64 / SAMPLES as f64;
            (1..=64)
                .map(|k| {
                    let c: Complex64 = tri
                        .iter()
                        .enumerate()
                        .map(|(j, &h)| h * Complex64::from_polar(1.0, -TAU * (k * j) as f64 / fine as f64))
                        .sum::<Complex64>()
                        / fine as f64;
                    let g = (-0.5 * (TAU * k as f64 * sigma).powi(2)).exp();
                    2.0 * g * (c * Complex64::from_polar(1.0, TAU * k as f64 * t)).re
                })
                .sum::<f64>()
        })
        .collect();
    Shape {
        name: "blazed".into(),
        period_nm: 1000.0,
        natural_depth: None,
        unit: normalise(unit),
        note: "saw-tooth, rise 80 % / fall 20 % of Λ, corners rounded (Gaussian σ = Λ/50)".into(),
    }
}

/// A built-in skin's dominant period, averaged along its ridges, then the trigonometric interpolant at
/// [`SAMPLES`] points. As many phase bins as the scan has pixels per period (even, at least 4): finer bins
/// would show the grid's aliasing (ridges along a grid axis put whole rows in a few phases: a staircase), not
/// the skin.
fn skin(spec: &str, name: &str) -> Result<Shape> {
    let patch = iridis_api::surface::load_patch(spec, &Default::default(), &iridis_api::Quiet)?;
    let peak = iridis_api::surface::dominant_period(&patch).with_context(|| format!("{spec}: no dominant period"))?;
    let bins = ((peak.period_nm / patch.dx.max(patch.dy)) as usize / 2 * 2).max(4);
    let binned = averaged_profile(&patch, peak.period_nm, peak.orientation_deg, bins);
    let h = resample(&binned, SAMPLES);
    let (lo, hi) = h.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| (a.min(x), b.max(x)));
    let (elo, ehi) = patch.heights.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| (a.min(x), b.max(x)));
    Ok(Shape {
        name: name.into(),
        period_nm: peak.period_nm,
        natural_depth: Some(0.5 * (hi - lo) / peak.period_nm),
        unit: normalise(h),
        note: format!(
            "`{spec}`: dominant period {:.1} nm at {:.1}° ({:.0} % of the variance), averaged along the ridges \
             in {bins} phase bins; averaged peak-to-valley {:.1} nm (the scan's {:.1} nm)",
            peak.period_nm,
            peak.orientation_deg,
            100.0 * peak.power,
            hi - lo,
            ehi - elo
        ),
    })
}

/// What reflects: a constant index (the dimensionless map) or a library material (the colour map).
#[derive(Debug, Clone)]
enum Medium {
    Constant { name: &'static str, n: Complex64 },
    Library { name: &'static str, fresnel: MetalFresnel },
}

impl Medium {
    fn name(&self) -> &'static str {
        match self {
            Medium::Constant { name, .. } | Medium::Library { name, .. } => name,
        }
    }
    fn index(&self, lambda: f64) -> Complex64 {
        match self {
            Medium::Constant { n, .. } => *n,
            Medium::Library { fresnel, .. } => fresnel.index(lambda),
        }
    }
    fn fresnel(&self) -> Box<dyn FresnelSource> {
        match self {
            Medium::Constant { n, .. } => Box::new(Fresnel::Index { n: *n }),
            Medium::Library { fresnel, .. } => Box::new(fresnel.clone()),
        }
    }
}

fn library(name: &'static str) -> Result<Medium> {
    let stack: iridis_thinfilm::Stack = format!("air | {name}").parse()?;
    Ok(Medium::Library { name, fresnel: MetalFresnel::new(stack.substrate, 380.0, 780.0)? })
}

#[derive(Debug, Clone, Copy)]
enum Pol {
    Te,
    Tm,
    Un,
}
const POLS: [Pol; 3] = [Pol::Te, Pol::Tm, Pol::Un];

fn r_eff(e: &REff, p: Pol) -> f64 {
    match p {
        Pol::Te => e.te,
        Pol::Tm => e.tm,
        Pol::Un => e.unpolarized,
    }
}
fn s_eff(e: &SEff, p: Pol) -> f64 {
    match p {
        Pol::Te => e.te,
        Pol::Tm => e.tm,
        Pol::Un => e.unpolarized,
    }
}

/// The largest relative error of a propagating order (η > [`FLOOR`] in either model), relative to
/// max(η_rigorous, FLOOR), and the order where it is.
fn order_error(rig: &Solution, sc: &GratingAnswer, p: Pol) -> (f64, i32) {
    let mut worst = (0.0, 0);
    for o in &rig.orders {
        let r = r_eff(&o.efficiency, p);
        let s =
            sc.orders.iter().find(|q| (q.m, q.n) == (o.m as i64, o.n as i64)).map_or(0.0, |q| s_eff(&q.efficiency, p));
        if r.max(s) > FLOOR {
            let e = (s - r).abs() / r.max(FLOOR);
            if e > worst.0 {
                worst = (e, o.m);
            }
        }
    }
    worst
}

/// Relative error of the total reflectance (signed: scalar above rigorous is positive).
fn total_error(rig: &Solution, sc: &GratingAnswer, p: Pol) -> f64 {
    let r = r_eff(&rig.reflected_total, p);
    (s_eff(&sc.reflected_total, p) - r) / r
}

/// The scalar model's unit cell of a 1-D profile (two identical rows: a grating along x).
fn scalar_cell(heights_nm: &[f64], period_nm: f64, lambda_min: f64) -> Result<UnitCell> {
    let n = heights_nm.len();
    let rows: Vec<f64> = heights_nm.iter().chain(heights_nm).copied().collect();
    let patch = Patch::from_row_major(2, n, period_nm / n as f64, period_nm / n as f64, &rows)?;
    Ok(UnitCell::new(&patch, lambda_min)?)
}

struct Both {
    rig: Solution,
    energy: GratingAnswer,
    kirchhoff: GratingAnswer,
}

fn solve_both(cell: &UnitCell, profile: &Profile1d, medium: &Medium, lambda: f64, theta_deg: f64) -> Result<Both> {
    let th = theta_deg.to_radians();
    let rig =
        iridis_rigorous::solve_1d(profile, &Problem::new(lambda, th, 0.0, medium.index(lambda)), &Options::default())?;
    let f = medium.fresnel();
    let wi = direction(th, 0.0);
    let energy = cell.efficiencies(wi, lambda, f.as_ref(), Normalisation::Energy)?;
    let kirchhoff = cell.efficiencies(wi, lambda, f.as_ref(), Normalisation::Kirchhoff)?;
    Ok(Both { rig, energy, kirchhoff })
}

/// One case of the dimensionless map.
#[derive(Debug, Clone)]
struct Row {
    shape: String,
    medium: &'static str,
    depth: f64,
    lambda: f64,
    theta: f64,
    /// Worst order error TE, TM, unpolarised, energy normalisation; then the printed Kirchhoff factor.
    err: [f64; 3],
    err_k: [f64; 3],
    worst_m: i32,
    /// Total reflectance error (relative, signed), TE, TM, unpolarised; energy, then Kirchhoff.
    r_err: [f64; 3],
    r_err_k: [f64; 3],
    r_rig: [f64; 3],
    orders: usize,
    m_used: usize,
    estimated: f64,
    met: bool,
}

fn dimensionless(shapes: &[Shape], media: &[Medium]) -> Vec<Row> {
    let period = 1000.0;
    let mut jobs = Vec::new();
    for s in shapes {
        for m in media {
            for &d in &DEPTHS {
                for &l in &LAMBDAS {
                    for &t in &THETAS {
                        jobs.push((s, m, d, l, t));
                    }
                }
            }
        }
    }
    let done = std::sync::atomic::AtomicUsize::new(0);
    let total = jobs.len();
    jobs.par_iter()
        .filter_map(|&(s, m, d, l, t)| {
            let heights: Vec<f64> = s.unit.iter().map(|u| u * d * period).collect();
            let profile = Profile1d { period_nm: period, heights_nm: heights.clone() };
            let lambda = l * period;
            let res = scalar_cell(&heights, period, lambda).and_then(|c| solve_both(&c, &profile, m, lambda, t));
            let k = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
            if k % 64 == 0 {
                eprintln!("  dimensionless map: {k}/{total}");
            }
            match res {
                Err(e) => {
                    eprintln!("  {} {} a/Λ {d} λ/Λ {l} θ {t}: {e:#}", s.name, m.name());
                    None
                }
                Ok(b) => {
                    let e = POLS.map(|p| order_error(&b.rig, &b.energy, p));
                    Some(Row {
                        shape: s.name.clone(),
                        medium: m.name(),
                        depth: d,
                        lambda: l,
                        theta: t,
                        err: e.map(|x| x.0),
                        err_k: POLS.map(|p| order_error(&b.rig, &b.kirchhoff, p).0),
                        worst_m: e[2].1,
                        r_err: POLS.map(|p| total_error(&b.rig, &b.energy, p)),
                        r_err_k: POLS.map(|p| total_error(&b.rig, &b.kirchhoff, p)),
                        r_rig: POLS.map(|p| r_eff(&b.rig.reflected_total, p)),
                        orders: b.rig.orders.len(),
                        m_used: b.rig.convergence.orders[0],
                        estimated: b.rig.convergence.estimated_error,
                        met: b.rig.convergence.met,
                    })
                }
            }
        })
        .collect()
}

/// One case of the colour map: a shape at its period, on a library material, at one depth and incidence.
#[derive(Debug, Clone)]
struct ColourRow {
    shape: String,
    medium: &'static str,
    period: f64,
    depth: f64,
    natural: bool,
    theta: f64,
    /// ΔE00 of the diffracted light and of the specular order, energy normalisation, then Kirchhoff's.
    de_diffracted: f64,
    de_specular: f64,
    de_diffracted_k: f64,
    de_specular_k: f64,
    /// Diffracted share of the reflected light (luminous, D65 × ȳ), rigorous and scalar.
    share_rig: f64,
    share_scalar: f64,
    /// Worst unpolarised order error over the spectrum.
    worst_order: f64,
    met: bool,
}

struct Colours {
    specular: Xyz,
    diffracted: Xyz,
    reflected: Xyz,
}

fn colours(w: &SpectralWeights, spec: &[f64], total: &[f64]) -> Colours {
    let diff: Vec<f64> = total.iter().zip(spec).map(|(t, s)| (t - s).max(0.0)).collect();
    Colours { specular: w.integrate(spec), diffracted: w.integrate(&diff), reflected: w.integrate(total) }
}

fn colour_map(shapes: &[Shape], media: &[Medium]) -> Vec<ColourRow> {
    let wl: Vec<f64> = (0..=40).map(|i| 380.0 + 10.0 * i as f64).collect();
    let weights = SpectralWeights::new(&wl, Illuminant::D65, Observer::Cie1931);
    let white = weights.white();
    let mut jobs = Vec::new();
    for s in shapes {
        let mut depths: Vec<(f64, bool)> = COLOUR_DEPTHS.iter().map(|&d| (d, false)).collect();
        if let Some(n) = s.natural_depth {
            depths.push((n, true));
        }
        for m in media {
            for &(d, nat) in &depths {
                for &t in &THETAS {
                    jobs.push((s, m, d, nat, t));
                }
            }
        }
    }
    let done = std::sync::atomic::AtomicUsize::new(0);
    let total = jobs.len();
    jobs.par_iter()
        .filter_map(|&(s, m, d, nat, t)| {
            let period = s.period_nm;
            let heights: Vec<f64> = s.unit.iter().map(|u| u * d * period).collect();
            let profile = Profile1d { period_nm: period, heights_nm: heights.clone() };
            let run = || -> Result<ColourRow> {
                let cell = scalar_cell(&heights, period, wl[0])?;
                let mut spec = [vec![], vec![], vec![]];
                let mut tot = [vec![], vec![], vec![]];
                let mut worst: f64 = 0.0;
                let mut met = true;
                for &l in &wl {
                    let b = solve_both(&cell, &profile, m, l, t)?;
                    met &= b.rig.convergence.met;
                    worst = worst.max(order_error(&b.rig, &b.energy, Pol::Un).0);
                    let sp_r =
                        b.rig.orders.iter().find(|o| (o.m, o.n) == (0, 0)).map_or(0.0, |o| o.efficiency.unpolarized);
                    spec[0].push(sp_r);
                    tot[0].push(b.rig.reflected_total.unpolarized);
                    for (k, a) in [(1, &b.energy), (2, &b.kirchhoff)] {
                        let sp =
                            a.orders.iter().find(|o| (o.m, o.n) == (0, 0)).map_or(0.0, |o| o.efficiency.unpolarized);
                        spec[k].push(sp);
                        tot[k].push(a.reflected_total.unpolarized);
                    }
                }
                let c: Vec<Colours> = (0..3).map(|k| colours(&weights, &spec[k], &tot[k])).collect();
                let de =
                    |a: Xyz, b: Xyz| iridis_color::lab::delta_e_2000(Lab::from_xyz(a, white), Lab::from_xyz(b, white));
                let share = |c: &Colours| if c.reflected.y > 0.0 { c.diffracted.y / c.reflected.y } else { 0.0 };
                Ok(ColourRow {
                    shape: s.name.clone(),
                    medium: m.name(),
                    period,
                    depth: d,
                    natural: nat,
                    theta: t,
                    de_diffracted: de(c[0].diffracted, c[1].diffracted),
                    de_specular: de(c[0].specular, c[1].specular),
                    de_diffracted_k: de(c[0].diffracted, c[2].diffracted),
                    de_specular_k: de(c[0].specular, c[2].specular),
                    share_rig: share(&c[0]),
                    share_scalar: share(&c[1]),
                    worst_order: worst,
                    met,
                })
            };
            let k = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
            eprintln!("  colour map: {k}/{total} ({} {} a/Λ {d:.3} θ {t}°)", s.name, m.name());
            run().map_err(|e| eprintln!("  {} {} a/Λ {d} θ {t}: {e:#}", s.name, m.name())).ok()
        })
        .collect()
}

/// A crossed grating `h = a/2 (sin Kx + sin Ky)`: the 2-D solver against the scalar model's crossed cell.
#[derive(Debug, Clone)]
struct CrossedRow {
    medium: &'static str,
    depth: f64,
    lambda: f64,
    err: [f64; 3],
    r_err: f64,
    orders: usize,
    m_used: [usize; 2],
    estimated: f64,
    seconds: f64,
}

fn crossed(media: &[Medium]) -> Vec<CrossedRow> {
    let (period, n, theta, phi) = (1000.0, 32, 30.0f64, 20.0f64);
    let mut out = Vec::new();
    for m in media {
        for (d, lambda) in [(0.05, 550.0), (0.1, 550.0)] {
            let a = d * period;
            let k = TAU / period;
            let prof =
                iridis_rigorous::sample_2d(period, period, n, n, |x, y| 0.5 * a * ((k * x).sin() + (k * y).sin()));
            let t0 = Instant::now();
            let problem = Problem::new(lambda, theta.to_radians(), phi.to_radians(), m.index(lambda));
            let rig = match iridis_rigorous::solve_2d(&prof, &problem, &Options::default()) {
                Ok(r) => r,
                Err(e) => {
                    eprintln!("  crossed {} a/Λ {d}: {e}", m.name());
                    continue;
                }
            };
            let seconds = t0.elapsed().as_secs_f64();
            // The same samples and row convention (row 0 at the top) as Profile2d.
            let patch =
                Patch::from_row_major(n, n, period / n as f64, period / n as f64, &prof.heights_nm).expect("grid");
            let cell = UnitCell::new(&patch, lambda).expect("cell");
            let f = m.fresnel();
            let sc = cell
                .efficiencies(
                    direction(theta.to_radians(), phi.to_radians()),
                    lambda,
                    f.as_ref(),
                    Normalisation::Energy,
                )
                .expect("scalar");
            out.push(CrossedRow {
                medium: m.name(),
                depth: d,
                lambda,
                err: POLS.map(|p| order_error(&rig, &sc, p).0),
                r_err: total_error(&rig, &sc, Pol::Un),
                orders: rig.orders.len(),
                m_used: rig.convergence.orders,
                estimated: rig.convergence.estimated_error,
                seconds,
            });
            eprintln!("  crossed {} a/Λ {d}: {seconds:.1} s", m.name());
        }
    }
    out
}

fn pct(x: f64) -> String {
    if !x.is_finite() {
        "—".into()
    } else if x >= 10.0 {
        format!("{:.0}×", x + 1.0)
    } else if x >= 0.995 {
        format!("{:.0} %", 100.0 * x)
    } else if x >= 0.0995 {
        format!("{:.0} %", 100.0 * x)
    } else {
        format!("{:.1} %", 100.0 * x)
    }
}

fn worst<'a>(rows: impl Iterator<Item = &'a Row>, f: impl Fn(&Row) -> f64) -> f64 {
    rows.map(f).fold(f64::NAN, |a, b| if a.is_nan() || b > a { b } else { a })
}

/// The largest depth of the grid up to which every case selected stays within `limit`.
fn trusted_depth(rows: &[Row], sel: impl Fn(&Row) -> bool, f: impl Fn(&Row) -> f64, limit: f64) -> String {
    let mut best = None;
    for &d in &DEPTHS {
        let w = worst(rows.iter().filter(|r| sel(r) && r.depth <= d + 1e-12), &f);
        if w <= limit {
            best = Some(d);
        } else {
            break;
        }
    }
    best.map_or("< 0.005".into(), |d| format!("{d}"))
}

fn main() -> Result<()> {
    let args: Vec<String> = std::env::args().collect();
    let opt = |name: &str| args.iter().position(|a| a == name).and_then(|i| args.get(i + 1)).cloned();
    let csv_path = opt("--csv").unwrap_or_else(|| "docs/validity_map.csv".into());
    let plot_path = opt("--plot").unwrap_or_else(|| "docs/img/validity_map.png".into());
    let start = Instant::now();
    eprintln!("profiles …");
    let shapes =
        vec![sine(), blazed(), skin("builtin:elaphe", "elaphe")?, skin("builtin:xenopeltis?size=10um", "xenopeltis")?];
    let metal = Medium::Constant {
        name: "metal ε = −20+1i",
        n: Problem::index_from_permittivity(Complex64::new(-20.0, 1.0)),
    };
    let glass = Medium::Constant { name: "glass n = 1.5", n: Complex64::new(1.5, 0.0) };
    let media = [metal.clone(), glass.clone()];
    eprintln!("dimensionless map ({} cases) …", shapes.len() * 2 * DEPTHS.len() * LAMBDAS.len() * THETAS.len());
    let t = Instant::now();
    let rows = dimensionless(&shapes, &media);
    let t_map = t.elapsed().as_secs_f64();
    eprintln!("colour map …");
    let t = Instant::now();
    let colour_media = [library("gold")?, library("keratin")?];
    let crows = colour_map(&shapes, &colour_media);
    let t_colour = t.elapsed().as_secs_f64();
    eprintln!("crossed gratings …");
    let xrows = crossed(&media);

    // ---- CSV: every case of the dimensionless map.
    {
        let mut f = std::io::BufWriter::new(std::fs::File::create(&csv_path).with_context(|| csv_path.clone())?);
        writeln!(
            f,
            "# iridis validity map (crates/api/examples/validity_map.rs): scalar (Kirchhoff) against rigorous (C-method) order efficiencies, period 1000 nm, incidence in the x-z plane across the grooves"
        )?;
        writeln!(f, "shape,medium,depth_over_period,wavelength_over_period,theta_deg,order_error_te,order_error_tm,order_error_unpolarized,worst_order_m,order_error_kirchhoff_te,order_error_kirchhoff_tm,order_error_kirchhoff_unpolarized,reflectance_error_te,reflectance_error_tm,reflectance_error_unpolarized,reflectance_error_kirchhoff_unpolarized,rigorous_reflectance_te,rigorous_reflectance_tm,propagating_orders,rigorous_m,rigorous_estimated_error,rigorous_converged")?;
        let mut sorted = rows.clone();
        sorted.sort_by(|a, b| {
            (a.shape.as_str(), a.medium, a.depth, a.lambda, a.theta)
                .partial_cmp(&(b.shape.as_str(), b.medium, b.depth, b.lambda, b.theta))
                .unwrap_or(std::cmp::Ordering::Equal)
        });
        for r in &sorted {
            writeln!(
                f,
                "{},{},{},{},{},{:.5},{:.5},{:.5},{},{:.5},{:.5},{:.5},{:.5},{:.5},{:.5},{:.5},{:.6},{:.6},{},{},{:.1e},{}",
                r.shape,
                r.medium,
                r.depth,
                r.lambda,
                r.theta,
                r.err[0],
                r.err[1],
                r.err[2],
                r.worst_m,
                r.err_k[0],
                r.err_k[1],
                r.err_k[2],
                r.r_err[0],
                r.r_err[1],
                r.r_err[2],
                r.r_err_k[2],
                r.r_rig[0],
                r.r_rig[1],
                r.orders,
                r.m_used,
                r.estimated,
                r.met
            )?;
        }
    }

    // ---- Markdown.
    let names: Vec<String> = shapes.iter().map(|s| s.name.clone()).collect();
    println!("Profiles:\n");
    println!("| profile | period used | own depth a/Λ | what it is |\n|---|---|---|---|");
    for s in &shapes {
        println!(
            "| {} | {:.0} nm | {} | {} |",
            s.name,
            s.period_nm,
            s.natural_depth.map_or("—".into(), |d| format!("{d:.3}")),
            s.note
        );
    }
    let unconverged = rows.iter().filter(|r| !r.met).count();
    println!(
        "\nRigorous answers: {} cases, {} not converged to the solver's tolerance 1e-3 (their estimated error: {}).",
        rows.len(),
        unconverged,
        worst(rows.iter().filter(|r| !r.met), |r| r.estimated)
    );

    for m in &media {
        println!(
            "\n**{}: worst relative error of a propagating order (unpolarised, η > 1e-3), over λ/Λ = 0.3, 0.5, 0.7, 0.9; \
             θ_i = 0° / 30° / 60° / 75°**\n",
            m.name()
        );
        println!("| a/Λ | {} |", names.join(" | "));
        println!("|---|{}", "---|".repeat(names.len()));
        for &d in &DEPTHS {
            let cells: Vec<String> = names
                .iter()
                .map(|n| {
                    THETAS
                        .iter()
                        .map(|&t| {
                            pct(worst(
                                rows.iter()
                                    .filter(|r| &r.shape == n && r.medium == m.name() && r.depth == d && r.theta == t),
                                |r| r.err[2],
                            ))
                        })
                        .collect::<Vec<_>>()
                        .join(" / ")
                })
                .collect();
            println!("| {d} | {} |", cells.join(" | "));
        }
    }

    println!("\n**TE / TM separately: worst order error over λ/Λ and θ_i ∈ {{0°, 30°}}**\n");
    print!("| a/Λ |");
    for m in &media {
        for n in &names {
            print!(" {n}, {} |", m.name().split(' ').next().unwrap_or(""));
        }
    }
    println!("\n|---|{}", "---|".repeat(names.len() * media.len()));
    for &d in &DEPTHS {
        print!("| {d} |");
        for m in &media {
            for n in &names {
                let sel =
                    || rows.iter().filter(|r| &r.shape == n && r.medium == m.name() && r.depth == d && r.theta <= 30.0);
                print!(" {} / {} |", pct(worst(sel(), |r| r.err[0])), pct(worst(sel(), |r| r.err[1])));
            }
        }
        println!();
    }

    println!("\n**Total reflectance: worst relative error (unpolarised) over λ/Λ and all θ_i; energy normalisation / printed Kirchhoff factor**\n");
    print!("| a/Λ |");
    for m in &media {
        for n in &names {
            print!(" {n}, {} |", m.name().split(' ').next().unwrap_or(""));
        }
    }
    println!("\n|---|{}", "---|".repeat(names.len() * media.len()));
    for &d in &DEPTHS {
        print!("| {d} |");
        for m in &media {
            for n in &names {
                let sel = || rows.iter().filter(|r| &r.shape == n && r.medium == m.name() && r.depth == d);
                print!(
                    " {} / {} |",
                    pct(worst(sel(), |r| r.r_err[2].abs())),
                    pct(worst(sel(), |r| r.r_err_k[2].abs()))
                );
            }
        }
        println!();
    }

    println!("\n**Energy normalisation against the printed Kirchhoff factor: worst unpolarised order error over λ/Λ, sine, by θ_i**\n");
    println!("| a/Λ | θ_i | metal: energy / printed | glass: energy / printed |\n|---|---|---|---|");
    for &d in &[0.01, 0.05, 0.1] {
        for &t in &THETAS {
            let cell = |m: &Medium| {
                let sel = || {
                    rows.iter().filter(|r| r.shape == "sine" && r.medium == m.name() && r.depth == d && r.theta == t)
                };
                format!("{} / {}", pct(worst(sel(), |r| r.err[2])), pct(worst(sel(), |r| r.err_k[2])))
            };
            println!("| {d} | {t}° | {} | {} |", cell(&metal), cell(&glass));
        }
    }

    println!("\n**Wavelength over period: worst unpolarised order error, sine, θ_i = 0° / 30°**\n");
    println!("| a/Λ | medium | {} |", LAMBDAS.map(|l| format!("λ/Λ = {l}")).join(" | "));
    println!("|---|---|{}", "---|".repeat(LAMBDAS.len()));
    for &d in &[0.02, 0.05, 0.1, 0.2] {
        for m in &media {
            let cells: Vec<String> = LAMBDAS
                .iter()
                .map(|&l| {
                    [0.0, 30.0]
                        .iter()
                        .map(|&t| {
                            pct(worst(
                                rows.iter().filter(|r| {
                                    r.shape == "sine"
                                        && r.medium == m.name()
                                        && r.depth == d
                                        && r.lambda == l
                                        && r.theta == t
                                }),
                                |r| r.err[2],
                            ))
                        })
                        .collect::<Vec<_>>()
                        .join(" / ")
                })
                .collect();
            println!("| {d} | {} | {} |", m.name(), cells.join(" | "));
        }
    }

    println!("\n**Where the scalar model holds: the largest a/Λ of the grid up to which every order (unpolarised) is within the bound, over λ/Λ 0.3–0.9**\n");
    println!("| profile | medium | ≤ 5 %, θ_i ≤ 30° | ≤ 20 %, θ_i ≤ 30° | ≤ 5 %, θ_i ≤ 60° | ≤ 20 %, θ_i ≤ 60° | ≤ 20 %, θ_i ≤ 75° | TE ≤ 20 %, θ_i ≤ 30° | TM ≤ 20 %, θ_i ≤ 30° |");
    println!("|---|---|---|---|---|---|---|---|---|");
    for n in &names {
        for m in &media {
            let sel30 = |r: &Row| &r.shape == n && r.medium == m.name() && r.theta <= 30.0;
            let sel60 = |r: &Row| &r.shape == n && r.medium == m.name() && r.theta <= 60.0;
            let sel75 = |r: &Row| &r.shape == n && r.medium == m.name();
            println!(
                "| {n} | {} | {} | {} | {} | {} | {} | {} | {} |",
                m.name(),
                trusted_depth(&rows, sel30, |r| r.err[2], 0.05),
                trusted_depth(&rows, sel30, |r| r.err[2], 0.2),
                trusted_depth(&rows, sel60, |r| r.err[2], 0.05),
                trusted_depth(&rows, sel60, |r| r.err[2], 0.2),
                trusted_depth(&rows, sel75, |r| r.err[2], 0.2),
                trusted_depth(&rows, sel30, |r| r.err[0], 0.2),
                trusted_depth(&rows, sel30, |r| r.err[1], 0.2),
            );
        }
    }

    println!(
        "\n**Colours, 380–780 nm (10 nm), D65, CIE 1931, unpolarised: CIEDE2000 between scalar (energy normalisation) \
         and rigorous, diffracted light (all non-specular orders) / specular order; θ_i = 0° / 30° / 60° / 75°**\n"
    );
    println!("| profile | period | medium | a/Λ | ΔE00 diffracted / specular, by θ_i | worst order error | diffracted share (rigorous → scalar) at 30° |");
    println!("|---|---|---|---|---|---|---|");
    let mut keys: Vec<(String, &'static str, f64, bool, f64)> =
        crows.iter().map(|r| (r.shape.clone(), r.medium, r.depth, r.natural, r.period)).collect();
    keys.sort_by(|a, b| {
        (names.iter().position(|n| *n == a.0), a.1, a.2)
            .partial_cmp(&(names.iter().position(|n| *n == b.0), b.1, b.2))
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    keys.dedup();
    for (s, m, d, nat, period) in &keys {
        let sel = || crows.iter().filter(|r| &r.shape == s && r.medium == *m && r.depth == *d);
        let cells: Vec<String> = THETAS
            .iter()
            .map(|&t| {
                sel()
                    .find(|r| r.theta == t)
                    .map_or("—".into(), |r| format!("{:.1} / {:.1}", r.de_diffracted, r.de_specular))
            })
            .collect();
        let w = sel().map(|r| r.worst_order).fold(0.0, f64::max);
        let at30 = sel().find(|r| r.theta == 30.0);
        let conv = if sel().all(|r| r.met) { "" } else { " (rigorous not converged somewhere)" };
        println!(
            "| {s} | {period:.0} nm | {m} | {d:.3}{} | {} | {}{conv} | {} |",
            if *nat { " (own)" } else { "" },
            cells.join(" · "),
            pct(w),
            at30.map_or("—".into(), |r| format!("{:.1} % → {:.1} %", 100.0 * r.share_rig, 100.0 * r.share_scalar))
        );
    }
    println!("\n**The printed Kirchhoff factor instead: ΔE00 diffracted / specular at θ_i = 60° / 75°**\n");
    println!("| profile | medium | a/Λ | 60° | 75° |\n|---|---|---|---|---|");
    for (s, m, d, nat, _) in &keys {
        let sel = || crows.iter().filter(|r| &r.shape == s && r.medium == *m && r.depth == *d);
        let cell = |t: f64| {
            sel()
                .find(|r| r.theta == t)
                .map_or("—".into(), |r| format!("{:.1} / {:.1}", r.de_diffracted_k, r.de_specular_k))
        };
        println!("| {s} | {m} | {d:.3}{} | {} | {} |", if *nat { " (own)" } else { "" }, cell(60.0), cell(75.0));
    }

    println!(
        "\n**Crossed sine h = a/2 (sin Kx + sin Ky), Λ = 1000 nm both ways, θ_i = 30°, φ_i = 20° (2-D solver)**\n"
    );
    println!("| medium | a/Λ | λ | orders | worst order error TE / TM / unpolarised | R error (unpolarised) | rigorous M, estimated error, time |");
    println!("|---|---|---|---|---|---|---|");
    for r in &xrows {
        println!(
            "| {} | {} | {} nm | {} | {} / {} / {} | {:+.1} % | {:?}, {:.0e}, {:.1} s |",
            r.medium,
            r.depth,
            r.lambda,
            r.orders,
            pct(r.err[0]),
            pct(r.err[1]),
            pct(r.err[2]),
            100.0 * r.r_err,
            r.m_used,
            r.estimated,
            r.seconds
        );
    }
    println!(
        "\nRun time: dimensionless map {t_map:.0} s, colour map {t_colour:.0} s, total {:.0} s on {} threads.",
        start.elapsed().as_secs_f64(),
        rayon::current_num_threads()
    );

    // ---- Figure: worst unpolarised order error against depth, θ_i ≤ 30°.
    let mut plot = iridis_plot::LinePlot::new(
        "Scalar vs rigorous: worst order error (unpolarised, θ_i ≤ 30°, λ/Λ 0.3–0.9)",
        "depth / period a/Λ (log10)",
        "worst relative order error (log10)",
    );
    let dashes = [false, true];
    for (mi, m) in media.iter().enumerate() {
        for (si, n) in names.iter().enumerate() {
            let xs: Vec<f64> = DEPTHS.iter().map(|d| d.log10()).collect();
            let ys: Vec<f64> = DEPTHS
                .iter()
                .map(|&d| {
                    worst(
                        rows.iter()
                            .filter(|r| &r.shape == n && r.medium == m.name() && r.depth == d && r.theta <= 30.0),
                        |r| r.err[2],
                    )
                    .max(1e-4)
                    .log10()
                })
                .collect();
            let c = iridis_plot::PALETTE[si];
            let mut s = iridis_plot::Series::new(format!("{n}, {}", m.name()), &xs, &ys).with_color([c.0, c.1, c.2]);
            if dashes[mi] {
                s = s.dashed();
            }
            plot = plot.series(s);
        }
    }
    for (level, label) in [(0.05f64, "5 %"), (0.2, "20 %")] {
        let xs = [DEPTHS[0].log10(), DEPTHS[DEPTHS.len() - 1].log10()];
        plot =
            plot.series(iridis_plot::Series::new(label, &xs, &[level.log10(); 2]).with_color([120, 120, 120]).dashed());
    }
    let img = plot.render()?;
    let mut bytes = Vec::new();
    image::ImageEncoder::write_image(
        image::codecs::png::PngEncoder::new(&mut bytes),
        &img.data,
        img.width,
        img.height,
        image::ExtendedColorType::Rgb8,
    )?;
    std::fs::write(&plot_path, bytes).with_context(|| plot_path.clone())?;
    eprintln!("wrote {csv_path} and {plot_path}");
    Ok(())
}
