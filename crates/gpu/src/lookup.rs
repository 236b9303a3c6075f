//! The lookup diffraction shader (`shaders/lookup.wgsl`): BRDF maps from the tables of `iridis precompute`.
//!
//! Per pixel `(col, row)` of a `size × size` map the view direction is that of
//! [`iridis_diffraction::map::view_direction`]; the colour is `X = C(ω_i, ω_r) Σ_{p=0}^{2N} w^p I_p(u, v)`
//! (paper eq. 10–12) with bilinear interpolation of `I_p` in the index space of the non-linear grid
//! `u_i = 2·sign(s_i)|s_i|^a` (sec. 5) and `C` of eq. 2–4 ([`iridis_diffraction::Shading::factor`]): Fresnel
//! (Schlick or the exact reflectance of a complex index) at the half-vector angle, the geometry term, and
//! Cook–Torrance shadowing. The table lives in `f32` storage buffers with the file's layout — one, or up to
//! [`MAX_CHUNKS`] split by rows of v when it exceeds one binding (128 MiB on lavapipe; the paper's 501² table with
//! N = 22 is 136 MB) — so the shader is the CPU's `Lookup::sum` with `Precision::F32`.

use iridis_color::{ToneMap, Xyz};
use iridis_diffraction::encoding::{EncodedTable, TableEncoding};
use iridis_diffraction::geometry::{Fresnel, FresnelConvention, FresnelSource};
use iridis_diffraction::LookupTable;
use wgpu::util::DeviceExt;

use crate::{
    dispatch, encoding_words, unpack_rgb8, xyz_to_srgb_words, FrameTime, Gpu, GpuError, Timer, COMMON_WGSL,
    LOOKUP_MAP_WGSL, LOOKUP_WGSL,
};

/// Storage buffers a table may be split into (by rows of v) when it exceeds one binding.
pub const MAX_CHUNKS: usize = 4;

/// A lookup table on the GPU with its pipeline and shading options.
#[derive(Debug)]
pub struct GpuLookup<'g> {
    gpu: &'g Gpu,
    pipeline: wgpu::ComputePipeline,
    /// The table split by rows of v (four bindings; unused ones hold one dummy value).
    tables: Vec<wgpu::Buffer>,
    rows_per_chunk: u32,
    res: u32,
    np: u32,
    inv_power: f32,
    fresnel: Fresnel,
    f0: f32,
    shadowing: bool,
    convention: FresnelConvention,
    /// How the cells are stored; [`TableEncoding::F32`] runs `lookup.wgsl`, the others `lookup_encoded.wgsl`
    /// with their per-(channel, coefficient) scales.
    encoding: TableEncoding,
    coefficients: u32,
    words: u32,
    scales: Option<wgpu::Buffer>,
}

/// A rendered map read back: linear XYZ per pixel (row-major, row 0 at the top) and the displayed 8-bit sRGB.
#[derive(Debug, Clone)]
pub struct MapOutput {
    pub size: usize,
    pub xyz: Vec<Xyz>,
    pub rgb8: Vec<u8>,
}

/// Buffers for repeated frames of one size (the benchmark's frame loop, a viewer's redraw).
#[derive(Debug)]
pub struct MapFrame<'a, 'g> {
    lookup: &'a GpuLookup<'g>,
    size: u32,
    params: wgpu::Buffer,
    bind: wgpu::BindGroup,
    out_xyz: wgpu::Buffer,
    out_rgba: wgpu::Buffer,
    timer: Option<Timer>,
}

impl<'g> GpuLookup<'g> {
    /// Uploads a table (as `f32`) and compiles the shader. `fresnel` must be one of the built-in,
    /// wavelength-independent models (the lookup method integrates over λ in advance).
    pub fn new(gpu: &'g Gpu, table: &LookupTable, fresnel: Fresnel, shadowing: bool) -> Result<Self, GpuError> {
        Self::with_binding_limit(gpu, table, fresnel, shadowing, u64::MAX)
    }

    /// As [`GpuLookup::new`], with table buffers of at most `max_binding_bytes` (or the device's limit, if
    /// lower): a table larger than that is split by rows of v into up to [`MAX_CHUNKS`] buffers.
    pub fn with_binding_limit(
        gpu: &'g Gpu,
        table: &LookupTable,
        fresnel: Fresnel,
        shadowing: bool,
        max_binding_bytes: u64,
    ) -> Result<Self, GpuError> {
        Self::encoded(gpu, table, fresnel, shadowing, TableEncoding::F32, max_binding_bytes)
    }

    /// As [`GpuLookup::with_binding_limit`], the table stored in `encoding` (`iridis_diffraction::encoding`):
    /// `f16` powers or Chebyshev coefficients in `w` instead of the `f32` powers.
    pub fn encoded(
        gpu: &'g Gpu,
        table: &LookupTable,
        fresnel: Fresnel,
        shadowing: bool,
        encoding: TableEncoding,
        max_binding_bytes: u64,
    ) -> Result<Self, GpuError> {
        let res = table.meta.uv_resolution;
        let np = table.powers();
        if res < 3 || table.uv.len() != res || table.data.len() != res * res * 3 * np {
            return Err(GpuError::Invalid(format!(
                "table {} is inconsistent: {} grid values and {} numbers for resolution {res} and {np} powers",
                table.meta.surface,
                table.uv.len(),
                table.data.len()
            )));
        }
        // The cells as 32-bit words: the f32 powers themselves, or the encoding's words and scales.
        let (words, per_row_cell, coefficients, scales) = match encoding {
            TableEncoding::F32 => {
                (table.data.iter().map(|&v| (v as f32).to_bits()).collect::<Vec<u32>>(), np, np, None)
            }
            _ => {
                let e = EncodedTable::encode(table, encoding).map_err(|e| GpuError::Invalid(e.to_string()))?;
                // Two scale slots per word and channel (the padding half of an odd count gets 0).
                let mut scales = vec![0f32; 3 * 2 * e.words_per_channel];
                for c in 0..3 {
                    for j in 0..e.per_channel {
                        scales[c * 2 * e.words_per_channel + j] = e.scales[c * e.per_channel + j];
                    }
                }
                let (wpc, k) = (e.words_per_channel, e.per_channel);
                (e.words, wpc, k, Some(scales))
            }
        };
        // Rows of v per buffer: a cell needs rows iv and iv + 1, so buffer k holds rows kR ..= kR + R.
        let per_row = res * 3 * per_row_cell;
        let row = (per_row * 4) as u64;
        let max = gpu.limits.max_storage_buffer_binding_size.min(gpu.limits.max_buffer_size).min(max_binding_bytes);
        let rows_per_chunk = ((max / row).saturating_sub(1) as usize).min(res - 1);
        let chunks = if rows_per_chunk == 0 { usize::MAX } else { (res - 1).div_ceil(rows_per_chunk) };
        if chunks > MAX_CHUNKS {
            return Err(GpuError::TooLarge(format!(
                "the lookup table ({:.1} MB as {}) does not fit {MAX_CHUNKS} storage buffers of {:.1} MB on {}; \
                 precompute it with a smaller --uv-resolution or fewer --terms (the size grows with res² × (2N+1)), \
                 or store it more compactly (--table-precision f16 or cheb12)",
                (words.len() * 4) as f64 / 1e6,
                encoding.name(),
                max as f64 / 1e6,
                gpu.adapter_name()
            )));
        }
        let parts: Vec<&[u32]> = (0..MAX_CHUNKS)
            .map(|k| {
                let first = k * rows_per_chunk;
                if k >= chunks {
                    return &[0u32][..];
                }
                let last = (first + rows_per_chunk + 1).min(res);
                &words[first * per_row..last * per_row]
            })
            .collect();
        let source = match encoding {
            TableEncoding::F32 => include_str!("shaders/lookup.wgsl"),
            _ => include_str!("shaders/lookup_encoded.wgsl"),
        };
        let source = format!("{COMMON_WGSL}\n{LOOKUP_WGSL}\n{LOOKUP_MAP_WGSL}\n{source}");
        let (tables, pipeline, scales) = gpu.checked("uploading the lookup table and compiling the shader", || {
            let bufs: Vec<wgpu::Buffer> =
                parts.iter().map(|part| gpu.storage_init("iridis lookup table", bytemuck::cast_slice(part))).collect();
            let scales = scales.as_ref().map(|s| gpu.storage_init("iridis lookup scales", bytemuck::cast_slice(s)));
            let module = gpu.shader("lookup.wgsl", &source);
            let pipeline = gpu.compute_pipeline(&module, "iridis lookup", "brdf_map");
            (bufs, pipeline, scales)
        })?;
        let f0 = fresnel.reflectance(500.0, 1.0) as f32;
        Ok(Self {
            gpu,
            pipeline,
            tables,
            rows_per_chunk: rows_per_chunk as u32,
            res: res as u32,
            np: np as u32,
            inv_power: (1.0 / table.meta.uv_power) as f32,
            fresnel,
            f0,
            shadowing,
            convention: FresnelConvention::Physical,
            encoding,
            coefficients: coefficients as u32,
            words: per_row_cell as u32,
            scales,
        })
    }

    /// How the table is stored on the GPU.
    pub fn encoding(&self) -> TableEncoding {
        self.encoding
    }

    /// The adapter this table lives on.
    pub fn gpu(&self) -> &Gpu {
        self.gpu
    }

    /// Number of storage buffers the table occupies.
    pub fn table_buffers(&self) -> usize {
        self.tables.iter().filter(|b| b.size() > 4).count()
    }

    /// Bytes of the table on the GPU (with the rows shared by neighbouring buffers).
    pub fn table_bytes(&self) -> u64 {
        self.tables.iter().map(|b| b.size()).filter(|&b| b > 4).sum()
    }

    /// Allocates the output of `size × size` maps.
    pub fn frame(&self, size: usize, tone: ToneMap) -> Result<MapFrame<'_, 'g>, GpuError> {
        if !(1..=16384).contains(&size) {
            return Err(GpuError::Invalid(format!("map size {size} must be between 1 and 16384 pixels")));
        }
        let pixels = (size * size) as u64;
        self.gpu.check_storage("the map", pixels * 16, "render a smaller map")?;
        let gpu = self.gpu;
        gpu.checked("allocating the map", || {
            let params = gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("lookup params"),
                size: 64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            let display = display_buffer(gpu, tone);
            let out_xyz = storage_out(gpu, "map xyz", pixels * 16);
            let out_rgba = storage_out(gpu, "map rgba", pixels * 4);
            let mut entries = vec![
                entry(0, &params),
                entry(1, &display),
                entry(2, &out_xyz),
                entry(3, &out_rgba),
                entry(4, &self.tables[0]),
                entry(5, &self.tables[1]),
                entry(6, &self.tables[2]),
                entry(7, &self.tables[3]),
            ];
            if let Some(s) = &self.scales {
                entries.push(entry(8, s));
            }
            let bind = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("lookup bindings"),
                layout: &self.pipeline.get_bind_group_layout(0),
                entries: &entries,
            });
            MapFrame { lookup: self, size: size as u32, params, bind, out_xyz, out_rgba, timer: gpu.timer() }
        })
    }

    /// The Fresnel convention of `C` (default: physical, `R` once; [`FresnelConvention::Paper`]: `R²`).
    pub fn with_convention(mut self, convention: FresnelConvention) -> Self {
        self.convention = convention;
        self
    }

    /// Renders one map and reads it back (the GPU counterpart of `iridis_diffraction::map::brdf_map`).
    pub fn render_map(&self, wi: [f64; 3], size: usize, tone: ToneMap) -> Result<MapOutput, GpuError> {
        let frame = self.frame(size, tone)?;
        frame.run(wi)?;
        frame.read()
    }

    fn param_words(&self, wi: [f64; 3], size: u32) -> [u32; 16] {
        let f = |v: f32| v.to_bits();
        let (flags_fresnel, n_re, n_im) = match self.fresnel {
            Fresnel::Schlick { n } => (0u32, n as f32, 0.0f32),
            Fresnel::Index { n } => (2u32, n.re as f32, n.im as f32),
        };
        let flags = u32::from(self.shadowing) | flags_fresnel | 4 | convention_flag(self.convention);
        [
            f(wi[0] as f32),
            f(wi[1] as f32),
            f(wi[2] as f32),
            0,
            size,
            self.res,
            self.np,
            flags,
            f(self.inv_power),
            f(self.f0),
            f(n_re),
            f(n_im),
            self.rows_per_chunk,
            // lookup_encoded.wgsl: coefficients and words per channel, mode (bit 0 f16, bit 1 Chebyshev).
            self.coefficients,
            self.words,
            u32::from(self.encoding.is_half())
                | if matches!(self.encoding, TableEncoding::Chebyshev { .. }) { 2 } else { 0 },
        ]
    }
}

impl MapFrame<'_, '_> {
    /// Renders the map for light direction `wi` (a unit vector, z = the surface normal) and waits for the GPU;
    /// returns the time from submission to completion (and the GPU's timestamps where it has them).
    pub fn run(&self, wi: [f64; 3]) -> Result<FrameTime, GpuError> {
        let gpu = self.lookup.gpu;
        gpu.queue.write_buffer(&self.params, 0, bytemuck::cast_slice(&self.lookup.param_words(wi, self.size)));
        let groups = self.size.div_ceil(8);
        dispatch(gpu, self.timer.as_ref(), &self.lookup.pipeline, &self.bind, (groups, groups), "rendering the map")
    }

    /// The displayed pixels as the shader packed them (`pack4x8unorm`, row-major), for the viewer's present pass.
    #[cfg(feature = "viewer")]
    pub(crate) fn packed(&self) -> &wgpu::Buffer {
        &self.out_rgba
    }

    /// Reads the last rendered map back.
    pub fn read(&self) -> Result<MapOutput, GpuError> {
        let gpu = self.lookup.gpu;
        let size = self.size as usize;
        let xyz_bytes = gpu.read_buffer(&self.out_xyz, self.out_xyz.size())?;
        let rgba_bytes = gpu.read_buffer(&self.out_rgba, self.out_rgba.size())?;
        let xyz: Vec<f32> = bytemuck::pod_collect_to_vec(&xyz_bytes);
        let words: Vec<u32> = bytemuck::pod_collect_to_vec(&rgba_bytes);
        Ok(MapOutput {
            size,
            xyz: xyz.chunks_exact(4).map(|p| Xyz::new(p[0] as f64, p[1] as f64, p[2] as f64)).collect(),
            rgb8: unpack_rgb8(&words),
        })
    }
}

pub(crate) fn entry(binding: u32, buffer: &wgpu::Buffer) -> wgpu::BindGroupEntry<'_> {
    wgpu::BindGroupEntry { binding, resource: buffer.as_entire_binding() }
}

pub(crate) fn storage_out(gpu: &Gpu, label: &str, bytes: u64) -> wgpu::Buffer {
    gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: bytes.max(4),
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    })
}

/// The `Display` uniform of `common.wgsl`: XYZ → sRGB rows, exposure, encoding.
pub(crate) fn display_words(tone: ToneMap) -> Vec<u32> {
    let m = xyz_to_srgb_words();
    let (kind, inv_gamma) = encoding_words(tone.encoding);
    let mut words: Vec<u32> = m.iter().map(|v| v.to_bits()).collect();
    words.extend([(tone.exposure_ru as f32).to_bits(), kind, inv_gamma.to_bits(), 0]);
    words
}

/// A `Display` uniform buffer (rewritable: the viewer changes exposure and gamma).
pub(crate) fn display_buffer(gpu: &Gpu, tone: ToneMap) -> wgpu::Buffer {
    gpu.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("display"),
        contents: bytemuck::cast_slice(&display_words(tone)),
        // Uniform for the lookup and film shaders, storage for the scene shader (scene.wgsl says why).
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
    })
}

/// Flag bit 3 of the shaders' `Table.flags`: the paper's `R²` Fresnel convention (lookup_math.wgsl).
pub(crate) fn convention_flag(c: FresnelConvention) -> u32 {
    match c {
        FresnelConvention::Physical => 0,
        FresnelConvention::Paper => 8,
    }
}
