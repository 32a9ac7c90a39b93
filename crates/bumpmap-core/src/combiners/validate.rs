//! [`CombinerSetup::validate`]: every INVALID_OPERATION and INVALID_VALUE rule of
//! NV_register_combiners (SPECS.md §1) that a setup can break, each a [`CombinerError`].

use super::*;

/// `GL_MAX_GENERAL_COMBINERS_NV` of a GeForce 256.
pub const MAX_GENERAL_COMBINERS: usize = 2;

/// RGB or alpha, for error messages.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PortionName {
    /// The RGB portion.
    Rgb,
    /// The alpha portion.
    Alpha,
}

impl std::fmt::Display for PortionName {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str(match self {
            PortionName::Rgb => "RGB",
            PortionName::Alpha => "alpha",
        })
    }
}

/// The setups the specification rejects, with the GL error it names.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum CombinerError {
    /// `GL_NUM_GENERAL_COMBINERS_NV` (the number of stages) outside 1..=[`MAX_GENERAL_COMBINERS`].
    #[error("INVALID_VALUE: NUM_GENERAL_COMBINERS_NV = {0}, must be 1..={MAX_GENERAL_COMBINERS}")]
    StageCount(usize),
    /// An RGB-portion variable with `GL_BLUE` component usage.
    #[error("INVALID_OPERATION: stage {stage} RGB portion, variable {var}: BLUE component usage")]
    BlueOnRgb {
        /// The general stage, from 0.
        stage: usize,
        /// The variable, 'A'–'D'.
        var: char,
    },
    /// An alpha-portion variable with `GL_RGB` component usage.
    #[error("INVALID_OPERATION: stage {stage} alpha portion, variable {var}: RGB component usage")]
    RgbOnAlpha {
        /// The general stage, from 0.
        stage: usize,
        /// The variable, 'A'–'D'.
        var: char,
    },
    /// A general-combiner variable reading `GL_FOG` with `GL_ALPHA` usage.
    #[error(
        "INVALID_OPERATION: stage {stage} {portion} portion, variable {var}: FOG alpha is only readable by the final combiner"
    )]
    FogAlphaInGeneral {
        /// The general stage, from 0.
        stage: usize,
        /// The portion.
        portion: PortionName,
        /// The variable, 'A'–'D'.
        var: char,
    },
    /// abDotProduct or cdDotProduct set on an alpha portion.
    #[error("INVALID_VALUE: stage {stage} alpha portion: dot products exist only on the RGB portion")]
    DotOnAlpha {
        /// The general stage, from 0.
        stage: usize,
    },
    /// `GL_SCALE_BY_FOUR_NV` or `GL_SCALE_BY_ONE_HALF_NV` with `GL_BIAS_BY_NEGATIVE_ONE_HALF_NV`.
    #[error("INVALID_OPERATION: stage {stage} {portion} portion: scale {scale:?} cannot be combined with bias −½")]
    ScaleWithBias {
        /// The general stage, from 0.
        stage: usize,
        /// The portion.
        portion: PortionName,
        /// The scale given with the bias.
        scale: Scale,
    },
    /// Two of a portion's abOutput, cdOutput and sumOutput naming the same register.
    #[error("INVALID_OPERATION: stage {stage} {portion} portion writes {register:?} more than once")]
    DuplicateOutput {
        /// The general stage, from 0.
        stage: usize,
        /// The portion.
        portion: PortionName,
        /// The register written more than once.
        register: Register,
    },
    /// An output naming a read-only register: `GL_ZERO`, a constant colour or `GL_FOG`.
    #[error("INVALID_ENUM: stage {stage} {portion} portion writes read-only register {register:?}")]
    NotWritable {
        /// The general stage, from 0.
        stage: usize,
        /// The portion.
        portion: PortionName,
        /// The read-only register.
        register: Register,
    },
    /// A final-combiner mapping other than `GL_UNSIGNED_IDENTITY_NV` or `GL_UNSIGNED_INVERT_NV`.
    #[error(
        "INVALID_OPERATION: final combiner variable {var}: mapping {mapping:?} (only UNSIGNED_IDENTITY or UNSIGNED_INVERT)"
    )]
    FinalMapping {
        /// The variable, 'A'–'G'.
        var: char,
        /// The mapping given.
        mapping: InputMapping,
    },
    /// `GL_E_TIMES_F_NV` outside A–D, or `GL_SPARE0_PLUS_SECONDARY_COLOR_NV` outside B–D.
    #[error("INVALID_OPERATION: final combiner variable {var} cannot read {from:?}")]
    FinalSourceNotAllowed {
        /// The variable, 'A'–'G'.
        var: char,
        /// The pseudo-register it may not read.
        from: FinalSource,
    },
    /// Final-combiner usage not allowed: BLUE on A–F, RGB on G, or ALPHA of a pseudo-register.
    #[error("INVALID_OPERATION: final combiner variable {var}: component usage {usage:?} not allowed")]
    FinalUsage {
        /// The variable, 'A'–'G'.
        var: char,
        /// The component usage given.
        usage: ComponentUsage,
    },
}

impl CombinerSetup {
    /// Checks every rule of the specification; the first violation is returned.
    pub fn validate(&self) -> Result<(), CombinerError> {
        if self.stages.is_empty() || self.stages.len() > MAX_GENERAL_COMBINERS {
            return Err(CombinerError::StageCount(self.stages.len()));
        }
        for (stage, s) in self.stages.iter().enumerate() {
            for (portion, p) in [(PortionName::Rgb, &s.rgb), (PortionName::Alpha, &s.alpha)] {
                for (var, input) in [('A', p.a), ('B', p.b), ('C', p.c), ('D', p.d)] {
                    match (portion, input.usage) {
                        (PortionName::Rgb, ComponentUsage::Blue) => {
                            return Err(CombinerError::BlueOnRgb { stage, var });
                        }
                        (PortionName::Alpha, ComponentUsage::Rgb) => {
                            return Err(CombinerError::RgbOnAlpha { stage, var });
                        }
                        _ => {}
                    }
                    if input.register == Register::Fog && input.usage == ComponentUsage::Alpha {
                        return Err(CombinerError::FogAlphaInGeneral { stage, portion, var });
                    }
                }
                let o = &p.outputs;
                if portion == PortionName::Alpha && (o.ab_dot || o.cd_dot) {
                    return Err(CombinerError::DotOnAlpha { stage });
                }
                if o.bias == Bias::MinusOneHalf && matches!(o.scale, Scale::ByOneHalf | Scale::ByFour) {
                    return Err(CombinerError::ScaleWithBias { stage, portion, scale: o.scale });
                }
                let written: Vec<Register> = [o.ab, o.cd, o.sum].into_iter().flatten().collect();
                for (i, &register) in written.iter().enumerate() {
                    if !register.writable() {
                        return Err(CombinerError::NotWritable { stage, portion, register });
                    }
                    if written[..i].contains(&register) {
                        return Err(CombinerError::DuplicateOutput { stage, portion, register });
                    }
                }
            }
        }
        let f = &self.final_combiner;
        for (var, input) in [('A', f.a), ('B', f.b), ('C', f.c), ('D', f.d), ('E', f.e), ('F', f.f), ('G', f.g)] {
            if !matches!(input.mapping, InputMapping::UnsignedIdentity | InputMapping::UnsignedInvert) {
                return Err(CombinerError::FinalMapping { var, mapping: input.mapping });
            }
            let pseudo = !matches!(input.source, FinalSource::Register(_));
            let allowed = match input.source {
                FinalSource::Register(_) => true,
                FinalSource::ETimesF => ('A'..='D').contains(&var),
                FinalSource::Spare0PlusSecondary => ('B'..='D').contains(&var),
            };
            if !allowed {
                return Err(CombinerError::FinalSourceNotAllowed { var, from: input.source });
            }
            let usage_ok = match (var, input.usage) {
                ('G', ComponentUsage::Rgb) => false,
                ('G', _) => true,
                (_, ComponentUsage::Blue) => false,
                (_, ComponentUsage::Alpha) => !pseudo,
                (_, ComponentUsage::Rgb) => true,
            };
            if !usage_ok {
                return Err(CombinerError::FinalUsage { var, usage: input.usage });
            }
        }
        Ok(())
    }
}
