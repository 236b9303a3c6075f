//! A SURFACE argument (a file or `builtin:NAME`) read with its options and levelled for the diffraction model:
//! what `precompute`, `brdf-map`, `brdf eval`, the lab commands and Python's evaluators all start from.

use anyhow::{Context, Result};
use iridis_diffraction::Patch;
use iridis_surface::formats::channel::ChannelSel;
use iridis_surface::LoadOptions;

use crate::report::{with_step, Report};

/// How to read a SURFACE (with the feature `cli`, the flags of every command that reads one).
#[derive(Debug, Clone, Default)]
#[cfg_attr(feature = "cli", derive(clap::Args))]
pub struct SurfaceOptions {
    /// Pixel size for image surfaces without physical units (e.g. 65nm).
    #[cfg_attr(feature = "cli", arg(long = "pixel-size", value_name = "PIXEL_SIZE"))]
    #[cfg_attr(feature = "cli", arg(value_parser = crate::args::positive_length_nm))]
    pub pixel_size_nm: Option<f64>,
    /// Height of the brightest grey value for image surfaces (e.g. 300nm).
    #[cfg_attr(feature = "cli", arg(long = "max-height", value_name = "MAX_HEIGHT"))]
    #[cfg_attr(feature = "cli", arg(value_parser = crate::args::positive_length_nm))]
    pub max_height_nm: Option<f64>,
    /// Channel of a multi-channel file, by index or name (`iridis surface channels FILE` lists them);
    /// default the channel named Height, else the first height channel (.npz: the only 2-D array).
    #[cfg_attr(feature = "cli", arg(long))]
    pub channel: Option<ChannelSel>,
    /// Unit of heights in files that do not give one (.npy, text, a unitless channel), e.g. m or nm.
    #[cfg_attr(feature = "cli", arg(long))]
    pub height_unit: Option<String>,
    /// Levelling before the model: plane (default for files), poly, lines (median line correction), rows,
    /// mean or none (built-ins are used as generated unless this is given).
    #[cfg_attr(feature = "cli", arg(long))]
    pub level: Option<String>,
    #[cfg_attr(feature = "cli", command(flatten))]
    pub units: UnitOverrides,
}

/// What a SURFACE's own metadata may be overruled by (with the feature `cli`, flags flattened into every
/// command that reads one).
#[derive(Debug, Clone, Copy, Default)]
#[cfg_attr(feature = "cli", derive(clap::Args))]
pub struct UnitOverrides {
    /// Let --pixel-size and --height-unit replace the pixel size and height unit an instrument file states
    /// itself (without it the file's win, and a warning names both).
    #[cfg_attr(feature = "cli", arg(long))]
    pub override_units: bool,
    /// Read a channel that is not a height (an amplitude, error, phase or deformation channel, or one whose
    /// unit is not a length; `iridis surface channels FILE` marks them) as heights anyway.
    #[cfg_attr(feature = "cli", arg(long))]
    pub as_height: bool,
}

impl SurfaceOptions {
    /// The reader's options.
    pub fn load_options(&self) -> LoadOptions {
        LoadOptions {
            pixel_size_nm: self.pixel_size_nm,
            max_height_nm: self.max_height_nm,
            channel: self.channel.clone(),
            height_unit: self.height_unit.clone(),
            override_units: self.units.override_units,
            as_height: self.units.as_height,
            ..Default::default()
        }
    }

    /// These options without those that only read files (channel, height unit, height of white, the unit
    /// overrides), which a built-in refuses: for a built-in read beside a file with one set of options.
    pub fn without_file_options(&self) -> SurfaceOptions {
        SurfaceOptions { pixel_size_nm: self.pixel_size_nm, level: self.level.clone(), ..SurfaceOptions::default() }
    }

    /// The command-line flags that give these options to another command (lengths in nm): what `iridis report`
    /// passes on to each step's command line.
    pub fn flags(&self) -> Vec<String> {
        self.given().into_iter().flat_map(|(flag, value)| std::iter::once(flag.to_string()).chain(value)).collect()
    }

    /// The reading options given, each flag with its value if it has one (`("--level", Some("none"))`,
    /// `("--override-units", None)`), in [`Self::flags`]'s order.
    pub fn given(&self) -> Vec<(&'static str, Option<String>)> {
        let mut given = Vec::new();
        if let Some(c) = &self.channel {
            given.push(("--channel", Some(c.to_string())));
        }
        for (flag, v) in [("--pixel-size", self.pixel_size_nm), ("--max-height", self.max_height_nm)] {
            if let Some(v) = v {
                given.push((flag, Some(format!("{v}nm"))));
            }
        }
        if let Some(u) = &self.height_unit {
            given.push(("--height-unit", Some(u.clone())));
        }
        for (flag, on) in [("--override-units", self.units.override_units), ("--as-height", self.units.as_height)] {
            if on {
                given.push((flag, None));
            }
        }
        // Only a level that was asked for: without it, each command says which default it used.
        if let Some(l) = &self.level {
            given.push(("--level", Some(l.clone())));
        }
        given
    }
}

/// Loads a SURFACE argument as a diffraction patch, saying what the reader warned about (e.g. heights of
/// unknown unit) and how it was levelled; the model's own warnings come with the Taylor terms or the ground
/// truth.
pub fn load_patch(spec: &str, opts: &SurfaceOptions, report: &dyn Report) -> Result<Patch> {
    let load = opts.load_options();
    let hf = with_step(report, &format!("loading {spec}"), || iridis_surface::load_surface(spec, &load))
        .with_context(|| format!("cannot load surface {spec}"))?;
    // Which channel of several, why, and how to pick another (a file of one channel has nothing to choose).
    if let Some(c) = hf.meta.channel.as_ref().filter(|c| c.of > 1) {
        report.note(&format!("{spec}: {}", c.describe()));
    }
    for w in &hf.meta.warnings {
        report.warn(&format!("{spec}: {w}"));
    }
    let (hf, levelling) = iridis_surface::prep::level_for_model(spec, hf, opts.level.as_deref())?;
    report.info(&format!("{spec}: {levelling}"));
    Ok(Patch::from_row_major(hf.rows, hf.cols, hf.dx_nm, hf.dy_nm, &hf.heights_nm)?)
}

/// Where a height field comes from: a SURFACE argument (read with [`SurfaceOptions`]) or a patch already in
/// memory (Python's `iridis.surface.Surface`), with the name tables and reports give it.
#[derive(Debug, Clone)]
pub enum Source {
    Spec(String),
    Patch { patch: Patch, name: String },
}

impl Source {
    /// The name: the SURFACE argument, or the in-memory patch's.
    pub fn name(&self) -> &str {
        match self {
            Source::Spec(s) => s,
            Source::Patch { name, .. } => name,
        }
    }

    /// The patch: loaded and levelled ([`load_patch`]) for a SURFACE argument, as it is otherwise.
    pub fn patch(&self, opts: &SurfaceOptions, report: &dyn Report) -> Result<Patch> {
        match self {
            Source::Spec(s) => load_patch(s, opts, report),
            Source::Patch { patch, .. } => Ok(patch.clone()),
        }
    }
}

/// The strongest peaks of a patch's spectrum, strongest first, as `iridis surface info` finds them: period and
/// orientation (the direction of the grating vector, degrees in `[0, 180)` from +x with y up).
fn strongest_peaks(patch: &Patch, max_peaks: usize) -> Vec<iridis_surface::Peak> {
    let cols = patch.cols;
    // Back to the readers' row order (row 0 at the top); the patch keeps y growing with the row.
    let heights: Vec<f64> =
        (0..patch.rows).rev().flat_map(|j| patch.heights[j * cols..(j + 1) * cols].iter().copied()).collect();
    let Ok(hf) = iridis_surface::HeightField::new(patch.rows, cols, patch.dx, patch.dy, heights) else {
        return Vec::new();
    };
    let opts = iridis_surface::PeakOptions { max_peaks, ..iridis_surface::PeakOptions::default() };
    iridis_surface::find_peaks(&hf, &opts)
}

/// The strongest peak of a patch's spectrum, whether or not it is a period of the structure (a random surface
/// has one too): a direction to look along. `None` for a flat patch.
pub fn strongest_period(patch: &Patch) -> Option<iridis_surface::Peak> {
    strongest_peaks(patch, 1).into_iter().next()
}

/// The strongest period of a patch where it is one of its structure ([`is_dominant`]); `Err` with the strongest
/// peak and the next one's share of the height variance where it is a random surface's peak (`None` for a flat
/// patch).
pub fn dominant_period(patch: &Patch) -> Result<iridis_surface::Peak, Option<(iridis_surface::Peak, f64)>> {
    let mut peaks = strongest_peaks(patch, 2).into_iter();
    let strongest = peaks.next().ok_or(None)?;
    let next = peaks.next().map_or(0.0, |p| p.power);
    if is_dominant(strongest.power, next) {
        Ok(strongest)
    } else {
        Err(Some((strongest, next)))
    }
}

/// Below this share of the height variance in its strongest peak, and under 1.5 × the next's, a surface has no
/// dominant period. Measured: the Gaussian random surface 1.1 % (1.1 × the next) on 65 µm, 5.3 % (1.2 ×) on
/// 20 µm; Xenopeltis 4.2 % (1.75 ×), Elaphe 62 %.
pub const NO_DOMINANT_PERIOD_BELOW: f64 = 0.1;

/// Below this share of the height variance no peak is a period of the structure, however far above the next
/// (built-ins: Elaphe 0.62, the blazed grating 0.61, Xenopeltis 0.042; the AFM samples' molecules 0.015–0.10; a
/// 1500 nm sine on a 1 µm patch, shorter than its period, 0.0002, which `--unit-cell auto` took as a 289 nm
/// grating). At 0.2 %, 4 of 40 Gaussian random 5 µm patches passed (0.36–0.90 %, up to 2 × the next); a sine
/// under noise 20 times its amplitude (0.53 %) is refused with them: its averaged profile would stand for a
/// surface that is 99.5 % something else.
pub const MIN_DOMINANT_SHARE: f64 = 0.01;

/// Whether the strongest peak of a surface's spectrum, holding `strongest` of the height variance, is a period of
/// its structure rather than one of a random surface's peaks: at least [`MIN_DOMINANT_SHARE`], and
/// [`NO_DOMINANT_PERIOD_BELOW`] or 1.5 × the `next`.
pub fn is_dominant(strongest: f64, next: f64) -> bool {
    strongest >= MIN_DOMINANT_SHARE && (strongest >= NO_DOMINANT_PERIOD_BELOW || strongest >= 1.5 * next)
}

/// Why a surface's strongest peak (`strongest`, the next holding `next` of the height variance) is not a period of
/// its structure ([`is_dominant`]), in words.
pub fn why_not_dominant(strongest: &iridis_surface::Peak, next: f64) -> String {
    if strongest.power < MIN_DOMINANT_SHARE {
        format!(
            "its strongest spectral peak ({:.0} nm) holds {:.2} % of the height variance, too little for a period of \
             the structure (at least {} %)",
            strongest.period_nm,
            100.0 * strongest.power,
            iridis_color::spectrum::short_number(100.0 * MIN_DOMINANT_SHARE)
        )
    } else {
        format!(
            "its strongest spectral peak ({:.0} nm) holds {:.1} % of the height variance, {:.2} × the next peak's, the \
             peaks of a random surface (a period holds at least {:.0} %, or 1.5 × the next)",
            strongest.period_nm,
            100.0 * strongest.power,
            strongest.power / next.max(f64::MIN_POSITIVE),
            100.0 * NO_DOMINANT_PERIOD_BELOW
        )
    }
}

/// The periods (nm) of `surface info --json`'s `peaks` that are periods of the structure: all of them where the
/// strongest is dominant ([`is_dominant`]), none where the spectrum's peaks are a random surface's.
pub fn structural_periods_nm(info: &serde_json::Value) -> Vec<f64> {
    let peaks = info["peaks"].as_array().map_or(&[][..], Vec::as_slice);
    let power = |k: usize| peaks.get(k).and_then(|p| p["power"].as_f64()).unwrap_or(0.0);
    if peaks.is_empty() || !is_dominant(power(0), power(1)) {
        return Vec::new();
    }
    peaks.iter().filter_map(|p| p["period_nm"].as_f64()).collect()
}

/// Everything `iridis surface info --json` reports (keys in docs/json.md): sizes, heights, the dominant periods
/// with their orientations, roughness of the plane-levelled field, radial PSDF and ACF, notes and warnings.
pub fn info(hf: &iridis_surface::HeightField, n_peaks: usize, coherence_nm: f64) -> serde_json::Value {
    let (lo, hi) = hf.min_max();
    let opts = iridis_surface::PeakOptions { max_peaks: n_peaks, ..iridis_surface::PeakOptions::default() };
    let peaks = iridis_surface::find_peaks(hf, &opts);
    let mut warnings = hf.meta.warnings.clone();
    warnings.extend(hf.physics_warnings(coherence_nm));
    let mut notes = hf.meta.notes.clone();
    notes.extend(hf.coherence_note(coherence_nm));
    // Say where the structure is there but too long for the patch: no period found, or the periods listed carry
    // less of the variance than it (a 2500 nm grating on an 8 µm patch listed its 1250 nm harmonic alone).
    let long = iridis_surface::analysis::long_period_share(hf, &opts);
    let (too_long, cycles) = (100.0 * opts.max_period_fraction, 1.0 / opts.max_period_fraction);
    match peaks.first() {
        None if long > 0.5 => notes.push(format!(
            "no period found, but {:.0} % of the height variance lies in structure longer than {too_long:.0} % of \
             the patch (fewer than {cycles:.0} cycles across it), too few repeats to read a period from: scan a \
             larger area to measure it",
            100.0 * long,
        )),
        Some(p) if long > p.power => notes.push(format!(
            "{:.0} % of the height variance lies in structure longer than {too_long:.0} % of the patch (fewer than \
             {cycles:.0} cycles across it), more than the strongest period listed carries ({:.0} %): too few \
             repeats to read a period from, so the periods listed may be its harmonics; scan a larger area to \
             measure it",
            100.0 * long,
            100.0 * p.power
        )),
        _ => {}
    }
    // A random surface's spectrum has peaks everywhere: the strongest, holding a few per cent and barely above the
    // next, is no period of the structure (builtin:gaussian listed five "periods" of ~1 % each). Dominant as the
    // test bench's ridges are: 1.5 × the next (two equal periods of a lattice hold far more than 10 %).
    let next = peaks.get(1).map_or(0.0, |p| p.power);
    if let Some(p) = peaks.first().filter(|p| p.power < MIN_DOMINANT_SHARE) {
        notes.push(format!(
            "no dominant period: the strongest peak holds {:.2} % of the height variance, too little for a period of \
             the structure (at least {} %); the periods listed are not periods of the structure",
            100.0 * p.power,
            iridis_color::spectrum::short_number(100.0 * MIN_DOMINANT_SHARE)
        ));
    } else if let Some(p) = peaks.first().filter(|p| !is_dominant(p.power, next)) {
        notes.push(format!(
            "no dominant period: the strongest peak holds {:.1} % of the height variance, little more than the next \
             ({:.1} %), as a random surface's spectrum has peaks everywhere; the periods listed are not periods of \
             the structure",
            100.0 * p.power,
            100.0 * next
        ));
    }
    let levelled = iridis_surface::prep::level_plane(hf);
    // A plane (a flat or tilted field, or a constant channel) has nothing left once levelled: no period, and a PSDF
    // and ACF of zeros, whose figures are black; said rather than shown black.
    let (flat_lo, flat_hi) = levelled.min_max();
    if flat_hi - flat_lo <= 1e-9 * (hi - lo).abs().max(1e-3) {
        warnings.push(
            "the field is a plane: nothing is left once its tilt is levelled (rms 0 nm), so it has no periods, and \
             its PSDF and ACF are zero (their figures black); check that the data are heights (the channel read)"
                .into(),
        );
    }
    // The struct's own keys (Python's `Surface.roughness()` gives the same), and the levelling they follow.
    let mut roughness = serde_json::to_value(iridis_surface::stats::roughness(&levelled)).expect("numbers");
    roughness["levelling"] = "plane".into();
    let psdf = iridis_surface::stats::radial_of(&iridis_surface::stats::psdf(&levelled));
    let acf = iridis_surface::stats::radial_of(&iridis_surface::stats::acf(&levelled));
    serde_json::json!({
        "source": hf.meta.source,
        "format": hf.meta.format,
        "rows": hf.rows,
        "cols": hf.cols,
        "pixel_size_nm": [hf.dx_nm, hf.dy_nm],
        "extent_nm": [hf.extent_nm().0, hf.extent_nm().1],
        "height_min_nm": lo,
        "height_max_nm": hi,
        "mean_nm": hf.mean(),
        "rms_nm": hf.rms(),
        "z_unit_in_file": hf.meta.z_unit,
        // Which channel of a multi-channel file was read, why, and the file's height channels; null otherwise.
        "channel": hf.meta.channel,
        "peaks": peaks,
        "peaks_asked": n_peaks,
        "roughness": roughness,
        // Annular means of the plane-levelled field's 2-D PSDF (nm⁴, against spatial frequency) and ACF (nm²,
        // against lag), bin k at k × step.
        "psdf_radial": {"levelling": "plane", "frequency_step_per_nm": psdf.step, "values_nm4": psdf.values},
        "acf_radial": {"levelling": "plane", "lag_step_nm": acf.step, "values_nm2": acf.values},
        "notes": notes,
        "warnings": warnings,
    })
}
