//! Lights and the environment. Radiometry is in relative units (RU, PHYSICS.md): a directional light of
//! intensity 1 RU on a normal-incidence mirror gives `Y = 1`, which an image at exposure 1 shows as white.
//! Colours are linear sRGB triples; `[1, 1, 1]` is D65 white.

use iridis_color::{Illuminant, Observer, Xyz};

use crate::math::*;
use crate::texture::Texture;

/// Linear sRGB (D65 white = `[1, 1, 1]`).
pub type Rgb = [f64; 3];

/// The colour of an illuminant relative to D65, in linear sRGB: `rgb(S) / rgb(D65)` per channel, with each
/// white point normalised to `Y = 1`. D65 gives exactly `[1, 1, 1]`, so a D65 light leaves the diffraction
/// tables (integrated under D65) unchanged; another spectrum tints them by this ratio (a von Kries-style
/// approximation: the tables are not re-integrated).
pub fn illuminant_tint(ill: Illuminant) -> Rgb {
    let rgb = |i: Illuminant| {
        let w = iridis_color::integrate::white_point(i, Observer::Cie1931);
        Xyz::new(w.x / w.y, 1.0, w.z / w.y).to_linear_srgb()
    };
    let (s, d) = (rgb(ill), rgb(Illuminant::D65));
    [s[0] / d[0], s[1] / d[1], s[2] / d[2]]
}

/// A light source.
#[derive(Debug, Clone, PartialEq)]
pub enum Light {
    /// Parallel light from `direction` (unit, pointing towards the light), irradiance `rgb` (RU).
    Directional { direction: V3, rgb: Rgb },
    /// A point at `position`; `rgb` is the irradiance (RU) at distance 1, falling off as `1/r²`.
    Point { position: V3, rgb: Rgb },
    /// A laser beam's spot on a diffraction sample (paper sec. 6.2), seen as the light source it is for
    /// everything else: a point that sends each direction what the sample reflects of the beam there.
    Laser(Box<LaserSpot>),
}

/// The reflection of a thin laser beam off a sample: a point source at the spot whose intensity towards
/// `ω_o` is `P·F(ω_i, ω_o)·cos θ_o / cos θ_i`, where `P` is the beam's power, `F` the sample's reflection of a
/// 1 RU light (what a camera sees of it: `Diffraction::shade_light` for unit irradiance) and the
/// `cos θ_o / cos θ_i` the spot's projected area towards `ω_o` (the beam's cross-section spreads over
/// `1/cos θ_i` of the surface). A surface at distance `r` receives `P·F·cos θ_o / (cos θ_i·r²)`.
#[derive(Debug, Clone, PartialEq)]
pub struct LaserSpot {
    /// Where the beam meets the sample, lifted off it a little along its normal (by 10⁻⁴ of the scene's
    /// scale, more than the GPU's ray offsets); only what lies in front of that point is lit.
    pub position: V3,
    /// The beam's power `P` (RU · scene unit²: a 1 RU light over one square unit of cross-section) × tint.
    pub rgb: Rgb,
    /// The sample's frame at the spot: the nanostructure's axis `t`, `b = n × t` and the normal `n`.
    pub frame: [V3; 3],
    /// `cos θ_i` of the beam on the sample.
    pub cos_in: f64,
    /// `F(ω_i, ω_o)` for every outgoing direction, as a BRDF map (`iridis brdf-map`'s layout: pixel `(x, y)`
    /// of the unit disk shows `ω_o = (x, y, √(1 − x² − y²))` in the frame), linear sRGB.
    pub profile: Texture,
}

impl LaserSpot {
    /// Direction towards the spot, distance and irradiance arriving at `p` (zero behind the sample).
    pub fn arrive(&self, p: V3) -> (V3, f64, Rgb) {
        let d = sub(self.position, p);
        let r2 = dot(d, d).max(1e-300);
        let r = r2.sqrt();
        let wi = mul(d, 1.0 / r);
        let [t, b, n] = self.frame;
        if dot(sub(p, self.position), n) <= 0.0 {
            return (wi, r, [0.0; 3]);
        }
        let wo = mul(wi, -1.0);
        let (x, y, z) = (dot(wo, t), dot(wo, b), dot(wo, n));
        let f = self.profile.sample([(x + 1.0) / 2.0, (1.0 - y) / 2.0]);
        (wi, r, mul(hadamard(self.rgb, f), z / (self.cos_in * r2)))
    }
}

impl Light {
    /// Direction towards the light, distance to it and the irradiance arriving at `p`.
    pub fn arrive(&self, p: V3) -> (V3, f64, Rgb) {
        match *self {
            Light::Directional { direction, rgb } => (direction, f64::INFINITY, rgb),
            Light::Point { position, rgb } => {
                let d = sub(position, p);
                let r2 = dot(d, d).max(1e-12);
                (mul(d, 1.0 / r2.sqrt()), r2.sqrt(), mul(rgb, 1.0 / r2))
            }
            Light::Laser(ref spot) => spot.arrive(p),
        }
    }
}

/// Light arriving from far away in every direction.
#[derive(Debug, Clone, Default)]
pub enum Environment {
    /// No environment: black.
    #[default]
    None,
    /// The same radiance from every direction.
    Uniform(Rgb),
    /// A procedural sky: `zenith` overhead blending to `horizon`, `ground` below (y is up).
    Sky { zenith: Rgb, horizon: Rgb, ground: Rgb },
    /// An equirectangular (latitude–longitude) HDR image: row 0 is straight up (+y), the centre column looks
    /// towards −z, `rotation` turns it about +y. Texture values are linear sRGB radiance × `intensity`.
    Map { texture: Box<Texture>, rotation: f64, intensity: f64, mean: Rgb },
}

impl Environment {
    /// Radiance arriving from direction `d` (unit, pointing away from the scene).
    pub fn radiance(&self, d: V3) -> Rgb {
        match self {
            Environment::None => [0.0; 3],
            Environment::Uniform(c) => *c,
            Environment::Sky { zenith, horizon, ground } => {
                if d[1] >= 0.0 {
                    let t = d[1].clamp(0.0, 1.0).powf(0.6);
                    [0, 1, 2].map(|k| horizon[k] + (zenith[k] - horizon[k]) * t)
                } else {
                    let t = (-d[1] * 8.0).clamp(0.0, 1.0);
                    [0, 1, 2].map(|k| horizon[k] + (ground[k] - horizon[k]) * t)
                }
            }
            Environment::Map { texture, rotation, intensity, .. } => {
                let (u, v) = equirect_uv(d, *rotation);
                mul(texture.sample_with([u, v], true), *intensity)
            }
        }
    }

    /// Mean radiance over the sphere (the ambient level used by diffuse materials).
    pub fn mean(&self) -> Rgb {
        match self {
            Environment::None => [0.0; 3],
            Environment::Uniform(c) => *c,
            Environment::Sky { zenith, horizon, ground } => {
                // Area-weighted average over the sphere of the profiles above (numerical, 1000 bands in y).
                let mut acc = [0.0; 3];
                let n = 1000;
                for i in 0..n {
                    let y = -1.0 + (2 * i + 1) as f64 / n as f64;
                    let c = Environment::Sky { zenith: *zenith, horizon: *horizon, ground: *ground }.radiance([
                        (1.0 - y * y).sqrt(),
                        y,
                        0.0,
                    ]);
                    acc = add(acc, mul(c, 1.0 / n as f64));
                }
                acc
            }
            Environment::Map { mean, .. } => *mean,
        }
    }
}

/// Number of directional lights that stand for the environment ([`Environment::as_lights`]); the GPU shader's
/// `ENV_LIGHTS` is the same number.
pub const ENVIRONMENT_LIGHTS: usize = 64;

/// How many of its cells' solid angle (`4π/ENVIRONMENT_LIGHTS` each) an environment light's diffraction lobe is
/// averaged over: 4, a square twice as wide as the light's own cell, so that neighbouring lights overlap and a
/// narrow lobe under a smooth sky blends them instead of reflecting each cell as a flat, hard-edged patch
/// (issue 32's blocky sphere). The environment keeps its power (each light's mean lobe still carries its own
/// irradiance); its detail is blurred by about one cell, which the 64 cells could not resolve anyway. The GPU's
/// `scene.wgsl` uses the same factor.
pub const ENVIRONMENT_LIGHT_SPREAD: f64 = 4.0;

/// Equirectangular cells (columns, rows) into which the environment's radiance is averaged.
pub const RADIANCE_CELLS: (usize, usize) = (128, 64);

/// Size of the irradiance map (equirectangular, like an environment map; irradiance varies slowly). Its rows
/// sit at polar angles `π r / (rows − 1)`, so the first and last rows are the poles themselves
/// ([`irradiance_map_v`]).
pub const IRRADIANCE_SIZE: [usize; 2] = [32, 17];

/// The texture coordinate `v` at which the irradiance map is sampled for a direction at `v = θ/π`: its rows
/// hold the poles exactly, so a normal straight up or down reads the same value in every column. (With
/// rows at texel centres the pole's value depended on the azimuth of an exactly vertical normal, which
/// `atan2(0, −0)` decides: π on the CPU, 0 on some GPUs — a floor came out 1.6 % apart, issue 19.)
pub fn irradiance_map_v(v: f64) -> f64 {
    let rows = IRRADIANCE_SIZE[1] as f64;
    (v * (rows - 1.0) + 0.5) / rows
}

impl Environment {
    /// The environment's irradiance around every normal, divided by π (the radiance a white Lambertian surface
    /// with that normal reflects: `E(n)/π = ∫ L(ω) max(n·ω, 0) dω / π`), as a 32 × 17 equirectangular map
    /// (row 0 is +y itself, the last row −y, centre column −z, no rotation) that the renderers sample
    /// bilinearly at [`irradiance_map_v`]. The radiance is
    /// first averaged into 128 × 64 solid-angle cells (a map's texels box-filtered into them, a sky sampled at
    /// their centres); the cosine integral is then a sum over the cells, normalised by the same sum of the
    /// weights, so that a uniform environment gives exactly its radiance. `None` where the irradiance is the
    /// same for every normal (no environment, uniform).
    pub fn irradiance_map(&self) -> Option<Texture> {
        if matches!(self, Environment::Uniform(_)) {
            return None;
        }
        let cells = self.radiance_cells()?;
        let (cw, ch) = RADIANCE_CELLS;
        let dirs: Vec<(V3, f64)> = (0..cw * ch)
            .map(|k| {
                let (u, v) = (((k % cw) as f64 + 0.5) / cw as f64, ((k / cw) as f64 + 0.5) / ch as f64);
                (equirect_dir(u, v, 0.0), (v * std::f64::consts::PI).sin())
            })
            .collect();
        let [ow, oh] = IRRADIANCE_SIZE;
        let mut data = Vec::with_capacity(ow * oh * 3);
        for r in 0..oh {
            for c in 0..ow {
                let n = equirect_dir((c as f64 + 0.5) / ow as f64, r as f64 / (oh - 1) as f64, 0.0);
                let (mut acc, mut wsum) = ([0.0; 3], 0.0);
                for (k, (d, s)) in dirs.iter().enumerate() {
                    let w = dot(n, *d).max(0.0) * s;
                    acc = add(acc, mul(cells[k], w));
                    wsum += w;
                }
                data.extend(mul(acc, 1.0 / wsum).map(|x| x as f32));
            }
        }
        Some(Texture::Image {
            width: ow,
            height: oh,
            channels: 3,
            data,
            kind: crate::texture::TexKind::Color,
            name: "environment irradiance".into(),
        })
    }

    /// The environment as [`ENVIRONMENT_LIGHTS`] directional lights, for the BRDFs that have no environment
    /// integral of their own (diffraction): `(direction, e)` where the directions
    /// are a Fibonacci sphere (near-equal solid angles) and each carries the irradiance `E_k = ∫ L dω` over the
    /// [`RADIANCE_CELLS`] cells nearest to it (its Voronoi cell), in the unit of the scene's lights: `e = E/π`,
    /// the radiance a white Lambertian surface facing the light reflects (a light of `e` gives it `e cos θ`).
    /// So `Σ_k π f(ω_k, ω_o) e_k cos θ_k` is a quadrature of the reflected radiance `∫ f L cos θ dω` that keeps
    /// the environment's total power (`Σ e_k = ∫ L dω / π`; a uniform radiance 1 gives 4). Empty without an
    /// environment. The same directions light the CPU and the GPU renderer.
    pub fn as_lights(&self) -> Vec<(V3, Rgb)> {
        let Some(cells) = self.radiance_cells() else { return Vec::new() };
        let (cw, ch) = RADIANCE_CELLS;
        let n = ENVIRONMENT_LIGHTS;
        let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
        let dirs: Vec<V3> = (0..n)
            .map(|k| {
                let y = 1.0 - (2 * k + 1) as f64 / n as f64;
                let r = (1.0 - y * y).max(0.0).sqrt();
                let phi = k as f64 * golden;
                [r * phi.cos(), y, r * phi.sin()]
            })
            .collect();
        let mut e = vec![[0.0f64; 3]; n];
        let dphi = std::f64::consts::TAU / cw as f64;
        for (k, cell) in cells.iter().enumerate() {
            let (c, r) = (k % cw, k / cw);
            let (u, v) = ((c as f64 + 0.5) / cw as f64, (r as f64 + 0.5) / ch as f64);
            let d = equirect_dir(u, v, 0.0);
            // The cell's solid angle: Δφ (cos θ₀ − cos θ₁) between its polar edges.
            let (t0, t1) =
                (r as f64 / ch as f64 * std::f64::consts::PI, (r + 1) as f64 / ch as f64 * std::f64::consts::PI);
            let omega = dphi * (t0.cos() - t1.cos());
            let nearest = (0..n).max_by(|&a, &b| dot(dirs[a], d).total_cmp(&dot(dirs[b], d))).unwrap_or(0);
            e[nearest] = add(e[nearest], mul(*cell, omega / std::f64::consts::PI));
        }
        dirs.into_iter().zip(e).collect()
    }

    /// The radiance averaged into [`RADIANCE_CELLS`] equirectangular solid-angle cells (row 0 is +y, centre
    /// column −z, no rotation): a map's texels box-filtered into them, a sky sampled at their centres, a
    /// uniform radiance as it is. `None` without an environment.
    fn radiance_cells(&self) -> Option<Vec<Rgb>> {
        let (cw, ch) = RADIANCE_CELLS;
        self.radiance_grid(cw, ch)
    }

    /// The radiance averaged into `cw × ch` equirectangular cells (as [`Environment::radiance_cells`]).
    fn radiance_grid(&self, cw: usize, ch: usize) -> Option<Vec<Rgb>> {
        let mut cells = vec![[0.0f64; 3]; cw * ch];
        match self {
            Environment::None => return None,
            Environment::Uniform(c) => cells.fill(*c),
            Environment::Sky { .. } => {
                for r in 0..ch {
                    for c in 0..cw {
                        let (u, v) = ((c as f64 + 0.5) / cw as f64, (r as f64 + 0.5) / ch as f64);
                        cells[r * cw + c] = self.radiance(equirect_dir(u, v, 0.0));
                    }
                }
            }
            Environment::Map { texture, rotation, intensity, .. } => {
                let Texture::Image { width, height, .. } = texture.as_ref() else { return None };
                let (w, h) = (*width, *height);
                let mut wsum = vec![0.0f64; cw * ch];
                for y in 0..h {
                    let v = (y as f64 + 0.5) / h as f64;
                    let s = (v * std::f64::consts::PI).sin();
                    for x in 0..w {
                        let u = (x as f64 + 0.5) / w as f64;
                        // The texel's direction in the world (the map turned by `rotation`), then its cell.
                        let (uw, vw) = equirect_uv(equirect_dir(u, v, *rotation), 0.0);
                        let k = ((vw * ch as f64) as usize).min(ch - 1) * cw + ((uw * cw as f64) as usize).min(cw - 1);
                        let t = texture.sample_with([u, v], true);
                        cells[k] = add(cells[k], mul(t, s * intensity));
                        wsum[k] += s;
                    }
                }
                for (k, c) in cells.iter_mut().enumerate() {
                    if wsum[k] > 0.0 {
                        *c = mul(*c, 1.0 / wsum[k]);
                    } else {
                        // A map smaller than the cell grid: sample it at the cell's centre.
                        let (u, v) = (((k % cw) as f64 + 0.5) / cw as f64, ((k / cw) as f64 + 0.5) / ch as f64);
                        *c = self.radiance(equirect_dir(u, v, 0.0));
                    }
                }
            }
        }
        Some(cells)
    }

    /// `E(n)/π` for a unit normal, from [`Environment::irradiance_map`]'s map (`map`) or, without one, the
    /// uniform radiance.
    pub fn irradiance(&self, map: Option<&Texture>, n: V3) -> Rgb {
        match (map, self) {
            (Some(t), _) => {
                let (u, v) = equirect_uv(n, 0.0);
                t.sample_with([u, irradiance_map_v(v)], true)
            }
            (None, Environment::Uniform(c)) => *c,
            (None, _) => self.mean(),
        }
    }
}

/// Largest grid of [`EnvSampler`] (columns, rows): an environment map finer than this is box-filtered into it.
pub const ENV_SAMPLER_MAX: (usize, usize) = (512, 256);

/// Importance sampling of the environment (image-based lighting): a piecewise-constant distribution over
/// equirectangular cells (row 0 is +y, centre column −z, no rotation — the map's rotation is applied when its
/// texels are filtered into the cells), each cell drawn with probability ∝ its mean luminance × its solid
/// angle, then a direction uniform in solid angle inside it (uniform in φ and cos θ). The pdf is the cell's
/// probability over its solid angle. The sampled direction's radiance is the environment's own (bilinear),
/// not the cell mean, so the estimator is unbiased at any grid size; a floor of 1 % of the mean luminance
/// keeps every direction reachable (the light-only estimator then has full support too).
#[derive(Debug, Clone)]
pub struct EnvSampler {
    pub dist: crate::sampling::Distribution2d,
}

impl EnvSampler {
    /// `None` without an environment or when it is black.
    pub fn new(env: &Environment) -> Option<Self> {
        let (cw, ch) = match env {
            Environment::None => return None,
            Environment::Map { texture, .. } => match texture.as_ref() {
                Texture::Image { width, height, .. } => {
                    ((*width).clamp(8, ENV_SAMPLER_MAX.0), (*height).clamp(4, ENV_SAMPLER_MAX.1))
                }
                _ => RADIANCE_CELLS,
            },
            _ => RADIANCE_CELLS,
        };
        let cells = env.radiance_grid(cw, ch)?;
        let lum = |c: &Rgb| (0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]).max(0.0);
        let omega = |r: usize| cell_solid_angle(r, cw, ch);
        let total: f64 = cells.iter().enumerate().map(|(k, c)| lum(c) * omega(k / cw)).sum();
        let floor = 0.01 * total / (4.0 * std::f64::consts::PI);
        let weights: Vec<f64> = cells.iter().enumerate().map(|(k, c)| (lum(c) + floor) * omega(k / cw)).collect();
        Some(Self { dist: crate::sampling::Distribution2d::new(cw, ch, &weights)? })
    }

    /// A direction and its solid-angle pdf from two uniform numbers.
    pub fn sample(&self, u: [f64; 2]) -> (V3, f64) {
        let (c, r, f) = self.dist.sample(u);
        let (cw, ch) = (self.dist.cols, self.dist.rows);
        let (t0, t1) = (r as f64 / ch as f64 * std::f64::consts::PI, (r + 1) as f64 / ch as f64 * std::f64::consts::PI);
        let cos_t = t0.cos() + (t1.cos() - t0.cos()) * f[1];
        let v = cos_t.clamp(-1.0, 1.0).acos() / std::f64::consts::PI;
        let d = equirect_dir((c as f64 + f[0]) / cw as f64, v, 0.0);
        (d, self.dist.prob(c, r) / cell_solid_angle(r, cw, ch))
    }

    /// The solid-angle pdf of direction `d`.
    pub fn pdf(&self, d: V3) -> f64 {
        let (cw, ch) = (self.dist.cols, self.dist.rows);
        let (u, v) = equirect_uv(d, 0.0);
        let c = ((u * cw as f64) as usize).min(cw - 1);
        let r = ((v * ch as f64) as usize).min(ch - 1);
        self.dist.prob(c, r) / cell_solid_angle(r, cw, ch)
    }
}

/// Solid angle of a cell of row `r` of a `cw × ch` equirectangular grid: `Δφ (cos θ₀ − cos θ₁)`.
pub fn cell_solid_angle(r: usize, cw: usize, ch: usize) -> f64 {
    let (t0, t1) = (r as f64 / ch as f64 * std::f64::consts::PI, (r + 1) as f64 / ch as f64 * std::f64::consts::PI);
    std::f64::consts::TAU / cw as f64 * (t0.cos() - t1.cos())
}

/// The direction of equirectangular coordinates (the inverse of [`equirect_uv`]).
pub fn equirect_dir(u: f64, v: f64, rotation: f64) -> V3 {
    let phi = (u - 0.5) * std::f64::consts::TAU + rotation;
    let theta = v * std::f64::consts::PI;
    let s = theta.sin();
    [s * phi.sin(), theta.cos(), -s * phi.cos()]
}

/// Equirectangular coordinates of a direction: `u` is the longitude (0.5 at −z), `v` from +y (0) to −y (1).
pub fn equirect_uv(d: V3, rotation: f64) -> (f64, f64) {
    let phi = d[0].atan2(-d[2]) - rotation;
    let u = 0.5 + phi / std::f64::consts::TAU;
    let v = d[1].clamp(-1.0, 1.0).acos() / std::f64::consts::PI;
    (u.rem_euclid(1.0), v)
}

/// The solid-angle-weighted mean of an equirectangular map (rows weighted by `sin θ`).
pub fn equirect_mean(texture: &Texture, intensity: f64) -> Rgb {
    let Texture::Image { width, height, .. } = texture else { return [0.0; 3] };
    let (w, h) = (*width, *height);
    let (mut acc, mut wsum) = ([0.0; 3], 0.0);
    for r in 0..h {
        let theta = (r as f64 + 0.5) / h as f64 * std::f64::consts::PI;
        let s = theta.sin();
        for c in 0..w {
            let v = texture.sample_with([(c as f64 + 0.5) / w as f64, (r as f64 + 0.5) / h as f64], true);
            acc = add(acc, mul(v, s));
            wsum += s;
        }
    }
    mul(acc, intensity / wsum.max(1e-300))
}
