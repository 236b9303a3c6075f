//! iridis-vision against an independent numpy implementation written from the papers
//! (`tools/gen_vision_fixtures.py`, committed output `tests/fixtures/vision_numpy.json`), which itself
//! reproduces pavo's values (docs/vision.md): templates, droplets, and six analyses — tetrachromats (blue tit,
//! average avian UV eye with quantum noise, an A2 system with droplets), trichromats (human, honeybee in the
//! hexagon) and a dichromat (ball python).

use serde_json::Value;

use iridis_vision::light::{Background, Light};
use iridis_vision::model::{analyse_table, NoiseModel, Options, ReceptorNoise};
use iridis_vision::space::Space;
use iridis_vision::system::VisualSystem;
use iridis_vision::table::{Curve, SpectraTable};
use iridis_vision::template::{alpha_band, beta_band, Chromophore, Droplet, DropletType};

fn fixture() -> Value {
    serde_json::from_str(include_str!("fixtures/vision_numpy.json")).unwrap()
}

fn nums(v: &Value) -> Vec<f64> {
    v.as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect()
}

fn close(a: f64, b: f64, rel: f64, what: &str) {
    assert!((a - b).abs() <= rel * b.abs().max(1e-12), "{what}: iridis {a} vs numpy {b}");
}

#[test]
fn templates_and_droplets_match_the_published_formulas() {
    let f = fixture();
    for t in f["templates"].as_array().unwrap() {
        let l = t["lambda_max_nm"].as_f64().unwrap();
        let c: Chromophore = t["chromophore"].as_str().unwrap().parse().unwrap();
        for ((w, a), b) in nums(&t["wavelength_nm"]).iter().zip(nums(&t["alpha"])).zip(nums(&t["beta"])) {
            close(alpha_band(l, *w, c), a, 1e-12, &format!("α {c} {l} at {w}"));
            close(beta_band(l, *w, c), b, 1e-12, &format!("β {c} {l} at {w}"));
        }
    }
    for d in f["droplets"].as_array().unwrap() {
        let kind: DropletType = d["type"].as_str().unwrap().parse().unwrap();
        let drop = Droplet::from_type(kind, d["lambda_cut_nm"].as_f64().unwrap()).unwrap().unwrap();
        for (w, t) in nums(&d["wavelength_nm"]).iter().zip(nums(&d["transmittance"])) {
            assert!((drop.transmittance(*w) - t).abs() < 1e-13, "{kind:?} at {w}");
        }
    }
}

fn system(id: &str) -> VisualSystem {
    if id == "custom-a2" {
        let drops = [(DropletType::T, 0.0), (DropletType::C, 410.0), (DropletType::Y, 500.0), (DropletType::R, 580.0)]
            .iter()
            .map(|&(t, c)| Droplet::from_type(t, c).unwrap())
            .collect::<Vec<_>>();
        return VisualSystem::from_lambda_max(&[360.0, 440.0, 520.0, 600.0], Chromophore::A2, &drops).unwrap();
    }
    VisualSystem::builtin(id).unwrap()
}

#[test]
fn analyses_match_numpy() {
    let f = fixture();
    let table =
        SpectraTable::parse(include_str!("../../../data/examples/vision_spectra.csv"), "vision_spectra").unwrap();
    let mut worst_s: f64 = 0.0;
    for case in f["cases"].as_array().unwrap() {
        let name = case["name"].as_str().unwrap();
        let sys = system(case["system"].as_str().unwrap());
        let background = match &case["background"] {
            Value::String(s) if s == "none" => Background::None,
            Value::String(s) => {
                let (_, v) = table.samples.iter().find(|(n, _)| n == s).unwrap();
                Background::Spectrum {
                    name: s.clone(),
                    reflectance: Curve::new(table.wavelengths_nm.clone(), v.clone()).unwrap(),
                }
            }
            v => Background::Grey(v.as_f64().unwrap()),
        };
        let noise = if case["per_receptor"].is_array() {
            ReceptorNoise::PerReceptor(nums(&case["per_receptor"]))
        } else {
            ReceptorNoise::Weber {
                weber: case["weber"].as_f64().unwrap(),
                reference: case["reference"].as_u64().unwrap() as usize,
                densities: nums(&case["densities"]),
            }
        };
        let options = Options {
            illuminant: Light::builtin(case["illuminant"].as_str().unwrap()).unwrap(),
            illuminant_scale: case["scale"].as_f64().unwrap_or(1.0),
            background,
            noise: Some(noise),
            noise_model: if case["noise_model"] == "quantum" { NoiseModel::Quantum } else { NoiseModel::Neural },
            space: case["space"].as_str().unwrap().parse::<Space>().unwrap(),
            ..Options::default()
        };
        let a = analyse_table(&table, &sys, &options).unwrap();
        for (s, want) in a.samples.iter().zip(case["samples"].as_array().unwrap()) {
            assert_eq!(s.name, want["name"].as_str().unwrap());
            for key in ["absolute_catches", "quantum_catches", "relative_catches"] {
                let got = match key {
                    "absolute_catches" => &s.absolute_catches,
                    "quantum_catches" => &s.quantum_catches,
                    _ => &s.relative_catches,
                };
                for (g, w) in got.iter().zip(nums(&want[key])) {
                    close(*g, w, 1e-9, &format!("{name}: {} {key}", s.name));
                }
            }
            close(s.achromatic_catch.unwrap(), want["achromatic_catch"].as_f64().unwrap(), 1e-9, name);
            let pos = &s.coordinates.as_ref().unwrap().position;
            for (g, w) in pos.iter().zip(nums(&want["position"])) {
                assert!((g - w).abs() < 1e-10, "{name}: {} position {g} vs {w}", s.name);
            }
        }
        for (d, want) in a.distances.iter().zip(case["distances"].as_array().unwrap()) {
            assert_eq!((d.a.as_str(), d.b.as_str()), (want["a"].as_str().unwrap(), want["b"].as_str().unwrap()));
            let (ds, dl) = (want["delta_s"].as_f64().unwrap(), want["delta_l"].as_f64().unwrap());
            let (gs, gl) = (d.delta_s.unwrap(), d.delta_l.unwrap());
            assert!((gs - ds).abs() <= 1e-8 * ds.max(1.0), "{name}: ΔS {} {}: {gs} vs {ds}", d.a, d.b);
            assert!((gl - dl).abs() <= 1e-8 * dl.max(1.0), "{name}: ΔL {} {}: {gl} vs {dl}", d.a, d.b);
            worst_s = worst_s.max((gs - ds).abs());
            if d.b == "uv_blue_copy" && d.a == "uv_blue" {
                assert_eq!(gs, 0.0, "{name}: identical spectra");
            }
        }
    }
    // Written out so that docs/vision.md can quote it: `cargo test -p iridis-vision -- --nocapture`.
    println!("largest |ΔS(iridis) − ΔS(numpy)| over the six cases: {worst_s:.2e} JND");
}
