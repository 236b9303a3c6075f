//! The unit tests of src/formats/ibw.rs, moved here so that `cargo test` compiles the library once.

use iridis_surface::formats::ibw::*;

/// A big-endian wave (Igor Pro on a PowerPC Mac) gives the same numbers as a little-endian one.
#[test]
fn wave_reads_both_byte_orders() {
    let (i, u, f) = (-123_456i32, 0xBEEFu16, 6.02e23f64);
    let le: Vec<u8> = [&i.to_le_bytes()[..], &u.to_le_bytes(), &f.to_le_bytes()].concat();
    let be: Vec<u8> = [&i.to_be_bytes()[..], &u.to_be_bytes(), &f.to_be_bytes()].concat();
    for (b, little) in [(&le, true), (&be, false)] {
        let w = Wave { le: little, b };
        assert_eq!((w.i32(0), w.u16(4), w.f64(6)), (i, u, f), "little-endian: {little}");
    }
}
