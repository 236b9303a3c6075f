//! Extended light by Monte Carlo: area lights and the environment at a surface that is not a mirror, with
//! importance sampling of the lights (solid angle for spheres, area for disks and rectangles, luminance for the
//! environment map) and of the BRDF (cosine, GGX visible normals, the diffraction lobe from its table),
//! combined by multiple importance sampling (one sample of each technique per light, the power heuristic).
//! The BRDF's sample also carries the path on (the surface it meets is shaded in turn, its own lights
//! sampled), so glossy and diffuse inter-reflections converge as well.
//!
//! Every material is seen through `Surface`: `eval` returns `π f(ω_i, ω_o) cos θ_i`, the reflected radiance
//! per RU of directional light (what [`crate::material`] computes for lights), so the reflected radiance of a
//! radiance field `L` is `(1/π) ∫ eval(ω_i) L(ω_i) dω_i` and one sample of it is `eval · L / (π pdf)`.

use crate::geometry::Hit;
use crate::light::Rgb;
use crate::material::{relative_azimuth, Diffraction, Microfacet, ThinFilm};
use crate::math::*;
use crate::sampling::{cosine_hemisphere, frame, from_local, ggx_visible_normal, next, next2, power_heuristic};
use crate::scene::Scene;
pub use crate::scene::{Integration, Strategy};

/// A surface as extended light sees it: `π f cos θ_i`, and how to sample its lobe.
pub(crate) enum Surface<'a> {
    Lambert {
        n: V3,
        albedo: Rgb,
    },
    Microfacet {
        m: Microfacet,
        n: V3,
        albedo: Rgb,
        /// Probability of sampling the GGX lobe (else the cosine lobe).
        p_spec: f64,
    },
    FilmOverBase {
        film: &'a ThinFilm,
        base: Microfacet,
        n: V3,
        albedo: Rgb,
        offset: f64,
        p_spec: f64,
    },
    /// A rough film's diffuse lobe `π k_d cos θ_l` (its specular part is a mirror, traced by the caller).
    RoughDiffuse {
        film: &'a ThinFilm,
        n: V3,
        cos_o: f64,
        offset: f64,
    },
    Diffraction {
        df: &'a Diffraction,
        hit: Hit,
        /// The nanostructure's frame: `t`, `n × t`, `n`.
        t: V3,
        b: V3,
        tex: Rgb,
    },
}

/// Probability of choosing the GGX lobe: its share of uniform light (specular vs diffuse albedo, as the
/// environment's weights split it), kept within [0.1, 0.9] so that neither lobe goes unsampled.
fn spec_probability(spec: Rgb, diffuse: Rgb) -> f64 {
    let (s, d) = (spec.iter().fold(0.0f64, |a, &b| a.max(b)), diffuse.iter().fold(0.0f64, |a, &b| a.max(b)));
    if s + d <= 0.0 {
        return 0.5;
    }
    (s / (s + d)).clamp(0.1, 0.9)
}

/// Probability of sampling a diffraction material's lobe from its table (else the cosine lobe, which covers the
/// texture terms of Algorithm 4 and every direction the table's distribution leaves out).
pub const DIFFRACTION_LOBE_PROBABILITY: f64 = 0.75;

impl<'a> Surface<'a> {
    pub fn microfacet(m: Microfacet, n: V3, albedo: Rgb, cos_o: f64) -> Self {
        let (spec, diffuse) = m.env_weights(cos_o, albedo);
        Surface::Microfacet { m, n, albedo, p_spec: spec_probability(spec, diffuse) }
    }

    pub fn film_over_base(film: &'a ThinFilm, base: Microfacet, n: V3, albedo: Rgb, offset: f64, cos_o: f64) -> Self {
        let r = film.colors(cos_o, offset).0.to_linear_srgb();
        let diffuse = [0, 1, 2].map(|k| (1.0 - r[k]) * albedo[k] * (1.0 - base.metallic));
        let spec = [0, 1, 2].map(|k| r[k].max(base.metallic));
        Surface::FilmOverBase { film, base, n, albedo, offset, p_spec: spec_probability(spec, diffuse) }
    }

    fn normal(&self) -> V3 {
        match self {
            Surface::Lambert { n, .. }
            | Surface::Microfacet { n, .. }
            | Surface::FilmOverBase { n, .. }
            | Surface::RoughDiffuse { n, .. } => *n,
            Surface::Diffraction { hit, .. } => hit.n,
        }
    }

    /// `π f(ω_i, ω_o) cos θ_i` per channel.
    pub fn eval(&self, wi: V3, wo: V3) -> Rgb {
        match self {
            Surface::Lambert { n, albedo } => mul(*albedo, dot(*n, wi).max(0.0)),
            Surface::Microfacet { m, n, albedo, .. } => m.reflect(*n, wi, wo, *albedo),
            Surface::FilmOverBase { film, base, n, albedo, offset, .. } => {
                let f = film.factor;
                let mut out = mul(film.over_base_light(base, *albedo, *n, wi, wo, *offset), f);
                if f < 1.0 {
                    out = add(out, mul(base.reflect(*n, wi, wo, *albedo), 1.0 - f));
                }
                out
            }
            Surface::RoughDiffuse { film, n, cos_o, offset } => {
                let cos_l = dot(*n, wi);
                if cos_l <= 0.0 || *cos_o <= 0.0 {
                    return [0.0; 3];
                }
                let dirs = [(cos_l, relative_azimuth(*n, wi, wo))];
                match film.rough_colors_tabulated(*cos_o, *offset, &dirs) {
                    Some((_, d)) => mul(d[0].to_linear_srgb(), cos_l * film.factor),
                    None => [0.0; 3],
                }
            }
            Surface::Diffraction { df, hit, t, tex, .. } => df.shade_light(hit, *t, wi, wo, [1.0; 3], *tex),
        }
    }

    /// A direction drawn from the lobe (`u[0]` picks the technique of a mixture); `None` where the draw fails.
    pub fn sample(&self, wo: V3, u: [f64; 3]) -> Option<V3> {
        let n = self.normal();
        let glossy = |m: &Microfacet, p_spec: f64| -> Option<V3> {
            if u[0] >= p_spec {
                return Some(cosine_hemisphere(n, [u[1], u[2]]));
            }
            let (t, b) = frame(n);
            let lo = [dot(wo, t), dot(wo, b), dot(wo, n)];
            if lo[2] <= 0.0 {
                return None;
            }
            let alpha = crate::energy::alpha2(m.roughness).sqrt();
            let h = ggx_visible_normal(lo, alpha, [u[1], u[2]]);
            let li = sub(mul(h, 2.0 * dot(lo, h)), lo);
            (li[2] > 0.0).then(|| normalize(from_local(t, b, n, li)))
        };
        match self {
            Surface::Lambert { .. } | Surface::RoughDiffuse { .. } => Some(cosine_hemisphere(n, [u[1], u[2]])),
            Surface::Microfacet { m, p_spec, .. } => glossy(m, *p_spec),
            Surface::FilmOverBase { base, p_spec, .. } => glossy(base, *p_spec),
            Surface::Diffraction { df, t, b, .. } => match df.lobe_sampler() {
                Some(s) if u[0] < DIFFRACTION_LOBE_PROBABILITY => {
                    let lo = [dot(wo, *t), dot(wo, *b), dot(wo, n)];
                    let (li, _) = s.sample(lo, [u[1], u[2]])?;
                    Some(normalize(from_local(*t, *b, n, li)))
                }
                _ => Some(cosine_hemisphere(n, [u[1], u[2]])),
            },
        }
    }

    /// The solid-angle pdf of [`Surface::sample`] for `wi`.
    pub fn pdf(&self, wi: V3, wo: V3) -> f64 {
        let n = self.normal();
        let ci = dot(n, wi);
        if ci <= 0.0 {
            return 0.0;
        }
        let cosine = ci / std::f64::consts::PI;
        let glossy = |m: &Microfacet, p_spec: f64| -> f64 {
            let co = dot(n, wo);
            if co <= 0.0 {
                return (1.0 - p_spec) * cosine;
            }
            let a2 = crate::energy::alpha2(m.roughness);
            let h = normalize(add(wi, wo));
            let vndf = crate::energy::smith_g1(a2, co) * crate::energy::ggx_d(a2, dot(n, h).max(0.0)) / (4.0 * co);
            p_spec * vndf + (1.0 - p_spec) * cosine
        };
        match self {
            Surface::Lambert { .. } | Surface::RoughDiffuse { .. } => cosine,
            Surface::Microfacet { m, p_spec, .. } => glossy(m, *p_spec),
            Surface::FilmOverBase { base, p_spec, .. } => glossy(base, *p_spec),
            Surface::Diffraction { df, t, b, .. } => match df.lobe_sampler() {
                Some(s) => {
                    let local = |v: V3| [dot(v, *t), dot(v, *b), dot(v, n)];
                    let p = DIFFRACTION_LOBE_PROBABILITY;
                    p * s.pdf(local(wo), local(wi)) + (1.0 - p) * cosine
                }
                None => cosine,
            },
        }
    }
}

fn black(c: Rgb) -> bool {
    c.iter().all(|&x| x <= 0.0)
}

impl Scene {
    /// Whether extended light is integrated by Monte Carlo.
    pub fn monte_carlo(&self) -> bool {
        matches!(self.integration, Integration::MonteCarlo(_))
    }

    /// The weights of a light sample whose pdf is `light` where the BRDF's is `brdf`, and of a BRDF sample
    /// the other way round.
    fn light_weight(&self, light: f64, brdf: f64) -> f64 {
        match self.integration {
            Integration::MonteCarlo(Strategy::Light) => 1.0,
            Integration::MonteCarlo(Strategy::Brdf) => 0.0,
            _ => power_heuristic(light, brdf),
        }
    }

    fn brdf_weight(&self, brdf: f64, light: f64) -> f64 {
        match self.integration {
            Integration::MonteCarlo(Strategy::Light) if light > 0.0 => 0.0,
            Integration::MonteCarlo(Strategy::Light) | Integration::MonteCarlo(Strategy::Brdf) => 1.0,
            _ => power_heuristic(brdf, light),
        }
    }

    /// The nearest area light along a ray before `t_max`: (distance, index). Camera rays see the visible ones.
    pub fn hit_area_light(&self, o: V3, d: V3, t_max: f64, camera: bool) -> Option<(f64, usize)> {
        self.hit_area_light_but(o, d, t_max, camera, usize::MAX)
    }

    /// [`Scene::hit_area_light`] ignoring light `skip`.
    fn hit_area_light_but(&self, o: V3, d: V3, t_max: f64, camera: bool, skip: usize) -> Option<(f64, usize)> {
        let mut best = None;
        let mut t_max = t_max;
        for (k, l) in self.area_lights.iter().enumerate() {
            if (camera && !l.visible) || k == skip {
                continue;
            }
            if let Some(t) = l.shape.intersect(o, d, t_max) {
                t_max = t;
                best = Some((t, k));
            }
        }
        best
    }

    /// The environment's solid-angle pdf of its importance sampler (0 without one).
    fn env_pdf(&self, d: V3) -> f64 {
        self.env_sampler.as_ref().map_or(0.0, |s| s.pdf(d))
    }

    /// Whether the segment from `o` along `wi` of length `dist` is blocked by a surface or by an area light
    /// other than `skip`, the one it goes to (lights hide what lies behind them, as the rays that meet them see).
    fn blocked(&self, o: V3, wi: V3, dist: f64, skip: usize) -> bool {
        self.hit_area_light_but(o, wi, dist, false, skip).is_some() || self.occluded(o, wi, dist)
    }

    /// The reflected radiance of the area lights, the environment and the rest of the scene (along the BRDF's
    /// sample) at a hit whose surface is `s`, seen from `wo` (Monte Carlo). One sample of each light,
    /// one of the environment, one of the BRDF; weighted by the power heuristic.
    pub(crate) fn extended_light(&self, h: &Hit, s: &Surface, wo: V3, depth: u32, weight: f64) -> Rgb {
        let o = add(h.p, mul(h.ng, crate::geometry::eps(h)));
        let inv_pi = 1.0 / std::f64::consts::PI;
        let mut out = [0.0; 3];
        for (k, l) in self.area_lights.iter().enumerate() {
            let Some(x) = l.shape.sample(h.p, next2()) else { continue };
            if dot(x.wi, h.ng) <= 0.0 {
                continue;
            }
            let f = s.eval(x.wi, wo);
            if black(f) || self.blocked(o, x.wi, x.dist * (1.0 - 1e-7), k) {
                continue;
            }
            let w = self.light_weight(x.pdf, s.pdf(x.wi, wo));
            out = add(out, mul(hadamard(f, l.radiance), w * inv_pi / x.pdf));
        }
        if let Some(es) = &self.env_sampler {
            let (wi, p) = es.sample(next2());
            if dot(wi, h.ng) > 0.0 {
                let f = s.eval(wi, wo);
                if !black(f) && !self.blocked(o, wi, f64::INFINITY, usize::MAX) {
                    let w = self.light_weight(p, s.pdf(wi, wo));
                    out = add(out, mul(hadamard(f, self.environment.radiance(wi)), w * inv_pi / p));
                }
            }
        }
        if let Some(wi) = s.sample(wo, [next(), next(), next()]) {
            if dot(wi, h.ng) > 0.0 {
                let p = s.pdf(wi, wo);
                let f = s.eval(wi, wo);
                if p > 0.0 && !black(f) {
                    let thr = mul(f, inv_pi / p);
                    let w = weight * thr.iter().fold(0.0f64, |a, &b| a.max(b));
                    out = add(out, hadamard(thr, self.sampled_radiance(h.p, o, wi, p, depth + 1, w)));
                }
            }
        }
        out
    }

    /// Radiance along a direction the BRDF sampled at `p` (pdf `pdf`), the ray leaving from `o`: an area light
    /// or the environment it meets, weighted against their own sampling; a surface, shaded in turn. Past
    /// `max_depth`, or when it can change the pixel by less than 1/500, the ray takes the environment's
    /// (weighted) radiance, as the renderer's other rays do.
    fn sampled_radiance(&self, p: V3, o: V3, d: V3, pdf: f64, depth: u32, weight: f64) -> Rgb {
        let env = || mul(self.environment.radiance(d), self.brdf_weight(pdf, self.env_pdf(d)));
        if depth > self.output.max_depth || weight < 2e-3 {
            return env();
        }
        let hit = self.intersect(o, d, f64::INFINITY);
        let t_surface = hit.as_ref().map_or(f64::INFINITY, |h| h.t);
        if let Some((_, k)) = self.hit_area_light(o, d, t_surface, false) {
            let l = &self.area_lights[k];
            return mul(l.radiance, self.brdf_weight(pdf, l.shape.pdf(p, d)));
        }
        match hit {
            Some(h) => self.shade(&h, d, depth, weight),
            None => env(),
        }
    }
}
