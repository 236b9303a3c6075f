//! Gwyddion native files (`GWYP`, the serialisation of a `GwyContainer`; gwyddion.net "Gwyddion Native File
//! Format"). An object is `name\0`, a little-endian `u32` byte size, then components `name\0 type value`.
//! Every length is checked against the bytes that are left before anything is allocated, and nesting is
//! bounded, so a corrupt file gives an error, not a panic or a huge allocation.

use crate::{HeightField, SurfaceError};

use super::{LoadOptions, Sidecar};

const MAX_DEPTH: usize = 32;

/// A deserialised component value (only what height fields need is kept in detail).
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    Bool(bool),
    Char(u8),
    Int(i32),
    Long(i64),
    Double(f64),
    Str(String),
    Object(Object),
    Doubles(Vec<f64>),
    /// Other arrays: kept only as a count.
    Array(usize),
    Objects(Vec<Object>),
}

/// A `GwySerializable` object: type name and named components in file order.
#[derive(Debug, Clone, PartialEq)]
pub struct Object {
    pub name: String,
    pub items: Vec<(String, Value)>,
}

impl Object {
    pub fn get(&self, key: &str) -> Option<&Value> {
        self.items.iter().find(|(k, _)| k == key).map(|(_, v)| v)
    }
}

fn err(m: impl Into<String>) -> SurfaceError {
    SurfaceError::invalid(format!("not a valid Gwyddion file: {}", m.into()))
}

struct Cursor<'a> {
    b: &'a [u8],
    pos: usize,
}

impl<'a> Cursor<'a> {
    fn left(&self) -> usize {
        self.b.len() - self.pos
    }
    fn take(&mut self, n: usize) -> Result<&'a [u8], SurfaceError> {
        if n > self.left() {
            return Err(err(format!("truncated at byte {} (needed {n} more bytes, {} left)", self.pos, self.left())));
        }
        let s = &self.b[self.pos..self.pos + n];
        self.pos += n;
        Ok(s)
    }
    fn cstr(&mut self) -> Result<String, SurfaceError> {
        let rest = &self.b[self.pos..];
        let n = rest.iter().position(|&c| c == 0).ok_or_else(|| err("unterminated string (truncated file?)"))?;
        let s = String::from_utf8_lossy(&rest[..n]).into_owned();
        self.pos += n + 1;
        Ok(s)
    }
    fn u32(&mut self) -> Result<u32, SurfaceError> {
        Ok(u32::from_le_bytes(self.take(4)?.try_into().expect("4 bytes")))
    }
    fn u64(&mut self) -> Result<u64, SurfaceError> {
        Ok(u64::from_le_bytes(self.take(8)?.try_into().expect("8 bytes")))
    }
    /// An array count whose elements take at least `elem` bytes each.
    fn count(&mut self, elem: usize) -> Result<usize, SurfaceError> {
        let n = self.u32()? as usize;
        if n.saturating_mul(elem) > self.left() {
            return Err(err(format!("array of {n} elements does not fit in the {} bytes left", self.left())));
        }
        Ok(n)
    }

    fn object(&mut self, depth: usize) -> Result<Object, SurfaceError> {
        if depth > MAX_DEPTH {
            return Err(err("objects nested too deeply"));
        }
        let name = self.cstr()?;
        let size = self.u32()? as usize;
        if size > self.left() {
            return Err(err(format!("object {name} claims {size} bytes, only {} left (truncated?)", self.left())));
        }
        let end = self.pos + size;
        let mut items = Vec::new();
        while self.pos < end {
            let key = self.cstr()?;
            let t = self.take(1)?[0];
            let v = match t {
                b'b' => Value::Bool(self.take(1)?[0] != 0),
                b'c' => Value::Char(self.take(1)?[0]),
                b'i' => Value::Int(self.u32()? as i32),
                b'q' => Value::Long(self.u64()? as i64),
                b'd' => Value::Double(f64::from_bits(self.u64()?)),
                b's' => Value::Str(self.cstr()?),
                b'o' => Value::Object(self.object(depth + 1)?),
                b'D' => {
                    let n = self.count(8)?;
                    let raw = self.take(n * 8)?;
                    Value::Doubles(
                        raw.chunks_exact(8).map(|c| f64::from_le_bytes(c.try_into().expect("8 bytes"))).collect(),
                    )
                }
                b'C' | b'B' => {
                    let n = self.count(1)?;
                    self.take(n)?;
                    Value::Array(n)
                }
                b'I' => {
                    let n = self.count(4)?;
                    self.take(n * 4)?;
                    Value::Array(n)
                }
                b'Q' => {
                    let n = self.count(8)?;
                    self.take(n * 8)?;
                    Value::Array(n)
                }
                b'S' => {
                    let n = self.count(1)?;
                    for _ in 0..n {
                        self.cstr()?;
                    }
                    Value::Array(n)
                }
                b'O' => {
                    // Each object needs at least a name terminator and a size.
                    let n = self.count(5)?;
                    let mut v = Vec::with_capacity(n);
                    for _ in 0..n {
                        v.push(self.object(depth + 1)?);
                    }
                    Value::Objects(v)
                }
                other => return Err(err(format!("unknown component type '{}' for {key}", other as char))),
            };
            if self.pos > end {
                return Err(err(format!("component {key} runs past the end of object {name}")));
            }
            items.push((key, v));
        }
        Ok(Object { name, items })
    }
}

/// Parses the top-level object of a `.gwy` file.
pub fn parse(bytes: &[u8]) -> Result<Object, SurfaceError> {
    if bytes.starts_with(b"GWYO") {
        return Err(err("this is the old Gwyddion 1 format (GWYO); open and re-save it in Gwyddion 2"));
    }
    if !bytes.starts_with(b"GWYP") {
        return Err(err("missing the GWYP magic"));
    }
    let mut c = Cursor { b: bytes, pos: 4 };
    c.object(0)
}

/// Unit string of a `GwySIUnit` component; `None` when absent.
fn unit(obj: &Object, key: &str) -> Option<String> {
    match obj.get(key) {
        Some(Value::Object(u)) => match u.get("unitstr") {
            Some(Value::Str(s)) => Some(s.clone()),
            _ => Some(String::new()),
        },
        _ => None,
    }
}

fn to_nm(u: Option<String>, what: &str, warnings: &mut Vec<String>) -> Result<(f64, String), SurfaceError> {
    match u.as_deref() {
        None | Some("") => {
            warnings.push(format!("the file gives no {what} unit; assumed metres (Gwyddion's AFM convention)"));
            Ok((1e9, "m (assumed)".into()))
        }
        Some(s) => match super::unit_to_nm(s) {
            Some(k) => Ok((k, s.to_string())),
            None => Err(SurfaceError::invalid(format!(
                "{what} unit '{s}' is not a length: this channel is not a height (choose another with --channel)"
            ))),
        },
    }
}

/// The container's `/N/data` fields, by number.
fn data_fields(top: &Object) -> Vec<(u32, &Object)> {
    let mut channels: Vec<(u32, &Object)> = top
        .items
        .iter()
        .filter_map(|(k, v)| {
            let id = k.strip_prefix('/')?.strip_suffix("/data")?.parse::<u32>().ok()?;
            match v {
                Value::Object(o) if o.name == "GwyDataField" => Some((id, o)),
                _ => None,
            }
        })
        .collect();
    channels.sort_by_key(|c| c.0);
    channels
}

fn infos(top: &Object, channels: &[(u32, &Object)]) -> Vec<super::channel::ChannelInfo> {
    channels
        .iter()
        .map(|(id, f)| {
            let int = |k: &str| match f.get(k) {
                Some(Value::Int(v)) => (*v).max(0) as usize,
                _ => 0,
            };
            let name = match top.get(&format!("/{id}/data/title")) {
                Some(Value::Str(s)) => s.clone(),
                _ => String::new(),
            };
            super::channel::ChannelInfo {
                index: *id,
                name,
                rows: int("yres"),
                cols: int("xres"),
                z_unit: unit(f, "si_unit_z").unwrap_or_default(),
                direction: String::new(),
                alias: String::new(),
            }
        })
        .collect()
}

/// The image channels of a `.gwy` file (index = the container's channel number).
pub fn channels(bytes: &[u8]) -> Result<Vec<super::channel::ChannelInfo>, SurfaceError> {
    let top = parse(bytes)?;
    if top.name == "GwyDataField" {
        return Ok(infos(&top, &[(0, &top)]));
    }
    Ok(infos(&top, &data_fields(&top)))
}

/// Reads the chosen data field (by default the one named Height, else the lowest-numbered height channel,
/// as [`super::channel::pick`] chooses).
pub fn read(bytes: &[u8], side: Option<&Sidecar>, opts: &LoadOptions) -> Result<HeightField, SurfaceError> {
    let top = parse(bytes)?;
    let fields: Vec<(u32, &Object)> = if top.name == "GwyDataField" {
        vec![(0, &top)]
    } else {
        let channels = data_fields(&top);
        if channels.is_empty() {
            return Err(SurfaceError::invalid("the Gwyddion file holds no image channel (/N/data)"));
        }
        channels
    };
    let list = infos(&top, &fields);
    let pos = match &opts.channel {
        // Gwyddion's own default is the lowest channel; among several, a height (not a stiffness map).
        None => super::channel::pick(&list, None)?,
        Some(sel) => super::channel::pick(&list, Some(sel))?,
    };
    let (id, field) = fields[pos];
    let int = |k: &str| match field.get(k) {
        Some(Value::Int(v)) => Ok(*v),
        _ => Err(err(format!("data field without '{k}'"))),
    };
    let dbl = |k: &str, default: Option<f64>| match field.get(k) {
        Some(Value::Double(v)) => Ok(*v),
        _ => default.ok_or_else(|| err(format!("data field without '{k}'"))),
    };
    let (xres, yres) = (int("xres")?, int("yres")?);
    if xres <= 0 || yres <= 0 {
        return Err(err(format!("data field of {xres} × {yres} samples")));
    }
    let (cols, rows) = (xres as usize, yres as usize);
    crate::check_dims(rows, cols)?;
    let data = match field.get("data") {
        Some(Value::Doubles(d)) => d,
        _ => return Err(err("data field without its 'data' array")),
    };
    if data.len() != rows * cols {
        return Err(err(format!("{} data values for {xres} × {yres} samples", data.len())));
    }
    // Gwyddion's defaults for a missing real size are 1 (in the xy unit).
    let (xreal, yreal) = (dbl("xreal", Some(1.0))?, dbl("yreal", Some(1.0))?);
    let mut warnings = Vec::new();
    let (kxy, uxy) = to_nm(unit(field, "si_unit_xy"), "lateral (xy)", &mut warnings)?;
    let z =
        super::channel::z_scale(&list, &list[pos], opts, side, Some((1e9, "m", "metres (Gwyddion's AFM convention)")))?;
    warnings.extend(z.warnings);
    let file_pixel = (xreal * kxy / cols as f64, yreal * kxy / rows as f64);
    let file_ok = file_pixel.0.is_finite() && file_pixel.0 > 0.0 && file_pixel.1.is_finite() && file_pixel.1 > 0.0;
    if !file_ok && opts.pixel_size_nm.is_none() && side.and_then(|s| s.pixel_nm()).is_none() {
        return Err(SurfaceError::invalid(format!(
            "the file's physical size {xreal} × {yreal} {uxy} gives no valid pixel size; give --pixel-size"
        )));
    }
    let ((dx, dy), pixel_warning) = super::pick_pixel(Some(file_pixel), side, opts, "this Gwyddion channel")?;
    warnings.extend(pixel_warning);
    let heights: Vec<f64> = data.iter().map(|v| v * z.nm_per_unit).collect();
    let hf = HeightField::new(rows, cols, dx, dy, heights)?;
    let mut meta = hf.meta.clone();
    meta.z_unit = z.unit;
    meta.warnings = warnings;
    let title = &list[pos].name;
    meta.notes.push(format!(
        "Gwyddion channel {id}{}: {cols} × {rows} samples, {:e} × {:e} {uxy}",
        if title.is_empty() { String::new() } else { format!(" '{title}'") },
        // The extent as the file's author wrote it, without the noise of its binary double.
        iridis_color::units::tidy(xreal),
        iridis_color::units::tidy(yreal)
    ));
    if top.name != "GwyDataField" {
        let choice = super::channel::ChannelChoice::new(&list, pos, opts.channel.as_ref());
        if list.len() > 1 {
            meta.notes.push(choice.describe());
        }
        meta.channel = Some(choice);
    }
    Ok(hf.with_meta(meta))
}

fn put_str(out: &mut Vec<u8>, s: &str) {
    out.extend_from_slice(s.as_bytes());
    out.push(0);
}

fn object(out: &mut Vec<u8>, name: &str, body: &[u8]) {
    put_str(out, name);
    out.extend_from_slice(&(body.len() as u32).to_le_bytes());
    out.extend_from_slice(body);
}

fn si_unit(unit: &str) -> Vec<u8> {
    let mut b = Vec::new();
    put_str(&mut b, "unitstr");
    b.push(b's');
    put_str(&mut b, unit);
    let mut o = Vec::new();
    object(&mut o, "GwySIUnit", &b);
    o
}

/// Serialises a field as a Gwyddion container with channel 0, in metres (Gwyddion's convention).
pub fn write(hf: &HeightField) -> Vec<u8> {
    let mut f = Vec::with_capacity(hf.heights_nm.len() * 8 + 256);
    let comp = |f: &mut Vec<u8>, k: &str, t: u8| {
        put_str(f, k);
        f.push(t);
    };
    comp(&mut f, "xres", b'i');
    f.extend_from_slice(&(hf.cols as i32).to_le_bytes());
    comp(&mut f, "yres", b'i');
    f.extend_from_slice(&(hf.rows as i32).to_le_bytes());
    comp(&mut f, "xreal", b'd');
    f.extend_from_slice(&(hf.cols as f64 * hf.dx_nm * 1e-9).to_le_bytes());
    comp(&mut f, "yreal", b'd');
    f.extend_from_slice(&(hf.rows as f64 * hf.dy_nm * 1e-9).to_le_bytes());
    comp(&mut f, "si_unit_xy", b'o');
    f.extend_from_slice(&si_unit("m"));
    comp(&mut f, "si_unit_z", b'o');
    f.extend_from_slice(&si_unit("m"));
    comp(&mut f, "data", b'D');
    f.extend_from_slice(&(hf.heights_nm.len() as u32).to_le_bytes());
    for h in &hf.heights_nm {
        f.extend_from_slice(&(h * 1e-9).to_le_bytes());
    }
    let mut field = Vec::new();
    object(&mut field, "GwyDataField", &f);
    let mut c = Vec::new();
    put_str(&mut c, "/0/data");
    c.push(b'o');
    c.extend_from_slice(&field);
    put_str(&mut c, "/0/data/title");
    c.push(b's');
    let title = if hf.meta.source.is_empty() { "Height".to_string() } else { format!("Height ({})", hf.meta.source) };
    put_str(&mut c, &title.replace('\0', " "));
    let mut out = b"GWYP".to_vec();
    object(&mut out, "GwyContainer", &c);
    out
}
