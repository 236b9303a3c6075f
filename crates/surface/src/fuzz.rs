//! Input mutation for robustness testing of the binary readers (used by `examples/fuzz.rs` and the
//! deterministic robustness tests; cargo-fuzz needs nightly). Bit flips, byte overwrites with "interesting"
//! values, truncation, 32-bit size fields overwritten with extreme values, splices from another input,
//! duplicated and deleted ranges — driven by a seeded [`Rng`], so a failure is reproducible.

use crate::rng::Rng;

const INTERESTING: [u8; 10] = [0, 1, 0x7f, 0x80, 0xff, b'0', b'9', b'\n', b'.', b'e'];

/// One mutated copy of `src` (1–8 operations); `other` supplies spliced bytes.
pub fn mutate(rng: &mut Rng, src: &[u8], other: &[u8]) -> Vec<u8> {
    let mut b = src.to_vec();
    let n_ops = 1 + rng.int(0, 7);
    for _ in 0..n_ops {
        let len = b.len().max(1);
        let at = (rng.next_u64() as usize) % len;
        match rng.int(0, 6) {
            0 if !b.is_empty() => b[at] ^= 1 << rng.int(0, 7),
            1 if !b.is_empty() => b[at] = INTERESTING[rng.int(0, 9) as usize],
            2 => b.truncate(at),
            3 if !b.is_empty() => {
                // Overwrite 4 bytes with a large or negative 32-bit value (sizes and counts).
                let v = [u32::MAX, 0x7fff_ffff, 0x8000_0000, 0, 1 << 20][rng.int(0, 4) as usize].to_le_bytes();
                for (k, byte) in v.iter().enumerate() {
                    if at + k < b.len() {
                        b[at + k] = *byte;
                    }
                }
            }
            4 if !other.is_empty() => {
                let from = (rng.next_u64() as usize) % other.len();
                let n = ((rng.next_u64() as usize) % 64).min(other.len() - from);
                b.splice(at.min(b.len())..at.min(b.len()), other[from..from + n].iter().copied());
            }
            5 if !b.is_empty() => {
                let n = ((rng.next_u64() as usize) % 32).min(b.len() - at);
                let chunk: Vec<u8> = b[at..at + n].to_vec();
                b.splice(at..at, chunk);
            }
            _ if !b.is_empty() => {
                let n = ((rng.next_u64() as usize) % 32).min(b.len() - at);
                b.drain(at..at + n);
            }
            _ => {}
        }
    }
    b
}
