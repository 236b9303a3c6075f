//! Channels: instrument files hold several images (height trace and retrace, amplitude, phase, …). Each
//! reader lists them as [`ChannelInfo`]; the user picks one by index or by name ([`ChannelSel`]), and
//! without a choice the first height-like channel (a length unit, named like a height) is read.

use std::str::FromStr;

use serde::Serialize;

use crate::SurfaceError;

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
    /// Whether the values are lengths (a height channel).
    pub fn is_length(&self) -> bool {
        length_nm(&self.z_unit).is_some()
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
    if unit.trim() == "A" {
        None
    } else {
        super::unit_to_nm(unit)
    }
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

/// Position in `list` of the chosen channel, or of the default: the first length channel whose name says
/// height/topography/Z, else the first length channel, else the first one.
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
        None => {
            let heightish = |c: &ChannelInfo| {
                let n = norm(&c.name);
                n.contains("height") || n.contains("topo") || n == "z"
            };
            Ok(list
                .iter()
                .position(|c| c.is_length() && heightish(c))
                .or_else(|| list.iter().position(ChannelInfo::is_length))
                .unwrap_or(0))
        }
    }
}

/// nm per stored unit of a channel, or why it cannot be a height; `height_unit` (`--height-unit`) stands in
/// for a unit the file lacks.
pub fn z_scale(
    list: &[ChannelInfo],
    c: &ChannelInfo,
    height_unit: Option<&str>,
) -> Result<(f64, String), SurfaceError> {
    if let Some(k) = length_nm(&c.z_unit) {
        return Ok((k, c.z_unit.clone()));
    }
    if c.z_unit.is_empty() {
        if let Some(u) = height_unit {
            let k = super::unit_to_nm(u)
                .ok_or_else(|| SurfaceError::invalid(format!("--height-unit '{u}' is not a length unit")))?;
            return Ok((k, format!("{u} (--height-unit)")));
        }
        return Err(SurfaceError::invalid(format!(
            "channel {} '{}' has no unit in the file: give --height-unit (e.g. m or nm) if it is a height",
            c.index, c.name
        )));
    }
    Err(SurfaceError::invalid(format!(
        "channel {} '{}' is in {}, not a length, so it is not a height; choose a height channel with --channel \
         (channels: {})",
        c.index,
        c.name,
        c.z_unit,
        listing(list)
    )))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ch(index: u32, name: &str, unit: &str, dir: &str) -> ChannelInfo {
        ChannelInfo {
            index,
            name: name.into(),
            rows: 4,
            cols: 4,
            z_unit: unit.into(),
            direction: dir.into(),
            alias: String::new(),
        }
    }

    #[test]
    fn selection_by_index_name_and_default() {
        let l = vec![
            ch(0, "Amplitude", "m", "trace"),
            ch(1, "Phase", "deg", "trace"),
            ch(2, "Height", "m", "trace"),
            ch(3, "Height", "m", "retrace"),
        ];
        assert_eq!(pick(&l, None).unwrap(), 2);
        assert_eq!(pick(&l, Some(&"1".parse().unwrap())).unwrap(), 1);
        assert_eq!(pick(&l, Some(&"height".parse().unwrap())).unwrap(), 2);
        assert_eq!(pick(&l, Some(&"height_retrace".parse().unwrap())).unwrap(), 3);
        let e = pick(&l, Some(&"Friction".parse().unwrap())).unwrap_err().to_string();
        assert!(e.contains("'Friction'") && e.contains("1: Phase (deg, trace)"), "{e}");
        let e = pick(&l, Some(&ChannelSel::Index(9))).unwrap_err().to_string();
        assert!(e.contains("no channel 9") && e.contains("3: Height (m, retrace)"), "{e}");
        assert!(z_scale(&l, &l[1], None).unwrap_err().to_string().contains("not a length"));
        assert_eq!(z_scale(&l, &l[2], None).unwrap().0, 1e9);
        let nounit = ch(0, "Z", "", "");
        assert!(z_scale(&l, &nounit, None).unwrap_err().to_string().contains("--height-unit"));
        assert_eq!(z_scale(&l, &nounit, Some("um")).unwrap().0, 1e3);
    }
}
