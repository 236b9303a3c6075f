//! The fit: weighted residuals `(model − measured)/σ`, Levenberg–Marquardt from several starts, covariance.

use levenberg_marquardt::{LeastSquaresProblem, LevenbergMarquardt};
use nalgebra::{storage::Owned, DMatrix, DVector, Dyn};

use crate::{FitError, Measured, Quantity, Template};

/// How to fit.
#[derive(Debug, Clone, PartialEq)]
pub struct FitOptions {
    pub angle_rad: f64,
    pub quantity: Quantity,
    /// Grid points per thickness parameter for the multi-start search (0: automatic, ~1 per 10 nm, ≤ 64;
    /// 1: no search, one local fit from the start values).
    pub grid: usize,
    /// How many of the best grid points are refined by Levenberg–Marquardt.
    pub refine: usize,
    /// How the Jacobian is computed.
    pub derivatives: Derivatives,
}

/// The Jacobian of the fit: exact (forward-mode automatic differentiation through the model,
/// [`iridis_thinfilm::jet`]) or central finite differences. Exact derivatives cover every parameter type
/// (thicknesses, constant indices, Cauchy and Sellmeier coefficients) for up to [`MAX_EXACT`] parameters;
/// beyond that, and where an exact derivative is infinite (a layer exactly at its critical angle), the fit
/// falls back to finite differences.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Derivatives {
    #[default]
    Exact,
    FiniteDifferences,
}

/// The most parameters with exact derivatives (the jets' width is fixed at compile time).
pub const MAX_EXACT: usize = 16;

impl Default for FitOptions {
    fn default() -> Self {
        Self { angle_rad: 0.0, quantity: Quantity::R, grid: 0, refine: 4, derivatives: Derivatives::Exact }
    }
}

/// The outcome: values, 1σ uncertainties, correlations, χ², the fitted curve.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct FitResult {
    pub names: Vec<String>,
    pub values: Vec<f64>,
    pub sigma: Vec<f64>,
    pub correlation: Vec<Vec<f64>>,
    /// Σ ((model − measured)/σ)²; with no σ given, σ = 1.
    pub chi2: f64,
    pub dof: usize,
    /// χ² / dof. With no σ given the uncertainties are scaled by √(χ²/dof) (σ estimated from the scatter).
    pub reduced_chi2: f64,
    pub sigma_given: bool,
    /// Parameters that ended on a bound of their range (their uncertainty is then not meaningful).
    pub at_bound: Vec<bool>,
    pub fitted: Vec<f64>,
    pub starts_tried: usize,
    pub evaluations: usize,
    /// How the Jacobian was computed: "exact", or "finite differences" where any Jacobian of the fit was
    /// (by choice, beyond [`MAX_EXACT`] parameters, or at a critical angle).
    pub jacobian: &'static str,
}

/// The model values on the measured wavelengths: R or T (unpolarised), or ψ, Δ in degrees interleaved.
pub fn model(template: &Template, values: &[f64], wavelengths: &[f64], opt: &FitOptions) -> Result<Vec<f64>, FitError> {
    let stack = template.stack(values)?;
    let mut out = Vec::with_capacity(wavelengths.len() * opt.quantity.width());
    for &w in wavelengths {
        match opt.quantity {
            Quantity::R | Quantity::T => {
                let x = stack.evaluate(w, opt.angle_rad).map_err(|e| FitError::Model(e.to_string()))?;
                out.push(if opt.quantity == Quantity::R { x.r() } else { x.t() });
            }
            Quantity::PsiDelta => {
                let (psi, delta) = stack.ellipsometry(w, opt.angle_rad).map_err(|e| FitError::Model(e.to_string()))?;
                out.push(psi.to_degrees());
                out.push(delta.to_degrees());
            }
        }
    }
    Ok(out)
}

/// The derivatives of [`model`] with respect to the parameters, exact (forward-mode automatic
/// differentiation, [`iridis_thinfilm::jet`]): one row per model value (ψ, Δ in degrees), `K ≥` the number of
/// parameters (the extra columns are zero).
pub fn model_jacobian<const K: usize>(
    template: &Template,
    values: &[f64],
    wavelengths: &[f64],
    opt: &FitOptions,
) -> Result<Vec<[f64; K]>, FitError> {
    if values.len() > K {
        return Err(FitError::Model(format!("{} parameters need jets of width ≥ {0}", values.len())));
    }
    let stack = template.stack(values)?;
    let mut out = Vec::with_capacity(wavelengths.len() * opt.quantity.width());
    let model_err = |e: iridis_thinfilm::ThinFilmError| FitError::Model(e.to_string());
    for &w in wavelengths {
        let tan = template.tangent::<K>(values, w);
        match opt.quantity {
            Quantity::R | Quantity::T => {
                let x = stack.evaluate_jet(w, opt.angle_rad, &tan).map_err(model_err)?;
                out.push(if opt.quantity == Quantity::R { x.r() } else { x.t() }.gradient());
            }
            Quantity::PsiDelta => {
                let (psi, delta) = stack.ellipsometry_jet(w, opt.angle_rad, &tan).map_err(model_err)?;
                out.push(psi.gradient().map(f64::to_degrees));
                out.push(delta.gradient().map(f64::to_degrees));
            }
        }
    }
    Ok(out)
}

struct Problem<'a> {
    template: &'a Template,
    data: &'a Measured,
    opt: &'a FitOptions,
    x: Vec<f64>,
    evaluations: std::cell::Cell<usize>,
    /// Set when some Jacobian came from finite differences.
    used_fd: std::cell::Cell<bool>,
}

impl Problem<'_> {
    fn residuals_at(&self, x: &[f64]) -> Option<Vec<f64>> {
        self.evaluations.set(self.evaluations.get() + 1);
        let m = model(self.template, x, &self.data.wavelength_nm, self.opt).ok()?;
        let psi_delta = self.opt.quantity == Quantity::PsiDelta;
        Some(
            m.iter()
                .zip(&self.data.values)
                .enumerate()
                .map(|(i, (m, d))| {
                    // Δ is an angle: the residual is the difference on the circle, in (−180°, 180°].
                    let mut r = m - d;
                    if psi_delta && i % 2 == 1 {
                        r = (r + 180.0).rem_euclid(360.0) - 180.0;
                    }
                    r / self.data.sigma.as_ref().map_or(1.0, |s| s[i])
                })
                .collect(),
        )
    }

    fn jacobian_at(&self, x: &[f64]) -> Option<DMatrix<f64>> {
        if self.opt.derivatives == Derivatives::FiniteDifferences {
            return self.fd_jacobian(x);
        }
        match x.len() {
            1 => self.exact_jacobian::<1>(x),
            2 => self.exact_jacobian::<2>(x),
            3 => self.exact_jacobian::<3>(x),
            4 => self.exact_jacobian::<4>(x),
            5 | 6 => self.exact_jacobian::<6>(x),
            7 | 8 => self.exact_jacobian::<8>(x),
            9..=12 => self.exact_jacobian::<12>(x),
            13..=MAX_EXACT => self.exact_jacobian::<MAX_EXACT>(x),
            _ => self.fd_jacobian(x),
        }
    }

    /// The Jacobian of the weighted residuals from [`model_jacobian`].
    fn exact_jacobian<const K: usize>(&self, x: &[f64]) -> Option<DMatrix<f64>> {
        self.evaluations.set(self.evaluations.get() + 1);
        let rows = model_jacobian::<K>(self.template, x, &self.data.wavelength_nm, self.opt).ok()?;
        // Exactly at a layer's critical angle (cos θ = 0) the derivative with respect to its index is
        // infinite: there the finite differences of the (finite) spectrum stand in.
        if rows.iter().flatten().any(|v| !v.is_finite()) {
            return self.fd_jacobian(x);
        }
        let sigma = self.data.sigma.as_deref();
        Some(DMatrix::from_fn(rows.len(), x.len(), |i, k| rows[i][k] / sigma.map_or(1.0, |s| s[i])))
    }

    /// Central differences, one-sided at a bound; steps ~1e-6 of the parameter's scale.
    fn fd_jacobian(&self, x: &[f64]) -> Option<DMatrix<f64>> {
        self.used_fd.set(true);
        let n = self.data.values.len();
        let mut j = DMatrix::zeros(n, x.len());
        for (k, p) in self.template.params.iter().enumerate() {
            let h = 1e-6 * x[k].abs().max(1e-3 * (p.hi - p.lo)).max(1e-9);
            let (a, b) = ((x[k] - h).max(p.lo), (x[k] + h).min(p.hi));
            let mut xa = x.to_vec();
            let mut xb = x.to_vec();
            xa[k] = a;
            xb[k] = b;
            let (ra, rb) = (self.residuals_at(&xa)?, self.residuals_at(&xb)?);
            for i in 0..n {
                j[(i, k)] = (rb[i] - ra[i]) / (b - a);
            }
        }
        Some(j)
    }
}

impl LeastSquaresProblem<f64, Dyn, Dyn> for Problem<'_> {
    type ResidualStorage = Owned<f64, Dyn>;
    type JacobianStorage = Owned<f64, Dyn, Dyn>;
    type ParameterStorage = Owned<f64, Dyn>;

    /// Parameters are kept inside their ranges by projection.
    fn set_params(&mut self, x: &DVector<f64>) {
        for (k, p) in self.template.params.iter().enumerate() {
            self.x[k] = x[k].clamp(p.lo, p.hi);
        }
    }
    fn params(&self) -> DVector<f64> {
        DVector::from_vec(self.x.clone())
    }
    fn residuals(&self) -> Option<DVector<f64>> {
        self.residuals_at(&self.x).map(DVector::from_vec)
    }
    fn jacobian(&self) -> Option<DMatrix<f64>> {
        self.jacobian_at(&self.x)
    }
}

fn chi2(r: &[f64]) -> f64 {
    r.iter().map(|v| v * v).sum()
}

/// The most multi-start points a thickness range gets when `thicknesses` ranges are searched: about 4000
/// starts in all (`4000^(1/thicknesses)` each, at least 2).
pub fn max_grid_points(thicknesses: usize) -> usize {
    (4000f64.powf(1.0 / thicknesses.max(1) as f64)).floor().max(2.0) as usize
}

/// The multi-start points: a grid over every thickness range (other parameters at their start), the start
/// values included.
fn starts(template: &Template, opt: &FitOptions) -> Vec<Vec<f64>> {
    let thick = template.thickness_params();
    let mut out = vec![template.starts()];
    if thick.is_empty() || opt.grid == 1 {
        return out;
    }
    // Fringes repeat every λ/(2n) ≈ 100–200 nm of thickness: a point every ~10 nm lands within reach of the
    // right fringe order.
    let cap = max_grid_points(thick.len());
    let per: Vec<usize> = thick
        .iter()
        .map(|&i| {
            let p = &template.params[i];
            let auto = ((p.hi - p.lo) / 10.0).ceil() as usize + 1;
            (if opt.grid > 0 { opt.grid } else { auto.clamp(2, 64) }).min(cap).max(2)
        })
        .collect();
    let total: usize = per.iter().product();
    for mut idx in 0..total {
        let mut x = template.starts();
        for (t, &i) in thick.iter().enumerate() {
            let p = &template.params[i];
            let k = idx % per[t];
            idx /= per[t];
            x[i] = p.lo + (p.hi - p.lo) * k as f64 / (per[t] - 1) as f64;
        }
        out.push(x);
    }
    out
}

/// Fits the template's parameters to the measured data.
pub fn fit(template: &Template, data: &Measured, opt: &FitOptions) -> Result<FitResult, FitError> {
    let n = data.values.len();
    let np = template.params.len();
    if data.values.len() != data.wavelength_nm.len() * opt.quantity.width() {
        return Err(FitError::Data("the measured values do not match the quantity".into()));
    }
    if n <= np {
        return Err(FitError::Data(format!(
            "{n} measured values cannot determine {np} parameters (need more than {np})"
        )));
    }
    let mut problem = Problem {
        template,
        data,
        opt,
        x: template.starts(),
        evaluations: std::cell::Cell::new(0),
        used_fd: std::cell::Cell::new(false),
    };
    // Every material must have data over the measured wavelengths (the error names the one that does not),
    // and the model must evaluate at the start.
    let (lo, hi) =
        data.wavelength_nm.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &w| (a.min(w), b.max(w)));
    crate::data::check_coverage(&template.stack(&template.starts())?, lo, hi)?;
    model(template, &template.starts(), &data.wavelength_nm, opt)?;
    let candidates = starts(template, opt);
    let mut scored: Vec<(f64, Vec<f64>)> =
        candidates.iter().filter_map(|x| problem.residuals_at(x).map(|r| (chi2(&r), x.clone()))).collect();
    scored.sort_by(|a, b| a.0.total_cmp(&b.0));
    let lm = LevenbergMarquardt::new().with_ftol(1e-14).with_xtol(1e-14).with_gtol(1e-14).with_patience(200);
    let mut best: Option<(f64, Vec<f64>)> = None;
    for (_, x0) in scored.iter().take(opt.refine.max(1)) {
        problem.x = x0.clone();
        let (p, _report) = lm.minimize(problem);
        problem = p;
        if let Some(r) = problem.residuals_at(&problem.x) {
            let c = chi2(&r);
            if best.as_ref().is_none_or(|b| c < b.0) {
                best = Some((c, problem.x.clone()));
            }
        }
    }
    let (chi2v, x) = best.ok_or_else(|| FitError::Model("the model could not be evaluated at any start".into()))?;
    let j = problem.jacobian_at(&x).ok_or_else(|| FitError::Model("the model failed at the optimum".into()))?;
    let dof = n - np;
    let sigma_given = data.sigma.is_some();
    let scale = if sigma_given { 1.0 } else { chi2v / dof as f64 };
    // (JᵀJ)⁻¹ through the columns scaled to unit norm, JᵀJ = D C D with C a correlation-like matrix of unit
    // diagonal: its smallest eigenvalue says how nearly two parameters do the same thing, whatever their
    // units. Below 1e-12 (|correlation| > 1 − 5e-13) the covariance is rounding noise.
    let singular = || {
        FitError::Model(
            "the data do not determine the parameters (JᵀJ is singular): some parameter has no effect on the \
             spectrum, or two have the same effect; fix one of them"
                .into(),
        )
    };
    let norms: Vec<f64> = (0..np).map(|k| j.column(k).norm()).collect();
    if norms.iter().any(|v| !(v.is_finite() && *v > 0.0)) {
        return Err(singular());
    }
    let d_inv = DMatrix::from_diagonal(&DVector::from_iterator(np, norms.iter().map(|v| 1.0 / v)));
    let js = &j * &d_inv;
    let c = js.transpose() * &js;
    let eig = c.clone().symmetric_eigenvalues();
    if eig.min() < 1e-12 * eig.max() {
        return Err(singular());
    }
    // The covariance (JᵀWJ)⁻¹, times χ²/dof where σ is estimated from the scatter. The correlations are taken
    // before that scale, which they do not depend on: data the model meets exactly (χ² = 0, synthetic spectra)
    // have zero uncertainties, and their correlations were 0/0.
    let cov = &d_inv * c.try_inverse().ok_or_else(singular)? * &d_inv;
    let sd: Vec<f64> = (0..np).map(|k| cov[(k, k)].max(0.0).sqrt()).collect();
    let correlation = (0..np).map(|a| (0..np).map(|b| cov[(a, b)] / (sd[a] * sd[b])).collect()).collect();
    let sigma: Vec<f64> = sd.iter().map(|s| s * scale.sqrt()).collect();
    let at_bound = template
        .params
        .iter()
        .zip(&x)
        .map(|(p, v)| (v - p.lo).abs() <= 1e-9 * (p.hi - p.lo) || (p.hi - v).abs() <= 1e-9 * (p.hi - p.lo))
        .collect();
    let fitted = model(template, &x, &data.wavelength_nm, opt)?;
    Ok(FitResult {
        names: template.params.iter().map(|p| p.name.clone()).collect(),
        values: x,
        sigma,
        correlation,
        chi2: chi2v,
        dof,
        reduced_chi2: chi2v / dof as f64,
        sigma_given,
        at_bound,
        fitted,
        starts_tried: candidates.len(),
        evaluations: problem.evaluations.get(),
        jacobian: if problem.used_fd.get() { "finite differences" } else { "exact" },
    })
}
