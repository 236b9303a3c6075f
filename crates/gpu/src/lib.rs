//! # iridis-gpu
//!
//! The iridis models on the GPU, through [wgpu](https://wgpu.rs) (Vulkan) and WGSL compute shaders, headless:
//! no window or surface, results are read back to the CPU.
//!
//! * [`lookup`]: the paper's lookup shader (Dhillon et al. 2014, eq. 10–12 and sec. 5; Single 2014,
//!   Algorithm 3 with the tables of sec. 4.4.1): `X = C(ω_i, ω_r) Σ_p w^p I_p(u, v)` with the tables written by
//!   `iridis precompute` in a storage buffer, bilinear interpolation in the non-linear u-v grid's index space,
//!   Horner's rule in `w`, the shading factor `C` of eq. 2–4 (Fresnel, geometry, Cook–Torrance shadowing) —
//!   the numbers of [`iridis_diffraction::Lookup`], evaluated in `f32`. It renders BRDF maps as
//!   [`iridis_diffraction::map::brdf_map`] does.
//! * [`film`]: Sussenbach's thin-film shader (ch. 4): per pixel and per wavelength sample, complex cosines from
//!   Snell's law (eq. 3.6), Fresnel amplitudes (eq. 3.7–3.10), the composite recurrence (eq. 3.1–3.4), R and T
//!   (eq. 3.12–3.13), and the colour integral `XYZ = Σ_λ w(λ) R(λ)` — the numbers of
//!   [`iridis_thinfilm::Stack::evaluate_offset`] and [`iridis_thinfilm::color::FilmColorimeter`], in `f32`,
//!   with a thickness gradient and a spatially varying thickness texture (SVT, eq. 4.3–4.4) — by default
//!   through a colour table over `cos θ` × thickness offset filled by that evaluation (the fast path).
//!
//! * [`table_build`]: `iridis precompute --gpu` — the tables `I_p(u, v)` themselves (eq. 8–12), one grid point
//!   per invocation, the numbers of [`iridis_diffraction::LookupTable::build`] in `f32`;
//! * [`ground_truth`]: `--method ground-truth --gpu` — `|A|²` of [`iridis_diffraction::GroundTruth`] (finite
//!   aperture or periodic extension) per direction pair and wavenumber, with fixed-point phases;
//! * [`accel`]: both behind [`iridis_diffraction::Accelerator`], for the lab's commands.
//!
//! The lookup and film shaders also write the displayed pixel (exposure in RU, XYZ → linear sRGB, clip, encode), so one
//! dispatch is one finished frame.
//!
//! On a machine without a GPU, Mesa's software Vulkan driver (lavapipe, Debian package `mesa-vulkan-drivers`)
//! provides an adapter. Without any adapter [`Gpu::new`] returns [`GpuError::NoAdapter`], whose message says
//! how to install it.

pub mod accel;
pub mod film;
pub mod ground_truth;
pub mod lookup;
#[cfg(feature = "viewer")]
mod present;
pub mod scene;
pub mod table_build;
#[cfg(feature = "viewer")]
pub mod viewer;

use std::time::{Duration, Instant};

use wgpu::util::DeviceExt;

pub use accel::GpuAccelerator;
pub use film::{FilmFrame, FilmOutput, FilmPath, FilmPathUsed, FilmRun, GpuFilm};
pub use ground_truth::{ground_truth_map, GpuGroundTruth};
pub use lookup::{GpuLookup, MapFrame, MapOutput};
pub use scene::{GpuScene, SceneFilm, SceneFrame, StackOverflow};
pub use table_build::build_table;

/// What the user reads when no adapter is found.
pub const NO_ADAPTER_HELP: &str = "no GPU adapter found (iridis uses Vulkan through wgpu). Install a Vulkan driver; \
on a machine without a GPU, Mesa's software driver works: `apt-get install mesa-vulkan-drivers` (Debian/Ubuntu; \
the package is called `mesa-vulkan-drivers` on Fedora too, `vulkan-swrast` on Arch). Check with `vulkaninfo --summary`.";

/// Errors of the GPU path; messages say what to do.
#[derive(Debug, thiserror::Error)]
pub enum GpuError {
    /// No Vulkan adapter (hardware or software) could be opened.
    #[error("{NO_ADAPTER_HELP} ({0})")]
    NoAdapter(String),
    /// The adapter was found but refused a device.
    #[error("the GPU adapter {adapter} refused to open a device: {message}")]
    Device { adapter: String, message: String },
    /// The data does not fit the adapter's limits.
    #[error("{0}")]
    TooLarge(String),
    /// Invalid input (sizes, stacks, wavelengths).
    #[error("{0}")]
    Invalid(String),
    /// The driver reported an error (shader compilation, validation, out of memory, a lost device).
    #[error("GPU error: {0}")]
    Driver(String),
}

/// An open GPU: adapter, device and queue.
#[derive(Debug)]
pub struct Gpu {
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
    pub info: wgpu::AdapterInfo,
    pub limits: wgpu::Limits,
    /// The scene renderer, compiled by the first [`GpuScene`] and reused by the next (software drivers take
    /// seconds to compile it).
    pub(crate) scene_pipeline: std::sync::OnceLock<wgpu::ComputePipeline>,
    /// The film shaders' pipelines (direct frame, colour-table build, table frame), compiled on first use.
    pub(crate) film_pipelines: std::sync::OnceLock<film::FilmPipelines>,
}

/// The instance, adapter, device and queue of every iridis GPU path, headless or in the viewer's window: Vulkan,
/// high-performance preference, the adapter's own limits, and timestamp queries where it has them (one recipe,
/// so that the viewer renders on exactly the device the tests and `render --gpu` use).
pub fn open_vulkan() -> Result<(wgpu::Instance, wgpu::Adapter, wgpu::Device, wgpu::Queue, wgpu::AdapterInfo), GpuError>
{
    let mut desc = wgpu::InstanceDescriptor::new_without_display_handle();
    desc.backends = wgpu::Backends::VULKAN;
    let instance = wgpu::Instance::new(desc);
    let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
        power_preference: wgpu::PowerPreference::HighPerformance,
        force_fallback_adapter: false,
        compatible_surface: None,
        apply_limit_buckets: false,
    }))
    .map_err(|e| GpuError::NoAdapter(e.to_string()))?;
    let info = adapter.get_info();
    let limits = adapter.limits();
    // GPU timestamps around each pass where the adapter has them (frame times without submission overhead).
    let features = adapter.features() & wgpu::Features::TIMESTAMP_QUERY;
    let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
        label: Some("iridis"),
        required_features: features,
        required_limits: limits,
        ..Default::default()
    }))
    .map_err(|e| GpuError::Device { adapter: describe(&info), message: e.to_string() })?;
    Ok((instance, adapter, device, queue, info))
}

impl Gpu {
    /// A WGSL module from `source`; `label` names it in the driver's messages.
    pub(crate) fn shader(&self, label: &str, source: &str) -> wgpu::ShaderModule {
        self.device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(label),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        })
    }

    /// The compute pipeline of entry point `entry` of `module`, its bind group layout read from the shader.
    pub(crate) fn compute_pipeline(
        &self,
        module: &wgpu::ShaderModule,
        label: &str,
        entry: &str,
    ) -> wgpu::ComputePipeline {
        self.device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some(label),
            layout: None,
            module,
            entry_point: Some(entry),
            compilation_options: Default::default(),
            cache: None,
        })
    }

    /// The bind group of a pipeline's group 0 with `(binding, buffer)` entries.
    pub(crate) fn bind_buffers(
        &self,
        label: &str,
        pipeline: &wgpu::ComputePipeline,
        buffers: &[(u32, &wgpu::Buffer)],
    ) -> wgpu::BindGroup {
        let entries: Vec<wgpu::BindGroupEntry> = buffers
            .iter()
            .map(|&(binding, b)| wgpu::BindGroupEntry { binding, resource: b.as_entire_binding() })
            .collect();
        self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(label),
            layout: &pipeline.get_bind_group_layout(0),
            entries: &entries,
        })
    }

    /// [`Gpu::bind_buffers`] with the buffers at bindings 0, 1, 2, … in order.
    pub(crate) fn bind_in_order(
        &self,
        label: &str,
        pipeline: &wgpu::ComputePipeline,
        buffers: &[&wgpu::Buffer],
    ) -> wgpu::BindGroup {
        let numbered: Vec<(u32, &wgpu::Buffer)> = buffers.iter().enumerate().map(|(i, &b)| (i as u32, b)).collect();
        self.bind_buffers(label, pipeline, &numbered)
    }

    /// A storage buffer holding `contents`.
    pub(crate) fn storage_init(&self, label: &str, contents: &[u8]) -> wgpu::Buffer {
        self.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents,
            usage: wgpu::BufferUsages::STORAGE,
        })
    }

    /// Opens the first suitable Vulkan adapter (high-performance preference; a software adapter such as
    /// lavapipe when nothing else exists) with the adapter's own limits, so large tables fit where they can.
    pub fn new() -> Result<Self, GpuError> {
        let (_, _, device, queue, info) = open_vulkan()?;
        Ok(Self::from_parts(device, queue, info))
    }

    /// Wraps a device opened elsewhere (the viewer's window integration opens one that can present).
    pub fn from_parts(device: wgpu::Device, queue: wgpu::Queue, info: wgpu::AdapterInfo) -> Self {
        let limits = device.limits();
        Self { device, queue, info, limits, scene_pipeline: Default::default(), film_pipelines: Default::default() }
    }

    /// `name (backend, device type, driver)`, e.g. `llvmpipe (LLVM 15.0.6, 256 bits) (Vulkan, Cpu, Mesa …)`.
    pub fn adapter_name(&self) -> String {
        describe(&self.info)
    }

    /// True for a software adapter (lavapipe/llvmpipe): its timings say nothing about a real GPU.
    pub fn is_software(&self) -> bool {
        self.info.device_type == wgpu::DeviceType::Cpu
    }

    /// Timestamp queries around one compute pass, or `None` when the adapter has no timestamps.
    pub(crate) fn timer(&self) -> Option<Timer> {
        if !self.device.features().contains(wgpu::Features::TIMESTAMP_QUERY) {
            return None;
        }
        let query = self.device.create_query_set(&wgpu::QuerySetDescriptor {
            label: Some("iridis pass timestamps"),
            ty: wgpu::QueryType::Timestamp,
            count: 2,
        });
        let resolve = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("iridis timestamps"),
            size: 16,
            usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        Some(Timer { query, resolve, period_ns: self.queue.get_timestamp_period() as f64 })
    }

    /// Runs `f` inside validation and out-of-memory error scopes and turns a captured error into
    /// [`GpuError::Driver`].
    pub(crate) fn checked<T>(&self, what: &str, f: impl FnOnce() -> T) -> Result<T, GpuError> {
        let oom = self.device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
        let validation = self.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let out = f();
        let v = pollster::block_on(validation.pop());
        let m = pollster::block_on(oom.pop());
        match v.or(m) {
            Some(e) => Err(GpuError::Driver(format!("{what}: {e}"))),
            None => Ok(out),
        }
    }

    /// Submits the command buffer and blocks until the GPU has finished it; returns the wall time from
    /// submission to completion.
    pub(crate) fn submit_and_wait(&self, cmd: wgpu::CommandBuffer) -> Result<Duration, GpuError> {
        let start = Instant::now();
        let index = self.queue.submit([cmd]);
        self.device
            .poll(wgpu::PollType::Wait { submission_index: Some(index), timeout: None })
            .map_err(|e| GpuError::Driver(format!("waiting for the GPU: {e}")))?;
        Ok(start.elapsed())
    }

    /// Checks that a storage buffer of `bytes` fits the device.
    pub(crate) fn check_storage(&self, what: &str, bytes: u64, hint: &str) -> Result<(), GpuError> {
        let max = self.limits.max_storage_buffer_binding_size.min(self.limits.max_buffer_size);
        if bytes > max {
            return Err(GpuError::TooLarge(format!(
                "{what} needs {:.1} MB but the adapter {} binds at most {:.1} MB in one storage buffer; {hint}",
                bytes as f64 / 1e6,
                self.adapter_name(),
                max as f64 / 1e6
            )));
        }
        Ok(())
    }

    /// Copies `bytes` of a GPU buffer back to the CPU.
    pub(crate) fn read_buffer(&self, src: &wgpu::Buffer, bytes: u64) -> Result<Vec<u8>, GpuError> {
        self.read_back("iridis readback", bytes, |enc, staging| enc.copy_buffer_to_buffer(src, 0, staging, 0, bytes))
    }

    /// Reads `bytes` back to the CPU: `copy` records the copy of the data into a mappable staging buffer
    /// (from a buffer or a texture), which is then submitted, waited for and mapped.
    pub(crate) fn read_back(
        &self,
        label: &str,
        bytes: u64,
        copy: impl FnOnce(&mut wgpu::CommandEncoder, &wgpu::Buffer),
    ) -> Result<Vec<u8>, GpuError> {
        let staging = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(label),
            size: bytes,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut enc = self.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("readback") });
        copy(&mut enc, &staging);
        self.submit_and_wait(enc.finish())?;
        let slice = staging.slice(..);
        let (tx, rx) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |r| {
            let _ = tx.send(r);
        });
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|e| GpuError::Driver(format!("waiting for the readback: {e}")))?;
        match rx.recv() {
            Ok(Ok(())) => {}
            Ok(Err(e)) => return Err(GpuError::Driver(format!("mapping the readback buffer: {e}"))),
            Err(_) => return Err(GpuError::Driver("the readback was never mapped".into())),
        }
        let data = slice
            .get_mapped_range()
            .map_err(|e| GpuError::Driver(format!("reading the readback buffer: {e}")))?
            .to_vec();
        staging.unmap();
        Ok(data)
    }
}

/// The time of one frame: wall clock from submission to completion, and the GPU's own timestamps around the
/// compute pass where the adapter has them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrameTime {
    pub wall: Duration,
    pub gpu: Option<Duration>,
}

/// Two timestamps around a compute pass.
#[derive(Debug)]
pub(crate) struct Timer {
    query: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    period_ns: f64,
}

impl Timer {
    pub(crate) fn writes(&self) -> wgpu::ComputePassTimestampWrites<'_> {
        wgpu::ComputePassTimestampWrites {
            query_set: &self.query,
            beginning_of_pass_write_index: Some(0),
            end_of_pass_write_index: Some(1),
        }
    }

    pub(crate) fn resolve(&self, enc: &mut wgpu::CommandEncoder) {
        enc.resolve_query_set(&self.query, 0..2, &self.resolve, 0);
    }

    /// The pass's duration, after the command buffer with [`Timer::resolve`] has completed.
    pub(crate) fn read(&self, gpu: &Gpu) -> Result<Duration, GpuError> {
        let t: Vec<u64> = bytemuck::pod_collect_to_vec(&gpu.read_buffer(&self.resolve, 16)?);
        Ok(Duration::from_nanos((t[1].saturating_sub(t[0]) as f64 * self.period_ns).round() as u64))
    }
}

/// Records one compute dispatch (with timestamps when available), submits it, waits, and times it.
pub(crate) fn dispatch(
    gpu: &Gpu,
    timer: Option<&Timer>,
    pipeline: &wgpu::ComputePipeline,
    bind: &wgpu::BindGroup,
    groups: (u32, u32),
    what: &str,
) -> Result<FrameTime, GpuError> {
    // Encoding, submission and completion inside the error scopes: a validation error becomes a GpuError.
    let wall = gpu.checked(what, || {
        let mut enc = gpu.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some(what) });
        {
            let mut pass = enc.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some(what),
                timestamp_writes: timer.map(Timer::writes),
            });
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, bind, &[]);
            pass.dispatch_workgroups(groups.0, groups.1, 1);
        }
        if let Some(t) = timer {
            t.resolve(&mut enc);
        }
        gpu.submit_and_wait(enc.finish())
    })??;
    let gpu_time = match timer {
        Some(t) => Some(t.read(gpu)?),
        None => None,
    };
    Ok(FrameTime { wall, gpu: gpu_time })
}

fn describe(info: &wgpu::AdapterInfo) -> String {
    let driver = [info.driver.as_str(), info.driver_info.as_str()]
        .iter()
        .filter(|s| !s.is_empty())
        .copied()
        .collect::<Vec<_>>()
        .join(" ");
    if driver.is_empty() {
        format!("{} ({:?}, {:?})", info.name, info.backend, info.device_type)
    } else {
        format!("{} ({:?}, {:?}, {driver})", info.name, info.backend, info.device_type)
    }
}

/// How the shaders encode the displayed pixel (mirrors [`iridis_color::Encoding`]): kind and parameter.
pub(crate) fn encoding_words(e: iridis_color::Encoding) -> (u32, f32) {
    match e {
        iridis_color::Encoding::Srgb => (0, 0.0),
        iridis_color::Encoding::Gamma(g) => (1, (1.0 / g) as f32),
        iridis_color::Encoding::Linear => (2, 0.0),
    }
}

/// The XYZ → linear sRGB matrix (IEC 61966-2-1, `iridis_color::convert::XYZ_TO_SRGB`) as three `vec4` rows.
pub(crate) fn xyz_to_srgb_words() -> [f32; 12] {
    let m = iridis_color::convert::XYZ_TO_SRGB;
    let mut out = [0.0f32; 12];
    for r in 0..3 {
        for c in 0..3 {
            out[r * 4 + c] = m[r][c] as f32;
        }
    }
    out
}

/// Splits 8-bit RGBA words (`pack4x8unorm`) into RGB bytes.
pub(crate) fn unpack_rgb8(words: &[u32]) -> Vec<u8> {
    words.iter().flat_map(|w| [(*w & 0xff) as u8, ((*w >> 8) & 0xff) as u8, ((*w >> 16) & 0xff) as u8]).collect()
}

/// The WGSL helpers every shader shares (complex arithmetic, display encoding).
pub(crate) const COMMON_WGSL: &str = include_str!("shaders/common.wgsl");
/// The lookup diffraction model, shared by the BRDF-map and scene shaders.
pub(crate) const LOOKUP_WGSL: &str = include_str!("shaders/lookup_math.wgsl");
/// The multilayer thin-film recurrence, shared by the film and scene shaders.
pub(crate) const FILM_WGSL: &str = include_str!("shaders/film_math.wgsl");
/// Phases as fixed-point fractions of a turn and 64-bit products, shared by the ground-truth and scene shaders.
pub(crate) const TURNS_WGSL: &str = include_str!("shaders/turns.wgsl");
/// Parameters, bindings and pixel loop of the two BRDF-map shaders (f32 and encoded tables).
pub(crate) const LOOKUP_MAP_WGSL: &str = include_str!("shaders/lookup_map.wgsl");
