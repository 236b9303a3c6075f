//! A stack with free parameters: `air | SiO2 {d1=100nm:50nm..500nm} | Si`. A parameter is written
//! `{NAME=START:LOW..HIGH}` and may stand for
//! * a layer thickness (the thickness word of a layer; values with a length unit),
//! * a constant real index, `n={n1=1.45:1.3..1.7}`,
//! * a coefficient of `cauchy:A,B,C` or `sellmeier:B1,C1,…` (plain numbers), e.g.
//!   `cauchy:{A=1.45:1.3..1.7},{B=0.004:0..0.05}`.

use iridis_thinfilm::jet::Tangent;
use iridis_thinfilm::{Complex64, Material, Stack};

use crate::FitError;

/// What a parameter sets.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Role {
    /// The thickness (nm) of layer `layer` (0 = top layer).
    Thickness { layer: usize },
    /// The constant real index of medium `medium` (0 = incident, N + 1 = substrate).
    Index { medium: usize },
    /// Coefficient `coef` of the Cauchy or Sellmeier formula of medium `medium`.
    Coefficient { medium: usize, coef: usize },
}

/// One free parameter: its name, start value, range and role.
#[derive(Debug, Clone, PartialEq)]
pub struct Param {
    pub name: String,
    pub start: f64,
    pub lo: f64,
    pub hi: f64,
    pub role: Role,
}

impl Param {
    /// "nm" for thicknesses, "" otherwise.
    pub fn unit(&self) -> &'static str {
        match self.role {
            Role::Thickness { .. } => "nm",
            _ => "",
        }
    }
}

#[derive(Debug, Clone, PartialEq)]
enum Coef {
    Fixed(f64),
    Free(usize),
}

#[derive(Debug, Clone, PartialEq)]
struct Formula {
    medium: usize,
    sellmeier: bool,
    coefs: Vec<Coef>,
    name: String,
}

/// A parsed template: the stack at the start values and how to set each parameter.
#[derive(Debug, Clone)]
pub struct Template {
    pub text: String,
    pub base: Stack,
    pub params: Vec<Param>,
    formulas: Vec<Formula>,
}

/// Finds `{…}` placeholders: (byte start, byte end exclusive, inner text).
fn placeholders(text: &str) -> Result<Vec<(usize, usize, &str)>, FitError> {
    let mut out = Vec::new();
    let mut rest = 0;
    while let Some(i) = text[rest..].find('{') {
        let start = rest + i;
        let end = text[start..]
            .find('}')
            .map(|j| start + j + 1)
            .ok_or_else(|| FitError::Template(format!("'{{' at column {} is not closed by '}}'", start + 1)))?;
        out.push((start, end, &text[start + 1..end - 1]));
        rest = end;
    }
    Ok(out)
}

impl Template {
    pub fn parse(text: &str) -> Result<Self, FitError> {
        let found = placeholders(text)?;
        if found.is_empty() {
            return Err(FitError::Template(format!(
                "\"{text}\" has no free parameter; write one as {{NAME=START:LOW..HIGH}}, e.g. \
                 \"air | SiO2 {{d1=100nm:50nm..500nm}} | Si\""
            )));
        }
        // Roles from the position of each placeholder: segment (medium) and word.
        let mut roles = Vec::new();
        let mut formulas: Vec<Formula> = Vec::new();
        let mut seg_start = 0;
        let segments: Vec<(usize, &str)> = text
            .split('|')
            .map(|s| {
                let r = (seg_start, s);
                seg_start += s.len() + 1;
                r
            })
            .collect();
        let last = segments.len().saturating_sub(1);
        for (k, &(off, seg)) in segments.iter().enumerate() {
            let mut words = Vec::new();
            let mut pos = 0;
            for w in seg.split_whitespace() {
                let at = seg[pos..].find(w).unwrap() + pos;
                words.push((off + at, w));
                pos = at + w.len();
            }
            for (wi, &(woff, w)) in words.iter().enumerate() {
                let inside: Vec<usize> =
                    (0..found.len()).filter(|&i| found[i].0 >= woff && found[i].1 <= woff + w.len()).collect();
                if inside.is_empty() {
                    continue;
                }
                if wi == 1 && k != 0 && k != last {
                    if inside.len() != 1 || found[inside[0]].0 != woff || found[inside[0]].1 != woff + w.len() {
                        return Err(FitError::Template(format!(
                            "thickness '{w}': write the whole thickness as one {{…}}"
                        )));
                    }
                    roles.push((inside[0], Role::Thickness { layer: k - 1 }));
                    continue;
                }
                let mat = w.strip_prefix("inc:").unwrap_or(w);
                let mat_off = woff + (w.len() - mat.len());
                if let Some(v) = mat.strip_prefix("n=") {
                    if inside.len() == 1
                        && found[inside[0]].0 == mat_off + 2
                        && found[inside[0]].1 == mat_off + 2 + v.len()
                    {
                        roles.push((inside[0], Role::Index { medium: k }));
                        continue;
                    }
                }
                let formula = [("cauchy:", false), ("sellmeier:", true)].into_iter().find(|(p, _)| mat.starts_with(p));
                let Some((prefix, sellmeier)) = formula else {
                    return Err(FitError::Template(format!(
                        "'{w}': a parameter may be a layer thickness, a whole constant index n={{…}}, or a \
                         coefficient of cauchy:A,B,C or sellmeier:B1,C1,…"
                    )));
                };
                let mut coefs = Vec::new();
                let mut item_off = mat_off + prefix.len();
                for item in mat[prefix.len()..].split(',') {
                    let hit = inside.iter().find(|&&i| found[i].0 == item_off && found[i].1 == item_off + item.len());
                    match hit {
                        Some(&i) => {
                            roles.push((i, Role::Coefficient { medium: k, coef: coefs.len() }));
                            coefs.push(Coef::Free(i));
                        }
                        None => coefs.push(Coef::Fixed(item.parse::<f64>().map_err(|_| {
                            FitError::Template(format!("'{item}' in '{w}' is neither a number nor a whole {{…}}"))
                        })?)),
                    }
                    item_off += item.len() + 1;
                }
                formulas.push(Formula { medium: k, sellmeier, coefs, name: mat.to_string() });
            }
        }
        if roles.len() != found.len() {
            return Err(FitError::Template("a {…} parameter stands where no value is expected".into()));
        }
        roles.sort_by_key(|r| r.0);
        let mut params: Vec<Param> = Vec::new();
        for (i, role) in roles {
            let p = parse_param(found[i].2, role)?;
            if params.iter().any(|q| q.name == p.name) {
                return Err(FitError::Template(format!("parameter '{}' is defined twice", p.name)));
            }
            params.push(p);
        }
        // Every placeholder has a role, so `params[i]` is placeholder `found[i]` (Coef::Free indices hold).
        // The stack at the start values (checks everything else in the text).
        let mut subst = String::new();
        let mut at = 0;
        for (p, &(s, e, _)) in params.iter().zip(&found) {
            subst.push_str(&text[at..s]);
            subst.push_str(&format!("{}{}", p.start, p.unit()));
            at = e;
        }
        subst.push_str(&text[at..]);
        let base = Stack::parse(&subst).map_err(|e| FitError::Template(e.to_string()))?;
        let t = Template { text: text.to_string(), base, params, formulas };
        t.stack(&t.starts())?;
        Ok(t)
    }

    /// The indices of the fitted thicknesses (`{d=…}`), the parameters the multi-start grid spans.
    pub fn thickness_params(&self) -> Vec<usize> {
        self.params
            .iter()
            .enumerate()
            .filter(|(_, p)| matches!(p.role, Role::Thickness { .. }))
            .map(|(i, _)| i)
            .collect()
    }

    pub fn starts(&self) -> Vec<f64> {
        self.params.iter().map(|p| p.start).collect()
    }

    /// The stack with these parameter values.
    pub fn stack(&self, values: &[f64]) -> Result<Stack, FitError> {
        let mut s = self.base.clone();
        let n = s.layers.len();
        for (p, &v) in self.params.iter().zip(values) {
            match p.role {
                Role::Thickness { layer } => s.layers[layer].thickness_nm = v,
                Role::Index { medium } => {
                    let m = Material::constant(format!("n={v}"), Complex64::new(v, 0.0))
                        .map_err(|e| FitError::Model(e.to_string()))?;
                    set_medium(&mut s, n, medium, m);
                }
                Role::Coefficient { .. } => {}
            }
        }
        for f in &self.formulas {
            let c = f.values(values);
            let m = if f.sellmeier { Material::sellmeier(&f.name, &c) } else { Material::cauchy(&f.name, &c) }
                .map_err(|e| FitError::Model(e.to_string()))?;
            set_medium(&mut s, n, f.medium, m);
        }
        Ok(s)
    }
}

impl Template {
    /// How the media and thicknesses of [`Template::stack`] depend on the parameters at one wavelength:
    /// 1 for a thickness or a constant index, `∂n/∂c` of the Cauchy or Sellmeier formula for a coefficient
    /// (`K ≥` the number of parameters; the other directions stay zero).
    pub fn tangent<const K: usize>(&self, values: &[f64], wavelength_nm: f64) -> Tangent<K> {
        let mut t = Tangent::zero(self.base.layers.len());
        let one = Complex64::new(1.0, 0.0);
        for (k, p) in self.params.iter().enumerate() {
            match p.role {
                Role::Thickness { layer } => t.thickness[layer][k] = 1.0,
                Role::Index { medium } => t.index[medium][k] = one,
                Role::Coefficient { .. } => {}
            }
        }
        for f in &self.formulas {
            let c = f.values(values);
            let g = if f.sellmeier {
                Material::sellmeier_gradient(&c, wavelength_nm)
            } else {
                Material::cauchy_gradient(&c, wavelength_nm)
            };
            for (coef, dn) in f.coefs.iter().zip(g) {
                if let Coef::Free(k) = coef {
                    t.index[f.medium][*k] += dn;
                }
            }
        }
        t
    }
}

impl Formula {
    fn values(&self, values: &[f64]) -> Vec<f64> {
        self.coefs
            .iter()
            .map(|c| match c {
                Coef::Fixed(v) => *v,
                Coef::Free(i) => values[*i],
            })
            .collect()
    }
}

fn set_medium(s: &mut Stack, n: usize, medium: usize, m: Material) {
    if medium == 0 {
        s.incident = m;
    } else if medium == n + 1 {
        s.substrate = m;
    } else {
        s.layers[medium - 1].material = m;
    }
}

/// `NAME=START:LOW..HIGH`; values with a length unit for thicknesses.
fn parse_param(inner: &str, role: Role) -> Result<Param, FitError> {
    let example = match role {
        Role::Thickness { .. } => "{d1=100nm:50nm..500nm}",
        Role::Index { .. } => "n={n1=1.45:1.3..1.7}",
        Role::Coefficient { .. } => "cauchy:{A=1.45:1.3..1.7},0.004",
    };
    let (name, rest) = inner
        .split_once('=')
        .ok_or_else(|| FitError::Template(format!("{{{inner}}}: write NAME=START:LOW..HIGH, e.g. {example}")))?;
    let name = name.trim();
    if name.is_empty() || !name.chars().all(|c| c.is_alphanumeric() || c == '_') {
        return Err(FitError::Template(format!("{{{inner}}}: '{name}' is not a parameter name (letters, digits, _)")));
    }
    let Some((start, range)) = rest.split_once(':') else {
        return Err(FitError::Template(format!(
            "parameter '{name}' has no range: the fit searches between two bounds; write e.g. {example}"
        )));
    };
    let (lo, hi) = range.split_once("..").ok_or_else(|| {
        FitError::Template(format!("parameter '{name}': range '{range}' is not LOW..HIGH, e.g. {example}"))
    })?;
    let value = |t: &str| -> Result<f64, FitError> {
        let t = t.trim();
        let v = match role {
            Role::Thickness { .. } => iridis_color::units::parse_length_nm(t)
                .map_err(|e| FitError::Template(format!("parameter '{name}': '{t}': {}", e.0)))?,
            _ => t
                .parse::<f64>()
                .map_err(|_| FitError::Template(format!("parameter '{name}': '{t}' is not a number")))?,
        };
        if v.is_finite() {
            Ok(v)
        } else {
            Err(FitError::Template(format!("parameter '{name}': '{t}' is not finite")))
        }
    };
    let (start, lo, hi) = (value(start)?, value(lo)?, value(hi)?);
    if lo >= hi {
        return Err(FitError::Template(format!(
            "parameter '{name}': the range {lo}..{hi} is empty (LOW must be below HIGH)"
        )));
    }
    if !(lo..=hi).contains(&start) {
        return Err(FitError::Template(format!(
            "parameter '{name}': the start {start} is outside its range {lo}..{hi}"
        )));
    }
    match role {
        Role::Thickness { .. } if lo < 0.0 => {
            return Err(FitError::Template(format!("parameter '{name}': a thickness cannot be negative ({lo} nm)")))
        }
        Role::Index { .. } if lo <= 0.0 => {
            return Err(FitError::Template(format!(
                "parameter '{name}': a refractive index must be > 0 (range starts at {lo})"
            )))
        }
        _ => {}
    }
    Ok(Param { name: name.to_string(), start, lo, hi, role })
}
