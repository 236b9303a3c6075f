//! The soap-film colour chart (`iridis thinfilm chart`, Sussenbach Figure 5.11; Python's `iridis.film.chart`):
//! the colour of a stack against the thickness of one layer, as two bands (reflected over transmitted, or for a
//! rough substrate the specular `k_r` over the diffuse `π k_d`) with a labelled thickness axis; and the demo's
//! thin-film section, which draws it.

use std::fmt::Write as _;

use anyhow::{anyhow, bail, Result};
use iridis_color::spectrum::uniform_grid;
use iridis_color::units::{parse_length_nm, parse_range};
use iridis_color::{Illuminant, Observer, ToneMap, Xyz};
use iridis_plot::{ImagePlot, LinePlot, RgbImage, Series};
use iridis_thinfilm::color::{FilmColorimeter, Polarization};
use iridis_thinfilm::Stack;

use crate::film::{fmt_deg, parse_stack, spectra, stack_title, write_png};
use crate::gallery::Gallery;
use crate::report::Report;
use crate::rough::RoughOptions;

/// A rough substrate for the chart: the model's options and the light's direction.
#[derive(Debug, Clone, Copy)]
pub struct RoughLight {
    pub options: RoughOptions,
    /// Light polar angle θ_l (rad); `None`: the view angle.
    pub light: Option<f64>,
    /// Azimuth of the light relative to the viewer (rad).
    pub azimuth: f64,
}

/// The chart's colours and how they are shown.
#[derive(Debug, Clone)]
pub struct FilmChart {
    /// Thicknesses of the swept layer (nm).
    pub thickness_nm: Vec<f64>,
    /// (top, bottom) band XYZ per thickness: reflected and transmitted, or specular and diffuse.
    pub colours: Vec<(Xyz, Xyz)>,
    /// Exposure of the top band (RU); the bottom band is shown at 1 RU.
    pub exposure: f64,
    pub angle_rad: f64,
    pub illuminant: Illuminant,
    /// Title's stack part (with the roughness when rough).
    pub title: String,
    pub rough: bool,
}

/// Colours of a thickness sweep: (reflected, transmitted) XYZ per thickness.
pub fn sweep(
    stack: &Stack,
    layer: usize,
    thicknesses: &[f64],
    angle: f64,
    meter: &FilmColorimeter,
) -> Result<Vec<(Xyz, Xyz)>> {
    thicknesses
        .iter()
        .map(|&d| {
            let c = meter.color(&stack.with_thickness(layer, d), angle, Polarization::Average)?;
            Ok((c.reflected, c.transmitted))
        })
        .collect()
}

/// The chart of `stack` (one thickness written `{d}`) over `thickness` (`FROM:TO:STEP` with units) at
/// `angle_rad`; `exposure` (RU) fixes the top band's exposure, otherwise its brightest colour reaches full scale.
#[allow(clippy::too_many_arguments)]
pub fn chart(
    stack: &str,
    thickness: &str,
    angle_rad: f64,
    illuminant: &str,
    exposure: Option<f64>,
    grid: &[f64],
    rough: Option<RoughLight>,
    report: &dyn Report,
) -> Result<FilmChart> {
    crate::film::check_colour_grid(grid, crate::film::GridGiven::Range, report)?;
    let (parsed, layer) = Stack::parse_sweep(stack)?;
    let ds = parse_range(thickness, parse_length_nm).map_err(|e| anyhow!("--thickness: {e}"))?;
    if ds[0] < 0.0 {
        bail!("--thickness: thicknesses must not be negative (got {} nm)", ds[0]);
    }
    if ds.len() > 20_000 {
        bail!("--thickness gives {} thicknesses; at most 20000", ds.len());
    }
    let illuminant: Illuminant = illuminant.parse()?;
    let colours = match &rough {
        Some(r) => crate::rough::chart_colours(
            &parsed,
            layer,
            &ds,
            &r.options,
            crate::rough::Angles::new(angle_rad, r.light, r.azimuth),
            grid,
            illuminant,
            Observer::Cie1931,
        )?,
        None => sweep(&parsed, layer, &ds, angle_rad, &FilmColorimeter::new(grid, illuminant, Observer::Cie1931))?,
    };
    let exposure = match exposure {
        Some(e) if e.is_finite() && e > 0.0 => e,
        Some(e) => bail!("--exposure {e} must be a positive number (RU)"),
        None => {
            let ymax = colours.iter().map(|c| c.0.y).fold(0.0, f64::max);
            if ymax > 0.0 {
                1.0 / ymax
            } else {
                1.0
            }
        }
    };
    let title = match &rough {
        Some(r) => format!("{}, rough σ {} nm, τ {} nm", stack_title(stack), r.options.sigma_nm, r.options.tau_nm),
        None => stack_title(stack),
    };
    Ok(FilmChart { thickness_nm: ds, colours, exposure, angle_rad, illuminant, title, rough: rough.is_some() })
}

impl FilmChart {
    /// The bands' names, top and bottom.
    pub fn bands(&self) -> (&'static str, &'static str) {
        if self.rough {
            ("specular k_r", "diffuse π·k_d")
        } else {
            ("reflected", "transmitted")
        }
    }

    fn tones(&self) -> (ToneMap, ToneMap) {
        (ToneMap { exposure_ru: self.exposure, ..ToneMap::default() }, ToneMap::default())
    }

    /// The picture.
    pub fn image(&self) -> Result<RgbImage> {
        let (top, bottom) = self.bands();
        let (tone, trans_tone) = self.tones();
        chart_image(
            &self.title,
            top,
            bottom,
            &self.thickness_nm,
            &self.colours,
            &tone,
            &trans_tone,
            self.angle_rad,
            self.illuminant,
            self.exposure,
        )
    }

    /// What was drawn, after the file's name: `(N thicknesses, A–B nm; … at exposure E RU, … at 1 RU)`.
    pub fn summary(&self) -> String {
        let (top, bottom) = self.bands();
        let ds = &self.thickness_nm;
        format!(
            "({} thicknesses, {}–{} nm; {top} at exposure {:.3} RU, {bottom} at 1 RU)",
            ds.len(),
            ds[0],
            ds[ds.len() - 1],
            self.exposure
        )
    }

    /// The numbers: thickness_nm, then X, Y, Z, hex and the exposure (RU) the hex is shown at, of each band
    /// (R_/T_ columns, S_/D_ when rough). The exposure is in the file: the reflected band's is chosen from the
    /// chart's own range, so one film's hex differed between two charts with nothing in the file to say why.
    pub fn csv(&self) -> String {
        let [t, b] = if self.rough { ["S", "D"] } else { ["R", "T"] };
        let (tone, trans_tone) = self.tones();
        let mut csv = format!(
            "thickness_nm,{t}_X,{t}_Y,{t}_Z,{t}_hex,{t}_hex_exposure_RU,{b}_X,{b}_Y,{b}_Z,{b}_hex,{b}_hex_exposure_RU\n"
        );
        for (d, (r, t)) in self.thickness_nm.iter().zip(&self.colours) {
            let _ = writeln!(
                csv,
                "{d},{},{},{},{},{},{},{},{},{},{}",
                r.x,
                r.y,
                r.z,
                iridis_color::tonemap::hex(tone.to_rgb8(*r)),
                tone.exposure_ru,
                t.x,
                t.y,
                t.z,
                iridis_color::tonemap::hex(trans_tone.to_rgb8(*t)),
                trans_tone.exposure_ru
            );
        }
        csv
    }
}

/// The two bands (top: reflected or specular; bottom: transmitted or diffuse) over the thickness axis.
#[allow(clippy::too_many_arguments)]
fn chart_image(
    title: &str,
    top: &str,
    bottom: &str,
    ds: &[f64],
    cols: &[(Xyz, Xyz)],
    tone: &ToneMap,
    trans_tone: &ToneMap,
    angle: f64,
    illuminant: Illuminant,
    exposure: f64,
) -> Result<RgbImage> {
    let w = ds.len().max(2) as u32;
    let h = 100u32;
    let mut px = RgbImage::new(w, h);
    for x in 0..w {
        let k = (x as usize).min(cols.len() - 1);
        let (r, t) = (tone.to_rgb8(cols[k].0), trans_tone.to_rgb8(cols[k].1));
        for y in 0..h {
            // Top half: reflected or specular, bottom half: transmitted or diffuse; a thin white gap.
            let c = if y < h / 2 - 1 {
                r
            } else if y > h / 2 {
                t
            } else {
                [255, 255, 255]
            };
            px.put(x, y, c);
        }
    }
    let x_range = (ds[0], ds[ds.len() - 1].max(ds[0] + 1e-9));
    let img = ImagePlot {
        title: format!("Film colours: {title}  ({}°, {illuminant}, {top} ×{exposure:.2} RU)", fmt_deg(angle)),
        x_label: "thickness of the {d} layer (nm)".into(),
        y_label: format!("{bottom} | {top}"),
        x_range,
        y_range: (0.0, 1.0),
        pixels: &px,
        overlays: Vec::new(),
        colorbar: None,
        size: (1200, 360),
    }
    .render_without_y_ticks()?;
    Ok(img)
}

/// The exposure that brings the largest linear sRGB channel of a colour to 1 (shows its hue).
fn hue_exposure(xyz: Xyz) -> f64 {
    let m = xyz.to_linear_srgb().into_iter().fold(0.0, f64::max);
    if m > 0.0 {
        1.0 / m
    } else {
        1.0
    }
}

/// The demo's thin-film section: the soap-film chart, the oil-slick and coated-glass spectra and colours.
pub fn demo_section(g: &mut Gallery) -> Result<()> {
    g.section(
        "Thin-film interference",
        "Soap films, oil slicks and lens coatings colour light by interference between the reflections at their \
         interfaces. iridis-thinfilm evaluates the multilayer recurrence of Hirayama et al. (Sussenbach's thesis, \
         eq. 3.1–3.13; checked against the thesis' Figure 3.8 and the Python tmm package). The chart is the \
         soap-film colour chart of Sussenbach's Figure 5.11 (water n = 1.33 in air, normal incidence, D65).",
    );
    // Soap-film chart.
    let grid = uniform_grid(380.0, 780.0, 5.0).map_err(|e| anyhow!("{e}"))?;
    let soap = chart("air | water {d} | air", "0nm:2000nm:2nm", 0.0, "d65", None, &grid, None, &crate::report::Quiet)?;
    write_png(&g.path("thinfilm_soap_chart.png"), &soap.image()?)?;
    g.image(
        "thinfilm_soap_chart.png",
        "Soap-film colours, 0–2000 nm of water in air at normal incidence (Sussenbach Fig. 5.11): \
         iridis thinfilm chart --stack \"air | water {d} | air\" --thickness 0nm:2000nm:2nm",
    );
    // Spectra.
    let mut rows = Vec::new();
    let white = iridis_color::integrate::white_point(Illuminant::D65, Observer::Cie1931);
    for (file, text, what, angle_deg) in [
        (
            "thinfilm_oil_slick.png",
            "air | gasoline 216nm | water 220nm | asphalt",
            "oil slick (Sussenbach section 5.1)",
            1.0,
        ),
        ("thinfilm_soap_348nm.png", "air | water 348nm | air", "soap film 348 nm (Sussenbach Fig. 5.1)", 1.0),
        ("thinfilm_coated_glass.png", "air | MgF2 100nm | BK7", "MgF2 anti-reflection coating on BK7", 0.0),
        ("thinfilm_si_on_glass.png", "air | Si 108nm | glass", "Si 108 nm on glass (Sussenbach Fig. 5.7)", 1.0),
    ] {
        let stack = parse_stack(text)?;
        let angle = f64::to_radians(angle_deg);
        let wl = uniform_grid(400.0, 780.0, 2.0).map_err(|e| anyhow!("{e}"))?;
        let xs = spectra(&stack, angle, &wl)?;
        let r: Vec<f64> = xs.iter().map(|x| x.r()).collect();
        let t: Vec<f64> = xs.iter().map(|x| x.t()).collect();
        let ab: Vec<f64> = xs.iter().map(|x| x.a()).collect();
        let mut plot =
            LinePlot::new(format!("{what}: {text}, {angle_deg}°"), "wavelength (nm)", "fraction of incident power")
                .series(Series::new("R (reflectance)", &wl, &r));
        if text.contains("Si") {
            plot =
                plot.series(Series::new("T (transmittance)", &wl, &t)).series(Series::new("A (absorptance)", &wl, &ab));
        }
        plot.x_range = Some((400.0, 780.0));
        write_png(&g.path(file), &plot.render()?)?;
        g.image(
            file,
            &format!(
                "{what}: iridis thinfilm spectrum --stack \"{text}\" --angle {angle_deg}deg --from 400nm --plot {file}"
            ),
        );
        // Colours need 380–780 nm; Si's data end at 827 nm, everything here covers it.
        let c = FilmColorimeter::new(&grid, Illuminant::D65, Observer::Cie1931).color(
            &stack,
            angle,
            Polarization::Average,
        )?;
        let lab_r = iridis_color::Lab::from_xyz(c.reflected, white);
        let hex = |tone: ToneMap, xyz: Xyz| format!("swatch:{}", iridis_color::tonemap::hex(tone.to_rgb8(xyz)));
        rows.push(vec![
            text.to_string(),
            format!("{:.4}", c.reflected.y),
            format!("{:.1}, {:.1}, {:.1}", lab_r.l, lab_r.a, lab_r.b),
            hex(ToneMap::default(), c.reflected),
            hex(ToneMap { exposure_ru: hue_exposure(c.reflected), ..ToneMap::default() }, c.reflected),
            hex(ToneMap::default(), c.transmitted),
        ]);
    }
    g.table(
        &[
            "stack",
            "reflected Y",
            "reflected L*a*b*",
            "reflected sRGB (1 RU)",
            "reflected hue (brightest channel at 1)",
            "transmitted sRGB",
        ],
        &rows,
    );
    Ok(())
}
