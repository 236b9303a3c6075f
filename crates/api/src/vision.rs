//! How an animal sees a diffracting surface from several directions (`iridis brdf vision`, the report's
//! "as a bird sees it", Python's `iridis.diffraction.vision`): the reflectance factor `π f_r(λ)` of the BRDF in
//! each view direction, from 300 nm (birds and bees see ultraviolet), analysed by the receptor-noise-limited
//! model of `iridis-vision` (quantum catches, ΔS and ΔL in JND between the directions); and a spectra file as an
//! animal sees it (`iridis vision`, [`analyse_file`]).

use anyhow::{bail, Context, Result};
use iridis_diffraction::geometry::{direction, Shading, Vec3};
use iridis_diffraction::grating::LobeScaled;
use iridis_diffraction::taylor::{window_radius, Band};
use iridis_diffraction::{Evaluator, Reference, SpectralSetup, TaylorTerms};

use crate::model::{coherence_for, term_count, ModelOptions};
use crate::report::{with_progress, Report};
use crate::surface::{Source, SurfaceOptions};

/// The shortest wavelength the directional spectra start at: birds' and bees' UV cones reach 300 nm.
pub const FROM_NM: f64 = 300.0;
/// The longest: the long-wave cones of birds and bees end before 700 nm.
pub const TO_NM: f64 = 700.0;

/// The spectra and what the animal makes of them.
#[derive(Debug, Clone)]
pub struct DirectionalVision {
    pub surface: String,
    /// Polar angle of the light (rad).
    pub light_theta: f64,
    /// The plane of incidence's azimuth in the surface frame (rad): the dominant period's orientation unless
    /// given.
    pub azimuth: f64,
    pub coherence_nm: f64,
    /// The Taylor terms `0..=N` of the reference evaluator: `N`.
    pub taylor_terms: usize,
    pub wavelengths_nm: Vec<f64>,
    /// Per view: its name, signed θ_r (degrees, positive on the specular side) and `π f_r(λ)` (unpolarised).
    pub views: Vec<(String, f64, Vec<f64>)>,
    /// Whether the lobes were energy-normalised (`--conserve-energy`).
    pub energy_normalised: bool,
    pub analysis: iridis_vision::Analysis,
}

/// What [`along_plane`] looks at: a light and views in one plane, and who looks.
#[derive(Debug, Clone, Copy)]
pub struct PlaneViews<'a> {
    /// Polar angle of the light (rad).
    pub light_theta: f64,
    /// The plane of incidence's azimuth in the surface frame (rad); default the dominant period's orientation.
    pub azimuth: Option<f64>,
    /// The views' signed polar angles in the plane (degrees, positive on the specular side).
    pub views_deg: &'a [f64],
    /// The visual system and its conditions (`--visual`, `--illuminant`, …).
    pub spec: &'a iridis_vision::Spec,
}

/// The reflectance factor `π f_r(λ)` (a white diffuser's is 1) of the reference evaluator on SURFACE for light
/// at `light_theta` in the plane of azimuth `azimuth` (default: the dominant period's orientation) and views at
/// the signed angles `views_deg` in that plane, from [`FROM_NM`] to [`TO_NM`] in steps of `model.step_nm`
/// (default 5 nm), with `model.terms` Taylor terms, seen by the visual system of `spec`.
pub fn along_plane(
    source: &Source,
    surface: &SurfaceOptions,
    model: &ModelOptions,
    shading: Shading,
    plane: PlaneViews<'_>,
    report: &dyn Report,
) -> Result<DirectionalVision> {
    let PlaneViews { light_theta, azimuth, views_deg, spec } = plane;
    if views_deg.is_empty() || views_deg.iter().any(|v| !(v.is_finite() && v.abs() < 90.0)) {
        bail!("the view angles must lie strictly between −90° and 90°");
    }
    crate::lab_run::refuse_repeats("--views", views_deg)?;
    if !(light_theta.is_finite() && (0.0..std::f64::consts::FRAC_PI_2).contains(&light_theta)) {
        bail!(
            "--light {}°: the light's polar angle must be from 0° up to (not including) 90°",
            iridis_color::spectrum::short_number(light_theta.to_degrees())
        );
    }
    if let Some(a) = azimuth.filter(|a| !a.is_finite()) {
        bail!("--azimuth {a}: the plane's azimuth must be a finite angle");
    }
    refuse_colour_options(model)?;
    let wavelengths =
        iridis_color::spectrum::range_grid(FROM_NM, TO_NM, model.step()).map_err(|e| anyhow::anyhow!("--step: {e}"))?;
    let system = spec.system().context("--visual")?;
    let options = spec.options(&system)?;
    let patch = source.patch(surface, report)?;
    let azimuth = match azimuth {
        Some(a) => a,
        None => match crate::surface::strongest_period(&patch) {
            Some(p) => {
                report.note(&format!(
                    "views in the plane of azimuth {:.1}°, the orientation of the surface's strongest period ({:.0} nm)",
                    p.orientation_deg, p.period_nm
                ));
                p.orientation_deg.to_radians()
            }
            None => 0.0,
        },
    };
    let light = direction(light_theta, azimuth);
    let (e, coherence, n) = uv_reference(&patch, model, shading, light, report)?;
    let view = |deg: f64| -> Vec3 {
        let t = deg.to_radians();
        [-t.sin() * azimuth.cos(), -t.sin() * azimuth.sin(), t.cos()]
    };
    let mut views = Vec::with_capacity(views_deg.len());
    for &deg in views_deg {
        let q = iridis_diffraction::point_query(e.as_ref(), &wavelengths, light, view(deg))?;
        let Some(b) = q.brdf else {
            bail!("the BRDF in sr⁻¹ needs the physical Fresnel convention (R once), not the paper's R²");
        };
        // Below the lit floor is the round-off of sums that cancel (a flat mirror's lobe seen 60° away: 1e-34),
        // whose "colour" is noise: no light (a flat patch's views were 94 JND apart in round-off).
        let factor: Vec<f64> = b
            .unpolarized
            .iter()
            .map(|f| std::f64::consts::PI * f)
            .map(|f| if f.abs() > crate::lit::LIT_FLOOR { f } else { 0.0 })
            .collect();
        views.push((format!("{deg:+.0}°"), deg, factor));
    }
    let samples: Vec<(String, Vec<f64>)> = views.iter().map(|(n, _, s)| (n.clone(), s.clone())).collect();
    let analysis = iridis_vision::analyse(&samples, &wavelengths, &system, &options)?;
    Ok(DirectionalVision {
        surface: source.name().to_string(),
        light_theta,
        azimuth,
        coherence_nm: coherence,
        taylor_terms: n,
        wavelengths_nm: wavelengths,
        views,
        energy_normalised: model.conserve_energy,
        analysis,
    })
}

/// The reference evaluator of `patch` for light from `light`, its Taylor terms made for wavelengths down to
/// [`FROM_NM`] (the model commands' `auto` stops at 380 nm, the CIE grid's start; an animal's UV cone reads below
/// it), with the energy-conserving lobes where `model` asks for them; with its coherence (nm) and N.
fn uv_reference(
    patch: &iridis_diffraction::Patch,
    model: &ModelOptions,
    shading: Shading,
    light: Vec3,
    report: &dyn Report,
) -> Result<(Box<dyn Evaluator>, f64, usize)> {
    let coherence = coherence_for(patch, model.coherence_nm, report)?;
    let n = term_count(patch, model, FROM_NM, report)?;
    // One light: the terms keep the bins its lobes read at 300 nm and longer (a large scan's memory).
    let band = Band::light(light, FROM_NM, 1.001 * window_radius(coherence));
    let terms = with_progress(report, n as u64 + 1, "Taylor terms", |p| {
        TaylorTerms::compute_in_band(patch, n, coherence, band, p)
    })?;
    report.info(&format!(
        "N = {n} Taylor terms, coherence {:.1} µm, π f_r(λ) from {FROM_NM} to {TO_NM} nm in {} nm steps",
        coherence / 1000.0,
        model.step()
    ));
    let reference = Reference { terms: std::sync::Arc::new(terms), shading, spectral: SpectralSetup::default() };
    let e: Box<dyn Evaluator> = if model.conserve_energy {
        report.note(crate::brdf::ENERGY_CONSERVING_LOBES);
        // The unit cell's orders down to 300 nm, below the CIE grid the lobes' colours are otherwise set up on.
        let energy = std::sync::Arc::new(iridis_diffraction::grating::SinkhornEnergy);
        Box::new(LobeScaled::down_to(Box::new(reference), patch, SpectralSetup::default(), energy, FROM_NM)?)
    } else {
        Box::new(reference)
    };
    Ok((e, coherence, n))
}

/// The reflectance factor `π f_r(λ)` (unpolarised) of the reference method on SURFACE for light `wi` and view
/// `wr`, from [`FROM_NM`] to [`TO_NM`] in `model`'s step: the spectrum `brdf eval --visual` gives the animal
/// (its own answer stops at 380 nm). Returns the wavelengths and the factor.
pub fn reflectance_factor_for_vision(
    source: &Source,
    surface: &SurfaceOptions,
    model: &ModelOptions,
    shading: Shading,
    wi: Vec3,
    wr: Vec3,
) -> Result<(Vec<f64>, Vec<f64>)> {
    // Quiet: the evaluation this accompanies has said the surface, the coherence and the terms.
    let quiet = &crate::report::Quiet;
    let wavelengths =
        iridis_color::spectrum::range_grid(FROM_NM, TO_NM, model.step()).map_err(|e| anyhow::anyhow!("--step: {e}"))?;
    let patch = source.patch(surface, quiet)?;
    let (e, _, _) = uv_reference(&patch, model, shading, wi, quiet)?;
    let q = iridis_diffraction::point_query(e.as_ref(), &wavelengths, wi, wr)?;
    let Some(b) = q.brdf else {
        bail!("--visual needs the BRDF in sr⁻¹, which the paper's R² convention does not give");
    };
    Ok((wavelengths, b.unpolarized.iter().map(|f| std::f64::consts::PI * f).collect()))
}

/// The model options [`along_plane`] would not use, refused rather than ignored: the CIE illuminant and observer
/// make XYZ, where the animal's receptors and `spec`'s illuminant take their place.
fn refuse_colour_options(model: &ModelOptions) -> Result<()> {
    let eye = "the animal's receptors and the vision illuminant take the place of CIE colour here";
    if let Some(i) = &model.illuminant {
        bail!("the model's illuminant ({i}) would be ignored: {eye}; give the animal's light as the vision illuminant");
    }
    if let Some(o) = &model.observer {
        bail!("--observer {o} would be ignored: {eye}");
    }
    Ok(())
}

impl DirectionalVision {
    /// The false colours of each view: the receptors' von Kries-adapted catches, longest three to R, G, B and
    /// (for a fourth, shortest receptor: UV) its own channel, each scaled to the brightest view. `[rgb, uv]` in
    /// 0..1 per view; `uv` is `None` for systems of three receptors or fewer.
    pub fn false_colours(&self) -> Vec<([f64; 3], Option<f64>)> {
        let k = self.analysis.receptors.len();
        let catches: Vec<&Vec<f64>> = self.analysis.samples.iter().map(|s| &s.quantum_catches).collect();
        let max_of = |i: usize| catches.iter().map(|c| c[i]).fold(0.0f64, f64::max).max(1e-300);
        let channel = |c: &Vec<f64>, i: Option<usize>| i.map_or(0.0, |i| (c[i] / max_of(i)).clamp(0.0, 1.0));
        // Receptors short to long: R the longest, G the next, B the third from the long end.
        let (r, g, b) = (k.checked_sub(1), k.checked_sub(2), k.checked_sub(3));
        catches
            .iter()
            .map(|c| ([channel(c, r), channel(c, g), channel(c, b)], (k >= 4).then(|| channel(c, Some(0)))))
            .collect()
    }

    /// What the views' spectra are, said in the text's heading and the JSON.
    pub fn quantity(&self) -> &'static str {
        if self.energy_normalised {
            "reflectance factor π f_r(λ), unpolarised, lobes energy-normalised (--conserve-energy): 1 for a white \
             diffuser"
        } else {
            "reflectance factor π f_r(λ), unpolarised: 1 for a white diffuser"
        }
    }

    /// What `iridis brdf vision --json` prints (keys in docs/json.md).
    pub fn to_json(&self) -> serde_json::Value {
        let views: Vec<serde_json::Value> = self
            .views
            .iter()
            .map(|(name, deg, s)| serde_json::json!({"name": name, "theta_r_deg": deg, "reflectance_factor": s}))
            .collect();
        serde_json::json!({
            "surface": self.surface,
            "light_theta_deg": self.light_theta.to_degrees(),
            "azimuth_deg": self.azimuth.to_degrees(),
            "coherence_nm": self.coherence_nm,
            "taylor_terms": self.taylor_terms,
            "quantity": self.quantity(),
            "wavelength_nm": self.wavelengths_nm,
            "views": views,
            "vision": serde_json::to_value(&self.analysis).unwrap_or_default(),
        })
    }
}

/// A spectra CSV (pavo's layout) as an animal sees it (`iridis vision`, Python's `iridis.vision.vision`).
#[derive(Debug, Clone)]
pub struct SpectraVision {
    /// The file as named.
    pub source: String,
    /// How many samples (spectra) it holds.
    pub samples: usize,
    pub analysis: iridis_vision::Analysis,
}

/// Reads the spectra in `path` (a wavelength column and one column per sample; `percent`: divided by 100) and
/// analyses them with the visual system and options of `spec`.
pub fn analyse_file(path: &std::path::Path, spec: &iridis_vision::Spec, percent: bool) -> Result<SpectraVision> {
    let system = spec.system().context("--visual")?;
    let options = spec.options(&system)?;
    let mut table = iridis_vision::SpectraTable::from_csv_path(path)?;
    if percent {
        for (_, v) in &mut table.samples {
            v.iter_mut().for_each(|x| *x /= 100.0);
        }
    }
    let mut analysis = iridis_vision::analyse_table(&table, &system, &options)?;
    if !percent {
        analysis.notes.extend(iridis_vision::table::percent_note(
            &table.samples,
            "give --percent (Python: percent=True)",
            options.noise_model == iridis_vision::model::NoiseModel::Quantum,
        ));
    }
    Ok(SpectraVision { source: path.display().to_string(), samples: table.samples.len(), analysis })
}

/// What ΔS and ΔL in JND rest on, as two lines for people: the light and the adaptation (von Kries), and the
/// receptor noise (model, Weber fraction, densities, the `e_i`) with the achromatic channel. `iridis vision`
/// prints them, and so do the commands that end in an animal's view (`brdf vision`, `thinfilm color --visual`).
pub fn conditions(r: &iridis_vision::Analysis) -> (String, String) {
    let join = |v: &[f64], digits: usize| v.iter().map(|x| format!("{x:.digits$}")).collect::<Vec<_>>().join(", ");
    let bg = match r.background.kind.as_str() {
        "none" => "no von Kries adaptation".to_string(),
        "grey" => format!("von Kries to a grey of reflectance {}", r.background.reflectance.unwrap_or(1.0)),
        _ => format!("von Kries to {}", r.background.source.as_deref().unwrap_or("a spectrum")),
    };
    let light = format!("{} ×{}; {bg}", r.illuminant, r.illuminant_scale);
    let noise = match (r.noise.weber, &r.noise.reference, &r.noise.densities) {
        (Some(w), Some(rf), Some(d)) => format!(
            "{} noise, Weber fraction {w} of {rf}, densities {} → e = {}",
            serde_json::to_value(r.noise.model).ok().and_then(|v| v.as_str().map(String::from)).unwrap_or_default(),
            d.iter().map(|x| x.to_string()).collect::<Vec<_>>().join(":"),
            join(&r.noise.receptor_noise, 3)
        ),
        _ => format!("noise per receptor e = {}", join(&r.noise.receptor_noise, 3)),
    };
    let achro = match (&r.noise.achromatic, r.noise.achromatic_weber) {
        (Some(c), Some(w)) => format!("; achromatic: {c}, Weber fraction {w}"),
        _ => "; no achromatic channel".into(),
    };
    (light, format!("{noise}{achro}"))
}

impl SpectraVision {
    /// What `--json` prints: the analysis (docs/vision.md).
    pub fn to_json(&self) -> Result<serde_json::Value> {
        Ok(serde_json::to_value(&self.analysis)?)
    }

    /// The analysis for people: what was assumed, then tables with units.
    pub fn text(&self) -> String {
        use std::fmt::Write as _;
        let join = |v: &[f64], digits: usize| v.iter().map(|x| format!("{x:.digits$}")).collect::<Vec<_>>().join(", ");
        let (r, mut o) = (&self.analysis, String::new());
        let names = r.receptors.join(", ");
        let _ = writeln!(o, "visual       {} — receptors {names}", r.visual.name);
        let _ = writeln!(o, "source       {}", r.visual.source);
        let (light, noise) = conditions(r);
        let _ = writeln!(o, "light        {light}");
        let _ = writeln!(o, "noise        {noise}");
        let _ = writeln!(
            o,
            "spectra      {}: {} sample{}, {}–{} nm",
            self.source,
            self.samples,
            if self.samples == 1 { "" } else { "s" },
            r.wavelength_range_nm[0],
            r.wavelength_range_nm[1]
        );
        let width = r.samples.iter().map(|s| s.name.chars().count()).max().unwrap_or(6).max(6);
        let _ = writeln!(
            o,
            "\nquantum catches q ({}; relative catches in brackets)",
            if r.background.kind == "none" { "absolute" } else { "relative to the background" }
        );
        let _ = write!(o, "  {:<width$}", "sample");
        for n in &r.receptors {
            let _ = write!(o, " {n:>18}");
        }
        let _ = writeln!(o);
        for s in &r.samples {
            let _ = write!(o, "  {:<width$}", s.name);
            for (q, rel) in s.quantum_catches.iter().zip(&s.relative_catches) {
                let _ = write!(o, " {:>18}", format!("{q:.4} ({rel:.3})"));
            }
            let _ = writeln!(o);
        }
        if let Some(space) = r.colour_space {
            let _ = writeln!(
                o,
                "\ncolour space: {space} (position; hue in degrees from +x; chroma = distance from the achromatic point)"
            );
            for s in &r.samples {
                if let Some(c) = &s.coordinates {
                    let hue = c.hue_deg.map_or("—".to_string(), |h| format!("{h:.1}°"));
                    let elev = c.elevation_deg.map_or(String::new(), |e| format!(", elevation {e:.1}°"));
                    let _ = writeln!(
                        o,
                        "  {:<width$}  ({})  hue {hue}{elev}, chroma {:.4}",
                        s.name,
                        join(&c.position, 4),
                        c.chroma
                    );
                } else {
                    // Relative catches of a sample that catches nothing are 0/0: it has no place in the space.
                    let _ = writeln!(o, "  {:<width$}  — (it catches no light: no position)", s.name);
                }
            }
        }
        if r.distances.is_empty() {
            let _ = writeln!(o, "\ndistances: none — one sample has no other to be compared with (give two or more)");
            return o;
        }
        let _ = writeln!(o, "\ndistances (JND: 1 is just noticeable)");
        let _ = writeln!(o, "  {:<width$}  {:<width$}  {:>10}  {:>10}", "a", "b", "ΔS (JND)", "ΔL (JND)");
        let f = |v: Option<f64>| v.map_or("—".to_string(), |x| format!("{x:.3}"));
        for d in &r.distances {
            let _ = writeln!(o, "  {:<width$}  {:<width$}  {:>10}  {:>10}", d.a, d.b, f(d.delta_s), f(d.delta_l));
        }
        o
    }
}
