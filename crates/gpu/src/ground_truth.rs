//! The ground truth on the GPU (`shaders/ground_truth.wgsl`): `|A(1/λ_k)|²` of
//! [`iridis_diffraction::GroundTruth`] — the coherence-windowed transform of `exp(ikwh)` summed directly over
//! the height samples, finite aperture or periodic extension — for batches of direction pairs, in `f32`; the
//! CPU turns them into colour with [`GroundTruth::xyz_from_power`] (shading, CIE weights, Nyquist), exactly as
//! its own evaluation does.
//!
//! Phases: `k(ux + vy)` reaches thousands of turns over a large patch, which `f32` cannot hold to better than
//! ~1e-4 turn, and `sin`/`cos` of drivers are only required to be accurate near zero. So the phase per lattice
//! step, `α = u·dx/λ` (and `γ = v·dy/λ`), is computed here in `f64` and passed as a 64-bit fixed-point
//! fraction of a turn; the shader multiplies it by the integer lattice index in wrapping `u32` arithmetic (exact
//! modulo one turn, `shaders/turns.wgsl`), adds the small height phase `w·h/λ` (a few turns, `f32`), and
//! evaluates `cos`/`sin` by its own polynomials after an exact reduction to an octant. The per-sample phase
//! error is then ~1e-8 turn (measured by `phase_accuracy`), against the CPU's `f64`.
//!
//! Where the CPU walks wavenumbers by a phasor recurrence (one `sin_cos` per sample and direction pair), the GPU
//! gives every wavenumber its own invocation and phase: no recurrence, so no error growing along the spectrum.

use std::time::{Duration, Instant};

use iridis_color::Xyz;
use iridis_diffraction::geometry::{uvw, Vec3};
use iridis_diffraction::map::view_direction;
use iridis_diffraction::{GroundTruth, Lattice};
use wgpu::util::DeviceExt;

use crate::lookup::storage_out;
use crate::{Gpu, GpuError, TURNS_WGSL};

/// Wavenumbers per workgroup (`WG` of the shader).
const WAVENUMBERS_PER_GROUP: usize = 64;
/// Wall time a batch of pairs aims at: long enough to keep the GPU busy, short enough for a progress bar.
const BATCH_SECONDS: f64 = 0.5;

/// The most memory [`GpuGroundTruth::power`] takes for its answer: every view pair at every wavenumber, in f32.
pub const MAX_POWER_BYTES: f64 = 8e9;

/// A ground truth uploaded to the GPU.
#[derive(Debug)]
pub struct GpuGroundTruth<'a, 'g> {
    gpu: &'g Gpu,
    gt: &'a GroundTruth,
    pipeline: wgpu::ComputePipeline,
    heights: wgpu::Buffer,
    spans: wgpu::Buffer,
    entries: wgpu::Buffer,
    ncl: u32,
    nrl: u32,
}

/// The images of one axis as spans (per live position: index, first entry, entry count) and entries
/// (lattice index, weight): lattice index `i + (m + m0)·n`, `m0` making the smallest one 0.
/// Per live position `(index, first entry, entries, 0)`, and per image `(lattice index, weight bits)`.
type Spans = (Vec<[u32; 4]>, Vec<[u32; 2]>);

fn axis_spans(images: &[Vec<(i64, f64)>], n: usize, what: &str) -> Result<Spans, GpuError> {
    let m0 = -images.iter().flatten().map(|&(m, _)| m).min().unwrap_or(0);
    let m1 = images.iter().flatten().map(|&(m, _)| m).max().unwrap_or(0);
    if ((m1 + m0 + 1) as u128) * (n as u128) > u32::MAX as u128 {
        return Err(GpuError::TooLarge(format!(
            "the periodic ground truth's window reaches {} images of the patch along {what}, more lattice steps \
             than the GPU's 32-bit indices hold; lower --coherence, or leave out --gpu",
            m1 + m0 + 1
        )));
    }
    let (mut spans, mut entries) = (Vec::new(), Vec::new());
    for (i, list) in images.iter().enumerate() {
        if list.is_empty() {
            continue;
        }
        spans.push([i as u32, entries.len() as u32, list.len() as u32, 0]);
        for &(m, g) in list {
            entries.push([(i as i64 + (m + m0) * n as i64) as u32, (g as f32).to_bits()]);
        }
    }
    Ok((spans, entries))
}

/// `x` turns as a 64-bit fixed-point fraction of a turn, `(low word, high word)`.
fn fixed_turns(x: f64) -> [u32; 2] {
    let mut f = x - x.floor();
    if !(0.0..1.0).contains(&f) {
        f = 0.0; // x − ⌊x⌋ rounds to 1 for tiny negative x
    }
    let hi = (f * 4294967296.0).floor();
    let lo = ((f * 4294967296.0 - hi) * 4294967296.0).floor();
    [lo as u32, hi as u32]
}

impl<'a, 'g> GpuGroundTruth<'a, 'g> {
    /// Uploads the ground truth's lattice (heights as `f32`, the window's images) and compiles the shader.
    pub fn new(gpu: &'g Gpu, gt: &'a GroundTruth) -> Result<Self, GpuError> {
        let l: &Lattice = gt.lattice();
        let (col_spans, col_entries) = axis_spans(&l.column_images, l.cols, "x")?;
        let (row_spans, row_entries) = axis_spans(&l.row_images, l.rows, "y")?;
        // Row entries follow the column entries.
        let offset = col_entries.len() as u32;
        let spans: Vec<[u32; 4]> =
            col_spans.iter().copied().chain(row_spans.iter().map(|s| [s[0], s[1] + offset, s[2], 0])).collect();
        let entries: Vec<[u32; 2]> = col_entries.iter().chain(&row_entries).copied().collect();
        let heights: Vec<f32> = l.heights.iter().map(|&h| h as f32).collect();
        gpu.check_storage("the height field", heights.len() as u64 * 4, "use a smaller patch or the CPU")?;
        let source = format!("{TURNS_WGSL}\n{}", include_str!("shaders/ground_truth.wgsl"));
        let (pipeline, bufs) =
            gpu.checked("uploading the height field and compiling the ground-truth shader", || {
                let module = gpu.shader("ground_truth.wgsl", &source);
                let pipeline = gpu.compute_pipeline(&module, "iridis ground truth", "power");
                let init = |label: &str, contents: &[u8]| gpu.storage_init(label, contents);
                let pad = [[0u32; 4]];
                let bufs = [
                    init("heights", bytemuck::cast_slice(&heights)),
                    init("spans", bytemuck::cast_slice(if spans.is_empty() { &pad[..] } else { &spans })),
                    init("entries", bytemuck::cast_slice(if entries.is_empty() { &[[0u32; 2]][..] } else { &entries })),
                ];
                (pipeline, bufs)
            })?;
        let [heights, spans_buf, entries_buf] = bufs;
        Ok(Self {
            gpu,
            gt,
            pipeline,
            heights,
            spans: spans_buf,
            entries: entries_buf,
            ncl: col_spans.len() as u32,
            nrl: row_spans.len() as u32,
        })
    }

    /// Every pair's power at every wavenumber is held at once: refused past [`MAX_POWER_BYTES`] rather than
    /// aborting on the allocation (a 2048² map at 4² samples a pixel asked for 34 GB).
    fn check_power_memory(&self, pairs: usize) -> Result<(), GpuError> {
        let count = self.gt.wavenumbers().len();
        let bytes = pairs as f64 * count as f64 * 4.0;
        if bytes > MAX_POWER_BYTES {
            return Err(GpuError::TooLarge(format!(
                "the GPU ground truth holds |A|² of {pairs} view directions at {count} wavenumbers at once, {:.1} GB \
                 (at most {:.0} GB): render a smaller map (--size, --subsamples), or use the lookup method",
                bytes / 1e9,
                MAX_POWER_BYTES / 1e9
            )));
        }
        Ok(())
    }

    /// `|A|²` at each of [`GroundTruth::wavenumbers`] for every pair (`[pair · count + k]`), pairs above the
    /// horizon or not. `progress(pairs_done)`.
    pub fn power(&self, pairs: &[(Vec3, Vec3)], progress: &(dyn Fn(usize) + Sync)) -> Result<Vec<f32>, GpuError> {
        let gpu = self.gpu;
        let s = self.gt.wavenumbers();
        let count = s.len();
        self.check_power_memory(pairs.len())?;
        let mut out = vec![0f32; pairs.len() * count];
        if pairs.is_empty() || self.ncl == 0 || self.nrl == 0 {
            progress(pairs.len());
            return Ok(out);
        }
        let (s0, ds) = (s[0], s[1] - s[0]);
        let l = self.gt.lattice();
        let max_binding = gpu.limits.max_storage_buffer_binding_size.min(gpu.limits.max_buffer_size);
        let cap = ((max_binding / (count as u64 * 16)) as usize)
            .min(gpu.limits.max_compute_workgroups_per_dimension as usize)
            .min(pairs.len())
            .max(1);
        // The bind group keeps the buffers it binds (the params among them) alive.
        let (phases, betas, power, bind) = gpu.checked("allocating the ground truth's batches", || {
            let phases = gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("gt phases"),
                size: (cap * count * 16) as u64,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            let betas = gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("gt betas"),
                size: (cap * count * 4) as u64,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            let power = storage_out(gpu, "gt power", (cap * count * 4) as u64);
            let params = gpu.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("gt params"),
                contents: bytemuck::cast_slice(&[count as u32, l.cols as u32, self.ncl, self.nrl]),
                usage: wgpu::BufferUsages::UNIFORM,
            });
            let bind = gpu.bind_in_order(
                "gt bindings",
                &self.pipeline,
                &[&params, &self.heights, &self.spans, &self.entries, &phases, &betas, &power],
            );
            (phases, betas, power, bind)
        })?;
        // Start small, then size batches to BATCH_SECONDS from the time per pair measured so far.
        let (mut done, mut batch, mut spent) = (0usize, 4usize.min(cap), Duration::ZERO);
        while done < pairs.len() {
            let n = batch.min(pairs.len() - done);
            let mut ph = Vec::with_capacity(n * count * 4);
            let mut be = Vec::with_capacity(n * count);
            for &(wi, wr) in &pairs[done..done + n] {
                let [u, v, w] = uvw(wi, wr);
                for k in 0..count {
                    let sk = s0 + ds * k as f64; // as GroundTruth::amplitudes
                    let [alo, ahi] = fixed_turns(u * l.dx * sk);
                    let [glo, ghi] = fixed_turns(v * l.dy * sk);
                    ph.extend([alo, ahi, glo, ghi]);
                    be.push((w * sk) as f32);
                }
            }
            gpu.queue.write_buffer(&phases, 0, bytemuck::cast_slice(&ph));
            gpu.queue.write_buffer(&betas, 0, bytemuck::cast_slice(&be));
            let t = Instant::now();
            let groups = (n as u32, count.div_ceil(WAVENUMBERS_PER_GROUP) as u32);
            crate::dispatch(gpu, None, &self.pipeline, &bind, groups, "evaluating the ground truth")?;
            let values: Vec<f32> = bytemuck::pod_collect_to_vec(&gpu.read_buffer(&power, (n * count * 4) as u64)?);
            spent += t.elapsed();
            out[done * count..(done + n) * count].copy_from_slice(&values);
            done += n;
            progress(done);
            let per_pair = spent.as_secs_f64() / done as f64;
            batch = ((BATCH_SECONDS / per_pair.max(1e-9)) as usize).clamp(1, (batch * 4).min(cap));
        }
        Ok(out)
    }

    /// The colour of each pair ([`iridis_diffraction::Evaluator::xyz`] of the ground truth): `|A|²` on the GPU,
    /// the spectral integral on the CPU; pairs below the horizon are black without GPU work.
    pub fn xyz(&self, pairs: &[(Vec3, Vec3)], progress: &(dyn Fn(usize) + Sync)) -> Result<Vec<Xyz>, GpuError> {
        let above = |p: &(Vec3, Vec3)| p.0[2] > 0.0 && p.1[2] > 0.0;
        self.check_power_memory(pairs.iter().filter(|p| above(p)).count())?;
        let lit: Vec<usize> = (0..pairs.len()).filter(|&i| above(&pairs[i])).collect();
        let lit_pairs: Vec<(Vec3, Vec3)> = lit.iter().map(|&i| pairs[i]).collect();
        let power = self.power(&lit_pairs, progress)?;
        let count = self.gt.wavenumbers().len();
        let mut out = vec![Xyz::default(); pairs.len()];
        let mut p64 = vec![0f64; count];
        for (k, &i) in lit.iter().enumerate() {
            for (d, s) in p64.iter_mut().zip(&power[k * count..(k + 1) * count]) {
                *d = *s as f64;
            }
            let (wi, wr) = pairs[i];
            out[i] = self.gt.xyz_from_power(wi, wr, &p64);
        }
        Ok(out)
    }
}

/// A `size × size` BRDF map of the ground truth on the GPU (the layout of
/// [`iridis_diffraction::map::brdf_map`]): XYZ per pixel, row-major, black outside the unit disk.
/// `progress(pixels_done)`.
pub fn ground_truth_map(
    gpu: &Gpu,
    gt: &GroundTruth,
    wi: Vec3,
    size: usize,
    progress: &(dyn Fn(usize) + Sync),
) -> Result<Vec<Xyz>, GpuError> {
    let cells: Vec<(usize, Vec3)> =
        (0..size * size).filter_map(|i| view_direction(i % size, i / size, size).map(|wr| (i, wr))).collect();
    let pairs: Vec<(Vec3, Vec3)> = cells.iter().map(|&(_, wr)| (wi, wr)).collect();
    let total = size * size;
    let xyz = GpuGroundTruth::new(gpu, gt)?.xyz(&pairs, &|d| progress(d * total / pairs.len().max(1)))?;
    let mut out = vec![Xyz::default(); total];
    for ((i, _), c) in cells.iter().zip(xyz) {
        out[*i] = c;
    }
    progress(total);
    Ok(out)
}

/// The ground-truth shader's phase arithmetic against `f64`, measured: for `n` pseudo-random cases — a
/// fraction `α` of a turn (64-bit), a lattice index `I < 2³¹`, a height phase `x ∈ [−8, 8]` turns (`f32`) —
/// the GPU's `e^{2πi(αI + x)}` against the exact value. Returns the largest `|Δ(cos, sin)|`, i.e. the phase
/// error in radians.
pub fn phase_accuracy(gpu: &Gpu, n: usize) -> Result<f64, GpuError> {
    // xorshift64*: reproducible inputs without a dependency.
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = move || {
        state ^= state >> 12;
        state ^= state << 25;
        state ^= state >> 27;
        state.wrapping_mul(0x2545_f491_4f6c_dd1d)
    };
    let cases: Vec<[u32; 4]> = (0..n.max(1))
        .map(|_| {
            let alpha = next();
            let i = (next() >> 33) as u32;
            let x = ((next() >> 11) as f64 / (1u64 << 53) as f64 * 16.0 - 8.0) as f32;
            [alpha as u32, (alpha >> 32) as u32, i, x.to_bits()]
        })
        .collect();
    let source = format!("{TURNS_WGSL}\n{}", include_str!("shaders/turns_check.wgsl"));
    let (pipeline, input, output) = gpu.checked("compiling the phase check", || {
        let module = gpu.shader("turns_check.wgsl", &source);
        let pipeline = gpu.compute_pipeline(&module, "iridis phase check", "check");
        let input = gpu.storage_init("phase cases", bytemuck::cast_slice(&cases));
        (pipeline, input, storage_out(gpu, "phase results", (cases.len() * 8) as u64))
    })?;
    let bind =
        gpu.checked("binding the phase check", || gpu.bind_in_order("phase check", &pipeline, &[&input, &output]))?;
    crate::dispatch(gpu, None, &pipeline, &bind, ((cases.len() as u32).div_ceil(64), 1), "checking the phases")?;
    let got: Vec<[f32; 2]> = bytemuck::pod_collect_to_vec(&gpu.read_buffer(&output, (cases.len() * 8) as u64)?);
    let mut worst = 0f64;
    for (c, g) in cases.iter().zip(&got) {
        let alpha = (c[1] as u64) << 32 | c[0] as u64;
        // frac(α I) exactly (α I mod 2^64), then + x; f64 keeps the sum to ~1e-15 turn.
        let t = ((alpha as u128 * c[2] as u128) as u64) as f64 / 18446744073709551616.0 + f32::from_bits(c[3]) as f64;
        let phase = std::f64::consts::TAU * (t - t.floor());
        let (s, co) = phase.sin_cos();
        worst = worst.max(((g[0] as f64 - co).powi(2) + (g[1] as f64 - s).powi(2)).sqrt());
    }
    Ok(worst)
}
