//! BRDF maps (paper sec. 7): the colour reflected towards every view direction for one light direction.
//! Pixel `(x, y) ∈ [−1, 1]²` shows the view direction `(x, y, √(1 − x² − y²))`; x grows to the right, y
//! upwards (row 0 is the top); outside the unit disk is black (PHYSICS.md).

use iridis_color::Xyz;
use rayon::prelude::*;

use crate::evaluator::Evaluator;
use crate::geometry::Vec3;

/// The view direction of pixel `(col, row)` of a `size × size` map, or `None` outside the unit disk.
pub fn view_direction(col: usize, row: usize, size: usize) -> Option<Vec3> {
    let x = -1.0 + (2 * col + 1) as f64 / size as f64;
    let y = 1.0 - (2 * row + 1) as f64 / size as f64;
    let r2 = x * x + y * y;
    if r2 >= 1.0 {
        return None;
    }
    Some([x, y, (1.0 - r2).sqrt()])
}

/// The mean of `f` over pixel `(col, row)`'s `k × k` view samples — the centres of the pixel's square cut into
/// `k²`, i.e. the pixels of the `size·k` map it covers — counting those outside the unit disk as black: the map of
/// `size` with `k` samples a pixel is the `size·k` map averaged over `k × k` blocks. `k = 1`: the pixel's centre.
fn pixel_mean<E>(col: usize, row: usize, size: usize, k: usize, f: &dyn Fn(Vec3) -> Result<Xyz, E>) -> Result<Xyz, E> {
    if k == 1 {
        return view_direction(col, row, size).map_or(Ok(Xyz::default()), f);
    }
    let mut sum = [0.0; 3];
    for r in 0..k {
        for c in 0..k {
            if let Some(wr) = view_direction(col * k + c, row * k + r, size * k) {
                let v = f(wr)?;
                sum = [sum[0] + v.x, sum[1] + v.y, sum[2] + v.z];
            }
        }
    }
    let n = (k * k) as f64;
    Ok(Xyz::new(sum[0] / n, sum[1] / n, sum[2] / n))
}

/// The BRDF `f_r` (sr⁻¹, unpolarised light) per pixel, as XYZ: `f_r(λ)` weighted by the light and the observer
/// as a reflectance is (`weights`, whose white has `Y = 1`), so `Y` is the luminous BRDF and `Σ Y·dx·dy` over
/// the disk (`dω = dx dy / cos θ_r`) the luminous share of the light reflected (docs/PHYSICS.md, "The BRDF in
/// sr⁻¹"); each pixel the mean of its `subsamples × subsamples` view samples. Refused for a method without
/// `f_r(λ)` (the lookup method integrates over λ in advance).
pub fn brdf_map_per_sr(
    evaluator: &dyn Evaluator,
    weights: &iridis_color::integrate::SpectralWeights,
    wi: Vec3,
    size: usize,
    subsamples: usize,
    progress: &(dyn Fn(usize) + Sync),
) -> Result<Vec<Xyz>, crate::DiffractionError> {
    let lambdas = weights.wavelengths_nm();
    let f_r = |wr: Vec3| -> Result<Xyz, crate::DiffractionError> {
        let q = crate::point::point_query(evaluator, lambdas, wi, wr)?;
        let b = q.brdf.ok_or_else(|| {
            crate::DiffractionError::Invalid(format!(
                "the {} method gives no BRDF f_r(λ) in sr⁻¹ (it integrates over wavelength in advance, or its \
                 Fresnel convention is the paper's); use reference, ground-truth or rigorous",
                evaluator.name()
            ))
        })?;
        Ok(weights.integrate(&b.unpolarized))
    };
    // One query first: a method without f_r is refused before the map's work.
    f_r([0.0, 0.0, 1.0])?;
    let done = std::sync::atomic::AtomicUsize::new(0);
    let rows: Vec<Vec<Xyz>> = (0..size)
        .into_par_iter()
        .map(|row| {
            let out =
                (0..size).map(|col| pixel_mean(col, row, size, subsamples, &f_r)).collect::<Result<Vec<Xyz>, _>>();
            progress(done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1);
            out
        })
        .collect::<Result<_, _>>()?;
    Ok(rows.into_iter().flatten().collect())
}

/// The map of `size / k` pixels a side whose pixels are the means of `k × k` blocks of the `size`² map `fine`
/// (row-major): what [`brdf_map`] computes with `k` view samples a pixel, from a map computed elsewhere (the GPU's)
/// at `k` times the size. The sums run in the order [`brdf_map`] sums a pixel's samples, so the two agree to the bit.
pub fn block_mean(fine: &[Xyz], size: usize, k: usize) -> Vec<Xyz> {
    assert!(k >= 1 && size.is_multiple_of(k) && fine.len() == size * size, "a {size}² map in {k} × {k} blocks");
    let coarse = size / k;
    let n = (k * k) as f64;
    let mut out = Vec::with_capacity(coarse * coarse);
    for row in 0..coarse {
        for col in 0..coarse {
            let mut sum = [0.0; 3];
            for r in 0..k {
                for c in 0..k {
                    let v = fine[(row * k + r) * size + col * k + c];
                    sum = [sum[0] + v.x, sum[1] + v.y, sum[2] + v.z];
                }
            }
            out.push(Xyz::new(sum[0] / n, sum[1] / n, sum[2] / n));
        }
    }
    out
}

/// XYZ per pixel, row-major, row 0 at the top, each pixel the mean of its `subsamples × subsamples` view
/// samples (1: its centre). `progress(rows_done)` is called as rows finish.
pub fn brdf_map(
    evaluator: &dyn Evaluator,
    wi: Vec3,
    size: usize,
    subsamples: usize,
    progress: &(dyn Fn(usize) + Sync),
) -> Vec<Xyz> {
    let xyz = |wr: Vec3| Ok::<_, std::convert::Infallible>(evaluator.xyz(wi, wr));
    let done = std::sync::atomic::AtomicUsize::new(0);
    let rows: Vec<Vec<Xyz>> = (0..size)
        .into_par_iter()
        .map(|row| {
            let out = (0..size)
                .map(|col| {
                    let Ok(v) = pixel_mean(col, row, size, subsamples, &xyz);
                    v
                })
                .collect();
            progress(done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1);
            out
        })
        .collect();
    rows.into_iter().flatten().collect()
}
