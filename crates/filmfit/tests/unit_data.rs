//! The unit tests of src/data.rs, moved here so that `cargo test` compiles the library once.

use iridis_filmfit::data::*;
use iridis_filmfit::Quantity;

fn read_r(text: &str) -> Reading {
    read(text, "x.csv", &ReadOptions::new(Quantity::R), &|_| Err("no".into())).unwrap()
}

#[test]
fn reads_and_refuses() {
    let m = Measured::from_csv(
        "# test\nwavelength_nm,R,sR\n400,0.1,0.01\n500,0.2,0.01\n",
        "x.csv",
        Quantity::R,
        Some("sR"),
    )
    .unwrap();
    assert_eq!(m.wavelength_nm, [400.0, 500.0]);
    assert_eq!(m.values, [0.1, 0.2]);
    assert_eq!(m.sigma, Some(vec![0.01, 0.01]));
    let e = Measured::from_csv("wavelength_nm,T,X\n400,0.1,3\n", "x.csv", Quantity::R, None).unwrap_err().to_string();
    assert!(e.contains("no measured column 'R' for --quantity R") && e.contains("x.csv, line 1"), "{e}");
    let e = Measured::from_csv("wavelength_nm,R\n400,0.1\n500,abc\n600,0.3\n", "x.csv", Quantity::R, None)
        .unwrap_err()
        .to_string();
    assert!(e.contains("line 3") && e.contains("'abc'"), "{e}");
    let e = Measured::from_csv("energy?,R,X\n400,0.1,1\n", "x.csv", Quantity::R, None).unwrap_err().to_string();
    assert!(e.contains("no wavelength column") && e.contains("--columns"), "{e}");
    let m = Measured::from_csv("wavelength_nm,psi,delta\n400,30,100\n", "e.csv", Quantity::PsiDelta, None).unwrap();
    assert_eq!(m.values, [30.0, 100.0]);
}

#[test]
fn headers_separators_and_units_in_common_forms() {
    // The forms issue 29 met, and more: all read the same two rows (400 nm: 0.25, 500 nm: 0.30).
    for text in [
        "wavelength_nm,R\n400,0.25\n500,0.30\n",
        "Wavelength (nm),Reflectance\n400,0.25\n500,0.30\n",
        "Wavelength (nm)\tReflectance\n400\t0.25\n500\t0.30\n",
        "lambda [nm]; R\n400;0,25\n500;0,30\n",
        "400 0.25\n500 0.30\n",
        "Instrument: XY-2000\nDate: 2026-11-25\n\"Wavelength (nm)\",\"R\"\n400,0.25\n500,0.30\nEnd of data\n",
        "Wavelength (µm),R\n0.4,0.25\n0.5,0.30\n",
        "wavelength_um,R\n0.4,0.25\n0.5,0.30\n",
        "Wavelength   R\n0.4 0.25\n0.5 0.30\n",
        "nm,%R\n400,25\n500,30\n",
        "Wavelength (nm),Reflectance (%)\n400,25.0\n500,30.0\n",
        "Wavelength (nm)  Reflectance  Dark\n400  25.0  1\n500  30.0  1\n",
    ] {
        let r = read_r(text);
        assert_eq!(r.data.wavelength_nm.len(), 2, "{text}");
        for (got, want) in r.data.wavelength_nm.iter().zip([400.0, 500.0]) {
            assert!((got - want).abs() < 1e-9, "{text}: {:?} {:?}", r.data.wavelength_nm, r.notes);
        }
        for (got, want) in r.data.values.iter().zip([0.25, 0.30]) {
            assert!((got - want).abs() < 1e-12, "{text}: {:?} {:?}", r.data.values, r.notes);
        }
    }
    // Percent is stated, with its reason.
    let r = read_r("Wavelength (nm),Reflectance\n400,11.5\n500,45.0\n");
    assert!(r.percent && r.notes.iter().any(|n| n.contains("45 > 1: read as percent")), "{:?}", r.notes);
    let r = read_r("Wavelength (nm),R (%)\n400,0.5\n500,0.9\n");
    assert!(r.percent && r.notes.iter().any(|n| n.contains("header 'R (%)'")), "{:?}", r.notes);
    assert!((r.data.values[0] - 0.005).abs() < 1e-15);
    let r = read_r("nm\tR\n400\t0.5\n");
    assert!(!r.percent && r.notes[0].starts_with("tab-separated, header on line 1"), "{:?}", r.notes);
    // Fractions are said too: an anti-reflection coating's R in percent (under 1) reads as fractions, and its
    // fit was a confident wrong film without a word.
    assert!(r.notes.iter().any(|n| n.starts_with("R read as fractions (no '%' in the header, none above 1.5")));
    let r = read_r("wavelength_nm,R\n450,0.341\n550,0.12\n650,0.29\n");
    let said = r.notes.iter().find(|n| n.starts_with("R read as fractions")).unwrap_or_else(|| panic!("{:?}", r.notes));
    assert!(!said.contains("anti-reflection") && said.ends_with("--percent if they are percent"), "{said}");
    let r = read_r("wavelength_nm,R\n450,1.1431\n550,0.12\n");
    assert!(r.notes.iter().any(|n| n.contains("above 1, which a fraction cannot be")), "{:?}", r.notes);
    let r = read_r("wavelength_nm,R\n450,0.0034\n550,0.0012\n");
    assert!(
        r.notes.iter().any(|n| n.contains("how a good anti-reflection coating's reads in percent")),
        "{:?}",
        r.notes
    );
    // Metres and photon energies.
    let r = read_r("4e-7,0.1\n5e-7,0.2\n");
    assert!((r.data.wavelength_nm[0] - 400.0).abs() < 1e-6 && r.notes.iter().any(|n| n.contains("metres")));
    let r = read_r("Energy (eV),R\n2.479684,0.1\n");
    assert!((r.data.wavelength_nm[0] - 500.0).abs() < 1e-3, "{:?}", r.data.wavelength_nm);
}

#[test]
fn columns_percent_and_window_can_be_chosen() {
    let text = "wl,R_sample,R_ref,sigma\n400,20,90,0.5\n500,30,91,0.5\n600,40,92,0.5\n700,45,93,0.5\n";
    let mut o = ReadOptions::new(Quantity::R);
    o.columns = Some("wl,R_ref".into());
    let r = read(text, "x.csv", &o, &|_| Err("no".into())).unwrap();
    assert_eq!(r.columns, ["wl", "R_ref"]);
    assert!((r.data.values[0] - 0.90).abs() < 1e-12 && r.percent);
    o.columns = Some("1,2".into());
    o.from_nm = Some(450.0);
    o.to_nm = Some(650.0);
    o.spread = Some(("sigma".into(), Spread::Sigma));
    let r = read(text, "x.csv", &o, &|_| Err("no".into())).unwrap();
    assert_eq!(r.data.wavelength_nm, [500.0, 600.0]);
    assert_eq!(r.data.values, [0.30, 0.40]);
    assert_eq!(r.data.sigma, Some(vec![0.005, 0.005])); // percent, like the values
    assert!(r.notes.iter().any(|n| n == "2 of 4 rows outside the wavelength window left out"), "{:?}", r.notes);
    o.percent = Some(false);
    o.spread = None;
    let r = read(text, "x.csv", &o, &|_| Err("no".into())).unwrap();
    assert_eq!(r.data.values, [30.0, 40.0]);
    assert!(r.notes.iter().any(|n| n.contains("outside 0–1")), "{:?}", r.notes);
    // Bad choices say what to do.
    o.columns = Some("wl".into());
    let e = read(text, "x.csv", &o, &|_| Err("no".into())).unwrap_err().to_string();
    assert!(e.contains("give 2 columns, wavelength then R"), "{e}");
    o.columns = Some("wl,R_x".into());
    let e = read(text, "x.csv", &o, &|_| Err("no".into())).unwrap_err().to_string();
    assert!(e.contains("no column 'R_x'"), "{e}");
    // Two R-like columns and no choice: the error lists the columns and points to --columns.
    let mut o = ReadOptions::new(Quantity::R);
    let e = read(text, "x.csv", &o, &|_| Err("no".into())).unwrap_err().to_string();
    assert!(e.contains("no measured column 'R'") && e.contains("R_ref") && e.contains("--columns"), "{e}");
    o.columns = Some("1,2".into());
    o.from_nm = Some(800.0);
    let e = read(text, "x.csv", &o, &|_| Err("no".into())).unwrap_err().to_string();
    assert!(e.contains("no wavelength of the file"), "{e}");
    // ψ and Δ are angles: a percent setting would change nothing, so it is refused.
    let mut o = ReadOptions::new(Quantity::PsiDelta);
    o.percent = Some(true);
    let e = read("wavelength_nm,psi,delta\n400,30,100\n", "e.csv", &o, &|_| Err("no".into())).unwrap_err();
    assert!(e.to_string().contains("--percent would be ignored: ψ and Δ are angles"), "{e}");
}

#[test]
fn weights_are_inverse_variances() {
    // w = 1/σ²: w = 10⁴ is σ = 0.01, w = 2500 is σ = 0.02.
    let text = "wavelength_nm,R,w\n400,0.1,10000\n500,0.2,2500\n";
    let m = Measured::from_csv_with(text, "x.csv", Quantity::R, Some(("w", Spread::Weight))).unwrap();
    assert_eq!(m.sigma, Some(vec![0.01, 0.02]));
    let e =
        Measured::from_csv_with("wavelength_nm,R,w\n400,0.1,0\n", "x.csv", Quantity::R, Some(("w", Spread::Weight)))
            .unwrap_err()
            .to_string();
    assert!(e.contains("weight 0 must be") && e.contains("line 2"), "{e}");
    let mut o = ReadOptions::new(Quantity::R);
    o.spread = Some(("wt".into(), Spread::Weight));
    let e = read(text, "x.csv", &o, &|_| Err("no such file".into())).unwrap_err().to_string();
    assert!(
        e.contains("--weights 'wt' is neither a number, a column") && e.contains("nor a file (no such file)"),
        "{e}"
    );
    // A separate file, row by row; ψ/Δ take two weights.
    let mut m =
        Measured::from_csv("wavelength_nm,psi,delta\n400,30,100\n450,31,101\n", "e.csv", Quantity::PsiDelta, None)
            .unwrap();
    m.set_weights_from_csv("wavelength_nm,w_psi,w_delta\n400,400,4\n450,100,1\n", "w.csv", Quantity::PsiDelta).unwrap();
    assert_eq!(m.sigma, Some(vec![0.05, 0.5, 0.1, 1.0]));
    let e = m.set_weights_from_csv("wavelength_nm,w\n400,1\n", "w.csv", Quantity::PsiDelta).unwrap_err().to_string();
    assert!(e.contains("1 rows of weights for 2 measured wavelengths"), "{e}");
    let e =
        m.set_weights_from_csv("wavelength_nm,w\n400,1\n460,1\n", "w.csv", Quantity::PsiDelta).unwrap_err().to_string();
    assert!(e.contains("w.csv, line 3: wavelength 460 nm, but the measurement has 450 nm"), "{e}");
}

#[test]
fn a_material_that_does_not_cover_the_range_is_named() {
    let stack = iridis_thinfilm::Stack::parse("air | SiO2 100nm | Si").unwrap();
    let e = check_coverage(&stack, 400.0, 1000.0).unwrap_err().to_string();
    assert!(
        e.contains("the measurement spans 400–1000 nm, but substrate 'si' has data for 206.6–826.6 nm only")
            && e.contains("si-green (250–1450 nm) covers it")
            && e.contains("--from 400nm --to 826.6nm"),
        "{e}"
    );
    assert!(check_coverage(&stack, 400.0, 800.0).is_ok());
}

#[test]
fn arrays_are_read_by_the_rules_of_a_file_that_need_no_file() {
    let (wl, r) = (vec![400.0, 500.0, 600.0, 700.0], vec![10.0, 20.0, 30.0, 40.0]);
    // Percent: said, the values and a σ array are divided by 100 and it is noted; not said, refused (an array
    // has no header to say it), where a file's values above 1.5 would be read as percent.
    let mut o = ReadOptions::new(Quantity::R);
    let e = read_arrays(wl.clone(), r.clone(), None, &o).unwrap_err().to_string();
    assert!(e.contains("the values reach 40 > 1: if they are percent, say percent=True"), "{e}");
    o.percent = Some(true);
    let got = read_arrays(wl.clone(), r.clone(), Some(vec![1.0; 4]), &o).unwrap();
    assert_eq!(got.data.values, [0.1, 0.2, 0.3, 0.4]);
    assert_eq!(got.data.sigma.as_deref(), Some(&[0.01; 4][..]));
    assert!(got.percent && got.notes.iter().any(|n| n == "R in percent (--percent): divided by 100"), "{got:?}");
    // The window, as for a file: 500–600 nm keeps two of four, and says so.
    o.from_nm = Some(500.0);
    o.to_nm = Some(600.0);
    let got = read_arrays(wl.clone(), r.clone(), None, &o).unwrap();
    assert_eq!((got.data.wavelength_nm, got.data.values), (vec![500.0, 600.0], vec![0.2, 0.3]));
    assert!(got.notes.iter().any(|n| n == "2 of 4 rows outside the wavelength window left out"), "{:?}", got.notes);
    // A weight as a number is σ = 1/√w (in the values' unit, percent here); a column name or two σ are refused.
    o.spread = Some(("4".into(), Spread::Weight));
    let got = read_arrays(wl.clone(), r.clone(), None, &o).unwrap();
    assert_eq!(got.data.sigma.as_deref(), Some(&[0.005; 2][..]));
    let e = read_arrays(wl.clone(), r.clone(), Some(vec![1.0; 4]), &o).unwrap_err().to_string();
    assert!(e.contains("weight given twice"), "{e}");
    o.spread = Some(("R_err".into(), Spread::Sigma));
    let e = read_arrays(wl.clone(), r.clone(), None, &o).unwrap_err().to_string();
    assert!(e.contains("--sigma 'R_err': with arrays give a number"), "{e}");
    o.spread = None;
    o.columns = Some("1,2".into());
    let e = read_arrays(wl, r, None, &o).unwrap_err().to_string();
    assert!(e.contains("--columns '1,2' would be ignored"), "{e}");
}

/// A column chosen by number whose header names another quantity is fitted as asked, and the reading says so
/// (`--columns 1,3` on `wl,R,T` fitted the T column as R without a word).
#[test]
fn a_chosen_column_named_for_another_quantity_is_said() {
    let text = "wl,R,T\n400,0.3,0.6\n500,0.35,0.55\n600,0.4,0.5\n";
    let note = |q: Quantity, columns: &str| {
        let mut o = ReadOptions::new(q);
        o.columns = Some(columns.into());
        let r = read(text, "x.csv", &o, &|_| Err("no".into())).unwrap();
        r.notes.iter().find(|n| n.contains("though its name says another quantity")).cloned()
    };
    let n = note(Quantity::R, "1,3").expect("T fitted as R is said");
    assert!(n.starts_with("column 'T' is fitted as R (--quantity R)"), "{n}");
    assert_eq!(note(Quantity::R, "1,2"), None);
    assert_eq!(note(Quantity::T, "wl,T"), None);
    assert!(note(Quantity::T, "1,2").expect("R fitted as T is said").starts_with("column 'R' is fitted as T"));
}
