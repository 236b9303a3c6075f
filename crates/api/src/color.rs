//! A colour as every front end reports it (the JSON "colour" shape of docs/json.md): XYZ, xyY, CIELAB against
//! the illuminant's white, linear and display sRGB, hex.

use iridis_color::tonemap::hex;
use iridis_color::{Lab, ToneMap, Xyz};
use serde_json::json;

/// Everything a person wants to know about one colour, as JSON (keys fixed by docs/json.md, "Shape: colour").
pub fn colour_report(xyz: Xyz, white: Xyz) -> serde_json::Value {
    let xyy = xyz.to_xyy();
    let lab = Lab::from_xyz(xyz, white);
    let tone = ToneMap::default();
    let rgb8 = tone.to_rgb8(xyz);
    json!({
        "XYZ": xyz.to_array(),
        "xyY": [xyy.x, xyy.y, xyy.big_y],
        "Lab": lab.to_array(),
        "linear_srgb": xyz.to_linear_srgb(),
        "srgb": tone.to_display(xyz),
        "hex": hex(rgb8),
    })
}
