//! `iridis surface …`: inspect, generate and convert height fields (the `iridis-surface` crate, through
//! `iridis_api::surface_info`).

use std::path::PathBuf;

use anyhow::Result;
use clap::{Args as ClapArgs, Subcommand};
use iridis_api::surface_info::{self as lib, InfoFigures};
use iridis_api::Report as _;
use iridis_surface::{HeightField, LoadOptions, DEFAULT_COHERENCE_NM};

use crate::output::{declare_opt, print_answer};
use crate::progress::Cli;

pub use iridis_api::surface_info::SURFACE_HELP;

// Parsed once per run: the size difference between variants costs nothing worth boxing for.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Subcommand)]
pub enum SurfaceCommand {
    /// Size, pixel size, heights and the dominant periods (with orientations) of a height field.
    #[command(after_help = INFO_HELP)]
    Info(InfoArgs),
    /// The channels (images) a file holds: index, name, scan direction, size and unit.
    #[command(after_help = CHANNELS_HELP)]
    Channels(ChannelsArgs),
    /// Generate a nanostructure (gratings, bump lattices, CD, random, snake skins) and write it.
    #[command(after_help = GENERATE_HELP)]
    Generate(GenerateArgs),
    /// Convert between formats, optionally levelling, cropping, resampling, tiling or padding on the way.
    #[command(after_help = CONVERT_HELP)]
    Convert(ConvertArgs),
}

const INFO_HELP: &str = "\
Periods come from the power spectrum of the plane-levelled, Hann-windowed field, refined off the FFT grid.
orientation_deg is the direction in which the height varies (the grating vector), counter-clockwise from +x
with y up: ridges along y give 0°, nanofingers along x give 90°. power is the share of the height variance
in the peak: a clean grating's first order holds most of it, a random surface spreads it (≈ 1 % a peak).

SURFACE is a file or builtin:NAME (see iridis surface --help); files are recognised by content.

Examples:
  iridis surface info builtin:blazed
  iridis surface info builtin:elaphe --json --image elaphe.png
  iridis surface info scan.gwy --level plane
  iridis surface info scan.png --pixel-size 65nm --max-height 300nm
  iridis surface info afm.npz --channel 1 --pixel-size 20nm
  iridis surface info scan.spm --channel Height --psdf psdf.png --acf acf.png --json
  iridis surface info scan.npy --pixel-size 10nm --height-unit m
  iridis surface info 'builtin:sine?period=1500nm&angle=30deg&size=20um&pixel=20nm'";

const CHANNELS_HELP: &str = "\
Instrument files hold several images (height trace and retrace, amplitude, phase, …). Every command that
reads a SURFACE takes --channel with the index or the name shown here (names match without regard to case
or punctuation; NAME_DIRECTION, e.g. height_retrace, picks a direction). Without --channel the channel
named Height is read (as AFMReader reads Bruker files), else the first height channel (a length unit, named
like a height); every command says which it took. Channels in another unit, or named for another signal
(amplitude, error, deformation, phase, …) even in metres, are not heights: --as-height reads one anyway.
A pixel size or height unit the file states wins over --pixel-size/--height-unit unless --override-units.

Examples:
  iridis surface channels scan.spm
  iridis surface channels scan.ibw --json
  iridis surface info scan.jpk --channel height_retrace
  iridis surface info scan.spm --channel 7";

const GENERATE_HELP: &str = "\
Kinds and their parameters (defaults shown; lengths need units):
  sine         --period 1100nm --depth 100nm
               h = depth/2 · sin(2π u/period)
  blazed       --period 2500nm --blaze 6deg | --depth …
               saw-tooth rising along +x: facets face −x
  rect-bumps   --period 1100nm (--period-x/-y) --fill 0.5 --depth 100nm
               Stam's boxes (paper Fig. 11a)
  tri-bumps    same as rect-bumps
               pyramids on the same footprint (Fig. 11c)
  cd           --pitch 1600nm --bit 231nm --pit-width 500nm --depth 110nm
               tracks along x, pits 3T–11T
  gaussian     --rms 30nm --corr 500nm
               correlation rms²·exp(−r²/corr²), tiles seamlessly
  elaphe       --spacing 1100nm --finger 4000nm --rms 60nm
               overlapping nanofinger layers along x
  xenopeltis   --along 1500nm --across 550nm --depth 120nm
               curving fingers, grains of other periods
Every kind also takes --size 65um (or --size-x/--size-y), --pixel-size 65nm and --angle 0deg
(counter-clockwise); the random ones (cd, gaussian, elaphe, xenopeltis) --seed 1.

The output format follows the extension: .gwy (with units), .npy (+ .npy.json sidecar), .npz (like
np.savez: one array 'heights', + .npz.json sidecar), .png (16-bit, + .png.json sidecar with pixel size and
height range) or .txt (Gwyddion-style header).

Examples:
  iridis surface generate blazed -o blazed.gwy
  iridis surface generate blazed --period 2500nm --blaze 10deg --angle 30deg -o blazed30.npy
  iridis surface generate elaphe --size 20um --pixel-size 40nm --seed 7 -o elaphe.png --image elaphe_preview.png
  iridis surface generate gaussian --rms 20nm --corr 300nm -o rough.txt";

const CONVERT_HELP: &str = "\
Steps run in this order: --level, --crop, --resample, --tile, --pad. Writing: .gwy, .npy (+ sidecar),
.npz (array 'heights' + sidecar), .png (16-bit + sidecar), .txt. TIFF is read but not written.

Examples:
  iridis surface convert scan.gwy scan.npy
  iridis surface convert scan.png scan.gwy --pixel-size 65nm --max-height 250nm --level plane
  iridis surface convert builtin:xenopeltis xeno.gwy --crop 0,0,500,500 --resample 50nm
  iridis surface convert small.npy tiled.npy --tile 4x4
  iridis surface convert afm.npz afm.gwy --channel 0 --pixel-size 10nm";

/// How to read a SURFACE (shared by every subcommand).
#[derive(Debug, Clone, ClapArgs)]
pub struct LoadArgs {
    /// Pixel size (e.g. 65nm): required for images, .npy and text without units; a file's own wins unless
    /// --override-units.
    #[arg(long, value_parser = crate::args::positive_length_nm)]
    pub pixel_size: Option<f64>,
    /// Images: the height that white stands for (black is 0), e.g. 250nm.
    #[arg(long, value_parser = crate::args::positive_length_nm)]
    pub max_height: Option<f64>,
    /// Channel of a multi-channel file, by index or name (`iridis surface channels FILE` lists them);
    /// default the channel named Height, else the first height channel (.npz: the only 2-D array).
    #[arg(long)]
    pub channel: Option<iridis_surface::formats::channel::ChannelSel>,
    /// Unit of heights in files that do not give one (.npy, text, a unitless channel), e.g. m or nm.
    #[arg(long)]
    pub height_unit: Option<String>,
    /// Built-ins: edge of the square patch (default 65um).
    #[arg(long, value_parser = crate::args::positive_length_nm)]
    pub size: Option<f64>,
    /// Built-ins: random seed (default 1).
    #[arg(long)]
    pub seed: Option<u64>,
    #[command(flatten)]
    pub units: iridis_api::surface::UnitOverrides,
}

impl LoadArgs {
    fn options(&self) -> LoadOptions {
        LoadOptions {
            pixel_size_nm: self.pixel_size,
            max_height_nm: self.max_height,
            channel: self.channel.clone(),
            height_unit: self.height_unit.clone(),
            size_nm: self.size,
            seed: self.seed,
            ignore_sidecar: false,
            override_units: self.units.override_units,
            as_height: self.units.as_height,
        }
    }
}

#[derive(Debug, ClapArgs)]
pub struct InfoArgs {
    /// File path or builtin:NAME.
    pub surface: String,
    #[command(flatten)]
    pub load: LoadArgs,
    /// Levelling before analysis: none, mean, plane, poly (degree 2), lines (median line correction) or rows
    /// (line means); the period analysis and the roughness figures always remove a plane as well.
    #[arg(long, default_value = "none")]
    pub level: String,
    /// How many periods to report.
    #[arg(long, default_value_t = 5)]
    pub peaks: usize,
    /// Coherence length 4σ_s for the patch-size warning.
    #[arg(long, default_value = "65um", value_parser = crate::args::positive_length_nm)]
    pub coherence: f64,
    /// Write a shaded-relief preview with a scale bar (PNG).
    #[arg(long)]
    pub image: Option<PathBuf>,
    /// Write the 2-D power spectral density (log scale, plane-levelled field) as a PNG.
    #[arg(long)]
    pub psdf: Option<PathBuf>,
    /// Write the 2-D autocorrelation function (plane-levelled field) as a PNG.
    #[arg(long)]
    pub acf: Option<PathBuf>,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
}

#[derive(Debug, ClapArgs)]
pub struct ChannelsArgs {
    /// The file.
    pub file: PathBuf,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
}

#[derive(Debug, ClapArgs)]
pub struct GenerateArgs {
    /// sine, blazed, rect-bumps, tri-bumps, cd, gaussian, elaphe or xenopeltis.
    pub kind: String,
    /// Output file (.gwy, .npy, .npz, .png or .txt).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Also write a shaded-relief preview (PNG).
    #[arg(long)]
    pub image: Option<PathBuf>,
    /// Print the generated field's info as JSON.
    #[arg(long)]
    pub json: bool,
    /// Edge of the square patch (default 65um).
    #[arg(long)]
    pub size: Option<String>,
    /// Patch width along x.
    #[arg(long)]
    pub size_x: Option<String>,
    /// Patch height along y.
    #[arg(long)]
    pub size_y: Option<String>,
    /// Pixel size (default 65nm); --pixel, the old name, is still read.
    #[arg(long = "pixel-size", alias = "pixel")]
    pub pixel: Option<String>,
    /// Counter-clockwise rotation of the pattern (e.g. 30deg).
    #[arg(long)]
    pub angle: Option<String>,
    /// Random seed (cd, gaussian, elaphe, xenopeltis; refused for the others, which have no randomness).
    #[arg(long)]
    pub seed: Option<String>,
    /// Grating or lattice period.
    #[arg(long)]
    pub period: Option<String>,
    /// Bump lattice period along x.
    #[arg(long)]
    pub period_x: Option<String>,
    /// Bump lattice period along y.
    #[arg(long)]
    pub period_y: Option<String>,
    /// Peak-to-valley depth (sine, blazed, bumps, cd pits, xenopeltis fingers).
    #[arg(long)]
    pub depth: Option<String>,
    /// Blaze angle of a blazed grating (instead of --depth).
    #[arg(long)]
    pub blaze: Option<String>,
    /// Bump footprint as a fraction of the period, (0, 1].
    #[arg(long)]
    pub fill: Option<String>,
    /// CD track pitch.
    #[arg(long)]
    pub pitch: Option<String>,
    /// CD channel bit length T.
    #[arg(long)]
    pub bit: Option<String>,
    /// CD pit width.
    #[arg(long)]
    pub pit_width: Option<String>,
    /// RMS height (gaussian, elaphe).
    #[arg(long)]
    pub rms: Option<String>,
    /// Correlation length (gaussian).
    #[arg(long)]
    pub corr: Option<String>,
    /// Finger row spacing (elaphe).
    #[arg(long)]
    pub spacing: Option<String>,
    /// Mean finger length (elaphe).
    #[arg(long)]
    pub finger: Option<String>,
    /// Period along the fingers (xenopeltis).
    #[arg(long)]
    pub along: Option<String>,
    /// Period across the fingers (xenopeltis).
    #[arg(long)]
    pub across: Option<String>,
}

#[derive(Debug, ClapArgs)]
pub struct ConvertArgs {
    /// Input file or builtin:NAME.
    pub input: String,
    /// Output file (.gwy, .npy, .npz, .png or .txt).
    pub output: PathBuf,
    #[command(flatten)]
    pub load: LoadArgs,
    /// Levelling: none, mean (remove the mean), plane (remove the tilt), poly (tilt and bow, degree 2), lines
    /// (median line correction) or rows (per-scan-line means).
    #[arg(long, default_value = "none")]
    pub level: String,
    #[command(flatten)]
    pub reshape: lib::Reshape,
}

pub fn run(command: SurfaceCommand) -> Result<()> {
    match command {
        SurfaceCommand::Info(a) => info(a),
        SurfaceCommand::Channels(a) => {
            let c = lib::channels(&a.file)?;
            print_answer(a.json, || Ok(c.to_json()), || c.text())
        }
        SurfaceCommand::Generate(a) => generate(a),
        SurfaceCommand::Convert(a) => convert(a),
    }
}

fn load(spec: &str, load: &LoadArgs, level: &str) -> Result<HeightField> {
    lib::level(lib::load(spec, &load.options(), &Cli)?, level)
}

fn info(a: InfoArgs) -> Result<()> {
    declare_opt("--image", a.image.as_deref(), &["png"])?;
    declare_opt("--psdf", a.psdf.as_deref(), &["png"])?;
    declare_opt("--acf", a.acf.as_deref(), &["png"])?;
    let hf = load(&a.surface, &a.load, &a.level)?;
    let figures = InfoFigures { image: a.image.as_deref(), psdf: a.psdf.as_deref(), acf: a.acf.as_deref() };
    let r = lib::info_with_figures(&hf, &a.surface, a.peaks, a.coherence, figures, &Cli)?;
    print_answer(a.json, || Ok(r.clone()), || lib::info_text(&r))?;
    lib::info_warnings(&r).iter().for_each(|w| Cli.warn(w));
    if let (Some(p), false) = (&a.image, a.json) {
        crate::outln!("preview      {}", p.display())?;
    }
    Ok(())
}

fn generate(a: GenerateArgs) -> Result<()> {
    lib::check_kind(&a.kind)?;
    lib::declare_surface("-o", &a.output)?;
    declare_opt("--image", a.image.as_deref(), &["png"])?;
    let given = [
        ("size", &a.size),
        ("size-x", &a.size_x),
        ("size-y", &a.size_y),
        ("pixel-size", &a.pixel),
        ("angle", &a.angle),
        ("seed", &a.seed),
        ("period", &a.period),
        ("period-x", &a.period_x),
        ("period-y", &a.period_y),
        ("depth", &a.depth),
        ("blaze", &a.blaze),
        ("fill", &a.fill),
        ("pitch", &a.pitch),
        ("bit", &a.bit),
        ("pit-width", &a.pit_width),
        ("rms", &a.rms),
        ("corr", &a.corr),
        ("spacing", &a.spacing),
        ("finger", &a.finger),
        ("along", &a.along),
        ("across", &a.across),
    ];
    let params: Vec<(String, String)> =
        given.into_iter().filter_map(|(k, v)| v.as_ref().map(|v| (k.to_string(), v.clone()))).collect();
    let hf = lib::generate(&a.kind, &params)?;
    lib::write_surface(&hf, &a.output)?;
    if let Some(p) = &a.image {
        lib::write_preview(&hf, p, &a.kind)?;
    }
    let info = || Ok(iridis_api::surface::info(&hf, 5, DEFAULT_COHERENCE_NM));
    print_answer(a.json, info, || lib::generated_text(&hf, &a.kind, &a.output))
}

fn convert(a: ConvertArgs) -> Result<()> {
    lib::declare_conversion(&a.input, &a.output)?;
    let hf = a.reshape.apply(load(&a.input, &a.load, &a.level)?)?;
    lib::write_surface(&hf, &a.output)?;
    // What the reader warned about; the model's concerns (coherence area, coarse pixels) belong to the
    // commands that run the model.
    hf.meta.warnings.iter().for_each(|w| Cli.warn(w));
    crate::outln!("{}", lib::converted_text(&hf, &a.output).trim_end_matches('\n'))
}
