//! Channels: instrument files hold several images (height trace and retrace, amplitude, phase, …). Each
//! reader lists them as [`ChannelInfo`]; the user picks one by index or by name ([`ChannelSel`]), and
//! without a choice the channel named "Height" is read where there is one (as AFMReader and TopoStats read
//! Bruker files), else the first height-like channel (a length unit, named like a height). A channel whose
//! name says it is another signal (amplitude, error, phase, deformation, …) or whose unit is not a length is
//! not a height: it is refused as one unless the user forces it (`LoadOptions::as_height`).

use std::str::FromStr;

use serde::Serialize;

use crate::SurfaceError;

use super::{LoadOptions, Sidecar};

/// One image in a file, as `iridis surface channels` lists it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ChannelInfo {
    /// What `--channel N` selects (file order from 0; Gwyddion: the container's `/N/data` number).
    pub index: u32,
    /// The instrument's name for it (`Height`, `HeightTracee`, `height`, `Z`, …).
    pub name: String,
    pub rows: usize,
    pub cols: usize,
    /// Unit of the stored values after the file's scaling (`m`, `nm`, `V`, `deg`, …; empty when unknown).
    pub z_unit: String,
    /// Scan direction (`trace`/`retrace`, `forward`/`backward`), empty when the file does not say.
    pub direction: String,
    /// Another name the channel is known by (igor2 and AFMReader read Asylum's `HeightTrace\0e` label as
    /// `HeightTracee`); empty when none.
    #[serde(skip_serializing_if = "String::is_empty")]
    pub alias: String,
}

impl ChannelInfo {
    /// Whether the values are lengths.
    pub fn is_length(&self) -> bool {
        length_nm(&self.z_unit).is_some()
    }

    /// Whether the channel is the surface's height: its unit is a length (or unknown) and its name is not that
    /// of another signal ([`other_signal`]). A tapping amplitude or a deformation is in metres too.
    pub fn is_height(&self) -> bool {
        (self.is_length() || self.z_unit.is_empty()) && other_signal(&self.name).is_none()
    }

    /// `name` plus direction, the form AFMReader uses (`height_trace`).
    pub fn full_name(&self) -> String {
        if self.direction.is_empty() {
            self.name.clone()
        } else {
            format!("{}_{}", self.name, self.direction)
        }
    }

    fn describe(&self) -> String {
        let unit = if self.z_unit.is_empty() { "unit unknown".to_string() } else { self.z_unit.clone() };
        let dir = if self.direction.is_empty() { String::new() } else { format!(", {}", self.direction) };
        format!("{}: {} ({}{dir})", self.index, self.name, unit)
    }
}

/// nm per unit of a channel's stored values. Instrument units are SI, so `A` is the ampere of a current
/// channel, not an ångström.
fn length_nm(unit: &str) -> Option<f64> {
    // A unit as the readers annotate it ("nm (assumed)", "um (--height-unit)") is still that unit: a .npy's
    // assumed nm was listed "(not a height)" while every command read it as heights.
    let unit = unit.split(" (").next().unwrap_or(unit).trim();
    if unit == "A" {
        None
    } else {
        super::unit_to_nm(unit)
    }
}

/// Signals an AFM records beside the height, some of them in a length unit (the tapping amplitude, the
/// feedback error, the deformation): the word in a channel's name that says so, or `None` for a name that
/// may be a height.
pub fn other_signal(name: &str) -> Option<&'static str> {
    const OTHERS: &[&str] = &[
        "amplitude",
        "deflection",
        "error",
        "deformation",
        "phase",
        "friction",
        "lateral",
        "current",
        "adhesion",
        "modulus",
        "stiffness",
        "dissipation",
        "force",
        "potential",
        "frequency",
        "userin",
        "bias",
        "voltage",
        "capacitance",
        "kelvin",
    ];
    let n = norm(name);
    OTHERS.iter().copied().find(|w| n.contains(w))
}

/// `--channel`: a number (index) or a name.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum ChannelSel {
    Index(u32),
    Name(String),
}

impl FromStr for ChannelSel {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        let t = s.trim();
        if t.is_empty() {
            return Err("a channel is a number (e.g. 2) or a name (e.g. Height); `iridis surface channels FILE` \
                        lists them"
                .into());
        }
        Ok(match t.parse::<u32>() {
            Ok(n) => ChannelSel::Index(n),
            Err(_) => ChannelSel::Name(t.to_string()),
        })
    }
}

impl std::fmt::Display for ChannelSel {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ChannelSel::Index(i) => write!(f, "{i}"),
            ChannelSel::Name(n) => write!(f, "{n}"),
        }
    }
}

/// The list in one line for messages.
pub fn listing(list: &[ChannelInfo]) -> String {
    list.iter().map(ChannelInfo::describe).collect::<Vec<_>>().join("; ")
}

fn norm(s: &str) -> String {
    s.chars().filter(|c| c.is_alphanumeric()).flat_map(char::to_lowercase).collect()
}

/// Position in `list` of the chosen channel, or of the default: the first channel named "Height" (trace
/// before retrace, as AFMReader reads Bruker files), else the first height channel whose name says
/// height/topography/Z, else the first height channel, else the first one.
pub fn pick(list: &[ChannelInfo], sel: Option<&ChannelSel>) -> Result<usize, SurfaceError> {
    if list.is_empty() {
        return Err(SurfaceError::invalid("the file holds no image channel"));
    }
    match sel {
        Some(ChannelSel::Index(i)) => list
            .iter()
            .position(|c| c.index == *i)
            .ok_or_else(|| SurfaceError::invalid(format!("no channel {i}; the file's channels are {}", listing(list)))),
        Some(ChannelSel::Name(n)) => {
            let want = norm(n);
            // Exact name with direction first (height_retrace), then the name alone (first direction wins).
            list.iter()
                .position(|c| norm(&c.full_name()) == want)
                .or_else(|| list.iter().position(|c| norm(&c.name) == want))
                .or_else(|| list.iter().position(|c| !c.alias.is_empty() && norm(&c.alias) == want))
                .ok_or_else(|| {
                    SurfaceError::invalid(format!(
                        "no channel named '{n}'; the file's channels are {} (pick one with --channel NAME or \
                         --channel N)",
                        listing(list)
                    ))
                })
        }
        None => Ok(default_rule(list).map_or(0, |(i, _)| i)),
    }
}

fn heightish(c: &ChannelInfo) -> bool {
    let n = norm(&c.name);
    n.contains("height") || n.contains("topo") || n == "z" || n.starts_with("zsensor")
}

/// The default channel and the rule that chose it; `None` when no channel is a height.
pub(crate) fn default_rule(list: &[ChannelInfo]) -> Option<(usize, &'static str)> {
    let named_height = |c: &ChannelInfo| norm(&c.name) == "height" && c.is_height();
    if let Some(i) = list.iter().position(named_height) {
        return Some((i, "the channel named Height, as AFMReader and TopoStats read it"));
    }
    if let Some(i) = list.iter().position(|c| c.is_height() && c.is_length() && heightish(c)) {
        return Some((i, "the first channel named like a height, in a length unit"));
    }
    list.iter().position(|c| c.is_height() && c.is_length()).map(|i| (i, "the first channel in a length unit"))
}

/// Which channel was read and why, as every command says it ([`crate::Metadata::channel`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ChannelChoice {
    /// What `--channel N` selects.
    pub index: u32,
    pub name: String,
    /// Scan direction, empty when the file does not record one.
    pub direction: String,
    /// How many channels the file holds.
    pub of: usize,
    /// Why this one: `--channel` as given, the file's only channel, or the default's rule.
    pub reason: String,
    /// The file's height channels (`index: name_direction`), the ones `--channel` should pick.
    pub heights: Vec<String>,
}

impl ChannelChoice {
    /// The choice of `list[pos]` under the user's selection `sel`.
    pub fn new(list: &[ChannelInfo], pos: usize, sel: Option<&ChannelSel>) -> Self {
        let c = &list[pos];
        let reason = match sel {
            Some(s @ ChannelSel::Index(_)) => format!("as asked (--channel {s})"),
            Some(s @ ChannelSel::Name(_)) => format!("as asked (--channel '{s}')"),
            None if list.len() == 1 => "the file's only channel".to_string(),
            None => match default_rule(list) {
                Some((i, why)) if i == pos => format!("the default: {why}"),
                _ => "the default: the first channel (none is a height)".to_string(),
            },
        };
        ChannelChoice {
            index: c.index,
            name: c.name.clone(),
            direction: c.direction.clone(),
            of: list.len(),
            reason,
            heights: list.iter().filter(|c| c.is_height()).map(|c| format!("{}: {}", c.index, c.full_name())).collect(),
        }
    }

    /// One line: which channel, why, and how to pick another.
    pub fn describe(&self) -> String {
        let dir = if self.direction.is_empty() { String::new() } else { format!(" ({})", self.direction) };
        if self.of <= 1 {
            return format!("channel {} '{}'{dir}, the file's only channel", self.index, self.name);
        }
        let heights = if self.heights.is_empty() { "none".to_string() } else { self.heights.join(", ") };
        format!(
            "channel {} '{}'{dir} of {}, {}; height channels: {heights}; pick another with --channel NAME or \
             --channel N (`iridis surface channels FILE` lists all)",
            self.index, self.name, self.of, self.reason
        )
    }
}

/// How a channel's stored values become heights ([`z_scale`]).
#[derive(Debug, Clone, PartialEq)]
pub struct ZScale {
    /// nm per stored unit.
    pub nm_per_unit: f64,
    /// The unit the values are read in, as reported (`m`, `µm (--height-unit, --override-units)`, …).
    pub unit: String,
    /// What the user should know: a flag that the file's own unit overrode, or that overrode it.
    pub warnings: Vec<String>,
}

/// The height unit the user gave (`--height-unit`, else the sidecar's): (nm per unit, the unit, where from).
fn given_unit(opts: &LoadOptions, side: Option<&Sidecar>) -> Result<Option<(f64, String, String)>, SurfaceError> {
    if let Some(u) = &opts.height_unit {
        let k = super::unit_to_nm(u).ok_or_else(|| {
            SurfaceError::invalid(format!("--height-unit '{u}' is not a length unit (m, um, µm, nm, pm, Å)"))
        })?;
        return Ok(Some((k, u.clone(), format!("--height-unit {u}"))));
    }
    Ok(side.and_then(|s| {
        let u = s.height_unit.clone()?;
        Some((s.height_scale()?, u.clone(), format!("the sidecar's height_unit \"{u}\"")))
    }))
}

/// nm per stored unit of channel `c`, or why it is not a height. The file's unit wins over a contradicting
/// `--height-unit` (or sidecar) unless `opts.override_units`; a channel that is not a height (another
/// signal's name, or a unit that is not a length) is refused unless `opts.as_height`, and then needs a
/// height unit where its own is not a length. `unitless`: what a channel without a unit is taken as when the
/// user gives none (nm per unit, the unit, how to say it; Gwyddion: metres, its AFM convention), `None` to ask
/// for `--height-unit`.
pub fn z_scale(
    list: &[ChannelInfo],
    c: &ChannelInfo,
    opts: &LoadOptions,
    side: Option<&Sidecar>,
    unitless: Option<(f64, &str, &str)>,
) -> Result<ZScale, SurfaceError> {
    let given = given_unit(opts, side)?;
    let mut warnings = Vec::new();
    let heights = {
        let h: Vec<String> =
            list.iter().filter(|c| c.is_height()).map(|c| format!("{}: {}", c.index, c.full_name())).collect();
        if h.is_empty() {
            "none in this file".to_string()
        } else {
            h.join(", ")
        }
    };
    let unit_shown = if c.z_unit.is_empty() { "no unit".to_string() } else { c.z_unit.clone() };
    if let Some(word) = other_signal(&c.name) {
        if !opts.as_height {
            return Err(SurfaceError::invalid(format!(
                "channel {} '{}' ({unit_shown}) records the {word}, not the surface's height; the height channels \
                 are {heights} (pick one with --channel), or give --as-height to read this one as heights anyway",
                c.index,
                c.full_name()
            )));
        }
        warnings.push(format!(
            "channel {} '{}' records the {word}, not the height; read as heights because of --as-height",
            c.index,
            c.full_name()
        ));
    }
    if let Some(k) = length_nm(&c.z_unit) {
        if opts.as_height && other_signal(&c.name).is_none() {
            return Err(SurfaceError::invalid(format!(
                "--as-height would be ignored: channel {} '{}' is a height already (in {}); it reads another \
                 signal's channel as heights",
                c.index,
                c.full_name(),
                c.z_unit
            )));
        }
        return Ok(match given {
            Some((gk, u, from)) if (gk / k - 1.0).abs() > 1e-9 => {
                if opts.override_units {
                    warnings.push(format!(
                        "{from} overrides the file's unit: the values it stores in {} are read as {u} \
                         (--override-units)",
                        c.z_unit
                    ));
                    ZScale { nm_per_unit: gk, unit: format!("{u} ({from}, --override-units)"), warnings }
                } else {
                    warnings.push(format!(
                        "{from} ignored: the file gives this channel's heights in {}; --override-units reads its \
                         values as {u} instead",
                        c.z_unit
                    ));
                    ZScale { nm_per_unit: k, unit: c.z_unit.clone(), warnings }
                }
            }
            _ => ZScale { nm_per_unit: k, unit: c.z_unit.clone(), warnings },
        });
    }
    if c.z_unit.is_empty() {
        if let Some((gk, u, from)) = given {
            return Ok(ZScale { nm_per_unit: gk, unit: format!("{u} ({from})"), warnings });
        }
        if let Some((k, u, said)) = unitless {
            warnings.push(format!(
                "the file gives no height unit for channel {} '{}'; assumed {said} (give --height-unit if it is \
                 another)",
                c.index, c.name
            ));
            return Ok(ZScale { nm_per_unit: k, unit: format!("{u} (assumed)"), warnings });
        }
        return Err(SurfaceError::invalid(format!(
            "channel {} '{}' has no unit in the file: give --height-unit (e.g. m or nm) if it is a height",
            c.index, c.name
        )));
    }
    if opts.as_height {
        let Some((gk, u, from)) = given else {
            return Err(SurfaceError::invalid(format!(
                "channel {} '{}' is in {}, not a length: with --as-height, give --height-unit (e.g. nm) for what \
                 one {} stands for",
                c.index, c.name, c.z_unit, c.z_unit
            )));
        };
        warnings.push(format!(
            "channel {} '{}' is in {}, not a length; its values are read as heights in {u} (--as-height, {from})",
            c.index, c.name, c.z_unit
        ));
        return Ok(ZScale { nm_per_unit: gk, unit: format!("{u} ({from}, --as-height)"), warnings });
    }
    Err(SurfaceError::invalid(format!(
        "channel {} '{}' is in {}, not a length, so it is not a height; the height channels are {heights} (pick \
         one with --channel), or give --as-height --height-unit UNIT to read it as heights anyway (channels: {})",
        c.index,
        c.name,
        c.z_unit,
        listing(list)
    )))
}
