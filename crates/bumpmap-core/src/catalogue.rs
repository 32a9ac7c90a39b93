//! The technique catalogue: every technique the project draws, by the name the command line,
//! `compare`, the examples and the viewer use, with a line saying what it is, what it needs of a
//! scene, which maps it reads and how it is drawn.
//!
//! A name is more than a [`Technique`]: `peercy-dependent` is the single pass over a map made
//! for the surface with Peercy's 7×7 kernel, `mip-renormalized` the single pass over mips
//! without the length factor. [`TechniqueName::prepare`] makes both halves — the [`Scene`] with
//! the maps the name reads, and the [`Technique`] that draws it — from a [`SceneSpec`] and
//! [`TechniqueOptions`].
//!
//! What this module does not do: draw (the backends and `bumpmap-reference`), or decide which
//! options a user may combine with a name (the command line refuses its own flags).

use std::fmt;

use bumpmap_math::tangent::TangentDecode;
use bumpmap_math::{Kernel, MipMode};

use crate::error::CoreError;
use crate::parallax::{Parallax, ParallaxMethod, ParallaxOptions, ParallaxShadow};
use crate::scene::Scene;
use crate::spec::BumpMap;
use crate::spec::{BumpSource, SceneParams, SceneSpec};
use crate::technique::{
    BackFacing, EmbossOptions, KilgardOptions, Normalize, ReferenceOptions, SinglePassOptions, SpecularFilter,
    Technique,
};

/// Every named technique, in the order `compare`'s report lists them (the reference, the oracle
/// the others are measured against, last).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum TechniqueName {
    /// Kilgard's three passes on the emulated GeForce 256.
    Kilgard,
    /// One float pass per light.
    SinglePass,
    /// The single pass normalizing L and H by the cube map.
    SinglePassCube,
    /// The single pass with an object-space map made for the surface.
    ObjectSpace,
    /// The single pass over mips without the length factor.
    MipRenormalized,
    /// The single pass with Toksvig's filtered specular exponent.
    Toksvig,
    /// The single pass with the exponent from the exported roughness map.
    RoughnessMap,
    /// The single pass with LEAN mapping's specular lobe.
    Lean,
    /// The single pass with CLEAN mapping's (isotropic LEAN) specular lobe.
    Clean,
    /// The single pass without bumps.
    NoBump,
    /// Peercy's surface-independent map (Figure 7).
    PeercyIndependent,
    /// Peercy's surface-dependent map (Figure 6).
    PeercyDependent,
    /// Embossing (Kilgard §3.1).
    Emboss,
    /// Embossing without forcing the shift to 0 where the light is behind.
    EmbossUnforced,
    /// An offset map (Kilgard §2.2).
    OffsetMap,
    /// Peercy's Figure 2 hardware (Figure 5).
    PeercyBlinn,
    /// The single pass with the horizon map's shadows (Max 1988; Sloan & Cohen 2000).
    Horizon,
    /// Parallax mapping with offset limiting (Kaneko et al. 2001, Welsh 2004).
    Parallax,
    /// Steep parallax mapping (McGuire & McGuire 2005).
    SteepParallax,
    /// Parallax occlusion mapping (Tatarchuk 2006).
    Pom,
    /// Relief mapping (Policarpo, Oliveira & Comba 2005).
    Relief,
    /// The min–max walk of the exact surface per pixel (Tevs et al. 2008).
    HeightExact,
    /// Ground truth.
    Reference,
    /// Ground truth for heights as geometry: the displaced surface.
    ReferenceDisplaced,
}

pub use crate::requirement::Requirement;

/// The options of every family of technique; a name takes those of its family and fixes what
/// the name says (`single-pass-cube` normalizes by the cube map whatever
/// [`SinglePassOptions::normalize`] says).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TechniqueOptions {
    /// For `kilgard`.
    pub kilgard: KilgardOptions,
    /// For `single-pass` and every name drawn by it.
    pub single_pass: SinglePassOptions,
    /// For `emboss` and `emboss-unforced`.
    pub emboss: EmbossOptions,
    /// For `reference`.
    pub reference: ReferenceOptions,
    /// For the techniques that take heights as geometry (`parallax` … `height-exact`), and the
    /// displaced reference's shadow rays (cast where `shadow` is not off).
    pub parallax: ParallaxOptions,
}

impl bumpmap_math::Named for TechniqueName {
    const ALL: &'static [Self] = &TechniqueName::ALL;

    fn name(self) -> &'static str {
        TechniqueName::name(self)
    }

    fn description(self) -> &'static str {
        TechniqueName::description(self)
    }

    /// The description, and what the technique needs (`[needs a height field]`).
    fn help(self) -> String {
        let needs: Vec<&str> = self.requirements().iter().map(|r| r.brief()).collect();
        match needs.as_slice() {
            [] => self.description().to_string(),
            needs => format!("{} [needs {}]", self.description(), needs.join(" and ")),
        }
    }
}

impl TechniqueName {
    /// Every name, in catalogue order.
    pub const ALL: [TechniqueName; 24] = [
        TechniqueName::Kilgard,
        TechniqueName::SinglePass,
        TechniqueName::SinglePassCube,
        TechniqueName::ObjectSpace,
        TechniqueName::MipRenormalized,
        TechniqueName::Toksvig,
        TechniqueName::RoughnessMap,
        TechniqueName::Lean,
        TechniqueName::Clean,
        TechniqueName::NoBump,
        TechniqueName::PeercyIndependent,
        TechniqueName::PeercyDependent,
        TechniqueName::Emboss,
        TechniqueName::EmbossUnforced,
        TechniqueName::OffsetMap,
        TechniqueName::PeercyBlinn,
        TechniqueName::Horizon,
        TechniqueName::Parallax,
        TechniqueName::SteepParallax,
        TechniqueName::Pom,
        TechniqueName::Relief,
        TechniqueName::HeightExact,
        TechniqueName::Reference,
        TechniqueName::ReferenceDisplaced,
    ];

    /// The name as the papers and the command line spell it.
    pub fn name(self) -> &'static str {
        match self {
            TechniqueName::Kilgard => "kilgard",
            TechniqueName::SinglePass => "single-pass",
            TechniqueName::SinglePassCube => "single-pass-cube",
            TechniqueName::ObjectSpace => "object-space",
            TechniqueName::MipRenormalized => "mip-renormalized",
            TechniqueName::Toksvig => "toksvig",
            TechniqueName::RoughnessMap => "roughness-map",
            TechniqueName::Lean => "lean",
            TechniqueName::Clean => "clean",
            TechniqueName::NoBump => "no-bump",
            TechniqueName::PeercyIndependent => "peercy-independent",
            TechniqueName::PeercyDependent => "peercy-dependent",
            TechniqueName::Emboss => "emboss",
            TechniqueName::EmbossUnforced => "emboss-unforced",
            TechniqueName::OffsetMap => "offset-map",
            TechniqueName::PeercyBlinn => "peercy-blinn",
            TechniqueName::Horizon => "horizon",
            TechniqueName::Parallax => "parallax",
            TechniqueName::SteepParallax => "steep-parallax",
            TechniqueName::Pom => "pom",
            TechniqueName::Relief => "relief",
            TechniqueName::HeightExact => "height-exact",
            TechniqueName::Reference => "reference",
            TechniqueName::ReferenceDisplaced => "reference-displaced",
        }
    }

    /// What the technique is, in one line, in the papers' words.
    pub fn description(self) -> &'static str {
        match self {
            TechniqueName::Kilgard => {
                "Kilgard's three passes on the emulated GeForce 256: normalization cube map, register combiners, 8-bit framebuffer (§5)"
            }
            TechniqueName::SinglePass => {
                "one float pass per light with the same model, L and H normalized by math (§6)"
            }
            TechniqueName::SinglePassCube => {
                "the single pass with L and H normalized by the cube map, as the hardware did (§5.4)"
            }
            TechniqueName::ObjectSpace => {
                "the single pass with an object-space normal map made for the surface (Peercy §2.1, Kilgard §5)"
            }
            TechniqueName::MipRenormalized => {
                "the single pass with mips that renormalize the averaged normal, dropping its length (§2.4.2)"
            }
            TechniqueName::Toksvig => {
                "the single pass with Toksvig's filter (2005, past §2.5.3): the mip chain's |N| widens and dims the specular lobe, exponent s·|N|/(|N| + s(1 − |N|))"
            }
            TechniqueName::RoughnessMap => {
                "the single pass sampling a roughness map as an engine does: the one `bumpmap normalmap` exports (Filament's prefilter of each level's |N|), made from the normal map or given as a file, turned into a Blinn–Phong exponent and normalization"
            }
            TechniqueName::Lean => {
                "the single pass with LEAN mapping (Olano & Baker 2010): the slopes' first and second moments mip-filtered linearly, the highlight a Gaussian of their covariance plus 1/s, anisotropic"
            }
            TechniqueName::Clean => {
                "the single pass with CLEAN mapping (Olano & Baker 2010, §5): LEAN's moments with the slopes' spread shared out equally in x and y, ½(Mxx + Myy − |B|²), one texture of four channels instead of two: a round highlight"
            }
            TechniqueName::NoBump => "the single pass on a flat height field: the surface without bumps",
            TechniqueName::PeercyIndependent => {
                "Peercy's surface-independent map (Eq. 8–11, Figure 7): tangent-space normals from the 7×7 derivative of a Gaussian, lit per pixel in the interpolated frame"
            }
            TechniqueName::PeercyDependent => {
                "Peercy's surface-dependent map (Eq. 3–6, Figures 3 and 6): Blinn's normal per texel from the surface's exact ∂P/∂u, ∂P/∂v and the same 7×7 kernel, in each texel's tangent frame, lit exactly as peercy-independent"
            }
            TechniqueName::Emboss => {
                "embossing (Kilgard §3.1, Eq. 29–30): the height field fetched twice, shifted toward the light by a texel, subtracted, plus L_z; L_x, L_y forced to 0 where L_z ≤ 0; diffuse only"
            }
            TechniqueName::EmbossUnforced => {
                "embossing without forcing the shift to 0 where the light is behind the surface"
            }
            TechniqueName::OffsetMap => {
                "an offset map (Kilgard §2.2, Eq. 6–7): the slopes' offset D stored in RG, filtered, and N + D renormalized per pixel, lit by the single pass"
            }
            TechniqueName::PeercyBlinn => {
                "Peercy's Figure 2 hardware (Figure 5): the height derivatives from the same 7×7 kernel in a texture, Blinn's normal made per pixel from them and the interpolated ∂P/∂u, ∂P/∂v"
            }
            TechniqueName::Horizon => {
                "the single pass with bumps that shadow each other: the horizon map's elevation in 8 directions a texel, interpolated toward the light and compared with its elevation, a soft edge (Max 1988; Sloan & Cohen 2000)"
            }
            TechniqueName::Parallax => {
                "parallax mapping (Kaneko et al. 2001) with Welsh's offset limiting (2004): the maps read one height's offset along the view ray from where it enters"
            }
            TechniqueName::SteepParallax => {
                "steep parallax mapping (McGuire & McGuire 2005): the view ray stepped down through the layer count's layers of height, the maps read at the first layer under the heights"
            }
            TechniqueName::Pom => {
                "parallax occlusion mapping (Tatarchuk 2006): layers from a quarter of the layer count looking straight on to all of them at grazing angles, the hit interpolated between the last two samples"
            }
            TechniqueName::Relief => {
                "relief mapping (Policarpo, Oliveira & Comba 2005): the layers' linear search, then eight halvings of the layer it ends in"
            }
            TechniqueName::HeightExact => {
                "the exact hit per pixel: the reference's min–max walk (Tevs et al. 2008) of the heights' C¹ interpolant, shaded with the interpolant's own normal"
            }
            TechniqueName::Reference => {
                "ground truth: Blinn's perturbed normal on the exact surface from a C¹ height interpolant, many samples per pixel, on the CPU"
            }
            TechniqueName::ReferenceDisplaced => {
                "ground truth for heights as geometry: the surface carved by the heights' C¹ interpolant times the depth, rays cast exactly (flat surfaces) or to a micro-tessellation (curved ones), shadow rays where parallax shadows are asked for, many samples per pixel, on the CPU"
            }
        }
    }

    /// What the technique needs of a scene; [`TechniqueName::check`] refuses a scene without it.
    pub fn requirements(self) -> &'static [Requirement] {
        use Requirement::*;
        match self {
            TechniqueName::Kilgard
            | TechniqueName::SinglePass
            | TechniqueName::SinglePassCube
            | TechniqueName::MipRenormalized
            | TechniqueName::Toksvig
            | TechniqueName::RoughnessMap
            | TechniqueName::Lean
            | TechniqueName::Clean
            | TechniqueName::NoBump => &[],
            TechniqueName::ObjectSpace => &[BuiltInSurface],
            TechniqueName::PeercyIndependent | TechniqueName::OffsetMap => &[HeightField],
            TechniqueName::PeercyDependent | TechniqueName::PeercyBlinn | TechniqueName::Reference => {
                &[BuiltInSurface, HeightField]
            }
            TechniqueName::Emboss | TechniqueName::EmbossUnforced => &[HeightField, OneLight],
            TechniqueName::Horizon
            | TechniqueName::Parallax
            | TechniqueName::SteepParallax
            | TechniqueName::Pom
            | TechniqueName::Relief
            | TechniqueName::HeightExact => &[Heights],
            TechniqueName::ReferenceDisplaced => &[BuiltInSurface, Heights],
        }
    }

    /// Every name, comma-separated, for messages.
    pub fn names() -> String {
        Self::ALL.map(TechniqueName::name).join(", ")
    }

    /// The technique called `name`, or an error that lists the valid names.
    pub fn parse(name: &str) -> Result<Self, CoreError> {
        Self::ALL.into_iter().find(|t| t.name() == name).ok_or_else(|| CoreError::UnknownTechnique {
            name: name.into(),
            known: TechniqueName::ALL.map(TechniqueName::name).join(", "),
        })
    }

    /// Refuses a scene that lacks one of [`TechniqueName::requirements`].
    pub fn check(self, spec: &SceneSpec) -> Result<(), CoreError> {
        for &requirement in self.requirements() {
            let met = match requirement {
                Requirement::BuiltInSurface => spec.kind.is_surface(),
                Requirement::HeightField => spec.params.bump_sources().all(|b| matches!(b, BumpSource::Heights(_))),
                Requirement::OneLight => spec.params.lights.len() <= 1,
                Requirement::Heights => {
                    spec.params.bump_sources().all(|b| matches!(b, BumpSource::Heights(_)))
                        || spec.params.height_mips.is_some()
                }
            };
            if !met {
                return Err(CoreError::Needs { technique: self.name(), requirement });
            }
        }
        Ok(())
    }

    /// The scene parameters with the maps this technique reads: its kernel, its bump texture,
    /// its mip mode, or no bumps at all.
    pub fn scene_params(self, base: &SceneParams) -> SceneParams {
        let mut params = base.clone();
        params.height_map = matches!(self, TechniqueName::Emboss | TechniqueName::EmbossUnforced);
        params.displacement = self.parallax_method().is_some() || self == TechniqueName::ReferenceDisplaced;
        let peercy = |params: &mut SceneParams, map| {
            params.normal_map.kernel = Kernel::Gaussian7;
            params.bump_map = map;
        };
        match self {
            TechniqueName::ObjectSpace => params.bump_map = BumpMap::ObjectSpace,
            TechniqueName::MipRenormalized => params.mip_mode = MipMode::Renormalize,
            TechniqueName::NoBump => {
                params.bumps = base.bumps.flat();
                if let Some(parts) = &mut params.parts {
                    std::sync::Arc::make_mut(parts).replace_bumps();
                }
            }
            TechniqueName::PeercyIndependent => peercy(&mut params, BumpMap::Tangent),
            TechniqueName::PeercyDependent => peercy(&mut params, BumpMap::SurfaceDependent),
            TechniqueName::PeercyBlinn => peercy(&mut params, BumpMap::Derivatives),
            TechniqueName::OffsetMap => params.bump_map = BumpMap::Offset,
            TechniqueName::Kilgard
            | TechniqueName::SinglePass
            | TechniqueName::SinglePassCube
            | TechniqueName::Toksvig
            | TechniqueName::RoughnessMap
            | TechniqueName::Lean
            | TechniqueName::Clean
            | TechniqueName::Emboss
            | TechniqueName::EmbossUnforced
            | TechniqueName::Horizon
            | TechniqueName::Parallax
            | TechniqueName::SteepParallax
            | TechniqueName::Pom
            | TechniqueName::Relief
            | TechniqueName::HeightExact
            | TechniqueName::Reference
            | TechniqueName::ReferenceDisplaced => {}
        }
        params
    }

    /// How a tangent-space map is decoded when the caller does not say: per pixel as
    /// MikkTSpace's header says on a mesh (what the files' tools bake for, `bumpmap bake`
    /// included) where this technique with `options` can (the single pass and its variants,
    /// without heights as geometry, LEAN or CLEAN, a detail map or Peercy's surface maps); in the
    /// papers' per-vertex frame on their built-in surfaces and wherever the technique lights
    /// in that frame.
    pub fn default_decode(self, kind: &crate::spec::SceneKind, options: &TechniqueOptions) -> TangentDecode {
        let Technique::SinglePass(single) = self.technique(options) else { return TangentDecode::PerVertex };
        let per_pixel = !kind.is_surface()
            && single.parallax.is_none()
            && single.detail.is_none()
            && !matches!(single.specular_filter, SpecularFilter::Lean | SpecularFilter::Clean)
            && !matches!(
                self,
                TechniqueName::ObjectSpace
                    | TechniqueName::PeercyDependent
                    | TechniqueName::PeercyBlinn
                    | TechniqueName::OffsetMap
            );
        if per_pixel { TangentDecode::MikkTSpace } else { TangentDecode::PerVertex }
    }

    /// Whether the name is one of the references (drawn by `bumpmap-reference` on the CPU, not
    /// as passes).
    pub fn is_reference(self) -> bool {
        matches!(self, TechniqueName::Reference | TechniqueName::ReferenceDisplaced)
    }

    /// The march of a technique that takes heights as geometry, `None` for the others.
    pub fn parallax_method(self) -> Option<ParallaxMethod> {
        match self {
            TechniqueName::Horizon => Some(ParallaxMethod::Flat),
            TechniqueName::Parallax => Some(ParallaxMethod::Offset),
            TechniqueName::SteepParallax => Some(ParallaxMethod::Steep),
            TechniqueName::Pom => Some(ParallaxMethod::Occlusion),
            TechniqueName::Relief => Some(ParallaxMethod::Relief),
            TechniqueName::HeightExact => Some(ParallaxMethod::Exact),
            _ => None,
        }
    }

    /// The technique that draws this name, with `options`' settings for its family and the
    /// name's own fixed on top.
    pub fn technique(self, options: &TechniqueOptions) -> Technique {
        let single = options.single_pass.clone();
        match self {
            TechniqueName::Kilgard => Technique::Kilgard(options.kilgard.clone()),
            TechniqueName::SinglePassCube => {
                Technique::SinglePass(SinglePassOptions { normalize: Normalize::Cube, ..single })
            }
            TechniqueName::Toksvig => {
                Technique::SinglePass(SinglePassOptions { specular_filter: SpecularFilter::Toksvig, ..single })
            }
            TechniqueName::RoughnessMap => {
                Technique::SinglePass(SinglePassOptions { specular_filter: SpecularFilter::RoughnessMap, ..single })
            }
            TechniqueName::Lean => {
                Technique::SinglePass(SinglePassOptions { specular_filter: SpecularFilter::Lean, ..single })
            }
            TechniqueName::Clean => {
                Technique::SinglePass(SinglePassOptions { specular_filter: SpecularFilter::Clean, ..single })
            }
            TechniqueName::SinglePass
            | TechniqueName::ObjectSpace
            | TechniqueName::MipRenormalized
            | TechniqueName::NoBump
            | TechniqueName::PeercyIndependent
            | TechniqueName::PeercyDependent
            | TechniqueName::OffsetMap
            | TechniqueName::PeercyBlinn => Technique::SinglePass(single),
            TechniqueName::Emboss => {
                Technique::Emboss(EmbossOptions { back_facing: BackFacing::Forced, ..options.emboss.clone() })
            }
            TechniqueName::EmbossUnforced => {
                Technique::Emboss(EmbossOptions { back_facing: BackFacing::Unforced, ..options.emboss.clone() })
            }
            TechniqueName::Horizon => Technique::SinglePass(SinglePassOptions {
                parallax: Some(Parallax {
                    method: ParallaxMethod::Flat,
                    options: ParallaxOptions { shadow: ParallaxShadow::Horizon, ..options.parallax },
                }),
                ..single
            }),
            TechniqueName::Parallax
            | TechniqueName::SteepParallax
            | TechniqueName::Pom
            | TechniqueName::Relief
            | TechniqueName::HeightExact => Technique::SinglePass(SinglePassOptions {
                parallax: self.parallax_method().map(|method| Parallax { method, options: options.parallax }),
                ..single
            }),
            TechniqueName::Reference => Technique::Reference(options.reference),
            TechniqueName::ReferenceDisplaced => Technique::Reference(ReferenceOptions {
                displaced: true,
                shadow_rays: options.parallax.shadow != ParallaxShadow::Off,
                ..options.reference
            }),
        }
    }

    /// The scene with this technique's maps and the technique that draws it; fails when the
    /// scene lacks a requirement or cannot be built. The passes themselves may still refuse an
    /// option (`kilgard` with a gloss map): [`Technique::passes`].
    pub fn prepare(self, spec: &SceneSpec, options: &TechniqueOptions) -> Result<(Scene, Technique), CoreError> {
        self.check(spec)?;
        let mut params = self.scene_params(&spec.params);
        params.decode = Some(params.decode.unwrap_or_else(|| self.default_decode(&spec.kind, options)));
        let scene = crate::scenes::build(&spec.kind, &params)?;
        Ok((scene, self.technique(options)))
    }
}

impl fmt::Display for TechniqueName {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.pad(self.name())
    }
}

impl std::str::FromStr for TechniqueName {
    type Err = CoreError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::parse(s)
    }
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use super::*;
    use crate::scenes::SceneKind;

    #[test]
    fn every_name_parses_back_and_is_unique() {
        for t in TechniqueName::ALL {
            assert_eq!(TechniqueName::parse(t.name()), Ok(t));
            assert!(!t.description().is_empty());
        }
        let mut names: Vec<_> = TechniqueName::ALL.map(TechniqueName::name).to_vec();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), TechniqueName::ALL.len());
        let err = TechniqueName::parse("phong").unwrap_err().to_string();
        assert!(err.contains("'phong'") && err.contains("peercy-blinn") && err.contains("reference"), "{err}");
    }

    #[test]
    fn every_name_prepares_the_torus_and_makes_passes_or_is_the_reference() {
        let spec = SceneSpec::new(SceneKind::Torus);
        for t in TechniqueName::ALL {
            let (scene, technique) = t.prepare(&spec, &TechniqueOptions::default()).unwrap();
            match technique {
                Technique::Reference(_) => assert_eq!(technique.passes(&scene).unwrap_err(), CoreError::NotPasses),
                _ => assert!(!technique.passes(&scene).unwrap().is_empty(), "{t}"),
            }
        }
    }

    #[test]
    fn a_mesh_or_a_normal_map_is_refused_by_name_and_reason() {
        let mesh = bumpmap_math::surface::Surface::Wall { width: 1.0, height: 1.0 }.tessellate(2, 2, glam::Vec2::ONE);
        let on_mesh = SceneSpec::new(SceneKind::Mesh(Arc::new(mesh)));
        let err = TechniqueName::PeercyDependent.prepare(&on_mesh, &TechniqueOptions::default()).unwrap_err();
        assert_eq!(err, CoreError::Needs { technique: "peercy-dependent", requirement: Requirement::BuiltInSurface });
        assert!(err.to_string().starts_with("peercy-dependent needs a built-in surface"), "{err}");
        // Techniques without requirements draw the mesh.
        assert!(TechniqueName::Kilgard.prepare(&on_mesh, &TechniqueOptions::default()).is_ok());

        let mut given = SceneSpec::new(SceneKind::Wall);
        let chain = bumpmap_math::MipChain::from_normals(
            4,
            4,
            &[glam::Vec3::Z; 16],
            bumpmap_math::Encoding::Unorm,
            MipMode::LengthInAlpha,
        );
        given.params.bumps = BumpSource::NormalMap(Arc::new(chain));
        for t in TechniqueName::ALL {
            let result = t.prepare(&given, &TechniqueOptions::default());
            if t.requirements().contains(&Requirement::HeightField) {
                assert!(matches!(result, Err(CoreError::Needs { requirement: Requirement::HeightField, .. })), "{t}");
            } else if t.requirements().contains(&Requirement::Heights) {
                // Heights as geometry: a normal map without heights given beside it has none.
                assert!(matches!(result, Err(CoreError::Needs { requirement: Requirement::Heights, .. })), "{t}");
            } else {
                assert!(result.is_ok(), "{t}: {:?}", result.err());
            }
        }
    }

    #[test]
    fn names_fix_what_they_say_over_the_options() {
        let options = TechniqueOptions::default();
        let Technique::SinglePass(o) = TechniqueName::SinglePassCube.technique(&options) else { panic!() };
        assert_eq!(o.normalize, Normalize::Cube);
        let Technique::Emboss(o) = TechniqueName::EmbossUnforced.technique(&options) else { panic!() };
        assert_eq!(o.back_facing, BackFacing::Unforced);
        let base = SceneParams::default();
        assert_eq!(TechniqueName::MipRenormalized.scene_params(&base).mip_mode, MipMode::Renormalize);
        assert_eq!(TechniqueName::PeercyBlinn.scene_params(&base).normal_map.kernel, Kernel::Gaussian7);
        assert_eq!(TechniqueName::Kilgard.scene_params(&base).normal_map, base.normal_map);
    }
}
