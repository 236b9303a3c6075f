//! Directions and the shading factors of the paper (eq. 2–4): Fresnel, geometry, shadowing, normalisation.
//!
//! Directions `ω_i` (to the light) and `ω_r` (to the viewer) point away from the surface; `z` is the normal.

use num_complex::Complex64;

/// A unit vector.
pub type Vec3 = [f64; 3];

/// Direction from polar angle θ and azimuth φ (radians).
pub fn direction(theta: f64, phi: f64) -> Vec3 {
    [theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos()]
}

pub fn dot(a: Vec3, b: Vec3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `(u, v, w) = −ω_i − ω_r` (paper, after eq. 2).
pub fn uvw(wi: Vec3, wr: Vec3) -> Vec3 {
    [-wi[0] - wr[0], -wi[1] - wr[1], -wi[2] - wr[2]]
}

/// Where the Fresnel factor comes from.
pub trait FresnelSource: Send + Sync + std::fmt::Debug {
    /// Unpolarised reflectance at wavelength `λ` (nm) for the cosine of the angle of incidence.
    fn reflectance(&self, wavelength_nm: f64, cos_theta: f64) -> f64;
    /// The reflectances `[R_s, R_p]` for s (TE) and p (TM) light; a model without a polarised form
    /// (Schlick's approximation) answers its unpolarised value for both ([`FresnelSource::polarised`] says
    /// which).
    fn reflectance_sp(&self, wavelength_nm: f64, cos_theta: f64) -> [f64; 2] {
        let r = self.reflectance(wavelength_nm, cos_theta);
        [r, r]
    }
    /// Whether [`FresnelSource::reflectance_sp`] tells s from p.
    fn polarised(&self) -> bool {
        false
    }
    /// Whether the value depends on λ (then it must stay inside the spectral integral).
    fn depends_on_wavelength(&self) -> bool;
    fn describe(&self) -> String;
    /// `F_0` of the normalisation in `C` (paper eq. 4: "BRDFs normalized by reflectance at normal
    /// incidence"): one number for all λ. A λ-independent source gives its normal-incidence reflectance;
    /// a λ-dependent one must not divide by its own `F(λ, 0)`, which would cancel the colour it adds.
    fn normal_reflectance(&self) -> f64 {
        self.reflectance(560.0, 1.0)
    }
    /// The built-in model this source is, if it is one (what a GPU shader can evaluate).
    fn as_builtin(&self) -> Option<&Fresnel> {
        None
    }
}

/// The built-in Fresnel models.
#[derive(Debug, Clone)]
pub enum Fresnel {
    /// Schlick's approximation `F_0 + (1 − F_0)(1 − cos θ)^5`, `F_0 = ((n − 1)/(n + 1))²` (thesis App. D).
    Schlick { n: f64 },
    /// Exact unpolarised Fresnel reflectance of a dielectric (or any complex index, e.g. gold) in air.
    Index { n: Complex64 },
}

impl Default for Fresnel {
    /// The paper's default: Schlick with n = 1.5 (`F_0 = 0.04`).
    fn default() -> Self {
        Fresnel::Schlick { n: 1.5 }
    }
}

/// Unpolarised Fresnel reflectance from a medium of index 1 into `n̂` (complex cosines from Snell's law).
pub fn fresnel_unpolarised(n: Complex64, cos_i: f64) -> f64 {
    let [rs, rp] = fresnel_sp(n, cos_i);
    0.5 * (rs + rp)
}

/// Fresnel power reflectances `[R_s, R_p]` from a medium of index 1 into `n̂` (s: E perpendicular to the plane
/// of incidence, TE; p: in it, TM), with the complex cosine of Snell's law.
pub fn fresnel_sp(n: Complex64, cos_i: f64) -> [f64; 2] {
    let cos_i = cos_i.clamp(0.0, 1.0);
    let sin2 = 1.0 - cos_i * cos_i;
    let cos_t = (Complex64::new(1.0, 0.0) - sin2 / (n * n)).sqrt();
    let ci = Complex64::new(cos_i, 0.0);
    let rs = (ci - n * cos_t) / (ci + n * cos_t);
    let rp = (n * ci - cos_t) / (n * ci + cos_t);
    [rs.norm_sqr(), rp.norm_sqr()]
}

impl FresnelSource for Fresnel {
    fn reflectance(&self, _wavelength_nm: f64, cos_theta: f64) -> f64 {
        match *self {
            Fresnel::Schlick { n } => {
                let f0 = ((n - 1.0) / (n + 1.0)).powi(2);
                f0 + (1.0 - f0) * (1.0 - cos_theta.clamp(0.0, 1.0)).powi(5)
            }
            Fresnel::Index { n } => fresnel_unpolarised(n, cos_theta),
        }
    }
    fn reflectance_sp(&self, wavelength_nm: f64, cos_theta: f64) -> [f64; 2] {
        match *self {
            Fresnel::Schlick { .. } => {
                let r = self.reflectance(wavelength_nm, cos_theta);
                [r, r]
            }
            Fresnel::Index { n } => fresnel_sp(n, cos_theta),
        }
    }
    fn polarised(&self) -> bool {
        matches!(self, Fresnel::Index { .. })
    }
    fn depends_on_wavelength(&self) -> bool {
        false
    }
    fn describe(&self) -> String {
        match self {
            Fresnel::Schlick { n } => format!("Schlick, n = {n}"),
            Fresnel::Index { n } => format!("Fresnel, n = {} + {}i", n.re, n.im),
        }
    }
    fn as_builtin(&self) -> Option<&Fresnel> {
        Some(self)
    }
}

/// A thin-film stack as the Fresnel source (e.g. a keratin film on the nanostructure, or a coating): the
/// unpolarised reflectance of the stack at λ and the half-vector angle, from the multilayer recurrence of
/// `iridis-thinfilm`. Wavelength-dependent, so it stays inside the spectral integral.
#[derive(Debug, Clone)]
pub struct FilmFresnel {
    stack: iridis_thinfilm::Stack,
    /// Mean normal-incidence reflectance over 380–780 nm (5 nm steps): the λ-independent `F_0`.
    f0_mean: f64,
}

impl FilmFresnel {
    /// Wraps a stack, checking that its materials cover the visible band (380–780 nm).
    pub fn new(stack: iridis_thinfilm::Stack) -> Result<Self, crate::DiffractionError> {
        for l in [380.0, 780.0] {
            stack.evaluate(l, 0.0).map_err(|e| {
                crate::DiffractionError::Invalid(format!("the Fresnel stack must cover 380–780 nm: {e}"))
            })?;
        }
        let samples: Vec<f64> = (0..=80)
            .map(|k| stack.evaluate(380.0 + 5.0 * k as f64, 0.0).map(|r| r.r()))
            .collect::<Result<_, _>>()
            .map_err(|e| crate::DiffractionError::Invalid(format!("the Fresnel stack: {e}")))?;
        let f0_mean = samples.iter().sum::<f64>() / samples.len() as f64;
        if !(f0_mean.is_finite() && f0_mean > 0.0) {
            return Err(crate::DiffractionError::Invalid(format!(
                "the Fresnel stack reflects nothing at normal incidence (mean R = {f0_mean}): nothing to normalise by"
            )));
        }
        Ok(Self { stack, f0_mean })
    }
}

impl FresnelSource for FilmFresnel {
    fn reflectance(&self, wavelength_nm: f64, cos_theta: f64) -> f64 {
        // The range was checked at construction; a failure here would be a bug in the stack code.
        self.stack.evaluate(wavelength_nm, cos_theta.clamp(0.0, 1.0).acos()).map(|r| r.r()).unwrap_or(f64::NAN)
    }
    fn reflectance_sp(&self, wavelength_nm: f64, cos_theta: f64) -> [f64; 2] {
        match self.stack.evaluate(wavelength_nm, cos_theta.clamp(0.0, 1.0).acos()) {
            Ok(r) => [r.r_s, r.r_p],
            Err(_) => [f64::NAN; 2],
        }
    }
    fn polarised(&self) -> bool {
        true
    }
    fn depends_on_wavelength(&self) -> bool {
        true
    }
    fn normal_reflectance(&self) -> f64 {
        self.f0_mean
    }
    fn describe(&self) -> String {
        format!("thin-film stack {}", self.stack)
    }
}

/// How the Fresnel reflectance enters `C` (docs/PHYSICS.md, "The Fresnel factor").
///
/// In Stam's Kirchhoff derivation (the paper's eq. 2–4) `F` is the Fresnel *amplitude* coefficient, so `F²` is
/// the power reflectance `R` — once. The paper puts Schlick's power reflectance in place of `F`, which squares
/// `R`: at a 75° half-angle (n = 1.5) the angular brightening is `(R/R₀)² ≈ 41` instead of `R/R₀ ≈ 6.4`, and a
/// wavelength-dependent source (a film) enters as `R(λ)²`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FresnelConvention {
    /// `C ∝ R/R₀`: the power reflectance once (physically right; the default).
    #[default]
    Physical,
    /// `C ∝ (R/R₀)²`: the paper's printed use of Schlick's `R` as the amplitude `F` (to reproduce its figures).
    Paper,
}

impl FresnelConvention {
    /// Parses `physical` or `paper`.
    pub fn parse(s: &str) -> Result<Self, crate::DiffractionError> {
        match s.trim().to_ascii_lowercase().as_str() {
            "physical" => Ok(Self::Physical),
            "paper" => Ok(Self::Paper),
            other => Err(crate::DiffractionError::Invalid(format!(
                "Fresnel convention '{other}': expected 'physical' (R once, the default) or 'paper' (R², as printed)"
            ))),
        }
    }
    pub fn name(self) -> &'static str {
        match self {
            Self::Physical => "physical",
            Self::Paper => "paper",
        }
    }
    /// The Fresnel part of `C`: `R/R₀`, or its square under the paper's convention.
    pub fn ratio(self, r: f64, r0: f64) -> f64 {
        let x = r / r0;
        match self {
            Self::Physical => x,
            Self::Paper => x * x,
        }
    }
}

/// The shading factors around |A|²: Fresnel, geometry, optional Cook–Torrance shadowing.
#[derive(Debug, Clone)]
pub struct Shading {
    pub fresnel: std::sync::Arc<dyn FresnelSource>,
    /// Multiply by the Cook–Torrance V-cavity shadowing–masking term.
    pub shadowing: bool,
    /// `R` once (physical) or `R²` (the paper's formula as printed).
    pub convention: FresnelConvention,
}

impl Default for Shading {
    fn default() -> Self {
        Self {
            fresnel: std::sync::Arc::new(Fresnel::default()),
            shadowing: true,
            convention: FresnelConvention::Physical,
        }
    }
}

impl Shading {
    /// The factor `C` of the relative reflectance `ρ_λ = C |A|²` (paper eq. 4 with `G` of eq. 2, as in
    /// PHYSICS.md): `C = (R/R₀) (1 + ω_i·ω_r)² / ((cos θ_i + cos θ_r)² cos θ_r)`, times the shadowing term,
    /// with `R` the power reflectance at the half-vector angle and wavelength λ — Stam's `F²` with `F` the
    /// amplitude coefficient — and `R₀` [`FresnelSource::normal_reflectance`], the same for all λ. Under
    /// [`FresnelConvention::Paper`] the ratio is squared, as the paper prints it (`F² / F₀²` with `F` Schlick's
    /// power reflectance). With a λ-independent source, normal incidence and mirror viewing give `C = 1`.
    /// Zero below the horizon or when `w = 0`.
    ///
    /// No separate `cos θ_i`: the paper's eq. 9 multiplies its `C = F²G/(F_0² w²)` by `cos θ_i`, and its `G`
    /// (eq. 2) divides by `cos θ_i cos θ_r`; the two cancel, leaving `cos θ_r` alone (docs/diffraction.md).
    pub fn factor(&self, wavelength_nm: f64, wi: Vec3, wr: Vec3) -> f64 {
        let (ci, cr) = (wi[2], wr[2]);
        if ci <= 0.0 || cr <= 0.0 {
            return 0.0;
        }
        let w = ci + cr;
        let mut h = [wi[0] + wr[0], wi[1] + wr[1], wi[2] + wr[2]];
        let hl = dot(h, h).sqrt();
        if hl < 1e-300 {
            return 0.0;
        }
        h = [h[0] / hl, h[1] / hl, h[2] / hl];
        let f = self.fresnel.reflectance(wavelength_nm, dot(wi, h));
        let f0 = self.fresnel.normal_reflectance();
        let g = (1.0 + dot(wi, wr)).powi(2);
        let mut c = self.convention.ratio(f, f0) * g / (w * w * cr);
        if self.shadowing {
            c *= cook_torrance(wi, wr, h);
        }
        c
    }
}

/// Cook–Torrance V-cavity shadowing–masking: `min(1, 2(n·h)(n·ω_r)/(ω_r·h), 2(n·h)(n·ω_i)/(ω_r·h))`.
pub fn cook_torrance(wi: Vec3, wr: Vec3, h: Vec3) -> f64 {
    let (nh, vh) = (h[2], dot(wr, h));
    if vh <= 0.0 {
        return 0.0;
    }
    (2.0 * nh * wr[2] / vh).min(2.0 * nh * wi[2] / vh).min(1.0)
}
