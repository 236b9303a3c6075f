//! Diffraction lookup tables for materials: a `.npz` written by `iridis precompute`, or `builtin:NAME`,
//! computed on first use exactly as `iridis precompute builtin:NAME --uv-resolution R` would (auto Taylor terms
//! from the remainder bound 1e-6, 65 µm coherence, D65, CIE 1931, 5 nm) and cached on disk.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, OnceLock};

use iridis_diffraction::table::{LookupTable, TableParams, FORMAT_VERSION};
use iridis_diffraction::taylor::terms_for_bound;
use iridis_diffraction::{Patch, SpectralSetup, TaylorTerms, DEFAULT_COHERENCE_NM};

use crate::error::RenderError;

/// Where computed built-in tables are kept: `$IRIDIS_CACHE`, else `<temp dir>/iridis-cache`.
pub fn cache_dir() -> PathBuf {
    std::env::var_os("IRIDIS_CACHE").map(PathBuf::from).unwrap_or_else(|| std::env::temp_dir().join("iridis-cache"))
}

fn memory() -> &'static Mutex<HashMap<String, Arc<LookupTable>>> {
    static M: OnceLock<Mutex<HashMap<String, Arc<LookupTable>>>> = OnceLock::new();
    M.get_or_init(|| Mutex::new(HashMap::new()))
}

/// Loads (or computes and caches) a table. `spec` is a path (relative to `base`) or `builtin:NAME`.
pub fn load_table(spec: &str, base: &Path, params: TableParams) -> Result<Arc<LookupTable>, RenderError> {
    let key = match spec.strip_prefix("builtin:") {
        Some(name) => format!("{name}-uv{}-a{}-v{}", params.uv_resolution, params.uv_power, FORMAT_VERSION),
        None => base.join(spec).display().to_string(),
    };
    if let Some(t) = memory().lock().ok().and_then(|m| m.get(&key).cloned()) {
        return Ok(t);
    }
    let table = match spec.strip_prefix("builtin:") {
        None => {
            let path = base.join(spec);
            LookupTable::load(&path).map_err(|e| {
                RenderError::Input(format!(
                    "diffraction table {}: {e} (make one with `iridis precompute SURFACE -o TABLE.npz`, or write \
                     table = \"builtin:elaphe\")",
                    path.display()
                ))
            })?
        }
        Some(name) => {
            let file = cache_dir().join(format!("{key}.npz"));
            match LookupTable::load(&file) {
                Ok(t) => t,
                Err(_) => {
                    let t = compute_builtin(name, params)?;
                    // The cache is an optimisation: failing to write it is not an error.
                    let _ = save_atomic(&t, &file);
                    t
                }
            }
        }
    };
    let table = Arc::new(table);
    if let Ok(mut m) = memory().lock() {
        m.insert(key, table.clone());
    }
    Ok(table)
}

/// `iridis precompute builtin:NAME` with default model options and the given u-v grid.
pub fn compute_builtin(name: &str, params: TableParams) -> Result<LookupTable, RenderError> {
    let spec = format!("builtin:{name}");
    let hf = iridis_surface::load_surface(&spec, &Default::default()).map_err(|e| {
        RenderError::Input(format!("{spec}: {e} (built-in surfaces: {})", iridis_surface::BUILTIN_NAMES.join(", ")))
    })?;
    let err = |e: iridis_diffraction::DiffractionError| RenderError::Input(format!("{spec}: {e}"));
    let patch = Patch::from_row_major(hf.rows, hf.cols, hf.dx_nm, hf.dy_nm, &hf.heights_nm).map_err(err)?;
    let n = terms_for_bound(patch.max_abs_height, 380.0, 1e-6);
    let terms = TaylorTerms::compute(&patch, n, DEFAULT_COHERENCE_NM).map_err(err)?;
    let spectral =
        SpectralSetup::new(iridis_color::Illuminant::D65, iridis_color::Observer::Cie1931, 5.0).map_err(err)?;
    LookupTable::build(&terms, &spectral, params, &spec, &|_| {}).map_err(err)
}

fn save_atomic(t: &LookupTable, file: &Path) -> Result<(), RenderError> {
    let dir = file.parent().unwrap_or(Path::new("."));
    std::fs::create_dir_all(dir)?;
    let mut tmp = tempfile::NamedTempFile::new_in(dir)?;
    t.write_npz(&mut tmp).map_err(|e| RenderError::Input(e.to_string()))?;
    tmp.persist(file).map_err(|e| RenderError::Io(e.error))?;
    Ok(())
}
