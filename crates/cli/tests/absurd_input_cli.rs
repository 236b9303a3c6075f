//! Input off by orders of magnitude (a mistyped unit or exponent) is refused with a message, never a panic or
//! a silently empty, black or NaN result: the cases an audit of every command found (2026-11-29), each of
//! which panicked, wrote an empty table or a black image with exit 0, or printed NaN before.

use crate::common;

use common::{assert_fails, iridis, json_of, ok, tmp, words, write_file};

const FILM: &str = "air | water 348nm | air";
const SINE: &str = "builtin:sine?size=2um&pixel=50nm";

/// A count of samples past usize wrapped to an empty grid: thin-film colours and the test bench indexed it
/// and panicked, spectra and charts came out empty or black with exit 0.
#[test]
fn wavelength_and_angle_counts_beyond_reach_are_refused() {
    let too_many = "more than 10000000: give a larger step";
    assert_fails(&["thinfilm", "color", "--stack", FILM, "--step", "1e-17nm"], &["4e19 samples", too_many]);
    assert_fails(&["thinfilm", "spectrum", "--stack", FILM, "--to", "1e300nm"], &["1e300 nm", too_many]);
    assert_fails(&["testbench", SINE, "--step", "1e-17nm"], &[too_many]);
    assert_fails(&["grating", SINE, "--from", "380nm", "--to", "1e300nm"], &[too_many]);
    assert_fails(&["testbench", SINE, "--angle-step", "1e-300deg"], &["1.78e302 angles", "too many"]);
    // A step longer than the range kept one wavelength and dropped --to without a word.
    assert_fails(
        &["thinfilm", "spectrum", "--stack", FILM, "--step", "1e300nm"],
        &["not a whole number of 1e300 nm steps", "would be 380 nm"],
    );
    assert_fails(&["thinfilm", "table", "--stack", FILM, "--angles", "0deg:10deg:1e300deg"], &["does not end on TO"]);
}

/// 1e300 µm overflowed the window's area: a NaN table, a black map and NaN f_r with exit 0. The bound is 1 m.
#[test]
fn a_coherence_length_beyond_a_metre_is_refused() {
    let dir = tmp();
    let table = dir.path().join("t.npz");
    let beyond = ["more than the 1 m this model takes", "give 1000mm or less"];
    assert_fails(&["precompute", SINE, "-o", table.to_str().unwrap(), "--coherence", "1e300um"], &beyond);
    assert_fails(&["brdf", "eval", SINE, "--coherence", "2000000mm", "--light", "0deg", "--view", "0deg"], &beyond);
    assert!(!table.exists());
    // 1 m itself is taken.
    let v = json_of(&["brdf", "eval", SINE, "--coherence", "1000mm", "--light", "0deg", "--view", "0deg", "--json"]);
    let numbers = |x: &serde_json::Value| x.as_array().unwrap().iter().all(|y| y.as_f64().is_some_and(f64::is_finite));
    assert!(numbers(&v["xyz"]) && numbers(&v["brdf_per_sr"]["p"]) && numbers(&v["brdf_per_sr"]["s"]), "{v}");
}

#[test]
fn colour_differences_and_heights_beyond_reach_are_refused() {
    assert_fails(&["color", "delta-e", "50,0,0", "1e300,0,0"], &["second colour's L* = 1e300", "outside CIELAB"]);
    assert_fails(
        &["surface", "info", "builtin:sine?depth=1e300nm&size=2um&pixel=50nm"],
        &["more than the 1 m any scan measures", "--height-unit"],
    );
}

/// A bare array has one unnamed channel: `--channel 3` was accepted and ignored.
#[test]
fn a_channel_of_a_single_channel_file_is_refused() {
    let dir = tmp();
    let npy = dir.path().join("sine.npy");
    ok(&["surface", "generate", "sine", "--size", "1um", "--pixel-size", "50nm", "-o", npy.to_str().unwrap()]);
    let out = dir.path().join("o.npy");
    assert_fails(
        &["surface", "convert", npy.to_str().unwrap(), out.to_str().unwrap(), "--channel", "3"],
        &["--channel 3 would be ignored", "one unnamed channel"],
    );
    assert!(!out.exists());
}

/// Lengths that put no relief on the patch wrote flat fields (rms 0) with exit 0.
#[test]
fn generators_refuse_a_flat_field() {
    let dir = tmp();
    let out = dir.path().join("r.npy");
    let o = out.to_str().unwrap();
    let base = ["--size", "2um", "--pixel-size", "50nm", "-o", o];
    let run = |kind: &'static str, extra: &[&'static str]| {
        [&["surface", "generate", kind][..], extra, &base].concat().iter().map(|s| s.to_string()).collect::<Vec<_>>()
    };
    assert_fails(
        &run("rect-bumps", &["--period", "1e300nm"]),
        &["rect-bumps is flat", "1e294mm", "far beyond the patch"],
    );
    assert_fails(&run("gaussian", &["--corr", "1e9um"]), &["gaussian is flat"]);
    assert_fails(&run("cd", &["--bit", "1e-5nm"]), &["shortest pit (3 bits", "shorter than two pixels"]);
    assert!(!out.exists());
    // A bit shorter than two pixels is fine while its 3-bit pits span two (231 nm bits at 130 nm pixels).
    ok(&["surface", "generate", "cd", "--size", "4um", "--pixel-size", "130nm", "-o", o]);
}

/// A map with no light, or an image black at the exposure given, said so only under --auto-exposure.
#[test]
fn a_black_map_or_image_is_said() {
    let dir = tmp();
    let png = dir.path().join("m.png");
    let map = |extra: &[&str]| {
        let size: &[&str] = if extra.contains(&"--size") { &[] } else { &["--size", "16"] };
        let args = [&["brdf-map", SINE, "-o", png.to_str().unwrap()][..], size, extra].concat();
        let out = iridis(&args);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        String::from_utf8_lossy(&out.stderr).to_string()
    };
    // Stam's periodic model puts the sine's orders on y = 0, which 16 pixels a side have no row on.
    let e = map(&["--method", "stam-periodic"]);
    assert!(e.contains("warning: the map is black") && e.contains("give an odd --size"), "{e}");
    assert!(!map(&["--method", "stam-periodic", "--size", "17"]).contains("is black"));
    // The reference's 16² samples miss the 2 µm cell's orders at 65 µm: what is left is round-off (~1e-35),
    // not light, and --auto-exposure no longer scales it to white (it chose 2.7e34 RU).
    let e = map(&["--method", "reference", "--auto-exposure"]);
    assert!(e.contains("warning: the map is black") && !e.contains("chosen from the map"), "{e}");
    // A lit map at an exposure that leaves every 8-bit pixel black.
    let e = map(&["--method", "reference", "--subsamples", "8", "--exposure", "1e-30"]);
    assert!(e.contains("warning: the image is black at --exposure 1e-30 RU") && e.contains("--auto-exposure"), "{e}");
    assert!(!map(&["--method", "reference", "--subsamples", "8"]).contains("is black"));
}

/// An index-matched stack reflects nothing, so ψ = atan|r_p/r_s| and Δ are undefined: empty cells, not NaN.
#[test]
fn an_undefined_ellipsometric_angle_is_an_empty_cell() {
    let csv =
        ok(&["thinfilm", "spectrum", "--stack", "air | n=1 100nm | n=1", "--csv", "--from", "500nm", "--to", "510nm"]);
    assert!(!csv.contains("NaN"), "{csv}");
    let rows: Vec<&str> = csv.lines().filter(|l| l.starts_with("50") || l.starts_with("51")).collect();
    assert_eq!(rows.len(), 3, "{csv}");
    assert!(rows.iter().all(|r| r.ends_with(",,")), "{csv}");
}

/// The smaller cases of the audit: a constant field's black PSDF, a key given twice, an unknown method with a
/// table, a map size of 0 in the bench, a light of no luminance.
#[test]
fn small_silent_cases_are_said_or_refused() {
    let dir = tmp();
    // A constant 8 × 8 field (a .txt grid): a plane, said as such.
    let flat = common::write_file(dir.path(), "flat.txt", &"3 3 3 3 3 3 3 3\n".repeat(8));
    let psdf = dir.path().join("p.png");
    let out = ok(&[
        "surface",
        "info",
        &flat,
        "--pixel-size",
        "10nm",
        "--height-unit",
        "nm",
        "--psdf",
        psdf.to_str().unwrap(),
    ]);
    assert!(out.contains("warning: the field is a plane") && psdf.exists(), "{out}");
    assert_fails(&["surface", "info", "builtin:sine?size=5um&size=6um"], &["gives size twice (5um, then 6um)"]);
    let table = dir.path().join("t.npz");
    ok(&["precompute", SINE, "-o", table.to_str().unwrap(), "--uv-resolution", "11"]);
    let png = dir.path().join("m.png");
    assert_fails(
        &["brdf-map", table.to_str().unwrap(), "--method", "foo", "-o", png.to_str().unwrap()],
        &["unknown method 'foo'", "rigorous"],
    );
    assert_fails(&["bench", "diffraction", "--map-sizes", "0"], &["--map-sizes 0 must be between 8 and"]);
    let zero = common::write_file(dir.path(), "zero.csv", "380,0\n580,0\n780,0\n");
    assert_fails(&["color", "xyz", &zero, "--emissive"], &["no luminance to scale to Y = 1"]);
    // A render exposed a thousand orders too low.
    let out = ok(&[
        "render",
        "examples/soap_bubble.toml",
        "-o",
        png.to_str().unwrap(),
        "--size",
        "16x16",
        "--exposure",
        "1e-300",
    ]);
    assert!(
        out.contains("warning: the image is black at exposure 1e-300 RU") && out.contains("white at --exposure"),
        "{out}"
    );
    // And a thousand orders too high: the image is white, said, with the exposure that shows the colours; the
    // scene's own exposure says nothing.
    let render = |exposure: &[&str]| {
        ok(&[&["render", "examples/soap_bubble.toml", "-o", png.to_str().unwrap(), "--size", "16x16"][..], exposure]
            .concat())
    };
    let out = render(&["--exposure", "1e300"]);
    assert!(
        out.contains("% of the image's lit pixels are clipped at --exposure 1e300 RU (a channel at white)"),
        "{out}"
    );
    assert!(!render(&[]).contains("clipped"));
}

/// Sizes, counts and angles the second audit (the Python functions, 2026-11-29) found unchecked in the library:
/// a bench surface of 10⁵ samples a side aborted on an 80 GB allocation, a rigorous grating at 0.5 nm grew past 6 GB,
/// a light at 2578° was analysed, a lossless layer of n = 1e300 lost all the light.
#[test]
fn library_limits_found_from_python_hold_on_the_command_line() {
    assert_fails(&["bench", "diffraction", "--size", "100000"], &["--size 100000", "from 8 to 8192"]);
    assert_fails(&["bench", "render", "--size", "0"], &["--size 0", "from 1 to 16384 pixels"]);
    assert_fails(
        &["grating", "builtin:sine?size=20um&pixel=100nm&period=20um", "--wavelength", "10nm", "--method", "rigorous"],
        &["3000 orders propagate each side along a period of 20000 nm at λ = 10 nm", "more than the 1000"],
    );
    // 10 nm on 1100 nm: 110 propagating orders each side, the truncation cannot grow past them; no estimate is
    // printed (it read "converged: … estimated error 5.6e-16 … NOT met: … the error is not estimated").
    let short = ok(&["grating", "builtin:sine?size=1100nm&pixel=10nm", "--wavelength", "10nm", "--method", "rigorous"]);
    assert!(short.contains("convergence NOT met: orders ±165, the truncation could not grow"), "{short}");
    assert!(!short.contains("estimated error") && !short.contains("converged:"), "{short}");
    assert!(short.contains("at 10 nm (no estimate: the truncation could not grow past the propagating orders)"));
    let j = json_of(&[
        "grating",
        "builtin:sine?size=1100nm&pixel=10nm",
        "--wavelength",
        "10nm",
        "--method",
        "rigorous",
        "--json",
    ]);
    assert!(j["convergence"][0]["estimated_error"].is_null() && j["convergence"][0]["met"] == false, "{j}");
    let history = j["convergence"][0]["history"].as_array().unwrap();
    assert!(history.last().unwrap()["change"].is_null(), "{history:?}");
    // A crossed lamellar grating at 250 nm: R + T = 4 × 10⁴ over glass, printed as efficiencies beside "NOT met"
    // only. Energy conservation says it is no answer: said so (the 2-D solve takes 5 s).
    let dir = tmp();
    let bumps = dir.path().join("rb.npy");
    ok(&words(&format!(
        "surface generate rect-bumps --size 1100nm --pixel-size 100nm --period 1100nm -o {}",
        bumps.display()
    )));
    let lamellar =
        ok(&[&["grating", bumps.to_str().unwrap()][..], &["--method", "rigorous", "--wavelength", "250nm"]].concat());
    assert!(lamellar.contains("(R + T − 1 = ") && lamellar.contains("the rigorous answer creates or loses light"));
    assert_fails(
        &["brdf", "vision", "builtin:sine?size=3300nm&pixel=100nm", "--visual", "bluetit", "--light", "100deg"],
        &["--light 100°", "up to (not including) 90°"],
    );
    assert_fails(
        &["thinfilm", "spectrum", "--stack", "air | n=1e300 100nm | air"],
        &["|n + iκ| = 1e300 is beyond 1e6"],
    );
    // Beyond the eye's response (it ends at 830 nm) a colour is of nothing: refused, not black.
    assert_fails(
        &["thinfilm", "color", "--stack", FILM, "--from", "1000nm", "--to", "1500nm"],
        &["1000–1500 nm (--from/--to) holds 0.00 % of it"],
    );
}

/// Wavelengths in µm or metres written as nm: a unit cell of 4 µm at 5.5e-7 nm has ~1e10 orders (the grating
/// aborted allocating 4 GB; Python's process was killed at 24 GB), and a test bench from 0.5 nm counted its
/// Taylor terms for 380 nm and printed reflectances of 1e77. Both are refused, saying what the unit likely was.
#[test]
fn wavelengths_in_the_wrong_unit_are_refused() {
    let sine = "builtin:sine?size=4um&pixel=50nm&period=1000nm&depth=100nm";
    assert_fails(&["grating", sine, "--wavelength", "5.5e-7nm"], &["0.00000055 nm", "looks like metres"]);
    // A crossed 20 µm cell at the extreme UV's 10 nm: π (L/λ)² ≈ 1.3e7 orders, refused before any is listed.
    assert_fails(
        &["grating", "builtin:gaussian?size=20um&pixel=100nm", "--wavelength", "10nm"],
        &["about 1.3e7 orders propagate at λ = 10 nm", "more than the 4e6"],
    );
    // A spectrum in µm: grey with a range warning before; refused by every reader of spectra.
    let dir = tempfile::tempdir().unwrap();
    let um: String = (40..=70).map(|k| format!("{},0.4\n", k as f64 / 100.0)).collect();
    let um = write_file(dir.path(), "um.csv", &format!("wavelength,R\n{um}"));
    assert_fails(&["color", "xyz", &um], &["reach only 0.7 nm: that looks like µm (0.7 µm is 700 nm)"]);
    assert_fails(&["vision", &um, "--visual", "bluetit"], &["reach only 0.7 nm: that looks like µm"]);
    // From 20 nm, light these models take: 2k|h|max = 2 · 2π/20 nm · 129 nm ≈ 81 > 26.8, beyond the Taylor
    // expansion at the bench's shortest wavelength (its terms were counted for 380 nm and it ran).
    assert_fails(
        &["testbench", "builtin:blazed?size=20um&pixel=50nm", "--from", "20nm", "--to", "40nm", "--step", "10nm"],
        &["too deep for the Taylor expansion (paper eq. 5) at 20 nm"],
    );
    assert_fails(
        &["testbench", "builtin:blazed?size=20um&pixel=50nm", "--from", "0.5nm", "--to", "0.7nm", "--step", "0.05nm"],
        &["0.5 nm is shorter than the light these models take", "looks like µm (0.5 µm is 500 nm)"],
    );
}

/// The diffraction commands take light from the extreme UV up (10 nm): a grating "at 0.55 nm" on a shallow cell
/// listed 3637 orders and a test bench "from 0.38 nm" read a period, µm taken for nm. A thin film takes X-rays
/// (X-ray reflectivity at 0.154 nm), so only metres are refused there.
#[test]
fn light_shorter_than_the_extreme_uv_is_refused_by_the_diffraction_commands() {
    let shallow = "builtin:sine?size=1um&pixel=10nm&depth=0.01nm";
    assert_fails(
        &["grating", shallow, "--wavelength", "0.55nm"],
        &["0.55 nm is shorter than the light these models take"],
    );
    assert_fails(
        &["testbench", shallow, "--from", "0.38nm", "--to", "0.78nm", "--step", "0.01nm"],
        &["0.38 nm is shorter than the light these models take", "looks like µm"],
    );
    let xrr = ok(&[
        "thinfilm",
        "spectrum",
        "--stack",
        "air | n=0.99+0.01i 10nm | air",
        "--from",
        "0.154nm",
        "--to",
        "0.2nm",
        "--step",
        "0.002nm",
    ]);
    assert!(xrr.contains("0.154"), "{xrr}");
    assert_fails(
        &["thinfilm", "spectrum", "--stack", "air | water 348nm | air", "--from", "4e-7nm"],
        &["looks like metres"],
    );
}
