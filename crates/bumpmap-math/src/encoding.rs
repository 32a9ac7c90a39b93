//! How a unit vector in [-1, 1]³ becomes bytes and back (Kilgard Eq. 28, Appendix D–F).
//!
//! Two encodings exist because the paper's code truncates `128 + 127·n` while today's tools
//! round `127.5·n + 127.5`. Normal maps are linear data: nothing here knows about sRGB.

/// Range compression of a signed component into a byte.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, Hash)]
pub enum Encoding {
    /// `round(127.5·n + 127.5)`: the modern default, symmetric, 0 ↦ 127.5 rounds to 128.
    #[default]
    Unorm,
    /// `(GLubyte)(128 + 127·n)`, truncated, as in Kilgard Appendices D, E and F.
    Kilgard,
}

impl Encoding {
    /// Encodes one signed component. Inputs outside [-1, 1] saturate.
    #[inline(always)]
    pub fn encode(self, n: f32) -> u8 {
        // 127.5 + 0.5 = 128 folds unorm's rounding into the offset; truncation does the rest.
        let v = match self {
            Encoding::Unorm => n * 127.5 + 128.0,
            Encoding::Kilgard => 128.0 + 127.0 * n,
        };
        // `max` first maps NaN to 0; the clamped value is a valid i32, so the unchecked
        // conversion is sound and vectorizes where a saturating `as u8` does not.
        #[allow(clippy::manual_clamp)] // clamp would keep NaN, which the conversion must not see
        let v = v.max(0.0).min(255.0);
        // SAFETY: v is finite and in [0, 255].
        unsafe { v.to_int_unchecked::<i32>() as u8 }
    }

    /// Encodes an unsigned magnitude in [0, 1] (the mip chain's alpha, Kilgard Appendix F).
    #[inline(always)]
    pub fn encode_unsigned(self, a: f32) -> u8 {
        let a = a.clamp(0.0, 1.0);
        match self {
            Encoding::Unorm => (a * 255.0 + 0.5) as u8,
            Encoding::Kilgard => (a * 255.0) as u8,
        }
    }

    /// The exact inverse of [`Encoding::encode`] at byte centres.
    #[inline(always)]
    pub fn decode(self, b: u8) -> f32 {
        match self {
            Encoding::Unorm => expand_normal(b),
            Encoding::Kilgard => (b as f32 - 128.0) / 127.0,
        }
    }

    /// The name used on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Encoding::Unorm => "unorm",
            Encoding::Kilgard => "kilgard",
        }
    }
}

/// What the register combiners' `EXPAND_NORMAL_NV` does to a texel byte: `2·b/255 − 1`.
#[inline(always)]
pub fn expand_normal(b: u8) -> f32 {
    b as f32 * (2.0 / 255.0) - 1.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unorm_round_trips_every_byte() {
        for b in 0..=255u8 {
            assert_eq!(Encoding::Unorm.encode(Encoding::Unorm.decode(b)), b);
        }
    }

    #[test]
    fn kilgard_matches_the_c_cast() {
        // 128 + 127·1 = 255, 128 + 127·(-1) = 1, 128 + 0 = 128: the paper never writes 0.
        assert_eq!(Encoding::Kilgard.encode(1.0), 255);
        assert_eq!(Encoding::Kilgard.encode(-1.0), 1);
        assert_eq!(Encoding::Kilgard.encode(0.0), 128);
        assert_eq!(Encoding::Kilgard.encode(0.5), 191); // 191.5 truncated
        assert_eq!(Encoding::Unorm.encode(0.0), 128);
        assert_eq!(Encoding::Unorm.encode(-1.0), 0);
    }
}
