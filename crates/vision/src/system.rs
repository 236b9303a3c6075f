//! Visual systems: a set of photoreceptors (template or tabulated sensitivities), the ocular media in front
//! of them, the receptor behind achromatic (brightness) vision and the receptor noise that sets the JND.
//! Built-in systems come with their sources (`data/vision/README.md`, `docs/vision.md`).

use serde::Serialize;

use crate::noise::ReceptorNoise;
use crate::space::Space;
use crate::table::{Curve, SpectraTable};
use crate::template::{template, Chromophore, Droplet, DropletType};
use crate::VisionError;

/// How a receptor's sensitivity is known.
#[derive(Debug, Clone, PartialEq)]
pub enum SensitivityModel {
    /// Govardovskii et al. (2000) template for `lambda_max_nm` (β band when `beta`), through an oil droplet.
    Template { lambda_max_nm: f64, chromophore: Chromophore, beta: bool, droplet: Option<Droplet> },
    /// Measured or published values, linear between samples, zero outside.
    Tabulated(Curve),
}

/// The 1 nm grid over which every sensitivity is normalised: 300–700 nm, pavo's range.
pub const NORMALISATION_RANGE_NM: (f64, f64) = (300.0, 700.0);

fn normalisation_grid() -> impl Iterator<Item = f64> {
    (0..=400).map(|i| NORMALISATION_RANGE_NM.0 + i as f64)
}

/// One photoreceptor class. Its sensitivity (before the ocular media) is scaled so that its sum over the
/// 1 nm samples of 300–700 nm is 1, as pavo's `sensmodel(integrate = TRUE)` does; a template is first scaled
/// to a peak of 1 on that grid, then filtered by its oil droplet.
#[derive(Debug, Clone, PartialEq)]
pub struct Receptor {
    pub name: String,
    pub model: SensitivityModel,
    peak: f64,
    norm: f64,
}

impl Receptor {
    /// A receptor from the Govardovskii template, optionally behind an oil droplet.
    pub fn template(
        name: impl Into<String>,
        lambda_max_nm: f64,
        chromophore: Chromophore,
        beta: bool,
        droplet: Option<Droplet>,
    ) -> Result<Self, VisionError> {
        if !(lambda_max_nm.is_finite() && (250.0..=800.0).contains(&lambda_max_nm)) {
            return Err(VisionError::invalid(format!(
                "λmax {lambda_max_nm} nm is outside 250–800 nm, where the templates hold"
            )));
        }
        let model = SensitivityModel::Template { lambda_max_nm, chromophore, beta, droplet };
        Self::build(name.into(), model)
    }

    /// A receptor from tabulated sensitivities.
    pub fn tabulated(name: impl Into<String>, curve: Curve) -> Result<Self, VisionError> {
        if let Some(v) = curve.values().iter().find(|v| **v < 0.0) {
            return Err(VisionError::invalid(format!("sensitivity value {v} is negative")));
        }
        Self::build(name.into(), SensitivityModel::Tabulated(curve))
    }

    fn build(name: String, model: SensitivityModel) -> Result<Self, VisionError> {
        let mut r = Receptor { name, model, peak: 1.0, norm: 1.0 };
        if let SensitivityModel::Template { lambda_max_nm, chromophore, beta, .. } = &r.model {
            r.peak = normalisation_grid().map(|l| template(*lambda_max_nm, l, *chromophore, *beta)).fold(0.0, f64::max);
        }
        let sum: f64 = normalisation_grid().map(|l| r.unnormalised(l)).sum();
        if sum.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
            return Err(VisionError::invalid(format!("receptor '{}' is blind over 300–700 nm", r.name)));
        }
        r.norm = 1.0 / sum;
        Ok(r)
    }

    fn unnormalised(&self, wavelength_nm: f64) -> f64 {
        match &self.model {
            SensitivityModel::Template { lambda_max_nm, chromophore, beta, droplet } => {
                let s = template(*lambda_max_nm, wavelength_nm, *chromophore, *beta) / self.peak;
                droplet.map_or(s, |d| s * d.transmittance(wavelength_nm))
            }
            SensitivityModel::Tabulated(c) => c.at(wavelength_nm),
        }
    }

    /// The receptor's sensitivity at `λ` (quantal, unit sum over the 1 nm samples of 300–700 nm), before the
    /// ocular media.
    pub fn sensitivity(&self, wavelength_nm: f64) -> f64 {
        self.norm * self.unnormalised(wavelength_nm)
    }

    /// The pigment's λmax for a template receptor.
    pub fn lambda_max_nm(&self) -> Option<f64> {
        match &self.model {
            SensitivityModel::Template { lambda_max_nm, .. } => Some(*lambda_max_nm),
            SensitivityModel::Tabulated(_) => None,
        }
    }

    /// Where the sensitivity (with its droplet) peaks on a 1 nm grid over 300–830 nm.
    pub fn peak_nm(&self) -> f64 {
        (300..=830)
            .map(f64::from)
            .fold((300.0, f64::MIN), |best, l| {
                let v = self.sensitivity(l);
                if v > best.1 {
                    (l, v)
                } else {
                    best
                }
            })
            .0
    }
}

/// The receptor signal behind achromatic (brightness) discrimination, for ΔL.
#[derive(Debug, Clone, PartialEq)]
pub enum Achromatic {
    /// One of the system's receptors (by index), e.g. the honeybee's green receptor.
    Receptor(usize),
    /// The sum of several receptors' catches, e.g. human M + L.
    Sum(Vec<usize>),
    /// A receptor of its own, e.g. a bird's double cone.
    Own(Box<Receptor>),
}

/// A visual system: receptors ordered from short to long wavelengths, optional ocular media, the achromatic
/// channel, the default receptor noise and colour space, and where the data come from.
#[derive(Debug, Clone, PartialEq)]
pub struct VisualSystem {
    /// Short name, as typed on the command line (`bluetit`).
    pub id: String,
    /// What it is, e.g. "Blue tit (Cyanistes caeruleus)".
    pub name: String,
    /// Where the numbers come from.
    pub source: String,
    pub receptors: Vec<Receptor>,
    /// Transmittance of the ocular media (cornea, lens, humours), with its source.
    pub ocular_media: Option<(String, Curve)>,
    pub achromatic: Option<Achromatic>,
    /// The receptor noise the system's source (or pavo's default) gives.
    pub noise: ReceptorNoise,
    /// The colour space coordinates are given in by default.
    pub space: Space,
}

/// Information about the system, as it appears in an analysis.
#[derive(Debug, Clone, Serialize)]
pub struct SystemInfo {
    pub id: String,
    pub name: String,
    pub source: String,
    pub receptors: Vec<ReceptorInfo>,
    /// Source of the ocular media transmittance, or null when none is applied.
    pub ocular_media: Option<String>,
    /// The achromatic channel, or null.
    pub achromatic: Option<String>,
}

#[derive(Debug, Clone, Serialize)]
pub struct ReceptorInfo {
    pub name: String,
    /// The pigment's λmax (templates), null for tabulated sensitivities.
    pub lambda_max_nm: Option<f64>,
    /// Where the receptor's sensitivity (with its oil droplet, before the ocular media) peaks.
    pub peak_nm: f64,
    /// The oil droplet: λcut and Bmid, null when none.
    pub oil_droplet: Option<Droplet>,
}

const BUILTIN: &[(&str, &str)] = &[
    ("human", "human cones (Stockman & Sharpe 2000, CIE 2006 LMS 2°)"),
    ("avian-uv", "average avian UV-type eye (Endler & Mielke 2005; pavo's avg.uv)"),
    ("avian-v", "average avian V-type eye (Endler & Mielke 2005; pavo's avg.v)"),
    ("bluetit", "blue tit, Cyanistes caeruleus (Hart et al. 2000)"),
    ("honeybee", "honeybee, Apis mellifera (Peitsch et al. 1992)"),
    ("ball-python", "ball python, Python regius (Sillman et al. 1999)"),
];

fn table(text: &str, name: &str) -> SpectraTable {
    // Compiled-in data (include_str!): a malformed file is a build defect the unit tests catch.
    SpectraTable::parse(text, name).expect("malformed built-in vision table")
}

fn curve(text: &str, name: &str) -> Curve {
    Curve::from_csv_str(text, name).expect("malformed built-in vision curve")
}

fn tabulated_receptors(t: SpectraTable) -> Result<Vec<Receptor>, VisionError> {
    let wl = t.wavelengths_nm;
    t.samples.into_iter().map(|(name, v)| Receptor::tabulated(name, Curve::new(wl.clone(), v)?)).collect()
}

fn blue_tit_double_cone() -> Result<Achromatic, VisionError> {
    let c = curve(include_str!("../../../data/vision/bluetit_double_cone_hart2000.csv"), "bluetit double cone");
    Ok(Achromatic::Own(Box::new(Receptor::tabulated("double cone (blue tit)", c)?)))
}

/// pavo's default receptor noise for birds: Weber fraction 0.1 of the LWS cone, densities 1:2:2:4.
fn bird_noise() -> ReceptorNoise {
    ReceptorNoise::Weber { weber: 0.1, reference: 3, densities: vec![1.0, 2.0, 2.0, 4.0] }
}

impl VisualSystem {
    /// The built-in systems: (id, description).
    pub fn builtin_names() -> &'static [(&'static str, &'static str)] {
        BUILTIN
    }

    /// A built-in system by id (or pavo's name for it: `avg.uv`, `avg.v`, `apis`).
    pub fn builtin(id: &str) -> Result<Self, VisionError> {
        let key = id.trim().to_ascii_lowercase();
        let key = match key.as_str() {
            "avg.uv" | "avian_uv" | "uvs" => "avian-uv",
            "avg.v" | "avian_v" | "vs" => "avian-v",
            "apis" | "bee" | "apis-mellifera" => "honeybee",
            "python" | "python-regius" | "snake" => "ball-python",
            "blue-tit" | "cyanistes" => "bluetit",
            other => other,
        };
        let system = match key {
            "human" => VisualSystem {
                id: key.into(),
                name: "Human (trichromat)".into(),
                source: "Stockman & Sharpe (2000) 2° cone fundamentals (CIE 2006 LMS), quantal, 390–830 nm; \
                         default noise: Weber fraction 0.02 of L, densities S:M:L = 1:5:10"
                    .into(),
                receptors: tabulated_receptors(table(
                    include_str!("../../../data/vision/human_ss2000_2deg_quantal.csv"),
                    "human cones",
                ))?,
                ocular_media: None,
                achromatic: Some(Achromatic::Sum(vec![1, 2])),
                noise: ReceptorNoise::Weber { weber: 0.02, reference: 2, densities: vec![1.0, 5.0, 10.0] },
                space: Space::Triangle,
            },
            "avian-uv" | "avian-v" => {
                let text = if key == "avian-uv" {
                    include_str!("../../../data/vision/avian_uv_endler_mielke_2005.csv")
                } else {
                    include_str!("../../../data/vision/avian_v_endler_mielke_2005.csv")
                };
                VisualSystem {
                    id: key.into(),
                    name: if key == "avian-uv" { "Average avian UV-type eye" } else { "Average avian V-type eye" }
                        .into(),
                    source: "Endler & Mielke (2005) online appendix: cone pigment × oil droplet, 300–700 nm (pavo's \
                             avg.uv / avg.v); default achromatic: blue-tit double cone (Hart et al. 2000, as in \
                             pavo); default noise: pavo's (Weber 0.1 of LWS, densities 1:2:2:4)"
                        .into(),
                    receptors: tabulated_receptors(table(text, key))?,
                    ocular_media: None,
                    achromatic: Some(blue_tit_double_cone()?),
                    noise: bird_noise(),
                    space: Space::Tetrahedron,
                }
            }
            "bluetit" => {
                let cones = [
                    ("UVS", 371.0, DropletType::T, 330.0),
                    ("SWS", 448.0, DropletType::C, 413.0),
                    ("MWS", 502.0, DropletType::Y, 507.0),
                    ("LWS", 563.0, DropletType::R, 572.0),
                ];
                let receptors = cones
                    .iter()
                    .map(|&(n, l, t, cut)| Receptor::template(n, l, Chromophore::A1, true, Droplet::from_type(t, cut)?))
                    .collect::<Result<Vec<_>, _>>()?;
                let media = curve(include_str!("../../../data/vision/bluetit_ocular_media_hart2000.csv"), "media");
                VisualSystem {
                    id: key.into(),
                    name: "Blue tit (Cyanistes caeruleus)".into(),
                    source: "Hart et al. (2000): λmax 371, 448, 502, 563 nm (A1 templates, Govardovskii et al. 2000), \
                             oil droplets T, C (λcut 413 nm), Y (507 nm), R (572 nm) in Hart & Vorobyev's (2005) \
                             model, blue-tit ocular media; default achromatic: blue-tit double cone (as in pavo); \
                             default noise: pavo's (Weber 0.1 of LWS, densities 1:2:2:4)"
                        .into(),
                    receptors,
                    ocular_media: Some(("blue tit, Hart et al. (2000)".into(), media)),
                    achromatic: Some(blue_tit_double_cone()?),
                    noise: bird_noise(),
                    space: Space::Tetrahedron,
                }
            }
            "honeybee" => VisualSystem {
                id: key.into(),
                name: "Honeybee (Apis mellifera)".into(),
                source: "Peitsch et al. (1992): λmax 344, 436, 556 nm (A1 templates, Govardovskii et al. 2000); \
                         default achromatic: the green receptor; default noise per receptor 0.13, 0.06, 0.12 \
                         (Vorobyev et al. 2001)"
                    .into(),
                receptors: [("UV", 344.0), ("B", 436.0), ("G", 556.0)]
                    .iter()
                    .map(|&(n, l)| Receptor::template(n, l, Chromophore::A1, true, None))
                    .collect::<Result<Vec<_>, _>>()?,
                ocular_media: None,
                achromatic: Some(Achromatic::Receptor(2)),
                noise: ReceptorNoise::PerReceptor(vec![0.13, 0.06, 0.12]),
                space: Space::Hexagon,
            },
            "ball-python" => VisualSystem {
                id: key.into(),
                name: "Ball python (Python regius)".into(),
                source: "Sillman, Carver & Loew (1999): cone pigments λmax 360 and 551 nm, A1 (templates, \
                         Govardovskii et al. 2000), no oil droplets, no ocular-media data; default achromatic: \
                         the LWS cone; default noise: Weber 0.1 of LWS with equal densities (the source gives no \
                         cone ratio)"
                    .into(),
                receptors: [("UVS", 360.0), ("LWS", 551.0)]
                    .iter()
                    .map(|&(n, l)| Receptor::template(n, l, Chromophore::A1, true, None))
                    .collect::<Result<Vec<_>, _>>()?,
                ocular_media: None,
                achromatic: Some(Achromatic::Receptor(1)),
                noise: ReceptorNoise::Weber { weber: 0.1, reference: 1, densities: vec![1.0, 1.0] },
                space: Space::Line,
            },
            _ => {
                let names: Vec<&str> = BUILTIN.iter().map(|(k, _)| *k).collect();
                // λmax values typed where the system's name goes: say where they belong.
                let looks_like_lambda_max =
                    key.split(',').all(|t| t.trim().trim_end_matches("nm").parse::<f64>().is_ok());
                let lambda_max = if looks_like_lambda_max {
                    format!("; λmax values are given as --lambda-max {key} (Python: lambda_max=), without a system")
                } else {
                    String::new()
                };
                return Err(VisionError::invalid(format!(
                    "unknown visual system '{id}'; built in: {} (or a CSV file of sensitivities, or λmax values){lambda_max}",
                    names.join(", ")
                )));
            }
        };
        Ok(system)
    }

    /// A system from pigment λmax values (templates), each optionally behind an oil droplet (`droplets`
    /// empty, or one entry per receptor). Receptors are named `λ344` etc. and sorted by λmax; noise: Weber
    /// fraction 0.1 of the longest receptor, equal densities; achromatic: the longest receptor.
    pub fn from_lambda_max(
        lambda_max_nm: &[f64],
        chromophore: Chromophore,
        droplets: &[Option<Droplet>],
    ) -> Result<Self, VisionError> {
        if lambda_max_nm.is_empty() {
            return Err(VisionError::invalid("no λmax given"));
        }
        if !droplets.is_empty() && droplets.len() != lambda_max_nm.len() {
            return Err(VisionError::invalid(format!(
                "{} oil droplets for {} receptors: give one per λmax (none for a receptor without one)",
                droplets.len(),
                lambda_max_nm.len()
            )));
        }
        let mut pairs: Vec<(f64, Option<Droplet>)> =
            lambda_max_nm.iter().enumerate().map(|(i, &l)| (l, droplets.get(i).copied().flatten())).collect();
        pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
        let receptors = pairs
            .iter()
            .map(|&(l, d)| Receptor::template(format!("λ{l}"), l, chromophore, true, d))
            .collect::<Result<Vec<_>, _>>()?;
        let list: Vec<String> = pairs.iter().map(|p| p.0.to_string()).collect();
        Ok(Self::custom(
            format!("λmax {} nm", list.join(", ")),
            format!("Govardovskii et al. (2000) {chromophore} templates with β band; oil droplets in Hart & Vorobyev's (2005) model"),
            receptors,
        ))
    }

    /// A system from a table of sensitivities (a wavelength column and one column per receptor, short to long).
    pub fn from_table(name: &str, table: SpectraTable) -> Result<Self, VisionError> {
        Ok(Self::custom(name.to_string(), format!("sensitivities from {name}"), tabulated_receptors(table)?))
    }

    fn custom(name: String, source: String, receptors: Vec<Receptor>) -> Self {
        let n = receptors.len();
        VisualSystem {
            id: "custom".into(),
            name,
            source: format!(
                "{source}; default noise: Weber 0.1 of the longest receptor, equal densities; default achromatic: the \
                 longest receptor"
            ),
            receptors,
            ocular_media: None,
            achromatic: Some(Achromatic::Receptor(n - 1)),
            noise: ReceptorNoise::Weber { weber: 0.1, reference: n - 1, densities: vec![1.0; n] },
            space: Space::Auto,
        }
    }

    /// The receptors' names.
    pub fn receptor_names(&self) -> Vec<String> {
        self.receptors.iter().map(|r| r.name.clone()).collect()
    }

    /// The index of a receptor by name (case-insensitive) or 1-based position.
    pub fn receptor_index(&self, key: &str) -> Result<usize, VisionError> {
        let k = key.trim();
        if let Some(i) = self.receptors.iter().position(|r| r.name.eq_ignore_ascii_case(k)) {
            return Ok(i);
        }
        if k.eq_ignore_ascii_case("longest") {
            return Ok(self.receptors.len() - 1);
        }
        match k.parse::<usize>() {
            Ok(i) if (1..=self.receptors.len()).contains(&i) => Ok(i - 1),
            _ => Err(VisionError::invalid(format!(
                "no receptor '{key}' in {}; its receptors are {} (or 1–{} by position, or 'longest')",
                self.name,
                self.receptor_names().join(", "),
                self.receptors.len()
            ))),
        }
    }

    /// Transmittance of the ocular media at `λ` (1 without media).
    pub fn media(&self, wavelength_nm: f64) -> f64 {
        self.ocular_media.as_ref().map_or(1.0, |(_, c)| c.at(wavelength_nm))
    }

    /// What an analysis reports about the system.
    pub fn info(&self) -> SystemInfo {
        SystemInfo {
            id: self.id.clone(),
            name: self.name.clone(),
            source: self.source.clone(),
            receptors: self
                .receptors
                .iter()
                .map(|r| ReceptorInfo {
                    name: r.name.clone(),
                    lambda_max_nm: r.lambda_max_nm(),
                    peak_nm: r.peak_nm(),
                    oil_droplet: match &r.model {
                        SensitivityModel::Template { droplet, .. } => *droplet,
                        SensitivityModel::Tabulated(_) => None,
                    },
                })
                .collect(),
            ocular_media: self.ocular_media.as_ref().map(|(s, _)| s.clone()),
            achromatic: self.achromatic.as_ref().map(|a| self.achromatic_name(a)),
        }
    }

    pub(crate) fn achromatic_name(&self, a: &Achromatic) -> String {
        match a {
            Achromatic::Receptor(i) => self.receptors[*i].name.clone(),
            Achromatic::Sum(v) => v.iter().map(|i| self.receptors[*i].name.as_str()).collect::<Vec<_>>().join(" + "),
            Achromatic::Own(r) => r.name.clone(),
        }
    }
}
