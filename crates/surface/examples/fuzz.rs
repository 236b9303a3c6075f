//! Stable-Rust fuzzing of every binary parser (cargo-fuzz needs nightly): seed inputs from each format are
//! mutated with a seeded RNG (bit flips, byte overwrites with "interesting" values, truncation, splices,
//! duplicated and deleted ranges) and parsed; any panic is caught, reported with the seed and iteration,
//! and makes the run fail.
//!
//!     cargo run --release -p iridis-surface --example fuzz -- [ITERATIONS per format] [SEED]

use std::panic::{catch_unwind, AssertUnwindSafe};

use iridis_surface::formats::{read_bytes, write_bytes, Format};
use iridis_surface::fuzz::mutate;
use iridis_surface::generate::{Generator, Grid};
use iridis_surface::rng::Rng;
use iridis_surface::LoadOptions;

fn seeds() -> Vec<(&'static str, Vec<Vec<u8>>)> {
    let grid = Grid { size_x_nm: 1200.0, size_y_nm: 800.0, pixel_nm: 100.0, angle_rad: 0.2, seed: 1 };
    let hf = Generator::Sine { period_nm: 400.0, depth_nm: 30.0 }.generate(&grid).unwrap();
    let enc = |f| write_bytes(&hf, f).unwrap().0;
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/");
    let file = |n: &str| std::fs::read(format!("{dir}{n}")).unwrap();
    let tiff = {
        let img = image::ImageBuffer::from_fn(12, 8, |x, y| image::Luma([(x * 5000 + y * 300) as u16]));
        let mut c = std::io::Cursor::new(Vec::new());
        img.write_to(&mut c, image::ImageFormat::Tiff).unwrap();
        c.into_inner()
    };
    vec![
        ("gwy", vec![enc(Format::Gwy), file("gwyfile_two_channels.gwy")]),
        ("npy", vec![enc(Format::Npy), file("numpy_f32_fortran.npy"), file("numpy_f64_bigendian.npy")]),
        ("npz", vec![enc(Format::Npz), file("numpy_savez.npz"), file("numpy_savez_compressed.npz")]),
        ("png/tiff", vec![enc(Format::Png), tiff]),
        ("text", vec![enc(Format::Text), b"# Width: 2 um\n# Value units: m\n1e-9 2e-9\n3e-9 4e-9\n".to_vec()]),
        ("gsf", vec![enc(Format::Gsf)]),
        ("sxm", vec![file("nanonis_synthetic.sxm")]),
    ]
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let iters: u64 = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(20_000);
    let seed: u64 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(1);
    std::panic::set_hook(Box::new(|_| {}));
    let opts = LoadOptions { pixel_size_nm: Some(10.0), max_height_nm: Some(100.0), ..Default::default() };
    let mut failures = 0;
    for (name, inputs) in seeds() {
        let mut rng = Rng::new(seed ^ name.len() as u64);
        let (mut ok, mut err) = (0u64, 0u64);
        let t = std::time::Instant::now();
        for i in 0..iters {
            let a = &inputs[(i as usize) % inputs.len()];
            let b = &inputs[(i as usize + 1) % inputs.len()];
            let data = mutate(&mut rng, a, b);
            match catch_unwind(AssertUnwindSafe(|| read_bytes(&data, "fuzz", None, &opts))) {
                Ok(Ok(_)) => ok += 1,
                Ok(Err(_)) => err += 1,
                Err(_) => {
                    failures += 1;
                    let path = format!("fuzz-crash-{name}-{seed}-{i}.bin").replace('/', "_");
                    let _ = std::fs::write(&path, &data);
                    eprintln!("PANIC in {name} parser, seed {seed}, iteration {i}: input saved to {path}");
                }
            }
        }
        println!("{name:9} {iters} inputs in {:.1?}: {ok} parsed, {err} refused with an error", t.elapsed());
    }
    if failures > 0 {
        eprintln!("{failures} panics");
        std::process::exit(1);
    }
    println!("no panics");
}
