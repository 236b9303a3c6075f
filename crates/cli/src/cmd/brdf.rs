//! `iridis precompute` and `iridis brdf-map`: the diffraction BRDF of a height field (issue 5).

use std::path::{Path, PathBuf};
use std::sync::Arc;

use anyhow::{bail, Context, Result};
use clap::Args as ClapArgs;
use iridis_api::brdf::{eval_point, map_evaluator, render_map};
use iridis_api::model::{build_table, is_table, spectral_setup, taylor_terms};
use iridis_api::surface::load_patch;
use iridis_api::{ModelOptions, SurfaceOptions};
use iridis_color::{Encoding, ToneMap, Xyz};
use iridis_diffraction::geometry::{direction, FresnelConvention, Shading};
use iridis_diffraction::table::{Lookup, Precision, TableParams};
use iridis_diffraction::Units;

use crate::args::{polar_azimuth, positive_length_nm, RigorousOpts};
use crate::progress::Cli;

pub use crate::args::SurfaceOpts;

/// Options shared by the commands that build Taylor terms.
#[derive(Debug, Clone, ClapArgs)]
pub struct ModelOpts {
    /// Taylor terms: `auto` (from the remainder bound) or a number N (terms 0..N).
    #[arg(long, default_value = "auto")]
    pub terms: String,
    /// Coherence length 4σ_s of the Gaussian window, a property of the light (default 65um, the paper's; a
    /// smaller patch is taken as one unit cell of a periodic surface; said in the output).
    #[arg(long, value_parser = positive_length_nm)]
    pub coherence: Option<f64>,
    /// Illuminant: d65, d50, a, e.
    #[arg(long)]
    pub illuminant: Option<String>,
    /// Observer: 1931 or 1964.
    #[arg(long)]
    pub observer: Option<String>,
    /// Wavelength step of the spectral integral (≤ 5nm recommended).
    #[arg(long, value_parser = positive_length_nm)]
    pub step: Option<f64>,
    /// Energy-conserving lobes (reference, ground-truth): each scaled by its order's factor in the patch's
    /// energy-normalised channel matrix, so that the BRDF never returns more light than it receives (Kirchhoff's
    /// obliquity factor as printed returns up to twice it at grazing light).
    #[arg(long)]
    pub conserve_energy: bool,
}

#[derive(Debug, ClapArgs)]
#[command(after_help = "\
Computes the DFTs of the Taylor terms (i h)^n of a height field (paper eq. 5-8) and the lookup tables
I_p(u, v), p = 0..2N, for X, Y and Z (eq. 10-12) on the non-linear u-v grid of sec. 5, and writes them
to one .npz file that numpy opens:  t = np.load('T.npz'); t['I'].shape == (res, res, 3, 2N+1);
json.loads(bytes(t['metadata_json'])).

--units radiometric weights the colours by 4πσ_s²/λ² (σ_s a quarter of the coherence length): the table
then holds the BRDF times cos θ_i over R₀, whose integral over the hemisphere is the light reflected (a
flat surface: R(θ)/R₀), for scenes with energy-conserving diffraction materials (units = \"radiometric\"
in a scene; docs/PHYSICS.md). The default, relative, is the paper's: a flat mirror's peak is 1 at every
wavelength, and images are scaled by an exposure in RU.

--gpu builds the tables on the GPU (Vulkan; lavapipe without a GPU): the same grid and metadata, the values
in f32 (relative error ~1e-6 of each power's largest value; docs/gpu.md); the FFTs stay on the CPU.

Examples:
  iridis precompute builtin:elaphe -o elaphe.npz
  iridis precompute 'builtin:elaphe?size=10um' -o elaphe10.npz --uv-resolution 101 --gpu
  iridis precompute scan.gwy -o scan.npz --terms 30 --coherence 65um --uv-resolution 501 --uv-power 5
  iridis precompute relief.png --pixel-size 65nm --max-height 300nm -o relief.npz --uv-power 1")]
pub struct PrecomputeArgs {
    /// Height field: a file (.gwy, .npy, .npz, PNG, TIFF, text) or builtin:NAME.
    pub surface: String,
    /// Output table (.npz).
    #[arg(short, long)]
    pub output: PathBuf,
    #[command(flatten)]
    pub model: ModelOpts,
    /// Samples per axis of the u-v grid.
    #[arg(long, default_value_t = 501)]
    pub uv_resolution: usize,
    /// Exponent a of the non-linear u-v grid (1 = linear).
    #[arg(long, default_value_t = 5.0)]
    pub uv_power: f64,
    /// What the colours measure: relative (the paper's: a flat mirror's peak is 1) or radiometric (the BRDF:
    /// a flat surface reflects R(θ)/R₀ of the light).
    #[arg(long, value_name = "relative|radiometric", default_value = "relative", value_parser = units)]
    pub units: Units,
    /// Build the tables on the GPU (values in f32).
    #[arg(long)]
    pub gpu: bool,
    #[command(flatten)]
    pub surface_opts: SurfaceOpts,
}

fn units(s: &str) -> Result<Units, String> {
    s.parse().map_err(|e: iridis_diffraction::DiffractionError| e.to_string())
}

#[derive(Debug, ClapArgs)]
#[command(after_help = "\
Renders the colour reflected towards every view direction for one light direction (paper sec. 7): pixel
(x, y) in [-1, 1]^2 shows the view direction (x, y, sqrt(1 - x^2 - y^2)); x right, y up.

Methods: ground-truth (direct windowed transform of exp(ikwh), slow: use --size 64 on big
surfaces), ground-truth-periodic (the same transform of the patch's periodic extension, the exact
answer the DFT-based methods approximate), reference (the thesis' FLSS shader: windowed DFT of the Taylor terms per wavelength),
lookup (the paper's fast path: precomputed tables; pass a TABLE from `iridis precompute`, or a
SURFACE to build one first), and the lab's comparison models (docs/lab.md): nmm and pq (the
thesis' variants), stam-periodic and stam-periodic-triangular (Stam's bumps on a lattice fitted
to the surface's dominant periods, ε = 0.01; a 1-D grating's orders lie on y = 0 only, so use an
odd --size) and stam-gaussian (Stam's Gaussian random surface from the height field's
correlation function). Every method but lookup needs the height field. rigorous: each order's lobe of the
SURFACE taken as one period (or, with --unit-cell auto, a scan's dominant period averaged along its ridges)
carries Maxwell's efficiency for it (the C-method over --material; docs/diffraction.md, \"The rigorous BRDF\").

Examples:
  iridis brdf-map builtin:blazed --method lookup -o blazed.png
  iridis precompute builtin:elaphe -o elaphe.npz && iridis brdf-map elaphe.npz -o elaphe.png --exposure 1500
  iridis brdf-map builtin:xenopeltis --method reference --incidence 20deg,0deg --size 256 -o x.png --raw x.npy
  iridis brdf-map builtin:xenopeltis --method reference --coherence 10um --size 128 -o x.png --brdf x_fr.npy
  iridis brdf-map builtin:sine --method ground-truth --size 48 -o gt.png --gamma 2.2
  iridis brdf-map 'builtin:elaphe?size=10um&pixel=50nm' --method stam-gaussian --coherence 5um -o stam.png
  iridis brdf-map elaphe.npz --gpu --size 1024 -o elaphe_gpu.png
  iridis brdf-map 'builtin:sine?size=4um' --method ground-truth --gpu --size 48 -o gt_gpu.png
  iridis brdf-map 'builtin:sine?size=1100nm&pixel=10nm' --method rigorous --material gold --coherence 5um --size 64 -o rigorous.png

--gpu renders the lookup method (the paper's shader; a SURFACE's table is built on the GPU too) and the
ground truths (ground-truth, ground-truth-periodic) on the GPU; the other methods run on the CPU only.
--table-precision says how the GPU stores the lookup table: K Chebyshev coefficients in w instead of the 2N+1
powers, in f32 (cheb12, the default: 3.75× less memory than the powers at N = 22, CIEDE2000 ≤ 0.001 against
the f64 lookup on the built-ins) or f16 (chebK-f16: half that again, mean ≤ 0.005 but single pixels up to 21
at a grating's specular peak), or the powers themselves (f32; f16 is there to show that half precision
breaks them). docs/gpu.md has the measurements.")]
pub struct BrdfMapArgs {
    /// A height field (file or builtin:NAME) or a lookup table from `iridis precompute`, told apart by content
    /// (a height field may be an .npz too).
    pub input: String,
    /// ground-truth, ground-truth-periodic, reference, lookup, nmm, pq, stam-periodic, stam-periodic-triangular,
    /// stam-gaussian or rigorous.
    #[arg(long, default_value = "lookup")]
    pub method: String,
    #[command(flatten)]
    pub rigorous: RigorousOpts,
    /// Light direction: polar angle θ_i[,azimuth φ_i].
    #[arg(long, default_value = "0deg")]
    pub incidence: String,
    /// Map size in pixels.
    #[arg(long, default_value_t = 512)]
    pub size: usize,
    /// Exposure in RU (1 RU: a normal-incidence mirror just saturates white).
    #[arg(long, default_value_t = 1500.0)]
    pub exposure: f64,
    /// Choose the exposure from the map: its 99th-percentile lit pixel becomes white; the clipped share is
    /// said.
    #[arg(long, conflicts_with = "exposure")]
    pub auto_exposure: bool,
    /// Also write the map as a figure with axes (view direction x = sin θr cos φr, y = sin θr sin φr) and a
    /// caption: the surface, light, method and exposure (PNG).
    #[arg(long)]
    pub plot: Option<PathBuf>,
    /// Encoding: srgb, linear or a gamma such as 2.2.
    #[arg(long, default_value = "srgb")]
    pub gamma: String,
    /// Output: .png (tone-mapped), .exr (linear sRGB) or .npy (linear XYZ), by its extension.
    #[arg(short, long)]
    pub output: PathBuf,
    /// Also write linear XYZ per pixel as .npy (float64, shape [size, size, 3]): the relative ρ's colour,
    /// the quantity the PNG shows (a flat mirror's peak is 1).
    #[arg(long)]
    pub raw: Option<PathBuf>,
    /// Also write the BRDF f_r in sr⁻¹ per pixel as .npy (float64, [size, size, 3]: X, Y, Z of f_r(λ) for
    /// unpolarised light weighted by the illuminant and observer; Y is the luminous BRDF, and Y·(2/size)²
    /// summed over the disk the luminous share of the light reflected). reference, ground-truth, rigorous.
    #[arg(long, value_name = "FILE.npy")]
    pub brdf: Option<PathBuf>,
    /// Also write linear XYZ·exposure as OpenEXR (RGB = linear sRGB).
    #[arg(long)]
    pub exr: Option<PathBuf>,
    #[command(flatten)]
    pub shading: ShadingOpts,
    /// Lookup sum in f32, as a GPU would evaluate it.
    #[arg(long)]
    pub f32: bool,
    /// Render on the GPU (Vulkan; lavapipe without a GPU): lookup or the ground truths, same image.
    #[arg(long)]
    pub gpu: bool,
    /// With --gpu and the lookup method: how the table is stored, chebK (default cheb12), chebK-f16, f32 or
    /// f16.
    #[arg(long, value_name = "ENCODING")]
    pub table_precision: Option<String>,
    #[command(flatten)]
    pub model: ModelOpts,
    /// u-v resolution when a table must be built from a SURFACE [default: 501]; refused with a TABLE.
    #[arg(long = "uv-resolution", value_name = "N")]
    pub uv_resolution_arg: Option<usize>,
    /// u-v power when a table must be built from a SURFACE [default: 5]; refused with a TABLE.
    #[arg(long = "uv-power", value_name = "A")]
    pub uv_power_arg: Option<f64>,
    /// The u-v resolution in effect (from --uv-resolution or the default), set by `run_brdf_map`.
    #[arg(skip = 501usize)]
    pub uv_resolution: usize,
    /// The u-v power in effect, set by `run_brdf_map`.
    #[arg(skip = 5.0)]
    pub uv_power: f64,
    #[command(flatten)]
    pub surface_opts: SurfaceOpts,
}

impl ModelOpts {
    /// The facade's model options.
    pub fn options(&self) -> ModelOptions {
        ModelOptions {
            terms: self.terms.clone(),
            coherence_nm: self.coherence,
            illuminant: self.illuminant.clone(),
            observer: self.observer.clone(),
            step_nm: self.step,
            conserve_energy: self.conserve_energy,
            light: None,
            // Set by the commands that take --material and --unit-cell (`RigorousOpts::apply`).
            material: None,
            unit_cell_auto: false,
        }
    }
}

pub fn run_precompute(a: PrecomputeArgs) -> Result<()> {
    crate::output::declare("-o", &a.output, &["npz"])?;
    let start = std::time::Instant::now();
    let model = a.model.options();
    let patch = load_patch(&a.surface, &a.surface_opts.options(), &Cli)?;
    let mut spectral = spectral_setup(&model, &Cli)?;
    let terms = taylor_terms(&patch, &model, &Cli)?;
    if a.units == Units::Radiometric {
        spectral = spectral.radiometric(terms.coherence_nm)?;
    }
    let params = TableParams { uv_resolution: a.uv_resolution, uv_power: a.uv_power };
    // The size is known once N is: say it before the long build and the write.
    let values = a.uv_resolution * a.uv_resolution * 3 * (2 * terms.n_max + 1);
    eprintln!(
        "{} will hold {}² × 3 × {} values in f64: {:.1} MB",
        a.output.display(),
        a.uv_resolution,
        2 * terms.n_max + 1,
        (values * 8) as f64 / 1e6
    );
    let table = if a.gpu {
        crate::cmd::gpu::build_table(&terms, &spectral, params, &a.surface)?
    } else {
        build_table(&terms, &spectral, params, &a.surface, &Cli)?
    };
    let mut buf = std::io::Cursor::new(Vec::new());
    table.write_npz(&mut buf)?;
    crate::output::write_bytes(&a.output, buf.get_ref())?;
    crate::outln!(
        "wrote {} ({} tables of {}², N = {}, {:.1} MB, {:.1} s)",
        a.output.display(),
        table.powers(),
        a.uv_resolution,
        table.meta.taylor_terms,
        buf.get_ref().len() as f64 / 1e6,
        start.elapsed().as_secs_f64()
    )?;
    Ok(())
}

/// The shading factors around |A|² (`C` of paper eq. 2–4), shared by `brdf-map` and `brdf eval`.
#[derive(Debug, Clone, ClapArgs)]
pub struct ShadingOpts {
    /// Fresnel factor: schlick[:N] (default schlick:1.5), index:N or index:N+Ki (gold near 550 nm:
    /// index:0.2+3.4i), gold (measured, Johnson & Christy) or a thin-film stack, e.g. "stack:air | keratin
    /// 300nm | n=1.56" (the last two depend on λ: reference or ground-truth).
    #[arg(long, default_value = "schlick:1.5")]
    pub fresnel: String,
    /// How the Fresnel reflectance enters: physical (R once, the default) or paper (R², the paper's formula as
    /// printed, to reproduce its figures; docs/PHYSICS.md).
    #[arg(long, value_name = "physical|paper", default_value = "physical", value_parser = fresnel_convention)]
    pub fresnel_convention: FresnelConvention,
    /// Leave out the Cook-Torrance shadowing term.
    #[arg(long)]
    pub no_shadowing: bool,
}

impl ShadingOpts {
    pub fn shading(&self) -> Result<Shading> {
        iridis_api::fresnel::shading(&self.fresnel, self.fresnel_convention, !self.no_shadowing)
    }
}

/// Parses `--fresnel-convention`.
pub fn fresnel_convention(s: &str) -> Result<FresnelConvention, String> {
    FresnelConvention::parse(s).map_err(|e| e.to_string())
}

/// Parses `--incidence θ[,φ]` into a light direction, refusing θ ≥ 90°.
pub fn parse_incidence(s: &str) -> Result<[f64; 3]> {
    let (theta, phi) = polar_azimuth("incidence", s)?;
    Ok(direction(theta, phi))
}

/// Refuses options that only shape how a table is built (or how a surface is read) when INPUT is a finished
/// table: they would be silently ignored.
pub(crate) fn refuse_build_options_for_table(a: &BrdfMapArgs) -> Result<()> {
    let mut given = Vec::new();
    if let Some(r) = a.uv_resolution_arg {
        given.push(format!("--uv-resolution {r}"));
    }
    if let Some(p) = a.uv_power_arg {
        given.push(format!("--uv-power {p}"));
    }
    if let Some(p) = a.surface_opts.pixel_size {
        given.push(format!("--pixel-size {p}nm"));
    }
    if let Some(h) = a.surface_opts.max_height {
        given.push(format!("--max-height {h}nm"));
    }
    if !given.is_empty() {
        bail!(
            "{} is a finished lookup table, so {} would be ignored: these options shape how a table is built \
             from a SURFACE; pass them to `iridis precompute` (or give brdf-map the surface itself)",
            a.input,
            given.join(", ")
        );
    }
    Ok(())
}

/// `iridis brdf …`: point queries of the diffraction BRDF.
#[derive(Debug, clap::Subcommand)]
pub enum BrdfCommand {
    /// ρ(λ) and XYZ of one method for one pair of directions (the evaluator interface, for scripts).
    Eval(BrdfEvalArgs),
    /// How an animal sees the surface from several directions: quantum catches and ΔS, ΔL in JND.
    Vision(BrdfVisionArgs),
}

#[derive(Debug, ClapArgs)]
#[command(after_help = "\
The reflectance factor π f_r(λ) of the BRDF (unpolarised; a white diffuser's is 1; the reference method,
300–700 nm: birds and bees see ultraviolet) in each view direction of the plane of incidence, analysed by the
receptor-noise-limited model (Vorobyev & Osorio 1998; `iridis vision`, docs/vision.md): each direction's
quantum catches and its colour distance ΔS (and achromatic ΔL) in JND to the mirror direction and to the next
view. Views are signed polar angles in the plane of incidence, positive on the specular side; the plane is
the surface's dominant orientation unless --azimuth says otherwise. --strip draws each view's false colour:
the three longest receptors' catches as R, G, B, and a fourth (UV) receptor's as a violet row below.

Examples:
  iridis brdf vision 'builtin:elaphe?size=10um&pixel=50nm' --visual bluetit --coherence 5um --views -60,-40,-20,0,20,40,60
  iridis brdf vision 'builtin:xenopeltis?size=10um&pixel=50nm' --visual honeybee --light 20deg --coherence 5um --strip bee.png
  iridis brdf vision 'builtin:elaphe?size=10um&pixel=50nm' --visual ball-python --coherence 5um --json")]
pub struct BrdfVisionArgs {
    /// A height field (file or builtin:NAME).
    pub input: String,
    /// The visual system: human, avian-uv, avian-v, bluetit, honeybee, ball-python, or a CSV of sensitivities.
    #[arg(long)]
    pub visual: String,
    /// Light polar angle θ_i (in the plane of incidence).
    #[arg(long, value_parser = crate::args::angle_rad, default_value = "0deg")]
    pub light: f64,
    /// The plane of incidence's azimuth [default: the orientation of the surface's strongest period].
    #[arg(long, value_parser = crate::args::angle_rad, allow_hyphen_values = true)]
    pub azimuth: Option<f64>,
    /// View angles θ_r in degrees, comma-separated, signed (positive on the specular side).
    #[arg(long, default_value = "-60,-50,-40,-30,-20,-10,0,10,20,30,40,50,60", allow_hyphen_values = true)]
    pub views: String,
    /// The light the animal sees by: d65 (default), bluesky, forestshade, … (`iridis vision --help`).
    #[arg(long, default_value = "d65")]
    pub illuminant: String,
    /// Write each view's false colour (PNG).
    #[arg(long)]
    pub strip: Option<PathBuf>,
    /// Print JSON: the spectra and the analysis.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub shading: ShadingOpts,
    #[command(flatten)]
    pub model: ModelOpts,
    #[command(flatten)]
    pub surface_opts: SurfaceOpts,
}

fn run_vision(a: BrdfVisionArgs) -> Result<()> {
    crate::output::declare_opt("--strip", a.strip.as_deref(), &["png"])?;
    let views: Vec<f64> = a
        .views
        .split(',')
        .map(|v| {
            let v = v.trim().trim_end_matches("deg");
            v.parse::<f64>().map_err(|_| anyhow::anyhow!("--views: '{v}' is not an angle in degrees"))
        })
        .collect::<Result<_>>()?;
    let spec = iridis_vision::Spec {
        visual: Some(a.visual.clone()),
        illuminant: Some(a.illuminant.clone()),
        ..Default::default()
    };
    let source = iridis_api::surface::Source::Spec(a.input.clone());
    let v = iridis_api::vision::along_plane(
        &source,
        &a.surface_opts.options(),
        &a.model.options(),
        a.shading.shading()?,
        a.light,
        a.azimuth,
        &views,
        &spec,
        &Cli,
    )?;
    if let Some(path) = &a.strip {
        let img = vision_strip(&v)?;
        crate::output::write_png_rgb8(path, img.width, img.height, &img.data)?;
    }
    if a.json {
        return crate::output::print_json(&v.to_json());
    }
    let an = &v.analysis;
    crate::outln!(
        "{} · seen by {} under {} · light θ {:.1}° in the plane of azimuth {:.1}° · π f_r(λ), 300–700 nm",
        v.surface,
        an.visual.name,
        an.illuminant,
        v.light_theta.to_degrees(),
        v.azimuth.to_degrees()
    )?;
    let mirror = v
        .views
        .iter()
        .min_by(|x, y| (x.1 - v.light_theta.to_degrees()).abs().total_cmp(&(y.1 - v.light_theta.to_degrees()).abs()))
        .map(|x| x.0.clone())
        .unwrap_or_default();
    let jnd = |d: Option<f64>| d.map_or("—".to_string(), |x| format!("{x:.2}"));
    crate::outln!(
        "  view      relative catches ({})      ΔS to {mirror} (JND)   ΔS to the previous (JND)",
        an.receptors.join(", ")
    )?;
    for (k, s) in an.samples.iter().enumerate() {
        let rel: Vec<String> = s.relative_catches.iter().map(|x| format!("{x:.3}")).collect();
        let to_mirror = an.distance(&s.name, &mirror).and_then(|d| d.delta_s);
        let to_prev = (k > 0).then(|| an.distance(&s.name, &an.samples[k - 1].name).and_then(|d| d.delta_s)).flatten();
        crate::outln!("  {:>6}    {:<32}  {:>12}   {:>12}", s.name, rel.join(" "), jnd(to_mirror), jnd(to_prev))?;
    }
    for n in &an.notes {
        eprintln!("note: {n}");
    }
    Ok(())
}

/// The views' false colours as a picture with its legend in the title (see [`iridis_api::vision`]).
fn vision_strip(v: &iridis_api::vision::DirectionalVision) -> Result<iridis_plot::RgbImage> {
    let colours = v.false_colours();
    let uv = colours.iter().any(|c| c.1.is_some());
    let (cell, rows) = (16usize, if uv { 2 } else { 1 });
    let n = colours.len();
    let mut data = vec![0u8; n * cell * rows * cell * 3];
    for (k, (rgb, u)) in colours.iter().enumerate() {
        for row in 0..rows {
            let c = if row == 0 {
                *rgb
            } else {
                let x = u.unwrap_or(0.0);
                [0.6 * x, 0.2 * x, x]
            };
            for y in row * cell..(row + 1) * cell {
                for x in k * cell..(k + 1) * cell {
                    let i = (y * n * cell + x) * 3;
                    for ch in 0..3 {
                        data[i + ch] = (255.0 * c[ch].clamp(0.0, 1.0).powf(1.0 / 2.2)).round() as u8;
                    }
                }
            }
        }
    }
    let pixels = iridis_plot::RgbImage { width: (n * cell) as u32, height: (rows * cell) as u32, data };
    let r = &v.analysis.receptors;
    let k = r.len();
    let legend = match k {
        0..=2 => format!("{}: catches of {}", v.analysis.visual.name, r.join(", ")),
        _ => format!(
            "{}: R {} G {} B {}{}",
            v.analysis.visual.name.split(" (").next().unwrap_or(""),
            r[k - 1],
            r[k - 2],
            r[k - 3],
            if uv { format!(", below {}", r[0]) } else { String::new() }
        ),
    };
    let (lo, hi) = (v.views.first().map_or(0.0, |x| x.1), v.views.last().map_or(0.0, |x| x.1));
    Ok(iridis_plot::ImagePlot {
        title: legend,
        x_label: "view θr (deg, + on the specular side)".into(),
        y_label: if uv { "UV | visible".into() } else { "visible".into() },
        x_range: (lo, hi),
        y_range: (0.0, rows as f64),
        pixels: &pixels,
        overlays: vec![],
        colorbar: None,
        size: (720, 260),
    }
    .render_without_y_ticks()?)
}

#[derive(Debug, ClapArgs)]
#[command(after_help = "\
Directions point away from the surface: θ from the normal, φ the azimuth from +x. The mirror direction of
light at (θ, φ) is (θ, φ + 180deg). Printed by default: the BRDF f_r(λ) in sr⁻¹ for s (TE) and p (TM) light
and unpolarised, f_r = R(θ_h) (1 + ω_i·ω_r)² |A(λ)|² (A_eff/λ²) / ((cos θ_i + cos θ_r)² cos θ_i cos θ_r)
(times the shadowing term), with A_eff the coherence window's effective area (4πσ_s², σ_s a quarter of the
coherence length) and R the Fresnel reflectance at the half-vector angle (s and p for --fresnel index:… or a
stack; Schlick's approximation has no polarised form). --relative prints instead the paper's relative
reflectance ρ(λ) = f_r cos θ_i λ² / (A_eff R₀) (eq. 4 with the cos θ_i of eq. 9): 1 at a flat mirror's peak
at every λ, what BRDF maps show at an exposure. XYZ is the colour of ρ (eq. 9, a normal-incidence mirror
has Y = 1). The lookup method integrates over λ in advance, so it answers XYZ only. Default method:
reference for a SURFACE, lookup for a TABLE. --method rigorous scales each order's lobe to Maxwell's
efficiency (the C-method, TE and TM apart, over --material) on SURFACE as one period or, with --unit-cell
auto, on a scan's dominant period. With a scalar method on a scan with a dominant period, the output states
how far the scalar model is from Maxwell's equations there (worst order error, ΔE00), with a warning above
20 % or ΔE00 2.

Examples:
  iridis brdf eval builtin:sine --light 30deg --view 10deg,180deg --json
  iridis brdf eval builtin:blazed --method ground-truth --light 0deg --view 20deg,180deg
  iridis brdf eval builtin:sine --light 30deg --view 10deg,180deg --visual bluetit --spectra sine_view.csv
  iridis brdf eval 'builtin:sine?size=1100nm&pixel=10nm' --method rigorous --light 30deg --view 0deg --material gold
  iridis precompute builtin:elaphe -o elaphe.npz && iridis brdf eval elaphe.npz --light 20deg,0deg --view 35deg,180deg --json")]
pub struct BrdfEvalArgs {
    /// A height field (file or builtin:NAME) or a lookup table from `iridis precompute`.
    pub input: String,
    /// Light direction θ[,φ] (towards the light).
    #[arg(long)]
    pub light: String,
    /// View direction θ[,φ] (towards the viewer).
    #[arg(long)]
    pub view: String,
    /// ground-truth, ground-truth-periodic, reference, lookup, nmm, pq, stam-periodic, stam-periodic-triangular,
    /// stam-gaussian or rigorous [default: reference for a SURFACE, lookup for a TABLE].
    #[arg(long)]
    pub method: Option<String>,
    #[command(flatten)]
    pub rigorous: RigorousOpts,
    #[command(flatten)]
    pub shading: ShadingOpts,
    /// u-v resolution when the lookup method builds a table from a SURFACE.
    #[arg(long, default_value_t = 501)]
    pub uv_resolution: usize,
    /// u-v power when the lookup method builds a table from a SURFACE.
    #[arg(long, default_value_t = 5.0)]
    pub uv_power: f64,
    #[command(flatten)]
    pub model: ModelOpts,
    #[command(flatten)]
    pub surface_opts: SurfaceOpts,
    /// Print the paper's relative reflectance ρ(λ) instead of the BRDF in sr⁻¹.
    #[arg(long)]
    pub relative: bool,
    /// Also as an animal sees this direction: a visual system of `iridis vision` (bluetit, honeybee, …),
    /// from the reflectance factor π f_r(λ); key vision in --json.
    #[arg(long)]
    pub visual: Option<String>,
    /// Write the spectra as CSV (pavo reads it): wavelength_nm, π f_r for s, p and unpolarised light, ρ.
    #[arg(long)]
    pub spectra: Option<PathBuf>,
    /// Print JSON: the inputs, the wavelength grid, f_r(λ) in sr⁻¹ per polarisation, ρ(λ) (null for lookup)
    /// and XYZ.
    #[arg(long)]
    pub json: bool,
}

pub fn run_brdf(c: BrdfCommand) -> Result<()> {
    match c {
        BrdfCommand::Eval(a) => run_eval(a),
        BrdfCommand::Vision(a) => run_vision(a),
    }
}

fn run_eval(a: BrdfEvalArgs) -> Result<()> {
    crate::output::declare_opt("--spectra", a.spectra.as_deref(), &["csv"])?;
    let (tl, pl) = polar_azimuth("light", &a.light)?;
    let (tv, pv) = polar_azimuth("view", &a.view)?;
    let (wi, wr) = (direction(tl, pl), direction(tv, pv));
    let shading = a.shading.shading()?;
    let params = TableParams { uv_resolution: a.uv_resolution, uv_power: a.uv_power };
    let (mut model, surface) = (a.model.options(), a.surface_opts.options());
    let paper = a.shading.fresnel_convention == FresnelConvention::Paper;
    let method = a.method.clone().unwrap_or_else(|| iridis_api::brdf::default_method(&a.input).to_string());
    a.rigorous.apply(&method, &a.shading.fresnel, paper, &mut model)?;
    let p = eval_point(&a.input, Some(&method), &model, shading, params, &surface, wi, wr, &Cli)?;
    let q = &p.query;
    let deg = |r: f64| (r.to_degrees() * 1e9).round() / 1e9;
    let r0 = shading_r0(&a.shading)?;
    if let Some(path) = &a.spectra {
        crate::output::write_bytes(path, p.spectra_csv()?.as_bytes())?;
    }
    let vision = match &a.visual {
        Some(v) => Some(p.vision(&iridis_vision::Spec { visual: Some(v.clone()), ..Default::default() })?),
        None => None,
    };
    let area_um2 = p.effective_area_nm2.map(|a| a / 1e6);
    if a.json {
        return crate::output::print_json(&serde_json::json!({
            "input": a.input,
            "method": p.method,
            "light": { "theta_deg": deg(tl), "phi_deg": deg(pl), "direction": wi },
            "view": { "theta_deg": deg(tv), "phi_deg": deg(pv), "direction": wr },
            "fresnel": if p.rigorous.is_some() { serde_json::Value::Null } else { serde_json::json!(a.shading.fresnel) },
            "fresnel_convention": a.shading.fresnel_convention.name(),
            "fresnel_r0": r0,
            "shadowing": !a.shading.no_shadowing,
            "coherence_nm": p.coherence_nm,
            "window_effective_area_um2": area_um2,
            "illuminant": a.model.illuminant.as_deref().unwrap_or("d65"),
            "observer": a.model.observer.as_deref().unwrap_or("1931"),
            "wavelength_nm": q.wavelengths_nm,
            "brdf_per_sr": q.brdf,
            "reflectance": q.reflectance,
            "xyz": [q.xyz.x, q.xyz.y, q.xyz.z],
            "vision": vision.as_ref().map(serde_json::to_value).transpose()?,
            "rigorous": p.rigorous.as_ref().map(|r| r.to_json()),
            "scalar_error": p.scalar_error.as_ref().map(|e| e.to_json()),
        }));
    }
    crate::outln!(
        "{} · {} · light θ {}° φ {}° · view θ {}° φ {}°",
        a.input,
        p.method,
        deg(tl),
        deg(pl),
        deg(tv),
        deg(pv)
    )?;
    match &p.rigorous {
        Some(r) => crate::outln!(
            "{}; coherence {} (window area A_eff {})",
            r.sentence(),
            p.coherence_nm.map_or("–".into(), |c| format!("{:.3} µm", c / 1000.0)),
            area_um2.map_or("–".into(), |x| format!("{x:.4} µm²"))
        )?,
        None => crate::outln!(
            "Fresnel {} (R₀ = {r0:.4}), {}, coherence {} (window area A_eff {})",
            a.shading.fresnel,
            if a.shading.no_shadowing { "no shadowing" } else { "Cook-Torrance shadowing" },
            p.coherence_nm.map_or("–".into(), |c| format!("{:.3} µm", c / 1000.0)),
            area_um2.map_or("–".into(), |x| format!("{x:.4} µm²"))
        )?,
    }
    if let Some(e) = &p.scalar_error {
        crate::outln!("scalar model: {}", e.sentence())?;
    }
    match (&q.reflectance, &q.brdf, a.relative) {
        (Some(_), Some(b), false) => {
            crate::outln!("    λ (nm)   f_r s (sr⁻¹)   f_r p (sr⁻¹)   f_r unpol. (sr⁻¹)")?;
            for (k, l) in q.wavelengths_nm.iter().enumerate() {
                crate::outln!("{l:10.1}  {:13.4e}  {:13.4e}  {:18.4e}", b.s[k], b.p[k], b.unpolarized[k])?;
            }
        }
        (Some(rho), b, _) => {
            if b.is_none() && !a.relative {
                crate::outln!(
                    "f_r: not available for the {} method{} — the relative reflectance instead:",
                    p.method,
                    if a.shading.fresnel_convention.name() == "paper" {
                        " under the paper's R² convention"
                    } else {
                        ""
                    }
                )?;
            }
            crate::outln!("    λ (nm)        ρ(λ) (relative: a flat mirror's peak is 1)")?;
            for (l, r) in q.wavelengths_nm.iter().zip(rho) {
                crate::outln!("{l:10.1}  {r:10.4e}")?;
            }
        }
        (None, _, _) => {
            crate::outln!("f_r(λ), ρ(λ): not available — the {} method integrates over λ in advance", p.method)?
        }
    }
    crate::outln!("XYZ {:.6e} {:.6e} {:.6e}  (of ρ; a normal-incidence mirror: Y = 1)", q.xyz.x, q.xyz.y, q.xyz.z)?;
    if let Some(v) = &vision {
        let s = &v.samples[0];
        let f = |x: &[f64]| x.iter().map(|c| format!("{c:.4}")).collect::<Vec<_>>().join("  ");
        crate::outln!("seen by {} under {} (receptors {}):", v.visual.name, v.illuminant, v.receptors.join(", "))?;
        crate::outln!("  quantum catches (von Kries)  {}", f(&s.quantum_catches))?;
        crate::outln!("  relative catches             {}", f(&s.relative_catches))?;
        for n in &v.notes {
            eprintln!("note: {n}");
        }
    }
    Ok(())
}

/// `R₀` of the Fresnel source (what the relative ρ divides by).
fn shading_r0(s: &ShadingOpts) -> Result<f64> {
    Ok(s.shading()?.fresnel.normal_reflectance())
}

/// Tone-maps a map to 8-bit sRGB.
pub fn map_to_rgb8(xyz: &[Xyz], tone: ToneMap) -> Vec<u8> {
    xyz.iter().flat_map(|&p| tone.to_rgb8(p)).collect()
}

pub fn run_brdf_map(a: BrdfMapArgs) -> Result<()> {
    if !(a.exposure.is_finite() && a.exposure > 0.0) {
        bail!("--exposure {} must be a positive number of RU", a.exposure);
    }
    if !(8..=8192).contains(&a.size) {
        bail!("--size {} must be between 8 and 8192 pixels", a.size);
    }
    let encoding = Encoding::parse(&a.gamma).map_err(anyhow::Error::msg)?;
    let wi = parse_incidence(&a.incidence)?;
    let mut a = a;
    a.uv_resolution = a.uv_resolution_arg.unwrap_or(501);
    a.uv_power = a.uv_power_arg.unwrap_or(5.0);
    if is_table(&a.input) {
        refuse_build_options_for_table(&a)?;
    }
    declare_map_outputs(&a)?;
    if a.gpu {
        if a.method == iridis_api::brdf::RIGOROUS {
            bail!("the rigorous BRDF runs on the CPU: leave out --gpu");
        }
        if a.auto_exposure || a.plot.is_some() {
            bail!("--auto-exposure and --plot are made on the CPU's map: leave out --gpu (or give --exposure)");
        }
        return crate::cmd::gpu::run_brdf_map(a, wi, encoding);
    }
    if a.table_precision.is_some() {
        bail!("--table-precision chooses how the GPU stores the lookup table: add --gpu (the CPU evaluates the f64 table)");
    }
    let shading = a.shading.shading()?;
    let params = TableParams { uv_resolution: a.uv_resolution, uv_power: a.uv_power };
    let precision = if a.f32 { Precision::F32 } else { Precision::F64 };
    let start = std::time::Instant::now();
    let (mut model, surface) = (a.model.options(), a.surface_opts.options());
    // The map asks about one light: the reference method keeps only its bins (memory).
    model.light = Some(wi);
    let paper = a.shading.fresnel_convention == FresnelConvention::Paper;
    a.rigorous.apply(&a.method, &a.shading.fresnel, paper, &mut model)?;
    if a.rigorous.material.is_some() && a.method != iridis_api::brdf::RIGOROUS {
        bail!("--material is the rigorous method's medium; the scalar methods take --fresnel (index:…, gold, stack:…)");
    }
    let (e, rigorous) = map_evaluator(&a.input, &a.method, &model, shading, params, precision, &surface, wi, &Cli)?;
    if let Some(r) = &rigorous {
        eprintln!("note: {}", r.sentence());
    }
    let prepared = start.elapsed().as_secs_f64();
    let xyz = render_map(e.as_ref(), wi, a.size, &Cli);
    // Before any file is written: a method without f_r(λ) is refused with nothing on disk.
    let per_sr = match &a.brdf {
        Some(_) => Some(iridis_api::brdf::render_map_per_sr(e.as_ref(), &model, wi, a.size, &Cli)?),
        None => None,
    };
    let total = start.elapsed().as_secs_f64();
    let secs = total - prepared;
    let mut exposure = a.exposure;
    if a.auto_exposure {
        match iridis_api::brdf::auto_exposure(&xyz, a.size) {
            Some(auto) => {
                exposure = auto.exposure_ru;
                eprintln!(
                    "note: exposure {:.4} RU, chosen from the map (its 99th-percentile lit pixel is white): {:.2} % of \
                     the disk's pixels clipped, {:.2} % lit",
                    exposure,
                    100.0 * auto.clipped_share,
                    100.0 * auto.lit_share
                );
            }
            None => eprintln!(
                "warning: the map is black: no light reaches these view directions (at this coherence a mirror's \
                 lobe is narrower than a pixel); the exposure stays {exposure} RU"
            ),
        }
    }
    let tone = ToneMap { exposure_ru: exposure, encoding };
    write_map_outputs(&a, &xyz, tone)?;
    if let (Some(path), Some(f)) = (&a.brdf, &per_sr) {
        write_xyz_npy(path, f, a.size)?;
        eprintln!(
            "note: {} holds f_r in sr⁻¹ (unpolarised; X, Y, Z weighted by {} and the {} observer, Y the luminous \
             BRDF), coherence {:.3} µm",
            path.display(),
            model.illuminant.as_deref().unwrap_or("D65"),
            model.observer.as_deref().unwrap_or("CIE 1931 2°"),
            e.coherence_nm().unwrap_or(f64::NAN) / 1000.0
        );
    }
    if let Some(path) = &a.plot {
        let name = std::path::Path::new(&a.input).file_name().map_or(a.input.clone(), |f| f.to_string_lossy().into());
        let (t, p) = (wi[2].clamp(-1.0, 1.0).acos().to_degrees(), wi[1].atan2(wi[0]).to_degrees());
        let title = format!("{name} · θi {t:.0}° φi {p:.0}° · {} · D65 · {exposure:.3e} RU", e.name());
        write_map_plot(path, &xyz, a.size, tone, title)?;
    }
    crate::outln!(
        "wrote {} ({} map, {}², {total:.2} s in all: {prepared:.2} s to load and prepare, {secs:.2} s for the \
         map, {:.0} pixels/s)",
        a.output.display(),
        e.name(),
        a.size,
        (a.size * a.size) as f64 / secs.max(1e-9)
    )?;
    Ok(())
}

/// The formats of `brdf-map -o`: a tone-mapped image, linear sRGB, or the linear XYZ numbers.
const MAP_FORMATS: &[&str] = &["png", "exr", "npy"];

/// Declares the outputs of `brdf-map` (-o, --raw, --exr) before anything is computed (output.rs).
pub fn declare_map_outputs(a: &BrdfMapArgs) -> Result<()> {
    crate::output::declare("-o", &a.output, MAP_FORMATS)?;
    crate::output::declare_opt("--raw", a.raw.as_deref(), &["npy"])?;
    crate::output::declare_opt("--brdf", a.brdf.as_deref(), &["npy"])?;
    crate::output::declare_opt("--exr", a.exr.as_deref(), &["exr"])?;
    crate::output::declare_opt("--plot", a.plot.as_deref(), &["png"])?;
    Ok(())
}

/// Writes a map's outputs: -o in the format its extension names, and --raw and --exr.
pub fn write_map_outputs(a: &BrdfMapArgs, xyz: &[Xyz], tone: ToneMap) -> Result<()> {
    let ext = crate::output::format_of("-o", &a.output, MAP_FORMATS)?;
    match ext.as_str() {
        "exr" => write_exr(&a.output, xyz, a.size, a.exposure)?,
        "npy" => write_xyz_npy(&a.output, xyz, a.size)?,
        _ => crate::output::write_png_rgb8(&a.output, a.size as u32, a.size as u32, &map_to_rgb8(xyz, tone))?,
    }
    if let Some(raw) = &a.raw {
        write_xyz_npy(raw, xyz, a.size)?;
    }
    if let Some(exr) = &a.exr {
        write_exr(exr, xyz, a.size, a.exposure)?;
    }
    Ok(())
}

/// A map drawn as a figure with the view-direction axes of the paper's layout and a title, written as PNG.
fn write_map_plot(path: &Path, xyz: &[Xyz], size: usize, tone: ToneMap, title: String) -> Result<()> {
    let pixels = iridis_plot::RgbImage { width: size as u32, height: size as u32, data: map_to_rgb8(xyz, tone) };
    let plot = iridis_plot::ImagePlot {
        title,
        x_label: "x = sin θr cos φr".into(),
        y_label: "y = sin θr sin φr".into(),
        x_range: (-1.0, 1.0),
        y_range: (-1.0, 1.0),
        pixels: &pixels,
        overlays: vec![],
        colorbar: None,
        size: (560, 600),
    }
    .render()?;
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
    image::DynamicImage::ImageRgb32F(img)
        .write_to(&mut bytes, image::ImageFormat::OpenExr)
        .map_err(|e| anyhow::anyhow!("cannot encode EXR: {e}"))?;
    crate::output::write_bytes(path, bytes.get_ref())
}

/// The demo's diffraction section: lookup BRDF maps of built-in surfaces (the kinds of the paper's Figs. 12–14).
pub fn demo(g: &mut iridis_api::gallery::Gallery) -> Result<()> {
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
        crate::outln!("  {spec}: Taylor terms and lookup tables …")?;
        let patch = load_patch(&spec, &none, &Cli)?;
        let spectral = spectral_setup(&model, &Cli)?;
        let terms = taylor_terms(&patch, &model, &Cli)?;
        let table = build_table(&terms, &spectral, TableParams { uv_resolution: 201, uv_power: 5.0 }, &spec, &Cli)?;
        let n = table.meta.taylor_terms;
        let lookup = Lookup::new(Arc::new(table), Shading::default(), Precision::F64)?;
        let wi = direction(f64::to_radians(theta_deg), 0.0);
        let xyz = render_map(&lookup, wi, size, &Cli);
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn incidence_parses() {
        assert!(parse_incidence("90deg").is_err());
        assert!(parse_incidence("20deg,0deg,1deg").is_err());
        let d = parse_incidence("0deg").unwrap();
        assert!((d[2] - 1.0).abs() < 1e-15);
    }
}
