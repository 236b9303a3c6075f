//! What the lab's test files share.
#![allow(dead_code)] // each test file uses its own subset

use std::sync::Arc;

use iridis_diffraction::{Patch, Reference, Shading, SpectralSetup, TaylorTerms};

/// The reference evaluator of `patch` at `coherence` nm, with as many Taylor terms as keep the remainder below
/// `bound` at 380 nm.
pub fn reference(patch: &Patch, coherence: f64, bound: f64) -> Reference {
    let n = iridis_diffraction::taylor::terms_for_bound(patch.max_abs_height, 380.0, bound).unwrap();
    Reference {
        terms: Arc::new(TaylorTerms::compute(patch, n, coherence).unwrap()),
        shading: Shading::default(),
        spectral: SpectralSetup::default(),
    }
}

/// A sine grating of `rows × cols` square pixels of `dx` nm: `amplitude · sin(2π x / period)` (nm), varying along
/// x only.
pub fn sine_along_x(rows: usize, cols: usize, dx: f64, amplitude: f64, period: f64) -> Patch {
    let h: Vec<f64> =
        (0..rows * cols).map(|k| amplitude * (std::f64::consts::TAU * (k % cols) as f64 * dx / period).sin()).collect();
    Patch::from_row_major(rows, cols, dx, dx, &h).unwrap()
}
