//! What the test files share: the fixtures made by independent implementations (tools/gen_color_fixtures.py).

use iridis_color::Spectrum;
use serde_json::Value;

/// `tests/fixtures/NAME`, parsed.
pub fn fixture(name: &str) -> Value {
    let path = format!("{}/tests/fixtures/{name}", env!("CARGO_MANIFEST_DIR"));
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// A fixture's three-number array.
pub fn arr3(v: &Value) -> [f64; 3] {
    let a: Vec<f64> = v.as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
    [a[0], a[1], a[2]]
}

/// colour_science.json's spectra: each entry (name, illuminant, observer and colour-science's colours) with its
/// reflectance spectrum on the fixture's wavelength grid.
pub fn spectra(doc: &Value) -> Vec<(&Value, Spectrum)> {
    let numbers = |v: &Value| -> Vec<f64> { v.as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect() };
    let wl = numbers(&doc["wavelengths_nm"]);
    let entries = doc["spectra"].as_array().unwrap();
    entries
        .iter()
        .map(|e| (e, Spectrum::new(wl.clone(), numbers(&doc["spectrum_values"][e["name"].as_str().unwrap()])).unwrap()))
        .collect()
}
