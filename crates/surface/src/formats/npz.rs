//! numpy `.npz` (`np.savez`, `np.savez_compressed`): a zip archive of `.npy` arrays. The height field is the
//! archive's only 2-D array, or — when there are several — the one `--channel N` picks (arrays in name
//! order, counted from 0). Units as for `.npy`: sidecar or options.

use std::io::{Cursor, Read};

use crate::{HeightField, SurfaceError};

use super::{npy, LoadOptions, Sidecar};

fn bad(m: impl Into<String>) -> SurfaceError {
    SurfaceError::invalid(format!("not a valid .npz height field: {}", m.into()))
}

/// The arrays of an archive that are 2-D (after dropping axes of length 1), in name order, with their bytes.
fn height_arrays(bytes: &[u8]) -> Result<Vec<(String, Vec<u8>)>, SurfaceError> {
    let mut zip = zip::ZipArchive::new(Cursor::new(bytes)).map_err(|e| bad(format!("zip archive: {e}")))?;
    let mut names: Vec<String> = zip.file_names().filter(|n| n.ends_with(".npy")).map(String::from).collect();
    names.sort();
    let mut out = Vec::new();
    for name in names {
        let mut f = zip.by_name(&name).map_err(|e| bad(format!("array {name}: {e}")))?;
        if f.size() > super::MAX_FILE_BYTES {
            return Err(bad(format!(
                "array {name} is {} MB, larger than any height field iridis reads",
                f.size() >> 20
            )));
        }
        let mut data = Vec::with_capacity(f.size() as usize);
        f.read_to_end(&mut data).map_err(|e| bad(format!("array {name}: {e}")))?;
        let two_d =
            npyz::NpyFile::new(&data[..]).map(|n| n.shape().iter().filter(|&&d| d != 1).count() == 2).unwrap_or(false);
        if two_d {
            out.push((name.trim_end_matches(".npy").to_string(), data));
        }
    }
    Ok(out)
}

pub fn read(bytes: &[u8], side: Option<&Sidecar>, opts: &LoadOptions) -> Result<HeightField, SurfaceError> {
    let arrays = height_arrays(bytes)?;
    let listing = || arrays.iter().enumerate().map(|(i, (n, _))| format!("{i}: {n}")).collect::<Vec<_>>().join(", ");
    let (name, data) = match (arrays.len(), opts.channel) {
        (0, _) => return Err(bad("the archive holds no 2-D array")),
        (1, None) => &arrays[0],
        (_, Some(i)) => arrays
            .get(i as usize)
            .ok_or_else(|| bad(format!("--channel {i}: the archive's 2-D arrays are {}", listing())))?,
        (_, None) => {
            return Err(bad(format!("the archive holds several 2-D arrays ({}); pick one with --channel N", listing())))
        }
    };
    let mut hf = npy::read(data, side, opts).map_err(|e| match e {
        SurfaceError::Invalid(m) => bad(format!("array {name}: {m}")),
        other => other,
    })?;
    hf.meta.notes.push(format!("array '{name}' of the archive"));
    Ok(hf)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Write;

    fn npy_bytes(rows: u64, cols: u64, values: &[f64]) -> Vec<u8> {
        let mut buf = Vec::new();
        {
            use npyz::WriterBuilder;
            let mut w =
                npyz::WriteOptions::new().default_dtype().shape(&[rows, cols]).writer(&mut buf).begin_nd().unwrap();
            w.extend(values.iter().copied()).unwrap();
            w.finish().unwrap();
        }
        buf
    }

    fn archive(entries: &[(&str, Vec<u8>)], method: zip::CompressionMethod) -> Vec<u8> {
        let mut zw = zip::ZipWriter::new(Cursor::new(Vec::new()));
        let opts = zip::write::SimpleFileOptions::default().compression_method(method);
        for (name, data) in entries {
            zw.start_file(*name, opts).unwrap();
            zw.write_all(data).unwrap();
        }
        zw.finish().unwrap().into_inner()
    }

    fn opts(channel: Option<u32>) -> LoadOptions {
        LoadOptions { pixel_size_nm: Some(50.0), channel, ..Default::default() }
    }

    #[test]
    fn reads_the_only_2d_array_stored_or_deflated() {
        let values: Vec<f64> = (0..12).map(|i| i as f64 * 1.5).collect();
        let axis = {
            let mut b = Vec::new();
            use npyz::WriterBuilder;
            let mut w = npyz::WriteOptions::new().default_dtype().shape(&[3]).writer(&mut b).begin_nd().unwrap();
            w.extend([1.0f64, 2.0, 3.0]).unwrap();
            w.finish().unwrap();
            b
        };
        for method in [zip::CompressionMethod::Stored, zip::CompressionMethod::Deflated] {
            let z = archive(&[("x.npy", axis.clone()), ("heights.npy", npy_bytes(3, 4, &values))], method);
            let hf = read(&z, None, &opts(None)).unwrap();
            assert_eq!((hf.rows, hf.cols), (3, 4));
            assert_eq!(hf.heights_nm, values);
            assert_eq!(hf.dx_nm, 50.0);
        }
    }

    #[test]
    fn several_arrays_need_a_channel_and_the_message_lists_them() {
        let a = npy_bytes(2, 2, &[1.0, 2.0, 3.0, 4.0]);
        let b = npy_bytes(2, 3, &[5.0; 6]);
        let z = archive(&[("b.npy", b), ("a.npy", a)], zip::CompressionMethod::Stored);
        let e = read(&z, None, &opts(None)).unwrap_err().to_string();
        assert!(e.contains("0: a") && e.contains("1: b") && e.contains("--channel"), "{e}");
        assert_eq!(read(&z, None, &opts(Some(1))).unwrap().cols, 3);
        let e = read(&z, None, &opts(Some(7))).unwrap_err().to_string();
        assert!(e.contains("--channel 7"), "{e}");
        let only_1d = archive(&[("x.npy", npy_bytes(1, 5, &[0.0; 5]))], zip::CompressionMethod::Stored);
        assert!(read(&only_1d, None, &opts(None)).unwrap_err().to_string().contains("no 2-D array"));
        assert!(read(&z[..z.len() / 2], None, &opts(None)).is_err());
    }
}
