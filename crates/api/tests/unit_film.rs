//! The unit tests of src/film.rs (thin-film spectra, grids and angles), moved here so that `cargo test` compiles the
//! library once.

use iridis_api::film::*;
use iridis_api::report::Quiet;

#[test]
fn a_quarter_wave_layer_reflects_as_the_closed_form_says() {
    // n₁ d = λ/4 at 550 nm: R = ((n₀ n_s − n₁²) / (n₀ n_s + n₁²))² (Born & Wolf §1.6.4), and R + T = 1.
    let d = 550.0 / (4.0 * 1.38);
    let stack = parse_stack(&format!("air | n=1.38 {d}nm | n=1.5")).unwrap();
    let s = spectrum(&stack, "air|n=1.38|n=1.5", 0.0, &[550.0], Polarization::Average, &Quiet).unwrap();
    let want: f64 = ((1.5 - 1.38 * 1.38) / (1.5 + 1.38 * 1.38f64)).powi(2);
    assert!((s.r()[0] - want).abs() < 1e-12, "{} vs {want}", s.r()[0]);
    assert!((s.r()[0] + s.t()[0] - 1.0).abs() < 1e-12);
    assert_eq!(s.a()[0], 0.0, "a lossless stack's 1 − R − T is printed as 0");
    assert_eq!(s.title, "air | n=1.38 | n=1.5");
    assert!(s.csv().starts_with("wavelength_nm,R,T,A,Rs,Rp,Ts,Tp,psi_deg,delta_deg\n550,"));
}

#[test]
fn grids_and_angles_refuse_what_cannot_be_meant() {
    assert_eq!(wavelength_grid(400.0, 410.0, 5.0).unwrap(), vec![400.0, 405.0, 410.0]);
    assert!(wavelength_grid(0.0, 410.0, 5.0).unwrap_err().to_string().contains("--from must be a positive"));
    assert!(wavelength_grid(500.0, 410.0, 5.0).unwrap_err().to_string().contains("must not be below"));
    assert!(wavelength_grid(400.0, 800.0, 0.001).unwrap_err().to_string().contains("too many"));
    // Both ends are samples: a step that does not divide the range names where the grid would end (400 + 42·7),
    // where it stopped short of --to before; one that divides it ends on --to whatever the rounding.
    let e = wavelength_grid(400.0, 700.0, 7.0).unwrap_err().to_string();
    assert!(e.contains("400–700 nm is not a whole number of 7 nm steps: the last wavelength would be 694 nm"), "{e}");
    assert!(e.contains("divides the 300 nm range, or end at 694 nm"), "{e}");
    let g = wavelength_grid(380.0, 780.0, 0.1).unwrap();
    assert_eq!(g.len(), 4001);
    assert!((g[4000] - 780.0).abs() < 1e-9, "{}", g[4000]);
    assert_eq!(wavelength_grid(550.0, 550.0, 5.0).unwrap(), vec![550.0]);
    assert!(parse_angles("0deg:100deg:50deg", "--angles").unwrap_err().to_string().contains("100° is outside"));
    assert_eq!(round_deg(30f64.to_radians()), 30.0);
    assert_eq!(fmt_deg(0.5f64.to_radians()), "0.5");
    // A colour of one wavelength would be black: refused (the spectrum of one wavelength is fine).
    let said = iridis_api::report::Collect::default();
    let e = check_colour_grid(&[500.0], GridGiven::Range, &said).unwrap_err().to_string();
    assert!(e.contains("only 500 nm; give a range"), "{e}");
    // A grid that misses part of the visible gives that band's colours, and says so; 380–780 nm says nothing.
    assert!(check_colour_grid(&[500.0, 505.0], GridGiven::Range, &said).is_ok());
    let lines = said.take();
    assert!(lines.len() == 1 && lines[0].1.contains("integrate over 500–505 nm only"), "{lines:?}");
    assert!(lines[0].1.contains("normalised on this band"), "{lines:?}");
    // Under 1 % of the eye's response (300–380 nm: 0.1 %), or the response sampled at two points 400 nm apart
    // (the trapezoid gives its white 97 % off), is a colour of nothing: refused.
    let e = check_colour_grid(&[300.0, 340.0, 380.0], GridGiven::Range, &said).unwrap_err().to_string();
    assert!(e.contains("300–380 nm (--from/--to) holds 0.0"), "{e}");
    let e = check_colour_grid(&[380.0, 780.0], GridGiven::Range, &said).unwrap_err().to_string();
    assert!(e.contains("so coarsely that its white is off by") && e.contains("a finer --step"), "{e}");
    // A grid given as a list (Python's `grid_nm`) is named so, not by flags its caller does not have.
    let e = check_colour_grid(&[380.0, 780.0], GridGiven::List("grid_nm"), &said).unwrap_err().to_string();
    assert!(e.contains("give a finer grid_nm (steps ≤ 10 nm") && !e.contains("--"), "{e}");
    let e = check_colour_grid(&[300.0, 380.0], GridGiven::List("grid_nm"), &said).unwrap_err().to_string();
    assert!(e.contains("300–380 nm (grid_nm) holds"), "{e}");
    let every_5nm = |from: f64, to: f64| wavelength_grid(from, to, 5.0).unwrap();
    check_colour_grid(&every_5nm(380.0, 780.0), GridGiven::Range, &said).unwrap();
    // Sussenbach's 400–700 nm and vision's 300–700 nm miss under 1 % of the observer's weight: nothing said.
    check_colour_grid(&every_5nm(400.0, 700.0), GridGiven::Range, &said).unwrap();
    check_colour_grid(&every_5nm(300.0, 700.0), GridGiven::Range, &said).unwrap();
    assert!(said.take().is_empty());
    // A wavelength that cannot be meant is refused, not answered with "no data" for every material.
    for w in [-1.0, 0.0, f64::NAN] {
        let e = materials(Some(w)).unwrap_err().to_string();
        assert!(e.contains("must be a positive, finite length"), "{e}");
    }
    // Water's constant index holds at any wavelength it is asked (Sussenbach's n = 1.33).
    let water = materials(Some(550.0)).unwrap().rows.into_iter().find(|r| r.0.contains(&"water")).unwrap();
    assert_eq!(water.4, Some(Ok((1.33, 0.0))));
}

/// The rough table's plot puts the light at the view angle, clamped to `--light-angles`: its title says so where
/// a view lies outside that range (it read "light at the view angle" for every row).
#[test]
fn the_rough_tables_plot_says_where_the_light_is_clamped() {
    let opts = iridis_api::rough::RoughOptions::new(25.0, 300.0);
    let stack = || iridis_thinfilm::Stack::parse("air | water 300nm | n=3.9").unwrap();
    let run = |lights: Option<&str>| {
        iridis_api::rough::table(stack(), "film", &opts, "0deg:60deg:30deg", lights, 0.0, &[500.0]).unwrap()
    };
    assert!(run(None).plot_title().starts_with("Diffuse π·k_d, light at the view angle: "));
    let clamped = run(Some("20deg:30deg:10deg")).plot_title();
    assert!(clamped.contains("within the lights' 20°–30°"), "{clamped}");
}
