//! Textures: images (colour, grey, vector) and procedural patterns (noise for SVT, a drainage gradient, snake
//! scales, a checker board). `uv = (0, 0)` is the top-left corner of an image (the glTF convention); UVs repeat.

use std::path::Path;

use crate::error::RenderError;

/// What a texture holds; materials ask for one kind and refuse the others.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TexKind {
    /// Linear RGB colours (PNG/JPEG-style 8-bit files are sRGB-decoded).
    Color,
    /// One value in `[0, 1]` per texel (thickness maps, masks): a single-channel image or a procedural field.
    Grey,
    /// A direction in tangent space, `xy = 2·rg − 1` (like a normal map), for orientation fields.
    Vector,
    /// Linear RGB data, read as stored (glTF's metallic-roughness texture: G roughness, B metallic).
    Data,
}

impl TexKind {
    pub fn parse(s: &str) -> Option<Self> {
        match s {
            "color" | "colour" => Some(TexKind::Color),
            "grey" | "gray" | "scalar" => Some(TexKind::Grey),
            "vector" => Some(TexKind::Vector),
            _ => None,
        }
    }
    pub fn name(self) -> &'static str {
        match self {
            TexKind::Color => "color",
            TexKind::Grey => "grey",
            TexKind::Vector => "vector",
            TexKind::Data => "data",
        }
    }
}

/// A texture ready for sampling.
#[derive(Debug, Clone, PartialEq)]
pub enum Texture {
    /// An image: `channels` values per texel (1–4), linear, row 0 at the top.
    Image { width: usize, height: usize, channels: usize, data: Vec<f32>, kind: TexKind, name: String },
    /// Fractal value noise in `[0, 1]` (`octaves` octaves, base frequency `scale` per UV unit).
    Noise { scale: f64, octaves: u32, seed: u32 },
    /// `from + (to − from) · v` (or along u): a film that drains, thin at the top and thick at the bottom.
    Gradient { from: f64, to: f64, along_u: bool },
    /// Overlapping rows of scales (colour): `base` in the middle of a scale, `edge` at its rim.
    Scales { base: [f64; 3], edge: [f64; 3] },
    /// A checker board of `n × n` squares per UV unit.
    Checker { a: [f64; 3], b: [f64; 3], n: f64 },
}

impl Texture {
    pub fn kind(&self) -> TexKind {
        match self {
            Texture::Image { kind, .. } => *kind,
            Texture::Noise { .. } | Texture::Gradient { .. } => TexKind::Grey,
            Texture::Scales { .. } | Texture::Checker { .. } => TexKind::Color,
        }
    }

    /// Loads an image file as a texture of `kind`, refusing images that do not fit the kind: a colour image
    /// where a grey one is needed, a grey image for a vector field.
    pub fn load(path: &Path, kind: TexKind) -> Result<Self, RenderError> {
        let bytes = std::fs::read(path)
            .map_err(|e| RenderError::Input(format!("cannot open texture {}: {e}", path.display())))?;
        // As `ImageReader::open` reads a file: the format from the content, else from the extension.
        let mut reader = image::ImageReader::new(std::io::Cursor::new(bytes.as_slice()));
        if let Ok(format) = image::ImageFormat::from_path(path) {
            reader.set_format(format);
        }
        let reader = reader
            .with_guessed_format()
            .map_err(|e| RenderError::Input(format!("cannot read texture {}: {e}", path.display())))?;
        let img = iridis_surface::formats::raster::decode(reader).map_err(|e| {
            RenderError::Input(format!(
                "texture {} is not a readable image ({e}); use PNG, TIFF, EXR or HDR",
                path.display()
            ))
        })?;
        Self::from_image(img, kind, &path.display().to_string())
    }

    pub fn from_image(img: image::DynamicImage, kind: TexKind, name: &str) -> Result<Self, RenderError> {
        use image::ColorType as C;
        let ct = img.color();
        let float = matches!(ct, C::Rgb32F | C::Rgba32F);
        let has_color = ct.has_color();
        let (width, height) = (img.width() as usize, img.height() as usize);
        if width == 0 || height == 0 {
            return Err(RenderError::Input(format!("texture {name} is empty")));
        }
        let data: Vec<f32> = match kind {
            TexKind::Grey => {
                if has_color {
                    let rgb = img.to_rgb32f();
                    let mixed = rgb.pixels().any(|p| (p[0] - p[1]).abs() > 1e-3 || (p[1] - p[2]).abs() > 1e-3);
                    if mixed {
                        return Err(RenderError::Input(format!(
                            "texture {name} is a colour image, but a grey texture (thickness or mask) is needed: \
                             save it as a single-channel (L) image, or declare it kind = \"color\" where a colour \
                             is wanted"
                        )));
                    }
                    rgb.pixels().map(|p| p[0]).collect()
                } else {
                    // Grey values are stored linearly (a thickness fraction, not a displayed colour).
                    img.to_luma32f().into_raw()
                }
            }
            TexKind::Data => img.to_rgb32f().into_raw(),
            TexKind::Vector => {
                if !has_color {
                    return Err(RenderError::Input(format!(
                        "texture {name} is a grey image, but an orientation (vector) texture needs RGB: \
                         x = 2R − 1 and y = 2G − 1 in tangent space"
                    )));
                }
                img.to_rgb32f().into_raw()
            }
            TexKind::Color => {
                let rgb = img.to_rgb32f();
                if float {
                    rgb.into_raw()
                } else {
                    rgb.into_raw().into_iter().map(|v| iridis_color::convert::srgb_decode(v as f64) as f32).collect()
                }
            }
        };
        let channels = match kind {
            TexKind::Grey => 1,
            _ => 3,
        };
        Ok(Texture::Image { width, height, channels, data, kind, name: name.to_string() })
    }

    /// The texture at `uv` (bilinear, repeating): RGB for colour and vector textures, `[a, a, a]` for grey ones.
    pub fn sample(&self, uv: [f64; 2]) -> [f64; 3] {
        self.sample_with(uv, false)
    }

    /// As [`Texture::sample`], with `clamp_v` holding `v` at the first and last rows instead of repeating (the
    /// poles of an equirectangular map must not blend with each other).
    pub fn sample_with(&self, uv: [f64; 2], clamp_v: bool) -> [f64; 3] {
        match self {
            Texture::Image { width, height, channels, data, .. } => {
                let x = uv[0].rem_euclid(1.0) * *width as f64 - 0.5;
                let v = if clamp_v { uv[1].clamp(0.0, 1.0) } else { uv[1].rem_euclid(1.0) };
                let y = v * *height as f64 - 0.5;
                let (x0, y0) = (x.floor(), y.floor());
                let (fx, fy) = (x - x0, y - y0);
                let wrap = |i: f64, n: usize| (i as i64).rem_euclid(n as i64) as usize;
                let mut out = [0.0; 3];
                for (dy, wy) in [(0.0, 1.0 - fy), (1.0, fy)] {
                    for (dx, wx) in [(0.0, 1.0 - fx), (1.0, fx)] {
                        let r = if clamp_v {
                            (y0 + dy).clamp(0.0, (*height - 1) as f64) as usize
                        } else {
                            wrap(y0 + dy, *height)
                        };
                        let c = wrap(x0 + dx, *width);
                        let base = (r * width + c) * channels;
                        for (k, o) in out.iter_mut().enumerate() {
                            *o += wx * wy * data[base + k.min(channels - 1)] as f64;
                        }
                    }
                }
                out
            }
            Texture::Noise { scale, octaves, seed } => {
                let a = fbm(uv[0] * scale, uv[1] * scale, *octaves, *seed);
                [a; 3]
            }
            Texture::Gradient { from, to, along_u } => {
                let s = if *along_u { uv[0] } else { uv[1] }.clamp(0.0, 1.0);
                [from + (to - from) * s; 3]
            }
            Texture::Scales { base, edge } => {
                // Rows of overlapping round scales, alternate rows offset by half a scale.
                let row = uv[1].floor();
                let x = uv[0] + if row.rem_euclid(2.0) == 1.0 { 0.5 } else { 0.0 };
                let (fx, fy) = (x.rem_euclid(1.0) - 0.5, uv[1].rem_euclid(1.0) - 0.5);
                let r = (fx * fx + fy * fy).sqrt() * 2.0;
                let t = ((r - 0.55) / 0.45).clamp(0.0, 1.0).powf(1.5);
                [0, 1, 2].map(|k| base[k] + (edge[k] - base[k]) * t)
            }
            Texture::Checker { a, b, n } => {
                let s = ((uv[0] * n).floor() + (uv[1] * n).floor()).rem_euclid(2.0);
                if s == 0.0 {
                    *a
                } else {
                    *b
                }
            }
        }
    }
}

fn hash(x: i64, y: i64, seed: u32) -> f64 {
    let mut h = (x as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15)
        ^ (y as u64).wrapping_mul(0xC2B2_AE3D_27D4_EB4F)
        ^ (seed as u64).wrapping_mul(0x1656_67B1_9E37_79F9);
    h ^= h >> 33;
    h = h.wrapping_mul(0xFF51_AFD7_ED55_8CCD);
    h ^= h >> 33;
    (h >> 11) as f64 / (1u64 << 53) as f64
}

fn value_noise(x: f64, y: f64, seed: u32) -> f64 {
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = (x - x0, y - y0);
    let s = |t: f64| t * t * (3.0 - 2.0 * t);
    let (sx, sy) = (s(fx), s(fy));
    let (i, j) = (x0 as i64, y0 as i64);
    let a = hash(i, j, seed) + (hash(i + 1, j, seed) - hash(i, j, seed)) * sx;
    let b = hash(i, j + 1, seed) + (hash(i + 1, j + 1, seed) - hash(i, j + 1, seed)) * sx;
    a + (b - a) * sy
}

/// Fractal value noise normalised to `[0, 1]`.
pub fn fbm(x: f64, y: f64, octaves: u32, seed: u32) -> f64 {
    let (mut sum, mut amp, mut norm, mut f) = (0.0, 1.0, 0.0, 1.0);
    for o in 0..octaves.max(1) {
        sum += amp * value_noise(x * f, y * f, seed.wrapping_add(o * 7919));
        norm += amp;
        amp *= 0.5;
        f *= 2.0;
    }
    sum / norm
}
