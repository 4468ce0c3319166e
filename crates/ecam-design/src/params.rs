//! Reading a generator's parameters: key/value pairs from any serde format
//! (TOML, JSON) or from flags, each checked against its field's kind in
//! [`ecam_core::generator::schema`] before the generator's `Params` read them.

use std::collections::BTreeMap;

use ecam_core::generator::Generator as Schema;
use ecam_core::generator::key_points::KeyPoint;
use ecam_core::generator::schema::{Field, FieldKind, Storage};
use ecam_core::segments::{InterpolationPoint, SegmentSpec};
use serde::Deserialize;
use serde::de::value::MapDeserializer;
use serde::de::{
    DeserializeOwned, DeserializeSeed, Error as _, IntoDeserializer, MapAccess, Visitor,
};

use crate::error::GenerateError;
use crate::expr;

/// Parameter values by key, each checked against its field's kind.
pub type Values = BTreeMap<&'static str, Param>;

/// One parameter value, as its field's kind reads it.
#[derive(Clone, Debug, PartialEq)]
pub enum Param {
    /// An integer field (`i64`, `u32` or `u16` storage).
    Int(i64),
    /// An integer field stored as `usize`.
    Uint(u64),
    /// A number field (arithmetic already evaluated).
    Float(f64),
    /// A choice (its name or code) or a text field.
    Text(String),
    /// A switch.
    Bool(bool),
    /// Key points.
    Keys(Vec<KeyPoint>),
    /// An interpolation point.
    Point(InterpolationPoint),
    /// Segments between interpolation points.
    Segments(Vec<SegmentSpec>),
}

/// Reads a map of parameters for one generator from any serde format:
/// refuses keys its schema does not have, reads each value as its field's
/// kind (numbers may be arithmetic text, choices names or codes). Names
/// are checked later, by the option types themselves.
#[derive(Clone, Copy, Debug)]
pub struct ValuesSeed {
    generator: &'static Schema,
    /// Say which key a bad value belongs to (formats that do not say it themselves).
    name_keys: bool,
}

impl ValuesSeed {
    /// Reads parameters of `generator`; `name_keys` adds the key to a bad
    /// value's error, for formats whose errors do not say it (JSON).
    pub fn new(generator: &'static Schema, name_keys: bool) -> Self {
        Self {
            generator,
            name_keys,
        }
    }
}

impl<'de> DeserializeSeed<'de> for ValuesSeed {
    type Value = Values;

    fn deserialize<D: serde::Deserializer<'de>>(self, d: D) -> Result<Values, D::Error> {
        d.deserialize_map(self)
    }
}

impl<'de> Visitor<'de> for ValuesSeed {
    type Value = Values;

    fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("a map")
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Values, A::Error> {
        let mut values = Values::new();
        while let Some(field) = map.next_key_seed(KeySeed(self.generator))? {
            let value = match field.kind {
                FieldKind::Integer { storage, .. } => match storage {
                    Storage::I64 => map.next_value::<i64>().map(Param::Int),
                    Storage::U32 => map.next_value::<u32>().map(|v| Param::Int(v.into())),
                    Storage::U16 => map.next_value::<u16>().map(|v| Param::Int(v.into())),
                    Storage::Usize => map.next_value::<usize>().map(|v| Param::Uint(v as u64)),
                },
                FieldKind::Number => map.next_value::<Number>().map(|n| Param::Float(n.0)),
                FieldKind::Choice(_) => map.next_value::<Word>().map(|w| Param::Text(w.0)),
                FieldKind::Text => map.next_value::<String>().map(Param::Text),
                FieldKind::Switch => map.next_value::<bool>().map(Param::Bool),
                FieldKind::KeyPoints => map.next_value::<Vec<KeyPoint>>().map(Param::Keys),
                FieldKind::Point => map
                    .next_value::<serde_json::Value>()
                    .and_then(|v| with_numbers(v).map_err(A::Error::custom))
                    .and_then(|v| serde_json::from_value(v).map_err(A::Error::custom))
                    .map(Param::Point),
                FieldKind::Segments => map
                    .next_value::<serde_json::Value>()
                    .and_then(|v| with_numbers(v).map_err(A::Error::custom))
                    .and_then(|v| serde_json::from_value(v).map_err(A::Error::custom))
                    .map(Param::Segments),
            };
            let value = match value {
                Err(e) if self.name_keys => {
                    return Err(A::Error::custom(format!("{e} in `{}`", field.key)));
                }
                other => other?,
            };
            values.insert(field.key, value);
        }
        Ok(values)
    }
}

/// Reads a key, refusing one the generator does not have (while reading
/// it, so a file's error points at the key).
struct KeySeed(&'static Schema);

impl<'de> DeserializeSeed<'de> for KeySeed {
    type Value = &'static Field;

    fn deserialize<D: serde::Deserializer<'de>>(self, d: D) -> Result<&'static Field, D::Error> {
        d.deserialize_str(self)
    }
}

impl Visitor<'_> for KeySeed {
    type Value = &'static Field;

    fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("a parameter name")
    }

    fn visit_str<E: serde::de::Error>(self, key: &str) -> Result<&'static Field, E> {
        self.0
            .field(key)
            .ok_or_else(|| E::custom(unknown_field(key, self.0)))
    }
}

/// Serde's own wording for an unknown field, listing the generator's keys.
fn unknown_field(key: &str, generator: &Schema) -> String {
    let keys: Vec<String> = generator
        .fields
        .iter()
        .map(|f| format!("`{}`", f.key))
        .collect();
    format!("unknown field `{key}`, expected one of {}", keys.join(", "))
}

/// The generator's `Params` from checked values; the rest keep their defaults.
pub(crate) fn typed<P: DeserializeOwned>(values: Values) -> Result<P, GenerateError> {
    let map = MapDeserializer::<_, serde_json::Error>::new(values.into_iter());
    P::deserialize(map)
        .map_err(|e| GenerateError::Values(ecam_core::io::plain_serde_message(&e.to_string())))
}

impl<'de> IntoDeserializer<'de, serde_json::Error> for Param {
    type Deserializer = Self;

    fn into_deserializer(self) -> Self {
        self
    }
}

impl<'de> serde::Deserializer<'de> for Param {
    type Error = serde_json::Error;

    fn deserialize_any<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Self::Error> {
        match self {
            Self::Int(v) => visitor.visit_i64(v),
            Self::Uint(v) => visitor.visit_u64(v),
            Self::Float(v) => visitor.visit_f64(v),
            Self::Text(v) => visitor.visit_string(v),
            Self::Bool(v) => visitor.visit_bool(v),
            Self::Keys(keys) => serde_json::to_value(keys)?.deserialize_any(visitor),
            Self::Point(point) => serde_json::to_value(point)?.deserialize_any(visitor),
            Self::Segments(s) => serde_json::to_value(s)?.deserialize_any(visitor),
        }
    }

    fn deserialize_option<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Self::Error> {
        visitor.visit_some(self)
    }

    serde::forward_to_deserialize_any! {
        bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string
        bytes byte_buf unit unit_struct newtype_struct seq tuple
        tuple_struct map struct enum identifier ignored_any
    }
}

/// The boundary values an interpolation point or a segment may write as
/// arithmetic (`velocity = "5/3"`).
const NUMBER_KEYS: [&str; 3] = ["velocity", "acceleration", "jerk"];

/// `value` (a point, or a list of segments) with its boundary values
/// written as arithmetic text turned into numbers.
fn with_numbers(value: serde_json::Value) -> Result<serde_json::Value, String> {
    use serde_json::Value;
    match value {
        Value::Array(items) => items
            .into_iter()
            .map(with_numbers)
            .collect::<Result<Vec<_>, _>>()
            .map(Value::Array),
        Value::Object(mut map) => {
            for key in NUMBER_KEYS {
                if let Some(Value::String(text)) = map.get(key) {
                    let n = expr::number(text).map_err(|e| format!("{key} {text:?}: {e:#}"))?;
                    let n = serde_json::Number::from_f64(n)
                        .ok_or_else(|| format!("{key} {text:?} is not a finite number"))?;
                    map.insert(key.to_string(), Value::Number(n));
                }
            }
            Ok(Value::Object(map))
        }
        other => Ok(other),
    }
}

/// A number written as a TOML number or as an arithmetic string (`"5/3"`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Number(pub f64);

impl<'de> Deserialize<'de> for Number {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        #[derive(Deserialize)]
        #[serde(untagged)]
        enum Raw {
            Int(i64),
            Float(f64),
            Text(String),
        }
        match Raw::deserialize(d)? {
            Raw::Int(i) => Ok(Self(i as f64)),
            Raw::Float(f) => Ok(Self(f)),
            Raw::Text(t) => expr::number(&t).map(Self).map_err(serde::de::Error::custom),
        }
    }
}

/// A name or code read from a flag or TOML (an integer or a string).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Word(pub String);

impl<'de> Deserialize<'de> for Word {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        #[derive(Deserialize)]
        #[serde(untagged)]
        enum Raw {
            Code(i64),
            Name(String),
        }
        Ok(Self(match Raw::deserialize(d)? {
            Raw::Code(c) => c.to_string(),
            Raw::Name(n) => n,
        }))
    }
}

/// What is wrong with `value` for `field`: a choice it does not offer, a
/// whole number outside its range.
fn out_of_bounds(field: &Field, value: &Param) -> Option<String> {
    match (field.kind, value) {
        (FieldKind::Choice(names), Param::Text(text)) if field.choice(text.trim()).is_none() => {
            Some(format!(
                "unknown {} {text:?}; use {}",
                field.name,
                names.join(", ")
            ))
        }
        (FieldKind::Integer { min, max, .. }, Param::Int(v)) if !(min..=max).contains(v) => {
            Some(format!("{v} is not between {min} and {max}"))
        }
        _ => None,
    }
}

/// Reads a TOML parameter file's text (`ecam table gen --params`) for
/// `generator`.
///
/// # Errors
/// TOML syntax, keys the generator does not have, values of the wrong kind.
pub fn read_toml(generator: &'static Schema, text: &str) -> Result<Values, GenerateError> {
    let values = ValuesSeed::new(generator, false)
        .deserialize(toml::Deserializer::new(text))
        .map_err(|e| GenerateError::Values(ecam_core::io::plain_serde_message(&e.to_string())))?;
    // A choice or a whole number is checked against the schema here, so
    // the message names the line it was written on (the generator would
    // refuse it too, without knowing where it came from).
    for (key, value) in &values {
        let problem = generator
            .field(key)
            .and_then(|field| out_of_bounds(field, value));
        if let Some(problem) = problem {
            let spans: BTreeMap<String, toml::Spanned<toml::Value>> =
                toml::from_str(text).unwrap_or_default();
            let at = spans.get(*key).map_or(0, |v| v.span().start);
            let line = text.get(..at).map_or(0, |t| t.lines().count().max(1));
            let written = text.lines().nth(line.saturating_sub(1)).unwrap_or_default();
            return Err(GenerateError::Values(format!(
                "line {line}: `{}`: {problem}",
                ecam_core::excerpt::excerpt(written.trim())
            )));
        }
    }
    Ok(values)
}
