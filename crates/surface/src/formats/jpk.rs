//! JPK Instruments `.jpk` images: a TIFF (read with the `tiff` crate) whose first page is a palette
//! thumbnail carrying the scan geometry, and whose other pages are the channels, each with JPK's private
//! tags (JPKImageSpec 2.0, the numbers AFMReader's configuration uses):
//!
//! | tag | meaning |
//! |---|---|
//! | 32834, 32835 / 32838, 32839 | grid length along u (fast), v (slow) in m / in pixels (first page) |
//! | 32848, 32849 | channel name, retrace flag (0 = trace) |
//! | 32896, 32897 | number of conversion slots, name of the default slot |
//! | 32912 + 48 n | slot n: name; + 18 its unit, + 19 scaling type, + 20 multiplier, + 21 offset |
//!
//! A value is `raw · multiplier + offset` of the default slot (`LinearScaling`; `NullScaling` keeps raw
//! counts); the multipliers are stored relative to the raw data, not chained. Row 0 is the last stored line,
//! as AFMReader (with its default `flip_image`) shows it.

use std::io::Cursor;

use tiff::decoder::{Decoder, DecodingResult, Limits};
use tiff::tags::Tag;

use crate::{HeightField, SurfaceError};

use super::channel::{self, ChannelInfo};
use super::{LoadOptions, Sidecar};

const SLOT0: u16 = 32912;
const SLOT_SIZE: u16 = 48;

fn bad(m: impl std::fmt::Display) -> SurfaceError {
    SurfaceError::invalid(format!("not a readable JPK image: {m}"))
}

fn decoder(bytes: &[u8]) -> Result<Decoder<Cursor<&[u8]>>, SurfaceError> {
    let mut limits = Limits::default();
    limits.decoding_buffer_size = crate::MAX_SAMPLES * 8;
    limits.intermediate_buffer_size = crate::MAX_SAMPLES * 8;
    Ok(Decoder::new(Cursor::new(bytes)).map_err(bad)?.with_limits(limits))
}

/// A TIFF whose first page carries JPK's tags.
pub fn detect(bytes: &[u8]) -> bool {
    if !(bytes.starts_with(b"II*\0") || bytes.starts_with(b"MM\0*")) {
        return false;
    }
    match Decoder::new(Cursor::new(bytes)) {
        Ok(mut d) => {
            matches!(d.find_tag(Tag::Unknown(32848)), Ok(Some(_)))
                || matches!(d.find_tag(Tag::Unknown(32768)), Ok(Some(_)))
        }
        Err(_) => false,
    }
}

fn text(d: &mut Decoder<Cursor<&[u8]>>, tag: u16) -> Option<String> {
    d.find_tag(Tag::Unknown(tag)).ok().flatten().and_then(|v| v.into_string().ok())
}

fn number(d: &mut Decoder<Cursor<&[u8]>>, tag: u16) -> Option<f64> {
    use tiff::decoder::ifd::Value;
    Some(match d.find_tag(Tag::Unknown(tag)).ok().flatten()? {
        Value::Byte(v) => f64::from(v),
        Value::Short(v) => f64::from(v),
        Value::SignedByte(v) => f64::from(v),
        Value::SignedShort(v) => f64::from(v),
        Value::Signed(v) => f64::from(v),
        Value::SignedBig(v) => v as f64,
        Value::Unsigned(v) => f64::from(v),
        Value::UnsignedBig(v) => v as f64,
        Value::Float(v) => f64::from(v),
        Value::Double(v) => v,
        _ => return None,
    })
}

struct Page {
    info: ChannelInfo,
    page: usize,
    multiply: f64,
    offset: f64,
}

/// The channel pages and the pixel size (nm) from the first page's grid.
type Pages = (Vec<Page>, Option<(f64, f64)>);

fn pages(bytes: &[u8]) -> Result<Pages, SurfaceError> {
    let mut d = decoder(bytes)?;
    let pixel = match (number(&mut d, 32834), number(&mut d, 32835), number(&mut d, 32838), number(&mut d, 32839)) {
        (Some(u), Some(v), Some(i), Some(j)) if i >= 1.0 && j >= 1.0 && u > 0.0 && v > 0.0 => {
            Some((u * 1e9 / i, v * 1e9 / j))
        }
        _ => None,
    };
    let mut out = Vec::new();
    let mut page = 0;
    while d.more_images() {
        d.next_image().map_err(|e| bad(format!("page {}: {e}", page + 1)))?;
        page += 1;
        if page > 256 {
            return Err(bad("more than 256 pages"));
        }
        let Some(name) = text(&mut d, 32848) else { continue };
        let (w, h) = d.dimensions().map_err(bad)?;
        let retrace = number(&mut d, 32849).unwrap_or(0.0) != 0.0;
        let n_slots = number(&mut d, 32896).unwrap_or(0.0).clamp(0.0, 64.0) as u16;
        let default = text(&mut d, 32897).unwrap_or_default();
        let mut scaling = (1.0, 0.0, String::new());
        for s in 0..n_slots {
            let base = SLOT0 + SLOT_SIZE * s;
            if text(&mut d, base).as_deref() != Some(default.as_str()) {
                continue;
            }
            let unit = text(&mut d, base + 18).unwrap_or_default();
            scaling = match text(&mut d, base + 19).as_deref() {
                Some("LinearScaling") => {
                    let m = number(&mut d, base + 20)
                        .ok_or_else(|| bad(format!("page {page}: slot without multiplier")))?;
                    let o = number(&mut d, base + 21).unwrap_or(0.0);
                    (m, o, unit)
                }
                Some("NullScaling") | None => (1.0, 0.0, unit),
                Some(other) => return Err(bad(format!("page {page} ('{name}'): scaling '{other}' is not linear"))),
            };
            break;
        }
        out.push(Page {
            info: ChannelInfo {
                index: out.len() as u32,
                name,
                rows: h as usize,
                cols: w as usize,
                z_unit: scaling.2,
                direction: if retrace { "retrace" } else { "trace" }.into(),
                alias: String::new(),
            },
            page,
            multiply: scaling.0,
            offset: scaling.1,
        });
    }
    if out.is_empty() {
        return Err(bad("no channel pages (TIFF pages with JPK's channel tag 32848)"));
    }
    Ok((out, pixel))
}

pub fn channels(bytes: &[u8]) -> Result<Vec<ChannelInfo>, SurfaceError> {
    Ok(pages(bytes)?.0.into_iter().map(|p| p.info).collect())
}

pub fn read(bytes: &[u8], side: Option<&Sidecar>, opts: &LoadOptions) -> Result<HeightField, SurfaceError> {
    let (list_pages, pixel) = pages(bytes)?;
    let list: Vec<ChannelInfo> = list_pages.iter().map(|p| p.info.clone()).collect();
    let p = &list_pages[channel::pick(&list, opts.channel.as_ref())?];
    let (rows, cols) = (p.info.rows, p.info.cols);
    crate::check_dims(rows, cols)?;
    let mut d = decoder(bytes)?;
    d.seek_to_image(p.page).map_err(bad)?;
    let raw: Vec<f64> = match d.read_image().map_err(|e| bad(format!("channel '{}': {e}", p.info.name)))? {
        DecodingResult::I32(v) => v.into_iter().map(f64::from).collect(),
        DecodingResult::U32(v) => v.into_iter().map(f64::from).collect(),
        DecodingResult::I16(v) => v.into_iter().map(f64::from).collect(),
        DecodingResult::U16(v) => v.into_iter().map(f64::from).collect(),
        DecodingResult::F32(v) => v.into_iter().map(f64::from).collect(),
        DecodingResult::F64(v) => v,
        DecodingResult::U8(v) => v.into_iter().map(f64::from).collect(),
        DecodingResult::I8(v) => v.into_iter().map(f64::from).collect(),
        _ => return Err(bad(format!("channel '{}': unsupported sample type", p.info.name))),
    };
    if raw.len() != rows * cols {
        return Err(bad(format!("channel '{}': {} samples for {cols} × {rows}", p.info.name, raw.len())));
    }
    let mut values = vec![0.0; rows * cols];
    for r in 0..rows {
        let src = (rows - 1 - r) * cols;
        for c in 0..cols {
            values[r * cols + c] = raw[src + c] * p.multiply + p.offset;
        }
    }
    super::finish_channel(values, &list, &p.info, pixel, side, opts, "JPK image")
}
