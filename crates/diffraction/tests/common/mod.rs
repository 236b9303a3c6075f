//! What the diffraction test files share.
#![allow(dead_code)] // each test file uses its own subset

/// Deterministic pseudo-random heights in [−amp, amp] (a linear congruential generator; any fixed field will do).
pub fn heights(n: usize, amp: f64, seed: u64) -> Vec<f64> {
    let mut s = seed;
    (0..n)
        .map(|_| {
            s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            amp * (2.0 * ((s >> 11) as f64 / (1u64 << 53) as f64) - 1.0)
        })
        .collect()
}

/// `∬ g(ω_r) du dv` over the unit disk of view directions `ω_r = (u, v, √(1 − u² − v²))` (so `du dv = cos θ_r dω_r`),
/// by the midpoint rule on an `n × n` grid over the square `[−1, 1]²`.
pub fn projected_disk_sum(n: usize, mut g: impl FnMut([f64; 3]) -> f64) -> f64 {
    let d = 2.0 / n as f64;
    let mut sum = 0.0;
    for j in 0..n {
        for i in 0..n {
            let (u, v) = (-1.0 + (i as f64 + 0.5) * d, -1.0 + (j as f64 + 0.5) * d);
            let r2 = u * u + v * v;
            if r2 < 1.0 {
                sum += g([u, v, (1.0 - r2).sqrt()]) * d * d;
            }
        }
    }
    sum
}
