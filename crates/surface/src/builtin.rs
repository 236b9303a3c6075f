//! `builtin:NAME[?key=value&…]` surfaces and the one parameter parser shared with
//! `iridis surface generate`. Defaults (a 65 µm patch at 65 nm per pixel, 1000 × 1000 samples, seed 1,
//! angle 0) are documented in [`HELP`]; `LoadOptions::size_nm`, `pixel_size_nm` and `seed` override them,
//! and the query string overrides those: `builtin:elaphe?size=16um&pixel=50nm&seed=3&angle=10deg`.

use iridis_color::units::{parse_angle_rad, parse_length_nm};

use crate::generate::{blazed_depth, BumpShape, Generator, Grid};
use crate::{HeightField, LoadOptions, SurfaceError};

/// Names accepted after `builtin:`.
pub const BUILTIN_NAMES: [&str; 6] = ["blazed", "sine", "cd", "elaphe", "xenopeltis", "gaussian"];
/// Every generator kind (the built-ins plus the bump lattices).
pub const KINDS: [&str; 8] = ["sine", "blazed", "rect-bumps", "tri-bumps", "cd", "gaussian", "elaphe", "xenopeltis"];

/// The defaults and parameters of every kind, for `--help` and the guide.
pub const HELP: &str = "\
Common parameters: size=65um (square patch; size-x, size-y for a rectangle), pixel=65nm, angle=0deg
(counter-clockwise rotation of the pattern), and seed=1 for the random ones (cd, gaussian, elaphe,
xenopeltis). Lengths need units (nm, um, µm, mm), angles deg or rad.
  sine        period=1100nm depth=100nm              h = depth/2 · sin(2π u/period)
  blazed      period=2500nm blaze=6deg | depth=…     saw-tooth rising along +x: facets face −x
                                                     (6° blazes green, d·sin 2β = 520 nm, depth 263 nm)
  rect-bumps  period=1100nm (period-x, period-y) fill=0.5 depth=100nm   Stam's boxes, paper Fig. 11a
  tri-bumps   same parameters                        pyramids on the same footprint, paper Fig. 11c
  cd          pitch=1600nm bit=231nm pit-width=500nm depth=110nm   tracks along x, pits/lands 3T–11T
  gaussian    rms=30nm corr=500nm                    correlation rms²·exp(−r²/corr²), tiles seamlessly
  elaphe      spacing=1100nm finger=4000nm rms=60nm  overlapping nanofinger layers along x
  xenopeltis  along=1500nm across=550nm depth=120nm  curving fingers, grains of slightly different period";

fn len(key: &str, v: &str) -> Result<f64, SurfaceError> {
    parse_length_nm(v).map_err(|e| SurfaceError::invalid(format!("{key}: {e}")))
}

/// Builds a generator and its grid from `key=value` pairs over the defaults (and `base`'s grid).
pub fn from_params(kind: &str, params: &[(String, String)], base: &Grid) -> Result<(Generator, Grid), SurfaceError> {
    let mut grid = base.clone();
    let mut gen = default_generator(kind)?;
    let mut blaze: Option<f64> = None;
    let mut depth_given = false;
    let mut seed_given = false;
    for (k, v) in params {
        let k = k.trim().to_ascii_lowercase().replace('_', "-");
        let v = v.trim();
        match k.as_str() {
            "size" => {
                let s = len(&k, v)?;
                grid.size_x_nm = s;
                grid.size_y_nm = s;
            }
            "size-x" | "width" => grid.size_x_nm = len(&k, v)?,
            "size-y" => grid.size_y_nm = len(&k, v)?,
            "pixel" | "pixel-size" => grid.pixel_nm = len(&k, v)?,
            "angle" => grid.angle_rad = parse_angle_rad(v).map_err(|e| SurfaceError::invalid(format!("angle: {e}")))?,
            "seed" => {
                grid.seed =
                    v.parse().map_err(|_| SurfaceError::invalid(format!("seed '{v}' is not a whole number ≥ 0")))?;
                seed_given = true;
            }
            _ => {
                set_param(&mut gen, &k, v, &mut blaze)?;
                depth_given |= k == "depth";
            }
        }
    }
    if seed_given {
        refuse_unused_seed(&gen, &format!("seed {}", grid.seed))?;
    }
    if let (Some(b), Generator::Blazed { period_nm, depth_nm }) = (blaze, &mut gen) {
        if depth_given {
            return Err(SurfaceError::invalid(
                "give either blaze=ANGLE or depth=LENGTH for a blazed grating, not both",
            ));
        }
        if !(b > 0.0 && b < std::f64::consts::FRAC_PI_2) {
            return Err(SurfaceError::invalid("blaze angle must be between 0° and 90°"));
        }
        *depth_nm = blazed_depth(*period_nm, b);
    } else if let Generator::Blazed { period_nm, depth_nm } = &mut gen {
        if !depth_given {
            *depth_nm = blazed_depth(*period_nm, 6f64.to_radians());
        }
    }
    Ok((gen, grid))
}

/// A seed for a structure with no randomness would change nothing: refused, naming the kinds it shapes.
fn refuse_unused_seed(gen: &Generator, said: &str) -> Result<(), SurfaceError> {
    if gen.is_random() {
        return Ok(());
    }
    let random: Vec<&str> =
        KINDS.iter().copied().filter(|k| default_generator(k).is_ok_and(|g| g.is_random())).collect();
    Err(SurfaceError::invalid(format!(
        "{said} would be ignored: {} has no randomness (a seed shapes {})",
        gen.kind(),
        random.join(", ")
    )))
}

fn default_generator(kind: &str) -> Result<Generator, SurfaceError> {
    Ok(match kind {
        "sine" => Generator::Sine { period_nm: 1100.0, depth_nm: 100.0 },
        "blazed" => Generator::Blazed { period_nm: 2500.0, depth_nm: blazed_depth(2500.0, 6f64.to_radians()) },
        "rect-bumps" | "tri-bumps" => Generator::Bumps {
            shape: if kind == "rect-bumps" { BumpShape::Rect } else { BumpShape::Tri },
            period_u_nm: 1100.0,
            period_v_nm: 1100.0,
            fill: 0.5,
            depth_nm: 100.0,
        },
        "cd" => Generator::Cd { pitch_nm: 1600.0, bit_nm: 231.0, pit_width_nm: 500.0, depth_nm: 110.0 },
        "gaussian" => Generator::Gaussian { rms_nm: 30.0, corr_nm: 500.0 },
        "elaphe" => Generator::Elaphe { spacing_nm: 1100.0, finger_nm: 4000.0, rms_nm: 60.0 },
        "xenopeltis" => Generator::Xenopeltis { along_nm: 1500.0, across_nm: 550.0, depth_nm: 120.0 },
        other => {
            return Err(SurfaceError::invalid(format!("unknown surface kind '{other}'; known: {}", KINDS.join(", "))))
        }
    })
}

fn set_param(gen: &mut Generator, key: &str, v: &str, blaze: &mut Option<f64>) -> Result<(), SurfaceError> {
    let kind = gen.kind();
    let unknown = || {
        SurfaceError::invalid(format!(
            "'{key}' is not a parameter of {kind}; see `iridis surface generate --help` for each kind's parameters"
        ))
    };
    match (gen, key) {
        (Generator::Sine { period_nm, .. } | Generator::Blazed { period_nm, .. }, "period") => {
            *period_nm = len(key, v)?
        }
        (Generator::Sine { depth_nm, .. } | Generator::Blazed { depth_nm, .. }, "depth") => *depth_nm = len(key, v)?,
        (Generator::Blazed { .. }, "blaze") => {
            *blaze = Some(parse_angle_rad(v).map_err(|e| SurfaceError::invalid(format!("blaze: {e}")))?)
        }
        (Generator::Bumps { period_u_nm, period_v_nm, .. }, "period") => {
            *period_u_nm = len(key, v)?;
            *period_v_nm = *period_u_nm;
        }
        (Generator::Bumps { period_u_nm, .. }, "period-x") => *period_u_nm = len(key, v)?,
        (Generator::Bumps { period_v_nm, .. }, "period-y") => *period_v_nm = len(key, v)?,
        (Generator::Bumps { fill, .. }, "fill") => {
            *fill = v.parse().map_err(|_| SurfaceError::invalid(format!("fill '{v}' is not a number in (0, 1]")))?
        }
        (Generator::Bumps { depth_nm, .. }, "depth") => *depth_nm = len(key, v)?,
        (Generator::Cd { pitch_nm, .. }, "pitch") => *pitch_nm = len(key, v)?,
        (Generator::Cd { bit_nm, .. }, "bit") => *bit_nm = len(key, v)?,
        (Generator::Cd { pit_width_nm, .. }, "pit-width") => *pit_width_nm = len(key, v)?,
        (Generator::Cd { depth_nm, .. }, "depth") => *depth_nm = len(key, v)?,
        (Generator::Gaussian { rms_nm, .. }, "rms") => *rms_nm = len(key, v)?,
        (Generator::Gaussian { corr_nm, .. }, "corr") => *corr_nm = len(key, v)?,
        (Generator::Elaphe { spacing_nm, .. }, "spacing") => *spacing_nm = len(key, v)?,
        (Generator::Elaphe { finger_nm, .. }, "finger") => *finger_nm = len(key, v)?,
        (Generator::Elaphe { rms_nm, .. }, "rms") => *rms_nm = len(key, v)?,
        (Generator::Xenopeltis { along_nm, .. }, "along") => *along_nm = len(key, v)?,
        (Generator::Xenopeltis { across_nm, .. }, "across") => *across_nm = len(key, v)?,
        (Generator::Xenopeltis { depth_nm, .. }, "depth") => *depth_nm = len(key, v)?,
        _ => return Err(unknown()),
    }
    Ok(())
}

/// `NAME[?k=v&…]` after `builtin:` as the built-in's name (trimmed) and its options (`k=v&…`, or empty).
pub fn builtin_parts(rest: &str) -> (&str, &str) {
    let (name, query) = rest.split_once('?').unwrap_or((rest, ""));
    (name.trim(), query)
}

/// `NAME[?k=v&…]` after `builtin:`.
pub fn builtin_surface(rest: &str, opts: &LoadOptions) -> Result<HeightField, SurfaceError> {
    let (name, query) = builtin_parts(rest);
    if !BUILTIN_NAMES.contains(&name) {
        return Err(SurfaceError::invalid(format!(
            "unknown built-in surface '{name}'; built-ins: {} (other kinds via `iridis surface generate`)",
            BUILTIN_NAMES.join(", ")
        )));
    }
    let mut base = Grid::default();
    if let Some(s) = opts.size_nm {
        base.size_x_nm = s;
        base.size_y_nm = s;
    }
    if let Some(p) = opts.pixel_size_nm {
        base.pixel_nm = p;
    }
    if let Some(s) = opts.seed {
        base.seed = s;
    }
    let mut params = Vec::new();
    for pair in query.split('&').filter(|p| !p.trim().is_empty()) {
        let (k, v) = pair
            .split_once('=')
            .ok_or_else(|| SurfaceError::invalid(format!("'{pair}' in builtin:{rest} is not key=value")))?;
        if let Some((_, first)) = params.iter().find(|(key, _): &&(String, String)| key.trim() == k.trim()) {
            return Err(SurfaceError::invalid(format!(
                "builtin:{rest} gives {} twice ({first}, then {v}); give it once",
                k.trim()
            )));
        }
        params.push((k.to_string(), v.to_string()));
    }
    let (gen, grid) = from_params(name, &params, &base)?;
    // A flag and the query string that say different things: which one was meant is not ours to guess.
    let fmt = iridis_color::units::format_length;
    for (flag, given, (q_x, q_y), (b_x, b_y)) in [
        ("--size", opts.size_nm.is_some(), (grid.size_x_nm, grid.size_y_nm), (base.size_x_nm, base.size_y_nm)),
        ("--pixel-size", opts.pixel_size_nm.is_some(), (grid.pixel_nm, grid.pixel_nm), (base.pixel_nm, base.pixel_nm)),
    ] {
        if given && (q_x != b_x || q_y != b_y) {
            return Err(SurfaceError::invalid(format!(
                "builtin:{rest} asks for {} {} but {flag} says {}; give it once, in the query string or as the flag",
                if flag == "--size" { "size" } else { "pixel" },
                if q_x == q_y { fmt(q_x) } else { format!("{} × {}", fmt(q_x), fmt(q_y)) },
                fmt(b_x)
            )));
        }
    }
    if opts.seed.is_some() && grid.seed != base.seed {
        return Err(SurfaceError::invalid(format!(
            "builtin:{rest} asks for seed {} but --seed says {}; give it once, in the query string or as the flag",
            grid.seed, base.seed
        )));
    }
    if let Some(s) = opts.seed {
        refuse_unused_seed(&gen, &format!("--seed {s}"))?;
    }
    let mut hf = gen.generate(&grid)?;
    hf.meta.source = format!("builtin:{rest}");
    hf.meta.format = "builtin".into();
    Ok(hf)
}
