//! Angle × wavelength grids (Sussenbach's simulation table, Figure 3.8), evaluated in parallel with rayon.
//! Wavelength-invariant stacks take the chapter 4 fast path (one preparation per angle).

use rayon::prelude::*;

use crate::error::ThinFilmError;
use crate::recurrence::Rta;
use crate::stack::Stack;

/// Which code path evaluates a grid.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Path {
    /// [`Stack::evaluate`] at every sample: complex arithmetic, indices looked up per sample.
    General,
    /// The chapter 4 fast path ([`Stack::prepare`]) when the stack is wavelength-invariant, else `General`.
    Auto,
}

/// R, T for every `(angle, wavelength)`; row-major: `out[i * wavelengths.len() + j]` is angle `i`,
/// wavelength `j`. `threads = false` runs on the calling thread only.
pub fn evaluate_grid(
    stack: &Stack,
    angles_rad: &[f64],
    wavelengths_nm: &[f64],
    path: Path,
    threads: bool,
) -> Result<Vec<Rta>, ThinFilmError> {
    let fast = path == Path::Auto && stack.is_wavelength_invariant() && !stack.has_incoherent();
    let row = |&th: &f64| -> Result<Vec<Rta>, ThinFilmError> {
        if fast {
            let p = stack.prepare(th)?;
            wavelengths_nm.iter().map(|&w| p.evaluate(w)).collect()
        } else {
            wavelengths_nm.iter().map(|&w| stack.evaluate(w, th)).collect()
        }
    };
    let rows: Vec<Vec<Rta>> = if threads {
        angles_rad.par_iter().map(row).collect::<Result<_, _>>()?
    } else {
        angles_rad.iter().map(row).collect::<Result<_, _>>()?
    };
    Ok(rows.into_iter().flatten().collect())
}

/// The number of threads a parallel grid uses (rayon's pool; `RAYON_NUM_THREADS` sets it).
pub fn threads() -> usize {
    rayon::current_num_threads()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paths_and_threads_agree() {
        let s = Stack::parse("air | gasoline 216nm | water 220nm | asphalt").unwrap();
        let angles: Vec<f64> = (0..90).map(|d| f64::to_radians(d as f64)).collect();
        let wl: Vec<f64> = (380..=780).step_by(20).map(f64::from).collect();
        let a = evaluate_grid(&s, &angles, &wl, Path::General, false).unwrap();
        let b = evaluate_grid(&s, &angles, &wl, Path::Auto, true).unwrap();
        assert_eq!(a.len(), angles.len() * wl.len());
        for (x, y) in a.iter().zip(&b) {
            assert!((x.r() - y.r()).abs() < 1e-13 && (x.t() - y.t()).abs() < 1e-13);
        }
        // Row-major: angle 45°, 540 nm.
        let k = 45 * wl.len() + 8;
        assert_eq!(a[k], s.evaluate(540.0, f64::to_radians(45.0)).unwrap());
    }
}
