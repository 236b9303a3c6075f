//! Plane waves in a homogeneous medium: wavevectors, the s/p polarisation basis, and the magnetic field.
//!
//! Units: wavevectors are normalised by the vacuum wavenumber `k0`, so `k·k = ε`; the magnetic field is
//! `Z0 H`, so Maxwell's curl equations read `∇×E = i H`, `∇×H = −i ε E` (time factor `exp(−iωt)`) and a plane
//! wave has `H = k × E`.

use num_complex::Complex64 as C64;

pub(crate) type V3 = [C64; 3];

pub(crate) fn cross(a: &V3, b: &V3) -> V3 {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

/// `z` component of a plane wave's wavevector in a medium of permittivity `eps`, for tangential components
/// `(kx, ky)`: the root of `kz² = ε − kx² − ky²` with `Im ≥ 0` (and `Re ≥ 0` when real): the wave `exp(+i kz z)`
/// travels or decays upwards, `exp(−i kz z)` downwards.
pub(crate) fn kz_up(eps: C64, kx: f64, ky: f64) -> C64 {
    let k = (eps - kx * kx - ky * ky).sqrt();
    if k.im < 0.0 || (k.im == 0.0 && k.re < 0.0) {
        -k
    } else {
        k
    }
}

/// The s and p unit vectors of a plane wave with wavevector `k` (`k·k = ε`): `s = ẑ × k_t / |k_t|`
/// (perpendicular to the plane of incidence of that wave) and `p = k × s / √ε`; both have unit length under the
/// bilinear product `v·v`, so a wave `A_s s + A_p p` in a lossless medium carries the power flux
/// `½ k_z (|A_s|² + |A_p|²)` along z. When `k_t = 0` the plane is the one of azimuth `phi_ref`:
/// `s = (sin φ, −cos φ, 0)`, the limit of `ẑ × k_t/|k_t|` for `k_t` pointing to azimuth `φ + π`, as an incident
/// wave from azimuth `φ` does.
pub(crate) fn sp_basis(k: &V3, eps: C64, phi_ref: f64) -> (V3, V3) {
    let kt = (k[0].norm_sqr() + k[1].norm_sqr()).sqrt();
    let s: V3 = if kt > 1e-12 * eps.norm().sqrt().max(1e-300) {
        [-k[1] / kt, k[0] / kt, C64::new(0.0, 0.0)]
    } else {
        [C64::new(phi_ref.sin(), 0.0), C64::new(-phi_ref.cos(), 0.0), C64::new(0.0, 0.0)]
    };
    let n = eps.sqrt();
    let ks = cross(k, &s);
    let p = [ks[0] / n, ks[1] / n, ks[2] / n];
    (s, p)
}
