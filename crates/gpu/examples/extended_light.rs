//! The figures of docs/render.md "Extended light": for three scenes, the real-time approximation (the fast
//! path: prefiltered area lights and environment lights) against the converged Monte Carlo render, in CIEDE2000
//! (mean, 99th percentile; the noise floor is two Monte Carlo renders with different seeds), and the frame times
//! of the new paths against the directional-light render of the same scene, on the CPU and the GPU (lavapipe
//! where there is no GPU), all in one run.
//!
//! ```sh
//! cargo run --release -p iridis-gpu --example extended_light -- --size 160x90 --spp 256 --out /tmp/extended
//! ```
//!
//! With `--out DIR` it writes each scene's fast, Monte Carlo and directional images as PNG (the docs' pictures).

use std::time::Instant;

#[path = "../tests/common/mod.rs"]
mod common;
use common::delta_e;

use iridis_render::{parse_scene, render, Image, Scene};

/// The snake of examples/snake_elaphe.toml (Elaphe-like nanostructure along the body, Algorithm 4 over a scale
/// texture) over a ground, under `light` — TOML for the `[[light]]` and `[environment]` sections.
fn snake(light: &str, integration: &str, seed: u64) -> String {
    include_str!("snake_extended_light.toml")
        .replace("LIGHT", light)
        .replace("INTEGRATION", integration)
        .replace("SEED", &seed.to_string())
}

const SKY: &str = "[environment]\nkind = \"sky\"\nvisible = false\n";

/// A disk light above and in front (angular radius about 8° from the snake), and a dim sky.
const DISK: &str = "[[light]]\nkind = \"disk\"\nposition = [1.8, 6.0, 4.8]\nlook_at = [0, 0, 0]\nradius = 1.1\n\
                    intensity = 12\n[environment]\nkind = \"sky\"\nintensity = 0.15\nvisible = false\n";

/// The disk light's directional light: its direction and its irradiance at the origin (`L r²/(r² + d²)`
/// head-on), with the same dim sky.
fn disk_as_directional() -> String {
    let (p, r, l) = ([1.8f64, 6.0, 4.8], 1.1f64, 12.0);
    let d2 = p.iter().map(|x| x * x).sum::<f64>();
    let e = l * r * r / (r * r + d2);
    format!(
        "[[light]]\nkind = \"directional\"\ndirection = {p:?}\nintensity = {e}\n\
         [environment]\nkind = \"sky\"\nintensity = 0.15\nvisible = false\n"
    )
}

/// A scene to measure: name, the fast scene, the Monte Carlo scene's text for a seed, the directional-light peer.
type Case = (&'static str, String, Box<dyn Fn(u64) -> String>, Option<String>);

fn scene(text: &str) -> Scene {
    parse_scene(text, "extended_light.toml", std::path::Path::new(".")).expect("scene")
}

fn timed<T>(f: impl FnOnce() -> T) -> (T, f64) {
    let t = Instant::now();
    let x = f();
    (x, t.elapsed().as_secs_f64())
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let get = |k: &str| args.iter().position(|a| a == k).and_then(|i| args.get(i + 1)).cloned();
    let (w, h) = get("--size")
        .and_then(|s| s.split_once('x').and_then(|(a, b)| Some((a.parse().ok()?, b.parse().ok()?))))
        .unwrap_or((160u32, 90u32));
    let spp: u32 = get("--spp").and_then(|s| s.parse().ok()).unwrap_or(256);
    let out = get("--out").map(std::path::PathBuf::from);
    if let Some(d) = &out {
        std::fs::create_dir_all(d).expect("output directory");
    }
    let gpu = iridis_gpu::Gpu::new().ok();
    let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
    println!(
        "{w}×{h}, Monte Carlo {spp} spp; CPU: {} threads; GPU: {}; load average at the start: {}",
        rayon::current_num_threads(),
        gpu.as_ref().map_or("none".into(), |g| g.adapter_name()),
        load.split_whitespace().take(3).collect::<Vec<_>>().join(" ")
    );
    let save = |name: &str, img: &Image| {
        if let Some(d) = &out {
            let png = img.encode_png(1.0, iridis_color::Encoding::Srgb).expect("png");
            std::fs::write(d.join(format!("{name}.png")), png).expect("write");
        }
    };
    let cases: Vec<Case> = vec![
        ("snake under a sky", snake(SKY, "fast", 0), Box::new(|s| snake(SKY, "monte-carlo", s)), None),
        (
            "snake under a disk light",
            snake(DISK, "fast", 0),
            Box::new(|s| snake(DISK, "monte-carlo", s)),
            Some(snake(&disk_as_directional(), "fast", 0)),
        ),
    ];
    for (name, fast_text, mc_text, directional) in &cases {
        let key = name.replace(' ', "_");
        let fast_scene = scene(fast_text);
        // Build the tables before timing.
        let _ = render(&fast_scene, 8, 8, 1, &|_| {});
        let (fast, t_fast) = timed(|| render(&fast_scene, w, h, 1, &|_| {}));
        let mc_scene = scene(&mc_text(0));
        let (mc, t_mc) = timed(|| render(&mc_scene, w, h, spp, &|_| {}));
        let mc2 = render(&scene(&mc_text(1)), w, h, spp, &|_| {});
        let (m, p) = delta_e(&fast, &mc);
        let (nm, np) = delta_e(&mc2, &mc);
        println!("\n{name}:");
        println!("  fast vs converged Monte Carlo: ΔE00 mean {m:.2}, p99 {p:.2} (noise floor, two MC seeds: {nm:.2} / {np:.2})");
        println!(
            "  CPU: fast {:.3} s/frame; Monte Carlo {:.4} s per sample of every pixel ({t_mc:.1} s for {spp})",
            t_fast,
            t_mc / spp as f64
        );
        save(&format!("{key}_fast"), &fast);
        save(&format!("{key}_monte_carlo"), &mc);
        if let Some(d) = directional {
            let ds = scene(d);
            let (img, t_dir) = timed(|| render(&ds, w, h, 1, &|_| {}));
            println!("  CPU: the directional-light render of the same scene {t_dir:.3} s/frame");
            save(&format!("{key}_directional"), &img);
        }
        if let Some(g) = &gpu {
            let gf = iridis_gpu::GpuScene::new(g, &fast_scene).expect("GPU scene");
            let _ = gf.render(w, h, 1, &|_| {});
            let (img, t) = timed(|| gf.render(w, h, 1, &|_| {}).expect("GPU"));
            let (gm, gp) = delta_e(&img, &fast);
            let gm_scene = iridis_gpu::GpuScene::new(g, &mc_scene).expect("GPU scene");
            let n = spp.min(64);
            let (gimg, tg) = timed(|| gm_scene.render(w, h, n, &|_| {}).expect("GPU"));
            let (mm, mp) = delta_e(&gimg, &mc);
            print!("  GPU: fast {t:.3} s/frame (ΔE00 to the CPU's fast {gm:.2} / {gp:.2}); Monte Carlo {:.4} s per sample of every pixel (at {n} spp, passes of 8: ΔE00 to the CPU's {spp} spp {mm:.2} / {mp:.2})", tg / n as f64);
            if let Some(d) = directional {
                let gd = iridis_gpu::GpuScene::new(g, &scene(d)).expect("GPU scene");
                let _ = gd.render(w, h, 1, &|_| {});
                let (_, td) = timed(|| gd.render(w, h, 1, &|_| {}).expect("GPU"));
                print!("; directional {td:.3} s/frame");
            }
            println!();
        }
    }
}
