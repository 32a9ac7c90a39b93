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

crate::named!(Encoding {
    Unorm => "unorm": "round(127.5·n + 127.5): symmetric, what modern tools write",
    Kilgard => "kilgard": "(byte)(128 + 127·n), truncated: the paper's Appendices D–F, byte for byte",
});

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

    /// [`Encoding::encode`] at 16 bits: `round(32767.5·n + 32767.5)` or the truncated
    /// `32768 + 32767·n`. Inputs outside [-1, 1] saturate; NaN encodes as 0.
    #[inline(always)]
    pub fn encode16(self, n: f32) -> u16 {
        let v = match self {
            Encoding::Unorm => n * 32767.5 + 32768.0,
            Encoding::Kilgard => 32768.0 + 32767.0 * n,
        };
        #[allow(clippy::manual_clamp)] // as in `encode`: NaN must become 0 before the conversion
        let v = v.max(0.0).min(65535.0);
        // SAFETY: v is finite and in [0, 65535].
        unsafe { v.to_int_unchecked::<i32>() as u16 }
    }

    /// [`Encoding::encode_unsigned`] at 16 bits.
    #[inline(always)]
    pub fn encode16_unsigned(self, a: f32) -> u16 {
        let a = a.clamp(0.0, 1.0);
        match self {
            Encoding::Unorm => (a * 65535.0 + 0.5) as u16,
            Encoding::Kilgard => (a * 65535.0) as u16,
        }
    }

    /// The inverse of [`Encoding::encode16`] at its steps.
    #[inline(always)]
    pub fn decode16(self, v: u16) -> f32 {
        match self {
            Encoding::Unorm => v as f32 * (2.0 / 65535.0) - 1.0,
            Encoding::Kilgard => (v as f32 - 32768.0) / 32767.0,
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

/// A stored normal-map texel: four unsigned-normalized channels, 8 or 16 bits each.
///
/// The normal map and its mip chain are written through this trait, so one code path (and
/// its SIMD variants) makes both depths. At 16 bits the encodings are the same formulas
/// with 2¹⁶ in place of 2⁸: unorm rounds `32767.5·n + 32767.5`, Kilgard truncates
/// `32768 + 32767·n`. Sealed: all-zero bytes are a valid value of every implementor, which
/// the zeroed output buffers rely on.
pub trait Texel: sealed::Sealed + Copy + Default + PartialEq + std::fmt::Debug + Send + Sync + 'static {
    /// Bits per channel.
    const BITS: u32;
    /// A direction's three signed components in RGB and an unsigned magnitude in [0, 1] in A.
    fn pack(x: f32, y: f32, z: f32, a: f32, enc: Encoding) -> Self;
    /// A unit direction with A at its largest value (level 0, whose length is 1).
    fn pack_opaque(x: f32, y: f32, z: f32, enc: Encoding) -> Self;
    /// [`Texel::pack`]'s inverse at its steps: the signed RGB components (not renormalized)
    /// and the unsigned A.
    fn unpack(self, enc: Encoding) -> [f32; 4];
    /// The texel with green mirrored (`max − g`): Y pointing the other way in the unorm
    /// encoding, which is symmetric about the middle of the range.
    fn mirror_green(self) -> Self;
    /// The texel at 8 bits, each channel rounded to the nearest byte.
    fn to_rgba8(self) -> [u8; 4];
    /// Four values in [0, 1] (clamped), each rounded to the nearest step: data that is not a
    /// direction (a horizon map's elevations).
    fn pack_unorm(v: [f32; 4]) -> Self;
}

mod sealed {
    pub trait Sealed {}
    impl Sealed for [u8; 4] {}
    impl Sealed for [u16; 4] {}
}

impl Texel for [u8; 4] {
    const BITS: u32 = 8;
    #[inline(always)]
    fn pack(x: f32, y: f32, z: f32, a: f32, enc: Encoding) -> Self {
        [enc.encode(x), enc.encode(y), enc.encode(z), enc.encode_unsigned(a)]
    }
    #[inline(always)]
    fn pack_opaque(x: f32, y: f32, z: f32, enc: Encoding) -> Self {
        [enc.encode(x), enc.encode(y), enc.encode(z), 255]
    }
    fn unpack(self, enc: Encoding) -> [f32; 4] {
        let [r, g, b, a] = self;
        [enc.decode(r), enc.decode(g), enc.decode(b), a as f32 / 255.0]
    }
    fn mirror_green(self) -> Self {
        [self[0], 255 - self[1], self[2], self[3]]
    }
    fn to_rgba8(self) -> [u8; 4] {
        self
    }
    fn pack_unorm(v: [f32; 4]) -> Self {
        v.map(|c| Encoding::Unorm.encode_unsigned(c))
    }
}

impl Texel for [u16; 4] {
    const BITS: u32 = 16;
    #[inline(always)]
    fn pack(x: f32, y: f32, z: f32, a: f32, enc: Encoding) -> Self {
        [enc.encode16(x), enc.encode16(y), enc.encode16(z), enc.encode16_unsigned(a)]
    }
    #[inline(always)]
    fn pack_opaque(x: f32, y: f32, z: f32, enc: Encoding) -> Self {
        [enc.encode16(x), enc.encode16(y), enc.encode16(z), u16::MAX]
    }
    fn unpack(self, enc: Encoding) -> [f32; 4] {
        let [r, g, b, a] = self;
        [enc.decode16(r), enc.decode16(g), enc.decode16(b), a as f32 / 65535.0]
    }
    fn mirror_green(self) -> Self {
        [self[0], u16::MAX - self[1], self[2], self[3]]
    }
    fn to_rgba8(self) -> [u8; 4] {
        self.map(|c| ((c as u32 + 128) / 257) as u8)
    }
    fn pack_unorm(v: [f32; 4]) -> Self {
        v.map(|c| Encoding::Unorm.encode16_unsigned(c))
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
    fn sixteen_bits_round_trip_and_agree_with_eight() {
        for enc in [Encoding::Unorm, Encoding::Kilgard] {
            for v in (0..=65535u16).step_by(7).chain([65535]) {
                let n = enc.decode16(v);
                if enc == Encoding::Kilgard && v == 0 {
                    continue; // below −1: Kilgard's formula never writes 0
                }
                assert_eq!(enc.encode16(n), v, "{enc:?} {v}");
            }
            // 16-bit values are 8-bit values with 8 more bits: the top byte of a 16-bit code is
            // within one step of the 8-bit code of the same component.
            for i in 0..=200 {
                let n = i as f32 / 100.0 - 1.0;
                let (a, b) = (enc.encode(n) as i32, (enc.encode16(n) >> 8) as i32);
                assert!((a - b).abs() <= 1, "{enc:?} {n}: {a} vs {b}");
            }
        }
        assert_eq!(Encoding::Unorm.encode16(f32::NAN), 0);
        assert_eq!(Encoding::Unorm.encode16(1.0), 65535);
        assert_eq!(Encoding::Unorm.encode16(-1.0), 0);
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
