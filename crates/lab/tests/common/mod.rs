//! What the lab's test files share.
#![allow(dead_code)] // each test file uses its own subset

use std::sync::Arc;

use iridis_diffraction::{Patch, Reference, Shading, SpectralSetup, TaylorTerms};

/// The reference evaluator of `patch` at `coherence` nm, with as many Taylor terms as keep the remainder below
/// `bound` at 380 nm.
pub fn reference(patch: &Patch, coherence: f64, bound: f64) -> Reference {
    let n = iridis_diffraction::taylor::terms_for_bound(patch.max_abs_height, 380.0, bound);
    Reference {
        terms: Arc::new(TaylorTerms::compute(patch, n, coherence).unwrap()),
        shading: Shading::default(),
        spectral: SpectralSetup::default(),
    }
}
