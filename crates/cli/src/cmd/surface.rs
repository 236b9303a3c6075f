//! `iridis surface …`: inspect, generate and convert height fields (the `iridis-surface` crate).

use std::path::{Path, PathBuf};

use anyhow::{bail, Context, Result};
use clap::{Args as ClapArgs, Subcommand};
use iridis_surface::builtin::{self, KINDS};
use iridis_surface::formats::{self, sidecar_path, Format};
use iridis_surface::generate::Grid;
use iridis_surface::render::{format_length, shaded_relief};
use iridis_surface::{find_peaks, load_surface, prep, HeightField, LoadOptions, PeakOptions, DEFAULT_COHERENCE_NM};
use serde_json::json;

pub const SURFACE_HELP: &str = "\
SURFACE is a file or builtin:NAME. Files are recognised by content: instrument files with their units
(Bruker NanoScope .spm/.000, Asylum .ibw, JPK .jpk, WSxM .stp/.top, Nanonis .sxm, Gwyddion .gwy/.gsf; pick a
channel with --channel NAME or --channel N, listed by `iridis surface channels FILE`), numpy .npy or .npz (np.savez / np.savez_compressed: the only 2-D array, or --channel N among several, in name
order), 8/16-bit greyscale PNG or TIFF (relative heights: give --max-height and --pixel-size), or a text
matrix (Gwyddion ASCII export header understood). Units missing from a file can come from a JSON sidecar
FILE.EXT.json or FILE.json: {\"pixel_size_nm\": 65, \"height_unit\": \"nm\", \"max_height_nm\": 250}.
Built-ins (blazed, sine, cd, elaphe, xenopeltis, gaussian) are generated on the fly: a 65 µm patch at
65 nm per pixel (1000 × 1000), seed 1; change them with --size/--pixel-size/--seed or a query string
(not both for one parameter), e.g. builtin:elaphe?size=16um&pixel=50nm&seed=3&angle=10deg (parameters: iridis surface generate --help).";

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
Every kind also takes --size 65um (or --size-x/--size-y), --pixel-size 65nm, --seed 1 and --angle 0deg
(counter-clockwise).

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
    pub units: crate::args::UnitFlags,
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
    #[arg(long, allow_hyphen_values = true)]
    pub angle: Option<String>,
    /// Random seed.
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
    /// Crop to ROW,COL,ROWS,COLS (samples).
    #[arg(long)]
    pub crop: Option<String>,
    /// Resample to this pixel size (e.g. 50nm), keeping the extent.
    #[arg(long, value_parser = crate::args::positive_length_nm)]
    pub resample: Option<f64>,
    /// Tile NYxNX times (e.g. 3x3).
    #[arg(long)]
    pub tile: Option<String>,
    /// Pad with the mean height to ROWSxCOLS samples (centred).
    #[arg(long)]
    pub pad: Option<String>,
}

pub fn run(command: SurfaceCommand) -> Result<()> {
    match command {
        SurfaceCommand::Info(a) => info(a),
        SurfaceCommand::Channels(a) => channels(a),
        SurfaceCommand::Generate(a) => generate(a),
        SurfaceCommand::Convert(a) => convert(a),
    }
}

fn load(spec: &str, load: &LoadArgs) -> Result<HeightField> {
    crate::progress::step(&format!("loading {spec}"), || load_surface(spec, &load.options()))
        .with_context(|| format!("cannot load surface {spec}"))
}

fn level(hf: HeightField, how: &str) -> Result<HeightField> {
    Ok(prep::level_by_name(&hf, how)?)
}

/// Everything `info` reports, as JSON (keys fixed by the documentation): the facade's, which Python's
/// `Surface.info` returns too.
pub fn report(hf: &HeightField, n_peaks: usize, coherence_nm: f64) -> serde_json::Value {
    iridis_api::surface::info(hf, n_peaks, coherence_nm)
}

fn print_report(r: &serde_json::Value) -> Result<()> {
    let f = |k: &str, i: usize| r[k][i].as_f64().unwrap_or(f64::NAN);
    let g = |k: &str| r[k].as_f64().unwrap_or(f64::NAN);
    crate::outln!("surface      {} ({})", r["source"].as_str().unwrap_or(""), r["format"].as_str().unwrap_or(""))?;
    crate::outln!("samples      {} rows × {} columns", r["rows"], r["cols"])?;
    crate::outln!("pixel size   {:.4} × {:.4} nm (x × y)", f("pixel_size_nm", 0), f("pixel_size_nm", 1))?;
    crate::outln!("extent       {:.3} × {:.3} µm", f("extent_nm", 0) / 1000.0, f("extent_nm", 1) / 1000.0)?;
    crate::outln!(
        "height       min {:.2} nm, max {:.2} nm, mean {:.2} nm, rms {:.2} nm",
        g("height_min_nm"),
        g("height_max_nm"),
        g("mean_nm"),
        g("rms_nm")
    )?;
    let ro = &r["roughness"];
    crate::outln!(
        "roughness    Sq {:.3} nm, Sa {:.3} nm, Ssk {:.3}, Sku−3 {:.3}, Sz {:.2} nm (plane-levelled)",
        ro["sq_nm"].as_f64().unwrap_or(f64::NAN),
        ro["sa_nm"].as_f64().unwrap_or(f64::NAN),
        ro["skewness"].as_f64().unwrap_or(f64::NAN),
        ro["excess_kurtosis"].as_f64().unwrap_or(f64::NAN),
        ro["sz_nm"].as_f64().unwrap_or(f64::NAN)
    )?;
    match ro["correlation_length_nm"].as_f64() {
        Some(t) => {
            crate::outln!("corr. length τ = {t:.2} nm (radial ACF at 1/e; σ = Sq and τ are the rough-film model's)")?
        }
        None => crate::outln!(
            "corr. length none: the ACF does not fall to 1/e within half the patch (periodic or too small)"
        )?,
    }
    let peaks = r["peaks"].as_array().cloned().unwrap_or_default();
    if peaks.is_empty() {
        crate::outln!("periods      none found")?;
    } else {
        crate::outln!("periods      period (nm)          orientation   power (share of variance)")?;
        for p in peaks {
            let period = iridis_surface::analysis::with_uncertainty(
                p["period_nm"].as_f64().unwrap_or(f64::NAN),
                p["period_uncertainty_nm"].as_f64().unwrap_or(f64::NAN),
            );
            crate::outln!(
                "             {period:>18}   {:>9.2}°     {:.4}{}",
                p["orientation_deg"].as_f64().unwrap_or(f64::NAN),
                p["power"].as_f64().unwrap_or(f64::NAN),
                if p["read_off"] == "grid" { "   (read off the DFT grid)" } else { "" }
            )?;
        }
    }
    for n in r["notes"].as_array().into_iter().flatten() {
        crate::outln!("note         {}", n.as_str().unwrap_or(""))?;
    }
    for w in r["warnings"].as_array().into_iter().flatten() {
        eprintln!("warning: {}", w.as_str().unwrap_or(""));
    }
    Ok(())
}

/// Writes a shaded-relief preview framed by axes in µm, with a height colour bar and a scale bar.
pub fn write_preview(hf: &HeightField, path: &Path, title: &str) -> Result<()> {
    use iridis_plot::{magma, ColorBar, ImagePlot, RgbImage};
    let relief = shaded_relief(hf, 700, magma);
    let mut pixels = RgbImage::new(relief.width as u32, relief.height as u32);
    pixels.data.copy_from_slice(&relief.rgb);
    let (ex, ey) = hf.extent_nm();
    let (lo, hi) = hf.min_max();
    let aspect = ey / ex;
    let w = 900u32;
    let h = ((w as f64 - 200.0) * aspect + 140.0).clamp(300.0, 1400.0) as u32;
    let plot = ImagePlot {
        title: format!("{title}  (scale bar {})", format_length(relief.scale_bar_nm)),
        x_label: "x (µm)".into(),
        y_label: "y (µm)".into(),
        x_range: (0.0, ex / 1000.0),
        y_range: (0.0, ey / 1000.0),
        pixels: &pixels,
        overlays: Vec::new(),
        colorbar: Some(ColorBar { label: "height (nm)".into(), min: lo, max: hi.max(lo + 1e-9), map: magma }),
        size: (w, h),
    };
    let img = plot.render().map_err(|e| anyhow::anyhow!("{e}"))?;
    crate::output::write_png_rgb8(path, img.width, img.height, &img.data)
}

/// A centred 2-D function (PSDF or ACF) as a colour map with axes (`unit` scales the grid steps to the axis
/// unit) and a colour bar; `log` plots log10 of the positive values.
fn write_grid(
    g: &iridis_surface::stats::Grid2,
    path: &Path,
    title: &str,
    xl: &str,
    yl: &str,
    unit: f64,
    log: bool,
) -> Result<()> {
    use iridis_plot::{magma, ColorBar, ImagePlot, RgbImage};
    let v: Vec<f64> = if log {
        let floor = g.values.iter().copied().fold(0.0f64, f64::max) * 1e-12;
        g.values.iter().map(|x| x.max(floor).max(1e-300).log10()).collect()
    } else {
        g.values.clone()
    };
    let (lo, hi) = v.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| (a.min(x), b.max(x)));
    let span = if hi > lo { hi - lo } else { 1.0 };
    let mut pixels = RgbImage::new(g.cols as u32, g.rows as u32);
    for (i, x) in v.iter().enumerate() {
        pixels.data[3 * i..3 * i + 3].copy_from_slice(&magma((x - lo) / span));
    }
    let (hx, hy) = ((g.cols / 2) as f64 * g.dx * unit, (g.rows / 2) as f64 * g.dy * unit);
    let plot = ImagePlot {
        title: title.into(),
        x_label: xl.into(),
        y_label: yl.into(),
        x_range: (-hx, hx),
        y_range: (-hy, hy),
        pixels: &pixels,
        overlays: Vec::new(),
        colorbar: Some(ColorBar {
            label: if log { "log10".into() } else { "nm²".into() },
            min: lo,
            max: lo + span,
            map: magma,
        }),
        size: (800, 700),
    };
    let img = plot.render().map_err(|e| anyhow::anyhow!("{e}"))?;
    crate::output::write_png_rgb8(path, img.width, img.height, &img.data)
}

fn info(a: InfoArgs) -> Result<()> {
    use crate::progress::step;
    crate::output::declare_opt("--image", a.image.as_deref(), &["png"])?;
    crate::output::declare_opt("--psdf", a.psdf.as_deref(), &["png"])?;
    crate::output::declare_opt("--acf", a.acf.as_deref(), &["png"])?;
    let hf = level(load(&a.surface, &a.load)?, &a.level)?;
    let r = step("periods and roughness", || report(&hf, a.peaks, a.coherence));
    if let Some(p) = &a.image {
        step("shaded-relief preview", || write_preview(&hf, p, &a.surface))?;
    }
    let levelled = prep::level_plane(&hf);
    if let Some(p) = &a.psdf {
        let g = step("power spectral density", || iridis_surface::stats::psdf(&levelled));
        write_grid(&g, p, &format!("PSDF of {} (log10 nm⁴)", a.surface), "kx (µm⁻¹)", "ky (µm⁻¹)", 1000.0, true)?;
    }
    if let Some(p) = &a.acf {
        let g = step("autocorrelation", || iridis_surface::stats::acf(&levelled));
        write_grid(&g, p, &format!("ACF of {} (nm²)", a.surface), "τx (µm)", "τy (µm)", 1e-3, false)?;
    }
    if a.json {
        crate::output::print_json(&r)?;
        for w in r["warnings"].as_array().into_iter().flatten() {
            eprintln!("warning: {}", w.as_str().unwrap_or(""));
        }
        Ok(())
    } else {
        print_report(&r)?;
        if let Some(p) = &a.image {
            crate::outln!("preview      {}", p.display())?;
        }
        Ok(())
    }
}

fn channels(a: ChannelsArgs) -> Result<()> {
    let name = a.file.display().to_string();
    let meta = std::fs::metadata(&a.file).with_context(|| format!("cannot read {name}"))?;
    if meta.len() > formats::MAX_FILE_BYTES {
        bail!("{name} is {} MB, larger than any height-field file iridis reads", meta.len() >> 20);
    }
    let bytes = std::fs::read(&a.file).with_context(|| format!("cannot read {name}"))?;
    let list = formats::list_channels(&bytes, &name)?;
    let fmt = formats::detect_format(&bytes).map_or("?", Format::name);
    if a.json {
        let channels: Vec<serde_json::Value> = list
            .iter()
            .map(|c| {
                let mut v = json!(c);
                v["height"] = json!(c.is_height());
                v
            })
            .collect();
        return crate::output::print_json(&json!({ "file": name, "format": fmt, "channels": channels }));
    }
    crate::outln!("{name} ({fmt}): {} channel{}", list.len(), if list.len() == 1 { "" } else { "s" })?;
    crate::outln!("  index  name                           direction  size         unit")?;
    for c in &list {
        let unit = if c.z_unit.is_empty() { "?" } else { c.z_unit.as_str() };
        crate::outln!(
            "  {:>5}  {:<30} {:<10} {:<12} {}{}",
            c.index,
            if c.alias.is_empty() { c.name.clone() } else { format!("{} (or {})", c.name, c.alias) },
            if c.direction.is_empty() { "-" } else { c.direction.as_str() },
            format!("{}×{}", c.cols, c.rows),
            unit,
            if c.is_height() { "" } else { "  (not a height)" }
        )?;
    }
    let default = formats::channel::pick(&list, None).ok().map(|i| list[i].index);
    let heights = list.iter().filter(|c| c.is_height()).count();
    if list.len() > 1 {
        let are =
            if heights == 1 { "1 of them is a height".to_string() } else { format!("{heights} of them are heights") };
        crate::outln!(
            "{are}; without --channel, commands read channel {} (pick another with --channel NAME or --channel N; \
             --as-height reads one that is not a height)",
            default.map_or("?".to_string(), |i| i.to_string())
        )?;
    }
    Ok(())
}

/// The extensions `surface generate` and `surface convert` write (TIFF and instrument formats are read only).
const SURFACE_OUTPUTS: &[&str] = &["gwy", "gsf", "npy", "npz", "png", "txt"];

fn output_format(path: &Path) -> Result<Format> {
    crate::output::format_of("", path, SURFACE_OUTPUTS)?;
    Format::from_extension(path).with_context(|| format!("{}: unknown output format", path.display()))
}

/// Declares the outputs of a surface written to `path`: the file and, for formats without units, its sidecar.
fn declare_surface(flag: &str, path: &Path) -> Result<()> {
    crate::output::declare(flag, path, SURFACE_OUTPUTS)?;
    if matches!(output_format(path)?, Format::Npy | Format::Png | Format::Npz) {
        crate::output::declare("", &sidecar_path(path), &["json"])?;
    }
    Ok(())
}

/// Writes a field in the format its extension names, with a sidecar where the format has no units.
pub fn write_surface(hf: &HeightField, path: &Path) -> Result<()> {
    let fmt = output_format(path)?;
    let (bytes, side) = formats::write_bytes(hf, fmt)?;
    crate::output::write_bytes(path, &bytes)?;
    if let Some(s) = side {
        crate::output::write_bytes(&sidecar_path(path), s.as_bytes())?;
    }
    Ok(())
}

fn generate(a: GenerateArgs) -> Result<()> {
    if !KINDS.contains(&a.kind.as_str()) {
        bail!("unknown kind '{}'; kinds: {}", a.kind, KINDS.join(", "));
    }
    declare_surface("-o", &a.output)?;
    crate::output::declare_opt("--image", a.image.as_deref(), &["png"])?;
    let mut params = Vec::new();
    for (k, v) in [
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
    ] {
        if let Some(v) = v {
            params.push((k.to_string(), v.clone()));
        }
    }
    let (gen, grid) = builtin::from_params(&a.kind, &params, &Grid::default())
        .with_context(|| format!("bad parameters for {}", a.kind))?;
    let mut hf = gen.generate(&grid)?;
    hf.meta.source = format!("iridis surface generate {}", a.kind);
    write_surface(&hf, &a.output)?;
    if let Some(p) = &a.image {
        write_preview(&hf, p, &a.kind)?;
    }
    if a.json {
        crate::output::print_json(&report(&hf, 5, DEFAULT_COHERENCE_NM))?;
    } else {
        let (ex, ey) = hf.extent_nm();
        crate::outln!(
            "wrote {}: {} {}×{} samples, {:.3}×{:.3} µm at {} nm/pixel, rms {:.2} nm",
            a.output.display(),
            a.kind,
            hf.rows,
            hf.cols,
            ex / 1000.0,
            ey / 1000.0,
            hf.dx_nm,
            hf.rms()
        )?;
    }
    Ok(())
}

fn pair(s: &str, what: &str) -> Result<(usize, usize)> {
    let parts: Vec<&str> = s.split(['x', 'X', '×', ',']).map(str::trim).collect();
    match parts.as_slice() {
        [a, b] => match (a.parse(), b.parse()) {
            (Ok(a), Ok(b)) => Ok((a, b)),
            _ => bail!("--{what} '{s}': expected two whole numbers like 3x3"),
        },
        _ => bail!("--{what} '{s}': expected two whole numbers like 3x3"),
    }
}

fn convert(a: ConvertArgs) -> Result<()> {
    declare_surface("OUTPUT", &a.output)?;
    let mut hf = level(load(&a.input, &a.load)?, &a.level)?;
    if let Some(c) = &a.crop {
        let v: Vec<usize> = c
            .split(',')
            .map(|p| p.trim().parse::<usize>())
            .collect::<Result<_, _>>()
            .map_err(|_| anyhow::anyhow!("--crop '{c}': expected ROW,COL,ROWS,COLS (whole numbers)"))?;
        if v.len() != 4 {
            bail!("--crop '{c}': expected ROW,COL,ROWS,COLS (four whole numbers)");
        }
        hf = prep::crop(&hf, v[0], v[1], v[2], v[3])?;
    }
    if let Some(p) = a.resample {
        hf = prep::resample(&hf, p, p)?;
    }
    if let Some(t) = &a.tile {
        let (ny, nx) = pair(t, "tile")?;
        hf = prep::tile(&hf, ny, nx)?;
    }
    if let Some(p) = &a.pad {
        let (r, c) = pair(p, "pad")?;
        hf = prep::pad(&hf, r, c)?;
    }
    write_surface(&hf, &a.output)?;
    // What the reader warned about; the model's concerns (coherence area, coarse pixels) belong to the
    // commands that run the model.
    for w in &hf.meta.warnings {
        eprintln!("warning: {w}");
    }
    crate::outln!(
        "wrote {}: {}×{} samples at {:.4}×{:.4} nm/pixel",
        a.output.display(),
        hf.rows,
        hf.cols,
        hf.dx_nm,
        hf.dy_nm
    )?;
    Ok(())
}

/// The demo's surface section: previews of the built-in nanostructures with their analysed periods.
pub fn demo(g: &mut iridis_api::gallery::Gallery) -> Result<()> {
    g.section(
        "Nanostructures (height fields)",
        &format!(
            "The built-in surfaces, generated on the fly (65 µm at 65 nm per pixel, seed 1), shown as shaded \
             relief coloured by height, with the dominant periods found in their power spectra \
             (orientation: direction of the grating vector, counter-clockwise from +x). The paper reports \
             2500 nm for its blazed grating, 1144 nm for Elaphe and 1552 nm along Xenopeltis' fingers. {SURFACE_HELP}"
        ),
    );
    let mut rows = Vec::new();
    for name in iridis_surface::BUILTIN_NAMES {
        let spec = format!("builtin:{name}");
        let hf = load_surface(&spec, &LoadOptions::default())?;
        let peaks = find_peaks(&hf, &PeakOptions { max_peaks: 3, ..PeakOptions::default() });
        let file = format!("surface_{name}.png");
        write_preview(&hf, &g.path(&file), &spec)?;
        let listed = peaks
            .iter()
            .map(|p| format!("{} at {:.1}°", p.period_text(), p.orientation_deg))
            .collect::<Vec<_>>()
            .join(", ");
        g.image(
            &file,
            &format!("{spec}: rms {:.1} nm; periods {listed}. `iridis surface info {spec} --image {file}`", hf.rms()),
        );
        for p in &peaks {
            rows.push(vec![
                spec.clone(),
                iridis_surface::analysis::with_uncertainty(p.period_nm, p.period_uncertainty_nm),
                format!("{:.2}", p.orientation_deg),
                format!("{:.4}", p.power),
            ]);
        }
    }
    g.table(&["surface", "period (nm)", "orientation (°)", "power (share of variance)"], &rows);
    Ok(())
}
