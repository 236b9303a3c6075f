//! Materials: diffraction from a nanostructure (lookup tables of `iridis precompute`, an orientation field,
//! the thesis' texture blending, Algorithm 4), thin films (Sussenbach's smooth illumination model, eq. 3.14,
//! with spatially varying thickness, eq. 4.3–4.4; on a rough substrate, the LSRS model, eq. 3.15–3.20),
//! Lambert, and a GGX microfacet base.

use std::sync::Arc;

use iridis_color::{Illuminant, Observer, Xyz};
use iridis_diffraction::Evaluator;
use iridis_thinfilm::color::FilmColorimeter;
use iridis_thinfilm::htsg::Htsg;
use iridis_thinfilm::rough::RoughStack;
use iridis_thinfilm::{Stack, ThinFilmError};

use crate::energy;
use crate::error::RenderError;
use crate::geometry::Hit;
use crate::light::Rgb;
use crate::math::*;
use crate::texture::Texture;

/// A colour: a constant or a colour texture.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ColorSource {
    Const(Rgb),
    Texture(usize),
}

impl ColorSource {
    pub fn at(&self, uv: [f64; 2], textures: &[Texture]) -> Rgb {
        match *self {
            ColorSource::Const(c) => c,
            ColorSource::Texture(i) => textures[i].sample(uv),
        }
    }
}

/// Where the nanostructure's x axis lies on the surface (PHYSICS.md: the tangent `t` is `+x`, `b = n × t`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum OrientRule {
    /// The mesh's tangent attribute (glTF TANGENT or MikkTSpace from the UVs; `∂P/∂u` on spheres and planes).
    Tangent,
    /// Along the body: the snake's spine direction; a sphere's meridian (north → south); a plane's tangent.
    Along,
    /// A fixed world direction projected onto the surface.
    Direction(V3),
    /// A vector texture in tangent space: `x = 2R − 1` along the tangent, `y = 2G − 1` along the bitangent.
    Texture(usize),
}

/// An orientation field: a rule and an extra rotation about the normal.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Orientation {
    pub rule: OrientRule,
    pub angle: f64,
}

impl Orientation {
    /// The unit tangent `t` (the nanostructure's `+x`) at a hit, perpendicular to the shading normal.
    pub fn tangent(&self, hit: &Hit, textures: &[Texture]) -> V3 {
        let n = hit.n;
        let base = hit.tangent.unwrap_or_else(|| any_perpendicular(n));
        let t = match self.rule {
            OrientRule::Tangent => Some(base),
            OrientRule::Along => hit.along.or(Some(base)),
            OrientRule::Direction(d) => orthogonalize(d, n),
            OrientRule::Texture(i) => {
                let c = textures[i].sample(hit.uv);
                let (x, y) = (2.0 * c[0] - 1.0, 2.0 * c[1] - 1.0);
                let b = cross(n, base);
                try_normalize(add(mul(base, x), mul(b, y)))
            }
        }
        .unwrap_or(base);
        if self.angle != 0.0 {
            normalize(rotate_about(t, n, self.angle))
        } else {
            t
        }
    }
}

/// The diffraction material.
#[derive(Clone)]
pub struct Diffraction {
    /// Colour (XYZ) for local directions `(ω_i, ω_r)` — the same evaluator `iridis brdf-map` uses.
    pub evaluator: Arc<dyn Evaluator>,
    pub orientation: Orientation,
    /// Multiplier of the diffraction colour (RU): 1500 shows the table as `iridis brdf-map --exposure 1500`
    /// does at scene exposure 1, while texture and diffuse terms keep the scene's brightness.
    pub scale_ru: f64,
    /// `w_diffuse` of Algorithm 4.
    pub w_diffuse: f64,
    /// `c_texture` of Algorithm 4 (lit as a Lambertian surface).
    pub texture: ColorSource,
    /// Ambient term: this fraction of the texture colour is added whatever the lights do.
    pub ambient: f64,
    /// Index for the Schlick Fresnel weight `α = |F|` of Algorithm 4.
    pub fresnel_n: f64,
    pub description: String,
    /// How the diffraction and the texture are combined.
    pub blend: Blend,
    /// The lobe's sampler and prefiltered table for extended light, made on first use from a lookup
    /// evaluator (`Default::default()` for a new material).
    pub extended: ExtendedLight,
}

/// How a diffraction material combines its lobe with its texture.
#[derive(Debug, Clone)]
pub enum Blend {
    /// The thesis' Algorithm 4: `(1 − w_d)·c_diffraction + (1 − α)·c_texture + w_d·c_texture`, `α` Schlick's
    /// Fresnel at the half vector. An artist's model: `scale_ru` is an exposure and the texture does not give up
    /// the light the lobe reflects, so it does not conserve energy.
    Algorithm4,
    /// Energy-conserving (needs a radiometric table): `(1 − w_d)·(c_diffraction + c_texture·s) + w_d·c_texture`,
    /// with `c_diffraction` the radiometric BRDF times `R₀` and `s = (1 − A(ω_i))(1 − A(ω_o))/(1 − A_avg)` the
    /// share the lobe leaves ([`crate::lobe_albedo::LobeAlbedo`]): a white texture passes the white furnace, and
    /// the BRDF stays reciprocal.
    Energy(Arc<crate::lobe_albedo::LobeAlbedo>),
}

impl Blend {
    pub fn name(&self) -> &'static str {
        match self {
            Blend::Algorithm4 => "algorithm4",
            Blend::Energy(_) => "energy",
        }
    }
}

/// Per diffraction material, what extended light needs of its lookup table ([`crate::lobe`]): made on first
/// use, `None` for evaluators that are not lookup tables.
#[derive(Debug, Clone, Default)]
pub struct ExtendedLight {
    sampler: std::sync::OnceLock<Option<Arc<crate::lobe::LobeSampler>>>,
    prefiltered: std::sync::OnceLock<Option<Arc<crate::lobe::Prefiltered>>>,
}

impl std::fmt::Debug for Diffraction {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Diffraction")
            .field("table", &self.description)
            .field("orientation", &self.orientation)
            .field("scale_ru", &self.scale_ru)
            .field("w_diffuse", &self.w_diffuse)
            .finish()
    }
}

/// Schlick's Fresnel `F_0 + (1 − F_0)(1 − cos θ)^5`, `F_0 = ((n − 1)/(n + 1))²` (thesis App. D).
pub fn schlick(n: f64, cos: f64) -> f64 {
    let f0 = ((n - 1.0) / (n + 1.0)).powi(2);
    f0 + (1.0 - f0) * (1.0 - cos.clamp(0.0, 1.0)).powi(5)
}

impl Diffraction {
    /// The lobe's importance sampler ([`crate::lobe::LobeSampler`]); `None` when the evaluator is not a lookup
    /// table or the table is black.
    pub fn lobe_sampler(&self) -> Option<&crate::lobe::LobeSampler> {
        self.extended
            .sampler
            .get_or_init(|| {
                let l = self.evaluator.as_lookup()?;
                let s = crate::lobe::LobeSampler::new(l);
                s.levels.iter().any(Option::is_some).then(|| Arc::new(s))
            })
            .as_deref()
    }

    /// The table's summed-area tables ([`crate::lobe::Prefiltered`]); `None` for other evaluators.
    pub fn prefiltered(&self) -> Option<&crate::lobe::Prefiltered> {
        self.extended
            .prefiltered
            .get_or_init(|| self.evaluator.as_lookup().map(|l| Arc::new(crate::lobe::Prefiltered::new(l))))
            .as_deref()
    }

    /// The table's colour for local directions, averaged over a light of solid angle `omega` around `li`
    /// (the prefiltered area light of [`crate::lobe::Prefiltered`]); the point value for `omega = 0` or an
    /// evaluator that is not a lookup table.
    pub fn xyz_filtered(&self, li: V3, lo: V3, omega: f64) -> Xyz {
        match (omega > 0.0, self.evaluator.as_lookup(), self.prefiltered()) {
            (true, Some(l), Some(p)) if li[2] > 0.0 && lo[2] > 0.0 => {
                let c = l.shading.factor(500.0, li, lo);
                let m = p.mean(l, li, lo, omega);
                Xyz::new(c * m[0], c * m[1], c * m[2])
            }
            _ => self.evaluator.xyz(li, lo),
        }
    }

    /// Algorithm 4 for one light: `(1 − w_d)·c_diffraction + (1 − α)·c_texture + w_d·c_texture`, `α = min(|F|, 1)`,
    /// where `c_diffraction` is the table's colour for the light and view directions in the local frame
    /// `(t, n × t, n)` times the irradiance and `scale_ru`, and `c_texture` is the texture colour lit as a
    /// Lambertian surface (`cos θ_i` × irradiance).
    pub fn shade_light(&self, hit: &Hit, t: V3, wi: V3, wo: V3, e: Rgb, tex: Rgb) -> Rgb {
        self.shade_light_filtered(hit, t, wi, wo, e, tex, 0.0)
    }

    /// [`Diffraction::shade_light`] for a light of solid angle `omega` (> 0: an area light or a cell of the
    /// environment seen as one light), whose diffraction colour is the lobe averaged over the light
    /// ([`Diffraction::xyz_filtered`]).
    #[allow(clippy::too_many_arguments)]
    pub fn shade_light_filtered(&self, hit: &Hit, t: V3, wi: V3, wo: V3, e: Rgb, tex: Rgb, omega: f64) -> Rgb {
        let (li, lo) = (local_frame(hit.n, t, wi), local_frame(hit.n, t, wo));
        if li[2] <= 0.0 || lo[2] <= 0.0 {
            return [0.0; 3];
        }
        let c_diff = self.lobe(li, lo, e, omega);
        let c_tex = mul(hadamard(tex, e), li[2]);
        let rest = match &self.blend {
            Blend::Algorithm4 => {
                let h = normalize(add(wi, wo));
                let alpha = schlick(self.fresnel_n, dot(wi, h)).abs().min(1.0);
                mul(c_tex, 1.0 - alpha)
            }
            Blend::Energy(a) => hadamard(c_tex, a.diffuse_share(li, lo)),
        };
        add(add(mul(c_diff, 1.0 - self.w_diffuse), rest), mul(c_tex, self.w_diffuse))
    }

    /// The light's diffraction alone, `scale_ru · XYZ(ω_i, ω_o) · e` (averaged over a light of solid angle
    /// `omega`), for local directions above the surface.
    fn lobe(&self, li: V3, lo: V3, e: Rgb, omega: f64) -> Rgb {
        hadamard(self.xyz_filtered(li, lo, omega).to_linear_srgb(), mul(e, self.scale_ru))
    }

    /// One light of the environment's quadrature ([`crate::Scene::environment_lights`], a cell of solid angle
    /// `omega`): all of Algorithm 4; under the energy blend only the lobe, since the texture takes the
    /// environment through [`Diffraction::environment_diffuse`].
    #[allow(clippy::too_many_arguments)]
    pub fn shade_environment_light(&self, hit: &Hit, t: V3, wi: V3, wo: V3, e: Rgb, tex: Rgb, omega: f64) -> Rgb {
        match &self.blend {
            Blend::Algorithm4 => self.shade_light_filtered(hit, t, wi, wo, e, tex, omega),
            Blend::Energy(_) => {
                let (li, lo) = (local_frame(hit.n, t, wi), local_frame(hit.n, t, wo));
                if li[2] <= 0.0 || lo[2] <= 0.0 {
                    return [0.0; 3];
                }
                mul(self.lobe(li, lo, e, omega), 1.0 - self.w_diffuse)
            }
        }
    }

    /// Under the energy blend, the texture's share of the environment: `c_texture ⊙ (1 − (1 − w_d) A(ω_o)) ⊙ E(n)/π`
    /// (exact for a uniform environment, as the microfacet's diffuse share); nothing under Algorithm 4, whose
    /// texture takes the environment's lights one by one.
    pub fn environment_diffuse(&self, hit: &Hit, t: V3, wo: V3, tex: Rgb, irradiance: Rgb) -> Rgb {
        match &self.blend {
            Blend::Algorithm4 => [0.0; 3],
            Blend::Energy(a) => {
                let lo = local_frame(hit.n, t, wo);
                if lo[2] <= 0.0 {
                    return [0.0; 3];
                }
                let share = a.environment_share(lo);
                let w = self.w_diffuse;
                hadamard(hadamard(tex, irradiance), share.map(|s| (1.0 - w) * s + w))
            }
        }
    }
}

/// `v` in the frame `(t, n × t, n)`.
fn local_frame(n: V3, t: V3, v: V3) -> V3 {
    let b = cross(n, t);
    [dot(v, t), dot(v, b), dot(v, n)]
}

/// Spatially varying thickness (Sussenbach sec. 4.2): every layer gets `d_rel · (2α − 1)` added, with `α` from
/// a grey texture or generated noise (eq. 4.3–4.4).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Svt {
    pub texture: usize,
    pub d_rel_nm: f64,
}

/// A thin-film material: the composite reflectance `k_r` and transmittance `k_t` of a stack weight the light
/// reflected and transmitted along the ray, `I_e = k_r I_r + k_t I_t` (Sussenbach eq. 3.14). On a rough
/// substrate (`rough`), eq. 3.20: `I_e = k_r I_r + Σ_m k_d cos θ_l L_m`, the composite specular reflectance
/// weighting the mirror ray and the composite diffuse BRDF lit by the lights.
#[derive(Debug, Clone)]
pub struct ThinFilm {
    pub stack: Stack,
    pub svt: Option<Svt>,
    /// Trace the transmitted ray too (bubbles); off for films on opaque bases.
    pub transmission: bool,
    /// A base material under the film (glTF iridescence over its base, oil over asphalt): lit by the lights
    /// with the share of light the film does not reflect, `1 − Y(k_r)`.
    pub base: Option<Microfacet>,
    /// glTF `iridescenceFactor`: the film's reflection is scaled by it and the base shows through `1 − factor`.
    pub factor: f64,
    /// The same film over the metal of a metallic `base` (glTF: its substrate is the metal, whose index comes
    /// from the base colour as `F_0`); the specular of the base's metallic part. `None`: the base is dielectric.
    pub metal_stack: Option<Stack>,
    /// A rough substrate: the bottom interface (last layer | substrate) has rms height σ and correlation
    /// length τ, and the film follows Hirayama's LSRS model with the HTSG BRDF (Sussenbach sec. 3.2,
    /// eq. 3.15–3.20; `iridis_thinfilm::rough`). Set it with [`ThinFilm::set_rough`], which checks the model's
    /// validity over 380–780 nm. `None`: the smooth model.
    pub rough: Option<Htsg>,
    colorimeter: FilmColorimeter,
    invariant: bool,
    /// A rough film's diffuse directional albedo over view angle and SVT offset, made on first use
    /// ([`ThinFilm::rough_env_diffuse`]).
    rough_albedo: std::sync::OnceLock<RoughAlbedo>,
    /// A rough film's colour tables (`k_r` and `π k_d` over the view, light, azimuth and SVT offset), made on
    /// first use ([`ThinFilm::rough_table`]) for the CPU renderer and the GPU alike; the error where they cannot
    /// be made.
    rough_table: std::sync::OnceLock<Result<iridis_thinfilm::rough_table::RoughColorTable, ThinFilmError>>,
}

/// The diffuse directional albedo `∫ k_d cos θ dω` of a rough film as XYZ, on a grid of `cos θ_v` (rows) and
/// SVT offsets (columns), bilinear in between.
#[derive(Debug, Clone)]
struct RoughAlbedo {
    cos: Vec<f64>,
    offsets: Vec<f64>,
    xyz: Vec<Xyz>,
}

/// `cos θ_v` nodes of [`RoughAlbedo`] (0.02 to 1, uniform), and the midpoint cells per hemisphere axis of each
/// albedo integral: the table's values are within 0.1 % of a 60-step integral (render_cli's rough plane).
const ROUGH_ALBEDO_COS: usize = 12;
const ROUGH_ALBEDO_STEPS: usize = 16;

impl ThinFilm {
    /// Checks that the stack covers 380–780 nm and sets up the colour integral (D65, CIE 1931, 5 nm — the
    /// defaults of `iridis thinfilm color`).
    pub fn new(stack: Stack, svt: Option<Svt>, transmission: bool) -> Result<Self, RenderError> {
        let grid = iridis_color::spectrum::uniform_grid(380.0, 780.0, 5.0)
            .map_err(|e| RenderError::Input(format!("wavelength grid: {e}")))?;
        // Every wavelength of the colour integral, at both ends of the SVT thickness range: a stack that
        // cannot be evaluated is refused here, never rendered as R = T = 0 (a silently black film).
        let offsets = match svt {
            Some(s) => vec![-s.d_rel_nm, 0.0, s.d_rel_nm],
            None => vec![0.0],
        };
        for &l in &grid {
            for &o in &offsets {
                stack.evaluate_offset(l, 0.0, o).map_err(|e| {
                    RenderError::Input(format!("thin-film stack {stack}: cannot be evaluated at {l} nm ({e})"))
                })?;
            }
        }
        let invariant = stack.is_wavelength_invariant();
        Ok(Self {
            stack,
            svt,
            transmission,
            base: None,
            factor: 1.0,
            metal_stack: None,
            rough: None,
            colorimeter: FilmColorimeter::new(&grid, Illuminant::D65, Observer::Cie1931),
            invariant,
            rough_albedo: std::sync::OnceLock::new(),
            rough_table: std::sync::OnceLock::new(),
        })
    }

    /// The table behind [`ThinFilm::rough_env_diffuse`] (made on first use): the `cos θ_v` nodes (uniform),
    /// the SVT offset nodes (nm, uniform; one without SVT) and the XYZ at `[cos][offset]`, between which it
    /// interpolates bilinearly, clamped to the nodes. `None` for a smooth film. The GPU uploads it as it is.
    pub fn rough_env_table(&self) -> Option<(&[f64], &[f64], &[Xyz])> {
        let t = self.rough_albedo()?;
        Some((&t.cos, &t.offsets, &t.xyz))
    }

    fn rough_albedo(&self) -> Option<&RoughAlbedo> {
        let htsg = self.rough?;
        Some(self.rough_albedo.get_or_init(|| {
            use rayon::prelude::*;
            let cos: Vec<f64> =
                (0..ROUGH_ALBEDO_COS).map(|k| 0.02 + 0.98 * k as f64 / (ROUGH_ALBEDO_COS - 1) as f64).collect();
            let offsets = match self.svt {
                Some(s) => (-2..=2).map(|k| s.d_rel_nm * k as f64 / 2.0).collect(),
                None => vec![0.0],
            };
            let grid = self.colorimeter.wavelengths_nm();
            let xyz = cos
                .iter()
                .flat_map(|&c| offsets.iter().map(move |&o| (c, o)))
                .collect::<Vec<_>>()
                .par_iter()
                .map(|&(c, o)| {
                    let mut stack = self.stack.clone();
                    for l in &mut stack.layers {
                        l.thickness_nm = (l.thickness_nm + o).max(0.0);
                    }
                    let rough = RoughStack::new(stack, htsg);
                    let d: Vec<f64> = grid
                        .iter()
                        .map(|&l| rough.albedo(l, c.acos(), ROUGH_ALBEDO_STEPS).map_or(0.0, |a| a.diffuse))
                        .collect();
                    self.colorimeter.from_spectra(&d, &d).reflected
                })
                .collect();
            RoughAlbedo { cos, offsets, xyz }
        }))
    }

    /// A rough film's diffuse light from the environment per unit irradiance `E(n)/π`: its diffuse directional
    /// albedo `∫ k_d(ω, ω_v) cos θ dω` (by reciprocity the diffuse fraction [`RoughStack::albedo`] returns for
    /// light from `ω_v`) as XYZ — exact for a uniform environment, and the same split as the microfacet's
    /// diffuse lobe under the irradiance map elsewhere. Made once per material over 12 view angles × the SVT
    /// range, so that a pixel costs a table lookup instead of a diffuse evaluation per environment direction.
    /// `None` for a smooth film.
    pub fn rough_env_diffuse(&self, cos_view: f64, offset_nm: f64) -> Option<Xyz> {
        let t = self.rough_albedo()?;
        // Bilinear in (cos θ_v, offset), clamped to the table.
        let at = |v: f64, nodes: &[f64]| -> (usize, usize, f64) {
            if nodes.len() == 1 || v <= nodes[0] {
                return (0, 0, 0.0);
            }
            let i = nodes.partition_point(|&x| x <= v).min(nodes.len() - 1);
            let (a, b) = (nodes[i - 1], nodes[i]);
            (i - 1, i, ((v - a) / (b - a)).clamp(0.0, 1.0))
        };
        let (c0, c1, fc) = at(cos_view, &t.cos);
        let (o0, o1, fo) = at(offset_nm, &t.offsets);
        let w = t.offsets.len();
        let g = |c: usize, o: usize| t.xyz[c * w + o].to_array();
        let lerp = |a: [f64; 3], b: [f64; 3], f: f64| [0, 1, 2].map(|k| a[k] + (b[k] - a[k]) * f);
        let v = lerp(lerp(g(c0, o0), g(c0, o1), fo), lerp(g(c1, o0), g(c1, o1), fo), fc);
        Some(Xyz::new(v[0], v[1], v[2]))
    }

    /// The SVT thickness offset (nm) at a hit.
    pub fn offset_nm(&self, uv: [f64; 2], textures: &[Texture]) -> f64 {
        match self.svt {
            Some(s) => iridis_thinfilm::stack::svt_offset(s.d_rel_nm, textures[s.texture].sample(uv)[0]),
            None => 0.0,
        }
    }

    /// Reflected and transmitted film colour (XYZ under D65, normalised so `R = 1` gives `Y = 1`) at the
    /// cosine of the angle of incidence and a thickness offset: exactly `iridis thinfilm color` for that stack.
    pub fn colors(&self, cos_theta: f64, offset_nm: f64) -> (Xyz, Xyz) {
        let angle = cos_theta.clamp(0.0, 1.0).acos();
        let grid = self.colorimeter.wavelengths_nm();
        let mut r = Vec::with_capacity(grid.len());
        let mut t = Vec::with_capacity(grid.len());
        let prepared = if self.invariant { self.stack.prepare(angle).ok() } else { None };
        for &l in grid {
            let x = match &prepared {
                Some(p) => p.evaluate_offset(l, offset_nm),
                None => self.stack.evaluate_offset(l, angle, offset_nm),
            };
            match x {
                Ok(x) => {
                    r.push(x.r());
                    t.push(x.t());
                }
                Err(_) => {
                    r.push(0.0);
                    t.push(0.0);
                }
            }
        }
        let c = self.colorimeter.from_spectra(&r, &t);
        (c.reflected, c.transmitted)
    }

    /// `π f cos θ_i` of the film over its base for light from `wi` (glTF `KHR_materials_iridescence`: the film's
    /// reflectance `R(v·h)` replaces the base's specular Fresnel in its GGX lobe, the base's diffuse takes
    /// `1 − R(v·h)` per channel, a metallic base mixes in the film over the metal), without
    /// `iridescenceFactor`: the caller mixes it with the base alone. `albedo` is the base colour at the hit.
    pub fn over_base_light(&self, base: &Microfacet, albedo: Rgb, n: V3, wi: V3, wo: V3, offset_nm: f64) -> Rgb {
        let ci = dot(n, wi);
        if ci <= 0.0 || dot(n, wo) <= 0.0 {
            return [0.0; 3];
        }
        let m = base.metallic;
        let vh = dot(wi, normalize(add(wi, wo))).clamp(0.0, 1.0);
        let d = self.colors(vh, offset_nm).0.to_linear_srgb();
        let metal = self.metal_color(vh, offset_nm).map(|x| x.to_linear_srgb()).unwrap_or(d);
        let spec = base.ggx_single(n, wi, wo);
        [0, 1, 2].map(|k| spec * ((1.0 - m) * d[k] + m * metal[k]) + (1.0 - d[k]) * albedo[k] * (1.0 - m) * ci)
    }

    /// The reflected colour of [`ThinFilm::metal_stack`] (like [`ThinFilm::colors`]); `None` without one.
    pub fn metal_color(&self, cos_theta: f64, offset_nm: f64) -> Option<Xyz> {
        let stack = self.metal_stack.as_ref()?;
        let angle = cos_theta.clamp(0.0, 1.0).acos();
        let r: Vec<f64> = self
            .colorimeter
            .wavelengths_nm()
            .iter()
            .map(|&l| stack.evaluate_offset(l, angle, offset_nm).map(|x| x.r()).unwrap_or(0.0))
            .collect();
        Some(self.colorimeter.from_spectra(&r, &r).reflected)
    }

    /// Makes the substrate rough (LSRS). Refused where the film transmits (the LSRS model describes
    /// reflection only) or has a `base` (the rough substrate of the stack is the base), and where the HTSG
    /// model is not valid at some wavelength of 380–780 nm (the message says which condition fails).
    pub fn set_rough(&mut self, htsg: Htsg) -> Result<(), RenderError> {
        if self.transmission {
            return Err(RenderError::Input(
                "a rough substrate (`roughness`) reflects only: the LSRS model has no transmitted part, so \
                 `transmission = true` cannot be combined with it"
                    .into(),
            ));
        }
        if self.base.is_some() {
            return Err(RenderError::Input(
                "a rough film's substrate is the last medium of its `stack` (its diffuse light comes from there), \
                 so it takes no `base` material"
                    .into(),
            ));
        }
        let rough = RoughStack::new(self.stack.clone(), htsg);
        // Normal light and view give the HTSG series its largest phase variance g = (2kσ)²: a series that
        // converges there converges at every angle, so no pixel falls back to a zero diffuse part.
        for &l in self.colorimeter.wavelengths_nm() {
            rough
                .evaluate(l, 0.0, 0.0, std::f64::consts::PI)
                .map_err(|e| RenderError::Input(format!("rough substrate at {l} nm: {e}")))?;
        }
        self.rough = Some(htsg);
        Ok(())
    }

    /// The thickness offsets (nm) the film's SVT texture can add to every layer, `(−|d_rel|, |d_rel|)`; `(0, 0)`
    /// without SVT. The colour tables of the film (the GPU's smooth-film table, the rough tables) cover it.
    pub fn svt_range_nm(&self) -> (f64, f64) {
        self.svt.map_or((0.0, 0.0), |s| (-s.d_rel_nm.abs(), s.d_rel_nm.abs()))
    }

    /// The rough film's colour tables ([`iridis_thinfilm::rough_table`]), made on first use and shared by the
    /// CPU renderer and the GPU (a scene rendered on both builds them once; they are most of a rough film's
    /// set-up time): `k_r` and `π k_d` integrated over the spectrum at every node of 3° in the view and light
    /// angles, 10° in their relative azimuth and the SVT offsets a smooth table of the stack would have.
    /// `None` for a smooth film; the error for a stack without a table (incoherent layers).
    pub fn rough_table(&self) -> Option<Result<&iridis_thinfilm::rough_table::RoughColorTable, &ThinFilmError>> {
        use iridis_thinfilm::rough_table::{RoughColorTable, ANGLE_NODES, AZIMUTH_NODES};
        let htsg = self.rough?;
        let table = self.rough_table.get_or_init(|| {
            let dense = iridis_thinfilm::spectral::dense_weights();
            let range = self.svt_range_nm();
            let offsets = if range.1 > range.0 {
                iridis_thinfilm::table::TableGrid::for_stack(&self.stack, dense.wavelengths_nm(), range)?.offset_nodes
            } else {
                1
            };
            let rough = RoughStack::new(self.stack.clone(), htsg);
            RoughColorTable::build(&rough, &dense, ANGLE_NODES, AZIMUTH_NODES, offsets, range)
        });
        Some(table.as_ref())
    }

    /// [`ThinFilm::rough_colors`] as the renderer (and the GPU) shades it: from the colour tables
    /// ([`ThinFilm::rough_table`]), exact at their nodes and multilinear between them (measured against the
    /// direct evaluation: ΔE00 0.03 for the diffuse part at 40°, between the 39° and 42° nodes; 0.07 at most
    /// for the specular part near a sphere's rim; `render_cli.rs`). The direct evaluation is the HTSG series at
    /// 81 wavelengths for every light at every hit: `rough_film.toml` at 320 × 240 took 53 s of CPU that way,
    /// 4.6 s with the tables (2-core VM, 2026-11-27), most of it building them (once per material). Falls back to the direct
    /// evaluation where no table can be made.
    pub fn rough_colors_tabulated(
        &self,
        cos_view: f64,
        offset_nm: f64,
        lights: &[(f64, f64)],
    ) -> Option<(Xyz, Vec<Xyz>)> {
        let Some(Ok(t)) = self.rough_table() else { return self.rough_colors(cos_view, offset_nm, lights) };
        let spec = t.specular_at(cos_view, offset_nm);
        let diffuse = lights.iter().map(|&(cos_l, az)| t.diffuse_at(cos_view, cos_l, az, offset_nm)).collect();
        Some((spec, diffuse))
    }

    /// The rough film's colours at a hit (LSRS, Sussenbach eq. 3.15–3.19, evaluated directly at every
    /// wavelength of the 5 nm grid): the composite specular reflectance `k_r` at the view angle (`cos_view`),
    /// and for each light, given as (`cos θ_l`, azimuth of the light relative to the viewer about the normal),
    /// the diffuse radiance factor `π k_d` (zero where `cos θ_l ≤ 0`). XYZ under D65 normalised like
    /// [`ThinFilm::colors`]: exactly the "specular" and "diffuse" colours of `iridis thinfilm color --roughness σ
    /// --correlation τ --angle θ_v --light-angle θ_l --azimuth φ`. Layers are offset by `offset_nm` (SVT).
    /// Returns `None` for a smooth film.
    pub fn rough_colors(&self, cos_view: f64, offset_nm: f64, lights: &[(f64, f64)]) -> Option<(Xyz, Vec<Xyz>)> {
        let htsg = self.rough?;
        let mut stack = self.stack.clone();
        for l in &mut stack.layers {
            l.thickness_nm = (l.thickness_nm + offset_nm).max(0.0);
        }
        let rough = RoughStack::new(stack, htsg);
        let view = cos_view.clamp(0.0, 1.0).acos();
        let grid = self.colorimeter.wavelengths_nm();
        let mut spec = vec![0.0; grid.len()];
        let mut diff = vec![vec![0.0; grid.len()]; lights.len()];
        let lit: Vec<usize> = (0..lights.len()).filter(|&j| lights[j].0 > 0.0).collect();
        for (w, &l) in grid.iter().enumerate() {
            if lit.is_empty() {
                spec[w] = rough.specular(l, view).map(|(s, p)| 0.5 * (s + p)).unwrap_or(0.0);
            }
            for (k, &j) in lit.iter().enumerate() {
                let (cos_l, azimuth) = lights[j];
                if let Ok(x) = rough.evaluate(l, view, cos_l.min(1.0).acos(), azimuth) {
                    if k == 0 {
                        spec[w] = x.k_r();
                    }
                    diff[j][w] = std::f64::consts::PI * x.k_d();
                }
            }
        }
        let xyz = |s: &[f64]| self.colorimeter.from_spectra(s, s).reflected;
        Some((xyz(&spec), diff.iter().map(|d| xyz(d)).collect()))
    }
}

/// The azimuth of `wi` relative to `wo` about the normal `n`, in [0, π] (π: on opposite sides of the normal,
/// the mirror configuration). Where either direction is along the normal, the azimuth is immaterial; π.
pub fn relative_azimuth(n: V3, wi: V3, wo: V3) -> f64 {
    let project = |v: V3| try_normalize(sub(v, mul(n, dot(n, v))));
    match (project(wi), project(wo)) {
        (Some(a), Some(b)) => dot(a, b).clamp(-1.0, 1.0).acos(),
        _ => std::f64::consts::PI,
    }
}

/// A GGX microfacet surface: a dielectric coat over a Lambertian base (metallic = 0) or a coloured metal
/// (metallic = 1), energy-conserving ([`crate::energy`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Microfacet {
    pub color: ColorSource,
    /// GGX `α = roughness²`.
    pub roughness: f64,
    pub metallic: f64,
    /// Index of refraction of the dielectric coat (F_0 = ((n − 1)/(n + 1))²).
    pub ior: f64,
    /// glTF's metallicRoughnessTexture (a [`crate::texture::TexKind::Data`] texture): its G channel multiplies
    /// `roughness`, its B channel `metallic` ([`Microfacet::at`]).
    pub metallic_roughness: Option<usize>,
    /// glTF's normalTexture (a [`crate::texture::TexKind::Data`] texture) and its `scale`: the shading normal in
    /// tangent space ([`Microfacet::normal_at`]).
    pub normal_texture: Option<(usize, f64)>,
}

impl Microfacet {
    /// The surface at texture coordinate `uv`: roughness × G and metallic × B of the metallic-roughness
    /// texture, read linearly (glTF 2.0, sec. 3.9.2); itself where there is none.
    pub fn at(&self, uv: [f64; 2], textures: &[crate::texture::Texture]) -> Microfacet {
        match self.metallic_roughness.and_then(|i| textures.get(i)) {
            Some(t) => {
                let s = t.sample(uv);
                Microfacet {
                    roughness: (self.roughness * s[1]).clamp(0.0, 1.0),
                    metallic: (self.metallic * s[2]).clamp(0.0, 1.0),
                    metallic_roughness: None,
                    ..*self
                }
            }
            None => *self,
        }
    }

    /// The hit with its shading normal from the normal texture, where there is one and the hit has a tangent:
    /// `n' = normalize(T·x + B·y + N·z)` with `(x, y, z) = (2·rgb − 1)`, x and y × `scale`, `B = (N × T)·w`
    /// (glTF 2.0, sec. 3.9.3). A normal that would face away from the geometric normal is not used.
    pub fn normal_at(&self, h: &Hit, textures: &[crate::texture::Texture]) -> Hit {
        let (Some((i, scale)), Some(t)) = (self.normal_texture, h.tangent) else { return *h };
        let Some(tex) = textures.get(i) else { return *h };
        let s = tex.sample(h.uv);
        let (x, y, z) = ((2.0 * s[0] - 1.0) * scale, (2.0 * s[1] - 1.0) * scale, 2.0 * s[2] - 1.0);
        let b = mul(cross(h.n, t), h.tangent_sign);
        let Some(n) = try_normalize(add(add(mul(t, x), mul(b, y)), mul(h.n, z))) else { return *h };
        if dot(n, h.ng) <= 0.0 {
            return *h;
        }
        Hit { n, tangent: orthogonalize(t, n), ..*h }
    }

    /// Schlick `F_0 = ((n − 1)/(n + 1))²` of the dielectric coat. An index-matched coat (`ior = 1`, the films'
    /// Lambertian base) is no interface at all: no specular, a plain Lambertian.
    fn coat_f0(&self) -> Option<f64> {
        (self.ior != 1.0).then(|| ((self.ior - 1.0) / (self.ior + 1.0)).powi(2))
    }

    /// `π · f(ω_i, ω_o) · cos θ_i` for unit irradiance: glTF's `mix(dielectric, metal, metallic)` where the metal
    /// is the GGX lobe (`D G F / (4 cos θ_i cos θ_o)`, GGX `D`, Smith's separable `G`, Schlick's `F` from the
    /// albedo) plus Kulla & Conty's multiple-scattering lobe, and the dielectric is the same specular with the
    /// coat's `F_0` over a diffuse lobe that takes what the specular leaves, `ρ (1 − E_s(μ_i))(1 − E_s(μ_o)) /
    /// (1 − E_s,avg)` ([`crate::energy`]): a white surface reflects all the light it receives.
    pub fn reflect(&self, n: V3, wi: V3, wo: V3, albedo: Rgb) -> Rgb {
        let (ci, co) = (dot(n, wi), dot(n, wo));
        if ci <= 0.0 || co <= 0.0 {
            return [0.0; 3];
        }
        let h = normalize(add(wi, wo));
        let a2 = energy::alpha2(self.roughness);
        let d = energy::ggx_d(a2, dot(n, h).max(0.0));
        let g = energy::smith_g1(a2, ci) * energy::smith_g1(a2, co);
        let x5 = (1.0 - dot(wi, h).clamp(0.0, 1.0)).powi(5);
        // π f cos θ_i of the single-scattering lobe with F = 1, and of the multiple-scattering lobe with F_ms = 1.
        let single = d * g / (4.0 * ci * co) * std::f64::consts::PI * ci;
        let (ei, eo) = (energy::lookup(self.roughness, ci), energy::lookup(self.roughness, co));
        let multi = (1.0 - ei.0[0]) * (1.0 - eo.0[0]) / (1.0 - eo.1[0]).max(1e-9) * ci;
        let lobe = |f0: f64| {
            let e = energy::spec_energy(self.roughness, co, f0);
            single * (f0 + (1.0 - f0) * x5) + multi * e.f_ms
        };
        let dielectric = match self.coat_f0() {
            Some(f0) => {
                let s = lobe(f0);
                let (si, so) =
                    (energy::spec_energy(self.roughness, ci, f0), energy::spec_energy(self.roughness, co, f0));
                let k = (1.0 - si.e_s) * (1.0 - so.e_s) / (1.0 - so.e_s_avg).max(1e-9) * ci;
                albedo.map(|a| s + a * k)
            }
            None => albedo.map(|a| a * ci),
        };
        let m = self.metallic;
        [0, 1, 2].map(|k| (1.0 - m) * dielectric[k] + if m > 0.0 { m * lobe(albedo[k]) } else { 0.0 })
    }

    /// `π f cos θ_i` of the single-scattering GGX lobe with `F = 1` (a film's reflectance multiplies it).
    pub fn ggx_single(&self, n: V3, wi: V3, wo: V3) -> f64 {
        let (ci, co) = (dot(n, wi), dot(n, wo));
        if ci <= 0.0 || co <= 0.0 {
            return 0.0;
        }
        let a2 = energy::alpha2(self.roughness);
        let d = energy::ggx_d(a2, dot(n, normalize(add(wi, wo))).max(0.0));
        d * energy::smith_g1(a2, ci) * energy::smith_g1(a2, co) / (4.0 * co) * std::f64::consts::PI
    }

    /// How environment light of uniform radiance 1 leaves towards `ω_o` (`cos_o = n·ω_o`): the specular share
    /// (directional albedo of all specular lobes, per channel) and the diffuse share. Their sum is what
    /// [`Microfacet::reflect`] integrates to over the hemisphere of `ω_i`: 1 for a white surface.
    pub fn env_weights(&self, cos_o: f64, albedo: Rgb) -> (Rgb, Rgb) {
        let m = self.metallic;
        let (es_d, diffuse) = match self.coat_f0() {
            Some(f0) => {
                let e = energy::spec_energy(self.roughness, cos_o, f0).e_s;
                (e, 1.0 - e)
            }
            None => (0.0, 1.0),
        };
        let spec = [0, 1, 2].map(|k| {
            let metal = if m > 0.0 { energy::spec_energy(self.roughness, cos_o, albedo[k]).e_s } else { 0.0 };
            (1.0 - m) * es_d + m * metal
        });
        (spec, albedo.map(|a| (1.0 - m) * diffuse * a))
    }

    /// Fresnel reflectance towards the mirror direction (Schlick, the coat's `F_0` or the metal's albedo).
    pub fn mirror_fresnel(&self, cos: f64, albedo: Rgb) -> Rgb {
        let f0d = self.coat_f0().unwrap_or(0.0);
        let m = (1.0 - cos.clamp(0.0, 1.0)).powi(5);
        let coat = if self.coat_f0().is_some() { 1.0 } else { 0.0 };
        [0, 1, 2].map(|k| {
            let d = coat * (f0d + (1.0 - f0d) * m);
            let metal = albedo[k] + (1.0 - albedo[k]) * m;
            d * (1.0 - self.metallic) + metal * self.metallic
        })
    }
}

/// A material of the scene.
#[derive(Debug, Clone)]
pub enum Material {
    /// Lambertian: `albedo · cos θ_i` per RU of irradiance, plus `albedo` × the environment's mean radiance.
    Lambert {
        color: ColorSource,
    },
    Microfacet(Microfacet),
    Diffraction(Box<Diffraction>),
    ThinFilm(Box<ThinFilm>),
}

impl Material {
    /// Whether light passes through (such objects cast no shadows).
    pub fn transmissive(&self) -> bool {
        matches!(self, Material::ThinFilm(f) if f.transmission)
    }
    /// Whether this material reads UV coordinates (then a mesh must have them).
    pub fn needs_uv(&self) -> bool {
        let tex = |c: &ColorSource| matches!(c, ColorSource::Texture(_));
        match self {
            Material::Lambert { color } => tex(color),
            Material::Microfacet(m) => tex(&m.color),
            Material::Diffraction(d) => tex(&d.texture) || matches!(d.orientation.rule, OrientRule::Texture(_)),
            Material::ThinFilm(f) => f.svt.is_some(),
        }
    }
}
