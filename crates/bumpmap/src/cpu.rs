//! Which x86-64 level this build's CPU pipeline was compiled for, and whether the processor it
//! runs on has it.
//!
//! The workspace builds for x86-64-v3 by default (`.cargo/config.toml`: AVX2, FMA, BMI2, …), where
//! the CPU pipeline is four to five times faster than on baseline x86-64; its results are the
//! same bits on both (CI tests the baseline build). A program built for a level the processor
//! lacks dies on its first such instruction, so the command line asks [`has`] before it
//! does anything, and the Python wheel carries both builds and loads the one [`has`] allows.
//!
//! What this module does not do: choose code paths itself. The level is a property of the whole
//! build (the compiler's target CPU), not of a function.
//!
//! ```
//! // Whatever this processor is, a baseline build runs on it.
//! if bumpmap::cpu::built_for() == bumpmap::cpu::Level::X86_64 {
//!     assert!(bumpmap::cpu::has(bumpmap::cpu::Level::X86_64));
//! }
//! ```

/// An x86-64 micro-architecture level (the psABI's names), as far as this project uses them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Level {
    /// Baseline x86-64 (SSE2): every x86-64 processor. Also what non-x86 builds report.
    X86_64,
    /// x86-64-v3: AVX, AVX2, BMI1, BMI2, F16C, FMA, LZCNT, MOVBE, XSAVE (Intel since 2013,
    /// AMD since 2015).
    X86_64V3,
}

impl Level {
    /// The level's name as compilers spell it (`-C target-cpu=…`).
    pub fn name(self) -> &'static str {
        match self {
            Level::X86_64 => "x86-64",
            Level::X86_64V3 => "x86-64-v3",
        }
    }
}

impl std::fmt::Display for Level {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// The level this build was compiled for: x86-64-v3 when the compiler was allowed AVX2 and FMA.
pub fn built_for() -> Level {
    if cfg!(all(target_arch = "x86_64", target_feature = "avx2", target_feature = "fma")) {
        Level::X86_64V3
    } else {
        Level::X86_64
    }
}

/// Whether this processor (and its operating system, for the AVX registers) has every feature
/// of `level`. Scalar code only, so that a program can ask it first thing even where the rest of
/// its build uses instructions the processor lacks.
#[inline(never)]
pub fn has(level: Level) -> bool {
    match level {
        Level::X86_64 => true,
        #[cfg(target_arch = "x86_64")]
        Level::X86_64V3 => {
            let r = cpuid::read();
            let all = |reg: cpuid::Register| r[reg as usize] & cpuid::mask(reg) == cpuid::mask(reg);
            all(cpuid::Register::Leaf1Ecx)
                && all(cpuid::Register::Leaf7Ebx)
                && all(cpuid::Register::Ext1Ecx)
                && r[3] != 0
        }
        #[cfg(not(target_arch = "x86_64"))]
        Level::X86_64V3 => false,
    }
}

/// The features of `level` this processor lacks, by the names `/proc/cpuinfo` and the compilers
/// use (`osxsave`: the operating system does not save the AVX registers); empty when it has
/// them all.
pub fn missing(level: Level) -> Vec<&'static str> {
    match level {
        Level::X86_64 => Vec::new(),
        #[cfg(target_arch = "x86_64")]
        Level::X86_64V3 => {
            let r = cpuid::read();
            let mut out: Vec<&str> =
                cpuid::V3.iter().filter(|f| r[f.1 as usize] >> f.2 & 1 == 0).map(|f| f.0).collect();
            if r[3] == 0 && !out.contains(&"osxsave") {
                out.push("osxsave");
            }
            out
        }
        #[cfg(not(target_arch = "x86_64"))]
        Level::X86_64V3 => vec!["x86-64"],
    }
}

/// The processor's answers, read with CPUID itself: `is_x86_feature_detected!` answers `true`
/// without asking for every feature the build was compiled with, which here is the question.
#[cfg(target_arch = "x86_64")]
mod cpuid {
    use std::arch::x86_64::{__cpuid, __cpuid_count, _xgetbv};

    /// Where a feature's bit is.
    #[derive(Clone, Copy)]
    pub enum Register {
        /// CPUID leaf 1, ECX.
        Leaf1Ecx = 0,
        /// CPUID leaf 7 (subleaf 0), EBX.
        Leaf7Ebx = 1,
        /// CPUID leaf 0x8000_0001, ECX.
        Ext1Ecx = 2,
    }

    /// x86-64-v3's features (the psABI's list): name, register, bit.
    pub const V3: [(&str, Register, u32); 10] = [
        ("fma", Register::Leaf1Ecx, 12),
        ("movbe", Register::Leaf1Ecx, 22),
        ("xsave", Register::Leaf1Ecx, 26),
        ("osxsave", Register::Leaf1Ecx, 27),
        ("avx", Register::Leaf1Ecx, 28),
        ("f16c", Register::Leaf1Ecx, 29),
        ("bmi1", Register::Leaf7Ebx, 3),
        ("avx2", Register::Leaf7Ebx, 5),
        ("bmi2", Register::Leaf7Ebx, 8),
        ("lzcnt", Register::Ext1Ecx, 5),
    ];

    /// The bits of `reg` that x86-64-v3 needs set (folded at compile time).
    pub const fn mask(reg: Register) -> u32 {
        let mut m = 0;
        let mut i = 0;
        while i < V3.len() {
            if V3[i].1 as u32 == reg as u32 {
                m |= 1 << V3[i].2;
            }
            i += 1;
        }
        m
    }

    /// The three registers [`Register`] names, then 1 when the operating system saves the XMM
    /// and YMM registers (XCR0 bits 1 and 2), else 0.
    #[inline(always)]
    pub fn read() -> [u32; 4] {
        // A leaf above the highest one the processor reports is not asked.
        let max = __cpuid(0).eax;
        let leaf1 = __cpuid(1).ecx;
        let leaf7 = if max >= 7 { __cpuid_count(7, 0).ebx } else { 0 };
        let ext_max = __cpuid(0x8000_0000).eax;
        let ext1 = if ext_max >= 0x8000_0001 { __cpuid(0x8000_0001).ecx } else { 0 };
        let osxsave = leaf1 >> 27 & 1 == 1;
        // SAFETY: XGETBV exists when OSXSAVE is set (the operating system enabled XSAVE).
        let ymm = osxsave && unsafe { _xgetbv(0) } & 0b110 == 0b110;
        [leaf1, leaf7, ext1, ymm as u32]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_running_build_has_what_it_was_built_for() {
        // This test runs, so the processor has the build's level.
        assert!(has(built_for()) && missing(built_for()).is_empty(), "{:?}", missing(built_for()));
        assert_eq!(has(Level::X86_64V3), missing(Level::X86_64V3).is_empty());
        assert_eq!(built_for().to_string(), built_for().name());
    }
}
