//! Work that another device can take over from the CPU: building lookup tables and evaluating the ground truth
//! (`iridis-gpu` implements it on the GPU). The library's callers — the lab's workbench, the commands — hold an
//! `Option<Arc<dyn Accelerator>>` and fall back to the CPU where there is none or where it answers `None`.

use iridis_color::Xyz;

use crate::evaluator::Evaluator;
use crate::geometry::Vec3;
use crate::spectral::SpectralSetup;
use crate::table::{LookupTable, TableParams};
use crate::taylor::TaylorTerms;
use crate::DiffractionError;

/// A device that computes some of this crate's numbers (the same model, possibly in lower precision).
pub trait Accelerator: Send + Sync + std::fmt::Debug {
    /// The device's name, for the output (e.g. a GPU adapter).
    fn name(&self) -> String;

    /// [`LookupTable::build`] on the device; `progress(rows_done)` as rows of the grid finish.
    fn build_table(
        &self,
        terms: &TaylorTerms,
        spectral: &SpectralSetup,
        params: TableParams,
        surface: &str,
        progress: &(dyn Fn(usize) + Sync),
    ) -> Result<LookupTable, DiffractionError>;

    /// The colour [`Evaluator::xyz`] of `evaluator` for each `(ω_i, ω_r)` pair, or `None` when the device does
    /// not evaluate this kind of evaluator (the caller then uses the CPU). `progress(pairs_done)`.
    fn xyz_pairs(
        &self,
        evaluator: &dyn Evaluator,
        pairs: &[(Vec3, Vec3)],
        progress: &(dyn Fn(usize) + Sync),
    ) -> Option<Result<Vec<Xyz>, DiffractionError>>;
}
