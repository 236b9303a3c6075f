//! Every reader on mutated input (`iridis_surface::fuzz::mutate`): seeded, so deterministic; an error is fine,
//! a panic is a failure. The long run is `cargo run --release -p iridis-surface --example fuzz -- 1000000 7`.

use std::panic::{catch_unwind, AssertUnwindSafe};

use iridis_surface::formats::{read_bytes, write_bytes, Format};
use iridis_surface::fuzz::mutate;
use iridis_surface::generate::{Generator, Grid};
use iridis_surface::rng::Rng;
use iridis_surface::LoadOptions;

use crate::common;

const PER_SEED: usize = 1500;

fn fixture(name: &str) -> Vec<u8> {
    std::fs::read(format!("{}/tests/fixtures/{name}", env!("CARGO_MANIFEST_DIR"))).unwrap()
}

#[test]
fn mutated_files_of_every_format_never_panic() {
    let grid = Grid { size_x_nm: 1200.0, size_y_nm: 800.0, pixel_nm: 100.0, angle_rad: 0.2, seed: 1 };
    let hf = Generator::Sine { period_nm: 400.0, depth_nm: 30.0 }.generate(&grid).unwrap();
    let enc = |f| write_bytes(&hf, f).unwrap().0;
    let tiff = {
        let img = image::ImageBuffer::from_fn(12, 8, |x, y| image::Luma([(x * 5000 + y * 300) as u16]));
        let mut c = std::io::Cursor::new(Vec::new());
        img.write_to(&mut c, image::ImageFormat::Tiff).unwrap();
        c.into_inner()
    };
    let seeds: Vec<(&str, Vec<u8>)> = vec![
        ("gwy", enc(Format::Gwy)),
        ("gwyfile", fixture("gwyfile_two_channels.gwy")),
        ("npy", enc(Format::Npy)),
        ("npy-fortran", fixture("numpy_f32_fortran.npy")),
        ("npy-big-endian", fixture("numpy_f64_bigendian.npy")),
        ("npz", enc(Format::Npz)),
        ("npz-savez", fixture("numpy_savez.npz")),
        ("npz-savez-compressed", fixture("numpy_savez_compressed.npz")),
        ("png16", enc(Format::Png)),
        ("tiff16", tiff),
        ("text", enc(Format::Text)),
        ("gsf", enc(Format::Gsf)),
        ("nanoscope", common::nanoscope()),
        ("ibw", common::ibw()),
        ("jpk", common::jpk()),
        ("wsxm", common::wsxm_top()),
        ("sxm", fixture("nanonis_synthetic.sxm")),
    ];
    let opts = LoadOptions { pixel_size_nm: Some(10.0), max_height_nm: Some(100.0), ..Default::default() };
    let mut panics = Vec::new();
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    for (k, (name, seed)) in seeds.iter().enumerate() {
        let mut rng = Rng::new(1000 + k as u64);
        let other = &seeds[(k + 1) % seeds.len()].1;
        let mut refused = 0;
        for i in 0..PER_SEED {
            let data = mutate(&mut rng, seed, if i % 2 == 0 { seed } else { other });
            match catch_unwind(AssertUnwindSafe(|| read_bytes(&data, "fuzz", None, &opts))) {
                Ok(r) => refused += usize::from(r.is_err()),
                Err(_) => panics.push(format!("{name}, iteration {i}")),
            }
        }
        // The mutations must actually hit the parser: most inputs are damaged enough to be refused.
        assert!(refused > PER_SEED / 10, "{name}: only {refused} of {PER_SEED} mutated inputs refused");
    }
    std::panic::set_hook(hook);
    assert!(panics.is_empty(), "panics: {panics:?}");
}
