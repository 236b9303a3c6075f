//! Diffraction lookup tables for materials: a `.npz` written by `iridis precompute`, or any SURFACE the
//! command line takes — `builtin:NAME`, or a height-field file (an instrument file with its default channel,
//! `.gwy`, `.npy`, …) told apart from a table by content — computed on first use as `iridis precompute
//! SURFACE --uv-resolution R` would (a file plane-levelled, auto Taylor terms from the remainder bound 1e-6,
//! the coherence 65 µm or fitted to a smaller patch, D65, CIE 1931, 5 nm) and cached on disk, keyed by the
//! height field's content.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, OnceLock};

use iridis_diffraction::table::{LookupTable, TableParams, FORMAT_VERSION};
use iridis_diffraction::taylor::terms_for_bound;
use iridis_diffraction::{Patch, SpectralSetup, TaylorTerms, Units, DEFAULT_COHERENCE_NM};

use crate::error::RenderError;

/// Where computed built-in tables are kept: `$IRIDIS_CACHE`, else `<temp dir>/iridis-cache`.
pub fn cache_dir() -> PathBuf {
    std::env::var_os("IRIDIS_CACHE").map(PathBuf::from).unwrap_or_else(|| std::env::temp_dir().join("iridis-cache"))
}

fn memory() -> &'static Mutex<HashMap<String, Arc<LookupTable>>> {
    static M: OnceLock<Mutex<HashMap<String, Arc<LookupTable>>>> = OnceLock::new();
    M.get_or_init(|| Mutex::new(HashMap::new()))
}

/// Model options of a built-in table: those of `iridis precompute` at its defaults.
const BUILTIN_EPSILON: f64 = 1e-6;
const BUILTIN_STEP_NM: f64 = 5.0;

/// The cache key of a built-in table: a hash of everything that determines its content — the height field
/// the generator made (its [`Patch::fingerprint`], so a changed generator gives a new key), the u-v grid, the
/// model options (Taylor terms, coherence, illuminant, observer, wavelength step), the table format and the
/// version of the code that computes it. Readable prefix: the built-in's name.
pub fn builtin_key(name: &str, patch_fingerprint: &str, params: TableParams, terms: usize, units: Units) -> String {
    let what = format!(
        "{patch_fingerprint} uv={} a={} N={terms} coherence={DEFAULT_COHERENCE_NM} D65 CIE1931 step={BUILTIN_STEP_NM} \
         format={FORMAT_VERSION} iridis-render={}{}",
        params.uv_resolution,
        params.uv_power,
        env!("CARGO_PKG_VERSION"),
        // Relative tables keep the key they had before units existed.
        if units == Units::Relative { String::new() } else { format!(" units={}", units.name()) }
    );
    // FNV-1a 64: stable across runs and platforms (std's hasher is not promised to be).
    let h = what.bytes().fold(0xcbf2_9ce4_8422_2325u64, |h, b| (h ^ b as u64).wrapping_mul(0x0000_0100_0000_01b3));
    format!("{name}-{h:016x}")
}

/// Loads (or computes and caches) a table. `spec` is a path (relative to `base`) of a table or of a height
/// field, or `builtin:NAME`; what was done to a height field (its channel, levelling, a fitted coherence, its
/// warnings) is added to `notes`. A table being computed reports to [`set_table_progress`].
pub fn load_table(
    spec: &str,
    base: &Path,
    params: TableParams,
    units: Units,
    notes: &mut Vec<String>,
) -> Result<Arc<LookupTable>, RenderError> {
    let path = base.join(spec);
    if !spec.starts_with("builtin:") && path.is_file() && !LookupTable::is_table_file(&path) {
        return surface_table(&path, params, units, notes);
    }
    let Some(name) = spec.strip_prefix("builtin:") else {
        let key = path.display().to_string();
        let cached = memory().lock().ok().and_then(|m| m.get(&key).cloned());
        let table = match cached {
            Some(t) => t,
            None => Arc::new(LookupTable::load(&path).map_err(|e| {
                RenderError::Input(format!(
                    "diffraction table {}: {e} (`table` takes a table from `iridis precompute SURFACE -o \
                     TABLE.npz`, a height field — an instrument file, .gwy, .npy, … — or \"builtin:elaphe\")",
                    path.display()
                ))
            })?),
        };
        if table.meta.units().ok() != Some(units) {
            return Err(RenderError::Input(format!(
                "diffraction table {}: its colours are in {} units, the material asks for {} (make it with \
                 `iridis precompute SURFACE --units {} -o TABLE.npz`)",
                path.display(),
                table.meta.units,
                units.name(),
                units.name()
            )));
        }
        if let Ok(mut m) = memory().lock() {
            m.insert(key, table.clone());
        }
        return Ok(table);
    };
    // The height field is generated (once a process) so that the key follows it. The file's readable prefix
    // is the built-in's name without its options (`sine`, not `sine?size=4um&pixel=50nm`: `?` is not allowed
    // in a Windows file name); the key's hash covers the options through the height field's fingerprint.
    let patch = generated_patch(name)?;
    let stem = iridis_surface::builtin::builtin_parts(name).0;
    cached_table(stem, &format!("builtin:{name}"), &patch, DEFAULT_COHERENCE_NM, params, units)
}

/// The table of a height-field file, read as every command reads a SURFACE (default channel, the file's own
/// units) and plane-levelled as the model commands level files.
fn surface_table(
    path: &Path,
    params: TableParams,
    units: Units,
    notes: &mut Vec<String>,
) -> Result<Arc<LookupTable>, RenderError> {
    let spec = path.display().to_string();
    let hf = iridis_surface::load_surface(&spec, &Default::default()).map_err(|e| {
        RenderError::Input(format!(
            "{spec} is neither a lookup table (from `iridis precompute`) nor a height field iridis can read: {e}"
        ))
    })?;
    if let Some(c) = hf.meta.channel.as_ref().filter(|c| c.of > 1) {
        notes.push(format!("{spec}: {}", c.describe()));
    }
    notes.extend(hf.meta.warnings.iter().map(|w| format!("{spec}: {w}")));
    let (hf, levelling) = iridis_surface::prep::level_for_model(&spec, hf, None)
        .map_err(|e| RenderError::Input(format!("{spec}: {e}")))?;
    notes.push(format!("{spec}: {levelling}"));
    let patch = Patch::from_row_major(hf.rows, hf.cols, hf.dx_nm, hf.dy_nm, &hf.heights_nm)
        .map_err(|e| RenderError::Input(format!("{spec}: {e}")))?;
    let coherence = patch.coherence(None);
    notes.push(format!("{spec}: {}", coherence.note()));
    let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("surface");
    cached_table(stem, &spec, &patch, coherence.nm, params, units)
}

/// The table of `patch` from memory, the disk cache or computed, under a key that follows its content.
fn cached_table(
    name: &str,
    spec: &str,
    patch: &Patch,
    coherence_nm: f64,
    params: TableParams,
    units: Units,
) -> Result<Arc<LookupTable>, RenderError> {
    let n = terms_for_bound(patch.max_abs_height, 380.0, BUILTIN_EPSILON)
        .map_err(|e| RenderError::Input(format!("{spec}: {e}")))?;
    let key = table_key(name, &patch.fingerprint(), params, n, coherence_nm, units);
    if let Some(t) = memory().lock().ok().and_then(|m| m.get(&key).cloned()) {
        return Ok(t);
    }
    let file = cache_dir().join(format!("{key}.npz"));
    let table = match LookupTable::load(&file) {
        Ok(t) => t,
        Err(_) => {
            let t = compute_table(spec, patch, n, coherence_nm, params, units)?;
            // The cache is an optimisation: failing to write it is not an error.
            let _ = save_atomic(&t, &file);
            t
        }
    };
    let table = Arc::new(table);
    if let Ok(mut m) = memory().lock() {
        m.insert(key, table.clone());
    }
    Ok(table)
}

/// [`builtin_key`] for any coherence: the paper's 65 µm keeps the key it always had.
fn table_key(
    name: &str,
    fingerprint: &str,
    params: TableParams,
    terms: usize,
    coherence_nm: f64,
    units: Units,
) -> String {
    if coherence_nm == DEFAULT_COHERENCE_NM {
        return builtin_key(name, fingerprint, params, terms, units);
    }
    builtin_key(name, &format!("{fingerprint} coherence={coherence_nm}"), params, terms, units)
}

/// [`builtin_patch`], generated once a process. A process that loads several scenes (the gallery, the tests)
/// generated the same surface for every scene that uses it, only to hash it: a fifth of loading a snake scene.
fn generated_patch(name: &str) -> Result<Arc<Patch>, RenderError> {
    static PATCHES: OnceLock<Mutex<HashMap<String, Arc<Patch>>>> = OnceLock::new();
    let patches = PATCHES.get_or_init(|| Mutex::new(HashMap::new()));
    if let Some(p) = patches.lock().ok().and_then(|m| m.get(name).cloned()) {
        return Ok(p);
    }
    let patch = Arc::new(builtin_patch(name)?);
    if let Ok(mut m) = patches.lock() {
        m.insert(name.to_string(), patch.clone());
    }
    Ok(patch)
}

/// The height field of the built-in surface `builtin:NAME` as a diffraction patch (what its table is built from).
pub fn builtin_patch(name: &str) -> Result<Patch, RenderError> {
    let spec = format!("builtin:{name}");
    let hf = iridis_surface::load_surface(&spec, &Default::default()).map_err(|e| {
        RenderError::Input(format!("{spec}: {e} (built-in surfaces: {})", iridis_surface::BUILTIN_NAMES.join(", ")))
    })?;
    Patch::from_row_major(hf.rows, hf.cols, hf.dx_nm, hf.dy_nm, &hf.heights_nm)
        .map_err(|e| RenderError::Input(format!("{spec}: {e}")))
}

/// `iridis precompute builtin:NAME` with default model options and the given u-v grid.
pub fn compute_builtin(name: &str, params: TableParams, units: Units) -> Result<LookupTable, RenderError> {
    let patch = builtin_patch(name)?;
    let n = terms_for_bound(patch.max_abs_height, 380.0, BUILTIN_EPSILON)
        .map_err(|e| RenderError::Input(format!("builtin:{name}: {e}")))?;
    compute_table(&format!("builtin:{name}"), &patch, n, DEFAULT_COHERENCE_NM, params, units)
}

fn compute_table(
    spec: &str,
    patch: &Patch,
    n: usize,
    coherence_nm: f64,
    params: TableParams,
    units: Units,
) -> Result<LookupTable, RenderError> {
    let err = |e: iridis_diffraction::DiffractionError| RenderError::Input(format!("{spec}: {e}"));
    let report = progress();
    let total = params.uv_resolution + n + 1;
    let what = format!("table {spec}");
    let terms =
        TaylorTerms::compute_with_progress(patch, n, coherence_nm, &|d| report(d, total, &what)).map_err(err)?;
    let mut spectral =
        SpectralSetup::new(iridis_color::Illuminant::D65, iridis_color::Observer::Cie1931, BUILTIN_STEP_NM)
            .map_err(err)?;
    if units == Units::Radiometric {
        spectral = spectral.radiometric(coherence_nm).map_err(err)?;
    }
    // Rows finish out of order on many threads: only the call after the build says "done".
    let t = LookupTable::build(&terms, &spectral, params, spec, &|d| report((n + 1 + d).min(total - 1), total, &what))
        .map_err(err)?;
    report(total, total, &what);
    Ok(t)
}

/// How a caller hears of built-in tables being computed (seconds to minutes): `(done, total, what)`.
pub type TableProgress = dyn Fn(usize, usize, &str) + Send + Sync;

static PROGRESS: OnceLock<Box<TableProgress>> = OnceLock::new();

/// Sets, once per process, where the progress of built-in tables goes (the command line's progress bar).
pub fn set_table_progress(f: Box<TableProgress>) {
    let _ = PROGRESS.set(f);
}

fn progress() -> impl Fn(usize, usize, &str) {
    |d, t, w| {
        if let Some(f) = PROGRESS.get() {
            f(d, t, w)
        }
    }
}

fn save_atomic(t: &LookupTable, file: &Path) -> Result<(), RenderError> {
    std::fs::create_dir_all(file.parent().unwrap_or(Path::new(".")))?;
    t.save(file).map_err(|e| RenderError::Input(e.to_string()))
}
