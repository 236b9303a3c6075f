//! The GPU as an [`iridis_diffraction::Accelerator`]: lookup tables built by `table_build.wgsl` and the ground
//! truths evaluated by `ground_truth.wgsl`, so that the lab's commands (`iridis compare --gpu`, `iridis sweep
//! --gpu`) put their expensive steps on the GPU through `iridis_lab::Workbench` without knowing about it.

use iridis_color::Xyz;
use iridis_diffraction::geometry::Vec3;
use iridis_diffraction::table::{LookupTable, TableParams};
use iridis_diffraction::{Accelerator, DiffractionError, Evaluator, SpectralSetup, TaylorTerms};

use crate::{build_table, Gpu, GpuError, GpuGroundTruth};

/// An open GPU that builds tables and evaluates ground truths.
#[derive(Debug)]
pub struct GpuAccelerator {
    gpu: Gpu,
}

fn lift(e: GpuError) -> DiffractionError {
    DiffractionError::Invalid(e.to_string())
}

impl GpuAccelerator {
    /// Opens the GPU ([`Gpu::new`]).
    pub fn new() -> Result<Self, GpuError> {
        Ok(Self { gpu: Gpu::new()? })
    }

    pub fn gpu(&self) -> &Gpu {
        &self.gpu
    }
}

impl Accelerator for GpuAccelerator {
    fn name(&self) -> String {
        self.gpu.adapter_name()
    }

    fn build_table(
        &self,
        terms: &TaylorTerms,
        spectral: &SpectralSetup,
        params: TableParams,
        surface: &str,
        progress: &(dyn Fn(usize) + Sync),
    ) -> Result<LookupTable, DiffractionError> {
        build_table(&self.gpu, terms, spectral, params, surface, progress).map_err(lift)
    }

    fn xyz_pairs(
        &self,
        evaluator: &dyn Evaluator,
        pairs: &[(Vec3, Vec3)],
        progress: &(dyn Fn(usize) + Sync),
    ) -> Option<Result<Vec<Xyz>, DiffractionError>> {
        let gt = evaluator.as_ground_truth()?;
        Some(GpuGroundTruth::new(&self.gpu, gt).and_then(|g| g.xyz(pairs, progress)).map_err(lift))
    }
}
