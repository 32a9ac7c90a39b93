//! Every closed set's words: each value's name and aliases read back as that value, no word
//! names two values, and each value says what it does. The command line's value parsers and
//! the Python keywords read these words, so a clash here would make one of them ambiguous.

use std::fmt::Debug;

use bumpmap::bumpmap_core::combiners::Precision;
use bumpmap::bumpmap_io::texture_file::TextureFormat;
use bumpmap::bumpmap_io::{Channel, ObjTexcoords};
use bumpmap::bumpmap_math::integration::Derivative;
use bumpmap::bumpmap_math::tangent::TangentMode;
use bumpmap::heights::HeightMethod;
use bumpmap::options::{Filter, RoughnessLayout};
use bumpmap::{
    BackendChoice, Encoding, HalfAngle, Kernel, MipMode, Named, Normalize, ParallaxShadow, SelfShadow, SpecularFilter,
    SpecularMode, SpecularShadow, TechniqueName, ViewerModel, Wrap, YConvention,
};

fn words_read_back<T: Named + Debug>() -> usize {
    let mut words: Vec<&str> = Vec::new();
    for &value in T::ALL {
        assert_eq!(T::parse(value.name()), Some(value), "{value:?}'s name");
        for alias in value.aliases() {
            assert_eq!(T::parse(alias), Some(value), "{value:?}'s alias {alias}");
        }
        assert!(!value.description().is_empty(), "{value:?} says what it does");
        assert!(!value.description().contains("--"), "{value:?}'s description names a flag");
        words.push(value.name());
        words.extend(value.aliases());
    }
    let mut unique = words.clone();
    unique.sort();
    unique.dedup();
    assert_eq!(unique.len(), words.len(), "a word names two values: {words:?}");
    assert_eq!(T::parse("no-such-word"), None);
    T::ALL.len()
}

#[test]
fn every_closed_set_reads_its_own_words() {
    let counts = [
        words_read_back::<YConvention>(),
        words_read_back::<ObjTexcoords>(),
        words_read_back::<ViewerModel>(),
        words_read_back::<Filter>(),
        words_read_back::<Precision>(),
        words_read_back::<SpecularMode>(),
        words_read_back::<Normalize>(),
        words_read_back::<SelfShadow>(),
        words_read_back::<HalfAngle>(),
        words_read_back::<SpecularShadow>(),
        words_read_back::<SpecularFilter>(),
        words_read_back::<ParallaxShadow>(),
        words_read_back::<RoughnessLayout>(),
        words_read_back::<BackendChoice>(),
        words_read_back::<TechniqueName>(),
        words_read_back::<Kernel>(),
        words_read_back::<Wrap>(),
        words_read_back::<Encoding>(),
        words_read_back::<MipMode>(),
        words_read_back::<Channel>(),
        words_read_back::<TangentMode>(),
        words_read_back::<TextureFormat>(),
        words_read_back::<Derivative>(),
        words_read_back::<HeightMethod>(),
    ];
    assert_eq!(counts, [2, 2, 2, 3, 2, 2, 2, 3, 2, 3, 5, 4, 4, 3, 24, 7, 3, 2, 2, 5, 2, 4, 8, 4]);
}

/// The sets a user may leave to the tool take `auto` beside their words, so none may have a
/// value of that name.
#[test]
fn auto_is_no_value_of_a_set_that_may_be_left_to_the_tool() {
    use bumpmap::bumpmap_math::named::{AUTO, parse_or_auto};
    assert_eq!(Derivative::parse(AUTO), None);
    assert_eq!(YConvention::parse(AUTO), None);
    assert_eq!(parse_or_auto::<Derivative>("sobel3"), Some(Some(Derivative::Kernel(Kernel::Sobel3))));
    assert_eq!(parse_or_auto::<Derivative>(AUTO), Some(None));
}
