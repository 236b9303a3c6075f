//! The one parser for quantities that people type: lengths (`65nm`, `0.43um`, `65µm`, `2.5 um`, `1mm`) and
//! angles (`75deg`, `75°`, `1.2rad`), and ranges of them (`1deg:90deg:1deg`). Lengths come back in
//! nanometres, angles in radians (`docs/PHYSICS.md`). A bare number is refused: the unit is the point.

/// A quantity that could not be parsed; the message says which units are accepted.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{0}")]
pub struct UnitError(pub String);

const LENGTH_UNITS: &[(&str, f64)] =
    &[("nm", 1.0), ("um", 1e3), ("µm", 1e3), ("μm", 1e3), ("micron", 1e3), ("mm", 1e6), ("pm", 1e-3)];
const ANGLE_UNITS: &[(&str, f64)] =
    &[("deg", std::f64::consts::PI / 180.0), ("°", std::f64::consts::PI / 180.0), ("mrad", 1e-3), ("rad", 1.0)];

fn parse_with(s: &str, kind: &str, units: &[(&str, f64)], accepted: &str) -> Result<f64, UnitError> {
    let t = s.trim();
    let article = if kind.starts_with(['a', 'e', 'i', 'o', 'u']) { "an" } else { "a" };
    for &(suffix, factor) in units {
        if let Some(num) = t.strip_suffix(suffix) {
            let num = num.trim();
            return match num.parse::<f64>() {
                Ok(v) if v.is_finite() => Ok(v * factor),
                _ => Err(UnitError(format!("'{s}' is not {article} {kind}: '{num}' is not a finite number"))),
            };
        }
    }
    match t.parse::<f64>() {
        Ok(v) if v.is_finite() => Err(UnitError(format!(
            "'{s}' has no unit; write {article} {kind} with a unit ({accepted}), e.g. '{t}{}'",
            units[0].0
        ))),
        // `nan`, `inf` parse as numbers but are no quantity: suggesting 'nannm' would mislead.
        Ok(_) => Err(UnitError(format!(
            "'{s}' is not {article} {kind}: write a finite number with a unit ({accepted}), e.g. '{}'",
            example_of(units[0].0)
        ))),
        Err(_) => Err(UnitError(format!("'{s}' is not {article} {kind}; accepted units: {accepted}"))),
    }
}

/// An example value of the kind whose first unit is `unit`, for messages.
fn example_of(unit: &str) -> &'static str {
    if unit == "nm" {
        "65nm"
    } else {
        "30deg"
    }
}

/// A length in nanometres from `65nm`, `0.43um`, `65µm`, `2.5 um`, `1mm`.
pub fn parse_length_nm(s: &str) -> Result<f64, UnitError> {
    parse_with(s, "length", LENGTH_UNITS, "nm, um, µm, mm")
}

/// An angle in radians from `75deg`, `75°`, `1.2rad`, `20mrad`.
pub fn parse_angle_rad(s: &str) -> Result<f64, UnitError> {
    parse_with(s, "angle", ANGLE_UNITS, "deg, °, rad, mrad")
}

/// A strictly positive length.
pub fn parse_positive_length_nm(s: &str) -> Result<f64, UnitError> {
    let v = parse_length_nm(s)?;
    if v > 0.0 {
        Ok(v)
    } else {
        Err(UnitError(format!("'{s}' must be a positive length")))
    }
}

/// The most values a `FROM:TO:STEP` range gives.
pub const MAX_RANGE_VALUES: usize = 1_000_000;

/// `from:to:step` with units on each part, e.g. `1deg:90deg:1deg` or `0nm:2000nm:2nm`; returns the
/// inclusive list of values (FROM and TO both in it: a STEP that does not divide TO − FROM is refused).
pub fn parse_range(s: &str, parse: fn(&str) -> Result<f64, UnitError>) -> Result<Vec<f64>, UnitError> {
    let parts: Vec<&str> = s.split(':').collect();
    if parts.len() != 3 {
        // The example is in the quantity this range is of (an angle range is not shown in nm).
        let example = if parse("1deg").is_ok() { "0deg:80deg:1deg" } else { "0nm:2000nm:2nm" };
        return Err(UnitError(format!("'{s}' is not a range; write FROM:TO:STEP, e.g. {example}")));
    }
    let (a, b, step) = (parse(parts[0])?, parse(parts[1])?, parse(parts[2])?);
    if step <= 0.0 || b < a {
        return Err(UnitError(format!("'{s}': need FROM ≤ TO and STEP > 0")));
    }
    // Counted in f64 first: a count past usize (a tiny STEP) would wrap to an empty list.
    if (b - a) / step + 1.0 > MAX_RANGE_VALUES as f64 {
        return Err(UnitError(format!(
            "'{s}' has {} values, more than {MAX_RANGE_VALUES}; give a larger STEP",
            crate::spectrum::short_number(((b - a) / step).floor() + 1.0)
        )));
    }
    // Both ends are values: a STEP that does not divide the range would stop short of TO without a word.
    let n = crate::spectrum::whole_steps(a, b, step).map_err(|steps| {
        UnitError(format!(
            "'{s}' does not end on TO: (TO − FROM)/STEP = {steps:.3} is not a whole number, so the last value would \
             fall short of {}; give a STEP that divides TO − FROM",
            parts[1].trim()
        ))
    })? + 1;
    Ok((0..n).map(|i| a + i as f64 * step).collect())
}

/// `x` without the noise of a unit round trip (`30deg` → rad → deg gives 29.999999999999996): rounded to 12
/// significant digits, which is far below any figure iridis reports and far above f64's 16.
pub fn tidy(x: f64) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return x;
    }
    format!("{x:.11e}").parse().unwrap_or(x)
}

/// An angle in degrees from radians, [`tidy`]: what a person wrote (`30`, not `29.999999999999996`).
pub fn degrees(rad: f64) -> f64 {
    tidy(rad.to_degrees())
}

/// A length as a person writes it on the command line (`1100nm`, `6.4um`, `2.5mm`): nm up to 5 µm (periods
/// are written in nm), µm up to 5 mm, at most 6 significant digits, no trailing zeros.
pub fn format_length(nm: f64) -> String {
    let (v, unit) = match nm.abs() {
        a if a >= 5e6 => (nm / 1e6, "mm"),
        a if a >= 5e3 => (nm / 1e3, "um"),
        _ => (nm, "nm"),
    };
    let v = format!("{v:.5e}").parse::<f64>().unwrap_or(v);
    // Past a kilometre in exponent form (still read back), not hundreds of digits.
    if v.abs() >= 1e6 {
        format!("{v:e}{unit}")
    } else {
        format!("{v}{unit}")
    }
}

/// An angle as a person writes it (`30deg`, `6.5deg`), from radians.
pub fn format_angle(rad: f64) -> String {
    format!("{}deg", format!("{:.5e}", rad.to_degrees()).parse::<f64>().unwrap_or(rad.to_degrees()))
}
