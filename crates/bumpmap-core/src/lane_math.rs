//! `max`, `min` and `clamp` for the lane loops, written so that each compiles to one vector
//! instruction.
//!
//! `f32::max` must return the other argument when one is NaN, whichever side the NaN is on,
//! and `f32::clamp` must return a NaN unchanged; both cost a compare and a blend per vector on
//! top of the `maxps`/`minps`. Here the bound always wins over a NaN (`x86`'s own rule when the
//! NaN is the first operand), which is also what the pipeline wants: a NaN fragment value
//! clamps to the range's low end instead of spreading. For other inputs the results are those
//! of the `std` functions. Not for anything where a NaN must survive.

/// `x` if `x > lo`, else `lo` (also when `x` is NaN).
#[inline(always)]
pub fn max_lo(x: f32, lo: f32) -> f32 {
    if x > lo { x } else { lo }
}

/// `x` if `x < hi`, else `hi` (also when `x` is NaN).
#[inline(always)]
pub fn min_hi(x: f32, hi: f32) -> f32 {
    if x < hi { x } else { hi }
}

/// `x` clamped to `[lo, hi]`; NaN gives `lo`. Precondition: `lo <= hi`.
#[inline(always)]
pub fn clamp_lo(x: f32, lo: f32, hi: f32) -> f32 {
    debug_assert!(lo <= hi, "clamp_lo: empty range [{lo}, {hi}]");
    min_hi(max_lo(x, lo), hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn agree_with_std_except_that_nan_takes_the_bound() {
        let values = [-2.0f32, -1.0, -0.5, 0.0, 0.25, 1.0, 3.0, f32::INFINITY, f32::NEG_INFINITY];
        for &x in &values {
            for &b in &values {
                assert_eq!(max_lo(x, b), x.max(b), "max_lo({x}, {b})");
                assert_eq!(min_hi(x, b), x.min(b), "min_hi({x}, {b})");
            }
            assert_eq!(clamp_lo(x, -1.0, 1.0), x.clamp(-1.0, 1.0), "clamp_lo({x})");
        }
        assert_eq!(max_lo(f32::NAN, 0.0), 0.0);
        assert_eq!(min_hi(f32::NAN, 1.0), 1.0);
        assert_eq!(clamp_lo(f32::NAN, 0.0, 1.0), 0.0);
    }
}
