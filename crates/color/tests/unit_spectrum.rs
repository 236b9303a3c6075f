//! The unit tests of src/spectrum.rs, moved here so that `cargo test` compiles the library once.

use iridis_color::spectrum::*;

#[test]
fn trapezoid_integrates_a_line_exactly() {
    let s = Spectrum::from_fn(400.0, 700.0, 7.0, |w| 2.0 * w + 1.0).unwrap();
    let (a, b) = s.range_nm();
    let exact = (b * b + b) - (a * a + a);
    assert!((s.integrate() - exact).abs() < 1e-9 * exact);
}

#[test]
fn csv_with_header_and_comments() {
    let s = Spectrum::from_csv_str("# a comment\nwavelength,value\n400, 0.5\n410,0.7\n\n420;0.9\n", "t").unwrap();
    assert_eq!(s.wavelengths_nm(), &[400.0, 410.0, 420.0]);
    assert!((s.value_at(405.0) - 0.6).abs() < 1e-12);
    assert_eq!(s.value_at(300.0), 0.5);
}

#[test]
fn csv_errors_name_line_and_value() {
    let e = Spectrum::from_csv_str("400,0.5\n410,abc\n", "f.csv").unwrap_err().to_string();
    assert!(e.contains("f.csv:2") && e.contains("abc"), "{e}");
    let e = Spectrum::from_csv_str("400,0.5\n390,0.1\n", "f.csv").unwrap_err().to_string();
    assert!(e.contains("f.csv:2") && e.contains("increase"), "{e}");
    let e = Spectrum::from_csv_str("400,0.5\n410,NaN\n", "f.csv").unwrap_err().to_string();
    assert!(e.contains("f.csv:2") && e.contains("NaN"), "{e}");
    assert!(Spectrum::from_csv_str("400,0.5\n", "f.csv").is_err());
}

#[test]
fn csv_header_only_on_the_first_line() {
    // A header after a comment is still the first line that counts.
    assert!(Spectrum::from_csv_str("# c\n\nnm,R\n400,0.5\n410,0.7\n", "f.csv").is_ok());
    // A non-numeric row after the data is not a second header.
    let e = Spectrum::from_csv_str("400,0.5\n410,0.7\nnm,R\n420,0.9\n", "f.csv").unwrap_err().to_string();
    assert!(e.contains("f.csv:3") && e.contains("'nm'"), "{e}");
    // Two header lines: the second is an error.
    let e = Spectrum::from_csv_str("nm,R\nunits,percent\n400,0.5\n410,0.7\n", "f.csv").unwrap_err().to_string();
    assert!(e.contains("f.csv:2") && e.contains("'units'"), "{e}");
}

#[test]
fn csv_rows_need_exactly_two_columns() {
    let e = Spectrum::from_csv_str("400,0.5\n410,0.7,0.1\n420,0.9\n", "f.csv").unwrap_err().to_string();
    assert!(e.contains("f.csv:2") && e.contains("found 3"), "{e}");
    let e = Spectrum::from_csv_str("400,0.5\n410\n420,0.9\n", "f.csv").unwrap_err().to_string();
    assert!(e.contains("f.csv:2") && e.contains("found 1"), "{e}");
    // Whitespace-separated with several spaces is still two columns.
    assert!(Spectrum::from_csv_str("400   0.5\n410\t0.7\n", "f.csv").is_ok());
}

#[test]
fn text_rows_skip_comments_and_split_by_the_policy() {
    use iridis_color::spectrum::{text_rows, Separators};
    let fields = |text: &str, s: Separators| -> Vec<(usize, Vec<String>)> {
        text_rows(text, s).map(|r| (r.line, r.fields.iter().map(|f| f.to_string()).collect())).collect()
    };
    // Mixed separators, empty fields dropped; lines counted from 1 with blanks and comments.
    let any = fields("# comment\n\n400, 0.5\n410;0.7\t \n420   0.9\n", Separators::Any);
    assert_eq!(
        any,
        vec![
            (3, vec!["400".into(), "0.5".into()]),
            (4, vec!["410".into(), "0.7".into()]),
            (5, vec!["420".into(), "0.9".into()])
        ]
    );
    // One separator a line: names with spaces stay whole, a missing value stays an empty field.
    let one = fields("wl,sample one,b\n400,,0.5\n410   0.7\n", Separators::OnePerLine);
    assert_eq!(one[0].1, ["wl", "sample one", "b"]);
    assert_eq!(one[1].1, ["400", "", "0.5"]);
    assert_eq!(one[2].1, ["410", "0.7"]);
}
