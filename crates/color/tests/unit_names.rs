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
