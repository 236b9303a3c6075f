//! The unit tests of src/scene_toml.rs, moved here so that `cargo test` compiles the library once.

use iridis_render::error::RenderError;
use iridis_render::material::*;
use iridis_render::scene::Scene;
use iridis_render::scene_toml::*;
use std::path::Path;

fn parse(t: &str) -> Result<Scene, RenderError> {
    parse_scene(t, "test.toml", Path::new("."))
}

/// The message of a scene that must be refused.
fn parse_err(t: &str) -> String {
    parse(t).unwrap_err().to_string()
}

const OK: &str = r#"
[output]
size = [32, 24]
[camera]
position = [0, 0, 5]
[[light]]
kind = "directional"
direction = [0, 1, 1]
[materials.grey]
kind = "lambert"
[[object]]
kind = "sphere"
radius = 1
material = "grey"
"#;

#[test]
fn a_minimal_scene_parses() {
    let s = parse(OK).unwrap();
    assert_eq!((s.output.width, s.output.height), (32, 24));
    assert_eq!(s.spheres.len(), 1);
}

#[test]
fn errors_name_line_and_key() {
    let e = parse_err(&OK.replace("radius = 1", "radius = \"big\""));
    assert!(e.starts_with("test.toml:13:") && e.contains("invalid type") && e.contains("radius = \"big\""), "{e}");
    let e = parse_err(&OK.replace("radius = 1", "radus = 1"));
    assert!(e.contains("radus") && e.contains("test.toml:13"), "{e}");
    let e = parse_err(&OK.replace("material = \"grey\"", "material = \"gray\""));
    assert!(e.contains("test.toml:11:") && e.contains("\"gray\" is not defined"), "{e}");
    let e = parse_err(&OK.replace("radius = 1\n", ""));
    assert!(e.contains("missing key `radius`"), "{e}");
    let e = parse_err(&OK.replace("kind = \"lambert\"", "kind = \"lambert\"\ntexture = \"nope\""));
    assert!(e.contains("no texture of that name"), "{e}");
    let e = parse_err(&OK.replace("[camera]\nposition = [0, 0, 5]", "[camera]\nposition = [0, 0, 5\n"));
    assert!(e.starts_with("test.toml:"), "{e}");
}

#[test]
fn keys_of_another_material_kind_are_refused() {
    let e = parse_err(
        &OK.replace("kind = \"lambert\"", "kind = \"lambert\"\ncolor = [1, 0, 0]\nstack = \"air | water 300nm | air\""),
    );
    assert!(e.starts_with("test.toml:12:"), "{e}");
    assert!(e.contains("`stack` is not a key of a lambert material") && e.contains("belongs to thinfilm"), "{e}");
    assert!(e.contains("takes color, texture"), "{e}");
    // A thin film with a diffraction key; an inline table names the line of the key too.
    let film = "[camera]\nposition = [0, 0, 5]\n[materials]\nf = { kind = \"thinfilm\", stack = \"air | water 300nm | air\", w_diffuse = 0.5 }\n";
    let e = parse_err(film);
    assert!(
        e.starts_with("test.toml:4:")
            && e.contains("`w_diffuse` is not a key of a thinfilm material")
            && e.contains("belongs to diffraction"),
        "{e}"
    );
    // `roughness` is shared by microfacet and thinfilm, not by lambert.
    let e = parse_err(&OK.replace("kind = \"lambert\"", "kind = \"lambert\"\n\nroughness = 0.2"));
    assert!(e.starts_with("test.toml:12:") && e.contains("belongs to microfacet and thinfilm"), "{e}");
    // The keys of the kind itself are fine.
    parse(&OK.replace("kind = \"lambert\"", "kind = \"microfacet\"\nroughness = 0.2\nmetallic = 1")).unwrap();
}

#[test]
fn rough_film_keys_are_checked() {
    let film = |extra: &str| {
        OK.replace("kind = \"lambert\"", &format!("kind = \"thinfilm\"\nstack = \"air | water 348nm | Si\"\n{extra}"))
    };
    let s = parse(&film("roughness = \"25nm\"\ncorrelation = \"300nm\"")).unwrap();
    let Material::ThinFilm(f) = &s.materials[0] else { panic!("a thin film") };
    let r = f.rough.expect("rough");
    assert_eq!((r.roughness.sigma_nm(), r.roughness.tau_nm()), (25.0, 300.0));
    for (extra, needle) in [
        ("roughness = \"25nm\"", "`roughness` needs `correlation`"),
        ("correlation = \"300nm\"", "`correlation` needs `roughness`"),
        ("roughness = 0.3\ncorrelation = \"300nm\"", "a length with its unit"),
        ("roughness = \"25\"\ncorrelation = \"300nm\"", "`roughness` = \"25\""),
        ("roughness = \"-5nm\"\ncorrelation = \"300nm\"", "must be finite and > 0"),
        ("roughness = \"200nm\"\ncorrelation = \"300nm\"", "rms facet slope"),
        ("roughness = \"25nm\"\ncorrelation = \"100nm\"", "radius of curvature"),
        ("roughness = \"25nm\"\ncorrelation = \"300nm\"\ntransmission = true", "no transmitted part"),
    ] {
        let e = parse_err(&film(extra));
        assert!(e.starts_with("test.toml:") && e.contains(needle), "{extra}: {e}");
    }
    let e = parse_err(
        &(film("roughness = \"25nm\"\ncorrelation = \"300nm\"\nbase = \"under\"")
            + "[materials.under]\nkind = \"lambert\"\n"),
    );
    assert!(e.contains("takes no `base` material"), "{e}");
    let e = parse_err(&OK.replace("kind = \"lambert\"", "kind = \"microfacet\"\nroughness = \"25nm\""));
    assert!(e.contains("a microfacet roughness is a number in [0, 1]"), "{e}");
}

#[test]
fn texture_kinds_are_checked() {
    let t =
        OK.replace("kind = \"lambert\"", "kind = \"lambert\"\ntexture = \"n\"") + "[textures.n]\nkind = \"noise\"\n";
    let e = parse_err(&t);
    assert!(e.contains("a color texture is needed here") && e.contains("grey texture"), "{e}");
}

/// `[output]` takes what `--size` and `--spp` take (a 0 × 0 image failed only at the PNG encoder after the
/// render, 10⁵ × 10⁵ began a 120 GB render, `spp = 0` wrote a black image), and a background that is a colour.
#[test]
fn output_settings_have_the_limits_of_the_flags() {
    let with = |extra: &str| OK.replace("size = [32, 24]", extra);
    for (bad, said) in [
        ("size = [0, 24]", "`size` = [0, 24]: width and height must be from 1 to 16384"),
        ("size = [32, 16385]", "`size` = [32, 16385]"),
        ("size = [32, 24]\nspp = 0", "`spp` = 0: use 1 to 4096 samples per pixel"),
        ("size = [32, 24]\nspp = 4097", "`spp` = 4097"),
        ("size = [32, 24]\nbackground = [-0.1, 0, 0]", "`background` must be three finite linear sRGB values ≥ 0"),
    ] {
        let e = parse_err(&with(bad));
        assert!(e.contains(said), "{bad}: {e}");
    }
    // The limits themselves are allowed.
    let s = parse(&with("size = [1, 16384]\nspp = 4096\nbackground = [0, 0.5, 1]")).unwrap();
    assert_eq!((s.output.width, s.output.height, s.output.spp), (1, 16384, 4096));
}

/// TOML's `nan` and `inf` are numbers, but no position, colour or intensity is one (a sphere centred at nan was
/// drawn nowhere without a word); a reflectance lies in [0, 1] (a Lambertian colour of 3 returned three times
/// the light it received); a checker needs squares.
#[test]
fn numbers_are_finite_and_reflectances_lie_in_0_1() {
    for (from, to, said) in [
        ("radius = 1", "radius = 1\ncenter = [nan, 0, 0]", "test.toml:14: [[object]] #1: `center` holds NaN"),
        ("size = [32, 24]", "size = [32, 24]\nexposure = inf", "test.toml:4: [output]: `exposure` holds inf"),
        ("direction = [0, 1, 1]", "direction = [0, -inf, 1]", "[[light]] #1: `direction` holds -inf"),
        (
            "kind = \"lambert\"",
            "kind = \"lambert\"\ncolor = [1.2, 0.5, 0.5]",
            "[materials.grey]: `color` = [1.2, 0.5, 0.5]",
        ),
        (
            "kind = \"lambert\"",
            "kind = \"lambert\"\ncolor = [0.5, -0.1, 0.5]",
            "a reflectance has each channel in [0, 1]",
        ),
    ] {
        let e = parse_err(&OK.replace(from, to));
        assert!(e.contains(said), "{to}: {e}");
    }
    let textured = |t: &str| {
        OK.replace("kind = \"lambert\"", "kind = \"lambert\"\ntexture = \"t\"")
            .replace("[materials.grey]", &format!("{t}\n[materials.grey]"))
    };
    let e = parse_err(&textured("[textures.t]\nkind = \"checker\"\na = [2, 2, 2]"));
    assert!(e.contains("[textures.t]: `a` = [2.0, 2.0, 2.0]: a reflectance"), "{e}");
    let e = parse_err(&textured("[textures.t]\nkind = \"checker\"\nn = 0"));
    assert!(e.contains("[textures.t]: `n` = 0: squares per unit of u and v must be > 0"), "{e}");
    let e = parse_err(&textured("[textures.t]\nkind = \"scales\"\nedge = [0, 0, 1.5]"));
    assert!(e.contains("`edge` = [0.0, 0.0, 1.5]"), "{e}");
    // The limits are allowed.
    parse(&textured("[textures.t]\nkind = \"checker\"\na = [1, 1, 1]\nb = [0, 0, 0]\nn = 0.5")).unwrap();
}

/// An svt that thins a layer by more than it holds clamps it at 0 nm: a note says where, α < (1 − d/d_rel)/2,
/// or α > (1 + d/|d_rel|)/2 for a negative d_rel (d = d_avg + d_rel(2α − 1), Sussenbach eq. 4.3); within the
/// layer, none.
#[test]
fn an_svt_deeper_than_a_layer_is_noted() {
    let film = |d_rel: &str| {
        let text = OK.replace(
            "[materials.grey]\nkind = \"lambert\"",
            &format!(
                "[textures.g]\nkind = \"gradient\"\nfrom = 0.0\nto = 1.0\nalong = \"v\"\n[materials.grey]\n\
                 kind = \"thinfilm\"\nstack = \"air | gasoline 300nm | water 220nm | air\"\nsvt = \"g\"\n\
                 d_rel = \"{d_rel}\""
            ),
        );
        parse(&text).unwrap().notes
    };
    let notes = film("250nm");
    let n = notes.iter().find(|n| n.contains("|d_rel| = 250 nm")).unwrap_or_else(|| panic!("{notes:?}"));
    assert!(n.contains("thinnest layer (220 nm)") && n.contains("below 0.060"), "{n}");
    // A negative d_rel thins where the texture is high: above (1 + 220/250)/2 = 0.940.
    let notes = film("-250nm");
    assert!(notes.iter().any(|n| n.contains("above 0.940")), "{notes:?}");
    assert!(!film("200nm").iter().any(|n| n.contains("d_rel")));
}

/// A negative radiance in the environment was clipped to 0 silently (the same on the CPU and the GPU).
#[test]
fn a_negative_environment_radiance_is_refused() {
    let sky = |zenith: &str| OK.to_string() + &format!("[environment]\nkind = \"sky\"\nzenith = {zenith}\n");
    assert!(parse(&sky("[0.2, 0.35, 0.8]")).is_ok());
    let e = parse_err(&sky("[-100.0, 0.35, 0.8]"));
    assert!(e.contains("`zenith`") && e.contains("must be ≥ 0"), "{e}");
}
