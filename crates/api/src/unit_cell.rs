//! One period of a scan as a 1-D grating profile: the height field averaged along its ridges (what
//! `--unit-cell auto` and the validity map in docs/diffraction.md use to take a skin's dominant period as a
//! grating for the rigorous solver, which needs a periodic profile).

use iridis_diffraction::Patch;

/// The mean profile of `patch` over one period of a grating of period `period_nm` whose grating vector points
/// along `orientation_deg` (degrees from +x, y up: the orientation `iridis surface info` reports): every
/// height is put in the bin of its phase `(x cos φ + y sin φ)/Λ mod 1` (`x = col·dx`, `y` up as in [`Patch`]),
/// and each of the `samples` bins gives the mean of its heights. Bin `i` is centred on phase `i/samples`, so
/// the result is sampled at `x = i·Λ/samples` as `iridis_rigorous::Profile1d` wants. A bin no height falls in
/// (a pixel coarser than `Λ/samples` along a grid axis) takes the linear interpolation of its nearest filled
/// neighbours around the period. Heights are those of the patch (mean removed); the profile's mean is
/// therefore close to zero. Averaging along the ridges keeps what repeats with the period and washes out what
/// does not (rows of unequal phase, finger ends, noise): the result is shallower than the scan's
/// peak-to-valley wherever the ridges are not straight or not in phase.
///
/// `samples` is at least 1; a non-finite or non-positive period gives all zeros.
pub fn averaged_profile(patch: &Patch, period_nm: f64, orientation_deg: f64, samples: usize) -> Vec<f64> {
    let samples = samples.max(1);
    if !(period_nm.is_finite() && period_nm > 0.0 && orientation_deg.is_finite()) {
        return vec![0.0; samples];
    }
    let (s, c) = orientation_deg.to_radians().sin_cos();
    let mut sum = vec![0.0; samples];
    let mut count = vec![0usize; samples];
    for j in 0..patch.rows {
        let y = j as f64 * patch.dy;
        for i in 0..patch.cols {
            let x = i as f64 * patch.dx;
            let phase = ((x * c + y * s) / period_nm).rem_euclid(1.0);
            let bin = ((phase * samples as f64).round() as usize) % samples;
            sum[bin] += patch.heights[j * patch.cols + i];
            count[bin] += 1;
        }
    }
    let filled: Vec<usize> = (0..samples).filter(|&b| count[b] > 0).collect();
    let mean = |b: usize| sum[b] / count[b] as f64;
    (0..samples)
        .map(|b| {
            if count[b] > 0 {
                return mean(b);
            }
            // Nearest filled bins before and after b, around the period.
            let after = filled.iter().copied().find(|&f| f > b).unwrap_or(filled[0] + samples);
            let before = filled
                .iter()
                .copied()
                .rev()
                .find(|&f| f < b)
                .map_or(filled[filled.len() - 1] as isize - samples as isize, |f| f as isize);
            let t = (b as isize - before) as f64 / (after as isize - before) as f64;
            (1.0 - t) * mean(before.rem_euclid(samples as isize) as usize) + t * mean(after % samples)
        })
        .collect()
}

/// The share of `patch`'s height variance its averaged cell keeps (both have their mean removed), at most 1:
/// the cell's whole periods against a patch of 9.09 of them read 101 %.
pub fn variance_share(cell: &Patch, patch: &Patch) -> f64 {
    let variance = |h: &[f64]| h.iter().map(|x| x * x).sum::<f64>() / h.len().max(1) as f64;
    (variance(&cell.heights) / variance(&patch.heights).max(f64::MIN_POSITIVE)).min(1.0)
}

/// [`averaged_profile`] in bins that match where the samples' phases fall. Where they sit on a lattice `k/q`
/// (a period of a whole, or rational, number of pixels along a grid axis), `4 ≤ q ≤ 256`, the profile has `q`
/// bins, one a cluster of phases: binned finer or coarser, bins fall between the clusters or straddle them and
/// bend the profile (a 1100 nm sine at 100 nm pixels, 11 clusters in 32 bins, lost a third of its second order;
/// a 2500 nm saw-tooth's 25 clusters in 27 bins moved its orders by half). Elsewhere `samples` bins.
pub fn averaged_profile_filled(patch: &Patch, period_nm: f64, orientation_deg: f64, samples: usize) -> Vec<f64> {
    let bins = phase_lattice(patch, period_nm, orientation_deg).unwrap_or(samples);
    averaged_profile(patch, period_nm, orientation_deg, bins)
}

/// The smallest `q` (`4 ≤ q ≤ 256`) whose lattice `k/q` the samples' phases `(x cos φ + y sin φ)/Λ mod 1` sit on
/// — each within a fifth of the lattice step of a node, every node taken —; `None` where they spread (an
/// oblique grating, a period of an irrational number of pixels). A period found to within a fraction of a pixel
/// drifts the phases along the scan (2496.1 nm for a 2500 nm saw-tooth at 200 nm pixels: 0.15 of a step over
/// the scan), which the fifth allows; a lattice of twice the nodes sits half a step off, which it does not. Every sample is tested (the drift grows across the scan); a `q` that fails does so within a
/// few samples, so the cost is about one pass.
fn phase_lattice(patch: &Patch, period_nm: f64, orientation_deg: f64) -> Option<usize> {
    if !(period_nm.is_finite() && period_nm > 0.0 && orientation_deg.is_finite()) {
        return None;
    }
    let (s, c) = orientation_deg.to_radians().sin_cos();
    let phase = |i: usize, j: usize| ((i as f64 * patch.dx * c + j as f64 * patch.dy * s) / period_nm).rem_euclid(1.0);
    (4..=256usize).find(|&q| {
        let mut taken = vec![false; q];
        let on_lattice = (0..patch.rows).all(|j| {
            (0..patch.cols).all(|i| {
                let at = phase(i, j) * q as f64;
                let node = at.round();
                taken[node as usize % q] = true;
                (at - node).abs() < 0.2
            })
        });
        on_lattice && taken.iter().all(|&t| t)
    })
}
