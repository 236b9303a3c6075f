//! Every `--help` page as a new user reads it: prose wrapped to the terminal with no word stranded on a line,
//! examples one command per line at any width — and every example, and every command in the README, runs.
//!
//! Examples run as written, each page's in a scratch folder of its own (with `data/` and `examples/` of the
//! repository linked in), in order, so that a file one example writes (`elaphe.npz`) is there for the next.
//! Two documented rules make them quick and self-contained:
//!
//! **Small sizes.** Every `builtin:NAME[?…]` is cut to a patch of at most 6 µm at no less than 1/64 of it per
//! pixel (`size=`, `pixel=` in its query string); `surface generate` gets the same patch; map and image
//! sizes (`--size N`, `--size WxH`, `--film-size WxH`) at most 24 pixels a side; `--frames` ≤ 2, `--spp` 1,
//! `--terms` ≤ 6, `--thickness A:B:STEP` at most 25 thicknesses, `--uv-resolution` ≤ 31, `--map-size` ≤ 8,
//! `--patch-sizes 64,96`, `--seconds 0.05`,
//! `--aperture` ≤ the patch, `--crop` at most 32 pixels a side. Commands that build lookup tables (their
//! `--help` lists `--uv-resolution`) get `--uv-resolution 31` when the example gives none (the default 501
//! is most of the time; brdf-map and brdf eval, which refuse it with a finished table, then get none, and an
//! example that refuses it as ignored — another method than lookup, a sweep of the grid — runs as written), and
//! those that draw a map or image of `--size N` pixels get `--size 24` (`render`:
//! `--size 24x18`) when it gives none. The benchmarks, whose defaults are full-size runs, get their small
//! equivalents when absent: `bench diffraction --map-sizes 16,24`, `bench diffraction-methods --patch-sizes
//! 64,96`, `bench diffraction-accuracy --surface` one small built-in and `--map-size 8` (its ground truth is most
//! of its time), `thinfilm bench --seconds 0.05`, `bench render --scene examples/gold_sphere.toml`, `bench grating
//! --quick`. Nothing else changes.
//!
//! **Repeats run once.** A command that, after the rules, has the same words and the same input files (byte for
//! byte) as one already run in this test process — the README and the pages share examples (`render
//! examples/rough_film.toml`, 5 s) — is not run again; its earlier outcome counts for it, failure included,
//! and the files it wrote are put into this example's folder for the commands after it. The README's test and
//! the pages' run side by side: one that comes to a command the other is running waits for its outcome.
//!
//! **Inputs.** A file an example reads that no earlier example of its page wrote is made first: height fields
//! (`.gwy`, `.npy`, `.png`, `.txt`, `.tif`) by `iridis surface generate sine` on the small patch (its heights in
//! the unit an example's `--height-unit` names); `.npz` is the
//! committed `np.savez_compressed` fixture of the surface crate (two height channels), `.sxm` its Nanonis
//! fixture; instrument files
//! (`.spm`, `.ibw`, `.jpk`, `.stp`, `.top`, `.gsf`) are the real scans of `tools/fetch_afm_samples.sh`
//! (examples that need one are skipped, saying so, when they have not been fetched); the CSV of `thinfilm fit`
//! is the spectrum (`thinfilm spectrum --csv`) of the example's own stack with every fitted parameter 10 %
//! above its start value; a beam spectrum (`--spectrum`) is CIE D65 from `data/cie/`.
//!
//! Not run, for the reason printed: the interactive window (`view`), GPU paths (`--gpu`, `bench gpu`; the GPU
//! tests run them on lavapipe) and the whole demo gallery (80 s; `demo_cli.rs` runs it with `--ignored`).

use std::path::{Path, PathBuf};

/// `iridis ARGS --help` at a terminal width of `columns` (clap reads `COLUMNS` when not on a terminal).
fn help_page(path: &[String], columns: usize) -> String {
    let out = crate::common::command()
        .args(path)
        .arg("--help")
        .env("COLUMNS", columns.to_string())
        .output()
        .expect("cannot run iridis");
    assert!(out.status.success(), "{path:?} --help: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stdout).expect("help is UTF-8")
}

/// Every command path, the top level first, in the order `--help` lists them.
fn command_paths() -> Vec<Vec<String>> {
    fn walk(path: Vec<String>, all: &mut Vec<Vec<String>>) {
        let page = help_page(&path, 1000);
        all.push(path.clone());
        let subs: Vec<String> = page
            .lines()
            .skip_while(|l| !l.starts_with("Commands:"))
            .skip(1)
            .take_while(|l| !l.trim().is_empty())
            .filter_map(|l| l.split_whitespace().next().map(str::to_string))
            .filter(|s| s != "help")
            .collect();
        for s in subs {
            let mut p = path.clone();
            p.push(s);
            walk(p, all);
        }
    }
    let mut all = Vec::new();
    walk(Vec::new(), &mut all);
    all
}

/// The lines under a page's `Examples:` heading.
fn example_lines(page: &str) -> Vec<String> {
    page.lines()
        .skip_while(|l| l.trim_end() != "Examples:")
        .skip(1)
        .take_while(|l| !l.trim().is_empty())
        .map(str::to_string)
        .collect()
}

#[test]
fn help_pages_wrap_prose_and_keep_examples_whole() {
    let paths = command_paths();
    assert!(paths.len() > 30, "only {} pages", paths.len());
    let mut problems = Vec::new();
    for path in &paths {
        let wide = example_lines(&help_page(path, 1000));
        if wide.is_empty() {
            problems.push(format!("iridis {}: no examples", path.join(" ")));
        }
        for columns in [80, 100] {
            let page = help_page(path, columns);
            let name = format!("iridis {} (at {columns} columns)", path.join(" "));
            // The examples are exactly the unwrapped ones: none split, each a command on its own line.
            let examples = example_lines(&page);
            if examples != wide {
                problems.push(format!("{name}: examples differ from the unwrapped page: {examples:#?}"));
            }
            for e in &examples {
                let cmd = e.trim_start();
                if !e.starts_with("  ") || !(cmd.starts_with("iridis ") || cmd.starts_with("xvfb-run ")) {
                    problems.push(format!("{name}: example line that is not a command: '{e}'"));
                }
            }
            for line in page.lines() {
                let t = line.trim();
                if examples.iter().any(|e| e == line) {
                    continue;
                }
                // Prose fits the terminal (clap never splits the usage line, a command itself)…
                if line.chars().count() > columns && !line.starts_with("Usage: ") {
                    problems.push(format!("{name}: line longer than {columns} columns: '{line}'"));
                }
                // …and never leaves one word alone on a line (headings end in ':'; flags and <VALUES> are
                // entries of clap's argument list).
                let lone = !t.is_empty()
                    && !t.contains(' ')
                    && !t.ends_with(':')
                    && !t.starts_with('-')
                    && !t.starts_with('<')
                    && !t.starts_with('[');
                if lone {
                    problems.push(format!("{name}: a lone word on a line: '{line}'"));
                }
            }
        }
    }
    assert!(problems.is_empty(), "{} problems:\n{}", problems.len(), problems.join("\n"));
}

// ---------------------------------------------------------------------------------------------------------
// Running the examples.

/// The repository root.
fn repo() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
}

/// Splits an example line into commands (`a && b`) of shell words, dropping the description after the
/// command (two spaces or a `#` comment). Quotes ('…', "…") group words, as in a POSIX shell.
fn commands_of(line: &str) -> Vec<Vec<String>> {
    let (mut commands, mut words, mut word) = (Vec::new(), Vec::new(), None::<String>);
    let mut quote = None;
    let mut prev = ' ';
    for c in line.trim().chars() {
        match quote {
            Some(q) if c == q => quote = None,
            Some(_) => word.get_or_insert_with(String::new).push(c),
            None if c == '\'' || c == '"' => {
                quote = Some(c);
                word.get_or_insert_with(String::new);
            }
            None if c == ' ' => {
                if prev == ' ' {
                    break; // two spaces: the description follows
                }
                words.extend(word.take());
            }
            None if c == '#' && prev == ' ' => break,
            None => word.get_or_insert_with(String::new).push(c),
        }
        prev = if quote.is_some() { 'x' } else { c };
    }
    words.extend(word.take());
    for w in words {
        if w == "&&" {
            commands.push(Vec::new());
        } else {
            if commands.is_empty() {
                commands.push(Vec::new());
            }
            commands.last_mut().unwrap().push(w);
        }
    }
    commands
}

/// The small patch of the rules: edge (nm) and pixel (nm) for a requested edge and pixel.
fn small_patch(size_nm: f64, pixel_nm: f64) -> (f64, f64) {
    let s = size_nm.min(6000.0);
    (s, pixel_nm.max(s / 64.0))
}

fn nm(s: &str) -> f64 {
    iridis_color::units::parse_length_nm(s).unwrap_or_else(|e| panic!("{s}: {e}"))
}

/// The options each command takes that the rules add when absent: `--uv-resolution` and a pixel `--size`.
#[derive(Debug, Default)]
struct Takes {
    uv_resolution: Vec<Vec<String>>,
    pixel_size: Vec<Vec<String>>,
}

impl Takes {
    fn of(paths: &[Vec<String>]) -> Self {
        let mut t = Takes::default();
        for p in paths {
            let page = help_page(p, 1000);
            if page.contains("--uv-resolution <") {
                t.uv_resolution.push(p.clone());
            }
            // A --size in pixels (not a length: `surface` commands take `--size 65um` for built-ins).
            if page.contains("--size <SIZE>") && !page.contains("edge of the square patch") {
                t.pixel_size.push(p.clone());
            }
        }
        t
    }

    /// The command path an example runs (the longest one its words start with).
    fn path_of<'a>(list: &'a [Vec<String>], words: &[String]) -> Option<&'a Vec<String>> {
        list.iter().filter(|p| words.len() > p.len() && words[1..=p.len()] == p[..]).max_by_key(|p| p.len())
    }

    /// Adds the options the rules add when absent.
    fn complete(&self, mut words: Vec<String>) -> Vec<String> {
        let has = |w: &[String], f: &str| w.iter().any(|x| x == f);
        // brdf-map and brdf eval refuse table-shaping options with a finished table (.npz read, not written);
        // the other commands check a table against their own settings, so they get the same 31.
        let reads_table = words.windows(2).any(|w| w[1].ends_with(".npz") && !OUTPUT_FLAGS.contains(&w[0].as_str()));
        let refuses = reads_table && (words[1] == "brdf-map" || words[1] == "brdf");
        if Self::path_of(&self.uv_resolution, &words).is_some() && !has(&words, "--uv-resolution") && !refuses {
            words.extend(["--uv-resolution".to_string(), "31".to_string()]);
        }
        // (`render --export-mesh` without -o renders no image, and refuses an image size.)
        let renders = words[1] != "render" || has(&words, "-o") || has(&words, "--output");
        if Self::path_of(&self.pixel_size, &words).is_some() && !has(&words, "--size") && renders {
            let size = if words[1] == "render" { "24x18" } else { "24" };
            words.extend(["--size".to_string(), size.to_string()]);
        }
        // The benchmarks' own defaults are full-size runs: the small equivalents.
        for (path, flag, value) in [
            (&["bench", "diffraction"][..], "--map-sizes", Some("16,24")),
            (&["bench", "diffraction-methods"][..], "--patch-sizes", Some("64,96")),
            (&["bench", "diffraction-accuracy"][..], "--surface", Some("builtin:blazed?size=6000nm&pixel=93.75nm")),
            (&["bench", "diffraction-accuracy"][..], "--map-size", Some("8")),
            (&["thinfilm", "bench"][..], "--seconds", Some("0.05")),
            (&["bench", "grating"][..], "--quick", None),
            // Every example scene is 40 s of CPU at any size (their tables); examples.rs renders them all.
            (&["bench", "render"][..], "--scene", Some("examples/gold_sphere.toml")),
        ] {
            if words.len() > path.len() && words[1..=path.len()] == *path && !has(&words, flag) {
                words.push(flag.to_string());
                words.extend(value.map(str::to_string));
            }
        }
        words
    }
}

/// Applies the small-size rules (module documentation) to one command's words.
fn small(words: &[String]) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    let generate = words.len() > 2 && words[1] == "surface" && words[2] == "generate";
    let (mut gen_size, mut gen_pixel) = (65_000.0, 65.0);
    let mut i = 0;
    while i < words.len() {
        let w = &words[i];
        let value = words.get(i + 1).cloned().unwrap_or_default();
        let mut flag = |f: &str, v: String| {
            out.push(f.to_string());
            out.push(v);
            i += 2;
        };
        match w.as_str() {
            _ if w.starts_with("builtin:") => {
                let (name, query) = w.split_once('?').unwrap_or((w, ""));
                let mut params: Vec<(String, String)> = query
                    .split('&')
                    .filter(|p| !p.is_empty())
                    .map(|p| p.split_once('=').map(|(k, v)| (k.to_string(), v.to_string())).unwrap())
                    .collect();
                let get = |k: &str, d: f64| params.iter().find(|p| p.0 == k).map_or(d, |p| nm(&p.1));
                let (s, p) = small_patch(get("size", 65_000.0), get("pixel", 65.0));
                params.retain(|p| p.0 != "size" && p.0 != "pixel");
                params.push(("size".into(), format!("{s}nm")));
                params.push(("pixel".into(), format!("{p}nm")));
                let q: Vec<String> = params.iter().map(|(k, v)| format!("{k}={v}")).collect();
                out.push(format!("{name}?{}", q.join("&")));
                i += 1;
            }
            "--size" if generate => {
                gen_size = nm(&value);
                i += 2;
            }
            "--pixel-size" | "--pixel" if generate => {
                gen_pixel = nm(&value);
                i += 2;
            }
            "--size" | "--film-size" => {
                let v = match value.split_once('x') {
                    Some((a, b)) => {
                        let (a, b): (f64, f64) = (a.parse().unwrap(), b.parse().unwrap());
                        let k = (24.0 / a.max(b)).min(1.0);
                        format!("{}x{}", ((a * k).round() as usize).max(2), ((b * k).round() as usize).max(2))
                    }
                    None => value.parse::<usize>().map_or(value.clone(), |n| n.min(24).to_string()),
                };
                flag(w, v);
            }
            "--frames" | "--terms" | "--uv-resolution" | "--map-size" => {
                let cap = match w.as_str() {
                    "--frames" => 2,
                    "--terms" => 6,
                    "--uv-resolution" => 31,
                    _ => 8,
                };
                flag(w, value.parse::<usize>().map_or(value.clone(), |n| n.min(cap).to_string()));
            }
            "--spp" => flag(w, "1".into()),
            // A thickness sweep A:B:STEP of a chart: at most 25 thicknesses.
            "--thickness" if value.split(':').count() == 3 => {
                let p: Vec<&str> = value.split(':').collect();
                let (a, b) = (nm(p[0]), nm(p[1]));
                flag(w, format!("{}:{}:{}nm", p[0], p[1], nm(p[2]).max((b - a) / 24.0)))
            }
            "--patch-sizes" => flag(w, "64,96".into()),
            "--seconds" => flag(w, "0.05".into()),
            // A laser's aperture is a length; the accuracy bench's is a kind (`finite`), left alone.
            "--aperture" if iridis_color::units::parse_length_nm(&value).is_ok() => {
                flag(w, format!("{}nm", nm(&value).min(6000.0)))
            }
            "--crop" => {
                let v: Vec<String> = value
                    .split(',')
                    .enumerate()
                    .map(|(k, x)| if k < 2 { "0".into() } else { x.parse::<usize>().unwrap().min(32).to_string() })
                    .collect();
                flag(w, v.join(","));
            }
            _ => {
                out.push(w.clone());
                i += 1;
            }
        }
    }
    if generate {
        let (s, p) = small_patch(gen_size, gen_pixel);
        out.extend(["--size".into(), format!("{s}nm"), "--pixel-size".into(), format!("{p}nm")]);
    }
    out
}

/// Why an example is not run, if it is not.
fn not_run(words: &[String]) -> Option<&'static str> {
    let w = |k: usize| words.get(k).map(String::as_str).unwrap_or("");
    if w(0) == "xvfb-run" || w(1) == "view" {
        Some("the interactive window on the GPU")
    } else if words.iter().any(|a| a == "--gpu") || (w(1) == "bench" && w(2) == "gpu") {
        Some("needs a GPU (the GPU tests run these paths on lavapipe)")
    } else if w(1) == "demo" && !words.iter().any(|a| a == "--only") {
        Some("the whole gallery, 80 s (demo_cli.rs runs it with --ignored)")
    } else {
        None
    }
}

/// Flags whose value is a file the command writes.
const OUTPUT_FLAGS: [&str; 16] = [
    "-o",
    "--spectra",
    "--output",
    "--out",
    "--image",
    "--plot",
    "--psdf",
    "--acf",
    "--raw",
    "--exr",
    "--csv",
    "--save",
    "--save-table",
    "--maps",
    "--convergence-plot",
    "--export-mesh",
];

/// The input files a command names (by extension), with the flag before each.
fn inputs(words: &[String]) -> Vec<String> {
    let convert = words.get(1).is_some_and(|w| w == "surface") && words.get(2).is_some_and(|w| w == "convert");
    let mut found = Vec::new();
    let mut positional_files = 0;
    for (k, w) in words.iter().enumerate().skip(1) {
        let prev = words[k - 1].as_str();
        // A word with a file extension that is not a flag, a number with a unit (`93.75nm`) or a `kind:value`.
        let is_file = Path::new(w)
            .extension()
            .and_then(|e| e.to_str())
            .is_some_and(|e| e.len() <= 4 && e.chars().all(char::is_alphanumeric))
            && !w.starts_with(|c: char| c == '-' || c.is_ascii_digit())
            && !w.contains([':', ' ', '|', '=']);
        if !is_file || OUTPUT_FLAGS.contains(&prev) {
            continue;
        }
        if !prev.starts_with('-') {
            positional_files += 1;
            if convert && positional_files == 2 {
                continue; // `surface convert IN OUT`
            }
        }
        found.push(w.clone());
    }
    found
}

/// The fetched instrument scans (tools/fetch_afm_samples.sh), as in the surface crate's tests.
fn afm_samples() -> PathBuf {
    std::env::var_os("IRIDIS_AFM_SAMPLES").map(PathBuf::from).unwrap_or_else(|| repo().join("target/afm-samples"))
}

fn run_in(dir: &Path, args: &[String]) -> std::process::Output {
    crate::common::command().args(args).current_dir(dir).output().expect("cannot run iridis")
}

/// Makes the missing input `name` of `words` in `dir` (module documentation); `Err` says why it cannot.
fn make_input(dir: &Path, name: &str, words: &[String]) -> Result<(), String> {
    let path = dir.join(name);
    let ext = Path::new(name).extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase();
    let fixtures = repo().join("crates/surface/tests/fixtures");
    let copy = |from: PathBuf| std::fs::copy(&from, &path).map(|_| ()).map_err(|e| format!("{}: {e}", from.display()));
    match ext.as_str() {
        "gwy" | "npy" | "png" | "txt" | "tif" | "tiff" => {
            let (s, p) = small_patch(65_000.0, 65.0);
            // An example that reads the heights in another unit (`--height-unit m`) gets them in that unit:
            // the sine's 100 nm depth written as 1e-7 "nm", read as metres.
            let unit = words.iter().position(|w| w == "--height-unit").and_then(|i| words.get(i + 1));
            let nm_per_unit = match unit.map(String::as_str) {
                Some("m") => 1e9,
                Some("mm") => 1e6,
                Some("um" | "µm") => 1e3,
                _ => 1.0,
            };
            let args: Vec<String> = ["surface", "generate", "sine", "-o", name, "--size", &format!("{s}nm")]
                .into_iter()
                .map(String::from)
                .chain(["--pixel-size".to_string(), format!("{p}nm")])
                .chain(
                    (nm_per_unit != 1.0)
                        .then(|| ["--depth".to_string(), format!("{}nm", 100.0 / nm_per_unit)])
                        .into_iter()
                        .flatten(),
                )
                .collect();
            let out = run_in(dir, &args);
            out.status.success().then_some(()).ok_or_else(|| String::from_utf8_lossy(&out.stderr).to_string())
        }
        "npz" => copy(fixtures.join("numpy_savez_compressed.npz")),
        "sxm" => copy(fixtures.join("nanonis_synthetic.sxm")),
        "spm" | "ibw" | "jpk" | "stp" | "top" | "gsf" => {
            let sample = afm_samples().join(format!("sample_0.{ext}"));
            if sample.exists() {
                copy(sample)
            } else {
                Err(format!("SKIPPED: {} is absent; run tools/fetch_afm_samples.sh", sample.display()))
            }
        }
        "csv" if words.iter().any(|w| w == "--spectrum") => copy(repo().join("data/cie/d65.csv")),
        "csv" if words.get(2).is_some_and(|w| w == "fit") => {
            // The example's stack with each {name=START:LO..HI} at 1.1 × START.
            let at = words.iter().position(|w| w == "--stack").ok_or("fit without --stack")?;
            let mut stack = String::new();
            let mut rest = words[at + 1].as_str();
            while let Some(open) = rest.find('{') {
                stack.push_str(&rest[..open]);
                let close = rest[open..].find('}').ok_or("unclosed {")? + open;
                let start = rest[open + 1..close].split_once('=').ok_or("no start value")?.1.split(':').next().unwrap();
                let digits = start.find(|c: char| !(c.is_ascii_digit() || c == '.')).unwrap_or(start.len());
                let v: f64 = start[..digits].parse().map_err(|_| format!("start value {start}"))?;
                stack.push_str(&format!("{}{}", v * 1.1, &start[digits..]));
                rest = &rest[close + 1..];
            }
            stack.push_str(rest);
            let mut args: Vec<String> =
                ["thinfilm", "spectrum", "--stack", &stack, "--from", "400nm", "--to", "800nm", "--step", "5nm"]
                    .into_iter()
                    .map(String::from)
                    .collect();
            if let Some(a) = words.iter().position(|w| w == "--angle") {
                args.extend(["--angle".to_string(), words[a + 1].clone()]);
            }
            args.push("--csv".into());
            let out = run_in(dir, &args);
            if !out.status.success() {
                return Err(String::from_utf8_lossy(&out.stderr).to_string());
            }
            std::fs::write(&path, &out.stdout).map_err(|e| e.to_string())
        }
        _ => Err(format!("no rule makes an input '{name}'")),
    }
}

/// What a command run left behind: the failure, if it failed, and the files it wrote (name, bytes), which a
/// repeat puts into its own folder so that the next command of its line finds them.
type Outcome = (Option<String>, Vec<(std::ffi::OsString, Vec<u8>)>);
/// A command's words and its input files' bytes.
type RunKey = (Vec<String>, Vec<Vec<u8>>);
/// The commands run so far in this process → their outcome (`None` while one test runs it).
type Ran = std::collections::HashMap<RunKey, Option<Outcome>>;

/// The files in `dir` with their modification times and sizes, to tell which ones a command wrote.
fn listing(dir: &Path) -> std::collections::HashMap<std::ffi::OsString, (std::time::SystemTime, u64)> {
    std::fs::read_dir(dir)
        .map(|entries| {
            entries
                .flatten()
                .filter_map(|e| {
                    let m = e.metadata().ok().filter(|m| m.is_file())?;
                    Some((e.file_name(), (m.modified().ok()?, m.len())))
                })
                .collect()
        })
        .unwrap_or_default()
}
static RAN: std::sync::LazyLock<std::sync::Mutex<Ran>> = std::sync::LazyLock::new(Default::default);
/// Signalled when a command that another test was waiting for has finished.
static RAN_DONE: std::sync::Condvar = std::sync::Condvar::new();

/// The outcome of `key` if a test of this process ran it — waiting while one runs it now (the README and
/// help tests run side by side and share examples) — or `None`, and then the caller runs it and must
/// [`Claim::finish`] it.
fn claim_run(key: &RunKey) -> Result<Outcome, Claim> {
    let mut ran = RAN.lock().unwrap_or_else(|e| e.into_inner());
    loop {
        match ran.get(key) {
            Some(Some(outcome)) => return Ok(outcome.clone()),
            Some(None) => ran = RAN_DONE.wait(ran).unwrap_or_else(|e| e.into_inner()),
            None => {
                ran.insert(key.clone(), None);
                return Err(Claim { key: Some(key.clone()) });
            }
        }
    }
}

/// A command this test runs; others asking for it wait until it is finished (or its runner panicked: then
/// the drop records a failure, so that no test waits for ever).
struct Claim {
    key: Option<RunKey>,
}

impl Claim {
    fn finish(mut self, outcome: Outcome) {
        Self::record(self.key.take().expect("claimed"), outcome);
    }
    fn record(key: RunKey, outcome: Outcome) {
        RAN.lock().unwrap_or_else(|e| e.into_inner()).insert(key, Some(outcome));
        RAN_DONE.notify_all();
    }
}

impl Drop for Claim {
    fn drop(&mut self) {
        if let Some(key) = self.key.take() {
            Self::record(key, (Some("the test running it panicked".to_string()), Vec::new()));
        }
    }
}

/// Runs the example lines in `dir` under the rules; returns the failures.
fn run_examples(dir: &Path, origin: &str, lines: &[String], takes: &Takes, log: &mut Vec<String>) -> Vec<String> {
    let mut failures = Vec::new();
    for line in lines {
        for words in commands_of(line) {
            if let Some(why) = not_run(&words) {
                log.push(format!("not run ({why}): {origin}: {}", line.trim()));
                eprintln!("{}", log.last().unwrap());
                continue;
            }
            assert_eq!(words[0], "iridis", "{origin}: '{line}' does not start with iridis");
            let args = takes.complete(small(&words));
            let mut skipped = None;
            for name in inputs(&args) {
                if !dir.join(&name).exists() {
                    if let Err(e) = make_input(dir, &name, &args) {
                        skipped = Some(e);
                    }
                }
            }
            if let Some(e) = skipped {
                if e.starts_with("SKIPPED") {
                    log.push(format!("{e}: {origin}: {}", line.trim()));
                    eprintln!("{}", log.last().unwrap());
                    continue;
                }
                failures.push(format!("{origin}: {}: cannot make its input: {e}", line.trim()));
                continue;
            }
            // The same words on the same bytes: the earlier run's outcome (module documentation).
            let key: RunKey =
                (args.clone(), inputs(&args).iter().map(|n| std::fs::read(dir.join(n)).unwrap_or_default()).collect());
            let claim = match claim_run(&key) {
                Ok((failed, wrote)) => {
                    for (name, bytes) in &wrote {
                        std::fs::write(dir.join(name), bytes).expect("scratch folder is writable");
                    }
                    log.push(format!(
                        "  once   {origin}: {} (ran before{})",
                        args[1..].join(" "),
                        if failed.is_some() { ", failed" } else { "" }
                    ));
                    eprintln!("{}", log.last().unwrap());
                    failures.extend(failed.map(|e| format!("{origin}: {}\n    {e}", line.trim())));
                    continue;
                }
                Err(claim) => claim,
            };
            let before = listing(dir);
            let t = std::time::Instant::now();
            let mut out = run_in(dir, &args[1..]);
            // The rules' --uv-resolution 31 refused where no table is built (another method, the parameter a
            // sweep sweeps), as it would be ignored: the example as written.
            if !out.status.success()
                && !words.iter().any(|w| w == "--uv-resolution")
                && String::from_utf8_lossy(&out.stderr).contains("--uv-resolution 31 would be ignored")
            {
                let at = args.windows(2).position(|w| w[0] == "--uv-resolution" && w[1] == "31").expect("added");
                let without: Vec<String> = args[..at].iter().chain(&args[at + 2..]).cloned().collect();
                out = run_in(dir, &without[1..]);
            }
            log.push(format!("{:6.2} s  {origin}: {}", t.elapsed().as_secs_f64(), args[1..].join(" ")));
            eprintln!("{}", log.last().unwrap()); // as it goes: a slow example shows itself
            let stderr = String::from_utf8_lossy(&out.stderr);
            let failed = (!out.status.success() || stderr.contains("panicked"))
                .then(|| format!("ran: {:?}\n    {}", &args[1..], stderr.trim()));
            let wrote = listing(dir)
                .into_iter()
                .filter(|(name, stamp)| before.get(name) != Some(stamp))
                .filter_map(|(name, _)| Some((name.clone(), std::fs::read(dir.join(&name)).ok()?)))
                .collect();
            claim.finish((failed.clone(), wrote));
            if let Some(e) = failed {
                failures.push(format!("{origin}: {}\n    {e}", line.trim()));
            }
        }
    }
    failures
}

/// A scratch folder with the repository's `data/` and `examples/` linked in.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("iridis-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    for sub in ["data", "examples"] {
        std::os::unix::fs::symlink(repo().join(sub), dir.join(sub)).unwrap();
    }
    dir
}

#[test]
fn every_help_example_runs() {
    let (mut failures, mut log) = (Vec::new(), Vec::new());
    let paths = command_paths();
    let takes = Takes::of(&paths);
    for (k, path) in paths.iter().enumerate() {
        let dir = scratch(&format!("help-examples-{k}"));
        let lines: Vec<String> = example_lines(&help_page(path, 1000));
        let origin = format!("iridis {} --help", path.join(" "));
        failures.extend(run_examples(&dir, &origin, &lines, &takes, &mut log));
        let _ = std::fs::remove_dir_all(&dir);
    }
    let _ = log; // printed as it went
    assert!(failures.is_empty(), "{} examples failed:\n{}", failures.len(), failures.join("\n"));
}

#[test]
fn every_readme_command_runs() {
    let readme = std::fs::read_to_string(repo().join("README.md")).unwrap();
    // The lines of the README's code blocks that run iridis (`cargo run --release -- ARGS` is `iridis ARGS`).
    let mut lines = Vec::new();
    let mut in_code = false;
    for l in readme.lines() {
        if l.starts_with("```") {
            in_code = !in_code;
        } else if in_code {
            if let Some(rest) = l.strip_prefix("cargo run --release -- ") {
                lines.push(format!("iridis {rest}"));
            } else if l.starts_with("iridis ") {
                lines.push(l.to_string());
            }
        }
    }
    assert!(lines.len() > 20, "only {} commands found in the README", lines.len());
    let dir = scratch("readme-examples");
    let mut log = Vec::new();
    let failures = run_examples(&dir, "README.md", &lines, &Takes::of(&command_paths()), &mut log);
    let _ = log; // printed as it went
    let _ = std::fs::remove_dir_all(&dir);
    assert!(failures.is_empty(), "{} README commands failed:\n{}", failures.len(), failures.join("\n"));
}

#[test]
fn the_rules_do_what_they_say() {
    let s = |v: &[&str]| v.iter().map(|x| x.to_string()).collect::<Vec<_>>();
    assert_eq!(
        commands_of("  iridis a 'b c' --x \"d | e\"   a note"),
        vec![s(&["iridis", "a", "b c", "--x", "d | e"])]
    );
    assert_eq!(
        commands_of("iridis a -o x.npz && iridis b x.npz  # note"),
        vec![s(&["iridis", "a", "-o", "x.npz"]), s(&["iridis", "b", "x.npz"])]
    );
    assert_eq!(
        small(&s(&["iridis", "brdf-map", "builtin:elaphe?size=10um&pixel=50nm", "--size", "256"])),
        s(&["iridis", "brdf-map", "builtin:elaphe?size=6000nm&pixel=93.75nm", "--size", "24"])
    );
    assert_eq!(
        small(&s(&["iridis", "surface", "generate", "elaphe", "--size", "20um", "--pixel-size", "40nm"])),
        s(&["iridis", "surface", "generate", "elaphe", "--size", "6000nm", "--pixel-size", "93.75nm"])
    );
    assert_eq!(
        small(&s(&["iridis", "render", "x.toml", "--size", "1024x768"])),
        s(&["iridis", "render", "x.toml", "--size", "24x18"])
    );
    assert_eq!(inputs(&s(&["iridis", "surface", "convert", "a.gwy", "b.npy", "--image", "c.png"])), s(&["a.gwy"]));
}

/// The help pages name every choice there is (issue 32: `brdf eval` and `brdf-map` did not list
/// ground-truth-periodic; the top level listed SURFACE as ".gwy, .npy, PNG/TIFF, text"). The methods are the
/// ones the parser itself lists when given an unknown one.
#[test]
fn help_lists_every_method_and_every_surface_format() {
    let out = crate::common::command()
        .args(["brdf", "eval", "builtin:sine?size=2um&pixel=50nm", "--light", "0deg", "--view", "0deg"])
        .args(["--method", "no-such-method"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    let methods: Vec<&str> = err
        .split("expected one of: ")
        .nth(1)
        .unwrap_or_else(|| panic!("no method list in: {err}"))
        .split(',')
        .map(|m| m.trim().trim_end_matches(|c: char| !c.is_alphanumeric()))
        .collect();
    assert!(methods.contains(&"ground-truth-periodic") && methods.len() >= 9, "{methods:?}");
    for page in [vec!["brdf-map".to_string()], vec!["brdf".to_string(), "eval".to_string()]] {
        let help = help_page(&page, 1000);
        for m in &methods {
            assert!(help.contains(m), "`iridis {} --help` does not list {m}", page.join(" "));
        }
    }
    let top = help_page(&[], 1000);
    let surface_line = top.split("SURFACE arguments").nth(1).expect("top-level help speaks of SURFACE");
    for ext in [".spm", ".ibw", ".jpk", ".stp", ".sxm", ".gwy", ".gsf", ".npy", ".npz", "PNG", "TIFF", "text"] {
        assert!(surface_line.contains(ext), "top-level --help: SURFACE without {ext}");
    }
}
