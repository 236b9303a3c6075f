//! The diffraction model's options and the steps every front end takes with them: the spectral setup, the
//! coherence length (given or fitted to the patch), the Taylor terms, lookup tables built or loaded and checked
//! against the options.

use std::path::Path;

use anyhow::{bail, Result};
use iridis_color::{Illuminant, Observer};
use iridis_diffraction::table::{LookupTable, Provenance, TableParams};
use iridis_diffraction::taylor::{remainder_bound, terms_for_bound, window_radius, Band};
use iridis_diffraction::{Coherence, Patch, SpectralSetup, TaylorTerms};
use iridis_gpu::Gpu;

use crate::report::{with_progress, Report};
use crate::surface::{load_patch, SurfaceOptions};

/// The name of the rigorous method (`--method rigorous`): the scalar lobes carrying Maxwell's efficiencies
/// ([`crate::rigorous_brdf`]); not one of the lab's methods.
pub const RIGOROUS: &str = "rigorous";

/// Bound on the Taylor remainder used by `--terms auto` (PHYSICS.md).
pub const DEFAULT_EPSILON: f64 = 1e-6;

/// The model's options (the CLI's `--terms --coherence --illuminant --observer --step`).
#[derive(Debug, Clone)]
pub struct ModelOptions {
    /// Taylor terms: `auto` (from the remainder bound) or a number N (terms 0..N).
    pub terms: String,
    /// Coherence length 4σ_s of the Gaussian window (nm), a property of the light; default 65 µm (the paper's).
    pub coherence_nm: Option<f64>,
    /// Illuminant: d65 (default), d50, a, e.
    pub illuminant: Option<String>,
    /// Observer: 1931 (default) or 1964.
    pub observer: Option<String>,
    /// Wavelength step of the spectral integral (nm); default 5.
    pub step_nm: Option<f64>,
    /// Scale each lobe by its order's factor in the energy-normalised channel matrix, so that the BRDF
    /// returns no more light than it receives (`iridis_diffraction::grating::LobeScaled::energy_normalised`; reference and
    /// ground truths).
    pub conserve_energy: bool,
    /// The one light direction the evaluator will be asked about (a BRDF map's incidence): the reference
    /// method's Taylor terms then keep only the DFT bins that light's lobes read (a twentieth of a 50 nm
    /// scan's; other light would read zeros). `None`: any light.
    pub light: Option<[f64; 3]>,
    /// The medium under the relief for the rigorous method (a stack's medium: `gold`, `keratin`, `n=1.5`, …;
    /// default [`crate::grating::DEFAULT_MATERIAL`]).
    pub material: Option<String>,
    /// Take a scan's dominant period, its profile averaged along the ridges, as the unit cell
    /// ([`crate::grating::averaged_unit_cell`]) instead of the whole patch (the rigorous method).
    pub unit_cell_auto: bool,
}

impl Default for ModelOptions {
    fn default() -> Self {
        Self {
            terms: "auto".into(),
            coherence_nm: None,
            illuminant: None,
            observer: None,
            step_nm: None,
            conserve_energy: false,
            light: None,
            material: None,
            unit_cell_auto: false,
        }
    }
}

impl ModelOptions {
    /// The wavelength step (nm): the one given, or 5 nm.
    pub fn step(&self) -> f64 {
        self.step_nm.unwrap_or(5.0)
    }
}

/// Spectral setup from the options (defaults: D65, CIE 1931, 5 nm).
pub fn spectral_setup(m: &ModelOptions, report: &dyn Report) -> Result<SpectralSetup> {
    let ill: Illuminant = m.illuminant.as_deref().unwrap_or("d65").parse()?;
    let obs: Observer = m.observer.as_deref().unwrap_or("1931").parse()?;
    let step = m.step();
    warn_coarse_step(step, report);
    Ok(SpectralSetup::new(ill, obs, step)?)
}

/// The paper's limit on the spectral integral's step: above 5 nm its maps show colour artefacts.
pub fn warn_coarse_step(step_nm: f64, report: &dyn Report) {
    if step_nm > 5.0 {
        report.warn(&format!("a wavelength step of {step_nm} nm shows colour artefacts (the paper: use ≤ 5 nm)"));
    }
}

/// The coherence length for a patch (the light's: the one given, or the paper's 65 µm), with the note that
/// says which and what a patch smaller than the window becomes, and the model's warnings; refused where the
/// patch's sampling cannot carry it ([`Patch::check_coherence`]).
pub fn coherence_for(patch: &Patch, given_nm: Option<f64>, report: &dyn Report) -> Result<f64> {
    coherence_noted(patch, given_nm, Coherence::note, report)
}

/// [`coherence_for`] the finite aperture (the ground truth), whose note says that a smaller patch is seen once.
pub fn coherence_for_finite_aperture(patch: &Patch, given_nm: Option<f64>, report: &dyn Report) -> Result<f64> {
    coherence_noted(patch, given_nm, Coherence::finite_aperture_note, report)
}

fn coherence_noted(
    patch: &Patch,
    given_nm: Option<f64>,
    note: fn(&Coherence) -> String,
    report: &dyn Report,
) -> Result<f64> {
    let c = patch.coherence(given_nm);
    patch.check_coherence(c.nm)?;
    report.note(&note(&c));
    for w in patch.warnings() {
        report.warn(&w);
    }
    Ok(c.nm)
}

/// The remainder bound above which a given `--terms` is warned about: the colours may be off by more than
/// 0.1 % of the amplitude.
pub const TERMS_WARN_REMAINDER: f64 = 1e-3;

/// The number of Taylor terms the options ask for (`auto`: from the remainder bound at `auto_from_nm`, the
/// shortest wavelength the terms serve). A relief too deep for the expansion is refused whatever the count; a
/// given count whose remainder bound exceeds [`TERMS_WARN_REMAINDER`] there is warned about.
pub fn term_count(patch: &Patch, m: &ModelOptions, auto_from_nm: f64, report: &dyn Report) -> Result<usize> {
    let auto = terms_for_bound(patch.max_abs_height, auto_from_nm, DEFAULT_EPSILON)?;
    let t = m.terms.trim();
    if t == "auto" {
        return Ok(auto);
    }
    let n = match t.parse::<usize>() {
        Ok(n) if n <= 200 => n,
        _ => bail!("--terms '{t}' must be 'auto' or a number of terms from 0 to 200"),
    };
    let bound = remainder_bound(patch.max_abs_height, auto_from_nm, n);
    if bound > TERMS_WARN_REMAINDER {
        report.warn(&format!(
            "--terms {n}: the Taylor remainder bound at {auto_from_nm} nm is {bound:.1e} of the amplitude for this \
             relief (|h|max {:.0} nm), so the colours may be far off; --terms auto takes N = {auto} (bound \
             {DEFAULT_EPSILON:.0e})",
            patch.max_abs_height
        ));
    }
    Ok(n)
}

/// Taylor terms of a patch, with progress: every DFT bin (what a lookup table or a GPU reads).
pub fn taylor_terms(patch: &Patch, m: &ModelOptions, report: &dyn Report) -> Result<TaylorTerms> {
    taylor_terms_in_band(patch, m, None, Coherence::note, report)
}

/// [`taylor_terms`] of a grating's unit cell (the rigorous method's), whose coherence note says that the cell
/// repeats by design: not that periods read off it are uncertain by `± d²/(2L)` (`L` the cell's own width, an
/// averaged cell's two rows).
pub fn taylor_terms_of_unit_cell(patch: &Patch, m: &ModelOptions, report: &dyn Report) -> Result<TaylorTerms> {
    taylor_terms_in_band(patch, m, None, Coherence::unit_cell_note, report)
}

/// [`taylor_terms`] keeping only the bins that light of wavelengths from `lambda_min_nm` up reads between
/// any two directions above the surface (`2/λ` about zero, widened by the window's `4σ_f`): what an evaluator
/// of those wavelengths needs, a fifth of the bins of a scan sampled at 50 nm; with [`ModelOptions::light`],
/// those of that light only (`1/λ` about `ω_i,xy/λ`).
pub fn taylor_terms_for_light(
    patch: &Patch,
    m: &ModelOptions,
    lambda_min_nm: f64,
    report: &dyn Report,
) -> Result<TaylorTerms> {
    taylor_terms_in_band(patch, m, Some(lambda_min_nm), Coherence::note, report)
}

fn taylor_terms_in_band(
    patch: &Patch,
    m: &ModelOptions,
    lambda_min_nm: Option<f64>,
    note: fn(&Coherence) -> String,
    report: &dyn Report,
) -> Result<TaylorTerms> {
    let coherence = coherence_noted(patch, m.coherence_nm, note, report)?;
    // `auto` at 380 nm, where the CIE grid begins.
    let n = term_count(patch, m, 380.0, report)?;
    let band = match lambda_min_nm {
        // The margin covers the rounding of the window's radius.
        Some(l) => match m.light {
            Some(wi) => Band::light(wi, l, 1.001 * window_radius(coherence)),
            None => Band::directions(l, 1.001 * window_radius(coherence)),
        },
        None => Band::ALL,
    };
    let terms = with_progress(report, n as u64 + 1, "Taylor terms", |p| {
        TaylorTerms::compute_in_band(patch, n, coherence, band, p)
    })?;
    report.info(&format!(
        "{}×{} samples at {:.1} × {:.1} nm, |h|max {:.1} nm, N = {n} Taylor terms, coherence {:.1} µm",
        patch.cols,
        patch.rows,
        patch.dx,
        patch.dy,
        patch.max_abs_height,
        coherence / 1000.0
    ));
    Ok(terms)
}

/// Builds a lookup table, with progress: on the CPU, or with `gpu` on the GPU in f32 (`iridis precompute --gpu`;
/// the time and the adapter are reported).
pub fn build_table(
    gpu: Option<&Gpu>,
    terms: &TaylorTerms,
    spectral: &SpectralSetup,
    params: TableParams,
    name: &str,
    report: &dyn Report,
) -> Result<LookupTable> {
    let Some(gpu) = gpu else {
        return Ok(with_progress(report, params.uv_resolution as u64, "lookup tables", |p| {
            LookupTable::build(terms, spectral, params, name, p)
        })?);
    };
    let t = std::time::Instant::now();
    let table = with_progress(report, params.uv_resolution as u64, "lookup tables (GPU)", |p| {
        iridis_gpu::build_table(gpu, terms, spectral, params, name, p)
    })?;
    report.info(&format!("lookup tables built on {} in f32, {:.2} s", gpu.adapter_name(), t.elapsed().as_secs_f64()));
    Ok(table)
}

/// The u-v grid of the lookup table a command builds from a SURFACE, as the user gave it (`None`: the default,
/// [`TableParams::default`]). Where no table is built from it — a finished TABLE, a method other than lookup —
/// it is refused, not ignored (with the feature `cli`, the flags of every command that builds a table).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
#[cfg_attr(feature = "cli", derive(clap::Args))]
pub struct TableGrid {
    /// u-v samples per axis of the lookup table built from a SURFACE (3 to 4001) [default: 501]; refused where
    /// none is built (a finished TABLE, another method).
    #[cfg_attr(feature = "cli", arg(long = "uv-resolution", value_name = "N"))]
    pub uv_resolution: Option<usize>,
    /// Exponent a of that table's non-linear u-v grid (1 = linear, up to 20) [default: 5]; refused where none is
    /// built.
    #[cfg_attr(feature = "cli", arg(long = "uv-power", value_name = "A"))]
    pub uv_power: Option<f64>,
}

impl TableGrid {
    /// The grid a table from a SURFACE is built on.
    pub fn params(&self) -> Result<TableParams> {
        self.params_or(TableParams::default())
    }

    /// The grid, with `default`'s values for what was not given; refused here, before any work, where out of
    /// range ([`TableParams::validate`]; the table's build checked it only after the Taylor terms).
    pub fn params_or(&self, default: TableParams) -> Result<TableParams> {
        let p = TableParams {
            uv_resolution: self.uv_resolution.unwrap_or(default.uv_resolution),
            uv_power: self.uv_power.unwrap_or(default.uv_power),
        };
        p.validate()?;
        Ok(p)
    }

    /// What was given, as flags (`--uv-resolution 101`, `--uv-power 1`).
    pub fn flags(&self) -> Vec<String> {
        let mut given: Vec<String> = self.uv_resolution.map(|v| format!("--uv-resolution {v}")).into_iter().collect();
        given.extend(self.uv_power.map(|p| format!("--uv-power {p}")));
        given
    }

    /// Refuses what was given when `method` builds no table from it, naming the method that would.
    pub fn refuse_unless_lookup(&self, method: &str) -> Result<()> {
        let given = self.flags();
        if method != "lookup" && !given.is_empty() {
            bail!(
                "{} would be ignored: the {method} method builds no lookup table (the lookup method does)",
                given.join(", ")
            );
        }
        Ok(())
    }
}

/// Refuses, when INPUT is a finished table, the options that only shape how a table is built (`grid`) or how a
/// surface is read (`surface`'s pixel size and height of white): they would be silently ignored. `command` is
/// the one that was given them, as the message names it (`` `iridis brdf eval` ``, Python's "the call").
pub fn refuse_build_options_for_table(
    input: &str,
    grid: TableGrid,
    surface: &SurfaceOptions,
    command: &str,
) -> Result<()> {
    if !is_table(input) {
        return Ok(());
    }
    refuse_build_options(input, grid, surface, command)
}

/// [`refuse_build_options_for_table`] for a table already loaded (`input` names it in the message).
pub fn refuse_build_options(input: &str, grid: TableGrid, surface: &SurfaceOptions, command: &str) -> Result<()> {
    let mut given = grid.flags();
    // How a SURFACE is read (`--level none`, `--override-units`).
    given.extend(surface.given().into_iter().map(|(flag, value)| match value {
        Some(v) => format!("{flag} {v}"),
        None => flag.to_string(),
    }));
    if !given.is_empty() {
        bail!(
            "{input} is a finished lookup table, so {} would be ignored: these options shape how a table is built \
             from a SURFACE; pass them to `iridis precompute` (or give {command} the surface itself)",
            given.join(", ")
        );
    }
    Ok(())
}

/// Whether INPUT is a lookup table from `iridis precompute` rather than a height field, by content: a height
/// field may be an `.npz` too (`np.savez`), a table is the archive with iridis' `metadata_json`.
pub fn is_table(input: &str) -> bool {
    !input.starts_with("builtin:") && LookupTable::is_table_file(Path::new(input))
}

/// Rejects model options that contradict a table's metadata (the library's provenance check, on the fields
/// the user gave: the table alone has no surface to fingerprint), and repeats the warnings the table was built
/// with (pixel size, patch size against the coherence length).
pub fn check_against_table(t: &LookupTable, m: &ModelOptions, report: &dyn Report) -> Result<()> {
    for w in &t.meta.warnings {
        report.warn(&format!("the table was computed from a surface with this problem: {w}"));
    }
    let terms = match m.terms.trim() {
        "auto" => None,
        s => Some(s.parse::<usize>().map_err(|_| anyhow::anyhow!("--terms '{s}' must be 'auto' or a number"))?),
    };
    let illuminant = match &m.illuminant {
        Some(i) => Some(i.parse::<Illuminant>()?.name().to_string()),
        None => None,
    };
    let expected = Provenance {
        coherence_nm: m.coherence_nm,
        illuminant,
        observer: m.observer.clone(),
        wavelength_step_nm: m.step_nm,
        taylor_terms: terms,
        ..Provenance::default()
    };
    let problems = t.mismatches(&expected);
    if !problems.is_empty() {
        bail!(
            "the table was computed with other parameters ({}); run `iridis precompute` with the ones you want",
            problems.join("; ")
        );
    }
    Ok(())
}

/// The lookup table of a TABLE (checked against the options) or built from a SURFACE ([`build_table`]: on the
/// GPU with `gpu`).
pub fn lookup_table(
    gpu: Option<&Gpu>,
    input: &str,
    model: &ModelOptions,
    params: TableParams,
    surface: &SurfaceOptions,
    report: &dyn Report,
) -> Result<LookupTable> {
    if is_table(input) {
        let table = LookupTable::load(Path::new(input))?;
        check_against_table(&table, model, report)?;
        return Ok(table);
    }
    let patch = load_patch(input, surface, report)?;
    let spectral = spectral_setup(model, report)?;
    let terms = taylor_terms(&patch, model, report)?;
    build_table(gpu, &terms, &spectral, params, input, report)
}
