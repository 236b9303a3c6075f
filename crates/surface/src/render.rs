//! A shaded-relief picture of a height field: colour from height (a caller-supplied colour map), brightness
//! from a light in the upper left, and a scale bar, so a person sees the structure's shape and size at once.

use crate::HeightField;

/// An RGB picture, row-major, row 0 at the top (the field's row 0).
#[derive(Debug, Clone)]
pub struct Relief {
    pub width: usize,
    pub height: usize,
    pub rgb: Vec<u8>,
    /// Physical size of one picture pixel (nm).
    pub pixel_nm: (f64, f64),
    /// Length of the drawn scale bar (nm).
    pub scale_bar_nm: f64,
}

/// 1, 2 or 5 × 10ⁿ nm, the largest not above `x`.
pub fn round_length(x: f64) -> f64 {
    let e = 10f64.powf(x.log10().floor());
    [5.0, 2.0, 1.0].iter().map(|m| m * e).find(|&v| v <= x).unwrap_or(e)
}

/// Human form of a length: `500 nm`, `2 µm`, `1.5 mm`.
pub fn format_length(nm: f64) -> String {
    if nm >= 1e6 {
        format!("{} mm", nm / 1e6)
    } else if nm >= 1e3 {
        format!("{} µm", nm / 1e3)
    } else {
        format!("{nm} nm")
    }
}

/// Renders at most `max_side` picture pixels per side (block-averaging larger fields).
pub fn shaded_relief(hf: &HeightField, max_side: usize, cmap: fn(f64) -> [u8; 3]) -> Relief {
    let k = hf.rows.max(hf.cols).div_ceil(max_side.max(2)).max(1);
    let (h, w) = (hf.rows.div_ceil(k), hf.cols.div_ceil(k));
    let mut z = vec![0.0; w * h];
    for r in 0..h {
        for c in 0..w {
            let (mut s, mut n) = (0.0, 0.0);
            for rr in r * k..((r + 1) * k).min(hf.rows) {
                for cc in c * k..((c + 1) * k).min(hf.cols) {
                    s += hf.heights_nm[rr * hf.cols + cc];
                    n += 1.0;
                }
            }
            z[r * w + c] = s / n;
        }
    }
    let (px, py) = (hf.dx_nm * k as f64, hf.dy_nm * k as f64);
    let (lo, hi) = z.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| (a.min(v), b.max(v)));
    let span = if hi > lo { hi - lo } else { 1.0 };
    // Vertical exaggeration: make the typical slope about 1 so shading shows the structure whatever its
    // aspect ratio (nanostructures are far flatter than they are wide).
    let mut grads = Vec::with_capacity(w * h);
    for r in 0..h {
        for c in 0..w {
            let gx = (z[r * w + (c + 1).min(w - 1)] - z[r * w + c.saturating_sub(1)]) / (2.0 * px);
            let gy = (z[r.saturating_sub(1) * w + c] - z[(r + 1).min(h - 1) * w + c]) / (2.0 * py);
            grads.push((gx, gy));
        }
    }
    let mut mags: Vec<f64> = grads.iter().map(|g| g.0.hypot(g.1)).collect();
    mags.sort_by(f64::total_cmp);
    let typical = mags[mags.len() * 9 / 10].max(1e-12);
    let exag = 1.0 / typical;
    // Light from the upper left (azimuth 135° from +x, y up), 45° above the horizon.
    let r = std::f64::consts::FRAC_1_SQRT_2;
    let l = [-0.5, 0.5, r];
    let mut rgb = vec![0u8; w * h * 3];
    for i in 0..w * h {
        let (gx, gy) = (grads[i].0 * exag, grads[i].1 * exag);
        let n = [-gx, -gy, 1.0];
        let nn = (n[0] * n[0] + n[1] * n[1] + 1.0).sqrt();
        let shade = ((n[0] * l[0] + n[1] * l[1] + n[2] * l[2]) / nn).max(0.0);
        let base = cmap((z[i] - lo) / span);
        let f = 0.3 + 0.9 * shade;
        for ch in 0..3 {
            rgb[i * 3 + ch] = (f64::from(base[ch]) * f).round().clamp(0.0, 255.0) as u8;
        }
    }
    // Scale bar: about a fifth of the width, bottom left, white with a black outline.
    let bar_nm = round_length(0.2 * w as f64 * px);
    let bar_px = ((bar_nm / px).round() as usize).max(1);
    let thick = (h / 60).max(3);
    let (x0, y1) = ((w / 20).max(2), h.saturating_sub((h / 20).max(2)));
    let y0 = y1.saturating_sub(thick);
    for y in y0.saturating_sub(1)..=(y1 + 1).min(h - 1) {
        for x in x0.saturating_sub(1)..=(x0 + bar_px + 1).min(w - 1) {
            let inside = y >= y0 && y <= y1 && x >= x0 && x <= x0 + bar_px;
            let c = if inside { 255 } else { 0 };
            rgb[(y * w + x) * 3..(y * w + x) * 3 + 3].copy_from_slice(&[c, c, c]);
        }
    }
    Relief { width: w, height: h, rgb, pixel_nm: (px, py), scale_bar_nm: bar_nm }
}
