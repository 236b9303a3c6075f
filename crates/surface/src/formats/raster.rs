//! PNG and TIFF height maps (via `image`). Grey levels are relative heights: black is the lowest, white the
//! highest; the user supplies the height of white (`--max-height`, black = 0) and the pixel size, or a
//! sidecar gives both ends (what iridis writes). Colour images are reduced to Rec. 709 luma with a
//! warning, because a false-colour AFM rendering does not store height that way.

use std::io::Cursor;

use image::{DynamicImage, ImageFormat, ImageReader, Limits};

use crate::{HeightField, SurfaceError};

use super::{Format, LoadOptions, Sidecar};

/// Decodes an image held in memory: every format the `image` crate reads here (PNG, TIFF, OpenEXR, Radiance HDR),
/// as `reader` names or guesses it. The renderer's textures and glTF images decode through here too: `decode` is
/// generic over the reader, and each crate that called it compiled every decoder again.
pub fn decode(reader: ImageReader<Cursor<&[u8]>>) -> image::ImageResult<DynamicImage> {
    reader.decode()
}

fn bad(fmt: Format, m: impl std::fmt::Display) -> SurfaceError {
    SurfaceError::invalid(format!("not a readable {} height map: {m}", fmt.name().to_uppercase()))
}

pub fn read(
    bytes: &[u8],
    fmt: Format,
    side: Option<&Sidecar>,
    opts: &LoadOptions,
) -> Result<HeightField, SurfaceError> {
    let ifmt = if fmt == Format::Png { ImageFormat::Png } else { ImageFormat::Tiff };
    // Dimensions first, from the header alone, so an absurd size is refused before decoding.
    let (w, h) = ImageReader::with_format(Cursor::new(bytes), ifmt).into_dimensions().map_err(|e| bad(fmt, e))?;
    crate::check_dims(h as usize, w as usize)?;
    let mut limits = Limits::default();
    limits.max_image_width = Some(crate::MAX_DIM as u32);
    limits.max_image_height = Some(crate::MAX_DIM as u32);
    limits.max_alloc = Some((crate::MAX_SAMPLES as u64) * 8);
    let mut reader = ImageReader::with_format(Cursor::new(bytes), ifmt);
    reader.limits(limits);
    let img = decode(reader).map_err(|e| bad(fmt, e))?;
    let (cols, rows) = (img.width() as usize, img.height() as usize);
    crate::check_dims(rows, cols)?;
    let mut warnings = Vec::new();
    let luma = |r: f64, g: f64, b: f64| 0.2126 * r + 0.7152 * g + 0.0722 * b;
    let (values, bits): (Vec<f64>, u32) = match &img {
        DynamicImage::ImageLuma8(b) => (b.as_raw().iter().map(|&v| f64::from(v) / 255.0).collect(), 8),
        DynamicImage::ImageLuma16(b) => (b.as_raw().iter().map(|&v| f64::from(v) / 65535.0).collect(), 16),
        DynamicImage::ImageLumaA8(_) | DynamicImage::ImageLumaA16(_) => {
            warnings.push("the image's alpha channel is ignored".into());
            let l = img.to_luma16();
            (l.as_raw().iter().map(|&v| f64::from(v) / 65535.0).collect(), 16)
        }
        _ => {
            let rgb = img.to_rgb32f();
            let grey = rgb.pixels().all(|p| p.0[0] == p.0[1] && p.0[1] == p.0[2]);
            if !grey {
                warnings.push(format!(
                    "colour image ({:?}): heights taken from its Rec. 709 luma 0.2126 R + 0.7152 G + 0.0722 B; \
                     a false-colour AFM picture does not store height this way — export the scan as greyscale, \
                     .gwy or .npy",
                    img.color()
                ));
            }
            let bits = if matches!(img, DynamicImage::ImageRgb8(_) | DynamicImage::ImageRgba8(_)) { 8 } else { 16 };
            (rgb.pixels().map(|p| luma(f64::from(p.0[0]), f64::from(p.0[1]), f64::from(p.0[2]))).collect(), bits)
        }
    };
    let (lo, hi) = match (opts.max_height_nm, side.and_then(|s| s.height_max_nm)) {
        (Some(m), _) => (0.0, m),
        (None, Some(m)) => (side.and_then(|s| s.height_min_nm).unwrap_or(0.0), m),
        (None, None) => {
            return Err(SurfaceError::invalid(format!(
                "a {} holds relative heights: give --max-height (the height of white, e.g. 250nm; black is 0) and \
                 --pixel-size, or a sidecar FILE.json with {{\"max_height_nm\": 250, \"pixel_size_nm\": 65}}",
                fmt.name().to_uppercase()
            )))
        }
    };
    if !(lo.is_finite() && hi.is_finite()) || hi < lo {
        return Err(SurfaceError::invalid(format!("height range {lo} … {hi} nm is not a finite, increasing range")));
    }
    if hi == lo {
        warnings.push("the height of white equals that of black: the field is flat".into());
    }
    let ((dx, dy), _) = super::pick_pixel(None, side, opts, &format!("a {} image", fmt.name().to_uppercase()))?;
    let heights = values.iter().map(|v| lo + v * (hi - lo)).collect();
    let hf = HeightField::new(rows, cols, dx, dy, heights)?;
    let mut meta = hf.meta.clone();
    meta.z_unit = "relative".into();
    meta.warnings = warnings;
    meta.notes.push(format!(
        "{}-bit {} image, black = {lo} nm, white = {hi} nm (step {:.4} nm)",
        bits,
        fmt.name().to_uppercase(),
        (hi - lo) / ((1u64 << bits) - 1) as f64
    ));
    Ok(hf.with_meta(meta))
}

/// 16-bit greyscale PNG spanning the field's min (black) to max (white); the sidecar keeps the range and
/// pixel size, so a round trip is exact to `(max − min)/65535/2`.
pub fn write_png16(hf: &HeightField) -> Result<Vec<u8>, SurfaceError> {
    let (lo, hi) = hf.min_max();
    let span = if hi > lo { hi - lo } else { 1.0 };
    let px: Vec<u16> =
        hf.heights_nm.iter().map(|h| (((h - lo) / span) * 65535.0).round().clamp(0.0, 65535.0) as u16).collect();
    let img = image::ImageBuffer::<image::Luma<u16>, Vec<u16>>::from_raw(hf.cols as u32, hf.rows as u32, px)
        .ok_or_else(|| SurfaceError::invalid("image buffer size mismatch"))?;
    let mut out = Cursor::new(Vec::new());
    // The PNG encoder by name: `write_to(…, ImageFormat::Png)` would compile every encoder `image` has.
    img.write_with_encoder(image::codecs::png::PngEncoder::new(&mut out))
        .map_err(|e| SurfaceError::invalid(format!("cannot encode PNG: {e}")))?;
    Ok(out.into_inner())
}
