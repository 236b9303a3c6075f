//! `iridis color …`: spectra to colours, colour differences.

use std::path::PathBuf;

use anyhow::{bail, Result};
use clap::{Args as ClapArgs, Subcommand};
use iridis_color::integrate::{emission_to_xyz, reflectance_to_xyz, white_point};
use iridis_color::lab::{delta_e_1976, delta_e_2000};
use iridis_color::tonemap::hex;
use iridis_color::{Illuminant, Lab, Observer, Spectrum, ToneMap, Xyz};
use serde_json::json;

#[derive(Debug, Subcommand)]
pub enum ColorCommand {
    /// The colour of a spectrum: XYZ, xyY, CIELAB, linear and encoded sRGB, hex.
    #[command(after_help = "\
The spectrum file has two columns, wavelength in nm and value, separated by commas, semicolons, tabs or
spaces; a header line and lines starting with # are allowed. By default the values are a reflectance (or
transmittance) lit by the illuminant and Y = 1 is a perfect white reflector; with --emissive the spectrum is
a light source and its colour is reported at Y = 1. CIELAB is relative to the illuminant's white.

Examples:
  iridis color xyz data/examples/colorchecker_green.csv
  iridis color xyz data/examples/colorchecker_green.csv --illuminant d50 --observer 1964 --json
  iridis color xyz data/cie/d65.csv --emissive")]
    Xyz(XyzArgs),
    /// Colour difference between two CIELAB colours.
    #[command(after_help = "\
Examples:
  iridis color delta-e 50,2.6772,-79.7751 50,0,-82.7485          # CIEDE2000: 2.0425
  iridis color delta-e 50,2.6772,-79.7751 50,0,-82.7485 --formula 1976 --json")]
    DeltaE(DeltaEArgs),
}

#[derive(Debug, ClapArgs)]
pub struct XyzArgs {
    /// Spectrum file (CSV: wavelength_nm, value).
    pub spectrum: PathBuf,
    /// Illuminant: d65, d50, a or e.
    #[arg(long, default_value = "d65")]
    pub illuminant: String,
    /// Standard observer: 1931 (2°) or 1964 (10°).
    #[arg(long, default_value = "1931")]
    pub observer: String,
    /// The spectrum is a light source, not a reflectance.
    #[arg(long)]
    pub emissive: bool,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
}

#[derive(Debug, ClapArgs)]
pub struct DeltaEArgs {
    /// First colour as L,a,b.
    #[arg(allow_hyphen_values = true)]
    pub first: String,
    /// Second colour as L,a,b.
    #[arg(allow_hyphen_values = true)]
    pub second: String,
    /// 2000 (CIEDE2000) or 1976 (ΔE*ab).
    #[arg(long, default_value = "2000")]
    pub formula: String,
    /// Print JSON.
    #[arg(long)]
    pub json: bool,
}

pub fn run(command: ColorCommand) -> Result<()> {
    match command {
        ColorCommand::Xyz(a) => xyz(a),
        ColorCommand::DeltaE(a) => delta_e(a),
    }
}

pub use iridis_api::color::colour_report;

fn xyz(a: XyzArgs) -> Result<()> {
    let illuminant: Illuminant = a.illuminant.parse()?;
    let observer: Observer = a.observer.parse()?;
    let spectrum = Spectrum::from_csv_path(&a.spectrum)?;
    let (lo, hi) = spectrum.range_nm();
    if lo > 380.0 || hi < 780.0 {
        eprintln!(
            "warning: {} covers {lo}–{hi} nm, less than the visible 380–780 nm; its end values are held beyond",
            a.spectrum.display()
        );
    }
    let (xyz, white) = if a.emissive {
        (emission_to_xyz(&spectrum, observer), white_point(Illuminant::D65, observer))
    } else {
        (reflectance_to_xyz(&spectrum, illuminant, observer), white_point(illuminant, observer))
    };
    let report = colour_report(xyz, white);
    if a.json {
        return crate::output::print_json(&report);
    }
    let f = |k: &str| -> String {
        report[k]
            .as_array()
            .map(|v| v.iter().map(|x| format!("{:.6}", x.as_f64().unwrap_or(f64::NAN))).collect::<Vec<_>>().join("  "))
            .unwrap_or_default()
    };
    crate::outln!("spectrum     {}  ({lo}–{hi} nm, {} samples)", a.spectrum.display(), spectrum.values().len())?;
    crate::outln!(
        "conditions   illuminant {illuminant}, CIE {observer} observer{}",
        if a.emissive { ", emissive" } else { "" }
    )?;
    crate::outln!("XYZ          {}", f("XYZ"))?;
    crate::outln!("xyY          {}", f("xyY"))?;
    crate::outln!("L*a*b*       {}", f("Lab"))?;
    crate::outln!("linear sRGB  {}", f("linear_srgb"))?;
    crate::outln!("sRGB         {}", f("srgb"))?;
    crate::outln!("hex          {}", report["hex"].as_str().unwrap_or(""))?;
    Ok(())
}

fn parse_lab(s: &str, which: &str) -> Result<Lab> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    if parts.len() != 3 {
        bail!("{which} colour '{s}' is not an L,a,b triple (three numbers separated by commas, e.g. 50,2.5,-80)");
    }
    let mut v = [0.0; 3];
    for (i, p) in parts.iter().enumerate() {
        v[i] = match p.parse::<f64>() {
            Ok(x) if x.is_finite() => x,
            _ => bail!("{which} colour '{s}': component {} ('{p}') is not a finite number", i + 1),
        };
    }
    Ok(Lab::new(v[0], v[1], v[2]))
}

fn delta_e(a: DeltaEArgs) -> Result<()> {
    let p = parse_lab(&a.first, "first")?;
    let q = parse_lab(&a.second, "second")?;
    let d = match a.formula.trim() {
        "2000" | "ciede2000" => delta_e_2000(p, q),
        "1976" | "cie76" => delta_e_1976(p, q),
        other => bail!("unknown formula '{other}'; expected 2000 or 1976"),
    };
    if a.json {
        crate::output::print_json(&json!({ "delta_e": d, "formula": a.formula.trim() }))
    } else {
        crate::outln!("{d:.4}")?;
        Ok(())
    }
}

/// The demo's colour section: the CIE 1931 chromaticity diagram and the colours of the built-in illuminants.
pub fn demo(g: &mut iridis_api::gallery::Gallery) -> Result<()> {
    use iridis_color::integrate::white_point;
    use iridis_plot::{ImagePlot, RgbImage, Series};

    g.section(
        "Colour science",
        "Every result in iridis ends in the same pipeline: spectrum → CIE XYZ (trapezoid rule, perfect white \
         reflector Y = 1) → linear sRGB (IEC 61966-2-1) or CIELAB → display. Below: the CIE 1931 spectral \
         locus with the sRGB gamut and the white points of the built-in illuminants.",
    );
    let cmfs = Observer::Cie1931.cmfs();
    let locus: Vec<(f64, f64)> = cmfs
        .wavelengths_nm
        .iter()
        .enumerate()
        .filter(|(_, &w)| w <= 700.0)
        .map(|(i, _)| {
            let s = cmfs.x[i] + cmfs.y[i] + cmfs.z[i];
            (cmfs.x[i] / s, cmfs.y[i] / s)
        })
        .collect();
    let (w, h) = (640u32, 720u32);
    let (xr, yr) = ((0.0, 0.8), (0.0, 0.9));
    let mut pixels = RgbImage::new(w, h);
    for py in 0..h {
        for px in 0..w {
            let x = xr.0 + (px as f64 + 0.5) / w as f64 * (xr.1 - xr.0);
            let y = yr.1 - (py as f64 + 0.5) / h as f64 * (yr.1 - yr.0);
            let c = if inside(&locus, (x, y)) {
                // Brightest displayable colour of this chromaticity.
                let rgb = iridis_color::Xyy { x, y, big_y: 1.0 }.to_xyz().to_linear_srgb().map(|v| v.max(0.0));
                let m = rgb.iter().cloned().fold(1e-12, f64::max);
                rgb.map(|v| (iridis_color::convert::srgb_encode(v / m) * 255.0).round() as u8)
            } else {
                [255, 255, 255]
            };
            pixels.put(px, py, c);
        }
    }
    let mut closed = locus.clone();
    closed.push(locus[0]);
    let srgb: Vec<(f64, f64)> = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]]
        .iter()
        .map(|&c| {
            let v = Xyz::from_linear_srgb(c).to_xyy();
            (v.x, v.y)
        })
        .collect();
    let mut overlays = vec![
        Series::new("spectral locus 360–700 nm", &[], &[]).with_color([60, 60, 60]),
        Series::new("sRGB gamut", &[], &[]).with_color([0, 0, 0]),
    ];
    overlays[0].points = closed;
    overlays[1].points = srgb;
    let marker_colors = [[213, 94, 0], [0, 114, 178], [0, 158, 115], [204, 121, 167]];
    let mut rows = Vec::new();
    for (k, ill) in Illuminant::ALL.into_iter().enumerate() {
        let wp = white_point(ill, Observer::Cie1931);
        let v = wp.to_xyy();
        let r = 0.006;
        overlays.push(Series {
            name: format!("white of {ill}"),
            points: (0..=16)
                .map(|k| {
                    let t = k as f64 / 16.0 * std::f64::consts::TAU;
                    (v.x + r * t.cos(), v.y + r * t.sin())
                })
                .collect(),
            emphasis: true,
            color: Some(marker_colors[k]),
            dashed: false,
        });
        let rgb8 = ToneMap::default().to_rgb8(wp);
        rows.push(vec![
            ill.name().to_string(),
            format!("{:.5}, {:.5}, {:.5}", wp.x, wp.y, wp.z),
            format!("{:.5}, {:.5}", v.x, v.y),
            format!("swatch:{}", hex(rgb8)),
        ]);
    }
    let plot = ImagePlot {
        title: "CIE 1931 chromaticity diagram".into(),
        x_label: "x".into(),
        y_label: "y".into(),
        x_range: xr,
        y_range: yr,
        pixels: &pixels,
        overlays,
        colorbar: None,
        size: (760, 820),
    }
    .render()?;
    crate::output::write_png_rgb8(&g.path("cie1931_locus.png"), plot.width, plot.height, &plot.data)?;
    g.image("cie1931_locus.png", "CIE 1931 spectral locus, sRGB gamut and illuminant white points");
    g.table(&["illuminant", "XYZ (Y = 1)", "xy", "sRGB (no adaptation)"], &rows);
    Ok(())
}

/// Point in polygon (even–odd rule).
fn inside(poly: &[(f64, f64)], p: (f64, f64)) -> bool {
    let mut c = false;
    let n = poly.len();
    for i in 0..n {
        let (a, b) = (poly[i], poly[(i + n - 1) % n]);
        if (a.1 > p.1) != (b.1 > p.1) && p.0 < (b.0 - a.0) * (p.1 - a.1) / (b.1 - a.1) + a.0 {
            c = !c;
        }
    }
    c
}
