//! The unit tests of src/formats/npz.rs, moved here so that `cargo test` compiles the library once.

use iridis_surface::formats::channel::ChannelSel;
use iridis_surface::formats::npz::*;
use iridis_surface::formats::LoadOptions;
use std::io::{Cursor, Write};

fn npy_bytes(rows: u64, cols: u64, values: &[f64]) -> Vec<u8> {
    let mut buf = Vec::new();
    {
        use npyz::WriterBuilder;
        let mut w = npyz::WriteOptions::new().default_dtype().shape(&[rows, cols]).writer(&mut buf).begin_nd().unwrap();
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
    LoadOptions { pixel_size_nm: Some(50.0), channel: channel.map(ChannelSel::Index), ..Default::default() }
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
    // One named height among them is read without --channel, as `surface channels` says, with a note; none named
    // height is refused (above: "none named height").
    assert!(e_none_named(&z).contains("none named height"));
    let h = npy_bytes(2, 3, &[1.0, 2.0, 3.0, 4.0, 5.0, 7.0]);
    let z =
        archive(&[("amplitude.npy", npy_bytes(2, 2, &[0.0; 4])), ("height.npy", h)], zip::CompressionMethod::Stored);
    let hf = read(&z, None, &opts(None)).unwrap();
    assert_eq!(hf.cols, 3);
    assert!(hf.meta.notes.iter().any(|n| n.contains("array 'height' of the archive's 2 2-D arrays")), "{:?}", hf.meta);
    let amp = read(&z, None, &opts(Some(0))).unwrap();
    assert!(amp.meta.warnings.iter().any(|w| w.contains("array 'amplitude' is named as another signal")), "{amp:?}");
}

fn e_none_named(z: &[u8]) -> String {
    read(z, None, &opts(None)).unwrap_err().to_string()
}
