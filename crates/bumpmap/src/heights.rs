//! From a normal map back to heights: [`bumpmap_math::integration`] with the defaults a user
//! expects — the Y convention and the kernel from the curl test, the boundary from the seam
//! test, unless given — and the choices said, so a caller can print why.
//!
//! ```
//! use bumpmap::heights::{HeightOptions, heights_from_normals};
//! use bumpmap::{HeightPreset, MipChain, MipMode, Named, NormalMapOptions, YConvention};
//! use bumpmap::bumpmap_math::inspect::signed_levels;
//!
//! let field = HeightPreset::Dimples.render(64, 64);
//! let options = NormalMapOptions { y_convention: YConvention::YUp, ..Default::default() };
//! let chain: MipChain = MipChain::from_height(&field, &options, MipMode::LengthInAlpha).unwrap();
//! let normals = signed_levels(&chain.levels[..1]).remove(0);
//! let got = heights_from_normals(&normals, &HeightOptions::default()).unwrap();
//! assert_eq!(got.y_convention, YConvention::YUp); // the curl test's verdict
//! assert_eq!(got.method.boundary.name(), "fft"); // the map tiles
//! assert_eq!(got.method.derivative.name(), "forward"); // the kernel that made it
//! ```
//!
//! What this module does not do: read or write files.

use bumpmap_math::Image;
use bumpmap_math::inspect::{ConventionVerdict, Inspection, Seam, detect_convention};
use bumpmap_math::integration::{
    Boundary, Derivative, DerivativeFit, IntegrationError, IntegrationMethod, Slopes, check_normals, check_scale,
    integrate, integrate_fitted,
};
use bumpmap_math::normalmap::YConvention;
use glam::Vec4;

/// How to integrate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HeightOptions {
    /// Periodic (`fft`) or free (`dct`); `None`: `fft` when the map and its heights tile (the
    /// seam test, and a mean slope near 0), else `dct`.
    pub boundary: Option<Boundary>,
    /// The derivative the map was made with; `None`: the model that leaves the least
    /// least-squares residual ([`DerivativeFit`]): the kernel that made the map, or `iω`
    /// (Frankot–Chellappa) where no kernel explains it better.
    pub derivative: Option<Derivative>,
    /// Which way the map's green points; `None`: the curl test's verdict, Y up where it cannot
    /// decide.
    pub y_convention: Option<YConvention>,
    /// The scale the map was made with (the height of a unit step in texels): the heights come
    /// back divided by it.
    pub scale: f32,
}

impl Default for HeightOptions {
    /// Method and convention from the map, scale 1.
    fn default() -> Self {
        Self { boundary: None, derivative: None, y_convention: None, scale: 1.0 }
    }
}

/// How the slopes are integrated, as a user names it: left to the map, a boundary, or a
/// kernel's difference undone exactly.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum HeightMethod {
    /// `fft` when the map tiles, else `dct`.
    #[default]
    Auto,
    /// Periodic: the Fourier least-squares solve.
    Fft,
    /// A free boundary: the DCT's mirrored extension.
    Dct,
    /// `fft` with a named kernel's transfer function.
    Kernel,
}

bumpmap_math::named!(HeightMethod {
    Auto => "auto": "fft when the map tiles (by the seam test), else dct",
    Fft => "fft": "The Fourier least-squares solve over the periodic map (Frankot–Chellappa): for maps that tile",
    Dct => "dct": "Poisson with a free boundary (the DCT's mirrored extension): for maps that do not tile",
    Kernel => "kernel": "fft with the named kernel's finite difference undone exactly (up to a constant, where the kernel is invertible)",
});

/// Options that contradict each other.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum HeightChoiceError {
    /// The `kernel` method without a kernel named.
    #[error(
        "the kernel method undoes the kernel the map was made with, so it needs one named; the fft method fits one itself"
    )]
    KernelUnnamed,
    /// The `kernel` method with the spectral derivative, which is no kernel to undo.
    #[error(
        "the kernel method undoes a finite-difference kernel, and the spectral derivative is none: the fft method integrates with it"
    )]
    KernelSpectral,
    /// A scale of 0, not finite, or beyond ±1e6 ([`check_scale`]).
    #[error(transparent)]
    Scale(#[from] IntegrationError),
}

impl HeightOptions {
    /// The options a user's words make: `method`, the `derivative` the map was made with
    /// (`None`: fitted), its Y convention (`None`: the curl test's) and its scale, checked here
    /// so that a caller can refuse it before reading a map.
    ///
    /// ```
    /// use bumpmap::heights::{HeightChoiceError, HeightMethod, HeightOptions};
    /// use bumpmap::bumpmap_math::integration::{Boundary, Derivative};
    /// use bumpmap::Kernel;
    ///
    /// let sobel = Some(Derivative::Kernel(Kernel::Sobel3));
    /// let o = HeightOptions::from_choices(HeightMethod::Kernel, sobel, None, 4.0).unwrap();
    /// assert_eq!((o.boundary, o.derivative), (Some(Boundary::Periodic), sobel));
    /// assert_eq!(HeightOptions::from_choices(HeightMethod::Kernel, None, None, 4.0), Err(HeightChoiceError::KernelUnnamed));
    /// let spectral = Some(Derivative::Spectral);
    /// assert_eq!(HeightOptions::from_choices(HeightMethod::Kernel, spectral, None, 4.0), Err(HeightChoiceError::KernelSpectral));
    /// assert_eq!(HeightOptions::from_choices(HeightMethod::Auto, None, None, 1.0), Ok(HeightOptions::default()));
    /// let zero = HeightOptions::from_choices(HeightMethod::Auto, None, None, 0.0);
    /// assert!(matches!(zero, Err(HeightChoiceError::Scale(_))), "a scale of 0 flattens every slope");
    /// ```
    pub fn from_choices(
        method: HeightMethod,
        derivative: Option<Derivative>,
        y_convention: Option<YConvention>,
        scale: f32,
    ) -> Result<Self, HeightChoiceError> {
        let boundary = match method {
            HeightMethod::Auto => None,
            HeightMethod::Fft | HeightMethod::Kernel => Some(Boundary::Periodic),
            HeightMethod::Dct => Some(Boundary::Free),
        };
        check_scale(scale)?;
        if method == HeightMethod::Kernel {
            match derivative {
                Some(Derivative::Kernel(_)) => {}
                Some(_) => return Err(HeightChoiceError::KernelSpectral),
                None => return Err(HeightChoiceError::KernelUnnamed),
            }
        }
        Ok(Self { boundary, derivative, y_convention, scale })
    }
}

/// What a user chooses of [`HeightOptions`], as `bumpmap height` and Python's
/// `height_from_normals` take it: the method by name, `auto` where the map's own tests decide,
/// and whether the heights are kept as they are. [`HeightChoices::options`] checks them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HeightChoices {
    /// How the slopes are integrated.
    pub method: HeightMethod,
    /// The difference the map was made with (`None`: fitted).
    pub kernel: Option<Derivative>,
    /// The scale the map was made with.
    pub scale: f32,
    /// Which way the map's green points (`None`: the curl test's verdict).
    pub y_convention: Option<YConvention>,
    /// Keep the heights as they are (texels divided by the scale, mean zero) instead of mapping
    /// them onto [0, 1].
    pub raw: bool,
}

impl Default for HeightChoices {
    fn default() -> Self {
        HeightChoices { method: HeightMethod::Auto, kernel: None, scale: 1.0, y_convention: None, raw: false }
    }
}

impl HeightChoices {
    /// The options they make ([`HeightOptions::from_choices`]).
    pub fn options(&self) -> Result<HeightOptions, HeightChoiceError> {
        HeightOptions::from_choices(self.method, self.kernel, self.y_convention, self.scale)
    }
}

/// Where a choice came from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Chosen {
    /// The caller gave it.
    Given,
    /// The map's own test decided (the curl test's confidence, or 1 for the seam test).
    Detected(f32),
    /// The test could not decide: the default was taken.
    Default,
}

/// Heights made from a normal map.
#[derive(Clone, Debug, PartialEq)]
pub struct RecoveredHeights {
    /// Width in texels.
    pub width: usize,
    /// Height in texels.
    pub height: usize,
    /// Heights in texels divided by the scale, mean zero, row 0 first.
    pub texels: Vec<f32>,
    /// The method used.
    pub method: IntegrationMethod,
    /// Where its boundary came from.
    pub boundary_chosen: Chosen,
    /// Where its derivative came from.
    pub derivative_chosen: Chosen,
    /// Every model's residual, where the derivative was fitted.
    pub fit: Option<DerivativeFit>,
    /// The convention the map was read with.
    pub y_convention: YConvention,
    /// Where the convention came from.
    pub convention_chosen: Chosen,
}

impl RecoveredHeights {
    /// The lowest and highest height.
    pub fn range(&self) -> (f32, f32) {
        self.texels.iter().fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), &v| (lo.min(v), hi.max(v)))
    }

    /// The heights mapped onto [0, 1] (lowest 0, highest 1); all 0 for a flat result.
    pub fn normalized(&self) -> Vec<f32> {
        let (lo, hi) = self.range();
        let span = hi - lo;
        if span <= f32::EPSILON * lo.abs().max(1.0) {
            return vec![0.0; self.texels.len()];
        }
        self.texels.iter().map(|v| (v - lo) / span).collect()
    }
}

/// Integrates `normals` (signed xyz, Z rebuilt for a two-channel map; w not read) into heights.
pub fn heights_from_normals(
    normals: &Image<Vec4>,
    options: &HeightOptions,
) -> Result<RecoveredHeights, IntegrationError> {
    recover(normals, options, || detect_convention(normals), || Seam::of(normals))
}

/// [`heights_from_normals`] for a map already inspected (its level 0 as `normals`): the curl
/// and seam tests are not run again.
pub fn heights_from_inspection(
    normals: &Image<Vec4>,
    inspection: &Inspection,
    options: &HeightOptions,
) -> Result<RecoveredHeights, IntegrationError> {
    recover(normals, options, || inspection.convention, || inspection.seam)
}

fn recover(
    normals: &Image<Vec4>,
    options: &HeightOptions,
    convention: impl FnOnce() -> ConventionVerdict,
    seam: impl FnOnce() -> Seam,
) -> Result<RecoveredHeights, IntegrationError> {
    // Size, NaN and scale are checked before the tests look at the texels.
    check_normals(normals, options.scale)?;
    let (y_convention, convention_chosen) = match options.y_convention {
        Some(y) => (y, Chosen::Given),
        None => {
            let verdict = convention();
            match verdict.convention {
                Ok(y) => (y, Chosen::Detected(verdict.confidence)),
                Err(_) => (YConvention::YUp, Chosen::Default),
            }
        }
    };
    let (boundary, boundary_chosen) = match options.boundary {
        Some(b) => (b, Chosen::Given),
        None if seam().heights_tile() => (Boundary::Periodic, Chosen::Detected(1.0)),
        None => (Boundary::Free, Chosen::Detected(1.0)),
    };
    let slopes = Slopes::from_normals(normals, y_convention, options.scale)?;
    let (texels, method, derivative_chosen, fit) = match options.derivative {
        Some(derivative) => {
            let method = IntegrationMethod { boundary, derivative };
            (integrate(&slopes, method)?, method, Chosen::Given, None)
        }
        None => {
            let (texels, fit) = integrate_fitted(&slopes, boundary)?;
            (texels, IntegrationMethod { boundary, derivative: fit.best() }, Chosen::Detected(1.0), Some(fit))
        }
    };
    Ok(RecoveredHeights {
        width: normals.width,
        height: normals.height,
        texels,
        method,
        boundary_chosen,
        derivative_chosen,
        fit,
        y_convention,
        convention_chosen,
    })
}
