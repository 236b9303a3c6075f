//! Compact encodings of a lookup table for the GPU's lookup shader, which is memory-bound (issue 17): what each
//! grid cell stores per channel, and the CPU evaluation of the stored numbers that the shader must reproduce.
//!
//! * [`TableEncoding::F32`]: the `2N+1` powers `I_p` (eq. 10–12) rounded to `f32` — the default, what
//!   `Lookup` with `Precision::F32` evaluates;
//! * [`TableEncoding::F16`]: the same powers in IEEE half precision, two per 32-bit word, each (channel, power)
//!   scaled by a power of two so that its largest value sits near the top of the half range (so values down
//!   to ~2e-9 of it stay normal numbers);
//! * [`TableEncoding::Chebyshev`]: instead of the `2N+1` powers, `K` Chebyshev coefficients in `w`. For a
//!   fixed `(u, v)` the lookup sum `f(w) = Σ_p w^p I_p(u, v)` is a polynomial of degree `2N` in
//!   `w = −(cos θ_i + cos θ_r) ∈ [−2, 0]`; with `t = w + 1 ∈ [−1, 1]` it is approximated by the interpolant at
//!   the `K` Chebyshev points, `f ≈ Σ_{j<K} a_j T_j(t)` (exact for `K = 2N+1`; the error of fewer terms falls
//!   as fast as the Chebyshev coefficients of `f`, i.e. with how much `|A|²` oscillates in `w`). The idea of
//!   Dhillon & Ghosh (2016), who store Chebyshev approximations in two textures instead of `2N+1` tables; their
//!   exact scheme is not among the sources here, this is ours. The coefficients are linear in the table, so
//!   bilinear interpolation in `(u, v)` commutes with the encoding; Clenshaw's recurrence evaluates them. They
//!   can be stored as `f32` or as `f16` (scaled like the powers).

use crate::table::{grid_index, LookupTable};
use crate::DiffractionError;

/// How a table's cells are stored for the GPU.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum TableEncoding {
    #[default]
    F32,
    F16,
    /// `terms` Chebyshev coefficients per cell and channel, in `f16` when `half`.
    Chebyshev {
        terms: usize,
        half: bool,
    },
}

impl TableEncoding {
    /// What `brdf-map --gpu` stores unless told otherwise: 12 Chebyshev terms in `f32`, 3.75× less memory
    /// than the `f32` powers of a table with N = 22 and as exact: against the `f64` lookup on every built-in at
    /// 501², mean CIEDE2000 < 0.0001 and at most 0.001 (docs/gpu.md, `examples/table_encodings.rs`), far
    /// inside the bound it had to meet (mean < 0.05). `cheb12-f16` halves the memory again and meets the mean
    /// bound too (≤ 0.005), but single pixels next to a grating's specular peak reach ΔE00 4–21. Surfaces whose
    /// `|h|max` far exceeds the built-ins' ~150 nm make `f(w)` oscillate faster and may need more terms.
    pub const GPU_DEFAULT: TableEncoding = TableEncoding::Chebyshev { terms: 12, half: false };

    /// The name the command line uses: `f32`, `f16`, `chebK`, `chebK-f16`.
    pub fn name(&self) -> String {
        match self {
            TableEncoding::F32 => "f32".into(),
            TableEncoding::F16 => "f16".into(),
            TableEncoding::Chebyshev { terms, half: false } => format!("cheb{terms}"),
            TableEncoding::Chebyshev { terms, half: true } => format!("cheb{terms}-f16"),
        }
    }

    /// Whether values are stored as `f16`.
    pub fn is_half(&self) -> bool {
        matches!(self, TableEncoding::F16 | TableEncoding::Chebyshev { half: true, .. })
    }
}

impl std::str::FromStr for TableEncoding {
    type Err = DiffractionError;
    fn from_str(s: &str) -> Result<Self, DiffractionError> {
        let t = s.trim().to_ascii_lowercase();
        let bad = || {
            DiffractionError::Invalid(format!(
                "table encoding '{s}': expected chebK or chebK-f16 (K Chebyshev coefficients in w instead of the \
                 2N+1 powers, K from 2 to 201; cheb12 is the GPU map's default), f32 or f16 (the powers, in half \
                 precision: half the memory)"
            ))
        };
        match t.as_str() {
            "f32" => return Ok(TableEncoding::F32),
            "f16" | "half" => return Ok(TableEncoding::F16),
            _ => {}
        }
        let rest = t.strip_prefix("cheb").ok_or_else(bad)?;
        let (k, half) = match rest.strip_suffix("-f16") {
            Some(k) => (k, true),
            None => (rest, false),
        };
        let terms: usize = k.parse().map_err(|_| bad())?;
        if !(2..=201).contains(&terms) {
            return Err(bad());
        }
        Ok(TableEncoding::Chebyshev { terms, half })
    }
}

/// A table in one of the encodings, as the GPU stores it: 32-bit words, cell by cell in the table's order.
#[derive(Debug, Clone)]
pub struct EncodedTable {
    pub encoding: TableEncoding,
    pub res: usize,
    pub uv_power: f64,
    /// Coefficients per channel: `2N+1` powers or `K` Chebyshev terms.
    pub per_channel: usize,
    /// 32-bit words per channel: `per_channel` in `f32`, half of it (rounded up) in `f16`.
    pub words_per_channel: usize,
    /// `words[((iv · res + iu) · 3 + c) · words_per_channel + j]`; in `f16` word `j` holds coefficient `2j` in its
    /// low half and `2j + 1` in its high half (`unpack2x16float`).
    pub words: Vec<u32>,
    /// The factor each stored value is multiplied by, per `(channel, coefficient)`: `[c · per_channel + j]`
    /// (1 in `f32`).
    pub scales: Vec<f32>,
}

/// Chebyshev interpolation of `f` on `[−1, 1]` at the `K` points of the first kind: coefficients `a_j` with
/// `f ≈ Σ_j a_j T_j(t)` (the constant term already halved).
pub fn chebyshev_coefficients(values_at_nodes: &[f64]) -> Vec<f64> {
    let k = values_at_nodes.len();
    (0..k)
        .map(|j| {
            let s: f64 = values_at_nodes
                .iter()
                .enumerate()
                .map(|(m, f)| f * (std::f64::consts::PI * j as f64 * (m as f64 + 0.5) / k as f64).cos())
                .sum();
            s * 2.0 / k as f64 * if j == 0 { 0.5 } else { 1.0 }
        })
        .collect()
}

/// The Chebyshev points of the first kind on `[−1, 1]`.
pub fn chebyshev_nodes(k: usize) -> Vec<f64> {
    (0..k).map(|m| (std::f64::consts::PI * (m as f64 + 0.5) / k as f64).cos()).collect()
}

/// `Σ_j a_j T_j(t)` by Clenshaw's recurrence (the shader's order of operations).
pub fn clenshaw(a: &[f64], t: f64) -> f64 {
    let (mut b1, mut b2) = (0.0, 0.0);
    for j in (1..a.len()).rev() {
        let b = a[j] + 2.0 * t * b1 - b2;
        b2 = b1;
        b1 = b;
    }
    a[0] + t * b1 - b2
}

/// The power of two that puts `max` near the top of the `f16` range (2¹⁵, below its 65504).
pub fn half_scale(max: f32) -> f32 {
    if max > 0.0 && max.is_finite() {
        2f32.powi(max.log2().ceil() as i32 - 15)
    } else {
        1.0
    }
}

impl EncodedTable {
    /// Encodes a table (the powers are taken from its `f64` values).
    pub fn encode(table: &LookupTable, encoding: TableEncoding) -> Result<Self, DiffractionError> {
        let res = table.meta.uv_resolution;
        let np = table.powers();
        let cells = res * res;
        // The coefficients per cell and channel, in f64.
        let coeffs: Vec<f64> = match encoding {
            TableEncoding::F32 | TableEncoding::F16 => table.data.clone(),
            TableEncoding::Chebyshev { terms, .. } => {
                if terms < 2 {
                    return Err(DiffractionError::Invalid("a Chebyshev encoding needs at least 2 terms".into()));
                }
                let nodes = chebyshev_nodes(terms);
                let mut out = vec![0.0; cells * 3 * terms];
                let mut f = vec![0.0; terms];
                for (cell, chunk) in table.data.chunks_exact(np).enumerate() {
                    for (fm, t) in f.iter_mut().zip(&nodes) {
                        let w = t - 1.0;
                        *fm = chunk.iter().rev().fold(0.0, |acc, ip| acc * w + ip);
                    }
                    out[cell * terms..(cell + 1) * terms].copy_from_slice(&chebyshev_coefficients(&f));
                }
                out
            }
        };
        let per_channel = match encoding {
            TableEncoding::Chebyshev { terms, .. } => terms,
            _ => np,
        };
        let half = encoding.is_half();
        let mut scales = vec![1f32; 3 * per_channel];
        if half {
            for c in 0..3 {
                for j in 0..per_channel {
                    let max = (0..cells)
                        .map(|cell| (coeffs[(cell * 3 + c) * per_channel + j] as f32).abs())
                        .fold(0.0f32, f32::max);
                    scales[c * per_channel + j] = half_scale(max);
                }
            }
        }
        let words_per_channel = if half { per_channel.div_ceil(2) } else { per_channel };
        let mut words = vec![0u32; cells * 3 * words_per_channel];
        for (k, (out, src)) in
            words.chunks_exact_mut(words_per_channel).zip(coeffs.chunks_exact(per_channel)).enumerate()
        {
            let c = k % 3;
            if half {
                for (j, v) in src.iter().enumerate() {
                    let h = half::f16::from_f32(*v as f32 / scales[c * per_channel + j]).to_bits() as u32;
                    out[j / 2] |= if j & 1 == 0 { h } else { h << 16 };
                }
            } else {
                for (o, v) in out.iter_mut().zip(src) {
                    *o = (*v as f32).to_bits();
                }
            }
        }
        Ok(Self { encoding, res, uv_power: table.meta.uv_power, per_channel, words_per_channel, words, scales })
    }

    /// Coefficient `j` of channel `c` at grid row `iv`, column `iu`, as the shader decodes it.
    pub fn coefficient(&self, iv: usize, iu: usize, c: usize, j: usize) -> f32 {
        let word = self.words[((iv * self.res + iu) * 3 + c) * self.words_per_channel + j / (1 + self.half() as usize)];
        if self.half() {
            let bits = if j & 1 == 0 { word & 0xffff } else { word >> 16 };
            half::f16::from_bits(bits as u16).to_f32() * self.scales[c * self.per_channel + j]
        } else {
            f32::from_bits(word)
        }
    }

    fn half(&self) -> bool {
        self.encoding.is_half()
    }

    /// Bytes the GPU stores.
    pub fn bytes(&self) -> usize {
        self.words.len() * 4
    }

    /// `Σ_p w^p I_p(u, v)` per channel from the stored numbers, as the shader evaluates it (bilinear in the
    /// grid's index space, then Horner or Clenshaw), in `f64`.
    pub fn sum(&self, u: f64, v: f64, w: f64) -> [f64; 3] {
        let res = self.res;
        let (qu, qv) = (grid_index(u, res, self.uv_power), grid_index(v, res, self.uv_power));
        let (iu, iv) = ((qu.floor() as usize).min(res - 2), (qv.floor() as usize).min(res - 2));
        let (fu, fv) = (qu - iu as f64, qv - iv as f64);
        let corners = [
            (iv, iu, (1.0 - fu) * (1.0 - fv)),
            (iv, iu + 1, fu * (1.0 - fv)),
            (iv + 1, iu, (1.0 - fu) * fv),
            (iv + 1, iu + 1, fu * fv),
        ];
        let mut out = [0.0; 3];
        for (c, o) in out.iter_mut().enumerate() {
            let a: Vec<f64> = (0..self.per_channel)
                .map(|j| corners.iter().map(|&(r, q, wt)| wt * self.coefficient(r, q, c, j) as f64).sum())
                .collect();
            *o = match self.encoding {
                TableEncoding::Chebyshev { .. } => clenshaw(&a, w + 1.0),
                _ => a.iter().rev().fold(0.0, |acc, ip| acc * w + ip),
            };
        }
        out
    }
}
