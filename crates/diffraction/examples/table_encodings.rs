//! What each compact table encoding (`iridis_diffraction::encoding`, the GPU's `--table-precision`) costs in
//! colour: BRDF maps from the encoded numbers (`EncodedTable::sum`, which the lookup shader reproduces to f32)
//! against the f64 lookup of the same table, CIEDE2000 of the displayed colours (exposure, clipped to the sRGB
//! cube) over the map's disk, light at 0° and 30° (φ = 40°), 1500 RU and 7500 RU.
//!
//!     iridis precompute builtin:elaphe -o elaphe.npz      # and the other built-ins
//!     cargo run --release -p iridis-diffraction --example table_encodings -- [--size 256] TABLE.npz …

use std::sync::Arc;

use iridis_color::integrate::white_point;
use iridis_color::lab::delta_e_2000;
use iridis_color::{Illuminant, Lab, Observer, Xyz};
use iridis_diffraction::encoding::{EncodedTable, TableEncoding};
use iridis_diffraction::geometry::{direction, uvw, Shading};
use iridis_diffraction::map::view_direction;
use iridis_diffraction::table::{Lookup, LookupTable, Precision};
use iridis_diffraction::Evaluator;
use rayon::prelude::*;

fn shown(x: Xyz, exposure: f64) -> Lab {
    let rgb = x.scale(exposure).to_linear_srgb().map(|c| if c.is_nan() { 0.0 } else { c.clamp(0.0, 1.0) });
    Lab::from_xyz(Xyz::from_linear_srgb(rgb), white_point(Illuminant::D65, Observer::Cie1931))
}

/// mean, p99, max.
fn stats(mut d: Vec<f64>) -> [f64; 3] {
    d.sort_by(f64::total_cmp);
    let n = d.len();
    [d.iter().sum::<f64>() / n as f64, d[((n as f64 * 0.99) as usize).min(n - 1)], d[n - 1]]
}

fn main() {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let mut size = 256usize;
    if let Some(k) = args.iter().position(|a| a == "--size") {
        size = args[k + 1].parse().expect("--size N");
        args.drain(k..k + 2);
    }
    let encodings: Vec<TableEncoding> = ["f16", "cheb8", "cheb12", "cheb16", "cheb24", "cheb12-f16", "cheb16-f16"]
        .iter()
        .map(|s| s.parse().unwrap())
        .collect();
    println!("table | encoding | MB | ΔE00 1500 RU mean / p99 / max | ΔE00 7500 RU mean / p99 / max");
    for path in &args {
        let table = Arc::new(LookupTable::load(std::path::Path::new(path)).expect("a table from iridis precompute"));
        let shading = Shading::default();
        let exact = Lookup::new(table.clone(), shading.clone(), Precision::F64).unwrap();
        let lights = [direction(0.0, 0.0), direction(30f64.to_radians(), 40f64.to_radians())];
        let pairs: Vec<([f64; 3], [f64; 3])> = lights
            .iter()
            .flat_map(|&wi| {
                (0..size * size).filter_map(move |i| view_direction(i % size, i / size, size).map(|wr| (wi, wr)))
            })
            .collect();
        let reference: Vec<Xyz> = pairs.par_iter().map(|&(wi, wr)| exact.xyz(wi, wr)).collect();
        for &e in &encodings {
            let enc = EncodedTable::encode(&table, e).unwrap();
            let xyz: Vec<Xyz> = pairs
                .par_iter()
                .map(|&(wi, wr)| {
                    let [u, v, w] = uvw(wi, wr);
                    let c = shading.factor(500.0, wi, wr);
                    let s = enc.sum(u, v, w);
                    Xyz::new(c * s[0], c * s[1], c * s[2])
                })
                .collect();
            let de = |ex: f64| {
                stats(reference.iter().zip(&xyz).map(|(a, b)| delta_e_2000(shown(*a, ex), shown(*b, ex))).collect())
            };
            let (a, b) = (de(1500.0), de(7500.0));
            println!(
                "{} | {} | {:.1} | {:.4} / {:.4} / {:.3} | {:.4} / {:.4} / {:.3}",
                table.meta.surface,
                e.name(),
                enc.bytes() as f64 / 1e6,
                a[0],
                a[1],
                a[2],
                b[0],
                b[1],
                b[2]
            );
        }
    }
}
