//! The He–Torrance–Sillion–Greenberg BRDF (He, Torrance, Sillion and Greenberg, "A comprehensive physical
//! model for light reflection", SIGGRAPH 1991; Sussenbach's reference \[7\]) for one rough interface: a
//! Gaussian random surface of rms height `σ` and Gaussian autocorrelation length `τ`
//! (`C(r) = σ² exp(−r²/τ²)`) between a lossless upper medium and a (possibly absorbing) lower medium.
//!
//! The paper is not among the seeds; its published equations are written out below where they are used,
//! each under the name the paper gives it. With unit directions `ω_i` (towards the light) and `ω_r` (towards
//! the viewer) pointing away from the surface (`docs/PHYSICS.md`), `k = 2π n₁/λ` in the upper medium and
//! `V = ω_i + ω_r` (He et al.'s `k̂_r − k̂_i` with their incident vector pointing into the surface):
//!
//! * **phase variance** `g = (k σ₀ V_z)² = [(2π σ₀/λ₁)(cos θ_i + cos θ_r)]²`;
//! * **specular term** `ρ_sp = |F(θ_i)|² e^{−g} S(θ_i) S(θ_r)`, the fraction of the incident power reflected
//!   into the mirror direction (He et al. write it as a BRDF with `Δ/(cos θ_i dω_i)`, a delta on the specular
//!   cone); at `θ_r = θ_i`, `g = (4π σ₀ cos θ_i/λ₁)²`;
//! * **directional-diffuse term** `ρ_dd = |F(θ_h)|²/π · G S D / (cos θ_i cos θ_r)` (sr⁻¹) with the geometric
//!   factor `G = (V·V / V_z)²` (the polarisation brackets of the paper sum to `|k̂_r × k̂_i|⁴` for unpolarised
//!   light and cancel its denominator), `F` at the local (bisector) angle `cos θ_h = ω_i·V/|V|`, and the
//!   **distribution** `D = (π² τ²/(4 λ₁²)) Σ_{m≥1} g^m e^{−g}/(m! m) · exp(−τ² v_xy²/(4m))`,
//!   `v_xy = k |V_xy|`;
//! * **shadowing** (Smith): `S(θ) = [1 − ½ erfc(a)] / (Λ + 1)`, `Λ = ½ [e^{−a²}/(√π a) − erfc(a)]`,
//!   `a = τ cot θ/(2σ)`;
//! * **effective roughness** `σ₀ = σ (1 + z₀²/σ²)^{−1/2}`, `z₀` the root of
//!   `√(π/2) z₀ = (σ/4)(K_i + K_r) exp(−z₀²/(2σ²))`, `K = tan θ · erfc(τ cot θ/(2σ))`: only the
//!   unshadowed part of the surface takes part, which lowers the roughness seen at grazing angles.
//!
//! The uniform-diffuse (subsurface) term of the paper is not part of the LSRS model (Sussenbach section 3.2
//! uses the specular and directional-diffuse reflectivities only) and is not implemented.
//!
//! The series of `D` is the thesis' "D-iterations" (Listing 3.6): [`Series::Fixed`] sums a fixed number of
//! terms as the thesis does, [`Series::Tolerance`] stops when the remainder bound (see [`dd_series`]) falls
//! below a fraction of the lobe's peak; both report the bound.
//!
//! **Validity** (checked, errors otherwise; [`Roughness::new`], [`Roughness::check_wavelength`]):
//! `σ > 0`, `τ > 0`; rms facet slope `2σ/τ ≤ 1` (Beckmann `m = 2σ/τ`; steeper surfaces scatter several
//! times between facets, which neither the Kirchhoff integral nor Smith's shadowing describe); and the
//! tangent-plane (Kirchhoff) approximation's radius of curvature `r_c = τ²/(2√3 σ)` (the rms curvature of
//! this surface is `2√3 σ/τ²`) at least one wavelength in the upper medium, `r_c ≥ λ/n₁`.

use std::f64::consts::PI;

use crate::error::ThinFilmError;

/// Largest phase variance `g` for which the series of `D` is summed (`σ₀/λ₁` up to about 18): beyond, the
/// number of terms grows like `g` and the geometrical-optics limit of the paper should be used instead.
pub const MAX_PHASE_VARIANCE: f64 = 50_000.0;

/// Smith's shadowing `S = [1 − ½ erfc(a)]/(Λ + 1)`, `Λ = ½ (e^{−a²}/(√π a) − erfc(a))`, for a finite
/// `a = τ cot θ/(2σ)` and its `erfc(a)` (module documentation).
fn smith(a: f64, erfc_a: f64) -> f64 {
    let lambda = 0.5 * ((-a * a).exp() / (PI.sqrt() * a) - erfc_a);
    (1.0 - 0.5 * erfc_a) / (lambda.max(0.0) + 1.0)
}

/// The statistics of a rough interface: rms height `σ` and autocorrelation length `τ`, both in nm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Roughness {
    sigma_nm: f64,
    tau_nm: f64,
}

impl Roughness {
    /// A rough interface; refuses `σ ≤ 0`, `τ ≤ 0`, non-finite values and rms slopes `2σ/τ > 1` (see the
    /// module documentation for why).
    pub fn new(sigma_nm: f64, tau_nm: f64) -> Result<Self, ThinFilmError> {
        if !(sigma_nm.is_finite() && sigma_nm > 0.0) {
            return Err(ThinFilmError::Invalid(format!(
                "rms roughness σ = {sigma_nm} nm must be finite and > 0 (for a smooth interface use the smooth model)"
            )));
        }
        if !(tau_nm.is_finite() && tau_nm > 0.0) {
            return Err(ThinFilmError::Invalid(format!(
                "autocorrelation length τ = {tau_nm} nm must be finite and > 0"
            )));
        }
        let r = Self { sigma_nm, tau_nm };
        if r.rms_slope() > 1.0 {
            return Err(ThinFilmError::Invalid(format!(
                "σ = {sigma_nm} nm with τ = {tau_nm} nm has an rms facet slope 2σ/τ = {:.3} > 1 (facets tilted beyond 45°): \
                 outside the HTSG model, whose Kirchhoff integral and Smith shadowing ignore multiple scattering between \
                 facets; use τ ≥ 2σ = {} nm",
                r.rms_slope(),
                2.0 * sigma_nm
            )));
        }
        Ok(r)
    }

    pub fn sigma_nm(&self) -> f64 {
        self.sigma_nm
    }

    pub fn tau_nm(&self) -> f64 {
        self.tau_nm
    }

    /// The Beckmann rms slope `m = 2σ/τ` of the surface (`tan` of the rms facet tilt).
    pub fn rms_slope(&self) -> f64 {
        2.0 * self.sigma_nm / self.tau_nm
    }

    /// The mean radius of curvature `τ²/(2√3 σ)` (nm): the Kirchhoff approximation needs it above a wavelength.
    pub fn curvature_radius_nm(&self) -> f64 {
        self.tau_nm * self.tau_nm / (2.0 * 3f64.sqrt() * self.sigma_nm)
    }

    /// Checks the tangent-plane condition `r_c ≥ λ/n₁` for a vacuum wavelength and the real index `n₁` of the
    /// medium above the rough interface.
    pub fn check_wavelength(&self, wavelength_nm: f64, n_upper: f64) -> Result<(), ThinFilmError> {
        if !(wavelength_nm.is_finite() && wavelength_nm > 0.0) {
            return Err(ThinFilmError::Invalid(format!("wavelength {wavelength_nm} nm must be positive")));
        }
        let lambda1 = wavelength_nm / n_upper;
        let rc = self.curvature_radius_nm();
        if rc < lambda1 {
            return Err(ThinFilmError::Invalid(format!(
                "σ = {} nm, τ = {} nm: the surface's radius of curvature τ²/(2√3σ) = {rc:.0} nm is below the wavelength \
                 {lambda1:.0} nm in the medium above it (λ = {wavelength_nm} nm, n = {n_upper}); the HTSG model's Kirchhoff \
                 (tangent-plane) approximation needs it larger: raise τ to ≥ {:.0} nm or lower σ to ≤ {:.1} nm",
                self.sigma_nm,
                self.tau_nm,
                (lambda1 * 2.0 * 3f64.sqrt() * self.sigma_nm).sqrt(),
                self.tau_nm * self.tau_nm / (2.0 * 3f64.sqrt() * lambda1),
            )));
        }
        Ok(())
    }

    /// `a = τ cot θ / (2σ)` for a direction with `cos θ`; infinite at normal incidence.
    fn a(&self, cos: f64) -> f64 {
        let sin = (1.0 - cos * cos).max(0.0).sqrt();
        if sin == 0.0 {
            f64::INFINITY
        } else {
            self.tau_nm * cos / (2.0 * self.sigma_nm * sin)
        }
    }

    /// Smith's shadowing function for one direction (module documentation): `S(θ) = [1 − ½ erfc(a)]/(Λ + 1)`,
    /// 1 at normal incidence, 0 at grazing (`cos θ ≤ 0`).
    pub fn shadowing(&self, cos: f64) -> f64 {
        if cos <= 0.0 {
            return 0.0;
        }
        let a = self.a(cos);
        if a.is_infinite() {
            return 1.0;
        }
        smith(a, libm::erfc(a))
    }

    /// `K = tan θ · erfc(τ cot θ/(2σ))` of the effective-roughness equation; infinite at grazing.
    pub fn k_factor(&self, cos: f64) -> f64 {
        if cos <= 0.0 {
            return f64::INFINITY;
        }
        let sin = (1.0 - cos * cos).max(0.0).sqrt();
        if sin == 0.0 {
            return 0.0;
        }
        (sin / cos) * libm::erfc(self.a(cos))
    }

    /// `(S(θ), K(θ))`: [`Roughness::shadowing`] and [`Roughness::k_factor`] of one direction, bit for bit, with
    /// one `erfc` between them (integrals over many directions need both).
    pub fn shadowing_and_k(&self, cos: f64) -> (f64, f64) {
        if cos <= 0.0 {
            return (0.0, f64::INFINITY);
        }
        let a = self.a(cos);
        if a.is_infinite() {
            return (1.0, self.k_factor(cos));
        }
        let e = libm::erfc(a);
        let sin = (1.0 - cos * cos).max(0.0).sqrt();
        (smith(a, e), (sin / cos) * e)
    }

    /// The effective roughness `σ₀` from `K_i + K_r` (module documentation): solves
    /// `√(π/2) u = (K/4) e^{−u²/2}` for `u = z₀/σ` (one root, bracketed in `[0, K/(4√(π/2))]`) by safeguarded
    /// Newton steps and returns `σ/√(1 + u²)`.
    pub fn effective_sigma_from_k(&self, k_sum: f64) -> f64 {
        if k_sum <= 0.0 {
            return self.sigma_nm;
        }
        if k_sum.is_infinite() {
            return 0.0;
        }
        let c = (PI / 2.0).sqrt();
        let f = |u: f64| c * u - 0.25 * k_sum * (-0.5 * u * u).exp();
        // u e^{u²/2} = L with L = K/(4√(π/2)): u ≤ L, and for L > 1 also u ≤ max(1, √(2 ln L)) (where u ≥ 1,
        // e^{u²/2} ≤ L). The start, √(2 ln(L/√(2 ln L))) for large L and L/(1 + L²/2) for small, is within a few
        // per cent of the root, so that Newton's steps stay inside the bracket: from the old start, L/2, a
        // grazing direction's huge K took ~50 bisections first.
        let l = k_sum / (4.0 * c);
        let mut lo = 0.0;
        let (mut hi, mut u) = if l > 1.0 {
            let t = (2.0 * l.ln()).sqrt().max(1.0);
            let hi = l.min(t);
            (hi, (2.0 * (l / t).ln()).max(0.0).sqrt().clamp(0.5 * hi, hi))
        } else {
            (l, l / (1.0 + 0.5 * l * l))
        };
        for _ in 0..200 {
            let fu = f(u);
            // An exact root, or a Newton step that converged, ends the search before the bracket is consulted:
            // at the root itself `u` is also the bracket's end, and the fallback would bisect back down from
            // the other end for ~45 steps (it did, and ended a few ulp away).
            if fu == 0.0 {
                break;
            }
            if fu > 0.0 {
                hi = u;
            } else {
                lo = u;
            }
            let df = c + 0.25 * k_sum * u * (-0.5 * u * u).exp();
            let mut next = u - fu / df;
            if (next - u).abs() <= 1e-15 * u.max(1e-300) {
                u = next;
                break;
            }
            if !(next > lo && next < hi) {
                next = 0.5 * (lo + hi);
            }
            if hi - lo <= 1e-15 * hi {
                u = next;
                break;
            }
            u = next;
        }
        self.sigma_nm / (1.0 + u * u).sqrt()
    }

    /// `σ₀` for a pair of directions given by their cosines.
    pub fn effective_sigma(&self, cos_i: f64, cos_r: f64) -> f64 {
        self.effective_sigma_from_k(self.k_factor(cos_i) + self.k_factor(cos_r))
    }
}

/// How the series of `D` is truncated (the thesis' "D-iterations", Listing 3.6).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Series {
    /// Exactly this many terms `m = 1 … M` (Sussenbach uses 5); the remainder bound is reported.
    Fixed(usize),
    /// As many terms as needed for the remainder bound to fall below this fraction of the lobe's peak value
    /// `Σ_{m≥1} g^m e^{−g}/(m! m)` (the sum at `v_xy = 0`).
    Tolerance(f64),
}

impl Default for Series {
    fn default() -> Self {
        Series::Tolerance(1e-6)
    }
}

/// A partial sum of the series of `D` with its remainder bound.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SeriesSum {
    /// `Σ_{m=1}^{M} g^m e^{−g}/(m! m) · exp(−c/m)`.
    pub value: f64,
    /// `M`, the number of terms summed.
    pub terms: usize,
    /// An upper bound of the terms left out, `Σ_{m>M} … ≤ P(X > M)/(M + 1)` for `X` Poisson with mean `g`,
    /// `P(X > M) ≤ p_{M+1}/(1 − g/(M + 2))` when `M + 2 > g` (else 1).
    pub bound: f64,
    /// The peak value `Σ_{m=1}^{M} g^m e^{−g}/(m! m)` (the same terms at `c = 0`).
    pub peak: f64,
}

/// The series of He et al.'s distribution `D`, `Σ_{m≥1} g^m e^{−g}/(m! m) exp(−c/m)` with
/// `c = τ² v_xy²/4 ≥ 0`, summed in log space (no overflow for large `g`). Each `exp(−c/m) ≤ 1`, hence the
/// bound of [`SeriesSum::bound`].
pub fn dd_series(g: f64, c: f64, series: Series) -> Result<SeriesSum, ThinFilmError> {
    if !(g.is_finite() && g >= 0.0 && c >= 0.0) {
        return Err(ThinFilmError::Invalid(format!("HTSG series: phase variance g = {g} and c = {c} must be ≥ 0")));
    }
    if g > MAX_PHASE_VARIANCE {
        return Err(ThinFilmError::Invalid(format!(
            "HTSG series: phase variance g = {g:.0} > {MAX_PHASE_VARIANCE} (σ/λ too large, ~{:.0} terms); this rough limit \
             is outside what the directional-diffuse series is summed for",
            g
        )));
    }
    let (fixed, tol) = match series {
        Series::Fixed(m) => {
            if m == 0 {
                return Err(ThinFilmError::Invalid("D-iterations must be ≥ 1".into()));
            }
            (Some(m), 0.0)
        }
        Series::Tolerance(t) => {
            if !(t.is_finite() && t > 0.0 && t < 1.0) {
                return Err(ThinFilmError::Invalid(format!("series tolerance {t} must lie in (0, 1)")));
            }
            (None, t)
        }
    };
    if g == 0.0 {
        return Ok(SeriesSum { value: 0.0, terms: fixed.unwrap_or(1), bound: 0.0, peak: 0.0 });
    }
    let ln_g = g.ln();
    // ln of the Poisson weight p_m = g^m e^{−g}/m! and the weight itself, for the term at hand: each step's
    // p_{m+1} serves the remainder bound and then the next term (one exp and one ln a term besides exp(−c/m)).
    let mut ln_p = ln_g - g;
    let mut p = ln_p.exp();
    let (mut value, mut peak) = (0.0, 0.0);
    let cap = fixed.unwrap_or((4.0 * g + 40.0 * g.sqrt() + 200.0) as usize);
    let mut m = 0usize;
    loop {
        m += 1;
        let mf = m as f64;
        let p_over_m = p / mf;
        value += p_over_m * (-c / mf).exp();
        peak += p_over_m;
        // Bound of the remainder after m terms.
        let next = mf + 1.0;
        ln_p += ln_g - next.ln();
        p = ln_p.exp();
        let tail = if next + 1.0 > g { (p / (1.0 - g / (next + 1.0))).min(1.0) } else { 1.0 };
        let bound = tail / next;
        let done = match fixed {
            // Past the Poisson mode a weight that underflows to 0 makes every later term exactly 0: the sum of
            // any larger fixed count is this one, to the bit (D-iterations = 10⁹ ran for minutes before).
            Some(n) => m >= n || (p == 0.0 && next > g),
            None => bound <= tol * peak,
        };
        if done || m >= cap {
            return Ok(SeriesSum { value, terms: m, bound, peak });
        }
    }
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The HTSG model of one rough interface: its statistics and how the series of `D` is truncated.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Htsg {
    pub roughness: Roughness,
    pub series: Series,
}

/// The geometric part of the directional-diffuse term for one pair of directions, without the Fresnel factor:
/// `ρ_dd = |F(θ_h)|² · factor`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DiffuseGeometry {
    /// `G S D / (π cos θ_i cos θ_r)` in sr⁻¹.
    pub factor: f64,
    /// `cos θ_h = ω_i·V/|V|`, the local angle at which `F` is taken.
    pub cos_local: f64,
    /// The phase variance `g` with the effective roughness.
    pub g: f64,
    pub sigma0_nm: f64,
    /// The series' number of terms and remainder bound (relative to `D` as the factor is).
    pub terms: usize,
    pub bound: f64,
}

/// The unpolarised HTSG values of a bare interface (see [`Htsg::evaluate`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HtsgValue {
    /// `ρ_sp = |F(θ_i)|² e^{−g} S(θ_i)²`: the fraction of the incident power reflected specularly.
    pub specular: f64,
    /// `ρ_dd(ω_i, ω_r)`, sr⁻¹.
    pub diffuse: f64,
    pub geometry: DiffuseGeometry,
}

impl Htsg {
    pub fn new(roughness: Roughness, series: Series) -> Self {
        Self { roughness, series }
    }

    /// The amplitude factor of the specular term for a direction with `cos θ` in a medium of wave number
    /// `k = 2π n₁/λ`: `e^{−g/2} S(θ)` with `g = (2 k σ₀ cos θ)²`, `σ₀ = σ₀(θ, θ)`, so that its square is
    /// `e^{−g} S(θ)²`, the specular term's attenuation of `|F|²`. Returns `(factor, g, σ₀)`.
    pub fn specular_amplitude(&self, cos: f64, k: f64) -> (f64, f64, f64) {
        if cos <= 0.0 {
            return (0.0, 0.0, 0.0);
        }
        let s0 = self.roughness.effective_sigma(cos, cos);
        let g = (2.0 * k * s0 * cos).powi(2);
        ((-0.5 * g).exp() * self.roughness.shadowing(cos), g, s0)
    }

    /// The directional-diffuse geometry (module documentation) for unit directions `wi`, `wr` (away from the
    /// surface) in a medium of wave number `k = 2π n₁/λ`. Zero when either direction is at or below the horizon.
    pub fn diffuse_geometry(&self, wi: [f64; 3], wr: [f64; 3], k: f64) -> Result<DiffuseGeometry, ThinFilmError> {
        let r = &self.roughness;
        let (ci, cr) = (wi[2], wr[2]);
        if ci <= 0.0 || cr <= 0.0 {
            return Ok(DiffuseGeometry { factor: 0.0, cos_local: 1.0, g: 0.0, sigma0_nm: 0.0, terms: 0, bound: 0.0 });
        }
        let sigma0 = r.effective_sigma(ci, cr);
        let shadow = r.shadowing(ci) * r.shadowing(cr);
        self.diffuse_geometry_with(wi, wr, k, sigma0, shadow)
    }

    /// [`Htsg::diffuse_geometry`] with `σ₀` and `S(θ_i) S(θ_r)` computed by the caller (tables reuse them).
    pub fn diffuse_geometry_with(
        &self,
        wi: [f64; 3],
        wr: [f64; 3],
        k: f64,
        sigma0: f64,
        shadow: f64,
    ) -> Result<DiffuseGeometry, ThinFilmError> {
        let (ci, cr) = (wi[2], wr[2]);
        if ci <= 0.0 || cr <= 0.0 || shadow <= 0.0 {
            return Ok(DiffuseGeometry {
                factor: 0.0,
                cos_local: 1.0,
                g: 0.0,
                sigma0_nm: sigma0,
                terms: 0,
                bound: 0.0,
            });
        }
        let tau = self.roughness.tau_nm;
        let v = [wi[0] + wr[0], wi[1] + wr[1], wi[2] + wr[2]];
        let vv = dot(v, v);
        let vz = v[2];
        let vxy2 = v[0] * v[0] + v[1] * v[1];
        let g = (k * sigma0 * vz).powi(2);
        let c = 0.25 * tau * tau * k * k * vxy2;
        let s = dd_series(g, c, self.series)?;
        // D = π² τ²/(4 λ₁²) Σ …, with λ₁ = 2π/k.
        let pre = PI * PI * tau * tau * k * k / (16.0 * PI * PI);
        let d = pre * s.value;
        let geom = (vv / vz).powi(2);
        let denom = PI * ci * cr;
        let factor = geom * shadow * d / denom;
        let bound = geom * shadow * pre * s.bound / denom;
        Ok(DiffuseGeometry {
            factor,
            cos_local: (dot(wi, v) / vv.sqrt()).clamp(0.0, 1.0),
            g,
            sigma0_nm: sigma0,
            terms: s.terms,
            bound,
        })
    }

    /// The HTSG BRDF of a bare interface between a lossless upper medium of index `n_upper` and a lower
    /// medium `n_lower = n + iκ`, at vacuum wavelength `λ`, for light from `wi` seen from `wr`. Checks the
    /// model's validity at this wavelength ([`Roughness::check_wavelength`]).
    pub fn evaluate(
        &self,
        n_upper: f64,
        n_lower: num_complex::Complex64,
        wi: [f64; 3],
        wr: [f64; 3],
        wavelength_nm: f64,
    ) -> Result<HtsgValue, ThinFilmError> {
        for w in [wi, wr] {
            if !(w.iter().all(|x| x.is_finite()) && (dot(w, w) - 1.0).abs() < 1e-9) {
                return Err(ThinFilmError::Invalid(format!("direction {w:?} is not a unit vector")));
            }
        }
        if !(n_upper.is_finite() && n_upper > 0.0) {
            return Err(ThinFilmError::Invalid(format!("upper index {n_upper} must be > 0")));
        }
        self.roughness.check_wavelength(wavelength_nm, n_upper)?;
        let k = 2.0 * PI * n_upper / wavelength_nm;
        let f_spec = fresnel_power(n_upper, n_lower, wi[2].max(0.0));
        let (amp, _, _) = self.specular_amplitude(wi[2], k);
        let geometry = self.diffuse_geometry(wi, wr, k)?;
        let f_local = fresnel_power(n_upper, n_lower, geometry.cos_local);
        Ok(HtsgValue { specular: f_spec * amp * amp, diffuse: f_local * geometry.factor, geometry })
    }
}

/// Unpolarised Fresnel reflectance `(|r_s|² + |r_p|²)/2` (Sussenbach eq. 3.7–3.8, 3.12) from a lossless
/// medium `n₁` into `n₂` at an angle with cosine `cos` in the upper medium.
pub fn fresnel_power(n_upper: f64, n_lower: num_complex::Complex64, cos: f64) -> f64 {
    let f = local_fresnel(num_complex::Complex64::new(n_upper, 0.0), n_lower, cos);
    0.5 * (f.r_s.norm_sqr() + f.r_p.norm_sqr())
}

/// The Fresnel amplitudes (Sussenbach eq. 3.7–3.10) of a facet hit at an angle with cosine `cos` in the upper
/// medium of index `n_upper` (for an absorbing upper medium its real part sets the Snell invariant).
pub fn local_fresnel(
    n_upper: num_complex::Complex64,
    n_lower: num_complex::Complex64,
    cos: f64,
) -> crate::recurrence::Fresnel {
    use crate::recurrence::{fresnel, Medium};
    let cos = cos.clamp(0.0, 1.0);
    let sin = (1.0 - cos * cos).sqrt();
    let upper = Medium { n: n_upper, cos: num_complex::Complex64::new(cos, 0.0) };
    let lower = Medium::new(n_lower, n_upper.re * sin);
    fresnel(upper, lower)
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_complex::Complex64;

    #[test]
    fn shadowing_and_k_are_the_two_functions_bit_for_bit() {
        // Normal incidence (a = ∞), grazing, below the horizon, NaN and the range between.
        let r = Roughness::new(25.0, 300.0).unwrap();
        let cosines =
            [1.0, 0.0, -0.3, f64::NAN, 1e-300, 1.0 - 1e-16].into_iter().chain((1..200).map(|k| k as f64 / 200.0));
        for c in cosines {
            let (s, k) = r.shadowing_and_k(c);
            assert_eq!(s.to_bits(), r.shadowing(c).to_bits(), "S at cos {c}");
            assert_eq!(k.to_bits(), r.k_factor(c).to_bits(), "K at cos {c}");
        }
    }

    #[test]
    fn erfc_matches_reference_values() {
        // The erfc of Smith's shadowing and K is musl's (the libm crate), < 1 ulp; the series / continued
        // fraction it replaced was 2.5e-13 off near x = 2 and 4.5× slower.
        // Values from Abramowitz & Stegun table 7.1 / high-precision evaluation.
        for (x, want) in [
            (0.0, 1.0),
            (0.1, 0.887_537_083_981_715),
            (0.5, 0.479_500_122_186_953_5),
            (1.0, 0.157_299_207_050_285_13),
            (1.9, 0.007_209_570_764_742_524),
            (2.0, 0.004_677_734_981_047_266),
            (3.0, 2.209_049_699_858_544e-5),
            (5.0, 1.537_459_794_428_035e-12),
            (10.0, 2.088_487_583_762_545e-45),
            (-1.0, 1.842_700_792_949_715),
        ] {
            let got = libm::erfc(x);
            assert!(((got - want) / want).abs() < 2e-15, "erfc({x}) = {got}, want {want}");
        }
    }

    #[test]
    fn bad_roughness_is_refused_with_a_reason() {
        for (s, t, needle) in [
            (0.0, 300.0, "σ"),
            (-5.0, 300.0, "σ"),
            (f64::NAN, 300.0, "σ"),
            (25.0, 0.0, "τ"),
            (25.0, -1.0, "τ"),
            (200.0, 300.0, "slope"),
        ] {
            let e = Roughness::new(s, t).unwrap_err().to_string();
            assert!(e.contains(needle), "{s}, {t}: {e}");
        }
        // Kirchhoff: radius of curvature below the wavelength.
        let r = Roughness::new(100.0, 250.0).unwrap(); // r_c = 180 nm
        let e = r.check_wavelength(500.0, 1.0).unwrap_err().to_string();
        assert!(e.contains("curvature"), "{e}");
        assert!(r.check_wavelength(170.0, 1.0).is_ok());
        // Listing 3.6 is valid over the visible range, in water.
        let l36 = Roughness::new(25.0, 300.0).unwrap();
        assert!(l36.check_wavelength(780.0, 1.0).is_ok());
    }

    #[test]
    fn shadowing_and_effective_roughness_limits() {
        let r = Roughness::new(25.0, 300.0).unwrap();
        assert_eq!(r.shadowing(1.0), 1.0);
        assert_eq!(r.shadowing(0.0), 0.0);
        // Monotone in the angle, within (0, 1].
        let mut last = 1.0;
        for deg in (0..90).step_by(5) {
            let s = r.shadowing(f64::to_radians(deg as f64).cos());
            assert!(s > 0.0 && s <= last + 1e-15, "{deg}°: {s}");
            last = s;
        }
        // σ₀ = σ where nothing is shadowed; σ₀ < σ at grazing; σ₀ → 0 as K → ∞.
        assert_eq!(r.effective_sigma(1.0, 1.0), 25.0);
        let s0 = r.effective_sigma(f64::to_radians(88.0).cos(), f64::to_radians(88.0).cos());
        assert!(s0 < 25.0 && s0 > 0.0, "{s0}");
        // The root satisfies its equation √(π/2) u = (K/4) e^{−u²/2}, u = z₀/σ, over K from near-normal pairs to
        // grazing ones (K = tan θ erfc(…) grows without bound), to a few ulp of the root.
        let c = (PI / 2.0).sqrt();
        for k in [0.02, 0.3, 1.0, 3.7, 12.0, 30.0, 1e3, 1e6, 1e12, 1e100] {
            let s0 = r.effective_sigma_from_k(k);
            let u = (25.0f64 * 25.0 / (s0 * s0) - 1.0).sqrt();
            // The residual relative to the size of its sides, and u inside the bracket (0, K/(4√(π/2))].
            let residual = (c * u - 0.25 * k * (-0.5 * u * u).exp()).abs() / (c * u);
            assert!(residual < 1e-9, "K = {k}: u = {u}, relative residual {residual:e}");
            assert!(u > 0.0 && u <= k / (4.0 * c), "K = {k}: u = {u} outside its bracket");
        }
    }

    #[test]
    fn series_bound_holds() {
        for g in [1e-3, 0.5, 1.2, 7.0, 40.0, 900.0] {
            for c in [0.0, 3.0, 50.0] {
                // Far beyond the Poisson mass: the terms left out are below 1e-300.
                let exact = dd_series(g, c, Series::Fixed((3.0 * g) as usize + 300)).unwrap();
                assert!(exact.bound < 1e-250);
                for m in [1, 2, 5, 10, 30] {
                    let part = dd_series(g, c, Series::Fixed(m)).unwrap();
                    assert_eq!(part.terms, m);
                    let err = exact.value - part.value;
                    assert!(
                        err >= -1e-15 * exact.value && err <= part.bound * (1.0 + 1e-9) + 1e-300,
                        "g {g} c {c} M {m}: {err} > {}",
                        part.bound
                    );
                }
                let t = dd_series(g, c, Series::Tolerance(1e-6)).unwrap();
                assert!(t.bound <= 1e-6 * t.peak && (exact.value - t.value) <= 1e-6 * t.peak);
            }
        }
        // Σ_{m≥1} p_m/m at c = 0 for small g ≈ g (first term), and it never exceeds 1.
        let s = dd_series(1e-4, 0.0, Series::default()).unwrap();
        assert!((s.value - 1e-4 * (-1e-4f64).exp()).abs() < 1e-8);
        assert!(dd_series(60_000.0, 0.0, Series::default()).is_err());
        assert!(dd_series(1.0, 0.0, Series::Fixed(0)).is_err());
        // A count far past where the weights underflow stops there, with the same sum to the bit.
        for g in [0.5, 40.0, 900.0] {
            let huge = dd_series(g, 3.0, Series::Fixed(1_000_000_000)).unwrap();
            let enough = dd_series(g, 3.0, Series::Fixed((3.0 * g) as usize + 400)).unwrap();
            assert!(huge.terms < (3.0 * g) as usize + 400, "{}", huge.terms);
            assert_eq!(huge.value.to_bits(), enough.value.to_bits());
        }
    }

    /// `ρ_sp + ∫ ρ_dd cos θ_r dω_r` over the hemisphere by the midpoint rule in (θ_r, φ_r).
    fn albedo(h: &Htsg, n2: Complex64, theta_i: f64, wl: f64) -> (f64, f64) {
        let wi = [theta_i.sin(), 0.0, theta_i.cos()];
        let (nt, np) = (240, 240);
        let mut sum = 0.0;
        let dt = 0.5 * PI / nt as f64;
        let dp = PI / np as f64; // φ ∈ [0, π], doubled by symmetry
        for a in 0..nt {
            let t = (a as f64 + 0.5) * dt;
            for b in 0..np {
                let p = (b as f64 + 0.5) * dp;
                let wr = [t.sin() * p.cos(), t.sin() * p.sin(), t.cos()];
                let v = h.evaluate(1.0, n2, wi, wr, wl).unwrap();
                sum += v.diffuse * t.cos() * t.sin() * dt * dp * 2.0;
            }
        }
        let v = h.evaluate(1.0, n2, wi, [-wi[0], 0.0, wi[2]], wl).unwrap();
        (v.specular, sum)
    }

    #[test]
    fn energy_never_exceeds_the_incident_energy() {
        let n_metal = Complex64::new(0.2, 3.4);
        for (s, t) in [(25.0, 300.0), (60.0, 400.0), (150.0, 600.0)] {
            let h = Htsg::new(Roughness::new(s, t).unwrap(), Series::Tolerance(1e-7));
            for n2 in [Complex64::new(1.5, 0.0), n_metal] {
                for deg in [0.0, 30.0, 60.0, 80.0] {
                    let th = f64::to_radians(deg);
                    let (spec, diff) = albedo(&h, n2, th, 500.0);
                    let total = spec + diff;
                    eprintln!("HTSG albedo σ {s} τ {t} n {n2} θ_i {deg}°: specular {spec:.5} + diffuse {diff:.5} = {total:.5}");
                    assert!(total <= 1.0, "σ {s} τ {t} n {n2} {deg}°: {spec} + {diff} = {total} > 1");
                    // Nothing is created, and at small slopes near normal incidence (no shadowing, Fresnel
                    // flat in angle) almost nothing is lost: the total is the smooth Fresnel reflectance.
                    let f = fresnel_power(1.0, n2, th.cos());
                    if deg <= 30.0 && s / t < 0.1 {
                        assert!((total - f).abs() < 0.02 * f, "σ {s} τ {t} n {n2} {deg}°: {total} vs |F|² {f}");
                    }
                }
            }
        }
    }

    #[test]
    fn specular_peak_falls_with_the_debye_waller_factor() {
        // exp(−(4πσ cos θ/λ)²) where the effective roughness is σ (no shadowing: τ ≫ σ, moderate angles).
        let n2 = Complex64::new(1.5, 0.0);
        for sigma in [1.0, 10.0, 25.0, 50.0] {
            let h = Htsg::new(Roughness::new(sigma, 1000.0).unwrap(), Series::default());
            for wl in [400.0, 550.0, 700.0] {
                for deg in [0.0, 20.0, 45.0, 60.0] {
                    let th = f64::to_radians(deg);
                    let wi = [th.sin(), 0.0, th.cos()];
                    let v = h.evaluate(1.0, n2, wi, [-wi[0], 0.0, wi[2]], wl).unwrap();
                    let want = fresnel_power(1.0, n2, th.cos()) * (-(4.0 * PI * sigma * th.cos() / wl).powi(2)).exp();
                    assert!(
                        ((v.specular - want) / want).abs() < 1e-9,
                        "σ {sigma} λ {wl} {deg}°: {} vs {want}",
                        v.specular
                    );
                }
            }
        }
        // At grazing incidence shadowing lowers the effective roughness: the peak is higher than the naive
        // factor but still scaled by S².
        let h = Htsg::new(Roughness::new(25.0, 200.0).unwrap(), Series::default());
        let th = f64::to_radians(85.0);
        let wi = [th.sin(), 0.0, th.cos()];
        let v = h.evaluate(1.0, n2, wi, [-wi[0], 0.0, wi[2]], 400.0).unwrap();
        let naive = fresnel_power(1.0, n2, th.cos()) * (-(4.0 * PI * 25.0 * th.cos() / 400.0).powi(2)).exp();
        let s = h.roughness.shadowing(th.cos());
        assert!(v.specular > naive * s * s * (1.0 + 1e-6), "{} vs {}", v.specular, naive * s * s);
    }

    #[test]
    fn brdf_is_reciprocal_and_peaks_near_the_mirror_direction() {
        let h = Htsg::new(Roughness::new(25.0, 300.0).unwrap(), Series::default());
        let n2 = Complex64::new(0.2, 3.4);
        let dir = |t: f64, p: f64| {
            let (t, p) = (t.to_radians(), p.to_radians());
            [t.sin() * p.cos(), t.sin() * p.sin(), t.cos()]
        };
        for (a, b) in [((30.0, 0.0), (50.0, 160.0)), ((70.0, 0.0), (10.0, 90.0)), ((5.0, 0.0), (85.0, 200.0))] {
            let x = h.evaluate(1.0, n2, dir(a.0, a.1), dir(b.0, b.1), 550.0).unwrap().diffuse;
            let y = h.evaluate(1.0, n2, dir(b.0, b.1), dir(a.0, a.1), 550.0).unwrap().diffuse;
            assert!(((x - y) / x).abs() < 1e-12, "{x} vs {y}");
        }
        let at = |t: f64| h.evaluate(1.0, n2, dir(40.0, 0.0), dir(t, 180.0), 550.0).unwrap().diffuse;
        assert!(at(40.0) > at(20.0) && at(40.0) > at(60.0) && at(40.0) > at(0.0));
    }
}
