//! What `iridis surface info|channels|generate|convert` and Python's `iridis.surface` compute: a height field's
//! report (sizes, heights, roughness, periods) as JSON and as the text table the command prints, its figures
//! (shaded relief, 2-D PSDF and ACF), a file's channel list, generated nanostructures, format conversion with
//! levelling, cropping, resampling, tiling and padding, and the demo's surface section.

use std::fmt::Write as _;
use std::path::Path;

use anyhow::{bail, Context, Result};
use iridis_surface::formats::{self, sidecar_path, Format};
use iridis_surface::generate::Grid;
use iridis_surface::render::{format_length, shaded_relief};
use iridis_surface::{builtin, prep, HeightField, LoadOptions};
use serde_json::{json, Value};

use crate::report::{with_step, Report};

/// How SURFACE arguments are read and what the built-ins are (`iridis surface --help`, the demo).
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

/// Loads a SURFACE argument as it is (no levelling), with a step for the report.
pub fn load(spec: &str, options: &LoadOptions, report: &dyn Report) -> Result<HeightField> {
    with_step(report, &format!("loading {spec}"), || iridis_surface::load_surface(spec, options))
        .with_context(|| format!("cannot load surface {spec}"))
}

/// Levels by name (none, mean, plane, poly, lines, rows).
pub fn level(hf: HeightField, how: &str) -> Result<HeightField> {
    Ok(prep::level_by_name(&hf, how)?)
}

/// The figures `surface info` can draw besides its numbers.
#[derive(Debug, Clone, Copy, Default)]
pub struct InfoFigures<'a> {
    /// Shaded relief with axes, scale bar and a height colour bar.
    pub image: Option<&'a Path>,
    /// The 2-D power spectral density of the plane-levelled field (log scale).
    pub psdf: Option<&'a Path>,
    /// The 2-D autocorrelation of the plane-levelled field.
    pub acf: Option<&'a Path>,
}

/// `surface info`: the report of [`crate::surface::info`] (keys in docs/json.md), writing the figures asked for
/// (titled with `name`) through the run's output set.
pub fn info_with_figures(
    hf: &HeightField,
    name: &str,
    n_peaks: usize,
    coherence_nm: f64,
    figures: InfoFigures<'_>,
    report: &dyn Report,
) -> Result<Value> {
    let r = with_step(report, "periods and roughness", || crate::surface::info(hf, n_peaks, coherence_nm));
    write_figures(hf, name, figures, report)?;
    Ok(r)
}

/// Writes `surface info`'s figures of `hf` (titled with `name`) through the run's output set.
pub fn write_figures(hf: &HeightField, name: &str, figures: InfoFigures<'_>, report: &dyn Report) -> Result<()> {
    if let Some(p) = figures.image {
        with_step(report, "shaded-relief preview", || write_preview(hf, p, name))?;
    }
    let levelled = prep::level_plane(hf);
    if let Some(p) = figures.psdf {
        let g = with_step(report, "power spectral density", || iridis_surface::stats::psdf(&levelled));
        write_grid(&g, p, &format!("PSDF of {name} (log10 nm⁴)"), "kx (µm⁻¹)", "ky (µm⁻¹)", 1000.0, true)?;
    }
    if let Some(p) = figures.acf {
        let g = with_step(report, "autocorrelation", || iridis_surface::stats::acf(&levelled));
        write_grid(&g, p, &format!("ACF of {name} (nm²)"), "τx (µm)", "τy (µm)", 1e-3, false)?;
    }
    Ok(())
}

/// The text `iridis surface info` prints for a report of [`crate::surface::info`] (warnings apart: they are
/// the report's `"warnings"`).
pub fn info_text(r: &Value) -> String {
    let f = |k: &str, i: usize| r[k][i].as_f64().unwrap_or(f64::NAN);
    let g = |k: &str| r[k].as_f64().unwrap_or(f64::NAN);
    let mut s = String::new();
    let _ = writeln!(s, "surface      {} ({})", r["source"].as_str().unwrap_or(""), r["format"].as_str().unwrap_or(""));
    let _ = writeln!(s, "samples      {} rows × {} columns", r["rows"], r["cols"]);
    let _ = writeln!(s, "pixel size   {:.4} × {:.4} nm (x × y)", f("pixel_size_nm", 0), f("pixel_size_nm", 1));
    let _ = writeln!(s, "extent       {:.3} × {:.3} µm", f("extent_nm", 0) / 1000.0, f("extent_nm", 1) / 1000.0);
    let _ = writeln!(
        s,
        "height       min {:.2} nm, max {:.2} nm, mean {:.2} nm, rms {:.2} nm",
        g("height_min_nm"),
        g("height_max_nm"),
        g("mean_nm"),
        g("rms_nm")
    );
    let ro = &r["roughness"];
    let q = |k: &str| ro[k].as_f64().unwrap_or(f64::NAN);
    let _ = writeln!(
        s,
        "roughness    Sq {:.3} nm, Sa {:.3} nm, Ssk {:.3}, Sku−3 {:.3}, Sz {:.2} nm (plane-levelled)",
        q("sq_nm"),
        q("sa_nm"),
        q("skewness"),
        q("excess_kurtosis"),
        q("sz_nm")
    );
    match ro["correlation_length_nm"].as_f64() {
        Some(t) => {
            let _ =
                writeln!(s, "corr. length τ = {t:.2} nm (radial ACF at 1/e; σ = Sq and τ are the rough-film model's)");
        }
        None => {
            s += "corr. length none: the ACF does not fall to 1/e within half the patch (periodic or too small)\n";
        }
    }
    let peaks = r["peaks"].as_array().cloned().unwrap_or_default();
    if r["peaks_asked"] == 0 {
        s += "periods      not looked for (--peaks 0)\n";
    } else if peaks.is_empty() {
        s += "periods      none found\n";
    } else {
        s += "periods      period (nm)          orientation   power (share of variance)\n";
        for p in peaks {
            let period = iridis_surface::analysis::with_uncertainty(
                p["period_nm"].as_f64().unwrap_or(f64::NAN),
                p["period_uncertainty_nm"].as_f64().unwrap_or(f64::NAN),
            );
            let _ = writeln!(
                s,
                "             {period:>18}   {:>9.2}°     {:.4}{}",
                p["orientation_deg"].as_f64().unwrap_or(f64::NAN),
                p["power"].as_f64().unwrap_or(f64::NAN),
                if p["read_off"] == "grid" { "   (read off the DFT grid)" } else { "" }
            );
        }
        s += "             (± the peak's resolution on the spectrum, not an accuracy: the window and neighbouring \
              peaks can shift it more)\n";
    }
    for n in r["notes"].as_array().into_iter().flatten() {
        let _ = writeln!(s, "note         {}", n.as_str().unwrap_or(""));
    }
    s
}

/// The report's warnings (`"warnings"` of [`crate::surface::info`]).
pub fn info_warnings(r: &Value) -> Vec<String> {
    r["warnings"].as_array().into_iter().flatten().map(|w| w.as_str().unwrap_or("").to_string()).collect()
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

// ---------------------------------------------------------------------------------------------------------
// channels

/// The channels of an instrument file (`iridis surface channels`).
#[derive(Debug)]
pub struct Channels {
    pub file: String,
    pub format: &'static str,
    pub list: Vec<formats::channel::ChannelInfo>,
}

/// Reads the channel list of `path`.
pub fn channels(path: &Path) -> Result<Channels> {
    let name = path.display().to_string();
    let meta = std::fs::metadata(path).with_context(|| format!("cannot read {name}"))?;
    if meta.len() > formats::MAX_FILE_BYTES {
        bail!("{name} is {} MB, larger than any height-field file iridis reads", meta.len() >> 20);
    }
    let bytes = std::fs::read(path).with_context(|| format!("cannot read {name}"))?;
    let list = formats::list_channels(&bytes, &name)?;
    let format = formats::detect_format(&bytes).map_or("?", Format::name);
    Ok(Channels { file: name, format, list })
}

impl Channels {
    /// As `iridis surface channels --json` prints it.
    pub fn to_json(&self) -> Value {
        let channels: Vec<Value> = self
            .list
            .iter()
            .map(|c| {
                let mut v = json!(c);
                v["height"] = json!(c.is_height());
                v
            })
            .collect();
        json!({ "file": self.file, "format": self.format, "channels": channels })
    }

    /// The table `iridis surface channels` prints.
    pub fn text(&self) -> String {
        let list = &self.list;
        let mut s = String::new();
        let _ = writeln!(
            s,
            "{} ({}): {} channel{}",
            self.file,
            self.format,
            list.len(),
            if list.len() == 1 { "" } else { "s" }
        );
        s += "  index  name                           direction  size         unit\n";
        for c in list {
            let unit = if c.z_unit.is_empty() { "?" } else { c.z_unit.as_str() };
            let _ = writeln!(
                s,
                "  {:>5}  {:<30} {:<10} {:<12} {}{}",
                c.index,
                if c.alias.is_empty() { c.name.clone() } else { format!("{} (or {})", c.name, c.alias) },
                if c.direction.is_empty() { "-" } else { c.direction.as_str() },
                format!("{}×{}", c.cols, c.rows),
                unit,
                if c.is_height() { "" } else { "  (not a height)" }
            );
        }
        let default = formats::channel::pick(list, None).ok().map(|i| list[i].index);
        let heights = list.iter().filter(|c| c.is_height()).count();
        if list.len() > 1 {
            let are = if heights == 1 {
                "1 of them is a height".to_string()
            } else {
                format!("{heights} of them are heights")
            };
            let _ = writeln!(
                s,
                "{are}; without --channel, commands read channel {} (pick another with --channel NAME or --channel N; \
                 --as-height reads one that is not a height)",
                default.map_or("?".to_string(), |i| i.to_string())
            );
        }
        s
    }
}

// ---------------------------------------------------------------------------------------------------------
// generate, convert, write

/// The extensions `surface generate` and `surface convert` write (TIFF and instrument formats are read only).
pub const SURFACE_OUTPUTS: &[&str] = &["gwy", "gsf", "npy", "npz", "png", "txt"];

fn output_format(path: &Path) -> Result<Format> {
    crate::output::format_of("", path, SURFACE_OUTPUTS)?;
    Format::from_extension(path).with_context(|| format!("{}: unknown output format", path.display()))
}

/// Declares the outputs of a surface written to `path`: the file and, for formats without units, its sidecar.
pub fn declare_surface(flag: &str, path: &Path) -> Result<()> {
    crate::output::declare(flag, path, SURFACE_OUTPUTS)?;
    if matches!(output_format(path)?, Format::Npy | Format::Png | Format::Npz) {
        crate::output::declare("", &sidecar_path(path), &["json"])?;
    }
    Ok(())
}

/// [`declare_surface`] for `iridis surface convert INPUT OUTPUT`, refusing an OUTPUT that is INPUT itself (or its
/// sidecar): the rename over it replaced the scan — its other channels and metadata, or its raw heights by levelled
/// ones — without a word.
pub fn declare_conversion(input: &str, output: &Path) -> Result<()> {
    let same = |a: &Path, b: &Path| match (a.canonicalize(), b.canonicalize()) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    };
    let input_path = Path::new(input);
    let sidecars = [output.to_path_buf(), sidecar_path(output)];
    if input_path.exists() && sidecars.iter().any(|o| same(input_path, o) || same(&sidecar_path(input_path), o)) {
        bail!(
            "OUTPUT {} would overwrite the scan being read ({input}), losing what the conversion leaves out (other \
             channels, metadata, the heights before levelling): write to another file",
            output.display()
        );
    }
    declare_surface("OUTPUT", output)
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

/// Refuses a kind `surface generate` does not know, listing those it does.
pub fn check_kind(kind: &str) -> Result<()> {
    if !builtin::KINDS.contains(&kind) {
        bail!("unknown kind '{kind}'; kinds: {}", builtin::KINDS.join(", "));
    }
    Ok(())
}

/// A built-in nanostructure of `kind` with its parameters (`("period", "1100nm")`, …; `iridis surface generate
/// --help` lists them), its source naming the command that makes it.
pub fn generate(kind: &str, params: &[(String, String)]) -> Result<HeightField> {
    check_kind(kind)?;
    let (gen, grid) =
        builtin::from_params(kind, params, &Grid::default()).with_context(|| format!("bad parameters for {kind}"))?;
    let mut hf = gen.generate(&grid)?;
    hf.meta.source = format!("iridis surface generate {kind}");
    Ok(hf)
}

/// The line `iridis surface generate` prints about the field it wrote.
pub fn generated_text(hf: &HeightField, kind: &str, path: &Path) -> String {
    let (ex, ey) = hf.extent_nm();
    format!(
        "wrote {}: {} {} × {} samples (x × y), {:.3} × {:.3} µm at {} nm/pixel, rms {:.2} nm\n",
        path.display(),
        kind,
        hf.cols,
        hf.rows,
        ex / 1000.0,
        ey / 1000.0,
        hf.dx_nm,
        hf.rms()
    )
}

/// The steps of `surface convert` after levelling, in this order: crop (`ROW,COL,ROWS,COLS`), resample (a
/// pixel size in nm), tile (`NYxNX`), pad (`ROWSxCOLS`) (with the feature `cli`, its flags).
#[derive(Debug, Clone, Default)]
#[cfg_attr(feature = "cli", derive(clap::Args))]
pub struct Reshape {
    /// Crop to ROW,COL,ROWS,COLS (samples).
    #[cfg_attr(feature = "cli", arg(long))]
    pub crop: Option<String>,
    /// Resample to this pixel size (e.g. 50nm), keeping the extent.
    #[cfg_attr(feature = "cli", arg(long = "resample", value_name = "RESAMPLE"))]
    #[cfg_attr(feature = "cli", arg(value_parser = crate::args::positive_length_nm))]
    pub resample_nm: Option<f64>,
    /// Tile NYxNX times (e.g. 3x3).
    #[cfg_attr(feature = "cli", arg(long))]
    pub tile: Option<String>,
    /// Pad with the mean height to ROWSxCOLS samples (centred).
    #[cfg_attr(feature = "cli", arg(long))]
    pub pad: Option<String>,
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

impl Reshape {
    /// Applies the steps to `hf`.
    pub fn apply(&self, mut hf: HeightField) -> Result<HeightField> {
        if let Some(c) = &self.crop {
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
        if let Some(p) = self.resample_nm {
            hf = prep::resample(&hf, p, p)?;
        }
        if let Some(t) = &self.tile {
            let (ny, nx) = pair(t, "tile")?;
            hf = prep::tile(&hf, ny, nx)?;
        }
        if let Some(p) = &self.pad {
            let (r, c) = pair(p, "pad")?;
            hf = prep::pad(&hf, r, c)?;
        }
        Ok(hf)
    }
}

/// The line `iridis surface convert` prints about the field it wrote.
pub fn converted_text(hf: &HeightField, path: &Path) -> String {
    // x before y throughout, as `surface channels`, `info` and the report give sizes (this printed rows × cols
    // beside dx × dy: "48×64 samples at 100×80 nm").
    format!(
        "wrote {}: {} × {} samples (x × y) at {:.4} × {:.4} nm/pixel (x × y)\n",
        path.display(),
        hf.cols,
        hf.rows,
        hf.dx_nm,
        hf.dy_nm
    )
}

// ---------------------------------------------------------------------------------------------------------
// demo

/// The demo's surface section: previews of the built-in nanostructures with their analysed periods.
pub fn demo_section(g: &mut crate::gallery::Gallery) -> Result<()> {
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
        let hf = iridis_surface::load_surface(&spec, &LoadOptions::default())?;
        let peaks = iridis_surface::find_peaks(
            &hf,
            &iridis_surface::PeakOptions { max_peaks: 3, ..iridis_surface::PeakOptions::default() },
        );
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
