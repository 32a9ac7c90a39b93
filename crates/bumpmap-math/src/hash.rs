//! Integer hashes, once: deterministic numbers from coordinates and seeds, the same on every
//! platform and run, for procedural heights (noise, the bricks' tints) and for the reference's
//! stratified jitter and occlusion rays. Two widths: [`splitmix64`] where 64 bits of a seed
//! matter (the noise presets), [`hash32`] of several 32-bit words elsewhere, and [`unit()`] to
//! turn a hash into a number in [0, 1).
//!
//! What this module does not do: cryptography, or sequences with low discrepancy (the
//! reference's strata add their own R2 offsets).
//!
//! ```
//! use bumpmap_math::hash::{hash32, splitmix64, unit};
//! assert_eq!(hash32(&[3, 4]), hash32(&[3, 4]), "the same words, the same hash");
//! assert_ne!(hash32(&[3, 4]), hash32(&[4, 3]));
//! assert!((0.0..1.0).contains(&unit(hash32(&[7]))));
//! assert_eq!(splitmix64(0), 0xe220_a839_7b1d_cdaf, "SplitMix64's first output for seed 0");
//! ```

/// SplitMix64's output function (Steele, Lea & Flood 2014) of `x`.
pub fn splitmix64(x: u64) -> u64 {
    let mut z = x.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// The odd multipliers that spread each word before they are combined (the golden ratio's and
/// MurmurHash3's and xxHash's primes); a word past the fifth reuses them in turn.
const SPREAD: [u32; 5] = [0x9E37_79B1, 0x85EB_CA77, 0xC2B2_AE3D, 0x27D4_EB2F, 0x1656_67B1];

/// A 32-bit hash of `words`: each multiplied by its own odd constant, combined by xor, then
/// mixed by lowbias32 (Wellons' 32-bit finalizer, bias about 0.17 ‰).
pub fn hash32(words: &[u32]) -> u32 {
    let mut h = words.iter().zip(SPREAD.iter().cycle()).fold(0u32, |h, (w, k)| h ^ w.wrapping_mul(*k));
    h ^= h >> 16;
    h = h.wrapping_mul(0x7FEB_352D);
    h ^= h >> 15;
    h = h.wrapping_mul(0x846C_A68B);
    h ^ (h >> 16)
}

/// A hash as a number in [0, 1): its top 24 bits over 2²⁴.
pub fn unit(h: u32) -> f32 {
    (h >> 8) as f32 / (1u32 << 24) as f32
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Neighbouring coordinates give unrelated numbers: over a 64×64 grid the mean is near ½
    /// and each output bit is set about half the time.
    #[test]
    fn neighbours_are_unrelated() {
        let hashes: Vec<u32> = (0..64u32).flat_map(|y| (0..64u32).map(move |x| hash32(&[x, y]))).collect();
        let mean = hashes.iter().map(|&h| unit(h) as f64).sum::<f64>() / hashes.len() as f64;
        assert!((mean - 0.5).abs() < 0.02, "{mean}");
        for bit in 0..32 {
            let set = hashes.iter().filter(|&&h| h >> bit & 1 == 1).count() as f64 / hashes.len() as f64;
            assert!((set - 0.5).abs() < 0.05, "bit {bit}: {set}");
        }
    }
}
