//! What the test files share: the fixtures made by independent implementations (tmm, refractiveindex.info's
//! formulas; each with the script in tools/ that wrote it).

use iridis_thinfilm::Complex64;
use serde_json::Value;

/// `tests/fixtures/NAME`, parsed.
pub fn fixture(name: &str) -> Value {
    let path = format!("{}/tests/fixtures/{name}", env!("CARGO_MANIFEST_DIR"));
    serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// A complex number written `[re, im]`.
pub fn complex(v: &Value) -> Complex64 {
    Complex64::new(v[0].as_f64().unwrap(), v[1].as_f64().unwrap())
}
