//! `iridis brdf-map` (and Python's `iridis.diffraction.brdf_map`): a BRDF map of any method on a SURFACE or
//! TABLE, on the CPU or the GPU, with its auto exposure, per-sr map and files (PNG, EXR, .npy, a figure); and
//! the demo's diffraction section.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use anyhow::{bail, Context, Result};
use iridis_color::{Encoding, ToneMap, Xyz};
use iridis_diffraction::encoding::TableEncoding;
use iridis_diffraction::geometry::{direction, FresnelConvention, Shading};
use iridis_diffraction::table::{Lookup, Precision, TableParams};
use iridis_diffraction::Evaluator;
use iridis_lab::methods::Method;

use crate::brdf::{
    auto_exposure, lobe_coherence_nm, lobe_shortfall, map_evaluator, render_map, render_map_per_sr, EvaluatorSetup,
    LobeShortfall, RIGOROUS,
};
use crate::gallery::Gallery;
use crate::model::{refuse_build_options_for_table, TableGrid};
use crate::report::{with_progress, Report};
use crate::{ModelOptions, SurfaceOptions};

/// What a BRDF map is asked for (`iridis brdf-map`'s options once parsed).
#[derive(Debug, Clone)]
pub struct MapRequest {
    /// A SURFACE argument or a TABLE file.
    pub input: String,
    /// The method (`lookup`, `reference`, `ground-truth`, …, `rigorous`).
    pub method: String,
    /// The model; its `light` is set to `wi` for the CPU's map.
    pub model: ModelOptions,
    pub surface: SurfaceOptions,
    /// The Fresnel source (`schlick:1.5`, `index:…`, `gold`, `stack:…`), its convention and the shadowing term.
    pub fresnel: String,
    pub convention: FresnelConvention,
    pub shadowing: bool,
    /// Towards the light.
    pub wi: [f64; 3],
    /// Pixels a side.
    pub size: usize,
    /// Exposure in RU (of the PNG, `--plot` and the EXR; `auto_exposure` chooses it from the map instead).
    pub exposure_ru: f64,
    /// Choose the image's exposure from the map.
    pub auto_exposure: bool,
    pub encoding: Encoding,
    /// u-v grid of a table built from a SURFACE, as given (refused with a TABLE).
    pub grid: TableGrid,
    /// The lookup sum in f32.
    pub f32: bool,
    /// On the GPU (lookup and the ground truths).
    pub gpu: bool,
    /// With `gpu` and lookup: how the table is stored (`cheb12` by default).
    pub table_precision: Option<String>,
    /// Also the BRDF f_r in sr⁻¹ per pixel.
    pub per_sr: bool,
    /// View samples a pixel side (1–16; 1: the pixel's centre): each pixel the mean of `subsamples²` directions
    /// across it, so that lobes narrower than a pixel are caught ([`lobes_between_pixels`]). On the GPU, its map
    /// `subsamples` times the size averaged over blocks ([`iridis_diffraction::map::block_mean`]).
    pub subsamples: usize,
}

impl MapRequest {
    /// A request with the CLI's defaults: 512², 1500 RU, sRGB, lookup, light at normal incidence.
    pub fn new(input: &str, method: &str) -> Self {
        Self {
            input: input.into(),
            method: method.into(),
            model: ModelOptions::default(),
            surface: SurfaceOptions::default(),
            fresnel: crate::fresnel::DEFAULT_FRESNEL.into(),
            convention: FresnelConvention::Physical,
            shadowing: true,
            wi: [0.0, 0.0, 1.0],
            size: 512,
            exposure_ru: DEFAULT_EXPOSURE_RU,
            auto_exposure: false,
            encoding: Encoding::Srgb,
            grid: TableGrid::default(),
            f32: false,
            gpu: false,
            table_precision: None,
            per_sr: false,
            subsamples: 1,
        }
    }
}

/// The files of a map: `-o` (PNG, EXR or .npy by extension), `--raw`, `--brdf`, `--exr`, `--plot`.
#[derive(Debug, Clone, Default)]
pub struct MapFiles {
    pub output: PathBuf,
    pub raw: Option<PathBuf>,
    pub brdf: Option<PathBuf>,
    pub exr: Option<PathBuf>,
    pub plot: Option<PathBuf>,
}

/// The formats of `brdf-map -o`: a tone-mapped image, linear sRGB, or the linear XYZ numbers.
const MAP_FORMATS: &[&str] = &["png", "exr", "npy"];

impl MapFiles {
    /// Declares the outputs before anything is computed ([`crate::output::declare`]).
    fn declare(&self) -> Result<()> {
        crate::output::declare("-o", &self.output, MAP_FORMATS)?;
        crate::output::declare_opt("--raw", self.raw.as_deref(), &["npy"])?;
        crate::output::declare_opt("--brdf", self.brdf.as_deref(), &["npy"])?;
        crate::output::declare_opt("--exr", self.exr.as_deref(), &["exr"])?;
        crate::output::declare_opt("--plot", self.plot.as_deref(), &["png"])?;
        Ok(())
    }

    /// Refuses an exposure or an encoding that no output of these files would use: `-o X.npy` holds XYZ as
    /// computed, an EXR linear values at the exposure, a PNG (`-o`, `--plot`) the exposure and the encoding.
    fn refuse_unused_tone(&self, r: &MapRequest) -> Result<()> {
        let ext = crate::output::format_of("-o", &self.output, MAP_FORMATS)?;
        let png = ext == "png" || self.plot.is_some();
        let exposed = png || ext == "exr" || self.exr.is_some();
        let what = format!("-o {} holds XYZ as computed", self.output.display());
        if r.auto_exposure && !exposed {
            bail!("--auto-exposure would be ignored: {what}; it chooses the exposure of -o X.png, --exr and --plot");
        }
        if r.exposure_ru != DEFAULT_EXPOSURE_RU && !exposed {
            bail!("--exposure {} would be ignored: {what}; it scales -o X.png, --exr and --plot", r.exposure_ru);
        }
        if r.encoding != Encoding::Srgb && !png {
            bail!(
                "--gamma would be ignored: it encodes PNG images (-o X.png, --plot); -o {} holds linear values{}",
                self.output.display(),
                if self.exr.is_some() { ", as --exr does" } else { "" }
            );
        }
        Ok(())
    }
}

/// The exposure of a map's image when none is given (RU): a normal-incidence mirror is 1500 times white, so
/// the diffracted colours of a scan, thousands of times fainter, show.
pub const DEFAULT_EXPOSURE_RU: f64 = 1500.0;

/// A computed map.
#[derive(Debug, Clone)]
pub struct BrdfMap {
    /// Linear XYZ of the relative ρ per pixel (row 0 at the top), `size²`.
    pub xyz: Vec<Xyz>,
    /// f_r in sr⁻¹ per pixel as XYZ (`per_sr`).
    pub per_sr: Option<Vec<Xyz>>,
    pub size: usize,
    /// The image's tone map (the exposure `auto_exposure` chose, if asked).
    pub tone: ToneMap,
    /// The evaluator's name (`lookup`, `reference`, …).
    pub method: String,
    /// The coherence length of the evaluator, where it has one.
    pub coherence_nm: Option<f64>,
    /// How the map was made, for the `wrote FILE (…)` line: method, size, device, seconds.
    pub how: String,
}

/// A map's side in pixels (`--size`): 8 to 8192.
pub fn check_size(size: usize) -> Result<()> {
    check_size_of("--size", size)
}

/// The largest map side, in pixels (and the most view samples a side the GPU renders for `--subsamples`).
pub const MAX_MAP_SIDE: usize = 8192;

/// A map's side given by `flag`: 8 to [`MAX_MAP_SIDE`] pixels (below 8 the disk of view directions has too few
/// pixels to compare or show: a 1² map is the normal alone).
pub fn check_size_of(flag: &str, size: usize) -> Result<()> {
    if !(8..=MAX_MAP_SIDE).contains(&size) {
        bail!("{flag} {size} must be between 8 and {MAX_MAP_SIDE} pixels");
    }
    Ok(())
}

/// What a map with no light in it says, with its reason (`samples_a_side`: the map's view samples a side), and
/// the exposure it keeps where it has one (the CLI's PNG; Python's XYZ array has none).
pub fn warn_black_map(method: &str, samples_a_side: usize, exposure_ru: Option<f64>, report: &dyn Report) {
    report.warn(&black_map(method, samples_a_side, exposure_ru));
}

/// [`warn_black_map`]'s sentence.
pub(crate) fn black_map(method: &str, samples_a_side: usize, exposure_ru: Option<f64>) -> String {
    let stays = exposure_ru
        .map_or(String::new(), |e| format!("; the exposure stays {} RU", iridis_color::spectrum::short_number(e)));
    if method.starts_with("stam-periodic") && samples_a_side.is_multiple_of(2) {
        format!(
            "the map is black: Stam's periodic models put a 1-D grating's orders on the row y = 0, which \
             {samples_a_side} samples a side miss: give an odd --size (and --subsamples){stays}"
        )
    } else {
        format!(
            "the map is black: no light reaches these view directions (at this coherence a mirror's lobe is \
             narrower than a pixel){stays}"
        )
    }
}

/// Says [`warn_black_map`] where `xyz` has no lit pixel (Python's maps, which no exposure follows).
pub fn warn_if_black(xyz: &[Xyz], method: &str, samples_a_side: usize, report: &dyn Report) {
    if crate::lit::brightest_lit(xyz).is_none() {
        warn_black_map(method, samples_a_side, None, report);
    }
}

/// What a map of `size`² pixels, `subsamples²` view samples each, misses at this coherence length, if anything:
/// its samples are `2/(size·subsamples)` apart in view direction `(u, v)`, and where that falls short of the
/// light's lobes ([`lobe_shortfall`]) a mirror's reflection or a grating's order can fall between them and
/// vanish, or show at its peak: a black or speckled map that says nothing of the surface. The warning names the
/// `--subsamples` (or the size) that shows every lobe, and the finer one that measures their light. With
/// `measuring` (f_r in sr⁻¹ is written, `--brdf`) a map that shows every lobe but sums only part of their light
/// is warned too (at 4 view samples a pixel a gold sine's map summed a quarter of it, in silence).
pub fn lobes_between_pixels(
    size: usize,
    subsamples: usize,
    coherence_nm: f64,
    light_coherence_nm: Option<f64>,
    measuring: bool,
) -> Option<String> {
    let spacing = 2.0 / (size * subsamples) as f64;
    let sigma = iridis_diffraction::spectral::lobe_sigma_uv(380.0, coherence_nm);
    let shortfall = lobe_shortfall(spacing, coherence_nm);
    // Showing every lobe is not measuring its light: sampled 6σ apart a lobe's sum is hit or miss (a 1100 nm
    // gold sine's map at --subsamples 2 summed 26 % of its light); within 1.5σ the sum is the integral to 0.1 %.
    let m = crate::brdf::MEASURE_SAMPLES_PER_LOBE_SIGMA;
    let measuring_short = spacing / (m * sigma);
    if shortfall.is_none() && !(measuring && measuring_short > 1.0) {
        return None;
    }
    // Samples a side the disk needs, `finer_by` times closer: as view samples a pixel (at most 16) at this size,
    // or as pixels.
    let samples_for = |finer_by: f64| {
        let needed = (size * subsamples) as f64 * finer_by;
        let per_pixel = (subsamples as f64 * finer_by).ceil();
        match (per_pixel <= MAX_SUBSAMPLES as f64, needed <= MAX_MAP_SIDE as f64) {
            (true, _) => Some(format!("--subsamples {per_pixel:.0}")),
            (false, true) => Some(format!("a map of {:.0}² pixels or more", needed.ceil())),
            (false, false) => None,
        }
    };
    let what = if subsamples > 1 { format!("view samples ({subsamples}² a pixel)") } else { "pixels".into() };
    let head = format!(
        "the map's {what} are {spacing:.4} apart in view direction (u, v), this light's lobes {sigma:.4} wide (σ of \
         the window's |G|² at 380 nm, {})",
        crate::brdf::lobe_coherence_label(coherence_nm, light_coherence_nm)
    );
    let Some(LobeShortfall { finer_by, .. }) = shortfall else {
        // Every lobe shows; the f_r written does not hold their light.
        return Some(format!(
            "{head}: every lobe shows, but the sum of f_r in sr⁻¹ over the disk takes only part of their light \
             (samples {:.1}σ apart; within {m}σ it is the integral to 0.1 %): {}",
            spacing / sigma,
            samples_for(measuring_short).unwrap_or_else(|| {
                "no map here samples them that finely; a shorter coherence length widens them".into()
            })
        ));
    };
    let remedy = match (samples_for(finer_by), samples_for(measuring_short)) {
        (Some(show), Some(measure)) => {
            // A --subsamples count is explained at its first mention; a map size needs no word.
            let how =
                if show.starts_with("--subsamples") { " (each pixel the mean of directions across it)" } else { "" };
            format!(
                "{show}{how} shows every lobe; to measure their light (the sum of f_r in sr⁻¹ over the disk) the \
                 samples must lie within {m}σ: {measure}"
            )
        }
        (Some(show), None) => {
            format!("{show} shows every lobe (no map here samples them within {m}σ, to measure them)")
        }
        (None, _) => "a shorter coherence length widens them".to_string(),
    };
    Some(format!(
        "{head}: a lobe narrower than that spacing — a mirror's reflection, a grating's order — can fall between them \
         and vanish from the map, or show at its peak; {remedy}"
    ))
}

/// The most view samples a pixel side `--subsamples` takes (256 directions a pixel).
pub const MAX_SUBSAMPLES: usize = 16;

/// Says [`lobes_between_pixels`]'s warning for a map of `e`, if any (`brdf-map`, Python's `brdf_map`); `measuring`
/// where f_r in sr⁻¹ is written.
pub fn warn_lobes_between_pixels(
    e: &dyn Evaluator,
    size: usize,
    subsamples: usize,
    measuring: bool,
    report: &dyn Report,
) {
    warn_lobes_at(size, subsamples, lobe_coherence_nm(e), e.coherence_nm(), measuring, report);
}

fn warn_lobes_at(
    size: usize,
    subsamples: usize,
    coherence_nm: Option<f64>,
    light_coherence_nm: Option<f64>,
    measuring: bool,
    report: &dyn Report,
) {
    if let Some(w) = coherence_nm.and_then(|c| lobes_between_pixels(size, subsamples, c, light_coherence_nm, measuring))
    {
        report.warn(&w);
    }
}

/// ", 4² view samples a pixel" for a map of `subsamples` > 1, for the line that says what was made.
fn samples_per_pixel(subsamples: usize) -> String {
    if subsamples > 1 {
        format!(", {subsamples}² view samples a pixel")
    } else {
        String::new()
    }
}

/// `--subsamples`: 1 to [`MAX_SUBSAMPLES`].
pub fn check_subsamples(subsamples: usize) -> Result<()> {
    if !(1..=MAX_SUBSAMPLES).contains(&subsamples) {
        bail!("--subsamples {subsamples} must be between 1 and {MAX_SUBSAMPLES} view samples a pixel side");
    }
    Ok(())
}

/// Computes the map (checks first; `files`, if any, are declared before the work starts), with a warning
/// where its pixels are too far apart for this light's lobes ([`lobes_between_pixels`]).
pub fn compute(r: &MapRequest, files: Option<&MapFiles>, report: &dyn Report) -> Result<BrdfMap> {
    if !(r.exposure_ru.is_finite() && r.exposure_ru > 0.0) {
        bail!("--exposure {} must be a positive number of RU", r.exposure_ru);
    }
    // The CLI's parser refuses the pair as well; Python's keywords reach here.
    if r.auto_exposure && r.exposure_ru != DEFAULT_EXPOSURE_RU {
        bail!("--exposure {} would be ignored: --auto-exposure chooses the exposure; give one", r.exposure_ru);
    }
    check_size(r.size)?;
    check_subsamples(r.subsamples)?;
    refuse_build_options_for_table(&r.input, r.grid, &r.surface, "`iridis brdf-map`")?;
    r.grid.refuse_unless_lookup(&r.method)?;
    if r.f32 && r.gpu {
        bail!(
            "--f32 evaluates the lookup sum on the CPU in f32, as a GPU does; --gpu evaluates in f32 already: give one"
        );
    }
    if r.f32 && r.method != "lookup" {
        bail!(
            "--f32 would be ignored: it evaluates the lookup method's sum in f32, and the {} method has none",
            r.method
        );
    }
    if r.model.material.is_some() && r.method != RIGOROUS {
        bail!("--material is the rigorous method's medium; the scalar methods take --fresnel (index:…, gold, stack:…)");
    }
    if r.model.unit_cell_auto && r.method != RIGOROUS {
        // (Also refused by the CPU's evaluator; said here for the GPU's map, which builds none.)
        bail!(crate::brdf::UNIT_CELL_AUTO_RIGOROUS);
    }
    if let Some(f) = files {
        f.declare()?;
        f.refuse_unused_tone(r)?;
    }
    if r.gpu {
        if r.method == RIGOROUS {
            bail!("the rigorous BRDF runs on the CPU: leave out --gpu");
        }
        if r.size * r.subsamples > MAX_MAP_SIDE {
            bail!(
                "--gpu with --size {} and --subsamples {} renders a map of {}² view samples, more than the \
                 {MAX_MAP_SIDE}² it takes: lower one of them",
                r.size,
                r.subsamples,
                r.size * r.subsamples
            );
        }
        if r.model.conserve_energy {
            bail!(
                "--conserve-energy scales each wavelength's lobes, which the CPU's reference and ground-truth methods \
                 do and the GPU's maps do not: leave out --gpu"
            );
        }
        if r.per_sr {
            // The GPU's maps are XYZ integrated over λ; f_r(λ) in sr⁻¹ is the CPU's (it wrote no file before).
            bail!(
                "--brdf writes f_r in sr⁻¹, which the CPU computes from f_r(λ) and the GPU's maps do not give: leave \
                 out --gpu (with --method reference, ground-truth or rigorous)"
            );
        }
        let mut map = gpu_map(r, report)?;
        map.tone.exposure_ru = exposure_for(&map.xyz, r, files, report)?;
        return Ok(map);
    }
    if r.table_precision.is_some() {
        bail!("--table-precision chooses how the GPU stores the lookup table: add --gpu (the CPU evaluates the f64 table)");
    }
    let shading = crate::fresnel::shading(&r.fresnel, r.convention, r.shadowing)?;
    let precision = if r.f32 { Precision::F32 } else { Precision::F64 };
    let start = std::time::Instant::now();
    // The map asks about one light: the reference method keeps only its bins (memory).
    let model = ModelOptions { light: Some(r.wi), ..r.model.clone() };
    if r.method == RIGOROUS {
        crate::fresnel::refuse_scalar_shading_for_rigorous(&r.fresnel, r.convention, r.shadowing)?;
    }
    let setup = EvaluatorSetup {
        method: &r.method,
        model: &model,
        shading,
        params: r.grid.params()?,
        precision,
        surface: &r.surface,
    };
    let (e, rigorous) = map_evaluator(&r.input, setup, r.wi, report)?;
    warn_lobes_between_pixels(e.as_ref(), r.size, r.subsamples, r.per_sr, report);
    if let Some(s) = &rigorous {
        report.note(&s.sentence());
    }
    let prepared = start.elapsed().as_secs_f64();
    let xyz = render_map(e.as_ref(), r.wi, r.size, r.subsamples, report);
    // Before any file is written: a method without f_r(λ) is refused with nothing on disk.
    let per_sr =
        if r.per_sr { Some(render_map_per_sr(e.as_ref(), &model, r.wi, r.size, r.subsamples, report)?) } else { None };
    let total = start.elapsed().as_secs_f64();
    let secs = total - prepared;
    let exposure = exposure_for(&xyz, r, files, report)?;
    let how = format!(
        "{} map, {}²{}, {total:.2} s in all: {prepared:.2} s to load and prepare, {secs:.2} s for the map, {:.0} \
         pixels/s",
        e.name(),
        r.size,
        samples_per_pixel(r.subsamples),
        (r.size * r.size) as f64 / secs.max(1e-9)
    );
    Ok(BrdfMap {
        xyz,
        per_sr,
        size: r.size,
        tone: ToneMap { exposure_ru: exposure, encoding: r.encoding },
        method: e.name().to_string(),
        coherence_nm: e.coherence_nm(),
        how,
    })
}

/// The image's exposure: the one given, or with `--auto-exposure` the one [`auto_exposure`] chooses from the
/// map (said in a note). A black map keeps the one given, with a warning whether or not the exposure was to be
/// chosen; so does a lit map whose image (`-o X.png`, `--plot`) would be black at the exposure given.
fn exposure_for(xyz: &[Xyz], r: &MapRequest, files: Option<&MapFiles>, report: &dyn Report) -> Result<f64> {
    // One pass for the brightest pixel; the percentile's sort only where an exposure is chosen or suggested.
    let Some(brightest) = crate::lit::brightest_lit(xyz) else {
        warn_black_map(&r.method, r.size * r.subsamples, Some(r.exposure_ru), report);
        return Ok(r.exposure_ru);
    };
    if r.auto_exposure {
        if let Some(auto) = auto_exposure(xyz, r.size) {
            report.note(&format!(
                "exposure {:.4} RU, chosen from the map (its 99th-percentile lit pixel is white): {:.2} % of the \
                 disk's pixels clipped, {:.2} % lit",
                auto.exposure_ru,
                100.0 * auto.clipped_share,
                100.0 * auto.lit_share
            ));
            return Ok(auto.exposure_ru);
        }
    }
    // Python's arrays (no files) make no image here.
    let image = match files {
        Some(f) => f.plot.is_some() || crate::output::format_of("-o", &f.output, MAP_FORMATS)? == "png",
        None => false,
    };
    // The encoding is monotone in each channel: the image is black when its brightest pixel is.
    let tone = ToneMap { exposure_ru: r.exposure_ru, encoding: r.encoding };
    if image && tone.to_rgb8(brightest) == [0, 0, 0] {
        let suggested = auto_exposure(xyz, r.size).map_or(String::new(), |a| {
            format!(
                " (at {:.4e} RU its 99th-percentile lit pixel is white: --auto-exposure chooses that)",
                a.exposure_ru
            )
        });
        report.warn(&format!(
            "the image is black at --exposure {} RU: the map's light is too faint for it{suggested}",
            iridis_color::spectrum::short_number(r.exposure_ru),
        ));
    }
    // The other end, for an exposure given: most of the light clipped shows where the light is, not its colour
    // (1e300 RU). The default 1500 RU is the paper's, whose maps clip their brightest lobes by design.
    let clipped = crate::lit::clipped_share(xyz, r.exposure_ru);
    if image && r.exposure_ru != DEFAULT_EXPOSURE_RU && clipped > 0.5 {
        let suggested = auto_exposure(xyz, r.size).map_or(String::new(), |a| {
            format!(" (--auto-exposure would choose {} RU)", iridis_color::spectrum::short_number(a.exposure_ru))
        });
        report.warn(&format!(
            "{:.0} % of the map's lit pixels are clipped at --exposure {} RU: the image shows where the light is, not \
             its colour or brightness{suggested}",
            100.0 * clipped,
            iridis_color::spectrum::short_number(r.exposure_ru),
        ));
    }
    Ok(r.exposure_ru)
}

/// The lookup method or a ground truth on the GPU: the image is tone-mapped on the CPU from the GPU's XYZ, so
/// `--raw` and `--exr` hold the GPU's numbers.
fn gpu_map(r: &MapRequest, report: &dyn Report) -> Result<BrdfMap> {
    let ground_truth = matches!(r.method.parse::<Method>(), Ok(m) if m.is_ground_truth());
    if r.method != "lookup" && !ground_truth {
        bail!(
            "--gpu renders the lookup method (the paper's shader) and the ground truths (--method ground-truth or \
             ground-truth-periodic); --method {} runs on the CPU only (leave out --gpu)",
            r.method
        );
    }
    let tone = ToneMap { exposure_ru: r.exposure_ru, encoding: r.encoding };
    let model = ModelOptions { light: None, ..r.model.clone() };
    let start = std::time::Instant::now();
    if ground_truth {
        if r.table_precision.is_some() {
            bail!("--table-precision applies to the lookup method's table; --method {} has none", r.method);
        }
        let shading = crate::fresnel::shading(&r.fresnel, r.convention, r.shadowing)?;
        let setup = EvaluatorSetup {
            method: &r.method,
            model: &model,
            shading,
            params: r.grid.params()?,
            precision: Precision::F64,
            surface: &r.surface,
        };
        let e = crate::brdf::make_evaluator(&r.input, setup, report)?;
        warn_lobes_between_pixels(e.as_ref(), r.size, r.subsamples, r.per_sr, report);
        let gt = e.as_ground_truth().context("internal: a ground-truth method without a ground truth")?;
        let gpu = crate::gpu::open()?;
        let t = std::time::Instant::now();
        let side = r.size * r.subsamples;
        let fine = with_progress(report, (side * side) as u64, &format!("{} map (GPU)", e.name()), |p| {
            iridis_gpu::ground_truth_map(&gpu, gt, r.wi, side, p)
        })?;
        let xyz = iridis_diffraction::map::block_mean(&fine, side, r.subsamples);
        let secs = t.elapsed().as_secs_f64();
        let how = format!(
            "{} map on the GPU, {}²{}, {:.2} s in all, of which the map {secs:.2} s on {}",
            e.name(),
            r.size,
            samples_per_pixel(r.subsamples),
            start.elapsed().as_secs_f64(),
            gpu.adapter_name()
        );
        let (method, coherence_nm) = (e.name().to_string(), e.coherence_nm());
        return Ok(BrdfMap { xyz, per_sr: None, size: r.size, tone, method, coherence_nm, how });
    }
    if r.fresnel.trim().starts_with("stack:") || matches!(r.fresnel.trim(), "gold" | "au") {
        bail!(
            "--gpu renders the lookup method, whose Fresnel factor must not depend on λ; a thin-film stack or \
             measured gold as Fresnel source needs --method reference (CPU) or ground-truth (CPU or --gpu)"
        );
    }
    let table_encoding: TableEncoding = match r.table_precision.as_deref() {
        Some(p) => p.parse()?,
        None => TableEncoding::GPU_DEFAULT,
    };
    if table_encoding == TableEncoding::F16 {
        report.warn(
            "--table-precision f16 stores the powers I_p in half precision, which the lookup sum's cancellation \
             turns into wrong colours (docs/gpu.md); chebK-f16 halves the memory without that",
        );
    }
    let fresnel = crate::fresnel::parse_fresnel(&r.fresnel)?;
    let gpu = crate::gpu::open()?;
    let table = crate::model::lookup_table(Some(&gpu), &r.input, &model, r.grid.params()?, &r.surface, report)?;
    let coherence_nm = Some(table.meta.coherence_nm);
    warn_lobes_at(r.size, r.subsamples, coherence_nm, coherence_nm, r.per_sr, report);
    let side = r.size * r.subsamples;
    let map =
        crate::gpu::lookup_map(&gpu, &table, fresnel, r.shadowing, r.convention, table_encoding, r.wi, side, tone)?;
    let how = format!(
        "lookup map on the GPU, {}²{}, table in {}, {:.2} s in all, of which the map {:.2} ms on {}",
        r.size,
        samples_per_pixel(r.subsamples),
        table_encoding.name(),
        start.elapsed().as_secs_f64(),
        map.map_seconds * 1e3,
        map.adapter
    );
    let xyz = iridis_diffraction::map::block_mean(&map.output.xyz, side, r.subsamples);
    Ok(BrdfMap { xyz, per_sr: None, size: r.size, tone, method: "lookup".into(), coherence_nm, how })
}

/// `iridis brdf-map`: the map computed and its files written into the run's output set; returns the line
/// that says what was written.
pub fn brdf_map(r: &MapRequest, files: &MapFiles, report: &dyn Report) -> Result<String> {
    let map = compute(r, Some(files), report)?;
    write_map_outputs(files, &map.xyz, map.size, map.tone)?;
    if let (Some(path), Some(f)) = (&files.brdf, &map.per_sr) {
        write_xyz_npy(path, f, map.size)?;
        report.note(&format!(
            "{} holds f_r in sr⁻¹ (unpolarised; X, Y, Z weighted by {} and the {} observer, Y the luminous BRDF), \
             coherence {:.3} µm",
            path.display(),
            r.model.illuminant.as_deref().unwrap_or("D65"),
            r.model.observer.as_deref().unwrap_or("CIE 1931 2°"),
            map.coherence_nm.unwrap_or(f64::NAN) / 1000.0
        ));
    }
    let wi = r.wi;
    let (t, p) = (wi[2].clamp(-1.0, 1.0).acos().to_degrees(), wi[1].atan2(wi[0]).to_degrees().rem_euclid(360.0));
    let illuminant = r.model.illuminant.as_deref().unwrap_or("d65").to_uppercase();
    if let Some(path) = &files.plot {
        let name = Path::new(&r.input).file_name().map_or(r.input.clone(), |f| f.to_string_lossy().into());
        let title =
            format!("{name} · θi {t:.0}° φi {p:.0}° · {} · {illuminant} · {:.3e} RU", map.method, map.tone.exposure_ru);
        write_map_plot(path, &map.xyz, map.size, map.tone, title)?;
    }
    // What the picture shows, beside where it went: the light, the exposure and the colour setup. The rigorous
    // method reflects off its material by Maxwell's equations, with no Fresnel factor (it read "Fresnel
    // schlick:1.5" over gold).
    let reflector = if map.method == crate::model::RIGOROUS {
        format!("material {}", r.model.material.as_deref().unwrap_or(crate::grating::DEFAULT_MATERIAL))
    } else {
        format!("Fresnel {}", r.fresnel.trim())
    };
    Ok(format!(
        "wrote {} ({}; light θ {t:.1}° φ {p:.1}°, exposure {} RU, {illuminant}, CIE {} observer, {reflector}{})",
        files.output.display(),
        map.how,
        iridis_color::spectrum::short_number(map.tone.exposure_ru),
        r.model.observer.as_deref().unwrap_or("1931"),
        map.coherence_nm.map_or(String::new(), |c| format!(", coherence {:.1} µm", c / 1000.0))
    ))
}

/// Tone-maps a map to 8-bit sRGB.
pub fn map_to_rgb8(xyz: &[Xyz], tone: ToneMap) -> Vec<u8> {
    xyz.iter().flat_map(|&p| tone.to_rgb8(p)).collect()
}

/// Writes a map's outputs: -o in the format its extension names, and --raw and --exr (linear sRGB at the tone
/// map's exposure).
pub fn write_map_outputs(f: &MapFiles, xyz: &[Xyz], size: usize, tone: ToneMap) -> Result<()> {
    let exposure_ru = tone.exposure_ru;
    let ext = crate::output::format_of("-o", &f.output, MAP_FORMATS)?;
    match ext.as_str() {
        "exr" => write_exr(&f.output, xyz, size, exposure_ru)?,
        "npy" => write_xyz_npy(&f.output, xyz, size)?,
        _ => crate::output::write_png_rgb8(&f.output, size as u32, size as u32, &map_to_rgb8(xyz, tone))?,
    }
    if let Some(raw) = &f.raw {
        write_xyz_npy(raw, xyz, size)?;
    }
    if let Some(exr) = &f.exr {
        write_exr(exr, xyz, size, exposure_ru)?;
    }
    Ok(())
}

/// A map drawn as a figure with the view-direction axes of the paper's layout and a title, written as PNG.
pub fn write_map_plot(path: &Path, xyz: &[Xyz], size: usize, tone: ToneMap, title: String) -> Result<()> {
    let pixels = iridis_plot::RgbImage { width: size as u32, height: size as u32, data: map_to_rgb8(xyz, tone) };
    let plot = crate::lab_run::view_plot(&pixels, &title, None, (560, 600))?;
    crate::output::write_png_rgb8(path, plot.width, plot.height, &plot.data)
}

/// Linear XYZ as a float64 `.npy` of shape `[size, size, 3]`.
pub fn write_xyz_npy(path: &Path, xyz: &[Xyz], size: usize) -> Result<()> {
    use npyz::WriterBuilder;
    crate::output::write_atomic(path, |w| {
        let mut wr =
            npyz::WriteOptions::new().default_dtype().shape(&[size as u64, size as u64, 3]).writer(w).begin_nd()?;
        wr.extend(xyz.iter().flat_map(|p| p.to_array()))?;
        wr.finish()?;
        Ok(())
    })
}

/// Linear sRGB (XYZ × exposure, unclipped) as OpenEXR.
pub fn write_exr(path: &Path, xyz: &[Xyz], size: usize, exposure: f64) -> Result<()> {
    let data: Vec<f32> = xyz.iter().flat_map(|p| p.scale(exposure).to_linear_srgb().map(|c| c as f32)).collect();
    let img = image::Rgb32FImage::from_raw(size as u32, size as u32, data).context("image size")?;
    let mut bytes = std::io::Cursor::new(Vec::new());
    // The EXR encoder by name, not `write_to(…, ImageFormat::OpenExr)`: that generic call compiles every
    // encoder the `image` crate has (TIFF, PNG, …) into this crate.
    image::DynamicImage::ImageRgb32F(img)
        .write_with_encoder(image::codecs::openexr::OpenExrEncoder::new(&mut bytes))
        .map_err(|e| anyhow::anyhow!("cannot encode EXR: {e}"))?;
    crate::output::write_bytes(path, bytes.get_ref())
}

/// The demo's diffraction section: lookup BRDF maps of built-in surfaces (the kinds of the paper's Figs. 12–14).
pub fn demo_section(g: &mut Gallery) -> Result<()> {
    use crate::model::{build_table, spectral_setup, taylor_terms};
    let quiet = crate::report::Quiet;
    g.section(
        "Diffraction from nanostructures",
        "BRDF maps (paper sec. 7): the colour reflected into every view direction (x, y) = (sin θ cos φ, \
         sin θ sin φ) for a fixed light, computed with the lookup method (precomputed tables I_p, N Taylor terms \
         from the error bound) on built-in surfaces, 1500 RU, sRGB. Light at normal incidence (20° for \
         Xenopeltis). Each map: `iridis brdf-map builtin:NAME -o map.png`.",
    );
    let model = ModelOptions::default();
    let none = SurfaceOptions::default();
    let size = 320;
    for (name, theta_deg) in [("blazed", 0.0), ("cd", 0.0), ("elaphe", 0.0), ("xenopeltis", 20.0)] {
        let spec = format!("builtin:{name}");
        g.log(&format!("  {spec}: Taylor terms and lookup tables …"));
        let patch = crate::surface::load_patch(&spec, &none, &quiet)?;
        let spectral = spectral_setup(&model, &quiet)?;
        let terms = taylor_terms(&patch, &model, &quiet)?;
        let table =
            build_table(None, &terms, &spectral, TableParams { uv_resolution: 201, uv_power: 5.0 }, &spec, &quiet)?;
        let n = table.meta.taylor_terms;
        let lookup = Lookup::new(Arc::new(table), Shading::default(), Precision::F64)?;
        let wi = direction(f64::to_radians(theta_deg), 0.0);
        let xyz = render_map(&lookup, wi, size, 1, &quiet);
        let tone = ToneMap { exposure_ru: 1500.0, encoding: Encoding::Srgb };
        let file = format!("brdf_{name}.png");
        let title = format!("{name}: θi = {theta_deg}°, N = {n}, lookup, 1500 RU");
        write_map_plot(&g.path(&file), &xyz, size, tone, title)?;
        g.image(
            &file,
            &format!("BRDF map of builtin:{name} (iridis brdf-map builtin:{name} --incidence {theta_deg}deg)"),
        );
    }
    Ok(())
}
