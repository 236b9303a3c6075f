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
    for &(suffix, factor) in units {
        if let Some(num) = t.strip_suffix(suffix) {
            let num = num.trim();
            return match num.parse::<f64>() {
                Ok(v) if v.is_finite() => Ok(v * factor),
                _ => Err(UnitError(format!("'{s}' is not a {kind}: '{num}' is not a finite number"))),
            };
        }
    }
    if t.parse::<f64>().is_ok() {
        Err(UnitError(format!("'{s}' has no unit; write a {kind} with a unit ({accepted}), e.g. '{t}{}'", units[0].0)))
    } else {
        Err(UnitError(format!("'{s}' is not a {kind}; accepted units: {accepted}")))
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

/// `from:to:step` with units on each part, e.g. `1deg:90deg:1deg` or `0nm:2000nm:2nm`; returns the
/// inclusive list of values.
pub fn parse_range(s: &str, parse: fn(&str) -> Result<f64, UnitError>) -> Result<Vec<f64>, UnitError> {
    let parts: Vec<&str> = s.split(':').collect();
    if parts.len() != 3 {
        return Err(UnitError(format!("'{s}' is not a range; write FROM:TO:STEP, e.g. 0nm:2000nm:2nm")));
    }
    let (a, b, step) = (parse(parts[0])?, parse(parts[1])?, parse(parts[2])?);
    if step <= 0.0 || b < a {
        return Err(UnitError(format!("'{s}': need FROM ≤ TO and STEP > 0")));
    }
    let n = ((b - a) / step + 1e-9).floor() as usize + 1;
    if n > 1_000_000 {
        return Err(UnitError(format!("'{s}' has {n} values; at most 1000000")));
    }
    Ok((0..n).map(|i| a + i as f64 * step).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lengths() {
        assert_eq!(parse_length_nm("65nm").unwrap(), 65.0);
        assert!((parse_length_nm("0.43um").unwrap() - 430.0).abs() < 1e-9);
        assert_eq!(parse_length_nm("65µm").unwrap(), 65_000.0);
        assert_eq!(parse_length_nm("65μm").unwrap(), 65_000.0);
        assert_eq!(parse_length_nm("2.5 um").unwrap(), 2_500.0);
        assert!(parse_length_nm("65").unwrap_err().0.contains("no unit"));
        assert!(parse_length_nm("abc").is_err());
        assert!(parse_length_nm("NaNnm").is_err());
        assert!(parse_positive_length_nm("-3nm").is_err());
    }

    #[test]
    fn angles_and_ranges() {
        assert!((parse_angle_rad("75deg").unwrap() - 75f64.to_radians()).abs() < 1e-15);
        assert!((parse_angle_rad("90°").unwrap() - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
        assert_eq!(parse_angle_rad("1rad").unwrap(), 1.0);
        let r = parse_range("1deg:90deg:1deg", parse_angle_rad).unwrap();
        assert_eq!(r.len(), 90);
        let r = parse_range("0nm:2000nm:2nm", parse_length_nm).unwrap();
        assert_eq!((r.len(), r[1000]), (1001, 2000.0));
        assert!(parse_range("0nm:10nm", parse_length_nm).is_err());
    }
}
