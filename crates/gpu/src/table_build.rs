//! `iridis precompute --gpu`: the lookup tables `I_p(u, v)` (paper eq. 8–12, the non-linear grid of sec. 5)
//! built by a compute shader (`shaders/table_build.wgsl`), the numbers of
//! [`iridis_diffraction::LookupTable::build`] in `f32`.
//!
//! The CPU spends its time in the windowed sums of eq. 8 — at every grid point and wavelength, `N + 1` complex
//! coefficients times the Gaussian weight of each DFT bin within `4σ_f` — and in the products of eq. 11–12;
//! both move to the GPU, one grid point per invocation looping over the wavelengths. The Taylor terms' FFTs stay
//! on the CPU (rustfft). What needs `f64` is prepared here:
//!
//! * per grid value and wavelength, the bins the window takes along each axis (the CPU's own
//!   [`window_bins`], beyond-Nyquist frequencies marked empty) and their weights `g_x = exp(−e_x)`,
//!   `e_x = (f_x − s/L_x)² / 2σ_f²` — the window is separable, `g = g_x g_y`, and the disk `|f − f_st| ≤ 4σ_f`
//!   is `e_x + e_y ≤ 8`. Frequencies are never formed in `f32`: `f·L` reaches hundreds of bins, whose `f32`
//!   rounding would shift the window by ~1e-5 of its width;
//! * the coefficients `c_n / H^n` (`H = max |h|`, so they stay ≤ 1 while `c_n` grows like `H^n` and overflows
//!   `f32` past `n ≈ 17` for `H = 150 nm`), cropped to the bins any record takes, and `(kH)^n / n!`, so that
//!   `G_n = (kH)^n/n! · F_n/H^n` is the CPU's `k^n/n! · F_n`.
//!
//! The output is read back in bands of grid rows (a 501² table with N = 22 is 136 MB, more than one storage
//! binding holds on lavapipe) and widened to `f64`.

use iridis_diffraction::table::{taylor_scale, LookupTable, TableParams};
use iridis_diffraction::taylor::window_bins;
use iridis_diffraction::{SpectralSetup, TaylorTerms};

use crate::lookup::storage_out;
use crate::{Gpu, GpuError};

/// Grid rows per dispatch at most (progress, and the watchdog of drivers that have one).
const MAX_ROWS_PER_DISPATCH: usize = 32;

/// The bins one axis's records take: per (grid value, wavelength), the first bin and the count, and the
/// window values `(g, e)` in slots of `stride`.
struct AxisWindows {
    records: Vec<[i32; 2]>,
    windows: Vec<[f32; 2]>,
    stride: usize,
    /// Smallest and largest bin any record takes (`None`: every frequency beyond Nyquist).
    span: Option<(i64, i64)>,
}

/// The window along one axis for every grid value and wavelength: the frequency is `−value/λ` (the table's
/// `f = (−u/λ, −v/λ)`, PHYSICS.md), `length` the patch's extent and `n` its samples along the axis.
fn axis_windows(grid: &[f64], lambdas: &[f64], length: f64, n: usize, pixel: f64, r: f64, inv2s2: f64) -> AxisWindows {
    let mut ranges = Vec::with_capacity(grid.len() * lambdas.len());
    for &value in grid {
        for &l in lambdas {
            let f = -value / l;
            // TaylorTerms::within_nyquist, one axis at a time (it tests both).
            let (s0, s1) = if f.abs() <= 0.5 / pixel { window_bins(f, r, length, n) } else { (0, -1) };
            ranges.push((f, s0, s1));
        }
    }
    let stride = ranges.iter().map(|&(_, s0, s1)| (s1 - s0 + 1).max(0) as usize).max().unwrap_or(0).max(1);
    let mut records = Vec::with_capacity(ranges.len());
    let mut windows = vec![[0f32; 2]; ranges.len() * stride];
    let mut span: Option<(i64, i64)> = None;
    for (k, &(f, s0, s1)) in ranges.iter().enumerate() {
        let count = (s1 - s0 + 1).max(0);
        records.push([s0 as i32, count as i32]);
        if count > 0 {
            span = Some(span.map_or((s0, s1), |(a, b)| (a.min(s0), b.max(s1))));
        }
        for j in 0..count {
            // As TaylorTerms::windowed: d = f − s/L, weight exp(−d²/2σ_f²).
            let d = f - (s0 + j) as f64 / length;
            let e = d * d * inv2s2;
            windows[k * stride + j as usize] = [(-e).exp() as f32, e as f32];
        }
    }
    AxisWindows { records, windows, stride, span }
}

/// Builds the lookup table of `terms` on the GPU: the same grid, wavelengths, weights and metadata as
/// [`LookupTable::build`] (recording the adapter in `built_on`), values computed in `f32`.
/// `progress(rows_done)` as bands of grid rows finish.
pub fn build_table(
    gpu: &Gpu,
    terms: &TaylorTerms,
    spectral: &SpectralSetup,
    params: TableParams,
    surface: &str,
    progress: &(dyn Fn(usize) + Sync),
) -> Result<LookupTable, GpuError> {
    params.validate().map_err(|e| GpuError::Invalid(e.to_string()))?;
    let res = params.uv_resolution;
    let grid = params.grid();
    let lambdas = spectral.wavelengths();
    let nl = lambdas.len();
    let (nt, np) = (terms.n_max + 1, 2 * terms.n_max + 1);
    let (lx, ly) = terms.extent();
    let r = terms.window_radius();
    let inv2s2 = 1.0 / (2.0 * terms.sigma_f * terms.sigma_f);
    let xs = axis_windows(&grid, lambdas, lx, terms.cols, terms.dx, r, inv2s2);
    let ys = axis_windows(&grid, lambdas, ly, terms.rows, terms.dy, r, inv2s2);
    let mut data = vec![0f64; res * res * 3 * np];
    let (Some((smin, smax)), Some((tmin, tmax))) = (xs.span, ys.span) else {
        // Every frequency lies beyond Nyquist: the CPU's table is zero too.
        progress(res);
        return table(terms, spectral, params, surface, data, gpu);
    };

    // The coefficients the records reach, scaled by 1/H^n.
    let h = if terms.max_abs_height > 0.0 { terms.max_abs_height } else { 1.0 };
    let inv_h: Vec<f64> = (0..nt).map(|n| h.powi(-(n as i32))).collect();
    let (width, height) = ((smax - smin + 1) as usize, (tmax - tmin + 1) as usize);
    let coef_bytes = (width * height * nt * 8) as u64;
    gpu.check_storage(
        "the Taylor coefficients the table reaches",
        coef_bytes,
        "build the table on the CPU (leave out --gpu), or use fewer --terms or a smaller patch",
    )?;
    let all = terms.coefficients();
    let mut coef = Vec::with_capacity(width * height * nt * 2);
    for t in tmin..=tmax {
        let ti = t.rem_euclid(terms.rows as i64) as usize;
        for s in smin..=smax {
            let si = s.rem_euclid(terms.cols as i64) as usize;
            let bin = &all[(ti * terms.cols + si) * nt..(ti * terms.cols + si + 1) * nt];
            for (c, k) in bin.iter().zip(&inv_h) {
                coef.extend([(c.re * k) as f32, (c.im * k) as f32]);
            }
        }
    }
    // Weights, then (kH)^n/n! = k^n/n! · H^n.
    let mut spectral_words: Vec<f32> =
        spectral.weights.weights().iter().flat_map(|w| [w[0], w[1], w[2], 0.0]).map(|v| v as f32).collect();
    for s in taylor_scale(lambdas, terms.n_max) {
        spectral_words.extend(s.iter().enumerate().map(|(n, v)| (v * h.powi(n as i32)) as f32));
    }
    let records: Vec<[i32; 2]> = xs.records.iter().chain(&ys.records).copied().collect();
    let windows: Vec<[f32; 2]> = xs.windows.iter().chain(&ys.windows).copied().collect();

    // The other inputs grow with the wavelength grid (a 0.0001 nm step: 320 MB of records), and a driver's
    // validation error would be the only word: each is checked as the coefficients are.
    let hint = "build the table on the CPU (leave out --gpu), or use a coarser --step or fewer --terms";
    gpu.check_storage("the table's window records", std::mem::size_of_val(records.as_slice()) as u64, hint)?;
    gpu.check_storage("the table's window weights", std::mem::size_of_val(windows.as_slice()) as u64, hint)?;
    gpu.check_storage("the table's spectral weights", std::mem::size_of_val(spectral_words.as_slice()) as u64, hint)?;
    let row_bytes = (res * 3 * np * 4) as u64;
    let max_binding = gpu.limits.max_storage_buffer_binding_size.min(gpu.limits.max_buffer_size);
    let rows_per_dispatch = ((max_binding / row_bytes) as usize).clamp(1, MAX_ROWS_PER_DISPATCH).min(res);
    if row_bytes > max_binding {
        return Err(GpuError::TooLarge(format!(
            "one row of the table ({:.1} MB) exceeds a storage binding of {} ({:.1} MB); build it on the CPU \
             (leave out --gpu) or with fewer --terms",
            row_bytes as f64 / 1e6,
            gpu.adapter_name(),
            max_binding as f64 / 1e6
        )));
    }
    let source =
        format!("const NT: u32 = {nt}u;\nconst NP: u32 = {np}u;\n{}", include_str!("shaders/table_build.wgsl"));
    let (pipeline, bufs) = gpu.checked("uploading the Taylor terms and compiling the table shader", || {
        let module = gpu.shader("table_build.wgsl", &source);
        let pipeline = gpu.compute_pipeline(&module, "iridis table build", "build");
        let init = |label: &str, contents: &[u8]| gpu.storage_init(label, contents);
        let bufs = [
            init("table records", bytemuck::cast_slice(&records)),
            init("table windows", bytemuck::cast_slice(&windows)),
            init("table coefficients", bytemuck::cast_slice(&coef)),
            init("table spectral", bytemuck::cast_slice(&spectral_words)),
        ];
        (pipeline, bufs)
    })?;
    let params_buf = gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("table params"),
        size: 48,
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let out = storage_out(gpu, "table rows", rows_per_dispatch as u64 * row_bytes);
    let bind = gpu.checked("binding the table buffers", || {
        gpu.bind_in_order("table bindings", &pipeline, &[&params_buf, &bufs[0], &bufs[1], &bufs[2], &bufs[3], &out])
    })?;
    let mut row0 = 0;
    while row0 < res {
        let rows = rows_per_dispatch.min(res - row0);
        let words: [u32; 12] = [
            res as u32,
            nl as u32,
            row0 as u32,
            rows as u32,
            xs.stride as u32,
            ys.stride as u32,
            width as u32,
            xs.windows.len() as u32,
            smin as i32 as u32,
            tmin as i32 as u32,
            ((r * r * inv2s2) as f32).to_bits(),
            0,
        ];
        gpu.queue.write_buffer(&params_buf, 0, bytemuck::cast_slice(&words));
        crate::dispatch(
            gpu,
            None,
            &pipeline,
            &bind,
            ((res as u32).div_ceil(8), (rows as u32).div_ceil(8)),
            "building the lookup table",
        )?;
        let values: Vec<f32> = bytemuck::pod_collect_to_vec(&gpu.read_buffer(&out, rows as u64 * row_bytes)?);
        let dst = &mut data[row0 * res * 3 * np..(row0 + rows) * res * 3 * np];
        for (d, v) in dst.iter_mut().zip(&values) {
            *d = *v as f64;
        }
        row0 += rows;
        progress(row0);
    }
    table(terms, spectral, params, surface, data, gpu)
}

fn table(
    terms: &TaylorTerms,
    spectral: &SpectralSetup,
    params: TableParams,
    surface: &str,
    data: Vec<f64>,
    gpu: &Gpu,
) -> Result<LookupTable, GpuError> {
    if let Some(bad) = data.iter().position(|v| !v.is_finite()) {
        return Err(GpuError::Driver(format!(
            "the GPU's table holds a non-finite value (entry {bad}); build it on the CPU (leave out --gpu)"
        )));
    }
    LookupTable::from_data(terms, spectral, params, surface, data, Some(gpu.adapter_name()))
        .map_err(|e| GpuError::Invalid(e.to_string()))
}

/// How far a table differs from a reference of the same grid and `N` (the GPU's from the CPU's).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TableError {
    /// `max |ΔI_p| / max |I_p|` over the cells, the largest over channels and powers `p`: each power's error
    /// relative to that power's own scale.
    pub per_power: f64,
    /// `max Σ_p 2^p |ΔI_p| / max Σ_p 2^p |I_p|` over cells and channels: a bound on the error of the lookup sum
    /// `Σ_p w^p I_p` (`|w| ≤ 2`) relative to the largest such bound of the reference.
    pub of_sum: f64,
}

/// The errors of `other` against `reference` ([`TableError`]).
pub fn table_error(reference: &LookupTable, other: &LookupTable) -> TableError {
    let np = reference.powers();
    if other.data.len() != reference.data.len() || other.powers() != np {
        return TableError { per_power: f64::INFINITY, of_sum: f64::INFINITY };
    }
    let mut scale = vec![0f64; 3 * np];
    let mut worst = vec![0f64; 3 * np];
    let (mut sum_scale, mut sum_err) = (0f64, 0f64);
    for (k, (r, o)) in reference.data.chunks_exact(np).zip(other.data.chunks_exact(np)).enumerate() {
        let c = k % 3;
        let (mut s, mut e, mut pow2) = (0.0, 0.0, 1.0);
        for p in 0..np {
            let d = (r[p] - o[p]).abs();
            scale[c * np + p] = scale[c * np + p].max(r[p].abs());
            worst[c * np + p] = worst[c * np + p].max(d);
            s += pow2 * r[p].abs();
            e += pow2 * d;
            pow2 *= 2.0;
        }
        sum_scale = sum_scale.max(s);
        sum_err = sum_err.max(e);
    }
    let per_power = scale
        .iter()
        .zip(&worst)
        .map(|(&s, &w)| {
            if s > 0.0 {
                w / s
            } else if w > 0.0 {
                f64::INFINITY
            } else {
                0.0
            }
        })
        .fold(0.0, f64::max);
    let of_sum = if sum_scale > 0.0 { sum_err / sum_scale } else { 0.0 };
    TableError { per_power, of_sum }
}
