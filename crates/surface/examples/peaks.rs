//! Prints the analysed periods of every built-in surface (and how long generation and analysis take).
use iridis_surface::{find_peaks, load_surface, LoadOptions, PeakOptions};

fn main() {
    let specs: Vec<String> = std::env::args().skip(1).collect();
    let specs = if specs.is_empty() {
        iridis_surface::BUILTIN_NAMES.iter().map(|n| format!("builtin:{n}")).collect()
    } else {
        specs
    };
    for s in specs {
        let t = std::time::Instant::now();
        let hf = match load_surface(&s, &LoadOptions::default()) {
            Ok(h) => h,
            Err(e) => {
                println!("{s}: error: {e}");
                continue;
            }
        };
        let tg = t.elapsed();
        let peaks = find_peaks(&hf, &PeakOptions::default());
        println!(
            "{s}: {}×{} rms {:.1} nm, generated in {:.2?}, analysed in {:.2?}",
            hf.rows,
            hf.cols,
            hf.rms(),
            tg,
            t.elapsed() - tg
        );
        for p in peaks {
            println!("   period {:9.2} nm  orientation {:7.2}°  power {:.4}", p.period_nm, p.orientation_deg, p.power);
        }
    }
}
