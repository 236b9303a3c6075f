//! `iridis grating`: order efficiencies of a height field taken as one unit cell of a grating (issue 27); the
//! numbers and tables are the library's (`iridis_api::grating`, `iridis_api::grating_run`).

use anyhow::{bail, Result};
use clap::Args as ClapArgs;
use iridis_api::grating::{Detector, GratingOptions};
use iridis_api::grating_run::{compare, grating_checked, grating_text};
use iridis_diffraction::geometry::direction;

use crate::args::{angle_rad, fraction, polar_azimuth, positive_length_nm};
use crate::output::print_answer;
use crate::progress::Cli;
use iridis_api::brdf::unit_cell_auto;

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
  iridis grating 'builtin:sine?size=1um&pixel=10nm' --light 20deg --from 400nm --to 700nm --step 10nm --detector 12deg,0deg --acceptance 2deg
  iridis grating 'builtin:sine?size=1100nm&pixel=10nm' --method rigorous --light 30deg --wavelength 550nm --material gold
  iridis grating 'builtin:sine?size=1100nm&pixel=10nm' --compare --light 0deg --from 400nm --to 700nm --step 50nm
  iridis grating 'builtin:elaphe?size=10um&pixel=50nm' --unit-cell auto --compare --light 0deg --from 380nm --to 780nm --step 20nm
  iridis grating strip.png --pixel-size 50nm --max-height 250nm --light 75deg --wavelength 600nm")]
pub struct GratingArgs {
    /// The unit cell: a height field (file or builtin:NAME) whose extent is the period.
    pub surface: String,
    /// Light direction θ[,φ] (towards the light).
    #[arg(long, alias = "incidence", default_value = "0deg")]
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
    /// Wavelength step of a spectrum (with --from and --to).
    #[arg(long, value_parser = positive_length_nm, default_value = "10nm", requires = "from")]
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
    /// The scalar model's channel matrix: energy (scaled so that energy and reciprocity hold) or kirchhoff
    /// (as printed) [default: energy]; refused with --method rigorous.
    #[arg(long)]
    pub normalisation: Option<String>,
    /// A detector's direction θ[,φ]: its reflectance is the orders inside its acceptance cone.
    #[arg(long)]
    pub detector: Option<String>,
    /// The unit cell: whole (the patch, its extent the period) or auto (the scan's strongest period, its
    /// profile averaged along the ridges: a 1-D grating at that orientation).
    #[arg(long, value_name = "whole|auto", default_value = "whole")]
    pub unit_cell: String,
    /// Half-angle of the detector's acceptance cone [default: 2deg].
    #[arg(long, value_parser = angle_rad, requires = "detector")]
    pub acceptance: Option<f64>,
    /// Print JSON: every order's efficiency per wavelength, the totals, the detector's spectrum.
    #[arg(long)]
    pub json: bool,
    /// List only the orders of at least this efficiency (a fraction, or a percentage: 1e-3, 0.1%), with the
    /// mirror order and those the detector sees; the totals and colours still count every order (a large
    /// scan as one unit cell has hundreds of thousands of orders a wavelength). Default: every order.
    #[arg(long, value_name = "FRACTION", value_parser = fraction)]
    pub orders_above: Option<f64>,
    #[command(flatten)]
    pub surface_opts: iridis_api::SurfaceOptions,
}

pub fn run(a: GratingArgs) -> Result<()> {
    let (t, p) = polar_azimuth("light", &a.light)?;
    let wavelengths_nm = match (a.wavelength, a.from, a.to) {
        (Some(l), _, _) => vec![l],
        (None, Some(f), Some(t)) => iridis_color::spectrum::range_grid(f, t, a.step)?,
        (None, None, None) => vec![550.0],
        _ => bail!("give --wavelength, or --from and --to (with --step) for a spectrum"),
    };
    let acceptance_rad = a.acceptance.unwrap_or(Detector::DEFAULT_ACCEPTANCE_DEG.to_radians());
    let detector = match &a.detector {
        Some(d) => {
            let (dt, dp) = polar_azimuth("detector", d)?;
            Some(Detector { direction: direction(dt, dp), acceptance_rad })
        }
        None => None,
    };
    let opts = GratingOptions {
        method: a.method.parse()?,
        light: direction(t, p),
        wavelengths_nm,
        material: a.material.clone(),
        fresnel: a.fresnel.clone(),
        normalisation: a.normalisation.as_deref().map(str::parse).transpose()?,
        detector,
        unit_cell_auto: unit_cell_auto(&a.unit_cell)?,
        orders_above: a.orders_above.unwrap_or(0.0),
    };
    let (source, surface) = (iridis_api::surface::Source::Spec(a.surface.clone()), a.surface_opts.clone());
    if a.compare {
        let c = compare(&source, &surface, &opts, &Cli)?;
        return print_answer(a.json, || Ok(c.to_json()), || c.text());
    }
    let g = grating_checked(&source, &surface, &opts, &Cli)?;
    print_answer(a.json, || Ok(g.to_json()), || grating_text(&g, (t, p), a.detector.as_deref(), acceptance_rad))
}
