//! Stable-Rust fuzzing of the lookup-table reader (`LookupTable::read_npz`): a small real table is mutated with
//! `iridis_surface::fuzz::mutate` (seeded) and read; a panic is reported with its iteration, the input saved,
//! and the run fails.
//!
//!     cargo run --release -p iridis-diffraction --example fuzz_table -- [ITERATIONS] [SEED]

use std::io::Cursor;
use std::panic::{catch_unwind, AssertUnwindSafe};

use iridis_diffraction::table::{LookupTable, TableParams};
use iridis_diffraction::{Patch, SpectralSetup, TaylorTerms};
use iridis_surface::{fuzz::mutate, rng::Rng};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let iters: u64 = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(20_000);
    let seed: u64 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(1);
    let h: Vec<f64> = (0..24 * 24).map(|k| 30.0 * ((k % 24) as f64 * 0.7).sin()).collect();
    let patch = Patch::from_row_major(24, 24, 60.0, 60.0, &h).unwrap();
    let terms = TaylorTerms::compute(&patch, 4, 1000.0).unwrap();
    let spectral = SpectralSetup::new(iridis_color::Illuminant::D65, iridis_color::Observer::Cie1931, 20.0).unwrap();
    let table = LookupTable::build(&terms, &spectral, TableParams { uv_resolution: 7, uv_power: 5.0 }, "fuzz", &|_| {})
        .unwrap();
    let mut buf = Cursor::new(Vec::new());
    table.write_npz(&mut buf).unwrap();
    let good = buf.into_inner();
    std::panic::set_hook(Box::new(|_| {}));
    let mut rng = Rng::new(seed);
    let (mut ok, mut err, mut panics) = (0u64, 0u64, 0u64);
    let t = std::time::Instant::now();
    for i in 0..iters {
        let data = mutate(&mut rng, &good, &good);
        match catch_unwind(AssertUnwindSafe(|| LookupTable::read_npz(Cursor::new(data.clone()), "fuzz.npz"))) {
            Ok(Ok(_)) => ok += 1,
            Ok(Err(_)) => err += 1,
            Err(_) => {
                panics += 1;
                let path = format!("fuzz-crash-table-{seed}-{i}.npz");
                let _ = std::fs::write(&path, &data);
                eprintln!("PANIC in the table reader, seed {seed}, iteration {i}: input saved to {path}");
            }
        }
    }
    println!("table     {iters} inputs in {:.1?}: {ok} read, {err} refused with an error", t.elapsed());
    if panics > 0 {
        eprintln!("{panics} panics");
        std::process::exit(1);
    }
    println!("no panics");
}
