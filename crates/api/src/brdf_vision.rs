//! `iridis brdf vision` (and Python's `iridis.diffraction.brdf_vision`): how an animal sees a nanostructure
//! from several directions of a plane ([`crate::vision::along_plane`]) as the command's table, and the views'
//! false colours as a strip.

use std::path::Path;

use anyhow::Result;

use iridis_diffraction::Shading;

use crate::report::Report;
use crate::surface::Source;
use crate::vision::{DirectionalVision, PlaneViews};
use crate::{ModelOptions, SurfaceOptions};

/// The analysis of [`crate::vision::along_plane`] (views in degrees, signed, in the plane of incidence), its
/// strip written to `strip` (PNG, declared first) and its notes passed to `report`.
pub fn brdf_vision(
    source: &Source,
    surface: &SurfaceOptions,
    model: &ModelOptions,
    shading: Shading,
    plane: PlaneViews<'_>,
    strip: Option<&Path>,
    report: &dyn Report,
) -> Result<DirectionalVision> {
    crate::output::declare_opt("--strip", strip, &["png"])?;
    let v = crate::vision::along_plane(source, surface, model, shading, plane, report)?;
    if let Some(path) = strip {
        let img = vision_strip(&v)?;
        crate::output::write_png_rgb8(path, img.width, img.height, &img.data)?;
    }
    for n in &v.analysis.notes {
        report.note(n);
    }
    Ok(v)
}

/// `brdf vision`'s table: each view's relative catches and ΔS to the mirror direction and to the previous view.
pub fn vision_text(v: &DirectionalVision) -> String {
    let an = &v.analysis;
    let mut t = vec![format!(
        "{} · seen by {} under {} · light θ {:.1}° in the plane of azimuth {:.1}° · π f_r(λ){}, 300–700 nm",
        v.surface,
        an.visual.name,
        an.illuminant,
        v.light_theta.to_degrees(),
        v.azimuth.to_degrees(),
        if v.energy_normalised { " of energy-normalised lobes" } else { "" }
    )];
    let mirror = v
        .views
        .iter()
        .min_by(|x, y| (x.1 - v.light_theta.to_degrees()).abs().total_cmp(&(y.1 - v.light_theta.to_degrees()).abs()))
        .map(|x| x.0.clone())
        .unwrap_or_default();
    let jnd = |d: Option<f64>| d.map_or("—".to_string(), |x| format!("{x:.2}"));
    let (light, noise) = crate::vision::conditions(an);
    t.push(format!("  light  {light}\n  noise  {noise}"));
    t.push(format!(
        "  view      relative catches ({})      ΔS to {mirror} (JND)   ΔS to the previous (JND)   ΔL to {mirror} (JND)",
        an.receptors.join(", ")
    ));
    for (k, s) in an.samples.iter().enumerate() {
        let rel: Vec<String> = s.relative_catches.iter().map(|x| format!("{x:.3}")).collect();
        let to_mirror = an.distance(&s.name, &mirror);
        let to_prev = (k > 0).then(|| an.distance(&s.name, &an.samples[k - 1].name).and_then(|d| d.delta_s)).flatten();
        t.push(format!(
            "  {:>6}    {:<32}  {:>12}   {:>12}   {:>12}",
            s.name,
            rel.join(" "),
            jnd(to_mirror.and_then(|d| d.delta_s)),
            jnd(to_prev),
            jnd(to_mirror.and_then(|d| d.delta_l))
        ));
    }
    t.join("\n")
}

/// The views' false colours as a picture with its legend in the title (see [`crate::vision`]).
pub fn vision_strip(v: &DirectionalVision) -> Result<iridis_plot::RgbImage> {
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
