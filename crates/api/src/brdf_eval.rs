//! `iridis brdf eval` (and Python's `iridis.diffraction.brdf_eval`): one method's BRDF for one pair of
//! directions with everything behind it — f_r(λ) in sr⁻¹ per polarisation, the relative ρ(λ), XYZ, the Fresnel
//! source and window, optionally how an animal sees it — as text and JSON.

use std::path::Path;

use anyhow::Result;
use iridis_diffraction::geometry::{direction, FresnelConvention};
use serde_json::{json, Value};

use crate::brdf::{default_method, eval_point, PointEval};
use crate::model::{refuse_build_options_for_table, TableGrid};
use crate::report::Report;
use crate::vision::FROM_NM;
use crate::{ModelOptions, SurfaceOptions};

/// What `iridis brdf eval` is asked for.
#[derive(Debug, Clone)]
pub struct EvalRequest {
    /// A SURFACE argument or a TABLE file.
    pub input: String,
    /// The method; `None`: reference for a SURFACE, lookup for a TABLE.
    pub method: Option<String>,
    pub model: ModelOptions,
    pub surface: SurfaceOptions,
    /// The Fresnel source, its convention and the shadowing term.
    pub fresnel: String,
    pub convention: FresnelConvention,
    pub shadowing: bool,
    /// u-v grid of a table the lookup method builds from a SURFACE, as given (refused with a TABLE).
    pub grid: TableGrid,
    /// Light and view directions (θ, φ) in radians.
    pub light: (f64, f64),
    pub view: (f64, f64),
    /// Also as an animal sees this direction (`iridis vision`'s visual systems).
    pub visual: Option<String>,
    /// Print the relative ρ(λ) instead of f_r in sr⁻¹.
    pub relative: bool,
}

/// The answer of `brdf eval`, with the request it answers.
#[derive(Debug)]
pub struct EvalReport {
    pub request: EvalRequest,
    pub point: PointEval,
    /// `R₀` of the Fresnel source (what ρ divides by).
    pub r0: f64,
    /// Whether the s and p columns differ by model: the rigorous method, or a Fresnel source that tells s from p
    /// (Schlick's approximation does not).
    pub polarised: bool,
    pub vision: Option<iridis_vision::Analysis>,
}

/// The method the request runs.
pub fn method_of(r: &EvalRequest) -> String {
    r.method.clone().unwrap_or_else(|| default_method(&r.input).to_string())
}

/// Evaluates the BRDF for the request; `spectra` (a CSV path, declared first) receives the spectra.
pub fn brdf_eval(r: &EvalRequest, spectra: Option<&Path>, report: &dyn Report) -> Result<EvalReport> {
    crate::output::declare_opt("--spectra", spectra, &["csv"])?;
    let (wi, wr) = (direction(r.light.0, r.light.1), direction(r.view.0, r.view.1));
    let shading = crate::fresnel::shading(&r.fresnel, r.convention, r.shadowing)?;
    refuse_build_options_for_table(&r.input, r.grid, &r.surface, "`iridis brdf eval`")?;
    let method = method_of(r);
    if method == crate::brdf::RIGOROUS {
        crate::fresnel::refuse_scalar_shading_for_rigorous(&r.fresnel, r.convention, r.shadowing)?;
    }
    r.grid.refuse_unless_lookup(&method)?;
    let r0 = shading.fresnel.normal_reflectance();
    let polarised_fresnel = shading.fresnel.polarised();
    let vision_shading = shading.clone();
    let p = eval_point(&r.input, Some(&method), &r.model, shading, r.grid.params()?, &r.surface, wi, wr, report)?;
    // A table of zeros reads like a failure; say why it is one (a 2 µm sine's orders lie in one plane, and a
    // view out of it printed 0.0000e0 at every λ without a word).
    let q = &p.query;
    if q.reflectance.as_ref().is_none_or(|rho| rho.iter().all(|x| *x == 0.0)) && [q.xyz.x, q.xyz.y, q.xyz.z] == [0.0; 3]
    {
        report.note(
            "no light goes from this light direction to this view at any wavelength: a periodic surface sends light \
             only near its diffraction orders (the grating equation), each lobe about λ/coherence wide, and this \
             view lies between them; `iridis brdf-map` shows where the light goes",
        );
    }
    if let Some(path) = spectra {
        crate::output::write_bytes(path, p.spectra_csv()?.as_bytes())?;
    }
    let mut vision = match &r.visual {
        Some(v) => {
            let spec = iridis_vision::Spec { visual: Some(v.clone()), ..Default::default() };
            // The reference method on a height field gives the animal π f_r from 300 nm (its terms made for it),
            // where its own answer, on the CIE grid, stops at 380 nm and leaves out most of a UV cone.
            if method == "reference" && !crate::model::is_table(&r.input) {
                let source = crate::surface::Source::Spec(r.input.clone());
                let (wl, factor) = crate::vision::reflectance_factor_for_vision(
                    &source,
                    &r.surface,
                    &r.model,
                    vision_shading,
                    wi,
                    wr,
                )?;
                Some(crate::brdf::vision_of_factor(&spec, &wl, factor)?)
            } else {
                Some(p.vision(&spec)?)
            }
        }
        None => None,
    };
    // The other methods' grid starts at 380 nm (the CIE observer's); where a receptor sees below it, say which
    // command starts at 300 nm.
    if let Some(v) = vision.as_mut().filter(|v| !v.notes.is_empty() && v.wavelength_range_nm[0] > FROM_NM) {
        v.notes.push(format!(
            "brdf eval's spectrum starts at {} nm, the CIE grid's; `iridis brdf vision` computes π f_r from {FROM_NM} \
             nm for animals that see ultraviolet",
            p.query.wavelengths_nm[0]
        ));
    }
    // Its notes are printed with its numbers (text) and in its JSON, not again on stderr.
    let polarised = polarised_fresnel || p.rigorous.is_some();
    Ok(EvalReport { request: r.clone(), point: p, r0, polarised, vision })
}

/// Degrees, rounded to 1e-9 (so that 30deg prints as 30).
/// What a lookup table was built from, as `brdf eval --json`'s `table` (and Python's `evaluate`).
pub fn table_json(t: &iridis_diffraction::table::TableMeta) -> Value {
    json!({"surface": t.surface, "taylor_terms": t.taylor_terms, "uv_resolution": t.uv_resolution,
        "uv_power": t.uv_power, "wavelength_step_nm": t.wavelength_step_nm,
        "wavelength_range_nm": [t.wavelength_min_nm, t.wavelength_max_nm], "illuminant": t.illuminant,
        "observer": t.observer, "coherence_nm": t.coherence_nm})
}

fn deg(r: f64) -> f64 {
    (r.to_degrees() * 1e9).round() / 1e9
}

impl EvalReport {
    /// `brdf eval --json`.
    pub fn to_json(&self) -> Result<Value> {
        let (r, p, q) = (&self.request, &self.point, &self.point.query);
        let ((tl, pl), (tv, pv)) = (r.light, r.view);
        Ok(json!({
            "input": r.input,
            "method": p.method,
            "light": { "theta_deg": deg(tl), "phi_deg": deg(pl), "direction": direction(tl, pl) },
            "view": { "theta_deg": deg(tv), "phi_deg": deg(pv), "direction": direction(tv, pv) },
            "fresnel": if p.rigorous.is_some() { Value::Null } else { json!(r.fresnel) },
            "fresnel_convention": r.convention.name(),
            "fresnel_r0": self.r0,
            "polarised": self.polarised,
            "shadowing": if p.rigorous.is_some() { Value::Null } else { json!(r.shadowing) },
            "coherence_nm": p.coherence_nm,
            "window_effective_area_um2": p.effective_area_nm2.map(|a| a / 1e6),
            "illuminant": r.model.illuminant.as_deref().unwrap_or("d65"),
            "observer": r.model.observer.as_deref().unwrap_or("1931"),
            "wavelength_nm": q.wavelengths_nm,
            "brdf_per_sr": q.brdf,
            "reflectance": q.reflectance,
            "xyz": [q.xyz.x, q.xyz.y, q.xyz.z],
            "vision": self.vision.as_ref().map(serde_json::to_value).transpose()?,
            "rigorous": p.rigorous.as_ref().map(|r| r.to_json()),
            "scalar_error": p.scalar_error.as_ref().map(|e| e.to_json()),
            "table": p.table.as_ref().map(table_json),
        }))
    }

    /// `brdf eval`'s text: the inputs, the spectra table and XYZ.
    pub fn text(&self) -> String {
        let (r, p, q) = (&self.request, &self.point, &self.point.query);
        let ((tl, pl), (tv, pv)) = (r.light, r.view);
        let area_um2 = p.effective_area_nm2.map(|a| a / 1e6);
        let coherence = p.coherence_nm.map_or("–".into(), |c| format!("{:.3} µm", c / 1000.0));
        let area = area_um2.map_or("–".into(), |x| format!("{x:.4} µm²"));
        let mut t = vec![format!(
            "{} · {} · light θ {}° φ {}° · view θ {}° φ {}°",
            r.input,
            p.method,
            deg(tl),
            deg(pl),
            deg(tv),
            deg(pv)
        )];
        t.push(match &p.rigorous {
            Some(g) => format!("{}; coherence {coherence} (window area A_eff {area})", g.sentence()),
            None => format!(
                "Fresnel {} (R₀ = {:.4}), {}, coherence {coherence} (window area A_eff {area})",
                r.fresnel,
                self.r0,
                if r.shadowing { "Cook-Torrance shadowing" } else { "no shadowing" },
            ),
        });
        if let Some(e) = &p.scalar_error {
            t.push(format!("scalar model: {}", e.sentence()));
        }
        t.extend(p.table_line());
        match (&q.reflectance, &q.brdf, r.relative) {
            (Some(_), Some(b), false) => {
                if !self.polarised {
                    t.push(format!(
                        "s = p: the Fresnel model ({}) does not tell s from p; --fresnel index:n+ki or a material \
                         (gold) gives both",
                        r.fresnel
                    ));
                }
                t.push("    λ (nm)   f_r s (sr⁻¹)   f_r p (sr⁻¹)   f_r unpol. (sr⁻¹)".into());
                for (k, l) in q.wavelengths_nm.iter().enumerate() {
                    t.push(format!("{l:10.1}  {:13.4e}  {:13.4e}  {:18.4e}", b.s[k], b.p[k], b.unpolarized[k]));
                }
            }
            (Some(rho), b, _) => {
                if b.is_none() && !r.relative {
                    t.push(format!(
                        "f_r: not available for the {} method{} — the relative reflectance instead:",
                        p.method,
                        if r.convention.name() == "paper" { " under the paper's R² convention" } else { "" }
                    ));
                }
                t.push("    λ (nm)        ρ(λ) (relative: a flat mirror's peak is 1)".into());
                for (l, x) in q.wavelengths_nm.iter().zip(rho) {
                    t.push(format!("{l:10.1}  {x:10.4e}"));
                }
            }
            (None, _, _) => {
                t.push(format!("f_r(λ), ρ(λ): not available — the {} method integrates over λ in advance", p.method))
            }
        }
        t.push(format!(
            "XYZ {:.6e} {:.6e} {:.6e}  (of ρ under {}, CIE {} observer; a normal-incidence mirror: Y = 1)",
            q.xyz.x,
            q.xyz.y,
            q.xyz.z,
            r.model.illuminant.as_deref().unwrap_or("d65").to_uppercase(),
            r.model.observer.as_deref().unwrap_or("1931")
        ));
        if let Some(v) = &self.vision {
            let s = &v.samples[0];
            let f = |x: &[f64]| x.iter().map(|c| format!("{c:.4}")).collect::<Vec<_>>().join("  ");
            let [lo, hi] = v.wavelength_range_nm;
            t.push(format!(
                "seen by {} under {} (receptors {}; π f_r from {lo} to {hi} nm):",
                v.visual.name,
                v.illuminant,
                v.receptors.join(", ")
            ));
            t.push(format!("  quantum catches (von Kries, to a grey of reflectance 1)  {}", f(&s.quantum_catches)));
            t.push(format!("  relative catches                                        {}", f(&s.relative_catches)));
            // Beside the numbers, not only on stderr: a UV cone cut off at 380 nm changes them.
            for n in &v.notes {
                t.push(format!("  note: {n}"));
            }
        }
        t.join("\n")
    }
}
