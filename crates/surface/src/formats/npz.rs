//! numpy `.npz` (`np.savez`, `np.savez_compressed`): a zip archive of `.npy` arrays. The height field is the
//! archive's only 2-D array, or — when there are several — the one `--channel N` picks (arrays in name
//! order, counted from 0). Units as for `.npy`: sidecar or options. Written like `np.savez`: one stored
//! array `heights` (f64, nm) with a sidecar for the pixel size.
//!
//! Nothing in the zip headers is trusted for memory: each array's `.npy` header is read alone (at most
//! [`MAX_HEADER`] bytes) to learn its shape, an array whose shape needs more than [`super::MAX_FILE_BYTES`]
//! is refused before its data is read, and the chosen array is decompressed through a bounded reader.

use std::io::{Cursor, Read, Seek, Write};

use crate::{HeightField, SurfaceError};

use super::channel::{ChannelInfo, ChannelSel};
use super::{npy, LoadOptions, Sidecar};

/// Longest `.npy` header read while scanning an archive (numpy writes 128 bytes or a few hundred).
pub const MAX_HEADER: usize = 1 << 16;

fn bad(m: impl Into<String>) -> SurfaceError {
    SurfaceError::invalid(format!("not a valid .npz height field: {}", m.into()))
}

/// One array of the archive, known from its header only.
#[derive(Debug, Clone)]
struct Entry {
    /// Array name (the zip member without `.npy`).
    name: String,
    shape: Vec<u64>,
    dtype: String,
    /// Bytes of data the header's shape and dtype call for (saturating).
    data_bytes: u64,
}

impl Entry {
    fn is_2d(&self) -> bool {
        self.shape.iter().filter(|&&d| d != 1).count() == 2
    }
    /// The two dimensions that are not 1.
    fn shape_rows_cols(&self) -> (usize, usize) {
        let d: Vec<usize> = self.shape.iter().filter(|&&d| d != 1).map(|&d| d as usize).collect();
        (d.first().copied().unwrap_or(1), d.get(1).copied().unwrap_or(1))
    }
    fn describe(&self) -> String {
        let dims = self.shape.iter().map(|d| d.to_string()).collect::<Vec<_>>().join(" × ");
        format!("{} ({} {})", self.name, if dims.is_empty() { "scalar".into() } else { dims }, self.dtype)
    }
}

type Zip<'a> = zip::ZipArchive<Cursor<&'a [u8]>>;

/// Reads the header of member `member`: its first bytes, bounded, parsed without trusting declared lengths.
fn entry(zip: &mut Zip, member: &str) -> Result<Entry, SurfaceError> {
    let name = member.trim_end_matches(".npy").to_string();
    let f = zip.by_name(member).map_err(|e| bad(format!("array {name}: {e}")))?;
    let mut head = Vec::with_capacity(512);
    f.take(MAX_HEADER as u64 + 12).read_to_end(&mut head).map_err(|e| bad(format!("array {name}: {e}")))?;
    let end = npy::header_len(&head);
    if end > MAX_HEADER + 12 {
        return Err(bad(format!("array {name} declares a {end}-byte header (at most {MAX_HEADER} read)")));
    }
    npy::check_header_length(&head).map_err(|m| bad(format!("array {name}: {m}")))?;
    let file = npyz::NpyFile::new(&head[..]).map_err(|e| bad(format!("array {name}: header: {e}")))?;
    let item = file.dtype().num_bytes().unwrap_or(0) as u64;
    let shape = file.shape().to_vec();
    let data_bytes = shape.iter().fold(item, |a, &d| a.saturating_mul(d));
    let dtype = match file.dtype() {
        npyz::DType::Plain(ts) => ts.to_string(),
        other => other.descr(),
    };
    Ok(Entry { name, shape, dtype, data_bytes })
}

/// The arrays of an archive (`.npy` members), in name order, from their headers.
fn entries(zip: &mut Zip) -> Result<Vec<Entry>, SurfaceError> {
    let mut members: Vec<String> = zip.file_names().filter(|n| n.ends_with(".npy")).map(String::from).collect();
    members.sort();
    members.iter().map(|m| entry(zip, m)).collect()
}

/// Decompresses one member, reading at most what its header says plus [`MAX_HEADER`] bytes (so a zip header
/// that lies about sizes cannot make it allocate or inflate more).
fn member_bytes(zip: &mut Zip, e: &Entry) -> Result<Vec<u8>, SurfaceError> {
    let limit = e.data_bytes.saturating_add(MAX_HEADER as u64 + 12);
    let f = zip.by_name(&format!("{}.npy", e.name)).map_err(|err| bad(format!("array {}: {err}", e.name)))?;
    let mut data = Vec::with_capacity(f.size().min(limit) as usize);
    f.take(limit).read_to_end(&mut data).map_err(|err| bad(format!("array {}: {err}", e.name)))?;
    Ok(data)
}

pub fn read(bytes: &[u8], side: Option<&Sidecar>, opts: &LoadOptions) -> Result<HeightField, SurfaceError> {
    let mut zip = zip::ZipArchive::new(Cursor::new(bytes)).map_err(|e| bad(format!("zip archive: {e}")))?;
    let all = entries(&mut zip)?;
    let arrays: Vec<&Entry> = all.iter().filter(|e| e.is_2d()).collect();
    let mut picked_by_rule = None;
    let listing = || arrays.iter().enumerate().map(|(i, e)| format!("{i}: {}", e.describe())).collect::<Vec<_>>();
    let chosen = match (arrays.len(), opts.channel.as_ref()) {
        (0, _) => {
            let held = all.iter().map(Entry::describe).collect::<Vec<_>>();
            return Err(bad(format!(
                "the archive holds no 2-D array ({})",
                if held.is_empty() { "no .npy arrays at all".into() } else { held.join(", ") }
            )));
        }
        (1, None) => arrays[0],
        (_, Some(ChannelSel::Index(i))) => arrays
            .get(*i as usize)
            .copied()
            .ok_or_else(|| bad(format!("--channel {i}: the archive's 2-D arrays are {}", listing().join(", "))))?,
        (_, Some(ChannelSel::Name(n))) => {
            let key = n.strip_suffix(".npy").unwrap_or(n);
            arrays.iter().copied().find(|e| e.name == key).ok_or_else(|| {
                bad(format!("--channel {n}: no such array; the archive's 2-D arrays are {}", listing().join(", ")))
            })?
        }
        // As `surface channels` says it: the array named as a height, where there is one (the archive was refused
        // while the listing said "without --channel, commands read channel 1").
        (_, None) => match super::channel::default_rule(&infos_of(&arrays)) {
            Some((i, why)) => {
                picked_by_rule = Some(why);
                arrays[i]
            }
            None => {
                return Err(bad(format!(
                    "the archive holds several 2-D arrays ({}) and none named height; pick one with --channel N",
                    listing().join(", ")
                )))
            }
        },
    };
    if chosen.data_bytes > super::MAX_FILE_BYTES {
        return Err(bad(format!(
            "array {} is too large: {} MB of data, more than the {} MB of the largest height field iridis reads",
            chosen.describe(),
            chosen.data_bytes >> 20,
            super::MAX_FILE_BYTES >> 20
        )));
    }
    let data = member_bytes(&mut zip, chosen)?;
    let name = chosen.name.clone();
    let mut hf = npy::read(&data, side, opts).map_err(|e| match e {
        SurfaceError::Invalid(m) => bad(format!("array {name}: {m}")),
        other => other,
    })?;
    // An array `surface channels` marks "(not a height)" read because --channel named it: said, not silent.
    let pos = arrays.iter().position(|e| std::ptr::eq(*e, chosen)).unwrap_or(0);
    if picked_by_rule.is_none() && arrays.len() > 1 && !infos_of(&arrays)[pos].is_height() {
        hf.meta.warnings.push(format!(
            "array '{name}' is named as another signal than a height, and is read as heights (nm unless a unit is \
             given) because --channel chose it"
        ));
    }
    hf.meta.notes.push(match picked_by_rule {
        Some(why) => {
            format!("array '{name}' of the archive's {} 2-D arrays: {why} (--channel picks another)", arrays.len())
        }
        None => format!("array '{name}' of the archive"),
    });
    Ok(hf)
}

/// The 2-D arrays as channels, in the archive's order (what `surface channels` lists).
fn infos_of(arrays: &[&Entry]) -> Vec<ChannelInfo> {
    arrays
        .iter()
        .enumerate()
        .map(|(i, e)| ChannelInfo {
            index: i as u32,
            name: e.name.clone(),
            rows: e.shape_rows_cols().0,
            cols: e.shape_rows_cols().1,
            z_unit: String::new(),
            direction: String::new(),
            alias: String::new(),
        })
        .collect()
}

/// The archive's 2-D arrays, in name order.
pub fn channels(bytes: &[u8]) -> Result<Vec<ChannelInfo>, SurfaceError> {
    let mut zip = zip::ZipArchive::new(Cursor::new(bytes)).map_err(|e| bad(format!("zip archive: {e}")))?;
    let all = entries(&mut zip)?;
    Ok(infos_of(&all.iter().filter(|e| e.is_2d()).collect::<Vec<_>>()))
}

/// Writes an archive as `np.savez(f, heights=h)` does: one stored member `heights.npy` (`<f8`, C order, nm).
pub fn write(hf: &HeightField) -> Result<Vec<u8>, SurfaceError> {
    let npy = npy::write(hf)?;
    let err = |e: zip::result::ZipError| SurfaceError::invalid(format!("cannot encode .npz: {e}"));
    let mut zw = zip::ZipWriter::new(Cursor::new(Vec::with_capacity(npy.len() + 256)));
    let opts = zip::write::SimpleFileOptions::default()
        .compression_method(zip::CompressionMethod::Stored)
        .large_file(npy.len() as u64 >= u32::MAX as u64);
    zw.start_file("heights.npy", opts).map_err(err)?;
    zw.write_all(&npy).map_err(|e| SurfaceError::invalid(format!("cannot encode .npz: {e}")))?;
    let mut cur = zw.finish().map_err(err)?;
    cur.rewind().map_err(|e| SurfaceError::invalid(format!("cannot encode .npz: {e}")))?;
    Ok(cur.into_inner())
}
