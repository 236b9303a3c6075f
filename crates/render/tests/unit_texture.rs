//! The unit tests of src/texture.rs, moved here so that `cargo test` compiles the library once.

use iridis_render::texture::*;

#[test]
fn grey_and_vector_kinds_are_checked() {
    let colour =
        image::DynamicImage::ImageRgb8(image::RgbImage::from_fn(4, 4, |x, _| image::Rgb([x as u8 * 60, 0, 9])));
    let err = Texture::from_image(colour.clone(), TexKind::Grey, "c.png").unwrap_err().to_string();
    assert!(err.contains("colour image") && err.contains("grey"), "{err}");
    let grey = image::DynamicImage::ImageLuma8(image::GrayImage::from_fn(4, 4, |x, _| image::Luma([x as u8 * 60])));
    let err = Texture::from_image(grey.clone(), TexKind::Vector, "g.png").unwrap_err().to_string();
    assert!(err.contains("vector"), "{err}");
    let t = Texture::from_image(grey, TexKind::Grey, "g.png").unwrap();
    // Texel centres reproduce the stored values (linear, not sRGB-decoded).
    let v = t.sample([2.5 / 4.0, 0.5 / 4.0]);
    assert!((v[0] - 120.0 / 255.0).abs() < 1e-6, "{v:?}");
    let c = Texture::from_image(colour, TexKind::Color, "c.png").unwrap();
    let v = c.sample([1.5 / 4.0, 0.5 / 4.0]);
    assert!((v[0] - iridis_color::convert::srgb_decode(60.0 / 255.0)).abs() < 1e-6);
}

#[test]
fn noise_stays_in_range_and_varies() {
    let vals: Vec<f64> = (0..500).map(|i| fbm(i as f64 * 0.137, i as f64 * 0.071, 4, 3)).collect();
    assert!(vals.iter().all(|v| (0.0..=1.0).contains(v)));
    let (lo, hi) = vals.iter().fold((1.0f64, 0.0f64), |(l, h), &v| (l.min(v), h.max(v)));
    assert!(hi - lo > 0.3);
}
