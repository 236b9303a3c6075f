//! Stable-Rust fuzzing of every binary parser (cargo-fuzz needs nightly): seed inputs from each format are
//! mutated with a seeded RNG (bit flips, byte overwrites with "interesting" values, truncation, splices,
//! duplicated and deleted ranges) and parsed; any panic is caught, reported with the seed and iteration,
//! and makes the run fail.
//!
//!     cargo run --release -p iridis-surface --example fuzz -- [ITERATIONS per format] [SEED]

use std::panic::{catch_unwind, AssertUnwindSafe};

use iridis_surface::formats::{read_bytes, write_bytes, Format};
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
        ("png/tiff", vec![enc(Format::Png), tiff]),
        ("text", vec![enc(Format::Text), b"# Width: 2 um\n# Value units: m\n1e-9 2e-9\n3e-9 4e-9\n".to_vec()]),
    ]
}

const INTERESTING: [u8; 10] = [0, 1, 0x7f, 0x80, 0xff, b'0', b'9', b'\n', b'.', b'e'];

fn mutate(rng: &mut Rng, src: &[u8], other: &[u8]) -> Vec<u8> {
    let mut b = src.to_vec();
    let n_ops = 1 + rng.int(0, 7);
    for _ in 0..n_ops {
        let len = b.len().max(1);
        let at = (rng.next_u64() as usize) % len;
        match rng.int(0, 6) {
            0 if !b.is_empty() => b[at] ^= 1 << rng.int(0, 7),
            1 if !b.is_empty() => b[at] = INTERESTING[rng.int(0, 9) as usize],
            2 => b.truncate(at),
            3 if !b.is_empty() => {
                // Overwrite 4 bytes with a large or negative 32-bit value (sizes and counts).
                let v = [u32::MAX, 0x7fff_ffff, 0x8000_0000, 0, 1 << 20][rng.int(0, 4) as usize].to_le_bytes();
                for (k, byte) in v.iter().enumerate() {
                    if at + k < b.len() {
                        b[at + k] = *byte;
                    }
                }
            }
            4 if !other.is_empty() => {
                let from = (rng.next_u64() as usize) % other.len();
                let n = ((rng.next_u64() as usize) % 64).min(other.len() - from);
                b.splice(at.min(b.len())..at.min(b.len()), other[from..from + n].iter().copied());
            }
            5 if !b.is_empty() => {
                let n = ((rng.next_u64() as usize) % 32).min(b.len() - at);
                let chunk: Vec<u8> = b[at..at + n].to_vec();
                b.splice(at..at, chunk);
            }
            _ if !b.is_empty() => {
                let n = ((rng.next_u64() as usize) % 32).min(b.len() - at);
                b.drain(at..at + n);
            }
            _ => {}
        }
    }
    b
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
