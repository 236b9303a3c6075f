//! The renderer: ray casting through a BVH, all cores (rayon, one image row per task), `spp` samples per pixel
//! on a rank-1 lattice (R2 sequence; one sample sits at the pixel centre), linear float output.

use rayon::prelude::*;

use iridis_color::{Encoding, ToneMap, Xyz};

use crate::geometry::{eps, triangle_hit, Hit};
use crate::integrate::Surface;
use crate::light::Rgb;
use crate::material::{relative_azimuth, ColorSource, Material, Microfacet, ThinFilm};
use crate::math::*;
use crate::scene::Scene;

/// A rendered image: linear sRGB per pixel (D65 white = 1 at exposure 1), row 0 at the top.
#[derive(Debug, Clone)]
pub struct Image {
    pub width: u32,
    pub height: u32,
    pub data: Vec<[f32; 3]>,
}

/// A pixel's linear sRGB as CIE XYZ.
fn pixel_xyz(p: [f32; 3]) -> Xyz {
    Xyz::from_linear_srgb(p.map(f64::from))
}

impl Image {
    /// CIE XYZ of pixel `(col, row)` (before exposure).
    pub fn xyz(&self, col: u32, row: u32) -> Xyz {
        pixel_xyz(self.data[(row * self.width + col) as usize])
    }

    /// CIE XYZ of every pixel, row-major (before exposure).
    pub fn to_xyz(&self) -> Vec<Xyz> {
        self.data.iter().map(|&p| pixel_xyz(p)).collect()
    }

    /// 8-bit display pixels: colours × exposure (RU), clipped, encoded (PHYSICS.md, "Exposure").
    pub fn to_rgb8(&self, exposure: f64, encoding: Encoding) -> Vec<u8> {
        let tone = ToneMap { exposure_ru: exposure, encoding };
        self.data.iter().flat_map(|&p| tone.to_rgb8(pixel_xyz(p))).collect()
    }

    /// PNG bytes of the tone-mapped image.
    pub fn encode_png(&self, exposure: f64, encoding: Encoding) -> Result<Vec<u8>, crate::RenderError> {
        let img = image::RgbImage::from_raw(self.width, self.height, self.to_rgb8(exposure, encoding))
            .ok_or_else(|| crate::RenderError::Input("image size".into()))?;
        let mut out = std::io::Cursor::new(Vec::new());
        // Encoders by name, not `write_to(…, ImageFormat)`: that generic call compiles every encoder the `image`
        // crate has (TIFF, EXR, …) into this crate, twice.
        img.write_with_encoder(image::codecs::png::PngEncoder::new(&mut out))
            .map_err(|e| crate::RenderError::Input(format!("cannot encode PNG: {e}")))?;
        Ok(out.into_inner())
    }

    /// OpenEXR bytes: linear sRGB × exposure, unclipped (32-bit float).
    pub fn encode_exr(&self, exposure: f64) -> Result<Vec<u8>, crate::RenderError> {
        let data: Vec<f32> = self.data.iter().flat_map(|p| p.map(|c| c * exposure as f32)).collect();
        let img = image::Rgb32FImage::from_raw(self.width, self.height, data)
            .ok_or_else(|| crate::RenderError::Input("image size".into()))?;
        let mut out = std::io::Cursor::new(Vec::new());
        image::DynamicImage::ImageRgb32F(img)
            .write_with_encoder(image::codecs::openexr::OpenExrEncoder::new(&mut out))
            .map_err(|e| crate::RenderError::Input(format!("cannot encode EXR: {e}")))?;
        Ok(out.into_inner())
    }
}

/// The `s`-th of `n` sample positions inside a pixel (`[0, 1)²`): the centre for `n = 1`, else the R2
/// low-discrepancy sequence started at the centre.
pub fn sample_offset(s: u32, n: u32) -> (f64, f64) {
    if n <= 1 {
        return (0.5, 0.5);
    }
    const G1: f64 = 0.754_877_666_246_692_7;
    const G2: f64 = 0.569_840_290_998_053_2;
    ((0.5 + s as f64 * G1).fract(), (0.5 + s as f64 * G2).fract())
}

/// Renders `scene` at `width × height` with `spp` samples per pixel. `progress(rows_done)` is called as rows
/// finish (from worker threads).
pub fn render(scene: &Scene, width: u32, height: u32, spp: u32, progress: &(dyn Fn(usize) + Sync)) -> Image {
    let done = std::sync::atomic::AtomicUsize::new(0);
    let aspect = width as f64 / height as f64;
    let spp = spp.max(1);
    let rows: Vec<Vec<[f32; 3]>> = (0..height)
        .into_par_iter()
        .map(|row| {
            let out = (0..width)
                .map(|col| {
                    let mut acc = [0.0; 3];
                    for s in 0..spp {
                        crate::sampling::seed(
                            row as u64 * width as u64 + col as u64,
                            s as u64 ^ (scene.output.seed << 32),
                        );
                        let (jx, jy) = sample_offset(s, spp);
                        let x = -1.0 + 2.0 * (col as f64 + jx) / width as f64;
                        let y = 1.0 - 2.0 * (row as f64 + jy) / height as f64;
                        if let Some((o, d)) = scene.camera.ray(x, y, aspect) {
                            acc = add(acc, scene.primary(o, d));
                        }
                    }
                    mul(acc, 1.0 / spp as f64).map(|c| c as f32)
                })
                .collect();
            progress(done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1);
            out
        })
        .collect();
    Image { width, height, data: rows.into_iter().flatten().collect() }
}

/// What a camera ray meets on a diffraction material, in that material's local frame `(t, n × t, n)`: the
/// directions `iridis brdf-map` takes, so that a pixel's colour can be read off the BRDF map it comes from.
#[derive(Debug, Clone)]
pub struct LocalView {
    /// The material hit (a diffraction material).
    pub material: usize,
    /// Towards the camera.
    pub view: V3,
    /// Towards each light that reaches the point (the scene's lights, then the environment's), with its
    /// irradiance.
    pub lights: Vec<(V3, Rgb)>,
}

impl Scene {
    /// [`LocalView`] of the camera ray through `(x, y) ∈ [−1, 1]²`; `None` where it meets no diffraction
    /// material.
    pub fn local_view(&self, x: f64, y: f64, aspect: f64) -> Option<LocalView> {
        let (o, d) = self.camera.ray(x, y, aspect)?;
        let h = self.intersect(o, d, f64::INFINITY)?;
        let Material::Diffraction(df) = &self.materials[h.material] else { return None };
        let t = df.orientation.tangent(&h, &self.textures);
        let b = cross(h.n, t);
        let local = |v: V3| [dot(v, t), dot(v, b), dot(v, h.n)];
        let lights = self
            .lights_at(&h)
            .into_iter()
            .chain(self.environment_lights_at(&h))
            .map(|(wi, e, _)| (local(wi), e))
            .filter(|(wi, _)| wi[2] > 0.0)
            .collect();
        Some(LocalView { material: h.material, view: local(mul(d, -1.0)), lights })
    }

    /// The nearest surface along a ray.
    pub fn intersect(&self, o: V3, d: V3, t_max: f64) -> Option<Hit> {
        let mut best: Option<Hit> = None;
        let mut t_max = t_max;
        for s in &self.spheres {
            if let Some(h) = s.intersect(o, d, t_max) {
                t_max = h.t;
                best = Some(h);
            }
        }
        for p in &self.planes {
            if let Some(h) = p.intersect(o, d, t_max) {
                t_max = h.t;
                best = Some(h);
            }
        }
        if let Some((t, b1, b2, r)) = self.bvh.intersect(&self.meshes, o, d, t_max) {
            best = Some(triangle_hit(&self.meshes[r.mesh as usize], r.tri as usize, o, d, t, b1, b2));
        }
        best
    }

    /// Whether something opaque lies between `p` and a light `dist` away along `wi`.
    pub(crate) fn occluded(&self, p: V3, wi: V3, dist: f64) -> bool {
        let mut o = p;
        let mut left = dist;
        for _ in 0..16 {
            match self.intersect(o, wi, left) {
                None => return false,
                Some(h) if self.materials[h.material].transmissive() => {
                    o = add(h.p, mul(wi, eps(&h)));
                    left -= h.t;
                }
                Some(_) => return true,
            }
        }
        true
    }

    /// Radiance (linear sRGB, RU) seen along a camera ray.
    pub fn primary(&self, o: V3, d: V3) -> Rgb {
        let hit = self.intersect(o, d, f64::INFINITY);
        if let Some((_, k)) = self.hit_area_light(o, d, hit.as_ref().map_or(f64::INFINITY, |h| h.t), true) {
            return self.area_lights[k].radiance;
        }
        match hit {
            Some(h) => self.shade(&h, d, 0, 1.0),
            None if self.environment_visible => self.environment.radiance(d),
            None => self.output.background,
        }
    }

    /// Radiance along a secondary ray whose contribution to the pixel is at most `weight`: rays that cannot
    /// change the pixel by more than 1/500 (or past `max_depth`) take the environment's radiance instead.
    fn trace(&self, o: V3, d: V3, depth: u32, weight: f64) -> Rgb {
        if depth > self.output.max_depth || weight < 2e-3 {
            return self.environment.radiance(d);
        }
        let hit = self.intersect(o, d, f64::INFINITY);
        // Monte Carlo: a mirror's ray sees the area lights (the fast path lights surfaces by them directly).
        if self.monte_carlo() {
            if let Some((_, k)) = self.hit_area_light(o, d, hit.as_ref().map_or(f64::INFINITY, |h| h.t), false) {
                return self.area_lights[k].radiance;
            }
        }
        match hit {
            Some(h) => self.shade(&h, d, depth, weight),
            None => self.environment.radiance(d),
        }
    }

    /// Lights visible from a hit: (direction to the light, irradiance, solid angle). The directional and point
    /// lights (solid angle 0) and, on the fast path, each area light as one light from its centre with its
    /// irradiance ([`crate::area::Shape::representative`]); Monte Carlo samples area lights instead.
    fn lights_at(&self, h: &Hit) -> Vec<(V3, Rgb, f64)> {
        let o = add(h.p, mul(h.ng, eps(h)));
        let mut out: Vec<(V3, Rgb, f64)> = self
            .lights
            .iter()
            .filter_map(|l| {
                let (wi, dist, e) = l.arrive(h.p);
                (dot(wi, h.ng) > 0.0 && !self.occluded(o, wi, dist)).then_some((wi, e, 0.0))
            })
            .collect();
        if !self.monte_carlo() {
            for l in &self.area_lights {
                let Some(r) = l.shape.representative(h.p) else { continue };
                if dot(r.wi, h.ng) > 0.0 && !self.occluded(o, r.wi, r.dist) {
                    out.push((r.wi, mul(l.radiance, r.e_per_radiance), r.solid_angle));
                }
            }
        }
        out
    }

    /// The environment's directional lights ([`Scene::environment_lights`]) above a hit's surface. Like the
    /// irradiance map, they are not shadowed: the environment is light from far away, open sky.
    fn environment_lights_at(&self, h: &Hit) -> impl Iterator<Item = (V3, Rgb, f64)> + '_ {
        let ng = h.ng;
        let omega = crate::light::ENVIRONMENT_LIGHT_SPREAD * 4.0 * std::f64::consts::PI
            / self.environment_lights.len().max(1) as f64;
        self.environment_lights.iter().filter(move |(wi, _)| dot(*wi, ng) > 0.0).map(move |&(wi, e)| (wi, e, omega))
    }

    fn color(&self, c: &ColorSource, uv: [f64; 2]) -> Rgb {
        c.at(uv, &self.textures)
    }

    /// `E(n)/π` of the environment: what a white Lambertian surface with normal `n` reflects of it.
    pub fn irradiance(&self, n: V3) -> Rgb {
        self.environment.irradiance(self.irradiance.as_ref(), n)
    }

    fn shade_microfacet(&self, m: &Microfacet, h: &Hit, wo: V3, depth: u32, weight: f64, with_env: bool) -> Rgb {
        let albedo = self.color(&m.color, h.uv);
        let mut out = [0.0; 3];
        for (wi, e, _) in self.lights_at(h) {
            out = add(out, hadamard(m.reflect(h.n, wi, wo, albedo), e));
        }
        if self.monte_carlo() {
            let s = Surface::microfacet(*m, h.n, albedo, dot(h.n, wo).clamp(0.0, 1.0));
            return add(out, self.extended_light(h, &s, wo, depth, weight));
        }
        // Environment light: the diffuse lobe takes the irradiance around the normal, the specular lobes their
        // directional albedo of the light along the mirror direction, blurred towards the irradiance around
        // that direction with roughness (a uniform environment comes back exactly: the white furnace).
        let (spec, diffuse) = m.env_weights(dot(h.n, wo).clamp(0.0, 1.0), albedo);
        out = add(out, hadamard(diffuse, self.irradiance(h.n)));
        if with_env {
            let r = reflect(wo, h.n);
            let blurred = self.irradiance(r);
            let mirror = if m.roughness < 0.6 && depth < self.output.max_depth {
                self.trace(
                    add(h.p, mul(h.ng, eps(h))),
                    r,
                    depth + 1,
                    weight * spec.iter().fold(0.0f64, |a, &b| a.max(b)),
                )
            } else {
                blurred
            };
            let rough = (m.roughness / 0.6).min(1.0);
            let l = [0, 1, 2].map(|k| mirror[k] * (1.0 - rough) + blurred[k] * rough);
            out = add(out, hadamard(spec, l));
        }
        out
    }

    pub(crate) fn shade(&self, h: &Hit, d: V3, depth: u32, weight: f64) -> Rgb {
        let wo = mul(d, -1.0);
        // A glTF normal texture (on the surface or on a film's base) replaces the shading normal first.
        let mapped = match &self.materials[h.material] {
            Material::Microfacet(m) => m.normal_at(h, &self.textures),
            Material::ThinFilm(f) => f.base.map_or(*h, |b| b.normal_at(h, &self.textures)),
            _ => *h,
        };
        let h = &mapped;
        match &self.materials[h.material] {
            Material::Lambert { color } => {
                let albedo = self.color(color, h.uv);
                let mut out = if self.monte_carlo() {
                    self.extended_light(h, &Surface::Lambert { n: h.n, albedo }, wo, depth, weight)
                } else {
                    hadamard(albedo, self.irradiance(h.n))
                };
                for (wi, e, _) in self.lights_at(h) {
                    out = add(out, mul(hadamard(albedo, e), dot(h.n, wi).max(0.0)));
                }
                out
            }
            Material::Microfacet(m) => self.shade_microfacet(&m.at(h.uv, &self.textures), h, wo, depth, weight, true),
            Material::Diffraction(df) => {
                let t = df.orientation.tangent(h, &self.textures);
                let tex = self.color(&df.texture, h.uv);
                let mut out = mul(tex, df.ambient);
                if self.monte_carlo() {
                    for (wi, e, _) in self.lights_at(h) {
                        out = add(out, df.shade_light(h, t, wi, wo, e, tex));
                    }
                    let b = cross(h.n, t);
                    let s = Surface::Diffraction { df, hit: *h, t, b, tex };
                    return add(out, self.extended_light(h, &s, wo, depth, weight));
                }
                // Lights; a light with a solid angle (an area light) sees the lobe averaged over it.
                for (wi, e, omega) in self.lights_at(h) {
                    out = add(out, df.shade_light_filtered(h, t, wi, wo, e, tex, omega));
                }
                // The environment as directional lights for the lobe (and for Algorithm 4's texture); the
                // energy blend's texture takes the irradiance around the normal.
                for (wi, e, omega) in self.environment_lights_at(h) {
                    out = add(out, df.shade_environment_light(h, t, wi, wo, e, tex, omega));
                }
                add(out, df.environment_diffuse(h, t, wo, tex, self.irradiance(h.n)))
            }
            Material::ThinFilm(f) => {
                let cos = dot(h.n, wo).clamp(0.0, 1.0);
                let offset = f.offset_nm(h.uv, &self.textures);
                let mut out = [0.0; 3];
                let (r, t) = if f.rough.is_some() {
                    // Eq. 3.20: the diffuse part π·k_d·cos θ_l per RU of irradiance, for every light; the
                    // environment lights it as it lights a microfacet's diffuse lobe, the film's diffuse
                    // directional albedo times the irradiance around the normal (the specular part follows the
                    // mirror ray below).
                    let lights = self.lights_at(h);
                    let dirs: Vec<(f64, f64)> =
                        lights.iter().map(|(wi, _, _)| (dot(h.n, *wi), relative_azimuth(h.n, *wi, wo))).collect();
                    let (spec, diffuse) = f.rough_colors_tabulated(cos, offset, &dirs).unwrap_or_default();
                    for (((_, e, _), (cos_l, _)), d) in lights.iter().zip(&dirs).zip(&diffuse) {
                        out = add(out, mul(hadamard(d.to_linear_srgb(), *e), cos_l.max(0.0) * f.factor));
                    }
                    if self.monte_carlo() {
                        let s = Surface::RoughDiffuse { film: f, n: h.n, cos_o: cos, offset };
                        out = add(out, self.extended_light(h, &s, wo, depth, weight));
                    } else if let Some(a) = f.rough_env_diffuse(cos, offset) {
                        out = add(out, mul(hadamard(a.to_linear_srgb(), self.irradiance(h.n)), f.factor));
                    }
                    (spec, Xyz::default())
                } else {
                    f.colors(cos, offset)
                };
                if let Some(base) = &f.base {
                    let base = base.at(h.uv, &self.textures);
                    return add(out, self.shade_film_over_base(f, &base, h, wo, r, offset, depth, weight));
                }
                let r_rgb = mul(r.to_linear_srgb(), f.factor);
                let w_r = weight * r_rgb.iter().fold(0.0f64, |a, &b| a.max(b));
                let refl = self.trace(add(h.p, mul(h.ng, eps(h))), reflect(wo, h.n), depth + 1, w_r);
                out = add(out, hadamard(r_rgb, refl));
                if f.transmission {
                    let t_rgb = mul(t.to_linear_srgb(), f.factor);
                    let w_t = weight * t_rgb.iter().fold(0.0f64, |a, &b| a.max(b));
                    let through = self.trace(add(h.p, mul(h.ng, -eps(h))), d, depth + 1, w_t);
                    out = add(out, hadamard(t_rgb, through));
                }
                out
            }
        }
    }

    /// A smooth film over a base material (glTF `KHR_materials_iridescence`, oil over asphalt): the film's
    /// reflectance `R` (spectral, at the angle of incidence on the microfacet) takes the place of the base's
    /// specular Fresnel, and the base's diffuse lobe takes what the film does not reflect, per channel as the
    /// glTF BRDF's `mix(diffuse, specular, F)`: lights give the GGX lobe `D G / (4 cos θ_i cos θ_o) · R(v·h)`
    /// plus `(1 − R(v·h)) ρ_d cos θ_i`, the environment `R(cos θ_o)` along the mirror (blurred with roughness)
    /// plus `(1 − R(cos θ_o)) ρ_d E(n)/π`. A metallic base (`metallic` m) takes `(1 − m) R + m R_metal`, with
    /// `R_metal` the film over the metal ([`ThinFilm::metal_stack`]), as its specular and `(1 − m) ρ` as its
    /// diffuse albedo. `iridescenceFactor` mixes this with the base alone.
    #[allow(clippy::too_many_arguments)]
    fn shade_film_over_base(
        &self,
        f: &ThinFilm,
        base: &Microfacet,
        h: &Hit,
        wo: V3,
        r_view: Xyz,
        offset: f64,
        depth: u32,
        weight: f64,
    ) -> Rgb {
        let fac = f.factor;
        let mut out = [0.0; 3];
        if self.monte_carlo() {
            // The film over the base and the base alone, mixed by the factor, as one BRDF for every light.
            let albedo = self.color(&base.color, h.uv);
            let s = Surface::film_over_base(f, *base, h.n, albedo, offset, dot(h.n, wo).clamp(0.0, 1.0));
            for (wi, e, _) in self.lights_at(h) {
                out = add(out, hadamard(s.eval(wi, wo), e));
            }
            return add(out, self.extended_light(h, &s, wo, depth, weight));
        }
        if fac < 1.0 {
            let below = self.shade_microfacet(base, h, wo, depth, weight * (1.0 - fac), true);
            out = mul(below, 1.0 - fac);
        }
        if fac <= 0.0 {
            return out;
        }
        let albedo = self.color(&base.color, h.uv);
        let m = base.metallic;
        let diffuse = mul(albedo, 1.0 - m);
        // The specular reflectance: the film over the dielectric, mixed with the film over the metal.
        let refl = |cos: f64, dielectric: Xyz| -> (Rgb, Rgb) {
            let d = dielectric.to_linear_srgb();
            let metal = f.metal_color(cos, offset).map(|x| x.to_linear_srgb()).unwrap_or(d);
            ([0, 1, 2].map(|k| (1.0 - m) * d[k] + m * metal[k]), d)
        };
        let mut film = [0.0; 3];
        for (wi, e, _) in self.lights_at(h) {
            film = add(film, hadamard(e, f.over_base_light(base, albedo, h.n, wi, wo, offset)));
        }
        let (r, d) = refl(dot(h.n, wo).clamp(0.0, 1.0), r_view);
        film = add(film, hadamard(hadamard(d.map(|x| 1.0 - x), diffuse), self.irradiance(h.n)));
        let dir = reflect(wo, h.n);
        let blurred = self.irradiance(dir);
        let rough = (base.roughness / 0.6).min(1.0);
        let mirror = if base.roughness < 0.6 {
            let w = weight * fac * r.iter().fold(0.0f64, |a, &b| a.max(b));
            self.trace(add(h.p, mul(h.ng, eps(h))), dir, depth + 1, w)
        } else {
            blurred
        };
        let l = [0, 1, 2].map(|k| mirror[k] * (1.0 - rough) + blurred[k] * rough);
        add(out, mul(add(film, hadamard(r, l)), fac))
    }
}
