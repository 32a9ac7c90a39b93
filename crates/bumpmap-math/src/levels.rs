//! The sizes of a mip chain, once: each level half the one before, rounded down, at least 1,
//! down to 1×1 (GL 1.2 §3.8.9); which texels of a level a texel of the next one covers (an odd
//! last texel folds into its neighbour's footprint); and the one check that a chain someone
//! hands over has those sizes. Normal maps, heights, horizons, LEAN's moments and the texture
//! files all take their levels' sizes from here.
//!
//! What this module does not do: filter a level (each chain's module does), or hold texels.
//!
//! ```
//! use bumpmap_math::levels::{chain_sizes, check_chain, level_count};
//! assert_eq!(chain_sizes(5, 3), [(5, 3), (2, 1), (1, 1)]);
//! assert_eq!(level_count(256, 64), 9);
//! assert!(check_chain([(4, 4), (2, 2), (1, 1)]).is_ok());
//! assert_eq!(check_chain([(4, 4), (2, 1)]).unwrap_err().to_string(), "level 1 is 2x1, but a 4x4 level 0 makes it 2x2");
//! ```

/// The size of the level after one of `n` texels: half, rounded down, at least 1.
#[inline]
pub fn next_size(n: usize) -> usize {
    (n / 2).max(1)
}

/// How many levels a full chain from a `width`×`height` level 0 has, down to 1×1:
/// `1 + floor(log2(max(width, height)))` (0 for an empty level 0).
///
/// ```
/// use bumpmap_math::levels::level_count;
/// assert_eq!((level_count(1, 1), level_count(256, 64), level_count(5, 3)), (1, 9, 3));
/// ```
pub fn level_count(width: usize, height: usize) -> usize {
    width.max(height).checked_ilog2().map_or(0, |l| l as usize + 1)
}

/// The range of texels of a level of size `n` that texel `i` of the next level covers.
#[inline]
pub fn footprint(i: usize, n: usize) -> std::ops::Range<usize> {
    let m = next_size(n);
    debug_assert!(i < m);
    let end = if i + 1 == m { n } else { 2 * i + 2 };
    2 * i..end
}

/// Every level's size of a full chain from `width`×`height`, level 0 first, down to 1×1.
pub fn chain_sizes(width: usize, height: usize) -> Vec<(usize, usize)> {
    let mut sizes = vec![(width, height)];
    while sizes.last() != Some(&(1, 1)) {
        let (w, h) = *sizes.last().expect("one size at least");
        sizes.push((next_size(w), next_size(h)));
    }
    sizes
}

/// Why a chain's sizes are not a chain's.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
pub enum LevelSizeError {
    /// No level at all.
    #[error("a chain without levels")]
    Empty,
    /// More levels than the chain has before 1×1.
    #[error("{levels} levels for a {}x{} level 0: its chain ends at 1x1 after {most} levels", first.0, first.1)]
    TooMany {
        /// The levels given.
        levels: usize,
        /// Level 0's size.
        first: (usize, usize),
        /// The most levels its chain has.
        most: usize,
    },
    /// A level of another size than the one before it makes.
    #[error("level {level} is {}x{}, but a {}x{} level 0 makes it {}x{}", got.0, got.1, first.0, first.1, want.0, want.1)]
    Size {
        /// The level.
        level: usize,
        /// Its size.
        got: (usize, usize),
        /// Level 0's size.
        first: (usize, usize),
        /// The size it must have.
        want: (usize, usize),
    },
}

/// Checks that `sizes` (level 0 first) are the first levels of a chain: each half the one
/// before, and no more of them than reach 1×1.
pub fn check_chain(sizes: impl IntoIterator<Item = (usize, usize)>) -> Result<(), LevelSizeError> {
    let mut sizes = sizes.into_iter();
    let first = sizes.next().ok_or(LevelSizeError::Empty)?;
    let most = level_count(first.0, first.1);
    let mut want = first;
    let mut levels = 1;
    for (level, got) in sizes.enumerate().map(|(k, s)| (k + 1, s)) {
        levels += 1;
        if levels > most {
            return Err(LevelSizeError::TooMany { levels, first, most });
        }
        want = (next_size(want.0), next_size(want.1));
        if got != want {
            return Err(LevelSizeError::Size { level, got, first, want });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_chain_halves_rounding_down_to_one_by_one() {
        for (w, h) in [(1, 1), (7, 3), (256, 64), (1000, 1)] {
            let sizes = chain_sizes(w, h);
            assert_eq!(sizes.len(), level_count(w, h), "{w}x{h}");
            assert_eq!(sizes.last(), Some(&(1, 1)));
            assert_eq!(check_chain(sizes.iter().copied()), Ok(()));
            // Every texel of a level lies in exactly one footprint of the next.
            for pair in sizes.windows(2) {
                let covered: usize = (0..pair[1].0).map(|i| footprint(i, pair[0].0).len()).sum();
                assert_eq!(covered, pair[0].0);
            }
        }
    }

    #[test]
    fn a_wrong_chain_is_named() {
        assert_eq!(check_chain([]), Err(LevelSizeError::Empty));
        let too_many = check_chain([(2, 2), (1, 1), (1, 1)]);
        assert_eq!(too_many, Err(LevelSizeError::TooMany { levels: 3, first: (2, 2), most: 2 }));
        let wrong = check_chain([(8, 4), (4, 2), (2, 2)]);
        assert_eq!(wrong, Err(LevelSizeError::Size { level: 2, got: (2, 2), first: (8, 4), want: (2, 1) }));
    }
}
