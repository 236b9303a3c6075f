//! The thin-film shader (`shaders/film.wgsl`): film colours over an image, after Sussenbach ch. 4.
//!
//! A [`FilmFrame`] puts the incidence angle on the x axis (linear from the first to the last column) and a
//! thickness offset on the y axis (linear from the top row to the bottom row), plus optionally a spatially
//! varying thickness texture: `offset += d_rel (2α − 1)` (eq. 4.3–4.4). Every layer's thickness is its
//! stack thickness plus the offset, clamped at 0, exactly as [`iridis_thinfilm::Stack::evaluate_offset`].
//! Per pixel and wavelength sample the shader runs the recurrence of eq. 3.1–3.10 with complex indices
//! (absorbing and dispersive media: the indices are tabulated per wavelength sample on the CPU), and sums
//! `XYZ = Σ_λ w(λ) R(λ)` (and the same for T) with the weights of [`iridis_color::SpectralWeights`].
//!
//! **Two paths.** [`FilmPath::Direct`] evaluates every pixel as above (the reference). [`FilmPath::Table`] (the
//! default, issue 17) first fills a colour table over `cos θ` × offset with that same evaluation on the GPU
//! (one invocation per node; the resolution from the interference period, [`iridis_thinfilm::table`]) and then
//! shades every pixel by bilinear lookup; a stack that a table cannot follow (a critical angle inside the
//! stack, fringes too dense) is evaluated directly instead, and [`FilmRun::path`] says why.
//!
//! Not on the GPU: the CPU's treatment of a layer at exactly its critical angle (`|cos| < 1e-5`, averaged
//! over `cos² ± δ²`; `iridis_thinfilm::recurrence::grazing_variants`) — in `f32` such a pixel is evaluated
//! directly (its cosine is never exactly 0); for an air gap in glass at the critical angle the reflected Y
//! differs from the CPU's by < 1e-4 (test `a_layer_at_its_critical_angle`).

use std::time::Duration;

use iridis_color::{SpectralWeights, ToneMap, Xyz};
use iridis_thinfilm::table::TableGrid;
use iridis_thinfilm::Stack;
use rayon::prelude::*;
use wgpu::util::DeviceExt;

use crate::lookup::{display_buffer, storage_out};
use crate::{dispatch, unpack_rgb8, FrameTime, Gpu, GpuError, Timer, COMMON_WGSL, FILM_WGSL};

/// Angles and thicknesses over an image.
#[derive(Debug, Clone, PartialEq)]
pub struct FilmFrame {
    pub width: usize,
    pub height: usize,
    /// Incidence angle (rad) of the first and the last column, each in [0, π/2].
    pub angle_rad: (f64, f64),
    /// Thickness offset (nm) of the top and the bottom row, added to every layer.
    pub offset_nm: (f64, f64),
    /// Spatially varying thickness: `d_rel` (nm) and the grey texture α ∈ [0, 1], `width × height`, row-major.
    pub svt: Option<(f64, Vec<f32>)>,
}

impl FilmFrame {
    /// The incidence angle (rad) and thickness offset (nm) of a pixel: the definition the shader evaluates
    /// in `f32` and the CPU reference in `f64`.
    pub fn pixel(&self, col: usize, row: usize) -> (f64, f64) {
        let fx = col as f64 / (self.width.max(2) - 1) as f64;
        let fy = row as f64 / (self.height.max(2) - 1) as f64;
        let theta = self.angle_rad.0 + (self.angle_rad.1 - self.angle_rad.0) * fx;
        let mut offset = self.offset_nm.0 + (self.offset_nm.1 - self.offset_nm.0) * fy;
        if let Some((d_rel, alpha)) = &self.svt {
            offset += iridis_thinfilm::stack::svt_offset(*d_rel, alpha[row * self.width + col] as f64);
        }
        (theta, offset)
    }

    /// The lowest and the highest thickness offset (nm) of any pixel: the gradient's ends widened by the SVT
    /// texture's darkest and brightest grey values.
    pub fn offset_range(&self) -> (f64, f64) {
        let (a, b) = self.offset_nm;
        let (lo, hi) = (a.min(b), a.max(b));
        match &self.svt {
            Some((d_rel, alpha)) => {
                let (amin, amax) = alpha.iter().fold((1.0f32, 0.0f32), |(l, h), &a| (l.min(a), h.max(a)));
                let ends = [amin, amax].map(|a| iridis_thinfilm::stack::svt_offset(*d_rel, a as f64));
                (lo + ends[0].min(ends[1]), hi + ends[0].max(ends[1]))
            }
            None => (lo, hi),
        }
    }

    fn check(&self) -> Result<(), GpuError> {
        let side = |n: usize| u32::try_from(n).unwrap_or(u32::MAX);
        iridis_render::scene::check_image_size(side(self.width), side(self.height))
            .map_err(|e| GpuError::Invalid(format!("frame {}×{}: {e}", self.width, self.height)))?;
        let (a, b) = self.angle_rad;
        let ok = |t: f64| t.is_finite() && (0.0..=std::f64::consts::FRAC_PI_2).contains(&t);
        if !(ok(a) && ok(b)) {
            return Err(GpuError::Invalid(format!(
                "incidence angles {:.3}°…{:.3}° must lie in 0°–90°",
                a.to_degrees(),
                b.to_degrees()
            )));
        }
        if !(self.offset_nm.0.is_finite() && self.offset_nm.1.is_finite()) {
            return Err(GpuError::Invalid("thickness offsets must be finite".into()));
        }
        if let Some((d_rel, alpha)) = &self.svt {
            if alpha.len() != self.width * self.height {
                return Err(GpuError::Invalid(format!(
                    "the SVT texture has {} values for a {}×{} frame",
                    alpha.len(),
                    self.width,
                    self.height
                )));
            }
            if !d_rel.is_finite() || alpha.iter().any(|a| !(0.0..=1.0).contains(a)) {
                return Err(GpuError::Invalid("SVT: d_rel must be finite and every α in [0, 1]".into()));
            }
        }
        Ok(())
    }
}

/// Film colours read back: reflected and transmitted XYZ per pixel (row-major) and the displayed reflected
/// colour as 8-bit sRGB.
#[derive(Debug, Clone)]
pub struct FilmOutput {
    pub width: usize,
    pub height: usize,
    pub reflected: Vec<Xyz>,
    pub transmitted: Vec<Xyz>,
    pub rgb8: Vec<u8>,
}

/// How a film frame gets its colours.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FilmPath {
    /// A colour table over `cos θ` × offset, built on the GPU by the direct evaluation, then a bilinear lookup
    /// per pixel (issue 17's fast path); the direct path where the stack has no table.
    #[default]
    Table,
    /// The recurrence at every wavelength sample for every pixel (the reference).
    Direct,
}

/// The path a frame took.
#[derive(Debug, Clone, PartialEq)]
pub enum FilmPathUsed {
    /// A colour table of this grid, built on the GPU in `build` (wall clock, submission to completion).
    Table { grid: TableGrid, build: Duration },
    /// Direct evaluation; `why` says why a table was not used when one was asked for.
    Direct { why: Option<String> },
}

impl std::fmt::Display for FilmPathUsed {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Table { grid, build } => write!(
                f,
                "colour table {} cos θ × {} offset nodes ({:.0}…{:.0} nm), built in {:.2} ms",
                grid.cos_nodes,
                grid.offset_nodes,
                grid.offset_nm.0,
                grid.offset_nm.1,
                build.as_secs_f64() * 1e3
            ),
            Self::Direct { why: None } => write!(f, "direct evaluation at every wavelength sample"),
            Self::Direct { why: Some(w) } => write!(f, "direct evaluation at every wavelength sample ({w})"),
        }
    }
}

/// The film module's three pipelines, compiled once per device.
#[derive(Debug, Clone)]
pub(crate) struct FilmPipelines {
    direct: wgpu::ComputePipeline,
    table: wgpu::ComputePipeline,
    lookup: wgpu::ComputePipeline,
}

impl FilmPipelines {
    fn get(gpu: &Gpu) -> Result<Self, GpuError> {
        if let Some(p) = gpu.film_pipelines.get() {
            return Ok(p.clone());
        }
        let source = format!("{COMMON_WGSL}\n{FILM_WGSL}\n{}", include_str!("shaders/film.wgsl"));
        let p = gpu.checked("compiling the film shaders", || {
            let module = gpu.shader("film.wgsl", &source);
            let pipeline = |entry: &str| gpu.compute_pipeline(&module, entry, entry);
            Self { direct: pipeline("film_frame"), table: pipeline("film_table"), lookup: pipeline("film_frame_table") }
        })?;
        Ok(gpu.film_pipelines.get_or_init(|| p).clone())
    }
}

/// Words of `FilmParams` (film.wgsl).
const PARAM_WORDS: usize = 16;

/// Fills a colour table of `grid` on the GPU from a stack's media (`n_media` per wavelength sample), layer
/// thicknesses and weights (as `GpuFilm` uploads them): one invocation per node, the direct evaluation.
/// Returns the table (two `vec4` per node, `STORAGE | COPY_SRC`) and the wall time of its dispatch.
pub(crate) fn build_table(
    gpu: &Gpu,
    media: &wgpu::Buffer,
    thickness: &wgpu::Buffer,
    weights: &wgpu::Buffer,
    n_media: u32,
    n_lambda: u32,
    grid: &TableGrid,
) -> Result<(wgpu::Buffer, Duration), GpuError> {
    let pipes = FilmPipelines::get(gpu)?;
    let bytes = grid.len() as u64 * 32;
    gpu.check_storage("the film colour table", bytes, "use a thinner stack or a smaller offset range")?;
    let mut words = [0u32; PARAM_WORDS];
    words[2] = n_media;
    words[3] = n_lambda;
    table_words(&mut words, grid);
    let (table, bind) = gpu.checked("allocating the film colour table", || {
        let params = gpu.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("film table params"),
            contents: bytemuck::cast_slice(&words),
            usage: wgpu::BufferUsages::UNIFORM,
        });
        let table = storage_out(gpu, "film colour table", bytes);
        let bind = gpu.bind_buffers(
            "film table bindings",
            &pipes.table,
            &[(0, &params), (2, media), (3, thickness), (4, weights), (8, &table)],
        );
        (table, bind)
    })?;
    let groups = ((grid.cos_nodes as u32).div_ceil(8), (grid.offset_nodes as u32).div_ceil(8));
    let t = dispatch(gpu, None, &pipes.table, &bind, groups, "building the film colour table")?;
    Ok((table, t.wall))
}

/// The table words 10–13 of `FilmParams`.
fn table_words(words: &mut [u32; PARAM_WORDS], grid: &TableGrid) {
    words[10] = grid.cos_nodes as u32;
    words[11] = grid.offset_nodes as u32;
    words[12] = (grid.offset_nm.0 as f32).to_bits();
    words[13] = (grid.offset_nm.1 as f32).to_bits();
}

/// A stack, its indices at every wavelength sample and the colour weights, on the GPU.
#[derive(Debug)]
pub struct GpuFilm<'g> {
    gpu: &'g Gpu,
    pipelines: FilmPipelines,
    stack: Stack,
    grid_nm: Vec<f64>,
    path: FilmPath,
    media: wgpu::Buffer,
    thickness: wgpu::Buffer,
    weights: wgpu::Buffer,
    n_media: u32,
    n_lambda: u32,
}

/// Buffers for repeated frames (the benchmark's loop).
#[derive(Debug)]
pub struct FilmRun<'a, 'g> {
    film: &'a GpuFilm<'g>,
    width: usize,
    height: usize,
    pipeline: wgpu::ComputePipeline,
    bind: wgpu::BindGroup,
    out_xyz: wgpu::Buffer,
    out_rgba: wgpu::Buffer,
    path: FilmPathUsed,
    timer: Option<Timer>,
}

impl<'g> GpuFilm<'g> {
    /// Tabulates the stack's complex indices at the weights' wavelengths (an error names a material without
    /// data there) and compiles the shaders (once per device). Frames take [`FilmPath::Table`] unless
    /// [`GpuFilm::with_path`] says otherwise.
    pub fn new(gpu: &'g Gpu, stack: &Stack, weights: &SpectralWeights) -> Result<Self, GpuError> {
        if stack.has_incoherent() {
            return Err(GpuError::Invalid(format!(
                "stack {stack}: incoherent (inc:) layers are evaluated on the CPU only; run without --gpu"
            )));
        }
        let grid = weights.wavelengths_nm();
        let n_media = stack.layers.len() + 2;
        let mut media = Vec::with_capacity(grid.len() * n_media * 2);
        for &l in grid {
            for (j, m) in stack.materials().enumerate() {
                let n = m.index_at(l).map_err(|e| GpuError::Invalid(format!("stack {stack}: {e}")))?;
                if j == 0 && n.im > 0.0 {
                    return Err(GpuError::Invalid(format!(
                        "stack {stack}: the incident medium must not absorb (κ = {} at {l} nm)",
                        n.im
                    )));
                }
                media.extend([n.re as f32, n.im as f32]);
            }
        }
        let mut thick: Vec<f32> = stack.thicknesses().iter().map(|&d| d as f32).collect();
        if thick.is_empty() {
            thick.push(0.0);
        }
        let w: Vec<f32> = grid
            .iter()
            .zip(weights.weights())
            .flat_map(|(&l, w)| [w[0] as f32, w[1] as f32, w[2] as f32, (std::f64::consts::TAU / l) as f32])
            .collect();
        let pipelines = FilmPipelines::get(gpu)?;
        let (media_buf, thick_buf, weights_buf) = gpu.checked("uploading the stack", || {
            let init = |label: &str, data: &[f32]| gpu.storage_init(label, bytemuck::cast_slice(data));
            (init("film media", &media), init("film thickness", &thick), init("film weights", &w))
        })?;
        Ok(Self {
            gpu,
            pipelines,
            stack: stack.clone(),
            grid_nm: grid.to_vec(),
            path: FilmPath::default(),
            media: media_buf,
            thickness: thick_buf,
            weights: weights_buf,
            n_media: n_media as u32,
            n_lambda: grid.len() as u32,
        })
    }

    /// The same film with another path (the default is [`FilmPath::Table`]).
    pub fn with_path(mut self, path: FilmPath) -> Self {
        self.path = path;
        self
    }

    /// The path frames are asked to take.
    pub fn path(&self) -> FilmPath {
        self.path
    }

    /// Uploads a frame's parameters and SVT texture and allocates its output.
    pub fn frame(&self, frame: &FilmFrame, tone: ToneMap) -> Result<FilmRun<'_, 'g>, GpuError> {
        frame.check()?;
        let gpu = self.gpu;
        let pixels = (frame.width * frame.height) as u64;
        gpu.check_storage("the film frame", pixels * 32, "render a smaller frame")?;
        let f = |v: f64| (v as f32).to_bits();
        let (flags_svt, d_rel) = match &frame.svt {
            Some((d, _)) => (1u32, *d),
            None => (0, 0.0),
        };
        let mut words: [u32; PARAM_WORDS] = [
            frame.width as u32,
            frame.height as u32,
            self.n_media,
            self.n_lambda,
            f(frame.angle_rad.0),
            f(frame.angle_rad.1),
            f(frame.offset_nm.0),
            f(frame.offset_nm.1),
            f(d_rel),
            flags_svt | 2,
            0,
            0,
            0,
            0,
            0,
            0,
        ];
        let (path, table) = match self.path {
            FilmPath::Direct => (FilmPathUsed::Direct { why: None }, None),
            FilmPath::Table => match TableGrid::for_stack(&self.stack, &self.grid_nm, frame.offset_range()) {
                Ok(grid) => {
                    let (table, build) = build_table(
                        gpu,
                        &self.media,
                        &self.thickness,
                        &self.weights,
                        self.n_media,
                        self.n_lambda,
                        &grid,
                    )?;
                    table_words(&mut words, &grid);
                    (FilmPathUsed::Table { grid, build }, Some(table))
                }
                Err(e) => (FilmPathUsed::Direct { why: Some(e.to_string()) }, None),
            },
        };
        let alpha: &[f32] = match &frame.svt {
            Some((_, a)) => a,
            None => &[0.0],
        };
        gpu.checked("allocating the film frame", || {
            let params = gpu.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("film params"),
                contents: bytemuck::cast_slice(&words),
                usage: wgpu::BufferUsages::UNIFORM,
            });
            let alpha = gpu.storage_init("film svt", bytemuck::cast_slice(alpha));
            let display = display_buffer(gpu, tone);
            let out_xyz = storage_out(gpu, "film xyz", pixels * 32);
            let out_rgba = storage_out(gpu, "film rgba", pixels * 4);
            let (pipeline, bind) = match &table {
                Some(table) => {
                    let p = &self.pipelines.lookup;
                    let bind = gpu.bind_buffers(
                        "film table frame bindings",
                        p,
                        &[(0, &params), (1, &display), (5, &alpha), (6, &out_xyz), (7, &out_rgba), (8, table)],
                    );
                    (p.clone(), bind)
                }
                None => {
                    let p = &self.pipelines.direct;
                    let bind = gpu.bind_in_order(
                        "film bindings",
                        p,
                        &[&params, &display, &self.media, &self.thickness, &self.weights, &alpha, &out_xyz, &out_rgba],
                    );
                    (p.clone(), bind)
                }
            };
            FilmRun {
                film: self,
                width: frame.width,
                height: frame.height,
                pipeline,
                bind,
                out_xyz,
                out_rgba,
                path,
                timer: gpu.timer(),
            }
        })
    }

    /// Renders one frame and reads it back.
    pub fn render(&self, frame: &FilmFrame, tone: ToneMap) -> Result<FilmOutput, GpuError> {
        let run = self.frame(frame, tone)?;
        run.run()?;
        run.read()
    }
}

impl FilmRun<'_, '_> {
    /// The path this frame takes (and, for a table, its grid and build time).
    pub fn path(&self) -> &FilmPathUsed {
        &self.path
    }

    /// Renders the frame and waits for the GPU; returns the time from submission to completion (and the GPU's
    /// timestamps where it has them).
    pub fn run(&self) -> Result<FrameTime, GpuError> {
        let groups = ((self.width as u32).div_ceil(8), (self.height as u32).div_ceil(8));
        dispatch(self.film.gpu, self.timer.as_ref(), &self.pipeline, &self.bind, groups, "rendering the film frame")
    }

    /// Reads the last frame back.
    pub fn read(&self) -> Result<FilmOutput, GpuError> {
        let gpu = self.film.gpu;
        let xyz: Vec<f32> = bytemuck::pod_collect_to_vec(&gpu.read_buffer(&self.out_xyz, self.out_xyz.size())?);
        let words: Vec<u32> = bytemuck::pod_collect_to_vec(&gpu.read_buffer(&self.out_rgba, self.out_rgba.size())?);
        let px: Vec<Xyz> = xyz.chunks_exact(4).map(|p| Xyz::new(p[0] as f64, p[1] as f64, p[2] as f64)).collect();
        Ok(FilmOutput {
            width: self.width,
            height: self.height,
            reflected: px.iter().step_by(2).copied().collect(),
            transmitted: px.iter().skip(1).step_by(2).copied().collect(),
            rgb8: unpack_rgb8(&words),
        })
    }
}

/// The CPU reference for chosen pixels of a frame (indices `row · width + col`): reflected and transmitted
/// XYZ from [`Stack::evaluate_offset`] (the general `f64` path, eq. 3.1–3.13) and the same weights, in
/// parallel.
pub fn cpu_reference(
    stack: &Stack,
    weights: &SpectralWeights,
    frame: &FilmFrame,
    pixels: &[usize],
) -> Result<Vec<(Xyz, Xyz)>, GpuError> {
    frame.check()?;
    pixels
        .par_iter()
        .map(|&i| {
            let (theta, offset) = frame.pixel(i % frame.width, i / frame.width);
            let mut r = Vec::with_capacity(weights.wavelengths_nm().len());
            let mut t = Vec::with_capacity(r.capacity());
            for &l in weights.wavelengths_nm() {
                let x = stack
                    .evaluate_offset(l, theta, offset)
                    .map_err(|e| GpuError::Invalid(format!("stack {stack}: {e}")))?;
                r.push(x.r());
                t.push(x.t());
            }
            Ok((weights.integrate(&r), weights.integrate(&t)))
        })
        .collect()
}
