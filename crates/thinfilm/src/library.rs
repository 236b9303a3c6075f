//! The built-in library of materials (constants of Sussenbach's thesis and measured data in
//! `data/materials/`, provenance in `data/materials/README.md`) and materials read from files
//! ([`crate::nkfile`] parses them): [`Material::builtin`], [`Material::library`], [`Material::from_file`]; and
//! the medium of the stack syntax (`water`, `n=1.38`, `cauchy:…`, `file:PATH`) read into a material.

use num_complex::Complex64;

use crate::error::ThinFilmError;
use crate::material::Material;
use crate::nkfile;

/// A measured material of `data/materials/`: its file name (named in messages) and its text, compiled in.
macro_rules! data_file {
    ($name:literal) => {
        Builtin::File($name, include_str!(concat!("../../../data/materials/", $name)))
    };
}

/// The built-in library: `(names, description, source)`. Constants are the values of Sussenbach's thesis
/// (water 1.33, gasoline 1.4, asphalt 1.635, glass 1.5); measured data are in `data/materials/`
/// (provenance in `data/materials/README.md`).
const LIBRARY: &[(&[&str], &str, Builtin)] = &[
    (&["air", "vacuum"], "n = 1 (vacuum; air's 1.0003 is below the model's accuracy)", Builtin::Const(1.0)),
    (&["water"], "n = 1.33, constant (Sussenbach's soap film, Figure 3.8)", Builtin::Const(1.33)),
    (&["glass"], "n = 1.5, constant (Sussenbach section 5.1)", Builtin::Const(1.5)),
    (&["gasoline", "oil"], "n = 1.4, constant (Sussenbach section 5.1)", Builtin::Const(1.4)),
    (&["asphalt"], "n = 1.635, constant (Sussenbach section 5.1)", Builtin::Const(1.635)),
    (&["bk7", "n-bk7"], "SCHOTT N-BK7 Sellmeier, 300–2500 nm", data_file!("bk7_schott.yml")),
    (
        &["fused-silica", "fused_silica", "silica", "sio2"],
        "fused silica, Malitson 1965 Sellmeier, 210–6700 nm",
        data_file!("sio2_malitson.yml"),
    ),
    (&["keratin"], "bird keratin, Leertouwer et al. 2011 Cauchy, 380–780 nm", data_file!("keratin_leertouwer.yml")),
    (&["chitin"], "butterfly chitin, Leertouwer et al. 2011 Cauchy, 380–780 nm", data_file!("chitin_leertouwer.yml")),
    (&["mgf2"], "MgF2 ordinary ray, Dodge 1984 Sellmeier, 200–7000 nm", data_file!("mgf2_dodge_o.yml")),
    (
        // A deposited film covers the whole visible band (and is what coatings are made of); bulk rutile
        // starts at 430 nm, so it is not the default.
        &["tio2"],
        "TiO2 thin film (200 nm on glass), Sarkar et al. 2019, 300–1690 nm",
        data_file!("tio2_sarkar.yml"),
    ),
    (
        &["rutile", "tio2-rutile"],
        "TiO2 (rutile) ordinary ray, Devore 1951, 430–1530 nm",
        data_file!("tio2_devore_o.yml"),
    ),
    (&["si", "silicon"], "crystalline Si, Aspnes & Studna 1983, 207–827 nm", data_file!("si_aspnes.yml")),
    (&["au", "gold"], "gold, Johnson & Christy 1972, 188–1937 nm", data_file!("au_johnson.yml")),
    (&["ag", "silver"], "silver, Johnson & Christy 1972, 188–1937 nm", data_file!("ag_johnson.yml")),
    (&["cu", "copper"], "copper, Johnson & Christy 1972, 188–1937 nm", data_file!("cu_johnson.yml")),
    (&["al", "aluminium", "aluminum"], "aluminium, Rakić 1995, 207–2066 nm", data_file!("al_rakic.yml")),
    (
        &["al2o3", "alumina"],
        "Al2O3 film (amorphous, pulsed-laser deposited), Boidin et al. 2016, 300–2498 nm",
        data_file!("al2o3_boidin.yml"),
    ),
    (
        &["si3n4", "silicon-nitride"],
        "Si3N4 (CVD film), Philipp 1973 Sellmeier, 207–1240 nm",
        data_file!("si3n4_philipp.yml"),
    ),
    (&["sio2-film"], "SiO2 film (ion-assisted e-beam), Gao et al. 2013, 252–1250 nm", data_file!("sio2_gao.yml")),
    (&["ito", "in2o3-sno2"], "ITO film (72 nm on BK7), König et al. 2014, 252–1000 nm", data_file!("ito_konig.yml")),
    (&["hfo2", "hafnia"], "HfO2 film (e-beam), Franta et al. 2015, 250–2497 nm", data_file!("hfo2_franta.yml")),
    (&["ta2o5"], "Ta2O5 film (e-beam), Franta et al. 2015, 253–2497 nm", data_file!("ta2o5_franta.yml")),
    (&["zno"], "ZnO film, Aguilar et al. 2019, 300–2500 nm", data_file!("zno_aguilar.yml")),
    (&["zns"], "ZnS (cubic), Ozaki & Adachi 1993, 221–1033 nm", data_file!("zns_ozaki.yml")),
    (&["cr", "chromium"], "chromium, Johnson & Christy 1974, 188–1937 nm", data_file!("cr_johnson.yml")),
    (&["ti", "titanium"], "titanium, Johnson & Christy 1974, 188–1937 nm", data_file!("ti_johnson.yml")),
    (&["ni", "nickel"], "nickel, Johnson & Christy 1974, 188–1937 nm", data_file!("ni_johnson.yml")),
    (&["pt", "platinum"], "platinum, Rakić et al. 1998 (Lorentz–Drude fit), 248–2499 nm", data_file!("pt_rakic.yml")),
    (&["w", "tungsten"], "tungsten, Rakić et al. 1998 (Lorentz–Drude fit), 248–2499 nm", data_file!("w_rakic.yml")),
    (&["ge", "germanium"], "germanium, Nunley et al. 2016, 188–2480 nm", data_file!("ge_nunley.yml")),
    (&["inp"], "InP, Adachi 1989 (model dielectric function), 207–2407 nm", data_file!("inp_adachi.yml")),
    (&["gaas"], "GaAs, Papatryfonos et al. 2021, 260–1879 nm", data_file!("gaas_papatryfonos.yml")),
    (&["si-green", "si-green2008"], "crystalline Si, Green 2008, 250–1450 nm", data_file!("si_green.yml")),
    (&["pmma"], "PMMA, Szczurowski 2013 Sellmeier, 405–1083 nm", data_file!("pmma_szczurowski.yml")),
    (&["pdms"], "PDMS (Sylgard 184, 10:1), Gupta et al. 2019, 300–1690 nm", data_file!("pdms_gupta.yml")),
    (
        &["melanin", "eumelanin"],
        "eumelanin, Stavenga et al. 2015 Cauchy + exponential κ, 380–780 nm",
        data_file!("melanin_stavenga.yml"),
    ),
    (
        // Birefringent: 1.83 in the plane of the biogenic plates, 1.46 normal to them; no dispersion data.
        &["guanine"],
        "guanine crystal plates, n = 1.83 in-plane (Land 1972; Jordan et al. 2012), constant",
        Builtin::Const(1.83),
    ),
];

#[derive(Debug, Clone, Copy)]
enum Builtin {
    Const(f64),
    File(&'static str, &'static str),
}

impl Material {
    /// A material of the built-in library by name (case-insensitive), e.g. `water`, `BK7`, `Au`.
    pub fn builtin(name: &str) -> Option<Self> {
        let key = name.trim().to_ascii_lowercase();
        let (names, _, b) = LIBRARY.iter().find(|(names, _, _)| names.contains(&key.as_str()))?;
        let m = match *b {
            Builtin::Const(v) => Material::constant(names[0], Complex64::new(v, 0.0)).ok()?,
            // The built-in files are part of the build and covered by the tests; a parse failure here
            // would be caught there.
            Builtin::File(file, text) => {
                let mut m = nkfile::parse_yaml(text, &format!("data/materials/{file}")).ok()?;
                m.name = names[0].to_string();
                m
            }
        };
        Some(m)
    }

    /// The library: each entry's names and a one-line description with its source.
    pub fn library() -> Vec<(Vec<&'static str>, &'static str)> {
        LIBRARY.iter().map(|(n, d, _)| (n.to_vec(), *d)).collect()
    }

    /// Reads a file: `.yml`/`.yaml` in the refractiveindex.info format, anything else as CSV
    /// (`wavelength_nm, n, κ`).
    pub fn from_file(path: &std::path::Path) -> Result<Self, ThinFilmError> {
        let shown = path.display().to_string();
        let text = std::fs::read_to_string(path)
            .map_err(|e| ThinFilmError::Unreadable { path: shown.clone(), message: e.to_string() })?;
        let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase();
        if ext == "yml" || ext == "yaml" {
            nkfile::parse_yaml(&text, &shown)
        } else {
            nkfile::parse_csv(&text, &shown)
        }
    }

    /// The library's description of this material ("gold, Johnson & Christy 1972, 188–1937 nm, from the
    /// built-in library") when it came from [`Material::builtin`]; `None` for constants and files.
    pub fn library_source(&self) -> Option<String> {
        LIBRARY
            .iter()
            .find(|(names, _, b)| names[0] == self.name && matches!(b, Builtin::File(..)))
            .map(|(_, d, _)| format!("{d}, from the built-in library"))
    }
}

/// Parses one medium: a library name, `n=…` or `file:PATH`. A file that cannot be read is
/// [`ThinFilmError::Unreadable`]; the other errors' messages carry no position (the stack adds it).
pub(crate) fn parse_material(t: &str) -> Result<Material, ThinFilmError> {
    let invalid = |m: String| ThinFilmError::Invalid(m);
    if let Some(v) = t.strip_prefix("n=") {
        let z = parse_complex(v).ok_or_else(|| {
            invalid(format!("'{v}' is not a refractive index; write n=1.38 or n=0.2+3.4i (κ after the sign, with i)"))
        })?;
        return Material::constant(t, z);
    }
    for (prefix, f) in [
        ("cauchy:", Material::cauchy as fn(String, &[f64]) -> Result<Material, ThinFilmError>),
        ("sellmeier:", Material::sellmeier),
    ] {
        if let Some(list) = t.strip_prefix(prefix) {
            let c: Vec<f64> = list
                .split(',')
                .map(|x| x.trim().parse::<f64>().map_err(|_| invalid(format!("'{x}' in {t} is not a number"))))
                .collect::<Result<_, _>>()?;
            return f(t.to_string(), &c);
        }
    }
    if let Some(p) = t.strip_prefix("file:") {
        if p.is_empty() {
            return Err(invalid("file: needs a path, e.g. file:data/materials/au_johnson.yml".into()));
        }
        return Material::from_file(std::path::Path::new(p));
    }
    Material::builtin(t).ok_or_else(|| {
        let names: Vec<&str> = Material::library().iter().map(|(n, _)| n[0]).collect();
        invalid(format!("unknown material '{t}'; known: {}; or n=1.38, n=0.2+3.4i, file:PATH", names.join(", ")))
    })
}

/// `1.38`, `0.2+3.4i`, `0.2-3.4i` (refused later as gain), `0.2+3.4j`.
fn parse_complex(v: &str) -> Option<Complex64> {
    let v = v.trim();
    let num = |s: &str| s.parse::<f64>().ok().filter(|x| x.is_finite());
    if let Some(body) = v.strip_suffix('i').or_else(|| v.strip_suffix('j')) {
        // Find the sign that separates the real and imaginary parts (not an exponent's sign).
        let bytes = body.as_bytes();
        let split = (1..bytes.len())
            .rev()
            .find(|&i| (bytes[i] == b'+' || bytes[i] == b'-') && !matches!(bytes[i - 1], b'e' | b'E'))?;
        let re = num(&body[..split])?;
        let im_txt = &body[split..];
        let im = if im_txt == "+" || im_txt == "-" { None } else { num(im_txt) }?;
        Some(Complex64::new(re, im))
    } else {
        num(v).map(|re| Complex64::new(re, 0.0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_builtin_loads_and_covers_its_range() {
        for (names, _) in Material::library() {
            let m = Material::builtin(names[0]).unwrap_or_else(|| panic!("{} does not load", names[0]));
            let (lo, hi) = m.range_nm();
            let mid = if hi.is_finite() { 0.5 * (lo + hi) } else { 550.0 };
            let n = m.index_at(mid).unwrap();
            assert!(n.re > 0.0 && n.im >= 0.0, "{}: {n}", names[0]);
        }
    }

    #[test]
    fn published_values() {
        // N-BK7: nd = 1.5168 at 587.56 nm (SCHOTT data sheet).
        let bk7 = Material::builtin("BK7").unwrap();
        assert!((bk7.index_at(587.56).unwrap().re - 1.5168).abs() < 5e-5);
        // Fused silica (Malitson): n = 1.4585 at 587.6 nm.
        let sio2 = Material::builtin("fused silica".replace(' ', "-").as_str()).unwrap();
        assert!((sio2.index_at(587.6).unwrap().re - 1.4585).abs() < 1e-4);
        // Gold, Johnson & Christy: the tabulated row 0.6595 µm → 0.14 + 3.697i exactly.
        let au = Material::builtin("Au").unwrap();
        let n = au.index_at(659.5).unwrap();
        assert!((n.re - 0.14).abs() < 1e-12 && (n.im - 3.697).abs() < 1e-12);
        // Halfway between rows 0.6168 (0.21, 3.272) and 0.6595 (0.14, 3.697): linear interpolation.
        let n = au.index_at(0.5 * (616.8 + 659.5)).unwrap();
        assert!((n.re - 0.175).abs() < 1e-12 && (n.im - 3.4845).abs() < 1e-12);
        // Rutile (Devore): n² = 5.913 + 0.2441/(λ² − 0.0803) at 0.5 µm.
        let rutile = Material::builtin("rutile").unwrap();
        let expect = (5.913f64 + 0.2441 / (0.25 - 0.0803)).sqrt();
        assert!((rutile.index_at(500.0).unwrap().re - expect).abs() < 1e-12);
        // TiO2 film (Sarkar et al.): the table's rows at 550 nm and 330 nm (absorbing below ~365 nm).
        let tio2 = Material::builtin("TiO2").unwrap();
        assert!((tio2.index_at(550.0).unwrap() - Complex64::new(2.164358, 0.0)).norm() < 1e-12);
        assert!((tio2.index_at(330.0).unwrap() - Complex64::new(2.747194, 0.179225)).norm() < 1e-12);
        // The database's tabulated rows, read back exactly: ITO (König et al.) 0.25157 µm, Cr (Johnson &
        // Christy) 0.582 µm; Si3N4 (Philipp) Sellmeier at 0.6328 µm.
        for (name, wl, want) in
            [("ITO", 251.57, Complex64::new(2.31717213, 0.57780161)), ("Cr", 582.0, Complex64::new(3.22, 3.30))]
        {
            let n = Material::builtin(name).unwrap().index_at(wl).unwrap();
            assert!((n - want).norm() < 1e-12, "{name} at {wl} nm: {n}");
        }
        let si3n4 = Material::builtin("Si3N4").unwrap().index_at(632.8).unwrap().re;
        let l2 = 0.6328f64.powi(2);
        assert!((si3n4 - (1.0 + 2.8939 * l2 / (l2 - 0.13967f64.powi(2))).sqrt()).abs() < 1e-12, "{si3n4}");
        // Melanin (Stavenga et al. 2015): 1.648 + 23 700/λ², κ = 0.56 e^{−λ/270}; n 1.7–1.8 in the visible.
        let mel = Material::builtin("melanin").unwrap();
        let n = mel.index_at(500.0).unwrap();
        assert!(
            (n.re - (1.648 + 23700.0 / 250000.0)).abs() < 1e-12
                && (n.im - 0.56 * (-500.0f64 / 270.0).exp()).abs() < 1e-6
        );
        // Chitin (Leertouwer et al.): 1.517 + 8800/λ² with λ in nm.
        let chitin = Material::builtin("chitin").unwrap();
        assert!((chitin.index_at(500.0).unwrap().re - (1.517 + 8800.0 / 250000.0)).abs() < 1e-12);
    }

    #[test]
    fn coating_materials_cover_300_to_1000_nm_where_the_source_does() {
        // Issue 29: what people coat with, from 300 nm (UV that birds and insects see) to 1000 nm.
        for name in [
            "Al2O3", "Si3N4", "ITO", "HfO2", "Ta2O5", "ZnO", "ZnS", "Cr", "Ti", "Ni", "Pt", "W", "Ge", "InP", "PDMS",
            "si-green",
        ] {
            let m = Material::builtin(name).unwrap();
            let (lo, hi) = m.range_nm();
            assert!(lo <= 300.0 + 1e-9 && hi >= 1000.0 - 1e-9, "{name}: {lo}–{hi} nm");
            for wl in [300.0, 450.0, 650.0, 1000.0] {
                let n = m.index_at(wl).unwrap();
                assert!(n.re > 0.0 && n.im >= 0.0, "{name} at {wl} nm: {n}");
            }
        }
        // Where the source starts later, the range says so: GaAs from 260 nm (covers), PMMA from 405 nm.
        assert!(Material::builtin("GaAs").unwrap().range_nm().0 <= 300.0);
        assert!(Material::builtin("PMMA").unwrap().index_at(350.0).is_err());
    }

    #[test]
    fn no_extrapolation() {
        let si = Material::builtin("Si").unwrap();
        let e = si.index_at(900.0).unwrap_err();
        assert!(matches!(e, ThinFilmError::OutOfRange { .. }), "{e}");
        assert!(e.to_string().contains("Si") || e.to_string().contains("si"), "{e}");
        let rutile = Material::builtin("rutile").unwrap();
        assert!(rutile.index_at(400.0).is_err());
    }
}
