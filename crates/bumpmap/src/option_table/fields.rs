//! How a field of the typed options takes a [`Value`]: its [`Kind`], its default as a value, and
//! the reading of a value into it. Numbers, flags, vectors and files here; closed sets through
//! [`Named`] ([`WordField`], [`MaybeWordField`]); the library's own texts (a scene, a decal, a
//! gloss map, a height source) through their `parse`.
//!
//! What this module does not do: check a range (the row's [`super::Opt::check`] and the typed
//! options' `set_up` do).

use std::path::PathBuf;

use bumpmap_core::scene::{Attenuation, SceneLight};
use bumpmap_io::HeightSource;
use bumpmap_math::Named;
use glam::{Vec2, Vec3};

use super::{Kind, Value, choices};
use crate::options::{DecalChoice, GlossChoice, SceneChoice};

/// A field of the typed options that one option sets.
pub trait Field {
    /// The kind of value it takes.
    fn kind(&self) -> Kind;
    /// Its value as the option would give it; `None` where there is none to show.
    fn get(&self) -> Option<Value>;
    /// Sets `value` (of [`Field::kind`]) into it.
    fn set(&mut self, value: Value) -> Result<(), String>;
}

/// A field holding a word of a closed set.
pub trait WordField {
    /// The set's words.
    fn kind(&self) -> Kind;
    /// The word it holds.
    fn get(&self) -> Option<Value>;
    /// Sets the value a word (name or alias) names.
    fn set(&mut self, value: Value) -> Result<(), String>;
}

/// A field holding a word of a closed set, or none (the library decides).
pub trait MaybeWordField {
    /// The set's words.
    fn kind(&self) -> Kind;
    /// The word it holds, if any.
    fn get(&self) -> Option<Value>;
    /// Sets the value a word names.
    fn set(&mut self, value: Value) -> Result<(), String>;
}

fn wrong(value: &Value) -> String {
    format!("{value} is not a value of this option's kind")
}

fn word<T: Named>(value: Value) -> Result<T, String> {
    let Value::Word(w) = value else { return Err(wrong(&value)) };
    // An option that ignores case hands over the word as typed (texconv's `BC5_UNORM`).
    T::parse(&w)
        .or_else(|| {
            T::ALL
                .iter()
                .copied()
                .find(|v| v.name().eq_ignore_ascii_case(&w) || v.aliases().iter().any(|a| a.eq_ignore_ascii_case(&w)))
        })
        .ok_or_else(|| format!("invalid value '{w}'; possible values: {}", T::names().join(", ")))
}

impl<T: Named> WordField for T {
    fn kind(&self) -> Kind {
        Kind::Word(choices::<T>())
    }
    fn get(&self) -> Option<Value> {
        Some(Value::Word(self.name().to_string()))
    }
    fn set(&mut self, value: Value) -> Result<(), String> {
        *self = word(value)?;
        Ok(())
    }
}

impl<T: Named> MaybeWordField for Option<T> {
    fn kind(&self) -> Kind {
        Kind::Word(choices::<T>())
    }
    fn get(&self) -> Option<Value> {
        self.map(|v| Value::Word(v.name().to_string()))
    }
    fn set(&mut self, value: Value) -> Result<(), String> {
        *self = Some(word(value)?);
        Ok(())
    }
}

/// A field holding a word of a closed set, or none where the option says `auto`.
pub trait AutoWordField {
    /// The set's words (`auto` is the option's to add).
    fn kind(&self) -> Kind;
    /// The word it holds, `auto` for none.
    fn get(&self) -> Option<Value>;
    /// Sets the value a word names, none for `auto`.
    fn set(&mut self, value: Value) -> Result<(), String>;
}

impl<T: Named> AutoWordField for Option<T> {
    fn kind(&self) -> Kind {
        Kind::Word(choices::<T>())
    }
    fn get(&self) -> Option<Value> {
        Some(Value::Word(self.map_or(bumpmap_math::named::AUTO, |v| v.name()).to_string()))
    }
    fn set(&mut self, value: Value) -> Result<(), String> {
        *self = match &value {
            Value::Word(w) if w == bumpmap_math::named::AUTO => None,
            _ => Some(word(value)?),
        };
        Ok(())
    }
}

fn number(value: Value) -> Result<f32, String> {
    match value {
        Value::Number(v) => Ok(v),
        other => Err(wrong(&other)),
    }
}

fn numbers<const N: usize>(value: Value) -> Result<[f32; N], String> {
    match value {
        Value::Numbers(v) if v.len() == N => Ok(v.try_into().expect("N numbers")),
        Value::Numbers(v) => Err(format!("takes {N} numbers, got {}", v.len())),
        other => Err(wrong(&other)),
    }
}

fn text(value: Value) -> Result<String, String> {
    match value {
        Value::Text(t) => Ok(t),
        Value::Path(p) => Ok(p.to_string_lossy().into_owned()),
        other => Err(wrong(&other)),
    }
}

fn numbers_value(v: &[f32]) -> Value {
    Value::Numbers(v.to_vec())
}

impl Field for f32 {
    fn kind(&self) -> Kind {
        Kind::Number
    }
    fn get(&self) -> Option<Value> {
        Some(Value::Number(*self))
    }
    fn set(&mut self, value: Value) -> Result<(), String> {
        *self = number(value)?;
        Ok(())
    }
}

impl Field for Option<f32> {
    fn kind(&self) -> Kind {
        Kind::Number
    }
    fn get(&self) -> Option<Value> {
        self.map(Value::Number)
    }
    fn set(&mut self, value: Value) -> Result<(), String> {
        *self = Some(number(value)?);
        Ok(())
    }
}

impl Field for u32 {
    fn kind(&self) -> Kind {
        Kind::Whole { min: 0, max: u32::MAX as u64 }
    }
    fn get(&self) -> Option<Value> {
        Some(Value::Whole(*self as u64))
    }
    fn set(&mut self, value: Value) -> Result<(), String> {
        match value {
            Value::Whole(v) => *self = u32::try_from(v).map_err(|_| format!("{v} is beyond {}", u32::MAX))?,
            other => return Err(wrong(&other)),
        }
        Ok(())
    }
}

impl Field for usize {
    fn kind(&self) -> Kind {
        Kind::Whole { min: 0, max: u32::MAX as u64 }
    }
    fn get(&self) -> Option<Value> {
        Some(Value::Whole(*self as u64))
    }
    fn set(&mut self, value: Value) -> Result<(), String> {
        match value {
            Value::Whole(v) => *self = usize::try_from(v).map_err(|_| format!("{v} is too large"))?,
            other => return Err(wrong(&other)),
        }
        Ok(())
    }
}

/// Bits a channel (8 or 16: the row checks which).
impl Field for u8 {
    fn kind(&self) -> Kind {
        Kind::Whole { min: 0, max: u8::MAX as u64 }
    }
    fn get(&self) -> Option<Value> {
        Some(Value::Whole(*self as u64))
    }
    fn set(&mut self, value: Value) -> Result<(), String> {
        match value {
            Value::Whole(v) => *self = u8::try_from(v).map_err(|_| format!("{v} is beyond {}", u8::MAX))?,
            other => return Err(wrong(&other)),
        }
        Ok(())
    }
}

/// Names the library checks itself (techniques by name).
impl Field for Vec<String> {
    fn kind(&self) -> Kind {
        Kind::List(None)
    }
    /// None: no names given means the library's own choice.
    fn get(&self) -> Option<Value> {
        None
    }
    fn set(&mut self, value: Value) -> Result<(), String> {
        match value {
            Value::Words(words) => *self = words,
            other => return Err(wrong(&other)),
        }
        Ok(())
    }
}

impl Field for HeightSource {
    fn kind(&self) -> Kind {
        Kind::Text
    }
    fn get(&self) -> Option<Value> {
        Some(Value::Text(self.to_string()))
    }
    fn set(&mut self, value: Value) -> Result<(), String> {
        *self = HeightSource::parse(&text(value)?);
        Ok(())
    }
}

impl Field for bool {
    fn kind(&self) -> Kind {
        Kind::Flag
    }
    fn get(&self) -> Option<Value> {
        Some(Value::Flag(*self))
    }
    fn set(&mut self, value: Value) -> Result<(), String> {
        match value {
            Value::Flag(b) => *self = b,
            other => return Err(wrong(&other)),
        }
        Ok(())
    }
}

impl Field for Option<Vec3> {
    fn kind(&self) -> Kind {
        Kind::Numbers(3)
    }
    fn get(&self) -> Option<Value> {
        self.map(|v| numbers_value(&v.to_array()))
    }
    fn set(&mut self, value: Value) -> Result<(), String> {
        *self = Some(Vec3::from(numbers::<3>(value)?));
        Ok(())
    }
}

impl Field for (f32, f32) {
    fn kind(&self) -> Kind {
        Kind::Numbers(2)
    }
    fn get(&self) -> Option<Value> {
        Some(numbers_value(&[self.0, self.1]))
    }
    fn set(&mut self, value: Value) -> Result<(), String> {
        let [a, b] = numbers::<2>(value)?;
        *self = (a, b);
        Ok(())
    }
}

impl Field for Option<Vec2> {
    fn kind(&self) -> Kind {
        Kind::Numbers(2)
    }
    fn get(&self) -> Option<Value> {
        self.map(|v| numbers_value(&v.to_array()))
    }
    fn set(&mut self, value: Value) -> Result<(), String> {
        *self = Some(Vec2::from(numbers::<2>(value)?));
        Ok(())
    }
}

/// Two counts (a tessellation): whole numbers given as numbers.
impl Field for Option<(usize, usize)> {
    fn kind(&self) -> Kind {
        Kind::Numbers(2)
    }
    fn get(&self) -> Option<Value> {
        self.map(|(u, v)| numbers_value(&[u as f32, v as f32]))
    }
    fn set(&mut self, value: Value) -> Result<(), String> {
        let [u, v] = numbers::<2>(value)?;
        let whole = |x: f32| x.fract() == 0.0 && x >= 0.0;
        if !(whole(u) && whole(v)) {
            return Err(format!("takes two whole numbers, got {u}, {v}"));
        }
        *self = Some((u as usize, v as usize));
        Ok(())
    }
}

impl Field for Option<PathBuf> {
    fn kind(&self) -> Kind {
        Kind::Path
    }
    fn get(&self) -> Option<Value> {
        self.clone().map(Value::Path)
    }
    fn set(&mut self, value: Value) -> Result<(), String> {
        *self = Some(match value {
            Value::Path(p) => p,
            Value::Text(t) => PathBuf::from(t),
            other => return Err(wrong(&other)),
        });
        Ok(())
    }
}

impl Field for Option<HeightSource> {
    fn kind(&self) -> Kind {
        Kind::Text
    }
    fn get(&self) -> Option<Value> {
        self.as_ref().map(|s| Value::Text(s.to_string()))
    }
    fn set(&mut self, value: Value) -> Result<(), String> {
        *self = Some(HeightSource::parse(&text(value)?));
        Ok(())
    }
}

impl Field for SceneChoice {
    fn kind(&self) -> Kind {
        Kind::Text
    }
    fn get(&self) -> Option<Value> {
        Some(Value::Text(self.to_string()))
    }
    fn set(&mut self, value: Value) -> Result<(), String> {
        let name = text(value)?;
        *self = SceneChoice::parse(&name).ok_or_else(|| {
            format!("unknown scene '{name}': use {} or mesh:FILE", bumpmap_core::SceneKind::built_in_names())
        })?;
        Ok(())
    }
}

impl Field for Option<DecalChoice> {
    fn kind(&self) -> Kind {
        Kind::Text
    }
    fn get(&self) -> Option<Value> {
        self.as_ref().map(|d| Value::Text(d.to_string()))
    }
    fn set(&mut self, value: Value) -> Result<(), String> {
        *self = Some(DecalChoice::parse(&text(value)?));
        Ok(())
    }
}

impl Field for GlossChoice {
    fn kind(&self) -> Kind {
        Kind::Text
    }
    /// None where there is no gloss map (the default shows as none given).
    fn get(&self) -> Option<Value> {
        (*self != GlossChoice::None).then(|| Value::Text(self.to_string()))
    }
    fn set(&mut self, value: Value) -> Result<(), String> {
        *self = GlossChoice::parse(&text(value)?);
        Ok(())
    }
}

impl Field for Vec<SceneLight> {
    fn kind(&self) -> Kind {
        Kind::Lights
    }
    /// None: no lights given means the scene's own.
    fn get(&self) -> Option<Value> {
        None
    }
    fn set(&mut self, value: Value) -> Result<(), String> {
        match value {
            Value::Lights(lights) => *self = lights,
            other => return Err(wrong(&other)),
        }
        Ok(())
    }
}

impl Field for Option<Attenuation> {
    fn kind(&self) -> Kind {
        Kind::Attenuation
    }
    fn get(&self) -> Option<Value> {
        self.map(Value::Attenuation)
    }
    fn set(&mut self, value: Value) -> Result<(), String> {
        match value {
            Value::Attenuation(a) => *self = Some(a),
            other => return Err(wrong(&other)),
        }
        Ok(())
    }
}
