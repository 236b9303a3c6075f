//! The Fresnel factor of the diffraction BRDF from its one text form (the CLI's `--fresnel`, Python's
//! `fresnel=`): `schlick[:N]`, `index:N[+Ki]`, `gold` (measured) or `stack:STACK` (a thin film).

use std::sync::Arc;

use anyhow::{bail, Context, Result};
use iridis_diffraction::geometry::{FilmFresnel, FresnelConvention, FresnelSource, Shading};
use iridis_diffraction::Fresnel;
use num_complex::Complex64;

/// The `--fresnel` of the scalar methods when none is given.
pub const DEFAULT_FRESNEL: &str = "schlick:1.5";

/// Refuses the scalar model's shading options for the rigorous method, whose lobes carry Maxwell's efficiencies
/// over its `--material`: a Fresnel factor, the paper's R² convention and leaving out the shadowing term would
/// each change nothing.
pub fn refuse_scalar_shading_for_rigorous(fresnel: &str, convention: FresnelConvention, shadowing: bool) -> Result<()> {
    if fresnel.trim() != DEFAULT_FRESNEL {
        bail!(
            "the rigorous method needs the medium under the relief (--material gold, keratin, n=1.5, …), not a \
             Fresnel factor (--fresnel {fresnel})"
        );
    }
    if convention == FresnelConvention::Paper {
        bail!("--fresnel-convention paper is the scalar model's R² as printed; the rigorous method has none");
    }
    if !shadowing {
        bail!(
            "--no-shadowing would be ignored: the rigorous method's lobes carry Maxwell's efficiencies, which no \
             shadowing term scales"
        );
    }
    Ok(())
}

/// The shading factors around |A|² (`C` of paper eq. 2–4): Fresnel source, its convention, shadowing.
pub fn shading(fresnel: &str, convention: FresnelConvention, shadowing: bool) -> Result<Shading> {
    Ok(Shading { fresnel: parse_fresnel_source(fresnel)?, shadowing, convention })
}

/// Parses `--fresnel`, the one parser of every command that takes it: the built-in models, measured gold
/// (`gold`, λ-dependent) and a thin-film stack (`stack:air | keratin 400nm | …`, λ-dependent).
pub fn parse_fresnel_source(s: &str) -> Result<Arc<dyn FresnelSource>> {
    if let Some(stack) = s.trim().strip_prefix("stack:") {
        let stack: iridis_thinfilm::Stack = stack.parse().with_context(|| format!("--fresnel '{s}'"))?;
        return Ok(Arc::new(FilmFresnel::new(stack)?));
    }
    if matches!(s.trim().to_ascii_lowercase().as_str(), "gold" | "au") {
        let m = iridis_thinfilm::Material::builtin("gold").context("the built-in gold data are missing")?;
        return Ok(Arc::new(iridis_lab::laser::MetalFresnel::new(m, 380.0, 780.0)?));
    }
    Ok(Arc::new(parse_fresnel(s)?))
}

/// Parses the built-in Fresnel models of `--fresnel` (those a GPU shader evaluates: no λ dependence).
pub fn parse_fresnel(s: &str) -> Result<Fresnel> {
    let t = s.trim().to_ascii_lowercase();
    let (kind, value) = t.split_once(':').unwrap_or((t.as_str(), ""));
    match kind {
        "schlick" => {
            // n = 1 gives F_0 = 0: a black surface, never what was meant.
            let n = if value.is_empty() {
                1.5
            } else {
                value
                    .parse::<f64>()
                    .ok()
                    .filter(|n| *n > 0.0 && *n != 1.0)
                    .with_context(|| format!("--fresnel '{s}': schlick:N needs a positive N ≠ 1"))?
            };
            Ok(Fresnel::Schlick { n })
        }
        "index" => {
            let n = parse_complex(value).with_context(|| {
                format!("--fresnel '{s}': write index:N or index:N+Ki with N > 0, K ≥ 0, e.g. index:0.2+3.4i")
            })?;
            Ok(Fresnel::Index { n })
        }
        "gold" | "au" => bail!(
            "--fresnel '{s}': measured gold depends on λ, which this path cannot evaluate; use index:0.2+3.4i \
             (gold near 550 nm) or a CPU method"
        ),
        _ => bail!("--fresnel '{s}': expected schlick[:N], index:N[+Ki], gold or stack:STACK"),
    }
}

fn parse_complex(s: &str) -> Option<Complex64> {
    let s = s.trim();
    if let Some(body) = s.strip_suffix('i') {
        let split = body.rfind(['+', '-']).filter(|&p| p > 0)?;
        let (re, im) = body.split_at(split);
        let (re, im) = (re.parse::<f64>().ok()?, im.parse::<f64>().ok()?);
        (re > 0.0 && im >= 0.0).then_some(Complex64::new(re, im))
    } else {
        s.parse::<f64>().ok().filter(|n| *n > 0.0).map(|n| Complex64::new(n, 0.0))
    }
}
