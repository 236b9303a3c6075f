//! The unit tests of src/lib.rs, moved here so that `cargo test` compiles the library once.

use iridis_plot::*;
use plotters::prelude::*;

#[test]
fn line_plot_draws_its_curve() {
    let xs: Vec<f64> = (0..100).map(|i| i as f64).collect();
    let ys: Vec<f64> = xs.iter().map(|x| x * x).collect();
    let img = LinePlot::new("t", "x (nm)", "y").series(Series::new("square", &xs, &ys)).render().unwrap();
    // The first palette colour must appear somewhere: the curve was drawn.
    let c = PALETTE[0];
    let found = img.data.chunks(3).any(|p| p == [c.0, c.1, c.2]);
    assert!(found);
    // And text was rendered (dark pixels near the top, where the title is).
    let dark =
        (0..img.width).flat_map(|x| (0..40).map(move |y| (x, y))).filter(|&(x, y)| img.get(x, y)[0] < 100).count();
    assert!(dark > 10);
}

/// Runs of `colour` along row `y` between columns `x0..x1`: one for a solid line, several for a dashed one.
fn runs(img: &RgbImage, y: u32, (x0, x1): (u32, u32), c: [u8; 3]) -> usize {
    let on: Vec<bool> = (x0..x1).map(|x| img.get(x, y) == c).collect();
    on.windows(2).filter(|w| w[1] && !w[0]).count() + usize::from(on.first() == Some(&true))
}

#[test]
fn dashed_series_have_dashed_lines_and_swatches() {
    // Two horizontal lines in one colour: y = 0.25 solid, y = 0.75 dashed; no margin (y range fixed).
    let c = [200, 30, 30];
    let xs = [0.0, 1.0];
    let mut plot = LinePlot::new("t", "x", "y")
        .series(Series::new("mean", &xs, &[0.25, 0.25]).with_color(c))
        .series(Series::new("95th percentile", &xs, &[0.75, 0.75]).with_color(c).dashed());
    plot.y_range = Some((0.0, 1.0));
    let img = plot.render().unwrap();
    // Rows of the colour, each with the number of separate runs it holds across the whole image.
    let rows: Vec<(u32, usize, usize)> = (0..img.height)
        .map(|y| {
            let n = (0..img.width).filter(|&x| img.get(x, y) == c).count();
            (y, n, runs(&img, y, (0, img.width), c))
        })
        .filter(|r| r.1 > 0)
        .collect();
    // The solid curve: a row with one long run (the plot area is ~800 px wide).
    assert!(rows.iter().any(|r| r.1 > 600 && r.2 <= 2), "{rows:?}");
    // The dashed curve: a row with dozens of runs of dash length (6 px dash, 4 px gap).
    assert!(rows.iter().any(|r| r.2 > 40), "{rows:?}");
    // The legend: two swatches 24 px long; the solid one is one run, the dashed one several. They lie in
    // rows apart from the curves, found as rows holding a short stretch of the colour.
    let swatches: Vec<usize> = rows.iter().filter(|r| r.1 >= 10 && r.1 <= 80).map(|r| r.2).collect();
    assert!(swatches.contains(&1) && swatches.iter().any(|&n| n >= 2), "{rows:?}");
}

fn plot_with(points: &[(f64, f64)]) -> LinePlot {
    let xs: Vec<f64> = points.iter().map(|p| p.0).collect();
    let ys: Vec<f64> = points.iter().map(|p| p.1).collect();
    LinePlot::new("t", "x", "y").series(Series::new("R (reflectance)", &xs, &ys)).series(Series::new(
        "flat",
        &[0.0, 1.0],
        &[0.0, 0.0],
    ))
}

#[test]
fn legend_avoids_the_curves() {
    // A curve that rises to the upper right: the legend goes to the upper left.
    let rising: Vec<(f64, f64)> = (0..=100).map(|i| (i as f64 / 100.0, (i as f64 / 100.0).powi(4))).collect();
    let p = plot_with(&rising);
    assert!(matches!(p.legend_position((0.0, 1.0), (0.0, 1.0)), SeriesLabelPosition::UpperLeft));
    // The oil-slick picture: a curve along the top, others along the bottom: the legend sits at mid height.
    let top: Vec<(f64, f64)> = (0..=100).map(|i| (i as f64 / 100.0, 0.93 + 0.04 * (i as f64 / 7.0).sin())).collect();
    let p = plot_with(&top);
    assert!(matches!(p.legend_position((0.0, 1.0), (0.0, 1.0)), SeriesLabelPosition::MiddleRight));
    // Nothing in the way: the usual upper right.
    let low: Vec<(f64, f64)> = (0..=100).map(|i| (i as f64 / 100.0, 0.1)).collect();
    assert!(matches!(plot_with(&low).legend_position((0.0, 1.0), (0.0, 1.0)), SeriesLabelPosition::UpperRight));
}

#[test]
fn tick_labels_have_the_decimals_their_spacing_needs() {
    let f = tick_format(400.0); // 380–780 nm: ticks every 50
    assert_eq!((f(&400.0), f(&750.0)), ("400".to_string(), "750".to_string()));
    let f = tick_format(1.07); // a reflectance axis: ticks every 0.1
    assert_eq!((f(&0.1), f(&1.0), f(&-0.0)), ("0.1".to_string(), "1.0".to_string(), "0".to_string()));
    let f = tick_format(0.08); // ticks every 0.01
    assert_eq!(f(&0.05), "0.05");
    let f = tick_format(2e-5);
    assert_eq!(f(&1.5e-5), "1.5e-5");
    assert_eq!(tick_format(1e7)(&5e6), "5.0e6");
    // The ACF's lag axis of a 0.43 µm scan, −0.22 to 0.22 µm: plotters' tick at −0.3 + 3 × 0.1 is
    // −5.6e-17, which is 0.
    let f = tick_format(0.44);
    assert_eq!((f(&(-0.3 + 3.0 * 0.1)), f(&-0.1)), ("0".to_string(), "-0.10".to_string()));
    assert_eq!(tick_format(2e-5)(&-5.6e-17), "0");
}

/// A title longer than the figure is wide is set smaller to fit inside the margins (a report's map figure cut
/// `builtin:sine?size=8um&pixel=50nm · θi 45° …` off at both edges).
#[test]
fn a_long_title_fits_inside_the_figure() {
    let pixels = RgbImage::new(8, 8);
    let title = "builtin:xenopeltis?size=20um&pixel=50nm&seed=3 · θi 45° φi 0° · reference · D65 · 5.123e3 RU";
    let img = ImagePlot::view_directions(title, &pixels, (560, 600)).render().unwrap();
    let dark_in = |xs: std::ops::Range<u32>| {
        xs.flat_map(|x| (0..40).map(move |y| (x, y))).filter(|&(x, y)| img.get(x, y)[0] < 100).count()
    };
    assert!(dark_in(60..500) > 100, "the title is drawn");
    assert_eq!(dark_in(0..10) + dark_in(550..560), 0, "the title runs into the edges");
}
