//! `iridis precompute`, `iridis brdf-map` and `iridis brdf eval|vision`: the diffraction BRDF of a height field
//! (issue 5), each a call of `iridis_api` (`precompute::precompute`, `brdf_map::brdf_map`, `brdf_eval::brdf_eval`,
//! `brdf_vision::brdf_vision`) that this module parses for and prints.

use std::path::PathBuf;

use anyhow::Result;
use clap::Args as ClapArgs;
use iridis_color::Encoding;
use iridis_diffraction::Units;

use crate::args::{parse_incidence, polar_azimuth, ColourOpts, ModelOpts, RigorousOpts, ShadingOpts};
use crate::output::print_answer;
use crate::progress::Cli;

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
    #[command(flatten)]
    pub colour: ColourOpts,
    #[command(flatten)]
    pub grid: iridis_api::model::TableGrid,
    /// What the colours measure: relative (the paper's: a flat mirror's peak is 1) or radiometric (the BRDF:
    /// a flat surface reflects R(θ)/R₀ of the light).
    #[arg(long, value_name = "relative|radiometric", default_value = "relative", value_parser = units)]
    pub units: Units,
    /// Build the tables on the GPU (values in f32).
    #[arg(long)]
    pub gpu: bool,
    #[command(flatten)]
    pub surface_opts: iridis_api::SurfaceOptions,
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
  iridis brdf-map 'builtin:sine?size=8um&pixel=50nm' --method reference --size 32 --subsamples 4 -o thumb.png
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
    #[arg(long, alias = "light", default_value = "0deg")]
    pub incidence: String,
    /// Map size in pixels.
    #[arg(long, default_value_t = 512)]
    pub size: usize,
    /// View samples a pixel side (1–16): each pixel the mean of N² directions across it, so that lobes narrower
    /// than a pixel still show (a small map of a grating); 1 samples the pixel's centre. With --gpu, the map of
    /// N times the size averaged over N × N blocks (the same numbers).
    #[arg(long, default_value_t = 1, value_name = "N")]
    pub subsamples: usize,
    /// Exposure in RU (1 RU: a normal-incidence mirror just saturates white).
    #[arg(long, default_value_t = iridis_api::brdf_map::DEFAULT_EXPOSURE_RU)]
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
    /// Lookup sum in f32, as a GPU would evaluate it (the lookup method on the CPU; refused otherwise).
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
    #[command(flatten)]
    pub colour: ColourOpts,
    #[command(flatten)]
    pub grid: iridis_api::model::TableGrid,
    #[command(flatten)]
    pub surface_opts: iridis_api::SurfaceOptions,
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
    #[arg(long, alias = "incidence", value_parser = crate::args::angle_rad, default_value = "0deg")]
    pub light: f64,
    /// The plane of incidence's azimuth [default: the orientation of the surface's strongest period].
    #[arg(long, value_parser = crate::args::angle_rad)]
    pub azimuth: Option<f64>,
    /// View angles θ_r in degrees, comma-separated, signed (positive on the specular side).
    #[arg(long, default_value = "-60,-50,-40,-30,-20,-10,0,10,20,30,40,50,60")]
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
    pub surface_opts: iridis_api::SurfaceOptions,
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
  iridis brdf eval builtin:elaphe --method ground-truth --light 0deg --view 30deg,270deg   first order of its 1.1 µm ridges: 550 nm
  iridis brdf eval builtin:sine --light 30deg --view 10deg,180deg --visual bluetit --spectra sine_view.csv
  iridis brdf eval 'builtin:sine?size=1100nm&pixel=10nm' --method rigorous --light 30deg --view 0deg --material gold
  iridis precompute builtin:elaphe -o elaphe.npz && iridis brdf eval elaphe.npz --light 20deg,0deg --view 35deg,180deg --json")]
pub struct BrdfEvalArgs {
    /// A height field (file or builtin:NAME) or a lookup table from `iridis precompute`.
    pub input: String,
    /// Light direction θ[,φ] (towards the light).
    #[arg(long, alias = "incidence")]
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
    #[command(flatten)]
    pub grid: iridis_api::model::TableGrid,
    #[command(flatten)]
    pub model: ModelOpts,
    #[command(flatten)]
    pub colour: ColourOpts,
    #[command(flatten)]
    pub surface_opts: iridis_api::SurfaceOptions,
    /// Print the paper's relative reflectance ρ(λ) instead of the BRDF in sr⁻¹.
    #[arg(long)]
    pub relative: bool,
    /// Also as an animal sees this direction: a visual system of `iridis vision` (bluetit, honeybee, …),
    /// from the reflectance factor π f_r(λ) over 300–700 nm (reference method; others their 380–780 nm grid,
    /// with a note); key vision in --json.
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

pub fn run_precompute(a: PrecomputeArgs) -> Result<()> {
    let r = iridis_api::precompute::PrecomputeRequest {
        surface: a.surface,
        surface_opts: a.surface_opts,
        model: a.model.with_colour(&a.colour),
        params: a.grid.params()?,
        units: a.units,
        gpu: a.gpu,
    };
    let line = iridis_api::precompute::precompute(&r, &a.output, &Cli)?;
    crate::outln!("{line}")
}

pub fn run_brdf_map(a: BrdfMapArgs) -> Result<()> {
    let encoding = Encoding::parse(&a.gamma).map_err(anyhow::Error::msg)?;
    let wi = parse_incidence(&a.incidence)?;
    let mut model = a.model.with_colour(&a.colour);
    a.rigorous.apply(&mut model)?;
    let r = iridis_api::brdf_map::MapRequest {
        input: a.input,
        method: a.method,
        model,
        surface: a.surface_opts,
        fresnel: a.shading.fresnel,
        convention: a.shading.fresnel_convention,
        shadowing: !a.shading.no_shadowing,
        wi,
        size: a.size,
        exposure_ru: a.exposure,
        auto_exposure: a.auto_exposure,
        encoding,
        grid: a.grid,
        f32: a.f32,
        gpu: a.gpu,
        table_precision: a.table_precision,
        per_sr: a.brdf.is_some(),
        subsamples: a.subsamples,
    };
    let files = iridis_api::brdf_map::MapFiles { output: a.output, raw: a.raw, brdf: a.brdf, exr: a.exr, plot: a.plot };
    let line = iridis_api::brdf_map::brdf_map(&r, &files, &Cli)?;
    crate::outln!("{line}")
}

pub fn run_brdf(c: BrdfCommand) -> Result<()> {
    match c {
        BrdfCommand::Eval(a) => run_eval(a),
        BrdfCommand::Vision(a) => run_vision(a),
    }
}

fn run_eval(a: BrdfEvalArgs) -> Result<()> {
    let (light, view) = (polar_azimuth("light", &a.light)?, polar_azimuth("view", &a.view)?);
    let mut model = a.model.with_colour(&a.colour);
    let method = a.method.clone().unwrap_or_else(|| iridis_api::brdf::default_method(&a.input).to_string());
    a.rigorous.apply(&mut model)?;
    let r = iridis_api::brdf_eval::EvalRequest {
        input: a.input,
        method: Some(method),
        model,
        surface: a.surface_opts,
        fresnel: a.shading.fresnel,
        convention: a.shading.fresnel_convention,
        shadowing: !a.shading.no_shadowing,
        grid: a.grid,
        light,
        view,
        visual: a.visual,
        relative: a.relative,
    };
    let e = iridis_api::brdf_eval::brdf_eval(&r, a.spectra.as_deref(), &Cli)?;
    print_answer(a.json, || e.to_json(), || e.text())
}

fn run_vision(a: BrdfVisionArgs) -> Result<()> {
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
    let plane =
        iridis_api::vision::PlaneViews { light_theta: a.light, azimuth: a.azimuth, views_deg: &views, spec: &spec };
    let v = iridis_api::brdf_vision::brdf_vision(
        &iridis_api::surface::Source::Spec(a.input.clone()),
        &a.surface_opts,
        &a.model.options(),
        a.shading.shading()?,
        plane,
        a.strip.as_deref(),
        &Cli,
    )?;
    print_answer(a.json, || Ok(v.to_json()), || iridis_api::brdf_vision::vision_text(&v))
}
