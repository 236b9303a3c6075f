//! Pixels as sets of direction pairs, rendering any evaluator into them, and the pictures the lab writes:
//! tone-mapped colour images, ΔE heat maps and contact sheets.

use iridis_color::{ToneMap, Xyz};
use iridis_diffraction::geometry::{direction, Vec3};
use iridis_diffraction::map::view_direction;
use iridis_diffraction::{Accelerator, Evaluator};
use iridis_plot::RgbImage;
use rayon::prelude::*;

use crate::{LabError, Progress};

/// One sample of a pixel: light direction, view direction and the weight of its XYZ in the pixel's mean.
pub type Sample = (Vec3, Vec3, f64);

/// An image whose pixels are sets of direction pairs (empty: nothing to see, black).
#[derive(Debug, Clone)]
pub struct Pixels {
    pub width: usize,
    pub height: usize,
    /// Row-major, row 0 at the top.
    pub samples: Vec<Vec<Sample>>,
}

impl Pixels {
    /// A BRDF map in the paper's layout (PHYSICS.md): light from `(θ_i, φ_i)`, pixel `(x, y) ∈ [−1, 1]²` viewing
    /// `(x, y, √(1 − x² − y²))`, black outside the unit disk.
    pub fn brdf_map(incidence: f64, light_azimuth: f64, size: usize) -> Self {
        let wi = direction(incidence, light_azimuth);
        let mut samples = Vec::with_capacity(size * size);
        for row in 0..size {
            for col in 0..size {
                samples.push(view_direction(col, row, size).map(|wr| vec![(wi, wr, 1.0)]).unwrap_or_default());
            }
        }
        Self { width: size, height: size, samples }
    }

    pub fn len(&self) -> usize {
        self.samples.len()
    }

    pub fn is_empty(&self) -> bool {
        self.samples.is_empty()
    }
}

/// XYZ per pixel (`None` where the pixel sees nothing): the weighted sum of its samples. All cores;
/// `progress(pixels_done)` every 64 pixels.
pub fn render(evaluator: &dyn Evaluator, pixels: &Pixels, progress: Progress) -> Vec<Option<Xyz>> {
    let done = std::sync::atomic::AtomicUsize::new(0);
    pixels
        .samples
        .par_iter()
        .map(|s| {
            let out = if s.is_empty() {
                None
            } else {
                let mut acc = [0.0; 3];
                for &(wi, wr, w) in s {
                    let c = evaluator.xyz(wi, wr);
                    acc[0] += w * c.x;
                    acc[1] += w * c.y;
                    acc[2] += w * c.z;
                }
                Some(Xyz::new(acc[0], acc[1], acc[2]))
            };
            let d = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
            if d & 63 == 0 || d == pixels.samples.len() {
                progress(d);
            }
            out
        })
        .collect()
}

/// [`render`] on an accelerator: every sample of every pixel as one batch of direction pairs, summed per pixel
/// with the samples' weights. `None` when the accelerator does not evaluate this evaluator. `progress(pixels_done)`.
pub fn render_on(
    accelerator: &dyn Accelerator,
    evaluator: &dyn Evaluator,
    pixels: &Pixels,
    progress: Progress,
) -> Option<Result<Vec<Option<Xyz>>, LabError>> {
    let pairs: Vec<(Vec3, Vec3)> = pixels.samples.iter().flatten().map(|&(wi, wr, _)| (wi, wr)).collect();
    // Pairs done → pixels done (the samples of a pixel are consecutive).
    let ends: Vec<usize> = pixels
        .samples
        .iter()
        .scan(0, |n, s| {
            *n += s.len();
            Some(*n)
        })
        .collect();
    let report = |done: usize| progress(ends.partition_point(|&e| e <= done));
    let xyz = match accelerator.xyz_pairs(evaluator, &pairs, &report)? {
        Ok(x) => x,
        Err(e) => return Some(Err(e.into())),
    };
    let mut next = xyz.iter();
    Some(Ok(pixels
        .samples
        .iter()
        .map(|s| {
            (!s.is_empty()).then(|| {
                let mut acc = [0.0; 3];
                for (&(_, _, w), c) in s.iter().zip(next.by_ref()) {
                    acc[0] += w * c.x;
                    acc[1] += w * c.y;
                    acc[2] += w * c.z;
                }
                Xyz::new(acc[0], acc[1], acc[2])
            })
        })
        .collect()))
}

/// The picture a camera records at `exposure_ru` (XYZ × exposure → linear sRGB → clip → sRGB curve).
pub fn to_rgb(image: &[Option<Xyz>], width: usize, height: usize, exposure_ru: f64) -> RgbImage {
    let tone = ToneMap { exposure_ru, ..ToneMap::default() };
    let mut out = RgbImage::new(width as u32, height as u32);
    for (k, p) in image.iter().enumerate() {
        if let Some(xyz) = p {
            out.put((k % width) as u32, (k / width) as u32, tone.to_rgb8(*xyz));
        }
    }
    out
}

/// A heat map of values in `[0, max]` with the magma colour map (`None`: white).
pub fn heat(values: &[Option<f64>], width: usize, height: usize, max: f64) -> RgbImage {
    let mut out = RgbImage::new(width as u32, height as u32);
    for (k, v) in values.iter().enumerate() {
        let c = match v {
            Some(v) => iridis_plot::magma(if max > 0.0 { v / max } else { 0.0 }),
            None => [255, 255, 255],
        };
        out.put((k % width) as u32, (k / width) as u32, c);
    }
    out
}

/// Tiles laid out left to right, top to bottom, `columns` per row, on white with a 12-pixel gap.
pub fn contact_sheet(tiles: &[RgbImage], columns: usize) -> RgbImage {
    let columns = columns.max(1);
    let tw = tiles.iter().map(|t| t.width).max().unwrap_or(1);
    let th = tiles.iter().map(|t| t.height).max().unwrap_or(1);
    let rows = tiles.len().div_ceil(columns).max(1);
    let gap = 12u32;
    let (w, h) = (columns as u32 * (tw + gap) + gap, rows as u32 * (th + gap) + gap);
    let mut out = RgbImage::new(w, h);
    out.data.iter_mut().for_each(|b| *b = 255);
    for (k, t) in tiles.iter().enumerate() {
        let (x0, y0) = (gap + (k % columns) as u32 * (tw + gap), gap + (k / columns) as u32 * (th + gap));
        for y in 0..t.height {
            for x in 0..t.width {
                out.put(x0 + x, y0 + y, t.get(x, y));
            }
        }
    }
    out
}

/// Nearest-neighbour upscaling by an integer factor (small maps become visible tiles).
pub fn upscale(img: &RgbImage, factor: u32) -> RgbImage {
    let f = factor.max(1);
    let mut out = RgbImage::new(img.width * f, img.height * f);
    for y in 0..out.height {
        for x in 0..out.width {
            out.put(x, y, img.get(x / f, y / f));
        }
    }
    out
}
