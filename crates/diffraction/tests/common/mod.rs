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
