//! The unit tests of src/integrate.rs, moved here so that `cargo test` compiles the library once.

use iridis_color::cie::{Illuminant, Observer};
use iridis_color::integrate::*;

#[test]
fn spectra_from_300nm_keep_the_observers_range() {
    // D65 is tabulated by the CIE from 300 nm (0.0341 at 300 nm, 3.2945 at 310 nm).
    let d65 = Illuminant::D65.spd();
    assert_eq!(d65.range_nm().0, 300.0);
    assert!((d65.value_at(310.0) - 3.2945).abs() < 1e-9);
    // A grid from 300 nm integrates to the XYZ of one from 360 nm: the observers end at 360 nm. (Not to
    // rounding: the trapezoid from 359 nm, where x̄ȳz̄ are zero, to 360 nm, where they are ~1e-4 of their
    // peaks, adds half a sample.)
    for o in Observer::ALL {
        assert_eq!(o.range_nm(), (360.0, 830.0));
        assert_eq!(o.cmfs().at(359.0), [0.0; 3]);
        let from = |lo: f64| {
            let grid: Vec<f64> = (0..).map(|i| lo + i as f64).take_while(|&l| l <= 830.0).collect();
            let w = SpectralWeights::new(&grid, Illuminant::D65, o);
            let r: Vec<f64> = grid.iter().map(|l| 0.2 + 0.6 * ((l - 300.0) / 530.0)).collect();
            w.integrate(&r).to_array()
        };
        let (a, b) = (from(300.0), from(360.0));
        for k in 0..3 {
            assert!((a[k] - b[k]).abs() < 2e-6 * b[k], "{o}: {a:?} vs {b:?}");
        }
    }
}
