//! The JSON sidecar: units for formats that have none (`.npy`, images, bare text). Looked up as
//! `FILE.EXT.json` (what iridis writes) or `FILE.json`. Keys, all optional:
//!
//! ```json
//! { "pixel_size_nm": 65,            // or [dx, dy]
//!   "height_unit": "nm",            // unit of the stored values (.npy, text): nm, um, µm, m, Å
//!   "height_min_nm": -120.5,        // images: height of black …
//!   "height_max_nm": 130.0,         // … and of full white
//!   "max_height_nm": 250 }          // images: shorthand for black = 0, white = this
//! ```

use std::path::{Path, PathBuf};

use serde_json::{json, Value};

use crate::{HeightField, SurfaceError};

/// A parsed sidecar.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Sidecar {
    pub path: PathBuf,
    pub pixel_size_nm: Option<(f64, f64)>,
    pub height_unit: Option<String>,
    pub height_min_nm: Option<f64>,
    pub height_max_nm: Option<f64>,
}

impl Sidecar {
    /// The sidecar of `path`, if one exists; a sidecar that exists but is malformed is an error.
    pub fn find(path: &Path) -> Result<Option<Sidecar>, SurfaceError> {
        if path.extension().is_some_and(|e| e.eq_ignore_ascii_case("json")) {
            return Ok(None);
        }
        let candidates = [super::sidecar_path(path), path.with_extension("json")];
        for c in candidates {
            if c.is_file() {
                let text = std::fs::read_to_string(&c)
                    .map_err(|e| SurfaceError::Io { path: c.display().to_string(), err: e })?;
                return Sidecar::parse(&text, &c).map(Some);
            }
        }
        Ok(None)
    }

    /// Parses sidecar JSON; `path` is for messages.
    pub fn parse(text: &str, path: &Path) -> Result<Sidecar, SurfaceError> {
        let bad = |m: String| SurfaceError::Format { path: path.display().to_string(), message: m };
        let v: Value = serde_json::from_str(text).map_err(|e| bad(format!("sidecar is not valid JSON: {e}")))?;
        let obj = v.as_object().ok_or_else(|| bad("sidecar must be a JSON object".into()))?;
        let num = |k: &str| -> Result<Option<f64>, SurfaceError> {
            match obj.get(k) {
                None | Some(Value::Null) => Ok(None),
                Some(x) => match x.as_f64() {
                    Some(f) if f.is_finite() => Ok(Some(f)),
                    _ => Err(bad(format!("'{k}' must be a finite number, got {x}"))),
                },
            }
        };
        let pixel = match obj.get("pixel_size_nm") {
            None | Some(Value::Null) => None,
            Some(Value::Array(a)) if a.len() == 2 => match (a[0].as_f64(), a[1].as_f64()) {
                (Some(x), Some(y)) => Some((x, y)),
                _ => return Err(bad("'pixel_size_nm' must be a number or [dx, dy]".into())),
            },
            Some(x) => match x.as_f64() {
                Some(p) => Some((p, p)),
                None => return Err(bad("'pixel_size_nm' must be a number or [dx, dy]".into())),
            },
        };
        if let Some((dx, dy)) = pixel {
            crate::check_pixel(dx, dy).map_err(|e| bad(e.to_string()))?;
        }
        let height_unit = match obj.get("height_unit") {
            None | Some(Value::Null) => None,
            Some(Value::String(s)) => {
                if super::unit_to_nm(s).is_none() {
                    return Err(bad(format!("'height_unit' '{s}' is not a length unit (nm, um, µm, m, Å)")));
                }
                Some(s.clone())
            }
            Some(x) => return Err(bad(format!("'height_unit' must be a string, got {x}"))),
        };
        let max = num("height_max_nm")?.or(num("max_height_nm")?);
        let min = num("height_min_nm")?.or(if num("max_height_nm")?.is_some() { Some(0.0) } else { None });
        Ok(Sidecar {
            path: path.to_path_buf(),
            pixel_size_nm: pixel,
            height_unit,
            height_min_nm: min,
            height_max_nm: max,
        })
    }

    pub fn pixel_nm(&self) -> Option<(f64, f64)> {
        self.pixel_size_nm
    }

    /// Scale from stored values to nm, if the sidecar gives a unit.
    pub fn height_scale(&self) -> Option<f64> {
        self.height_unit.as_deref().and_then(super::unit_to_nm)
    }

    /// The sidecar iridis writes beside a field; with `range`, the heights of black and white for images.
    pub fn for_field(hf: &HeightField, range: bool) -> Sidecar {
        let (lo, hi) = hf.min_max();
        Sidecar {
            path: PathBuf::new(),
            pixel_size_nm: Some((hf.dx_nm, hf.dy_nm)),
            height_unit: Some("nm".into()),
            height_min_nm: range.then_some(lo),
            height_max_nm: range.then_some(hi),
        }
    }

    pub fn to_json(&self) -> String {
        let mut v = json!({ "written_by": format!("iridis-surface {}", env!("CARGO_PKG_VERSION")) });
        if let Some((dx, dy)) = self.pixel_size_nm {
            v["pixel_size_nm"] = if dx == dy { json!(dx) } else { json!([dx, dy]) };
        }
        if let Some(u) = &self.height_unit {
            v["height_unit"] = json!(u);
        }
        if let Some(x) = self.height_min_nm {
            v["height_min_nm"] = json!(x);
        }
        if let Some(x) = self.height_max_nm {
            v["height_max_nm"] = json!(x);
        }
        serde_json::to_string_pretty(&v).unwrap_or_default() + "\n"
    }
}
