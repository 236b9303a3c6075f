//! A colour as every front end reports it (the JSON "colour" shape of docs/json.md): XYZ, xyY, CIELAB against
//! the illuminant's white, linear and display sRGB, hex; the colour of a spectrum file and colour differences
//! (`iridis color xyz|delta-e`, Python's `iridis.color`); the demo's colour section.

use std::path::Path;

use anyhow::{bail, Result};
use iridis_color::integrate::{emission_to_xyz, reflectance_to_xyz, white_point};
use iridis_color::lab::DeltaEFormula;
use iridis_color::tonemap::hex;
use iridis_color::{Illuminant, Lab, Observer, Spectrum, ToneMap, Xyz};
use serde_json::json;

/// Everything a person wants to know about one colour, as JSON (keys fixed by docs/json.md, "Shape: colour").
pub fn colour_report(xyz: Xyz, white: Xyz) -> serde_json::Value {
    let xyy = xyz.to_xyy();
    let lab = Lab::from_xyz(xyz, white);
    let tone = ToneMap::default();
    let rgb8 = tone.to_rgb8(xyz);
    json!({
        "XYZ": xyz.to_array(),
        "xyY": [xyy.x, xyy.y, xyy.big_y],
        "Lab": lab.to_array(),
        "linear_srgb": xyz.to_linear_srgb(),
        "srgb": tone.to_display(xyz),
        "hex": hex(rgb8),
    })
}

/// The numbers of a colour report's array `key`, each with `digits` decimals, two spaces apart.
fn numbers(report: &serde_json::Value, key: &str, digits: usize) -> String {
    report[key]
        .as_array()
        .map(|v| {
            v.iter().map(|x| format!("{:.digits$}", x.as_f64().unwrap_or(f64::NAN))).collect::<Vec<_>>().join("  ")
        })
        .unwrap_or_default()
}

/// A colour report for people, as `thinfilm color` prints each colour: its name, then XYZ, L*a*b*, sRGB, hex.
pub fn colour_text(name: &str, report: &serde_json::Value) -> String {
    format!(
        "{name}\n  XYZ        {}\n  L*a*b*     {}\n  sRGB       {}   {}\n",
        numbers(report, "XYZ", 5),
        numbers(report, "Lab", 5),
        numbers(report, "srgb", 5),
        report["hex"].as_str().unwrap_or("")
    )
}

/// The colour of a spectrum file (`iridis color xyz`, Python's `iridis.color.xyz`).
#[derive(Debug, Clone)]
pub struct SpectrumColour {
    /// The file as named.
    pub name: String,
    pub range_nm: (f64, f64),
    pub samples: usize,
    pub illuminant: Illuminant,
    pub observer: Observer,
    pub emissive: bool,
    /// The values were percent, divided by 100 (`--percent`).
    pub percent: bool,
    /// The colour report (docs/json.md, "Shape: colour").
    pub report: serde_json::Value,
}

/// The warning for a spectrum `name` sampled over `lo`–`hi` nm that does not cover the visible 380–780 nm: its
/// colour holds its end values beyond (a reflectance known from 400 to 500 nm is then white if flat there).
pub fn short_range(name: &str, lo: f64, hi: f64) -> Option<String> {
    (lo > 380.0 || hi < 780.0).then(|| {
        format!("{name} covers {lo}–{hi} nm, less than the visible 380–780 nm; its end values are held beyond")
    })
}

/// The colour of the spectrum in `path` (two columns, wavelength in nm and value): a reflectance lit by
/// `illuminant` (Y = 1 a perfect white reflector) or, `emissive`, a light source at Y = 1. L*a*b* is relative to
/// the illuminant's white either way (for a light, the white it is judged against). A spectrum that does not
/// cover 380–780 nm is warned about.
pub fn xyz(
    path: &Path,
    illuminant: &str,
    observer: &str,
    emissive: bool,
    percent: bool,
    report: &dyn crate::Report,
) -> Result<SpectrumColour> {
    let illuminant: Illuminant = illuminant.parse()?;
    let observer: Observer = observer.parse()?;
    let mut spectrum = Spectrum::from_csv_path(path)?;
    if percent {
        if emissive {
            bail!("--percent reads a reflectance in percent; an --emissive spectrum's scale sets no colour: leave one out");
        }
        spectrum =
            Spectrum::new(spectrum.wavelengths_nm().to_vec(), spectrum.values().iter().map(|v| v / 100.0).collect())?;
    }
    let (lo, hi) = spectrum.range_nm();
    // A reflectance of 50 (%) read as 50 (5000 %) came out as L* 411 and a white sRGB, without a word.
    let peak = spectrum.values().iter().copied().fold(f64::NEG_INFINITY, f64::max);
    if !emissive && !percent && peak > iridis_vision::table::PERCENT_ABOVE {
        report.warn(&format!(
            "{} reaches {peak}, read as a reflectance of {:.0} %: if the values are percent, give --percent (Python: \
             percent=True)",
            path.display(),
            100.0 * peak
        ));
    }
    if let Some(w) = short_range(&path.display().to_string(), lo, hi) {
        report.warn(&w);
    }
    let xyz = if emissive {
        let xyz = emission_to_xyz(&spectrum, observer);
        if !(xyz.y.is_finite() && xyz.y > 0.0 && [xyz.x, xyz.z].iter().all(|v| v.is_finite())) {
            bail!(
                "{} as an --emissive light has no luminance to scale to Y = 1 (it is zero, or negative, over the \
                 observer's wavelengths): it has no colour",
                path.display()
            );
        }
        xyz
    } else {
        reflectance_to_xyz(&spectrum, illuminant, observer)
    };
    // Negative values (a baseline subtracted past zero) are used as they are, and said; a negative Y has no
    // lightness (L* = 903.3·Y/Yn came out at −903 without a word).
    if let Some(v) = spectrum.values().iter().copied().filter(|v| *v < 0.0).reduce(f64::min) {
        let y = if xyz.y < 0.0 {
            format!("; Y is then {:.4}, and its L* is not a lightness", xyz.y)
        } else {
            String::new()
        };
        report.warn(&format!("{} has negative values (down to {v}); they were used as they are{y}", path.display()));
    }
    let white = white_point(illuminant, observer);
    Ok(SpectrumColour {
        name: path.display().to_string(),
        range_nm: (lo, hi),
        samples: spectrum.values().len(),
        illuminant,
        observer,
        emissive,
        percent,
        report: colour_report(xyz, white),
    })
}

impl SpectrumColour {
    /// What `--json` prints: the colour report with what it rests on (the spectrum's range and samples, the
    /// light and observer, and what Y = 1 is), as the text says them.
    pub fn to_json(&self) -> serde_json::Value {
        let mut v = self.report.clone();
        if let Some(o) = v.as_object_mut() {
            o.insert("wavelength_range_nm".into(), serde_json::json!([self.range_nm.0, self.range_nm.1]));
            o.insert("samples".into(), self.samples.into());
            o.insert("illuminant".into(), self.illuminant.name().into());
            o.insert("observer".into(), self.observer.name().into());
            let y = if self.emissive {
                "emissive: the light scaled to Y = 1"
            } else {
                "reflectance under the illuminant: the perfect white diffuser has Y = 1"
            };
            o.insert("normalisation".into(), y.into());
        }
        v
    }

    /// The colour for people.
    pub fn text(&self) -> String {
        let r = &self.report;
        let (lo, hi) = self.range_nm;
        format!(
            "spectrum     {}  ({lo}–{hi} nm, {} samples)\nconditions   illuminant {}, CIE {} observer{}\n\
             XYZ          {}\nxyY          {}\nL*a*b*       {}\nlinear sRGB  {}\nsRGB         {}\nhex          {}\n",
            self.name,
            self.samples,
            self.illuminant,
            self.observer,
            match (self.emissive, self.percent) {
                (true, _) => ", emissive",
                (false, true) => ", reflectance in percent (divided by 100)",
                (false, false) => "",
            },
            numbers(r, "XYZ", 6),
            numbers(r, "xyY", 6),
            numbers(r, "Lab", 6),
            numbers(r, "linear_srgb", 6),
            numbers(r, "srgb", 6),
            r["hex"].as_str().unwrap_or("")
        )
    }
}

/// The colour conditions of a film's report, after its geometry: `illuminant D65, CIE 1931 observer, 380–780 nm`.
pub fn light_and_observer(illuminant: Illuminant, observer: Observer, (from_nm, to_nm): (f64, f64)) -> String {
    format!("illuminant {illuminant}, CIE {observer} observer, {from_nm}–{to_nm} nm")
}

/// An `L,a,b` triple (`which` names it in messages: first, second).
pub fn parse_lab(s: &str, which: &str) -> Result<Lab> {
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

/// The colour difference of two `L,a,b` texts by `formula` (`2000`/`ciede2000` or `1976`/`cie76`), as
/// `iridis color delta-e` computes it.
pub fn delta_e(first: &str, second: &str, formula: &str) -> Result<f64> {
    Ok(delta_e_answer(first, second, formula)?.value)
}

/// A colour difference with the formula behind it: what `iridis color delta-e` prints.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DeltaE {
    pub value: f64,
    pub formula: DeltaEFormula,
}

impl DeltaE {
    /// `2.0425 ΔE00 (CIEDE2000)`: the number with its unit.
    pub fn text(&self) -> String {
        format!("{:.4} {}", self.value, self.formula.label())
    }

    /// `{"delta_e": …, "formula": "2000" | "1976"}` (docs/json.md).
    pub fn to_json(&self) -> serde_json::Value {
        serde_json::json!({ "delta_e": self.value, "formula": self.formula.name() })
    }
}

/// [`delta_e`] with its formula, for printing.
pub fn delta_e_answer(first: &str, second: &str, formula: &str) -> Result<DeltaE> {
    let p = parse_lab(first, "first")?;
    let q = parse_lab(second, "second")?;
    let formula: DeltaEFormula = formula.parse().map_err(anyhow::Error::msg)?;
    Ok(DeltaE { value: formula.delta_e_checked(p, q).map_err(anyhow::Error::msg)?, formula })
}

/// The demo's colour section: the CIE 1931 chromaticity diagram and the colours of the built-in illuminants.
pub fn demo_section(g: &mut crate::gallery::Gallery) -> Result<()> {
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
