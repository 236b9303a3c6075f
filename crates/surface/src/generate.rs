//! Synthetic nanostructures, reproducible from a seed, on a grid of given physical size and pixel size,
//! rotated by an orientation angle. Iridis ships no measured AFM scans, so these stand in for them; the
//! biological ones follow the descriptions in Dhillon et al. 2014 (sec. 6.1, Figures 5 and 12).
//!
//! Frame: the pattern is built in a local frame `(u, v)` rotated by `angle` counter-clockwise from the
//! surface frame `(x right, y up)`, about the patch centre: `u = x cos a + y sin a`, `v = −x sin a + y cos a`.
//! Gratings vary along `u` (their grating vector points along `angle`); nanofingers and CD tracks run along
//! `u` (the tangent `t` of PHYSICS.md) and repeat along `v`.

use std::f64::consts::{PI, TAU};

use crate::rng::Rng;
use crate::{check_dims, check_pixel, HeightField, Metadata, SurfaceError};

/// Physical size, resolution, orientation and seed shared by all generators.
#[derive(Debug, Clone, PartialEq)]
pub struct Grid {
    pub size_x_nm: f64,
    pub size_y_nm: f64,
    pub pixel_nm: f64,
    /// Counter-clockwise rotation of the pattern (radians).
    pub angle_rad: f64,
    pub seed: u64,
}

impl Default for Grid {
    /// The paper's patch: 65 µm (the coherence length) at 65 nm per pixel, 1000 × 1000 samples.
    fn default() -> Self {
        Self { size_x_nm: 65_000.0, size_y_nm: 65_000.0, pixel_nm: 65.0, angle_rad: 0.0, seed: 1 }
    }
}

impl Grid {
    /// `(rows, cols)`, validated before anything is allocated.
    pub fn dims(&self) -> Result<(usize, usize), SurfaceError> {
        check_pixel(self.pixel_nm, self.pixel_nm)?;
        for (n, v) in [("size x", self.size_x_nm), ("size y", self.size_y_nm)] {
            if !(v.is_finite() && v > 0.0) {
                return Err(SurfaceError::invalid(format!("{n} = {v} nm: it must be a finite positive length")));
            }
        }
        if !self.angle_rad.is_finite() {
            return Err(SurfaceError::invalid("the orientation angle must be finite"));
        }
        let cols = (self.size_x_nm / self.pixel_nm).round();
        let rows = (self.size_y_nm / self.pixel_nm).round();
        // A generated field is made to measure: the way out is a larger pixel or a smaller patch (there is
        // nothing to crop or resample yet).
        if cols > crate::MAX_DIM as f64 || rows > crate::MAX_DIM as f64 || rows * cols > crate::MAX_SAMPLES as f64 {
            return Err(SurfaceError::invalid(format!(
                "{:.0} × {:.0} samples is too large (at most {} per axis and {} in all); use a larger pixel or a \
                 smaller size",
                rows,
                cols,
                crate::MAX_DIM,
                crate::MAX_SAMPLES
            )));
        }
        let (rows, cols) = (rows as usize, cols as usize);
        check_dims(rows, cols)?;
        Ok((rows, cols))
    }

    /// Half the patch diagonal plus a margin: the radius the local-frame pattern must cover.
    fn radius(&self) -> f64 {
        0.5 * self.size_x_nm.hypot(self.size_y_nm) + 2.0 * self.pixel_nm
    }

    fn frame(&self) -> Frame {
        let (rows, cols) = self.dims().unwrap_or((2, 2));
        Frame {
            rows,
            cols,
            d: self.pixel_nm,
            cos: self.angle_rad.cos(),
            sin: self.angle_rad.sin(),
            cx: (cols as f64 - 1.0) / 2.0,
            cy: (rows as f64 - 1.0) / 2.0,
        }
    }
}

/// Pixel ↔ local `(u, v)` coordinates.
#[derive(Debug, Clone, Copy)]
struct Frame {
    rows: usize,
    cols: usize,
    d: f64,
    cos: f64,
    sin: f64,
    cx: f64,
    cy: f64,
}

impl Frame {
    #[inline]
    fn uv(&self, row: usize, col: usize) -> (f64, f64) {
        let x = (col as f64 - self.cx) * self.d;
        let y = (self.cy - row as f64) * self.d;
        (x * self.cos + y * self.sin, -x * self.sin + y * self.cos)
    }
    /// Fractional (row, col) of a local point.
    fn pixel(&self, u: f64, v: f64) -> (f64, f64) {
        let x = u * self.cos - v * self.sin;
        let y = u * self.sin + v * self.cos;
        (self.cy - y / self.d, x / self.d + self.cx)
    }
    /// Pixel bounding box (inclusive) of a local rectangle, clipped to the grid; `None` when outside.
    fn bbox(&self, u0: f64, u1: f64, v0: f64, v1: f64) -> Option<(usize, usize, usize, usize)> {
        let pts = [self.pixel(u0, v0), self.pixel(u0, v1), self.pixel(u1, v0), self.pixel(u1, v1)];
        let rmin = pts.iter().map(|p| p.0).fold(f64::INFINITY, f64::min).floor().max(0.0);
        let rmax = pts.iter().map(|p| p.0).fold(f64::NEG_INFINITY, f64::max).ceil();
        let cmin = pts.iter().map(|p| p.1).fold(f64::INFINITY, f64::min).floor().max(0.0);
        let cmax = pts.iter().map(|p| p.1).fold(f64::NEG_INFINITY, f64::max).ceil();
        if rmax < 0.0 || cmax < 0.0 || rmin > (self.rows - 1) as f64 || cmin > (self.cols - 1) as f64 {
            return None;
        }
        Some((rmin as usize, (rmax as usize).min(self.rows - 1), cmin as usize, (cmax as usize).min(self.cols - 1)))
    }
    fn fill(&self, f: impl Fn(f64, f64) -> f64) -> Vec<f64> {
        let mut h = Vec::with_capacity(self.rows * self.cols);
        for r in 0..self.rows {
            for c in 0..self.cols {
                let (u, v) = self.uv(r, c);
                h.push(f(u, v));
            }
        }
        h
    }
}

/// Bump profile for [`Generator::Bumps`] (Stam 1999's "periodic-like" bumps; paper Figure 11).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BumpShape {
    /// A box: flat top, vertical walls.
    Rect,
    /// A pyramid with the same footprint (the paper's triangular bump).
    Tri,
}

/// A nanostructure and its parameters (lengths in nm).
#[derive(Debug, Clone, PartialEq)]
pub enum Generator {
    /// `h = depth/2 · sin(2π u / period)`.
    Sine { period_nm: f64, depth_nm: f64 },
    /// Saw-tooth: `h = depth · frac(u / period)`, rising along `+u`, so at angle 0 the facets face `−x`
    /// (PHYSICS.md); blaze angle `atan(depth / period)`.
    Blazed { period_nm: f64, depth_nm: f64 },
    /// Bumps on a rectangular lattice; footprint `fill × period` in each direction, height `depth`.
    Bumps { shape: BumpShape, period_u_nm: f64, period_v_nm: f64, fill: f64, depth_nm: f64 },
    /// A CD: tracks along `u`, `pitch` apart in `v`; pits `pit_width` wide and `depth` deep, pits and lands
    /// each `3T..=11T` long (EFM run lengths, T = channel bit length).
    Cd { pitch_nm: f64, bit_nm: f64, pit_width_nm: f64, depth_nm: f64 },
    /// Isotropic Gaussian random surface with correlation `rms² exp(−r²/corr²)`, periodic (tiles seamlessly).
    Gaussian { rms_nm: f64, corr_nm: f64 },
    /// Elaphe-like: rows of nanofingers along `u` about `spacing` apart in `v`, each row two overlapping
    /// layers of fingers of random length (no period along the fingers); scaled to `rms` height.
    Elaphe { spacing_nm: f64, finger_nm: f64, rms_nm: f64 },
    /// Xenopeltis-like: fingers `along` long end to end and `across` apart, curving with local
    /// consistency; sub-regions (grains ≈ 15 µm) with slightly different periods.
    Xenopeltis { along_nm: f64, across_nm: f64, depth_nm: f64 },
}

/// Blaze angle (rad) → saw-tooth depth for a period: `depth = period · tan β`.
pub fn blazed_depth(period_nm: f64, blaze_rad: f64) -> f64 {
    period_nm * blaze_rad.tan()
}

/// A generator's length (nm) that must be finite and positive.
fn positive(name: &str, v: f64) -> Result<(), SurfaceError> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(SurfaceError::invalid(format!("{name} = {v} nm: it must be a finite positive length")))
    }
}

impl Generator {
    /// The short name used on the command line.
    pub fn kind(&self) -> &'static str {
        match self {
            Generator::Sine { .. } => "sine",
            Generator::Blazed { .. } => "blazed",
            Generator::Bumps { shape: BumpShape::Rect, .. } => "rect-bumps",
            Generator::Bumps { shape: BumpShape::Tri, .. } => "tri-bumps",
            Generator::Cd { .. } => "cd",
            Generator::Gaussian { .. } => "gaussian",
            Generator::Elaphe { .. } => "elaphe",
            Generator::Xenopeltis { .. } => "xenopeltis",
        }
    }

    /// Whether the seed shapes this structure: the regular gratings and lattices have no randomness (a seed
    /// given for one would change nothing).
    pub fn is_random(&self) -> bool {
        match self {
            Generator::Sine { .. } | Generator::Blazed { .. } | Generator::Bumps { .. } => false,
            Generator::Cd { .. }
            | Generator::Gaussian { .. }
            | Generator::Elaphe { .. }
            | Generator::Xenopeltis { .. } => true,
        }
    }

    /// The generator and its grid as a person writes them in a built-in's query string, e.g.
    /// `sine period=1100nm depth=100nm size=8um pixel=50nm angle=0deg` (`seed=1` after it for a random one).
    pub fn describe(&self, grid: &Grid) -> String {
        use iridis_color::units::{format_angle, format_length as len};
        let params = match *self {
            Generator::Sine { period_nm, depth_nm } | Generator::Blazed { period_nm, depth_nm } => {
                format!("period={} depth={}", len(period_nm), len(depth_nm))
            }
            Generator::Bumps { period_u_nm, period_v_nm, fill, depth_nm, .. } => format!(
                "period-x={} period-y={} fill={fill} depth={}",
                len(period_u_nm),
                len(period_v_nm),
                len(depth_nm)
            ),
            Generator::Cd { pitch_nm, bit_nm, pit_width_nm, depth_nm } => format!(
                "pitch={} bit={} pit-width={} depth={}",
                len(pitch_nm),
                len(bit_nm),
                len(pit_width_nm),
                len(depth_nm)
            ),
            Generator::Gaussian { rms_nm, corr_nm } => format!("rms={} corr={}", len(rms_nm), len(corr_nm)),
            Generator::Elaphe { spacing_nm, finger_nm, rms_nm } => {
                format!("spacing={} finger={} rms={}", len(spacing_nm), len(finger_nm), len(rms_nm))
            }
            Generator::Xenopeltis { along_nm, across_nm, depth_nm } => {
                format!("along={} across={} depth={}", len(along_nm), len(across_nm), len(depth_nm))
            }
        };
        let size = if grid.size_x_nm == grid.size_y_nm {
            format!("size={}", len(grid.size_x_nm))
        } else {
            format!("size-x={} size-y={}", len(grid.size_x_nm), len(grid.size_y_nm))
        };
        // The seed only where it shapes the structure: the line reads back as a query string, which refuses
        // a seed for a grating.
        let seed = if self.is_random() { format!(" seed={}", grid.seed) } else { String::new() };
        format!(
            "{} {params} {size} pixel={} angle={}{seed}",
            self.kind(),
            len(grid.pixel_nm),
            format_angle(grid.angle_rad)
        )
    }

    fn validate(&self, grid: &Grid) -> Result<(), SurfaceError> {
        let px = grid.pixel_nm;
        let period_ok = |name: &str, p: f64| -> Result<(), SurfaceError> {
            positive(name, p)?;
            if p < 2.0 * px {
                return Err(SurfaceError::invalid(format!(
                    "{name} {p} nm is shorter than two pixels ({} nm): it cannot be sampled; use a finer pixel",
                    2.0 * px
                )));
            }
            Ok(())
        };
        match *self {
            Generator::Sine { period_nm, depth_nm } | Generator::Blazed { period_nm, depth_nm } => {
                period_ok("period", period_nm)?;
                positive("depth", depth_nm)
            }
            Generator::Bumps { period_u_nm, period_v_nm, fill, depth_nm, .. } => {
                period_ok("period x", period_u_nm)?;
                period_ok("period y", period_v_nm)?;
                if !(fill > 0.0 && fill <= 1.0) {
                    return Err(SurfaceError::invalid(format!("fill = {fill}: it must be in (0, 1]")));
                }
                positive("depth", depth_nm)
            }
            Generator::Cd { pitch_nm, bit_nm, pit_width_nm, depth_nm } => {
                period_ok("track pitch", pitch_nm)?;
                positive("bit length", bit_nm)?;
                // The shortest pit or land is 3 bits (EFM's 3T): that must span two pixels to be sampled.
                if 3.0 * bit_nm < 2.0 * px {
                    return Err(SurfaceError::invalid(format!(
                        "bit length {bit_nm} nm: the shortest pit (3 bits, {} nm) is shorter than two pixels ({} nm); \
                         use a finer pixel",
                        3.0 * bit_nm,
                        2.0 * px
                    )));
                }
                positive("pit width", pit_width_nm)?;
                if pit_width_nm >= pitch_nm {
                    return Err(SurfaceError::invalid("pit width must be smaller than the track pitch"));
                }
                positive("depth", depth_nm)
            }
            Generator::Gaussian { rms_nm, corr_nm } => {
                positive("rms", rms_nm)?;
                positive("correlation length", corr_nm)
            }
            Generator::Elaphe { spacing_nm, finger_nm, rms_nm } => {
                period_ok("finger spacing", spacing_nm)?;
                period_ok("finger length", finger_nm)?;
                positive("rms", rms_nm)
            }
            Generator::Xenopeltis { along_nm, across_nm, depth_nm } => {
                period_ok("period along", along_nm)?;
                period_ok("period across", across_nm)?;
                positive("depth", depth_nm)
            }
        }
    }

    /// The relief's height scale as asked: its depth, or its rms for the random surfaces.
    fn height_scale_nm(&self) -> f64 {
        match *self {
            Generator::Sine { depth_nm, .. }
            | Generator::Blazed { depth_nm, .. }
            | Generator::Bumps { depth_nm, .. }
            | Generator::Cd { depth_nm, .. }
            | Generator::Xenopeltis { depth_nm, .. } => depth_nm,
            Generator::Gaussian { rms_nm, .. } | Generator::Elaphe { rms_nm, .. } => rms_nm,
        }
    }

    /// A field that came out flat (within a millionth of its asked depth or rms) is refused: its lengths do not
    /// fit the patch (a period or correlation length far beyond it), and a flat field would diffract nothing.
    fn refuse_flat(&self, heights: &[f64], grid: &Grid) -> Result<(), SurfaceError> {
        let (lo, hi) = heights.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &h| (lo.min(h), hi.max(h)));
        if hi - lo > 1e-6 * self.height_scale_nm() {
            return Ok(());
        }
        Err(SurfaceError::invalid(format!(
            "the generated {} is flat (heights within {:.1e} nm): its lengths ({}) put no relief on this patch's \
             samples (a period or correlation length far beyond the patch, or a period the pixels sample only at \
             its zeros)",
            self.kind(),
            hi - lo,
            self.describe(grid)
        )))
    }

    /// Generates the height field.
    pub fn generate(&self, grid: &Grid) -> Result<HeightField, SurfaceError> {
        let (rows, cols) = grid.dims()?;
        self.validate(grid)?;
        let f = grid.frame();
        let mut rng = Rng::new(grid.seed);
        let heights = match *self {
            Generator::Sine { period_nm, depth_nm } => f.fill(|u, _| 0.5 * depth_nm * (TAU * u / period_nm).sin()),
            Generator::Blazed { period_nm, depth_nm } => {
                f.fill(|u, _| depth_nm * (u / period_nm - (u / period_nm).floor()))
            }
            Generator::Bumps { shape, period_u_nm, period_v_nm, fill, depth_nm } => {
                let (wu, wv) = (fill * period_u_nm / 2.0, fill * period_v_nm / 2.0);
                f.fill(|u, v| {
                    let du = (u - period_u_nm * (u / period_u_nm).round()).abs();
                    let dv = (v - period_v_nm * (v / period_v_nm).round()).abs();
                    match shape {
                        BumpShape::Rect => {
                            if du < wu && dv < wv {
                                depth_nm
                            } else {
                                0.0
                            }
                        }
                        BumpShape::Tri => depth_nm * (1.0 - du / wu).min(1.0 - dv / wv).max(0.0),
                    }
                })
            }
            Generator::Cd { pitch_nm, bit_nm, pit_width_nm, depth_nm } => {
                cd(&f, grid.radius(), &mut rng, pitch_nm, bit_nm, pit_width_nm, depth_nm)
            }
            Generator::Gaussian { rms_nm, corr_nm } => gaussian(rows, cols, grid.pixel_nm, &mut rng, rms_nm, corr_nm),
            Generator::Elaphe { spacing_nm, finger_nm, rms_nm } => {
                elaphe(&f, grid.radius(), &mut rng, spacing_nm, finger_nm, rms_nm)
            }
            Generator::Xenopeltis { along_nm, across_nm, depth_nm } => {
                xenopeltis(&f, grid.radius(), &mut rng, along_nm, across_nm, depth_nm)
            }
        };
        self.refuse_flat(&heights, grid)?;
        let hf = HeightField::new(rows, cols, grid.pixel_nm, grid.pixel_nm, heights)?;
        Ok(hf.with_meta(Metadata {
            source: format!("generated {}", self.kind()),
            format: "generated".into(),
            z_unit: "nm".into(),
            notes: vec![self.describe(grid)],
            warnings: Vec::new(),
            channel: None,
        }))
    }
}

/// Smooth 0→1 ramp over `[0, w]` (cubic smoothstep).
#[inline]
fn smooth(x: f64, w: f64) -> f64 {
    let t = (x / w).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

fn cd(f: &Frame, radius: f64, rng: &mut Rng, pitch: f64, bit: f64, width: f64, depth: f64) -> Vec<f64> {
    // Pit walls slope over ~60 nm (moulded polycarbonate pits are not vertical).
    let wall = 60.0;
    let n_tracks = (radius / pitch).ceil() as i64 + 1;
    let tracks: Vec<Vec<(f64, f64)>> = (-n_tracks..=n_tracks)
        .map(|_| {
            let mut pits = Vec::new();
            let mut u = -radius - rng.range(0.0, 11.0 * bit);
            let mut is_pit = rng.uniform() < 0.5;
            while u < radius {
                let len = f64::from(rng.int(3, 11)) * bit;
                if is_pit {
                    pits.push((u, u + len));
                }
                u += len;
                is_pit = !is_pit;
            }
            pits
        })
        .collect();
    f.fill(|u, v| {
        let j = (v / pitch).round();
        let dv = (v - j * pitch).abs();
        let Some(pits) = tracks.get((j as i64 + n_tracks) as usize) else { return 0.0 };
        let fv = smooth(width / 2.0 - dv + wall / 2.0, wall);
        if fv <= 0.0 {
            return 0.0;
        }
        // The pit whose start is the last one ≤ u + wall.
        let k = pits.partition_point(|p| p.0 - wall / 2.0 <= u);
        if k == 0 {
            return 0.0;
        }
        let (a, b) = pits[k - 1];
        let fu = smooth(u - a + wall / 2.0, wall).min(smooth(b - u + wall / 2.0, wall));
        -depth * fu.min(fv)
    })
}

/// Gaussian random field by spectral filtering of white noise: PSD ∝ `exp(−π² f² corr²)`, the Fourier
/// transform of the correlation `exp(−r²/corr²)`; rescaled to the exact rms.
fn gaussian(rows: usize, cols: usize, d: f64, rng: &mut Rng, rms: f64, corr: f64) -> Vec<f64> {
    use iridis_fft::Complex;
    let mut data: Vec<Complex<f64>> = (0..rows * cols).map(|_| Complex::new(rng.normal(), 0.0)).collect();
    crate::fft::fft2(&mut data, rows, cols, false);
    for r in 0..rows {
        let fr = signed_bin(r, rows) / (rows as f64 * d);
        for c in 0..cols {
            let fc = signed_bin(c, cols) / (cols as f64 * d);
            let f2 = fr * fr + fc * fc;
            data[r * cols + c] *= (-PI * PI * f2 * corr * corr / 2.0).exp();
        }
    }
    crate::fft::fft2(&mut data, rows, cols, true);
    let mut h: Vec<f64> = data.iter().map(|z| z.re).collect();
    normalise_rms(&mut h, rms);
    h
}

fn signed_bin(k: usize, n: usize) -> f64 {
    if k <= n / 2 {
        k as f64
    } else {
        k as f64 - n as f64
    }
}

/// Removes the mean and scales to the given rms (a flat field stays flat).
fn normalise_rms(h: &mut [f64], rms: f64) {
    let n = h.len() as f64;
    let m = h.iter().sum::<f64>() / n;
    let s = (h.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / n).sqrt();
    let k = if s > 0.0 { rms / s } else { 0.0 };
    for x in h.iter_mut() {
        *x = (*x - m) * k;
    }
}

/// Elaphe: rows `v_k = k·spacing + jitter`; in each row two layers of fingers of random length laid end to
/// end with random gaps, offset against each other so they overlap (the upper one wins). Across a row a
/// finger rises over 80 % of its width and drops over the last 20 %: the shingle-like asymmetric profile
/// that makes Elaphe diffract mostly to one side (paper sec. 6.1).
fn elaphe(f: &Frame, radius: f64, rng: &mut Rng, spacing: f64, finger: f64, rms: f64) -> Vec<f64> {
    let mut h = vec![0.0; f.rows * f.cols];
    let n_rows = (radius / spacing).ceil() as i64 + 1;
    let taper = 0.15 * finger;
    for k in -n_rows..=n_rows {
        let vk = k as f64 * spacing + 0.04 * spacing * rng.normal();
        for _layer in 0..2 {
            let mut u = -radius - rng.range(0.0, finger);
            while u < radius {
                let len = finger * rng.range(0.5, 1.5);
                let (u0, u1) = (u, u + len);
                let amp = rng.range(0.7, 1.3);
                let w = spacing * rng.range(0.9, 1.05);
                let vc = vk + 0.03 * spacing * rng.normal();
                u = u1 + finger * rng.range(-0.2, 0.3);
                let Some((r0, r1, c0, c1)) = f.bbox(u0, u1, vc - w / 2.0, vc + w / 2.0) else { continue };
                for r in r0..=r1 {
                    for c in c0..=c1 {
                        let (pu, pv) = f.uv(r, c);
                        let t = (pv - vc) / w + 0.5;
                        if !(0.0..=1.0).contains(&t) || pu < u0 || pu > u1 {
                            continue;
                        }
                        let across = if t < 0.8 { t / 0.8 } else { (1.0 - t) / 0.2 };
                        let along = smooth(pu - u0, taper) * smooth(u1 - pu, taper);
                        let z = amp * across * along;
                        let cell = &mut h[r * f.cols + c];
                        if z > *cell {
                            *cell = z;
                        }
                    }
                }
            }
        }
    }
    normalise_rms(&mut h, rms);
    h
}

/// Xenopeltis: a lattice of fingers, `along` long end to end in each row and rows `across` apart, in a
/// warped frame (three long sinusoidal warps, 20–40 µm wavelengths, 0.4–0.9 µm amplitudes, so fingers
/// curve but neighbours stay parallel), cut into Voronoi grains ≈ 15 µm across, each with its own periods (±3 % along, ±8 % across)
/// and phases. Along a finger the height rises like a blazed facet and drops at its tip (paper sec. 7:
/// "vertical height profiles similar to a blazed grating").
fn xenopeltis(f: &Frame, radius: f64, rng: &mut Rng, along: f64, across: f64, depth: f64) -> Vec<f64> {
    struct Grain {
        u: f64,
        v: f64,
        along: f64,
        across: f64,
        phase_v: f64,
        phase_u: f64,
        key: u64,
    }
    let n_grains = ((2.0 * radius / 15_000.0).powi(2).ceil() as usize).clamp(1, 4096);
    let grains: Vec<Grain> = (0..n_grains)
        .map(|_| Grain {
            u: rng.range(-radius, radius),
            v: rng.range(-radius, radius),
            along: along * (1.0 + 0.03 * rng.normal().clamp(-2.0, 2.0)),
            across: across * (1.0 + 0.08 * rng.normal().clamp(-2.0, 2.0)),
            phase_v: rng.uniform(),
            phase_u: rng.uniform(),
            key: rng.next_u64(),
        })
        .collect();
    // Warps vary mostly along the fingers (within ±15° of u): the rows bend (up to ≈ 20°) without their
    // spacing being squeezed much.
    let warps: Vec<(f64, f64, f64, f64)> = (0..3)
        .map(|_| {
            let lambda = rng.range(20_000.0, 40_000.0);
            let dir = rng.range(-0.25, 0.25);
            (rng.range(400.0, 900.0), TAU / lambda * dir.cos(), TAU / lambda * dir.sin(), rng.range(0.0, TAU))
        })
        .collect();
    f.fill(|u, v| {
        let g = grains
            .iter()
            .min_by(|a, b| ((a.u - u).powi(2) + (a.v - v).powi(2)).total_cmp(&((b.u - u).powi(2) + (b.v - v).powi(2))))
            .expect("at least one grain");
        let vw = v + warps.iter().map(|&(a, ku, kv, p)| a * (ku * u + kv * v + p).sin()).sum::<f64>();
        let row_f = vw / g.across + g.phase_v;
        let row = row_f.floor();
        let t = row_f - row;
        // Finger tips line up from row to row within a grain, with a small jitter per row (a hash of grain
        // and row), so the period along the fingers is seen, as the paper's Xenopeltis diffracts along them.
        let mut hr = Rng::new(g.key ^ (row as i64 as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15));
        let s_f = u / g.along + g.phase_u + 0.08 * hr.normal();
        let s = s_f - s_f.floor();
        let along_p = if s < 0.85 { s / 0.85 } else { (1.0 - s) / 0.15 };
        let x = (t - 0.5) / 0.8;
        let across_p = if x.abs() < 0.5 { (PI * x).cos().powi(2) } else { 0.0 };
        depth * along_p * across_p
    })
}
