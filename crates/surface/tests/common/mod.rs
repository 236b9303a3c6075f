//! Small instrument files built by the published layouts (the formats' documents cited in each reader),
//! for the mutation fuzzing and for tests that must run without the fetched real files. Each holds a
//! known ramp `h(r, c)` so a reader's orientation and scaling can be checked exactly.
#![allow(dead_code)] // each test file uses some of them

/// The code stored for displayed row `r`, column `c` (row 0 at the top).
pub fn code(r: usize, c: usize) -> i32 {
    (100 * r + 3 * c) as i32 - 700
}

pub const ROWS: usize = 12;
pub const COLS: usize = 16;

/// NanoScope v9: one 16-bit "Height" image, 100 × 75 nm, sensitivity 4 nm/V, Z scale 131.072 V over 2^16
/// codes (0.002 V per code, so 0.008 nm per code); stored bottom line first.
pub fn nanoscope() -> Vec<u8> {
    let data_offset = 2048;
    let mut h = String::new();
    for l in [
        "\\*File list",
        "\\Version: 0x09300201",
        "\\*Scanner list",
        "\\@Sens. Zsens: V 4.000000 nm/V",
        "\\*Ciao image list",
        &format!("\\Data offset: {data_offset}"),
        &format!("\\Data length: {}", ROWS * COLS * 2),
        "\\Bytes/pixel: 2",
        &format!("\\Samps/line: {COLS}"),
        &format!("\\Number of lines: {ROWS}"),
        "\\Scan Size: 100 100 nm",
        "\\Line Direction: Trace",
        "\\@2:Image Data: S [Height] \"Height\"",
        "\\@2:Z scale: V [Sens. Zsens] (0.002000000 V/LSB) 131.0720 V",
        "\\*File list end",
    ] {
        h.push_str(l);
        h.push_str("\r\n");
    }
    let mut b = h.into_bytes();
    b.resize(data_offset, 0);
    for sr in 0..ROWS {
        for c in 0..COLS {
            b.extend_from_slice(&(code(ROWS - 1 - sr, c) as i16).to_le_bytes());
        }
    }
    b
}

/// Igor binary wave v5 (little-endian): f32, COLS × ROWS × 2 layers labelled HeightTrace, Phase; the note
/// gives a 1.6 µm × 1.2 µm scan; values in m (code × 1e-10 m = code × 0.1 nm); stored y up.
pub fn ibw() -> Vec<u8> {
    let layers = 2;
    let npnts = COLS * ROWS * layers;
    let note = b"ScanSize: 1.6e-06\rFastScanSize: 1.6e-06\rSlowScanSize: 1.2e-06\rScanPoints: 16\r".to_vec();
    let labels: i32 = 3 * 32; // the dimension's own label, then one per layer
    let mut bin = vec![0u8; 64];
    bin[0..2].copy_from_slice(&5i16.to_le_bytes());
    bin[4..8].copy_from_slice(&((320 + npnts * 4) as i32).to_le_bytes());
    bin[12..16].copy_from_slice(&(note.len() as i32).to_le_bytes());
    bin[36 + 8..36 + 12].copy_from_slice(&labels.to_le_bytes());
    let mut wave = vec![0u8; 320];
    wave[12..16].copy_from_slice(&(npnts as i32).to_le_bytes());
    wave[16..18].copy_from_slice(&2u16.to_le_bytes()); // f32
    for (k, n) in [COLS, ROWS, layers, 0].iter().enumerate() {
        wave[68 + 4 * k..72 + 4 * k].copy_from_slice(&(*n as i32).to_le_bytes());
    }
    for k in 0..2 {
        wave[84 + 8 * k..92 + 8 * k].copy_from_slice(&1e-7f64.to_le_bytes());
        wave[152 + 4 * k] = b'm';
    }
    let mut b = bin;
    b.extend(wave);
    for layer in 0..layers {
        for y in 0..ROWS {
            for x in 0..COLS {
                let v = code(ROWS - 1 - y, x) as f32 * 1e-10 * (1 + layer) as f32;
                b.extend_from_slice(&v.to_le_bytes());
            }
        }
    }
    b.extend(note);
    for name in ["", "HeightTrace", "Phase"] {
        let mut l = name.as_bytes().to_vec();
        l.resize(32, 0);
        b.extend(l);
    }
    b
}

/// WSxM `.top`: 16-bit codes, Z Amplitude = (max − min) × 0.01 nm, 160 × 120 nm, stored top row first.
pub fn wsxm_top() -> Vec<u8> {
    let (lo, hi) = (code(0, 0), code(ROWS - 1, COLS - 1));
    let body = format!(
        "[General Info]\r\n    Image Data Type: short\r\n    Number of columns: {COLS}\r\n    Number of rows: {ROWS}\r\n    \
         Z Amplitude: {} nm\r\n[Control]\r\n    X Amplitude: 160 nm\r\n    Y Amplitude: 120 nm\r\n[Miscellaneous]\r\n    \
         Maximum: {hi}\r\n    Minimum: {lo}\r\n[Header end]\r\n",
        f64::from(hi - lo) * 0.01
    );
    let first = "WSxM file copyright UAM\r\nSxM Image file\r\n";
    // The header size counts its own line, whose length depends on the number.
    let mut size = first.len() + body.len() + 26;
    loop {
        let line = format!("Image header size: {size}\r\n");
        let total = first.len() + line.len() + body.len();
        if total == size {
            let mut b = format!("{first}{line}{body}").into_bytes();
            for r in 0..ROWS {
                for c in 0..COLS {
                    b.extend_from_slice(&(code(r, c) as i16).to_le_bytes());
                }
            }
            return b;
        }
        size = total;
    }
}

/// A JPK-style TIFF: a thumbnail page with the grid (160 × 120 nm), then one int32 channel "height"
/// (trace) whose default slot "nominal" scales raw codes by 1e-10 m with offset 2e-9 m; stored bottom line
/// first (AFMReader flips it).
pub fn jpk() -> Vec<u8> {
    use tiff::encoder::{colortype, TiffEncoder};
    use tiff::tags::Tag;
    let mut out = std::io::Cursor::new(Vec::new());
    {
        let mut enc = TiffEncoder::new(&mut out).unwrap();
        let mut thumb = enc.new_image::<colortype::Gray8>(4, 4).unwrap();
        let d = thumb.encoder();
        d.write_tag(Tag::Unknown(32834), 1.6e-7f64).unwrap();
        d.write_tag(Tag::Unknown(32835), 1.2e-7f64).unwrap();
        d.write_tag(Tag::Unknown(32838), COLS as u32).unwrap();
        d.write_tag(Tag::Unknown(32839), ROWS as u32).unwrap();
        d.write_tag(Tag::Unknown(32848), "thumbnail").unwrap();
        thumb.write_data(&[0u8; 16]).unwrap();
        let mut page = enc.new_image::<colortype::GrayI32>(COLS as u32, ROWS as u32).unwrap();
        let d = page.encoder();
        d.write_tag(Tag::Unknown(32848), "height").unwrap();
        d.write_tag(Tag::Unknown(32849), 0u32).unwrap();
        d.write_tag(Tag::Unknown(32896), 2u32).unwrap();
        d.write_tag(Tag::Unknown(32897), "nominal").unwrap();
        d.write_tag(Tag::Unknown(32912), "raw").unwrap();
        d.write_tag(Tag::Unknown(32931), "NullScaling").unwrap();
        d.write_tag(Tag::Unknown(32912 + 48), "nominal").unwrap();
        d.write_tag(Tag::Unknown(32930 + 48), "m").unwrap();
        d.write_tag(Tag::Unknown(32931 + 48), "LinearScaling").unwrap();
        d.write_tag(Tag::Unknown(32932 + 48), 1e-10f64).unwrap();
        d.write_tag(Tag::Unknown(32933 + 48), 2e-9f64).unwrap();
        let data: Vec<i32> = (0..ROWS * COLS).map(|i| code(ROWS - 1 - i / COLS, i % COLS)).collect();
        page.write_data(&data).unwrap();
    }
    out.into_inner()
}
