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

/// XYZ per pixel, row-major, row 0 at the top. `progress(rows_done)` is called as rows finish.
pub fn brdf_map(evaluator: &dyn Evaluator, wi: Vec3, size: usize, progress: &(dyn Fn(usize) + Sync)) -> Vec<Xyz> {
    let done = std::sync::atomic::AtomicUsize::new(0);
    let rows: Vec<Vec<Xyz>> = (0..size)
        .into_par_iter()
        .map(|row| {
            let out = (0..size)
                .map(|col| view_direction(col, row, size).map(|wr| evaluator.xyz(wi, wr)).unwrap_or_default())
                .collect();
            progress(done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1);
            out
        })
        .collect();
    rows.into_iter().flatten().collect()
}
