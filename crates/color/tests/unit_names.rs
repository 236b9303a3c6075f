//! The unit tests of src/names.rs (the `names!` macro).

use iridis_color::{Illuminant, Observer};

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Edge {
    Rising,
    Falling,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Signal {
    Dc,
    Step(Edge),
}

// With the `else` clause: `FromStr` too, its error built from the unknown text (here named `text`).
iridis_color::names! {
    Edge {
        Rising => "rising" | "up",
        Falling => "falling" | "down",
    }
    else |text| -> String { format!("edge '{text}': expected rising or falling") }
}

// Without it: `name` and `from_name` only.
iridis_color::names! {
    Signal {
        Dc => "DC" | "constant",
        Step(Edge::Rising) => "step-up" | "rising",
        Step(Edge::Falling) => "step-down" | "falling",
    }
}

#[test]
fn canonical_names_are_given_as_written() {
    assert_eq!(Signal::Dc.name(), "DC");
    assert_eq!(Signal::Step(Edge::Rising).name(), "step-up");
    assert_eq!(Signal::Step(Edge::Falling).name(), "step-down");
}

#[test]
fn canonical_names_and_aliases_are_read() {
    assert_eq!(Signal::from_name("DC"), Some(Signal::Dc));
    assert_eq!(Signal::from_name("constant"), Some(Signal::Dc));
    assert_eq!(Signal::from_name("step-up"), Some(Signal::Step(Edge::Rising)));
    assert_eq!(Signal::from_name("falling"), Some(Signal::Step(Edge::Falling)));
}

#[test]
fn case_and_surrounding_space_are_ignored() {
    assert_eq!(Signal::from_name("dc"), Some(Signal::Dc));
    assert_eq!(Signal::from_name("  Constant\t"), Some(Signal::Dc));
    assert_eq!(Signal::from_name("\nSTEP-DOWN "), Some(Signal::Step(Edge::Falling)));
}

#[test]
fn other_text_is_none() {
    for text in ["", " ", "d c", "step", "step-up-", "rising edge", "ｄｃ"] {
        assert_eq!(Signal::from_name(text), None, "{text:?}");
    }
}

#[test]
fn every_name_reads_back_as_its_value() {
    for o in Observer::ALL {
        assert_eq!(Observer::from_name(o.name()), Some(o));
    }
    for i in Illuminant::ALL {
        assert_eq!(Illuminant::from_name(i.name()), Some(i));
    }
    // The spellings the CIE and colour-science use for the observers.
    assert_eq!(Observer::from_name("2deg"), Some(Observer::Cie1931));
    assert_eq!(Observer::from_name("CIE1964"), Some(Observer::Cie1964));
}

#[test]
fn the_else_clause_parses_the_names() {
    assert_eq!("rising".parse(), Ok(Edge::Rising));
    assert_eq!(" DOWN\t".parse(), Ok(Edge::Falling));
}

#[test]
fn the_else_clause_builds_the_error_from_the_text_as_given() {
    assert_eq!("sideways".parse::<Edge>(), Err("edge 'sideways': expected rising or falling".to_string()));
    // Untrimmed: the message quotes what was typed.
    assert_eq!(" step ".parse::<Edge>(), Err("edge ' step ': expected rising or falling".to_string()));
    // A crate's own error type, as color's enums use it.
    let error = "1900".parse::<Observer>().unwrap_err();
    assert_eq!((error.kind, error.given.as_str()), ("observer", "1900"));
    assert_eq!(error.to_string(), "unknown observer '1900'; expected one of: 1931, 1964");
    assert_eq!(
        "D75".parse::<Illuminant>().unwrap_err().to_string(),
        "unknown illuminant 'D75'; expected one of: d65, d50, a, e"
    );
}
