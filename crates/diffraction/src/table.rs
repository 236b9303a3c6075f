//! Lookup tables `I_p(u, v)` and the lookup evaluator (paper eq. 10–12 and sec. 5).
//!
//! `X = C(ω_i, ω_r) Σ_{p=0}^{2N} w^p I_p(u, v)` with
//! `I_p(u,v) = Σ_λ w_x(λ) Σ_{n+m=p} k^p/(n! m!) Re(F_n F_m*)` at `f = (−u/λ, −v/λ)` (PHYSICS.md's sign),
//! tabulated on the non-linear grid `u_i = 2·sign(s_i)|s_i|^a`, `s_i` uniform in [−1, 1] (sec. 5, a = 5).
//!
//! File format (`.npz`, numpy-readable, stored uncompressed like `np.savez`): `I` (float64, shape
//! `[res_v, res_u, 3, 2N+1]`: v index, u index, channel X/Y/Z, power p), `uv` (float64, the grid values of
//! both axes, increasing), `wavelengths_nm`, and `metadata_json` (uint8, UTF-8 JSON; [`TableMeta`]).

use std::io::{Read, Seek, Write};
use std::path::Path;
use std::sync::Arc;

use iridis_color::{Illuminant, Observer, Xyz};
use npyz::WriterBuilder;
use num_complex::Complex64;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::evaluator::{AsAny, Evaluator};
use crate::geometry::{uvw, Shading, Vec3};
use crate::spectral::SpectralSetup;
use crate::taylor::TaylorTerms;
use crate::DiffractionError;

/// The table format this build reads and writes.
pub const FORMAT: &str = "iridis-lookup-table";
pub const FORMAT_VERSION: u32 = 1;

/// Parameters of a table's u-v grid.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TableParams {
    /// Samples per axis (the paper: up to 501).
    pub uv_resolution: usize,
    /// Exponent `a` of the non-linear grid; 1 is linear (the paper: 5).
    pub uv_power: f64,
}

impl Default for TableParams {
    fn default() -> Self {
        Self { uv_resolution: 501, uv_power: 5.0 }
    }
}

impl TableParams {
    /// Checks the grid: 3–4001 samples per axis, exponent 1–20.
    pub fn validate(&self) -> Result<(), DiffractionError> {
        let res = self.uv_resolution;
        if !(3..=4001).contains(&res) {
            return Err(DiffractionError::Invalid(format!("u-v resolution {res} must be between 3 and 4001")));
        }
        if !(self.uv_power.is_finite() && self.uv_power >= 1.0 && self.uv_power <= 20.0) {
            return Err(DiffractionError::Invalid(format!("u-v power {} must be between 1 and 20", self.uv_power)));
        }
        Ok(())
    }

    /// The grid values of both axes, increasing ([`grid_value`]).
    pub fn grid(&self) -> Vec<f64> {
        (0..self.uv_resolution).map(|i| grid_value(i, self.uv_resolution, self.uv_power)).collect()
    }
}

/// `k^n / n!` for `n = 0..=N` at each wavelength, `k = 2π/λ`: the Taylor factors of eq. 6 that turn `F_n` into
/// `G_n` (eq. 11–12).
pub fn taylor_scale(wavelengths_nm: &[f64], n: usize) -> Vec<Vec<f64>> {
    wavelengths_nm
        .iter()
        .map(|&l| {
            let k = std::f64::consts::TAU / l;
            let mut s = vec![1.0; n + 1];
            for m in 1..=n {
                s[m] = s[m - 1] * k / m as f64;
            }
            s
        })
        .collect()
}

/// Everything needed to interpret (and reproduce) a table.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct TableMeta {
    pub format: String,
    pub version: u32,
    /// Where the height field came from (a path or `builtin:NAME`).
    pub surface: String,
    pub rows: usize,
    pub cols: usize,
    pub dx_nm: f64,
    pub dy_nm: f64,
    pub max_abs_height_nm: f64,
    /// Highest Taylor term `N`; the table holds `2N + 1` powers.
    pub taylor_terms: usize,
    pub coherence_nm: f64,
    pub uv_resolution: usize,
    pub uv_power: f64,
    pub illuminant: String,
    pub observer: String,
    pub wavelength_step_nm: f64,
    pub wavelength_min_nm: f64,
    pub wavelength_max_nm: f64,
    /// Human-readable layout of `I`.
    pub layout: String,
    /// What the user was warned about when the table was computed ([`crate::Patch::warnings`]): shown again
    /// whenever the table is used. Absent in tables written before it existed.
    #[serde(default)]
    pub warnings: Vec<String>,
    /// [`crate::Patch::fingerprint`] of the height field; absent in tables written before it existed.
    #[serde(default)]
    pub surface_fingerprint: Option<String>,
    /// The light's relative power at each of `wavelengths_nm` when a custom spectrum (a laser) replaced the
    /// illuminant (`illuminant` is then `light`); absent otherwise.
    #[serde(default)]
    pub light_spectrum: Option<Vec<f64>>,
    /// What the colours measure ([`crate::Units`]): `relative` (the paper's) or `radiometric`. Absent in tables
    /// written before it existed, which are relative.
    #[serde(default = "relative_units")]
    pub units: String,
    /// The device that computed the values when it was not the CPU (in `f64`): a GPU adapter's name (the GPU
    /// computes in `f32`, docs/gpu.md). Absent for tables built on the CPU.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub built_on: Option<String>,
}

fn relative_units() -> String {
    crate::Units::Relative.name().into()
}

impl TableMeta {
    /// The table's [`crate::Units`].
    pub fn units(&self) -> Result<crate::Units, DiffractionError> {
        self.units.parse()
    }
}

/// What a table must have been made from, to be used for a surface and settings. `None` fields are not
/// checked: `brdf-map` on a table alone checks the options a user gave; the lab, which has the surface, all.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Provenance {
    pub surface_fingerprint: Option<String>,
    /// Samples `(rows, cols)`.
    pub size: Option<(usize, usize)>,
    /// Pixel size `(dx, dy)` (nm).
    pub pixel_nm: Option<(f64, f64)>,
    pub coherence_nm: Option<f64>,
    /// An illuminant name (`D65`, …) or `light`.
    pub illuminant: Option<String>,
    /// The custom light's relative power on the wavelength grid (with `illuminant` = `light`).
    pub light_spectrum: Option<Vec<f64>>,
    pub observer: Option<String>,
    pub wavelength_step_nm: Option<f64>,
    /// First and last wavelength (nm).
    pub wavelength_range_nm: Option<(f64, f64)>,
    pub taylor_terms: Option<usize>,
    pub uv: Option<TableParams>,
    pub units: Option<crate::Units>,
}

impl Provenance {
    /// Everything a table built from `patch` with these settings records.
    pub fn of(
        patch: &crate::Patch,
        coherence_nm: f64,
        taylor_terms: usize,
        spectral: &SpectralSetup,
        uv: TableParams,
    ) -> Self {
        let l = spectral.wavelengths();
        Self {
            surface_fingerprint: Some(patch.fingerprint()),
            size: Some((patch.rows, patch.cols)),
            pixel_nm: Some((patch.dx, patch.dy)),
            coherence_nm: Some(coherence_nm),
            illuminant: Some(spectral.light_name().into()),
            light_spectrum: spectral.light.clone(),
            observer: Some(spectral.observer.name().into()),
            wavelength_step_nm: Some(spectral.step_nm),
            wavelength_range_nm: Some((l[0], l[l.len() - 1])),
            taylor_terms: Some(taylor_terms),
            uv: Some(uv),
            units: Some(spectral.units),
        }
    }
}

/// Equal to 1e-9 relative (values written as JSON text and read back).
fn same(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * a.abs().max(b.abs()).max(1e-300)
}

/// A lookup table in memory.
#[derive(Debug, Clone)]
pub struct LookupTable {
    pub meta: TableMeta,
    /// Grid values along u (and v): increasing, length `uv_resolution`.
    pub uv: Vec<f64>,
    pub wavelengths_nm: Vec<f64>,
    /// `I[((iv · res + iu) · 3 + c) · (2N+1) + p]`.
    pub data: Vec<f64>,
}

/// Grid value of index `i` of `res` on the non-linear grid.
pub fn grid_value(i: usize, res: usize, power: f64) -> f64 {
    let s = -1.0 + 2.0 * i as f64 / (res - 1) as f64;
    2.0 * s.signum() * s.abs().powf(power)
}

/// The grid nodes `(iv, iu)` that [`Lookup::sum`] reads at `(u, v)` on a `res`² grid of exponent `power`,
/// with their bilinear weights (in the grid's index space).
pub fn corners(res: usize, power: f64, u: f64, v: f64) -> [(usize, usize, f64); 4] {
    let (qu, qv) = (grid_index(u, res, power), grid_index(v, res, power));
    let (iu, iv) = ((qu.floor() as usize).min(res - 2), (qv.floor() as usize).min(res - 2));
    let (fu, fv) = (qu - iu as f64, qv - iv as f64);
    [
        (iv, iu, (1.0 - fu) * (1.0 - fv)),
        (iv, iu + 1, fu * (1.0 - fv)),
        (iv + 1, iu, (1.0 - fu) * fv),
        (iv + 1, iu + 1, fu * fv),
    ]
}

/// The nodes a lookup reads for these directions `(ω_i, ω_r)` (upper hemisphere), as a mask `iv · res + iu`
/// for [`LookupTable::build_nodes`].
pub fn nodes_for(params: TableParams, directions: impl IntoIterator<Item = (Vec3, Vec3)>) -> Vec<bool> {
    let res = params.uv_resolution;
    let mut mask = vec![false; res * res];
    for (wi, wr) in directions {
        if wi[2] <= 0.0 || wr[2] <= 0.0 {
            continue;
        }
        let [u, v, _] = uvw(wi, wr);
        for (iv, iu, _) in corners(res, params.uv_power, u, v) {
            mask[iv * res + iu] = true;
        }
    }
    mask
}

/// Continuous index of value `u ∈ [−2, 2]` on the grid (the inverse map the evaluator uses).
pub fn grid_index(u: f64, res: usize, power: f64) -> f64 {
    let s = u.signum() * (u.abs() / 2.0).min(1.0).powf(1.0 / power);
    (s + 1.0) / 2.0 * (res - 1) as f64
}

impl LookupTable {
    /// Computes `I_p` for every grid point, all cores, `f64` throughout (the Taylor terms grow to
    /// ~`x^x/x!` before they shrink). `progress(rows_done)` is called as rows of the grid finish.
    pub fn build(
        terms: &TaylorTerms,
        spectral: &SpectralSetup,
        params: TableParams,
        surface: &str,
        progress: &(dyn Fn(usize) + Sync),
    ) -> Result<Self, DiffractionError> {
        Self::build_nodes(terms, spectral, params, surface, None, progress)
    }

    /// [`LookupTable::build`] at the nodes `nodes` marks (`iv · res + iu`, from [`nodes_for`]) only, the others
    /// left 0: a lookup at the directions the mask was made for gives exactly what the whole table gives, at
    /// the cost of the marked nodes (a 64² BRDF map reads ~4 % of a 501² table). Not a table to keep or save.
    pub fn build_nodes(
        terms: &TaylorTerms,
        spectral: &SpectralSetup,
        params: TableParams,
        surface: &str,
        nodes: Option<&[bool]>,
        progress: &(dyn Fn(usize) + Sync),
    ) -> Result<Self, DiffractionError> {
        params.validate()?;
        if nodes.is_some_and(|m| m.len() != params.uv_resolution * params.uv_resolution) {
            return Err(DiffractionError::Invalid("the node mask does not match the table's grid".into()));
        }
        let res = params.uv_resolution;
        spectral.check_coherence(terms.coherence_nm)?;
        let n = terms.n_max;
        let np = 2 * n + 1;
        let uv = params.grid();
        let lambdas = spectral.wavelengths();
        let weights = spectral.weights.weights();
        let scale = taylor_scale(lambdas, n);
        let done = std::sync::atomic::AtomicUsize::new(0);
        let mut data = vec![0.0; res * res * 3 * np];
        data.par_chunks_mut(res * 3 * np).enumerate().for_each(|(iv, row)| {
            let v = uv[iv];
            let mut f = vec![Complex64::new(0.0, 0.0); n + 1];
            let mut d = vec![0.0; np];
            for (iu, &u) in uv.iter().enumerate() {
                if nodes.is_some_and(|m| !m[iv * res + iu]) {
                    continue;
                }
                let cell = &mut row[iu * 3 * np..(iu + 1) * 3 * np];
                for (li, &l) in lambdas.iter().enumerate() {
                    terms.windowed(-u / l, -v / l, &mut f);
                    if f.iter().all(|z| z.re == 0.0 && z.im == 0.0) {
                        continue;
                    }
                    for (z, s) in f.iter_mut().zip(&scale[li]) {
                        *z *= s;
                    }
                    // d_p = Σ_{n+m=p} Re(G_n conj G_m), G_n = k^n/n! F_n (eq. 11–12).
                    for (p, dp) in d.iter_mut().enumerate() {
                        let lo = p.saturating_sub(n);
                        let hi = p.min(n);
                        let mut acc = 0.0;
                        for a in lo..=hi {
                            let (x, y) = (f[a], f[p - a]);
                            acc += x.re * y.re + x.im * y.im;
                        }
                        *dp = acc;
                    }
                    let wt = weights[li];
                    for c in 0..3 {
                        let out = &mut cell[c * np..(c + 1) * np];
                        for (o, dp) in out.iter_mut().zip(&d) {
                            *o += wt[c] * dp;
                        }
                    }
                }
            }
            progress(done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1);
        });
        Self::from_data(terms, spectral, params, surface, data, None)
    }

    /// A table whose values were computed elsewhere — `data` in this type's layout, for these terms, settings
    /// and grid — with the metadata [`LookupTable::build`] records; `built_on` names the device (a GPU adapter,
    /// which computes in `f32`), `None` for the CPU.
    pub fn from_data(
        terms: &TaylorTerms,
        spectral: &SpectralSetup,
        params: TableParams,
        surface: &str,
        data: Vec<f64>,
        built_on: Option<String>,
    ) -> Result<Self, DiffractionError> {
        params.validate()?;
        let (res, n) = (params.uv_resolution, terms.n_max);
        if data.len() != res * res * 3 * (2 * n + 1) {
            return Err(DiffractionError::Invalid(format!(
                "{} table values for a {res}² grid with N = {n} (expected {})",
                data.len(),
                res * res * 3 * (2 * n + 1)
            )));
        }
        let lambdas = spectral.wavelengths().to_vec();
        let meta = TableMeta {
            format: FORMAT.into(),
            version: FORMAT_VERSION,
            surface: surface.into(),
            rows: terms.rows,
            cols: terms.cols,
            dx_nm: terms.dx,
            dy_nm: terms.dy,
            max_abs_height_nm: terms.max_abs_height,
            taylor_terms: n,
            coherence_nm: terms.coherence_nm,
            uv_resolution: res,
            uv_power: params.uv_power,
            illuminant: spectral.light_name().into(),
            observer: spectral.observer.name().into(),
            wavelength_step_nm: spectral.step_nm,
            wavelength_min_nm: lambdas[0],
            wavelength_max_nm: lambdas[lambdas.len() - 1],
            layout: "I[v_index, u_index, channel (X, Y, Z), power p = 0..2N]; X = C * sum_p w^p I_p".into(),
            warnings: crate::patch::model_warnings(terms.dx, terms.dy),
            surface_fingerprint: Some(terms.fingerprint.clone()),
            light_spectrum: spectral.light.clone(),
            units: spectral.units.name().into(),
            built_on,
        };
        Ok(Self { meta, uv: params.grid(), wavelengths_nm: lambdas, data })
    }

    pub fn powers(&self) -> usize {
        2 * self.meta.taylor_terms + 1
    }

    /// Each field in which the table differs from `expected`, named, with both values.
    pub fn mismatches(&self, e: &Provenance) -> Vec<String> {
        let m = &self.meta;
        let mut out = Vec::new();
        if let Some(f) = &e.surface_fingerprint {
            match &m.surface_fingerprint {
                None => out.push(format!(
                    "surface fingerprint: the table records none (written before iridis recorded it), this surface \
                     is {f}"
                )),
                Some(t) if t != f => out.push(format!(
                    "surface fingerprint: the table's height field is {t}, this one {f} (another surface, or the \
                     same one read differently)"
                )),
                _ => {}
            }
        }
        if let Some((r, c)) = e.size {
            if (m.rows, m.cols) != (r, c) {
                out.push(format!("size: the table's {}×{} samples, here {r}×{c}", m.rows, m.cols));
            }
        }
        if let Some((dx, dy)) = e.pixel_nm {
            if !(same(m.dx_nm, dx) && same(m.dy_nm, dy)) {
                out.push(format!("pixel size: the table's {} × {} nm, here {dx} × {dy} nm", m.dx_nm, m.dy_nm));
            }
        }
        if let Some(c) = e.coherence_nm {
            if !same(m.coherence_nm, c) {
                out.push(format!("coherence: the table's {} nm, here {c} nm", m.coherence_nm));
            }
        }
        if let Some(i) = &e.illuminant {
            if !i.eq_ignore_ascii_case(&m.illuminant) {
                out.push(format!("illuminant: the table's {}, here {i}", m.illuminant));
            }
        }
        if let Some(l) = &e.light_spectrum {
            let differs = match &m.light_spectrum {
                Some(t) => {
                    t.len() != l.len()
                        || t.iter().zip(l).any(|(a, b)| (a - b).abs() > 1e-9 * a.abs().max(b.abs()).max(1e-12))
                }
                None => true,
            };
            if differs {
                out.push(format!(
                    "light spectrum: {} the one given here",
                    if m.light_spectrum.is_some() {
                        "the table's differs from"
                    } else {
                        "the table records none, unlike"
                    }
                ));
            }
        }
        if let Some(o) = &e.observer {
            let parse = |s: &str| s.parse::<Observer>().ok();
            if parse(o).is_none() || parse(o) != parse(&m.observer) {
                out.push(format!("observer: the table's {}, here {o}", m.observer));
            }
        }
        if let Some(s) = e.wavelength_step_nm {
            if !same(m.wavelength_step_nm, s) {
                out.push(format!("wavelength step Δλ: the table's {} nm, here {s} nm", m.wavelength_step_nm));
            }
        }
        if let Some((a, b)) = e.wavelength_range_nm {
            if !(same(m.wavelength_min_nm, a) && same(m.wavelength_max_nm, b)) {
                out.push(format!(
                    "wavelength range: the table's {}–{} nm, here {a}–{b} nm",
                    m.wavelength_min_nm, m.wavelength_max_nm
                ));
            }
        }
        if let Some(n) = e.taylor_terms {
            if m.taylor_terms != n {
                out.push(format!("Taylor terms N: the table's {}, here {n}", m.taylor_terms));
            }
        }
        if let Some(u) = e.units {
            if m.units().ok() != Some(u) {
                out.push(format!(
                    "units: the table's colours are {}, here {} (iridis precompute --units {})",
                    m.units,
                    u.name(),
                    u.name()
                ));
            }
        }
        if let Some(p) = e.uv {
            if m.uv_resolution != p.uv_resolution || !same(m.uv_power, p.uv_power) {
                out.push(format!(
                    "u-v grid: the table's {} samples per axis at power {}, here {} at power {}",
                    m.uv_resolution, m.uv_power, p.uv_resolution, p.uv_power
                ));
            }
        }
        out
    }

    /// Refuses a table made from another surface or with other settings, naming every field that differs.
    pub fn check(&self, expected: &Provenance, path: &str) -> Result<(), DiffractionError> {
        let problems = self.mismatches(expected);
        if problems.is_empty() {
            return Ok(());
        }
        Err(DiffractionError::Table {
            path: path.into(),
            message: format!(
                "was not made from this surface with these settings ({}); run `iridis precompute` with them, or \
                 give the table's settings",
                problems.join("; ")
            ),
        })
    }

    /// Writes the table as `.npz` to any seekable writer.
    pub fn write_npz<W: Write + Seek>(&self, w: W) -> Result<(), DiffractionError> {
        let io = |e: zip::result::ZipError| DiffractionError::Io(std::io::Error::other(e));
        let mut zip = zip::ZipWriter::new(w);
        let large = self.data.len() * 8 > 2_000_000_000;
        let opts = zip::write::SimpleFileOptions::default()
            .compression_method(zip::CompressionMethod::Stored)
            .large_file(large);
        let res = self.meta.uv_resolution as u64;
        zip.start_file(npyz::npz::file_name_from_array_name("I"), opts).map_err(io)?;
        let mut wr = npyz::WriteOptions::new()
            .default_dtype()
            .shape(&[res, res, 3, self.powers() as u64])
            .writer(&mut zip)
            .begin_nd()?;
        wr.extend(self.data.iter().copied())?;
        wr.finish()?;
        for (name, values) in [("uv", &self.uv), ("wavelengths_nm", &self.wavelengths_nm)] {
            zip.start_file(npyz::npz::file_name_from_array_name(name), opts).map_err(io)?;
            let mut wr =
                npyz::WriteOptions::new().default_dtype().shape(&[values.len() as u64]).writer(&mut zip).begin_nd()?;
            wr.extend(values.iter().copied())?;
            wr.finish()?;
        }
        let json = serde_json::to_vec_pretty(&self.meta).map_err(|e| DiffractionError::Invalid(e.to_string()))?;
        zip.start_file(npyz::npz::file_name_from_array_name("metadata_json"), opts).map_err(io)?;
        let mut wr =
            npyz::WriteOptions::new().default_dtype().shape(&[json.len() as u64]).writer(&mut zip).begin_nd()?;
        wr.extend(json.iter().copied())?;
        wr.finish()?;
        zip.finish().map_err(io)?;
        Ok(())
    }

    /// Reads a table written by [`LookupTable::write_npz`], checking format, version and shapes.
    pub fn read_npz<R: Read + Seek>(r: R, path: &str) -> Result<Self, DiffractionError> {
        let bad = |message: String| DiffractionError::Table { path: path.into(), message };
        let mut zip = zip::ZipArchive::new(r).map_err(|e| bad(format!("not an npz (zip) file: {e}")))?;
        type Npy = npyz::NpyFile<std::io::Cursor<Vec<u8>>>;
        let mut array = |name: &str| -> Result<(Vec<u64>, Npy), DiffractionError> {
            let mut f = zip
                .by_name(&npyz::npz::file_name_from_array_name(name))
                .map_err(|_| bad(format!("has no array '{name}': not an iridis lookup table")))?;
            let mut bytes = Vec::new();
            f.read_to_end(&mut bytes).map_err(|e| bad(format!("array '{name}' is unreadable: {e}")))?;
            // The .npy header length is declared in the file (up to 4 GiB in version 2): check it against the
            // bytes present before the parser sizes a buffer from it.
            let declared = match bytes.get(6) {
                Some(1) if bytes.len() >= 10 => 10 + u16::from_le_bytes([bytes[8], bytes[9]]) as usize,
                Some(_) if bytes.len() >= 12 => {
                    12 + u32::from_le_bytes([bytes[8], bytes[9], bytes[10], bytes[11]]) as usize
                }
                _ => 0,
            };
            if declared > bytes.len() {
                return Err(bad(format!("array '{name}' is corrupt: its header runs past the end of the data")));
            }
            let npy = npyz::NpyFile::new(std::io::Cursor::new(bytes))
                .map_err(|e| bad(format!("array '{name}' is corrupt: {e}")))?;
            Ok((npy.shape().to_vec(), npy))
        };
        let (_, meta_npy) = array("metadata_json")?;
        let meta_bytes: Vec<u8> = meta_npy.into_vec().map_err(|e| bad(format!("metadata is corrupt: {e}")))?;
        let meta: TableMeta =
            serde_json::from_slice(&meta_bytes).map_err(|e| bad(format!("metadata is not valid JSON: {e}")))?;
        if meta.format != FORMAT {
            return Err(bad(format!("format '{}' is not '{FORMAT}'", meta.format)));
        }
        if meta.version != FORMAT_VERSION {
            return Err(bad(format!(
                "format version {} but this iridis reads version {FORMAT_VERSION}; run `iridis precompute` again",
                meta.version
            )));
        }
        let in_range = (3..=4001).contains(&meta.uv_resolution)
            && (1.0..=20.0).contains(&meta.uv_power)
            && meta.taylor_terms <= 1000;
        if !in_range {
            return Err(bad(format!(
                "metadata out of range (u-v resolution {}, power {}, N = {}): not a table iridis wrote",
                meta.uv_resolution, meta.uv_power, meta.taylor_terms
            )));
        }
        // The lengths the evaluator and the warnings use: a forged or damaged file said "lobes −34 wide". Heights
        // are at most 1 m, as iridis-surface reads every height field.
        let positive = |x: f64| x.is_finite() && x > 0.0;
        let lengths_ok = positive(meta.dx_nm)
            && positive(meta.dy_nm)
            && positive(meta.coherence_nm)
            && positive(meta.wavelength_step_nm)
            && positive(meta.wavelength_min_nm)
            && meta.wavelength_max_nm.is_finite()
            && meta.wavelength_max_nm >= meta.wavelength_min_nm
            && meta.max_abs_height_nm.is_finite()
            && (0.0..=1e9).contains(&meta.max_abs_height_nm);
        if !lengths_ok {
            return Err(bad(format!(
                "metadata out of range (pixel {} × {} nm, coherence {} nm, wavelengths {}–{} nm in {} nm steps, \
                 |h|max {} nm): not a table iridis wrote",
                meta.dx_nm,
                meta.dy_nm,
                meta.coherence_nm,
                meta.wavelength_min_nm,
                meta.wavelength_max_nm,
                meta.wavelength_step_nm,
                meta.max_abs_height_nm
            )));
        }
        meta.units().map_err(|e| bad(format!("metadata: {e}")))?;
        let res = meta.uv_resolution as u64;
        let np = (meta.taylor_terms as u64).saturating_mul(2).saturating_add(1);
        let (shape, i_npy) = array("I")?;
        if shape != [res, res, 3, np] {
            return Err(bad(format!("array I has shape {shape:?}, metadata says [{res}, {res}, 3, {np}]")));
        }
        let data: Vec<f64> = i_npy.into_vec().map_err(|e| bad(format!("array I is corrupt: {e}")))?;
        let (_, uv_npy) = array("uv")?;
        let uv: Vec<f64> = uv_npy.into_vec().map_err(|e| bad(format!("array uv is corrupt: {e}")))?;
        let (_, wl_npy) = array("wavelengths_nm")?;
        let wavelengths_nm: Vec<f64> =
            wl_npy.into_vec().map_err(|e| bad(format!("array wavelengths is corrupt: {e}")))?;
        if uv.len() as u64 != res || data.len() as u64 != res.saturating_mul(res).saturating_mul(3).saturating_mul(np) {
            return Err(bad("array sizes disagree with the metadata".into()));
        }
        // iridis' tables are normalised (|I| ≈ 6.5 at most, N = 27); beyond f32's range the GPU's copy is NaN.
        if data.iter().any(|v| !(v.is_finite() && v.abs() <= f32::MAX as f64)) {
            return Err(bad("table holds non-finite values, or values beyond f32's range (3.4e38)".into()));
        }
        Ok(Self { meta, uv, wavelengths_nm, data })
    }

    /// Writes the table to a file, atomically: into a temporary file beside it, renamed into place once whole, so
    /// a failed write (a full disk) leaves no half-written table and an existing file as it was.
    pub fn save(&self, path: &Path) -> Result<(), DiffractionError> {
        let dir = match path.parent() {
            Some(p) if !p.as_os_str().is_empty() => p,
            _ => Path::new("."),
        };
        // Errors name the file asked for, not the temporary one beside it (".iridis-vOwVAq.tmp").
        let named = |e: std::io::Error| {
            let why =
                if dir.is_dir() { e.kind().to_string() } else { format!("folder {} does not exist", dir.display()) };
            DiffractionError::Io(std::io::Error::new(e.kind(), format!("cannot write {}: {why}", path.display())))
        };
        let mut tmp = tempfile::Builder::new().prefix(".iridis-").suffix(".tmp").tempfile_in(dir).map_err(named)?;
        {
            let mut w = std::io::BufWriter::new(tmp.as_file_mut());
            self.write_npz(&mut w)?;
            w.flush()?;
        }
        // Temporary files are created private (0600); a table is an ordinary file that others may read.
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            tmp.as_file().set_permissions(std::fs::Permissions::from_mode(0o644))?;
        }
        tmp.persist(path).map_err(|e| named(e.error))?;
        Ok(())
    }

    /// Whether the file at `path` is a lookup table, by content rather than extension: a zip archive (`.npz`)
    /// holding the array `metadata_json`, which a height field saved with `np.savez` does not have. A file that
    /// is not a readable zip is not a table (the caller then reports why it is not a surface either).
    pub fn is_table_file(path: &Path) -> bool {
        let Ok(mut f) = std::fs::File::open(path) else { return false };
        let mut magic = [0u8; 4];
        if f.read_exact(&mut magic).is_err() || &magic[..2] != b"PK" {
            return false;
        }
        let Ok(f) = f.rewind().map(|_| f) else { return false };
        zip::ZipArchive::new(std::io::BufReader::new(f))
            .map(|z| z.index_for_name(&npyz::npz::file_name_from_array_name("metadata_json")).is_some())
            .unwrap_or(false)
    }

    /// Reads a table from a file.
    pub fn load(path: &Path) -> Result<Self, DiffractionError> {
        let name = path.display().to_string();
        let f = std::fs::File::open(path)
            .map_err(|e| DiffractionError::Table { path: name.clone(), message: e.to_string() })?;
        Self::read_npz(std::io::BufReader::new(f), &name)
    }

    pub fn illuminant(&self) -> Result<Illuminant, DiffractionError> {
        self.meta
            .illuminant
            .parse()
            .map_err(|e: iridis_color::cie::UnknownName| DiffractionError::Invalid(e.to_string()))
    }
    pub fn observer(&self) -> Result<Observer, DiffractionError> {
        self.meta.observer.parse().map_err(|e: iridis_color::cie::UnknownName| DiffractionError::Invalid(e.to_string()))
    }
}

/// Numeric precision of the lookup sum.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Precision {
    F64,
    /// As a GPU shader would: table values and the sum in `f32`.
    F32,
}

/// The lookup evaluator (paper sec. 5): bilinear interpolation of `I_p` in the non-linear grid's index
/// space, Horner's rule in `w`, times `C(ω_i, ω_r)` (a wavelength-independent Fresnel factor only).
#[derive(Debug, Clone)]
pub struct Lookup {
    pub table: Arc<LookupTable>,
    pub shading: Shading,
    precision: Precision,
    data32: Option<Arc<Vec<f32>>>,
}

impl Lookup {
    pub fn new(table: Arc<LookupTable>, shading: Shading, precision: Precision) -> Result<Self, DiffractionError> {
        if shading.fresnel.depends_on_wavelength() {
            return Err(DiffractionError::Invalid(format!(
                "the lookup method integrates over wavelength in advance, so its Fresnel factor must not depend on \
                 λ ({}); use --method reference or ground-truth",
                shading.fresnel.describe()
            )));
        }
        let data32 = (precision == Precision::F32).then(|| Arc::new(table.data.iter().map(|&v| v as f32).collect()));
        Ok(Self { table, shading, precision, data32 })
    }

    /// `Σ_p w^p I_p(u, v)` for the three channels.
    pub fn sum(&self, u: f64, v: f64, w: f64) -> [f64; 3] {
        let t = &self.table;
        let res = t.meta.uv_resolution;
        let np = t.powers();
        let a = t.meta.uv_power;
        let corners = corners(res, a, u, v);
        let mut out = [0.0; 3];
        match (self.precision, &self.data32) {
            (Precision::F32, Some(d32)) => {
                let w32 = w as f32;
                for (c, o) in out.iter_mut().enumerate() {
                    let mut acc = 0.0f32;
                    for p in (0..np).rev() {
                        let mut ip = 0.0f32;
                        for &(r, q, wt) in &corners {
                            ip += wt as f32 * d32[((r * res + q) * 3 + c) * np + p];
                        }
                        acc = acc * w32 + ip;
                    }
                    *o = acc as f64;
                }
            }
            _ => {
                for (c, o) in out.iter_mut().enumerate() {
                    let mut acc = 0.0;
                    for p in (0..np).rev() {
                        let mut ip = 0.0;
                        for &(r, q, wt) in &corners {
                            ip += wt * t.data[((r * res + q) * 3 + c) * np + p];
                        }
                        acc = acc * w + ip;
                    }
                    *o = acc;
                }
            }
        }
        out
    }
}

impl dyn Evaluator {
    /// The precomputed tables behind this evaluator, if it is the lookup method: what a GPU uploads to evaluate
    /// the same numbers (`iridis-gpu`). Other methods have nothing to upload.
    pub fn as_lookup(&self) -> Option<&Lookup> {
        AsAny::as_any(self).downcast_ref()
    }
}

impl Evaluator for Lookup {
    fn name(&self) -> &'static str {
        "lookup"
    }
    fn shading(&self) -> Option<&Shading> {
        Some(&self.shading)
    }
    fn radiometric_gain(&self, wavelength_nm: f64) -> Option<f64> {
        Some(crate::spectral::radiometric_gain(wavelength_nm, self.table.meta.coherence_nm))
    }
    fn coherence_nm(&self) -> Option<f64> {
        Some(self.table.meta.coherence_nm)
    }
    fn reflectance(&self, _wavelength_nm: f64, _wi: Vec3, _wr: Vec3) -> Option<f64> {
        None
    }
    fn xyz(&self, wi: Vec3, wr: Vec3) -> Xyz {
        if wi[2] <= 0.0 || wr[2] <= 0.0 {
            return Xyz::default();
        }
        let [u, v, w] = uvw(wi, wr);
        let c = self.shading.factor(500.0, wi, wr);
        let s = self.sum(u, v, w);
        Xyz::new(c * s[0], c * s[1], c * s[2])
    }
}
