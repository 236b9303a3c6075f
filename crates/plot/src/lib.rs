//! # iridis-plot
//!
//! Plots that a person can read — axes with units, legends, colour bars — rendered to 8-bit RGB buffers
//! with an embedded font (DejaVu Sans, `data/fonts/`), so they look the same on every machine. The caller
//! writes the buffer (the CLI does so atomically).

use std::sync::Once;

use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::FontStyle;

/// An RGB image, row-major, 3 bytes per pixel.
#[derive(Debug, Clone)]
pub struct RgbImage {
    pub width: u32,
    pub height: u32,
    pub data: Vec<u8>,
}

impl RgbImage {
    pub fn new(width: u32, height: u32) -> Self {
        Self { width, height, data: vec![0; width as usize * height as usize * 3] }
    }
    pub fn put(&mut self, x: u32, y: u32, rgb: [u8; 3]) {
        let i = (y as usize * self.width as usize + x as usize) * 3;
        self.data[i..i + 3].copy_from_slice(&rgb);
    }
    pub fn get(&self, x: u32, y: u32) -> [u8; 3] {
        let i = (y as usize * self.width as usize + x as usize) * 3;
        [self.data[i], self.data[i + 1], self.data[i + 2]]
    }
}

/// A plotting failure (these come from the drawing back end, not from user input).
#[derive(Debug, thiserror::Error)]
#[error("plot: {0}")]
pub struct PlotError(String);

fn err<E: std::fmt::Debug>(e: E) -> PlotError {
    PlotError(format!("{e:?}"))
}

const FONT: &str = "sans-serif";

/// The caption's font size: 22 px, or smaller (down to 12 px) where the title would run past the area's width
/// less its margins — a long SURFACE name made a title that was cut off at both edges.
fn caption_px<DB: DrawingBackend>(area: &DrawingArea<DB, plotters::coord::Shift>, title: &str) -> u32 {
    let room = area.dim_in_pixel().0.saturating_sub(2 * 16);
    let fits = |px: u32| {
        let style: TextStyle = (FONT, px as f64).into_font().into();
        area.estimate_text_size(title, &style).is_ok_and(|(w, _)| w <= room)
    };
    (12..=22).rev().find(|&px| fits(px)).unwrap_or(12)
}

fn register_font() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        let bytes: &'static [u8] = include_bytes!("../../../data/fonts/DejaVuSans.ttf");
        // The font is part of the build; failing to parse it is a programming error caught by the tests.
        let _ = plotters::style::register_font(FONT, FontStyle::Normal, bytes);
    });
}

/// Dash and gap of dashed lines, in pixels.
const DASH: u32 = 6;
const GAP: u32 = 4;

/// Distinguishable line colours (Okabe–Ito palette, readable for colour-blind viewers).
pub const PALETTE: [RGBColor; 7] = [
    RGBColor(0, 114, 178),
    RGBColor(213, 94, 0),
    RGBColor(0, 158, 115),
    RGBColor(204, 121, 167),
    RGBColor(230, 159, 0),
    RGBColor(86, 180, 233),
    RGBColor(0, 0, 0),
];

/// One named curve.
#[derive(Debug, Clone)]
pub struct Series {
    pub name: String,
    pub points: Vec<(f64, f64)>,
    /// A thick line when true, a thin one when false.
    pub emphasis: bool,
    /// Line colour; the palette's next colour when `None`.
    pub color: Option<[u8; 3]>,
    /// A dashed line (and a dashed legend swatch): tells apart two curves that share a colour.
    pub dashed: bool,
}

impl Series {
    pub fn new(name: impl Into<String>, xs: &[f64], ys: &[f64]) -> Self {
        Self {
            name: name.into(),
            points: xs.iter().copied().zip(ys.iter().copied()).collect(),
            emphasis: true,
            color: None,
            dashed: false,
        }
    }

    /// The same series drawn dashed, a thin line with a dashed legend swatch.
    pub fn dashed(mut self) -> Self {
        self.dashed = true;
        self.emphasis = false;
        self
    }

    /// The same series in a given colour.
    pub fn with_color(mut self, rgb: [u8; 3]) -> Self {
        self.color = Some(rgb);
        self
    }
}

/// A line plot with title, axis labels (with units) and a legend.
#[derive(Debug, Clone)]
pub struct LinePlot {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub series: Vec<Series>,
    /// Fixed y range; automatic (with a margin) when `None`.
    pub y_range: Option<(f64, f64)>,
    pub x_range: Option<(f64, f64)>,
    pub size: (u32, u32),
}

impl LinePlot {
    pub fn new(title: impl Into<String>, x_label: impl Into<String>, y_label: impl Into<String>) -> Self {
        Self {
            title: title.into(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            series: Vec::new(),
            y_range: None,
            x_range: None,
            size: (900, 560),
        }
    }

    pub fn series(mut self, s: Series) -> Self {
        self.series.push(s);
        self
    }

    /// Renders the plot.
    pub fn render(&self) -> Result<RgbImage, PlotError> {
        register_font();
        let (w, h) = self.size;
        let mut img = RgbImage::new(w, h);
        let finite = |v: &f64| v.is_finite();
        let xs = self.series.iter().flat_map(|s| s.points.iter().map(|p| p.0)).filter(finite);
        let ys = self.series.iter().flat_map(|s| s.points.iter().map(|p| p.1)).filter(finite);
        let (x0, x1) = self.x_range.unwrap_or_else(|| min_max(xs, 0.0));
        let (y0, y1) = self.y_range.unwrap_or_else(|| min_max(ys, 0.05));
        {
            let root = BitMapBackend::with_buffer(&mut img.data, (w, h)).into_drawing_area();
            root.fill(&WHITE).map_err(err)?;
            let mut chart = ChartBuilder::on(&root)
                .caption(&self.title, (FONT, caption_px(&root, &self.title)))
                .margin(16)
                .x_label_area_size(48)
                .y_label_area_size(72)
                .build_cartesian_2d(x0..x1, y0..y1)
                .map_err(err)?;
            let (x_fmt, y_fmt) = (tick_format(x1 - x0), tick_format(y1 - y0));
            chart
                .configure_mesh()
                .x_desc(&self.x_label)
                .y_desc(&self.y_label)
                .x_label_formatter(&x_fmt)
                .y_label_formatter(&y_fmt)
                .label_style((FONT, 15))
                .axis_desc_style((FONT, 17))
                .light_line_style(RGBColor(235, 235, 235))
                .draw()
                .map_err(err)?;
            for (i, s) in self.series.iter().enumerate() {
                let color = s.color.map(|c| RGBColor(c[0], c[1], c[2])).unwrap_or(PALETTE[i % PALETTE.len()]);
                let width = if s.emphasis { 2 } else { 1 };
                let pts: Vec<(f64, f64)> =
                    s.points.iter().copied().filter(|p| p.0.is_finite() && p.1.is_finite()).collect();
                // The legend swatch is drawn like its line (width and dashes), so curves that share a colour
                // keep distinct swatches.
                let swatch = color.stroke_width(width + 1);
                if s.dashed {
                    chart
                        .draw_series(DashedLineSeries::new(pts, DASH, GAP, color.stroke_width(width)))
                        .map_err(err)?
                        .label(&s.name)
                        .legend(move |(x, y)| DashedPathElement::new(vec![(x, y), (x + 24, y)], DASH, GAP, swatch));
                } else {
                    chart
                        .draw_series(LineSeries::new(pts, color.stroke_width(width)))
                        .map_err(err)?
                        .label(&s.name)
                        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 24, y)], swatch));
                }
            }
            if self.series.len() > 1 || self.series.iter().any(|s| !s.name.is_empty()) {
                chart
                    .configure_series_labels()
                    .label_font((FONT, 15))
                    .background_style(WHITE.mix(0.85))
                    .border_style(BLACK)
                    .position(self.legend_position((x0, x1), (y0, y1)))
                    .draw()
                    .map_err(err)?;
            }
            root.present().map_err(err)?;
        }
        Ok(img)
    }
}

impl LinePlot {
    /// Where the legend hides the least of the curves: the candidate box (corners first, then edge middles)
    /// that covers the fewest points of the curves, sampled densely along each segment. The box size is
    /// estimated from the labels' length and the plot size (15 px font, as drawn).
    // Public but hidden: not API, a pure layout helper reachable only for the crate's tests in tests/
    // (Cargo.toml, `[lib] test = false`).
    #[doc(hidden)]
    pub fn legend_position(&self, (x0, x1): (f64, f64), (y0, y1): (f64, f64)) -> SeriesLabelPosition {
        use SeriesLabelPosition::*;
        let (w, h) = (self.size.0 as f64 - 120.0, self.size.1 as f64 - 120.0);
        let chars = self.series.iter().map(|s| s.name.chars().count()).max().unwrap_or(0) as f64;
        let bw = ((chars * 8.5 + 60.0) / w).min(1.0);
        let bh = ((self.series.len() as f64 * 20.0 + 16.0) / h).min(1.0);
        // Boxes in plot fractions (0 = left/bottom), with the few pixels of padding plotters leaves.
        let candidates = [
            (UpperRight, 1.0 - bw, 1.0 - bh),
            (UpperLeft, 0.0, 1.0 - bh),
            (LowerRight, 1.0 - bw, 0.0),
            (LowerLeft, 0.0, 0.0),
            (MiddleRight, 1.0 - bw, 0.5 - bh / 2.0),
            (MiddleLeft, 0.0, 0.5 - bh / 2.0),
            (UpperMiddle, 0.5 - bw / 2.0, 1.0 - bh),
            (LowerMiddle, 0.5 - bw / 2.0, 0.0),
        ];
        let (sx, sy) = (x1 - x0, y1 - y0);
        let mut covered = [0usize; 8];
        for s in &self.series {
            let pts: Vec<(f64, f64)> = s
                .points
                .iter()
                .filter(|p| p.0.is_finite() && p.1.is_finite())
                .map(|p| ((p.0 - x0) / sx, (p.1 - y0) / sy))
                .collect();
            for seg in pts.windows(2) {
                for k in 0..8 {
                    let t = k as f64 / 8.0;
                    let (u, v) = (seg[0].0 + t * (seg[1].0 - seg[0].0), seg[0].1 + t * (seg[1].1 - seg[0].1));
                    for (c, &(_, bx, by)) in candidates.iter().enumerate() {
                        if u >= bx && u <= bx + bw && v >= by && v <= by + bh {
                            covered[c] += 1;
                        }
                    }
                }
            }
            if let [p] = pts[..] {
                for (c, &(_, bx, by)) in candidates.iter().enumerate() {
                    covered[c] += usize::from(p.0 >= bx && p.0 <= bx + bw && p.1 >= by && p.1 <= by + bh);
                }
            }
        }
        // The first of the least-covered candidates (the order above is the preference).
        let best = (0..8).min_by_key(|&c| covered[c]).unwrap_or(0);
        candidates.into_iter().nth(best).map_or(UpperRight, |c| c.0)
    }
}

/// Tick labels with as many decimals as the tick spacing needs (`400`, not `400.0`; `0.25`, not
/// `0.250000`), switching to exponents for very small or large values.
// Public but hidden: not API, a pure helper reachable only for the crate's tests in tests/ (Cargo.toml,
// `[lib] test = false`).
#[doc(hidden)]
pub fn tick_format(span: f64) -> impl Fn(&f64) -> String {
    // plotters puts up to ~10 ticks on an axis at 1, 2 or 5 × 10^k: the spacing is about span/8.
    let step = span.abs() / 8.0;
    let decimals = if step > 0.0 && step.is_finite() { (-step.log10() - 1e-9).ceil().max(0.0) as usize } else { 1 };
    move |v: &f64| {
        let a = v.abs();
        // A tick that is zero but for rounding (−5.6e-17 on an axis from −x to x) reads 0.
        if a <= step * 1e-9 {
            return "0".to_string();
        }
        if !(1e-3..1e6).contains(&a) || decimals > 4 {
            format!("{v:.1e}")
        } else if a < 0.5 * 10f64.powi(-(decimals as i32)) {
            "0".to_string() // −0.000 and friends
        } else {
            format!("{v:.decimals$}")
        }
    }
}

fn min_max(values: impl Iterator<Item = f64>, margin: f64) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if !lo.is_finite() || !hi.is_finite() {
        return (0.0, 1.0);
    }
    if hi - lo < 1e-12 {
        return (lo - 0.5, hi + 0.5);
    }
    let pad = (hi - lo) * margin;
    (lo - pad, hi + pad)
}

/// A colour bar beside an [`ImagePlot`]: its label (with units), the values at its ends, and the colour map
/// from `t ∈ [0, 1]` to RGB.
#[derive(Debug, Clone)]
pub struct ColorBar {
    pub label: String,
    pub min: f64,
    pub max: f64,
    pub map: fn(f64) -> [u8; 3],
}

/// A picture (e.g. a colour chart or a BRDF map) framed by axes with units. `pixels` is drawn to fill the
/// plotting area spanning `x_range × y_range`; row 0 of `pixels` is the top (largest y).
#[derive(Debug, Clone)]
pub struct ImagePlot<'a> {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub x_range: (f64, f64),
    pub y_range: (f64, f64),
    pub pixels: &'a RgbImage,
    /// Curves drawn over the picture, in data coordinates.
    pub overlays: Vec<Series>,
    /// A colour bar: (label, min, max, colour map) drawn on the right.
    pub colorbar: Option<ColorBar>,
    pub size: (u32, u32),
}

impl<'a> ImagePlot<'a> {
    /// A picture over the view directions of a BRDF map, in the paper's layout: pixel `(x, y)` views
    /// `(x, y, √(1 − x² − y²))`, axes `x = sin θr cos φr` and `y = sin θr sin φr` on [−1, 1]; no overlays or
    /// colour bar (set them on the value).
    pub fn view_directions(title: impl Into<String>, pixels: &'a RgbImage, size: (u32, u32)) -> Self {
        Self {
            title: title.into(),
            x_label: "x = sin θr cos φr".into(),
            y_label: "y = sin θr sin φr".into(),
            x_range: (-1.0, 1.0),
            y_range: (-1.0, 1.0),
            pixels,
            overlays: Vec::new(),
            colorbar: None,
            size,
        }
    }

    pub fn render(&self) -> Result<RgbImage, PlotError> {
        self.render_with(true)
    }

    /// Renders without numbers on the y axis: for pictures whose y axis is not a quantity (the film chart's
    /// two bands, named by the y label).
    pub fn render_without_y_ticks(&self) -> Result<RgbImage, PlotError> {
        self.render_with(false)
    }

    fn render_with(&self, y_ticks: bool) -> Result<RgbImage, PlotError> {
        register_font();
        let (w, h) = self.size;
        let mut img = RgbImage::new(w, h);
        let bar_w = if self.colorbar.is_some() { 110 } else { 0 };
        {
            let root = BitMapBackend::with_buffer(&mut img.data, (w, h)).into_drawing_area();
            root.fill(&WHITE).map_err(err)?;
            let (main, bar) = root.split_horizontally(w - bar_w);
            let mut chart = ChartBuilder::on(&main)
                .caption(&self.title, (FONT, caption_px(&main, &self.title)))
                .margin(16)
                .x_label_area_size(48)
                .y_label_area_size(72)
                .build_cartesian_2d(self.x_range.0..self.x_range.1, self.y_range.0..self.y_range.1)
                .map_err(err)?;
            let x_fmt = tick_format(self.x_range.1 - self.x_range.0);
            let y_fmt = tick_format(self.y_range.1 - self.y_range.0);
            let mut mesh = chart.configure_mesh();
            mesh.disable_mesh()
                .x_desc(&self.x_label)
                .y_desc(&self.y_label)
                .x_label_formatter(&x_fmt)
                .y_label_formatter(&y_fmt)
                .label_style((FONT, 15))
                .axis_desc_style((FONT, 17));
            if !y_ticks {
                mesh.y_labels(0);
            }
            mesh.draw().map_err(err)?;
            let area = chart.plotting_area();
            let ((px0, py0), (px1, py1)) = {
                let r = area.get_pixel_range();
                ((r.0.start, r.1.start), (r.0.end, r.1.end))
            };
            let (pw, ph) = ((px1 - px0).max(1), (py1 - py0).max(1));
            let (iw, ih) = (self.pixels.width as i32, self.pixels.height as i32);
            for py in 0..ph {
                let sy = ((py as i64 * ih as i64) / ph as i64) as u32;
                for px in 0..pw {
                    let sx = ((px as i64 * iw as i64) / pw as i64) as u32;
                    let c = self.pixels.get(sx.min(self.pixels.width - 1), sy.min(self.pixels.height - 1));
                    root.draw_pixel((px0 + px, py0 + py), &RGBColor(c[0], c[1], c[2])).map_err(err)?;
                }
            }
            for (i, s) in self.overlays.iter().enumerate() {
                let color = s
                    .color
                    .map(|c| RGBColor(c[0], c[1], c[2]))
                    .unwrap_or([RGBColor(255, 255, 255), RGBColor(0, 0, 0), PALETTE[1], PALETTE[2]][i % 4]);
                let pts: Vec<(f64, f64)> =
                    s.points.iter().copied().filter(|p| p.0.is_finite() && p.1.is_finite()).collect();
                chart
                    .draw_series(LineSeries::new(pts, color.stroke_width(2)))
                    .map_err(err)?
                    .label(&s.name)
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 24, y)], color.stroke_width(3)));
            }
            if !self.overlays.is_empty() {
                chart
                    .configure_series_labels()
                    .label_font((FONT, 15))
                    .background_style(WHITE.mix(0.85))
                    .border_style(BLACK)
                    .draw()
                    .map_err(err)?;
            }
            if let Some(ColorBar { label, min: lo, max: hi, map: cmap }) = &self.colorbar {
                let mut cb = ChartBuilder::on(&bar)
                    .margin_top(50)
                    .margin_bottom(64)
                    .margin_right(8)
                    .y_label_area_size(60)
                    .build_cartesian_2d(0.0..1.0, *lo..*hi)
                    .map_err(err)?;
                cb.configure_mesh()
                    .disable_mesh()
                    .disable_x_axis()
                    .y_desc(label.as_str())
                    .label_style((FONT, 13))
                    .axis_desc_style((FONT, 15))
                    .draw()
                    .map_err(err)?;
                let n = 200;
                for k in 0..n {
                    let t0 = lo + (hi - lo) * k as f64 / n as f64;
                    let t1 = lo + (hi - lo) * (k + 1) as f64 / n as f64;
                    let c = cmap((k as f64 + 0.5) / n as f64);
                    cb.draw_series(std::iter::once(Rectangle::new(
                        [(0.0, t0), (1.0, t1)],
                        RGBColor(c[0], c[1], c[2]).filled(),
                    )))
                    .map_err(err)?;
                }
            }
            root.present().map_err(err)?;
        }
        Ok(img)
    }
}

/// A perceptually ordered colour map for heat maps (a compact approximation of matplotlib's "magma":
/// black → purple → orange → pale yellow), `t ∈ [0, 1]`.
pub fn magma(t: f64) -> [u8; 3] {
    const STOPS: [[f64; 3]; 6] = [
        [0.0015, 0.0005, 0.0139],
        [0.2316, 0.0597, 0.4378],
        [0.5507, 0.1612, 0.5060],
        [0.8647, 0.2900, 0.4104],
        [0.9945, 0.6240, 0.4276],
        [0.9870, 0.9914, 0.7495],
    ];
    let t = if t.is_finite() { t.clamp(0.0, 1.0) } else { 0.0 };
    let x = t * (STOPS.len() - 1) as f64;
    let i = (x.floor() as usize).min(STOPS.len() - 2);
    let f = x - i as f64;
    let c = |k: usize| ((STOPS[i][k] * (1.0 - f) + STOPS[i + 1][k] * f) * 255.0).round() as u8;
    [c(0), c(1), c(2)]
}
