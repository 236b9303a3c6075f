//! `cargo run --release -p iridis-rigorous --example bench [REPEATS]`: the library benchmark as JSON on stdout
//! (`iridis bench grating` runs the same benchmark and times grcwa on the same cases).
fn main() {
    let repeats = std::env::args().nth(1).and_then(|s| s.parse().ok()).unwrap_or(3);
    match iridis_rigorous::benchmark(&iridis_rigorous::BenchCase::standard(), repeats) {
        Ok(r) => println!("{}", serde_json::to_string_pretty(&r).expect("plain data")),
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(1);
        }
    }
}
