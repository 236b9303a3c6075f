//! When a computed spectrum cannot be trusted: the fringes of a thick coherent layer closer together than
//! the wavelength grid can sample (aliasing), and layers so thick that ordinary light does not interfere in
//! them at all.
//!
//! A coherent group of optical thickness `L = Σ n_j d_j cos θ_j` has reflectance fringes `λ²/(2L)` apart
//! (the phase `4πL/λ` advances by 2π); the grid samples them faithfully only with at least two samples per
//! fringe (Nyquist). Light of bandwidth `δλ` has the coherence length `λ²/δλ` (e.g. Born & Wolf §7.5.8); a
//! layer whose round trip `2L` is longer shows no fringes and belongs in the stack as `inc:`.

use crate::stack::Stack;

/// A warning about the sampling of a spectrum of a stack.
#[derive(Debug, Clone, PartialEq)]
pub struct SamplingWarning {
    /// The thickest layer of the worst coherent group (1-based, top first).
    pub layer: usize,
    /// The fringe spacing (nm) at the shortest wavelength of the grid.
    pub fringe_nm: f64,
    pub at_nm: f64,
    /// The largest step (nm) that gives two samples per fringe.
    pub step_nm: f64,
    /// The round trip `2L` is longer than the coherence length of 1 nm-bandwidth light at `at_nm`
    /// (`λ²/1 nm`, ~0.14 mm at 380 nm): no spectrometer of ordinary resolution sees these fringes.
    pub suggest_incoherent: bool,
    pub message: String,
}

/// The bandwidth (nm) whose coherence length decides "thicker than the coherence length".
pub const COHERENCE_BANDWIDTH_NM: f64 = 1.0;

/// The round-trip field below which light coming back from under an absorbing layer makes no fringe the
/// printed R and T show (their fringes' amplitude is at most twice this): such a layer, and what lies under
/// it in its coherent group, adds nothing to the fringes.
pub const FRINGE_FLOOR: f64 = 1e-8;

/// Per layer: whether light returns through it to the top of its coherent group at some wavelength of the
/// grid with at least [`FRINGE_FLOOR`] of its field (`exp(−4π Im(n cos θ) d / λ)` per layer, a round trip).
fn returns_light(stack: &Stack, angle_rad: f64, wavelengths_nm: &[f64]) -> Vec<bool> {
    let mut returns = vec![false; stack.layers.len()];
    for &w in wavelengths_nm {
        let Ok(media) = stack.media(w, angle_rad) else { continue };
        let mut reach = 1.0f64;
        for (i, l) in stack.layers.iter().enumerate() {
            if l.incoherent {
                reach = 1.0;
                continue;
            }
            let kz = (media[i + 1].n * media[i + 1].cos).im.max(0.0);
            reach *= (-4.0 * std::f64::consts::PI * kz * l.thickness_nm / w).exp();
            returns[i] |= reach >= FRINGE_FLOOR;
        }
    }
    returns
}

/// Checks a wavelength grid (nm, increasing) against the fringes of every coherent group of the stack at
/// this angle; `None` when every group is sampled at least twice per fringe.
pub fn check(stack: &Stack, angle_rad: f64, wavelengths_nm: &[f64]) -> Option<SamplingWarning> {
    if wavelengths_nm.len() < 2 {
        return None;
    }
    let step = wavelengths_nm.windows(2).map(|w| (w[1] - w[0]).abs()).fold(0.0, f64::max);
    let at = wavelengths_nm.iter().copied().fold(f64::INFINITY, f64::min);
    let media = stack.media(at, angle_rad).ok()?;
    let returns = returns_light(stack, angle_rad, wavelengths_nm);
    // Coherent groups: runs of coherent layers between incoherent media.
    let mut worst: Option<(f64, usize)> = None; // (optical thickness, thickest layer)
    let mut group = (0.0, 0usize, 0.0f64);
    let flush = |g: &mut (f64, usize, f64), worst: &mut Option<(f64, usize)>| {
        if g.0 > worst.map_or(0.0, |w| w.0) {
            *worst = Some((g.0, g.1));
        }
        *g = (0.0, 0, 0.0);
    };
    for (i, l) in stack.layers.iter().enumerate() {
        let m = media[i + 1];
        let optical = l.thickness_nm * (m.n * m.cos).re.max(0.0);
        if l.incoherent {
            flush(&mut group, &mut worst);
            // An incoherent layer's own thickness matters only through its absorption.
            continue;
        }
        if !returns[i] {
            // Opaque at every wavelength (a millimetre of gold): no light comes back to interfere.
            continue;
        }
        group.0 += optical;
        if optical > group.2 {
            group.1 = i + 1;
            group.2 = optical;
        }
    }
    flush(&mut group, &mut worst);
    let (optical, layer) = worst?;
    let fringe = at * at / (2.0 * optical);
    if fringe >= 2.0 * step {
        return None;
    }
    let step_nm = fringe / 2.0;
    let suggest_incoherent = 2.0 * optical > at * at / COHERENCE_BANDWIDTH_NM;
    let l = &stack.layers[layer - 1];
    let mut message = format!(
        "layer {layer} ({} {} nm) makes interference fringes {} nm apart at {} nm, closer than two samples of \
         the {} nm grid: the spectrum is aliased (a smooth curve where the fringes are). Use --step {}nm or \
         smaller",
        l.material.name(),
        l.thickness_nm,
        digits(round_sig(fringe), 3),
        digits(at, 6),
        digits(step, 6),
        digits(round_down(step_nm), 2)
    );
    if suggest_incoherent {
        message += &format!(
            "; or, since it is thicker than the coherence length of ordinary light ({} µm for a \
             {COHERENCE_BANDWIDTH_NM} nm band at {at} nm), write it as incoherent: inc:{} {}nm",
            digits(round_sig(at * at / COHERENCE_BANDWIDTH_NM / 1000.0), 3),
            l.material.name(),
            l.thickness_nm
        );
    }
    Some(SamplingWarning { layer, fringe_nm: fringe, at_nm: at, step_nm, suggest_incoherent, message })
}

/// `x` written with at most `significant` digits and no trailing zeros: `0.00028`, not the
/// `0.00028000000000000003` a rounded f64 prints as (nor `0.1` read back as `0.10000000000000009`).
fn digits(x: f64, significant: i32) -> String {
    if x == 0.0 || !x.is_finite() {
        return x.to_string();
    }
    let decimals = (significant - 1 - x.abs().log10().floor() as i32).max(0) as usize;
    let s = format!("{x:.decimals$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

fn round_sig(x: f64) -> f64 {
    let p = 10f64.powf(x.abs().log10().floor() - 2.0);
    (x / p).round() * p
}

/// `x` rounded down to 2 significant digits (a step that still resolves).
fn round_down(x: f64) -> f64 {
    let p = 10f64.powf(x.abs().log10().floor() - 1.0);
    (x / p).floor() * p
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(step: f64) -> Vec<f64> {
        (0..).map(|i| 380.0 + step * i as f64).take_while(|w| *w <= 780.0).collect()
    }

    #[test]
    fn water_20um_at_5nm_is_aliased() {
        // Fringe spacing λ²/(2 n d) = 380² / (2 · 1.33 · 20000) = 2.714 nm < 2 × 5 nm.
        let s = Stack::parse("air | water 20um | air").unwrap();
        let w = check(&s, 0.0, &grid(5.0)).unwrap();
        assert!((w.fringe_nm - 380.0 * 380.0 / (2.0 * 1.33 * 20000.0)).abs() < 1e-9);
        assert_eq!(w.layer, 1);
        assert!(!w.suggest_incoherent);
        assert!(w.message.contains("--step 1.3nm"), "{}", w.message);
        // At that step the grid resolves the fringes.
        assert!(check(&s, 0.0, &grid(1.3)).is_none());
        // A soap film is fine at 5 nm.
        assert!(check(&Stack::parse("air | water 635nm | air").unwrap(), 0.0, &grid(5.0)).is_none());
    }

    /// The message's numbers as a person writes them: X-rays at 0.4–0.7 nm on a 0.1 nm grid printed "the
    /// 0.10000000000000009 nm grid" and "--step 0.00028000000000000003nm". λ²/(2nd) = 0.16/276 = 0.00058 nm.
    #[test]
    fn the_numbers_are_written_short() {
        let s = Stack::parse("air | n=1.38 100nm | n=1.5").unwrap();
        let xrays: Vec<f64> = (4..=7).map(|i| i as f64 * 0.1).collect();
        let w = check(&s, 0.0, &xrays).unwrap();
        assert!(w.message.contains("fringes 0.00058 nm apart at 0.4 nm"), "{}", w.message);
        assert!(w.message.contains("the 0.1 nm grid") && w.message.contains("--step 0.00028nm or"), "{}", w.message);
        assert!(w.message.contains("(0.00016 µm for a 1 nm band at 0.4 nm)"), "{}", w.message);
    }

    #[test]
    fn a_millimetre_suggests_inc() {
        let s = Stack::parse("air | MgF2 100nm | BK7 1mm | air").unwrap();
        let w = check(&s, 0.0, &grid(5.0)).unwrap();
        assert_eq!(w.layer, 2);
        assert!(w.suggest_incoherent && w.message.contains("inc:bk7 1000000nm"), "{}", w.message);
        // Written incoherent, the remaining coherent group (100 nm) is fine.
        assert!(check(&Stack::parse("air | MgF2 100nm | inc:BK7 1mm | air").unwrap(), 0.0, &grid(5.0)).is_none());
    }

    #[test]
    fn an_opaque_layer_makes_no_fringes() {
        // 1 mm of gold returns exp(−4π κ d/λ) ≈ e^−76000 of the field at 780 nm (κ = 4.74): no fringes to alias,
        // and none from the water under it; it was once told to write itself as incoherent.
        assert!(check(&Stack::parse("air | Au 1mm | water 20um | air").unwrap(), 0.0, &grid(5.0)).is_none());
        // 20 µm of water over 1 mm of gold still aliases (its own fringes come back).
        let w = check(&Stack::parse("air | water 20um | Au 1mm | air").unwrap(), 0.0, &grid(5.0)).unwrap();
        assert_eq!(w.layer, 1);
        // Silicon is opaque in the blue but not in the red: 30 µm returns 9e-159 of the field at 400 nm
        // (κ = 0.386) but 0.024 at 780 nm (κ = 0.0077), so its fringes are warned about.
        let si = Stack::parse("air | Si 30um | air").unwrap();
        let to_780: Vec<f64> = grid(5.0).into_iter().filter(|&w| w >= 400.0).collect();
        assert!(check(&si, 0.0, &to_780).is_some());
    }
}
