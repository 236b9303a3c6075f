//! `iridis vision` and the vision options of the thin-film commands as a user runs them: the numbers of the
//! independent numpy implementation (crates/vision/tests/fixtures), one film seen through both paths, units
//! in the text, and clear errors.

use crate::common;
use common::{assert_fails, iridis, json_of};

const SPECTRA: &str = "data/examples/vision_spectra.csv";

#[test]
fn bluetit_json_matches_the_numpy_fixture() {
    let v = json_of(&["vision", SPECTRA, "--visual", "bluetit", "--json"]);
    let f: serde_json::Value =
        serde_json::from_str(include_str!("../../vision/tests/fixtures/vision_numpy.json")).unwrap();
    // The fixture's first case is the blue tit under D65 with a grey background and pavo's default noise:
    // the CLI's defaults.
    let case = &f["cases"][0];
    assert_eq!(case["system"], "bluetit");
    let (got, want) = (v["distances"].as_array().unwrap(), case["distances"].as_array().unwrap());
    assert_eq!(got.len(), 15);
    for (g, w) in got.iter().zip(want) {
        assert_eq!((&g["a"], &g["b"]), (&w["a"], &w["b"]));
        for k in ["delta_s", "delta_l"] {
            let (g, w) = (g[k].as_f64().unwrap(), w[k].as_f64().unwrap());
            assert!((g - w).abs() <= 1e-8 * w.max(1.0), "{k}: {g} vs {w}");
        }
    }
    assert_eq!(v["receptors"], serde_json::json!(["UVS", "SWS", "MWS", "LWS"]));
    assert_eq!(v["colour_space"], "tetrahedron");
    assert_eq!(v["inputs"]["visual"], "bluetit");
}

#[test]
fn text_says_what_was_assumed_and_gives_units() {
    let out = iridis(&["vision", SPECTRA, "--visual", "ball-python"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8_lossy(&out.stdout);
    for needle in ["Ball python", "Sillman", "ΔS (JND)", "ΔL (JND)", "colour space: line", "Weber fraction 0.1 of LWS"]
    {
        assert!(text.contains(needle), "missing {needle:?} in\n{text}");
    }
}

#[test]
fn a_film_seen_through_spectra_csv_and_through_thinfilm_color_agrees() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("film.csv");
    let stack = "air | water 348nm | air";
    let grid = ["--from", "300nm", "--to", "700nm", "--step", "5nm"];
    let mut args = vec!["thinfilm", "spectrum", "--stack", stack, "--spectra", csv.to_str().unwrap(), "--json"];
    args.extend(grid);
    assert!(iridis(&args).status.success());
    let text = std::fs::read_to_string(&csv).unwrap();
    assert!(text.starts_with("wl,R,T\n300,"), "{}", &text[..40]);
    let a = json_of(&["vision", csv.to_str().unwrap(), "--visual", "bluetit", "--json"]);
    let mut args = vec!["thinfilm", "color", "--stack", stack, "--visual", "bluetit", "--json"];
    args.extend(grid);
    let b = json_of(&args);
    let (sa, sb) = (&a["samples"], &b["vision"]["samples"]);
    for i in 0..2 {
        for k in 0..4 {
            let (x, y) =
                (sa[i]["relative_catches"][k].as_f64().unwrap(), sb[i]["relative_catches"][k].as_f64().unwrap());
            assert!((x - y).abs() < 1e-12, "{x} vs {y}");
        }
    }
    // A lossless film: R + T = 1, so under a grey background the catches of R and T add up to those of white.
    for k in 0..4 {
        let q = sb[0]["quantum_catches"][k].as_f64().unwrap() + sb[1]["quantum_catches"][k].as_f64().unwrap();
        assert!((q - 1.0).abs() < 1e-9, "receptor {k}: {q}");
    }
    // Without --visual the film's JSON has no vision key (its shape is unchanged).
    let c = json_of(&["thinfilm", "color", "--stack", stack, "--json"]);
    assert!(c.get("vision").is_none());
}

#[test]
fn bad_input_is_refused_with_a_reason() {
    assert_fails(&["vision", SPECTRA, "--visual", "cat"], &["unknown visual system 'cat'", "bluetit"]);
    // λmax values typed as the system: the message says where they go (and the command it names runs).
    assert_fails(&["vision", SPECTRA, "--visual", "360,440,550"], &["--lambda-max 360,440,550"]);
    assert!(json_of(&["vision", SPECTRA, "--lambda-max", "360,440,550", "--json"]).get("samples").is_some());
    assert_fails(&["vision", SPECTRA, "--visual", "bluetit", "--densities", "1:2"], &["2 receptor densities for 4"]);
    assert_fails(
        &["vision", SPECTRA, "--visual", "human", "--space", "tetrahedron"],
        &["tetrahedron needs 4", "has 3"],
    );
    assert_fails(&["vision", SPECTRA, "--lambda-max", "344,436", "--oil-droplets", "Q:400,none"], &["'Q:400'"]);
    assert_fails(&["vision", "no/such.csv", "--visual", "bluetit"], &["no/such.csv"]);
    assert_fails(&["vision", SPECTRA], &["no visual system"]);
    // A Weber fraction for an achromatic channel that is not there would change nothing.
    assert_fails(
        &["vision", SPECTRA, "--visual", "bluetit", "--achromatic", "none", "--weber-achromatic", "0.2"],
        &["--weber-achromatic 0.2 would be ignored", "--achromatic none"],
    );
}

#[test]
fn the_achromatic_weber_fraction_divides_delta_l() {
    // ΔL = |ln(A_a/A_b)| / ω_A under neural noise (docs/vision.md, step 8): doubling ω_A halves every ΔL and
    // leaves ΔS.
    let delta = |extra: &[&str]| {
        let mut args = vec!["vision", SPECTRA, "--visual", "bluetit", "--json"];
        args.extend_from_slice(extra);
        let v = json_of(&args);
        let d = v["distances"].as_array().unwrap().clone();
        d.iter().map(|x| (x["delta_s"].as_f64().unwrap(), x["delta_l"].as_f64().unwrap())).collect::<Vec<_>>()
    };
    let (base, doubled) = (delta(&[]), delta(&["--weber-achromatic", "0.2"]));
    assert!(base.iter().any(|d| d.1 > 1.0), "{base:?}");
    for (b, d) in base.iter().zip(&doubled) {
        assert!((d.0 - b.0).abs() < 1e-12 && (2.0 * d.1 - b.1).abs() < 1e-9 * b.1.max(1.0), "{b:?} {d:?}");
    }
}

/// What cannot be computed is said, not left out: one sample has no pair (the distances table had a header and
/// no rows), and a sample that catches no light has no place in the colour space (its line was missing).
#[test]
fn one_sample_and_a_black_sample_are_said_so() {
    let dir = tempfile::tempdir().unwrap();
    let text_of = |name: &str, csv: &str| {
        let path = dir.path().join(name);
        std::fs::write(&path, csv).unwrap();
        let out = iridis(&["vision", path.to_str().unwrap(), "--visual", "bluetit"]);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        String::from_utf8_lossy(&out.stdout).into_owned()
    };
    let one = text_of("one.csv", "wl,a\n300,0.1\n500,0.2\n700,0.3\n");
    assert!(one.contains("1 sample, 300–700 nm"), "{one}");
    assert!(one.contains("distances: none — one sample") && !one.contains("ΔS (JND)"), "{one}");
    let black = text_of("black.csv", "wl,a,b\n300,0,0.1\n500,0,0.2\n700,0,0.3\n");
    assert!(black.contains("a       — (it catches no light: no position)"), "{black}");
    assert!(black.contains("\n  b       ("), "b keeps its position: {black}");
}

/// Spectra in percent read as fractions are said (the catches scale with them, ΔS does not); with --percent,
/// or in fractions, nothing is said, and ΔS is the same either way (the receptor-noise model's log ratios).
#[test]
fn percent_spectra_read_as_fractions_are_said() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("percent.csv");
    std::fs::write(&path, "wl,a,b\n300,10,20\n500,40,30\n700,80,35\n").unwrap();
    let p = path.to_str().unwrap();
    let plain = json_of(&["vision", p, "--visual", "bluetit", "--json"]);
    let notes = plain["notes"].as_array().unwrap();
    assert!(
        notes.iter().any(|n| n.as_str().unwrap().contains("spectrum 'a' reaches 80, read as a reflectance of 8000 %")),
        "{notes:?}"
    );
    let divided = json_of(&["vision", p, "--visual", "bluetit", "--percent", "--json"]);
    assert!(!divided["notes"].as_array().unwrap().iter().any(|n| n.as_str().unwrap().contains("percent")));
    let ds = |v: &serde_json::Value| v["distances"][0]["delta_s"].as_f64().unwrap();
    assert!((ds(&plain) - ds(&divided)).abs() < 1e-9 * ds(&divided), "{} vs {}", ds(&plain), ds(&divided));
    assert!(notes.iter().any(|n| n.as_str().unwrap().ends_with("ΔS and ΔL of the receptor-noise model do not")));
    // Under quantum noise, which depends on the absolute catches, ΔS does change: said so (the note said it did
    // not while ΔS went from 1.57 to 13.7).
    let quantum = |extra: &[&str]| {
        json_of(&[&["vision", p, "--visual", "bluetit", "--noise", "quantum", "--json"][..], extra].concat())
    };
    let (plain_q, divided_q) = (quantum(&[]), quantum(&["--percent"]));
    assert!((ds(&plain_q) - ds(&divided_q)).abs() > 0.1 * ds(&divided_q), "{} vs {}", ds(&plain_q), ds(&divided_q));
    let said = plain_q["notes"].to_string();
    assert!(said.contains("and so do ΔS and ΔL, whose quantum noise depends on the absolute catches"), "{said}");
}

/// The commands that end in an animal's view say what its JND rest on, as `iridis vision` does: the light and
/// the adaptation, and the receptor noise — for the blue tit e_i = ω √(η_LWS/η_i) = 0.1 · √(4/1, 4/2, 4/2, 4/4).
#[test]
fn a_films_colour_as_an_animal_sees_it_states_the_noise() {
    let out = iridis(&["thinfilm", "color", "--stack", "air | water 348nm | air", "--visual", "bluetit"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(
        text.contains("light  D65 (CIE, converted to photon flux) ×1; von Kries to a grey of reflectance 1"),
        "{text}"
    );
    let e: Vec<String> = [4.0f64, 2.0, 2.0, 1.0].iter().map(|r| format!("{:.3}", 0.1 * r.sqrt())).collect();
    let noise = format!("noise  neural noise, Weber fraction 0.1 of LWS, densities 1:2:2:4 → e = {}", e.join(", "));
    assert!(text.contains(&noise), "{noise}\n{text}");
}

/// `brdf vision`'s table has ΔL against the mirror view beside ΔS (it was in --json only), and states the noise.
#[test]
fn brdf_vision_text_has_the_achromatic_difference() {
    let args = ["brdf", "vision", "builtin:sine?size=6um&pixel=100nm", "--visual", "bluetit", "--coherence", "3um"];
    let out = iridis(&args);
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(text.contains("ΔL to +0° (JND)") && text.contains("  noise  neural noise"), "{text}");
    let v = json_of(&[&args[..], &["--json"]].concat());
    let d = v["vision"]["distances"].as_array().unwrap();
    let dl = d.iter().find(|d| d["a"] == "+0°" && d["b"] == "+20°" || d["a"] == "+20°" && d["b"] == "+0°").unwrap();
    let row = text.lines().find(|l| l.trim_start().starts_with("+20°")).unwrap();
    let last: f64 = row.split_whitespace().last().unwrap().parse().unwrap();
    assert!((last - dl["delta_l"].as_f64().unwrap()).abs() <= 0.005, "{row} against {dl}");
}

/// `brdf eval --visual` gives the animal π f_r from 300 nm (its own answer, on the CIE grid, stops at 380 nm and
/// left out 68 % of the blue tit's UV cone). On a 1100 nm sine lit at 30°, the view at 10° on the mirror side
/// receives order −1 at λ = d(sin 30° − sin 10°) = 359 nm, and no other order between 300 and 700 nm (−2 is at
/// 180 nm): what the bird sees there is ultraviolet, the UVS cone's relative catch ≈ 1 (it was 0.89, from the
/// visible leakage alone). The same catches as `brdf vision` in that plane; the XYZ line names its light.
/// (A 3 µm window's lobes, 0.06 wide in u at 380 nm, would let the order's blue end in too.)
#[test]
fn brdf_eval_visual_sees_from_300_nm_as_brdf_vision_does() {
    // 8.8 µm holds 8 periods: one unit cell whose orders are the grating's, each a lobe of the 65 µm window.
    let surface = "builtin:sine?size=8.8um&pixel=100nm";
    let args = ["brdf", "eval", surface, "--light", "30deg", "--view", "10deg,180deg"];
    let out = iridis(&[&args[..], &["--visual", "bluetit"]].concat());
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(text.contains("(of ρ under D65, CIE 1931 observer; a normal-incidence mirror: Y = 1)"), "{text}");
    assert!(text.contains("(receptors UVS, SWS, MWS, LWS; π f_r from 300 to 700 nm):"), "{text}");
    assert!(!text.contains("lies outside"), "{text}");
    let e = json_of(&[&args[..], &["--visual", "bluetit", "--json"]].concat());
    let relative = e["vision"]["samples"][0]["relative_catches"][0].as_f64().unwrap();
    assert!(relative > 0.99, "UVS relative catch {relative}");
    let v = json_of(
        &["brdf", "vision", surface, "--visual", "bluetit", "--light", "30deg", "--views", "10"]
            .iter()
            .chain(&["--azimuth", "0deg", "--json"])
            .collect::<Vec<_>>(),
    );
    let (a, b) = (&e["vision"]["samples"][0]["quantum_catches"], &v["vision"]["samples"][0]["quantum_catches"]);
    for k in 0..4 {
        let (x, y) = (a[k].as_f64().unwrap(), b[k].as_f64().unwrap());
        assert!((x - y).abs() <= 1e-9 * y.abs().max(1e-12), "receptor {k}: brdf eval {x}, brdf vision {y}");
    }
}

/// A flat mirror under a 4 µm window sends nothing 30°–60° away but the round-off of sums that cancel
/// (π f_r ~ 1e-34): no light, ΔS undefined ("—"), where those round-off spectra were given hues 5–11 JND from
/// the mirror's. Nearer (±20°) its window's faint tails are light, and keep their ΔS.
#[test]
fn round_off_views_are_no_light() {
    let dir = tempfile::tempdir().unwrap();
    let flat = dir.path().join("flat.gwy");
    let hf = iridis_surface::HeightField::new(80, 80, 50.0, 50.0, vec![0.0; 80 * 80]).unwrap();
    std::fs::write(&flat, iridis_surface::formats::gwy::write(&hf)).unwrap();
    let j = json_of(&[
        "brdf",
        "vision",
        flat.to_str().unwrap(),
        "--visual",
        "bluetit",
        "--light",
        "0deg",
        "--coherence",
        "4um",
        "--json",
    ]);
    let to_mirror = |view: &str| {
        j["vision"]["distances"]
            .as_array()
            .unwrap()
            .iter()
            .find(|d| (d["a"] == view && d["b"] == "+0°") || (d["a"] == "+0°" && d["b"] == view))
            .map(|d| d["delta_s"].clone())
            .unwrap()
    };
    for far in ["-60°", "-30°", "+30°", "+60°"] {
        assert!(to_mirror(far).is_null(), "{far}: {}", to_mirror(far));
    }
    assert!(to_mirror("+10°").as_f64().unwrap() > 1.0);
}

/// Spectra over 500–510 nm hold ~0 % of the blue tit's UVS sensitivity: its relative catch was the ratio of its
/// tails in sample and background (0.2, a colour of nothing), and is refused; 400–700 nm is analysed with a note.
#[test]
fn a_band_without_a_receptor_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let narrow = dir.path().join("narrow.csv");
    std::fs::write(&narrow, "wavelength_nm,a,b\n500,0.2,0.5\n505,0.2,0.5\n510,0.2,0.5\n").unwrap();
    assert_fails(
        &["vision", narrow.to_str().unwrap(), "--visual", "bluetit"],
        &["500–510 nm, which holds 0.00 % of receptor UVS's sensitivity"],
    );
    let wide = dir.path().join("wide.csv");
    let rows: String = (0..=30).map(|k| format!("{},0.2,{}\n", 400 + 10 * k, 0.2 + 0.01 * k as f64)).collect();
    std::fs::write(&wide, format!("wavelength_nm,a,b\n{rows}")).unwrap();
    let j = json_of(&["vision", wide.to_str().unwrap(), "--visual", "bluetit", "--json"]);
    assert!(j["notes"].to_string().contains("of receptor UVS's sensitivity over 300–700 nm lies outside"), "{j}");
}
