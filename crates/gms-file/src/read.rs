//! Reading and writing: JSON text (or an already parsed JSON value) to [`ModelFile`] and back.
//!
//! Text is parsed once into a JSON value, strictly: a key given twice in any object, a number
//! beyond the f64 range and anything that is not JSON (NaN, Infinity, trailing text) are refused
//! there, a syntax error with its line and column, the others with the key path. The value's
//! `format` and `version` then say what it is, so that a file of another version is called that
//! rather than refused for keys this version does not know. Last, the value is read into the
//! typed structs of its version through [`Strict`], which refuses an array where an object is
//! expected (serde's derived structs would take one field by position), tracking the key path so
//! that every refusal names the key.

use core::fmt;

use serde::de::{
    self, DeserializeSeed, Deserializer, IgnoredAny, IntoDeserializer, MapAccess, SeqAccess,
    Visitor,
};
use serde::{Deserialize, Serialize};
use serde_json::{Map, Number, Value};

use crate::error::{FileError, Problem};
use crate::file::{Friction, Measurement, ModelFile, PositionTerms, Reconstruction, Report, Units};
use crate::{FORMAT, MAX_FILE_BYTES, VERSION};

/// A version 2 or 3 model file's object (version 2 has no `reconstruction.acceleration_cutoff`,
/// checked after the read).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Body {
    #[allow(dead_code)] // checked before the typed read, by `kind`
    format: IgnoredAny,
    #[allow(dead_code)] // checked before the typed read, by `kind`
    version: IgnoredAny,
    units: Units,
    friction: Friction,
    #[serde(default)]
    level: Option<PositionTerms>,
    #[serde(default)]
    position_force: Option<PositionTerms>,
    #[serde(default)]
    measurement: Measurement,
    #[serde(default)]
    reconstruction: Option<Reconstruction>,
    #[serde(default, deserialize_with = "report")]
    report: Option<Report>,
}

/// A version 1 model file's object: no `position_force`, no `reconstruction` (and no
/// `friction.sigma2_neg`, checked after the read).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct BodyV1 {
    #[allow(dead_code)] // checked before the typed read, by `kind`
    format: IgnoredAny,
    #[allow(dead_code)] // checked before the typed read, by `kind`
    version: IgnoredAny,
    units: Units,
    friction: Friction,
    #[serde(default)]
    level: Option<PositionTerms>,
    #[serde(default)]
    measurement: Measurement,
    #[serde(default, deserialize_with = "report")]
    report: Option<Report>,
}

impl From<Body> for ModelFile {
    fn from(body: Body) -> Self {
        ModelFile {
            units: body.units,
            friction: body.friction,
            level: body.level,
            position_force: body.position_force,
            measurement: body.measurement,
            reconstruction: body.reconstruction,
            report: body.report,
        }
    }
}

impl From<BodyV1> for ModelFile {
    fn from(body: BodyV1) -> Self {
        ModelFile {
            units: body.units,
            friction: body.friction,
            level: body.level,
            position_force: None,
            measurement: body.measurement,
            reconstruction: None,
            report: body.report,
        }
    }
}

/// What the object is: a parameter file (no `format` key) or a model file of a version.
enum Kind {
    Parameters,
    Model(u64),
}

/// The kind of file, from its `format` and `version`.
fn kind(format: Option<&Value>, version: Option<&Value>) -> Result<Kind, FileError> {
    let Some(format) = format else {
        return Ok(Kind::Parameters);
    };
    if format.as_str() != Some(FORMAT) {
        return Err(FileError::Format { got: shown(format) });
    }
    let Some(version) = version else {
        return Err(FileError::Version { got: None });
    };
    match version.as_u64() {
        Some(number @ 1..=VERSION) => Ok(Kind::Model(number)),
        Some(number) if number > VERSION => Err(FileError::Newer { version: number }),
        _ => Err(FileError::Version {
            got: Some(shown(version)),
        }),
    }
}

/// A JSON value as a message shows it: its text, cut to 80 characters.
fn shown(value: &Value) -> String {
    let text = value.to_string();
    match text.char_indices().nth(80) {
        Some((end, _)) => format!("{}…", &text[..end]),
        None => text,
    }
}

/// The JSON value of `text`, parsed strictly (module documentation).
pub(crate) fn parse(text: &str) -> Result<Value, FileError> {
    let mut deserializer = serde_json::Deserializer::from_str(text);
    let Parsed(value) = serde_path_to_error::deserialize(&mut deserializer)
        .map_err(|error| file_error(&error.path().to_string(), error.inner()))?;
    deserializer
        .end()
        .map_err(|error| file_error(".", &error))?;
    Ok(value)
}

/// The model file (or parameter file) of a JSON value.
pub(crate) fn model_from_value(value: Value) -> Result<ModelFile, FileError> {
    let Value::Object(object) = &value else {
        return Err(not_an_object(&value));
    };
    match kind(object.get("format"), object.get("version"))? {
        // A parameter file is the friction of the model file it reads as: its keys are named
        // as the model file has them (`friction.W[2]`).
        Kind::Parameters => Ok(ModelFile::new(
            track(value).map_err(|error: FileError| error.under("friction"))?,
        )),
        Kind::Model(1) => version_one(track(value)?),
        Kind::Model(2) => version_two(track(value)?),
        Kind::Model(_) => Ok(track::<Body>(value)?.into()),
    }
}

/// The friction parameters of a parameter file's JSON value (the object alone).
pub(crate) fn friction_from_value(value: Value) -> Result<Friction, FileError> {
    if !value.is_object() {
        return Err(not_an_object(&value));
    }
    track(value)
}

fn not_an_object(value: &Value) -> FileError {
    FileError::NotAnObject {
        got: json_type(value).to_owned(),
    }
}

/// A version 1 body, refusing the key that came only with version 2.
fn version_one(body: BodyV1) -> Result<ModelFile, FileError> {
    // Present exactly when the key is: the reader refuses `null` for it.
    if body.friction.sigma2_neg.is_some() {
        return Err(FileError::Shape {
            key: "friction.sigma2_neg".to_owned(),
            problem: Problem::UnknownKey,
            message: "unknown key in a version 1 model file (it came with version 2)".to_owned(),
        });
    }
    Ok(body.into())
}

/// A version 2 body, refusing the key that came only with version 3.
fn version_two(body: Body) -> Result<ModelFile, FileError> {
    // Present exactly when the key is: the reader refuses `null` for it.
    if body
        .reconstruction
        .is_some_and(|r| r.acceleration_cutoff.is_some())
    {
        return Err(FileError::Shape {
            key: "reconstruction.acceleration_cutoff".to_owned(),
            problem: Problem::UnknownKey,
            message: "unknown key in a version 2 model file (it came with version 3)".to_owned(),
        });
    }
    Ok(body.into())
}

/// Reads `T` from `value` through [`Strict`], turning serde's error into a [`FileError`] with
/// the key path.
fn track<T: for<'de> Deserialize<'de>>(value: Value) -> Result<T, FileError> {
    serde_path_to_error::deserialize(Strict(value)).map_err(|error| {
        let path = error.path().to_string();
        file_error(&path, error.inner())
    })
}

/// `serde_json`'s error at `path` (`"."` for the root) as a [`FileError`].
fn file_error(path: &str, error: &serde_json::Error) -> FileError {
    use serde_json::error::Category;
    let text = error.to_string();
    // serde_json appends " at line L column C" to the message when it knows the place.
    let message = match text.rfind(" at line ") {
        Some(at) if error.line() > 0 => &text[..at],
        _ => text.as_str(),
    };
    let root = path == ".";
    let syntax = matches!(error.classify(), Category::Syntax | Category::Eof);
    // A number beyond the f64 range is the value of a key, not a fault of the syntax.
    let out_of_range = message.starts_with("number out of range");
    if syntax && (root || !out_of_range) {
        return FileError::Syntax {
            line: error.line(),
            column: error.column(),
            message: message.to_owned(),
        };
    }
    // serde names the key of an unknown, missing or duplicate field in the message; the path
    // ends at the key itself for an unknown one, at the object that holds it otherwise.
    let found = [
        ("unknown field `", "unknown key", Problem::UnknownKey),
        ("missing field `", "missing key", Problem::MissingKey),
        ("duplicate field `", "key given twice", Problem::Repeated),
    ]
    .iter()
    .find_map(|(prefix, said, problem)| {
        let (name, tail) = message.strip_prefix(prefix)?.split_once('`')?;
        let key = if root || path == name {
            name.to_owned()
        } else if path.ends_with(&format!(".{name}")) {
            path.to_owned()
        } else {
            format!("{path}.{name}")
        };
        Some((key, *problem, format!("{said}{tail}")))
    });
    let (key, problem, message) = found.unwrap_or_else(|| {
        let key = if root { String::new() } else { path.to_owned() };
        (key, problem_of(message), message.to_owned())
    });
    if key.is_empty() {
        return FileError::NotAnObject { got: message };
    }
    let message = if error.line() > 0 {
        format!(
            "{message} (line {}, column {})",
            error.line(),
            error.column()
        )
    } else {
        message
    };
    FileError::Shape {
        key,
        problem,
        message,
    }
}

/// The problem a message of serde (or of this reader's strict value) describes.
fn problem_of(message: &str) -> Problem {
    if message.starts_with("number out of range") {
        Problem::OutOfRange
    } else if message.starts_with("invalid length") {
        Problem::WrongLength
    } else if message.starts_with("key given twice") {
        Problem::Repeated
    } else {
        Problem::WrongType
    }
}

/// JSON's name for the type of `value`, as serde's messages give it.
fn json_type(value: &Value) -> &'static str {
    match value {
        Value::Null => "null",
        Value::Bool(_) => "a boolean",
        Value::Number(_) => "a number",
        Value::String(_) => "a string",
        Value::Array(_) => "a sequence",
        Value::Object(_) => "a map",
    }
}

/// A report: `null` or a JSON object, whose keys, at every depth, are each given once.
fn report<'de, D: Deserializer<'de>>(deserializer: D) -> Result<Option<Report>, D::Error> {
    match deserializer.deserialize_any(StrictValue)? {
        Value::Null => Ok(None),
        Value::Object(object) => Ok(Some(object)),
        other => Err(de::Error::invalid_type(
            unexpected(&other),
            &"a JSON object or null",
        )),
    }
}

fn unexpected(value: &Value) -> de::Unexpected<'_> {
    match value {
        Value::Null => de::Unexpected::Unit,
        Value::Bool(b) => de::Unexpected::Bool(*b),
        Value::Number(_) => de::Unexpected::Other("number"),
        Value::String(s) => de::Unexpected::Str(s),
        Value::Array(_) => de::Unexpected::Seq,
        Value::Object(_) => de::Unexpected::Map,
    }
}

/// A JSON value read as [`Value`] reads it, except that a key given twice in an object is
/// refused (`serde_json`'s own `Value` keeps the last one silently).
struct StrictValue;

impl<'de> DeserializeSeed<'de> for StrictValue {
    type Value = Value;

    fn deserialize<D: Deserializer<'de>>(self, deserializer: D) -> Result<Value, D::Error> {
        deserializer.deserialize_any(self)
    }
}

/// A JSON value parsed by [`StrictValue`].
struct Parsed(Value);

impl<'de> Deserialize<'de> for Parsed {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_any(StrictValue).map(Parsed)
    }
}

/// Refuses, at the path of the repeated key, the second value of a key (so that the error's
/// path names it).
struct Repeated<'a>(&'a str);

impl<'de> DeserializeSeed<'de> for Repeated<'_> {
    type Value = Value;

    fn deserialize<D: Deserializer<'de>>(self, _deserializer: D) -> Result<Value, D::Error> {
        Err(de::Error::custom(format_args!(
            "key given twice: `{}` appears more than once in the same object",
            self.0
        )))
    }
}

impl<'de> Visitor<'de> for StrictValue {
    type Value = Value;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("any JSON value")
    }

    fn visit_bool<E>(self, value: bool) -> Result<Value, E> {
        Ok(Value::Bool(value))
    }

    fn visit_i64<E>(self, value: i64) -> Result<Value, E> {
        Ok(Value::Number(value.into()))
    }

    fn visit_u64<E>(self, value: u64) -> Result<Value, E> {
        Ok(Value::Number(value.into()))
    }

    fn visit_f64<E: de::Error>(self, value: f64) -> Result<Value, E> {
        // JSON text has no spelling for a non-finite number; a parsed value may not hold one.
        Number::from_f64(value)
            .map(Value::Number)
            .ok_or_else(|| E::custom(format_args!("number out of range: {value}")))
    }

    fn visit_str<E>(self, value: &str) -> Result<Value, E> {
        Ok(Value::String(value.to_owned()))
    }

    fn visit_string<E>(self, value: String) -> Result<Value, E> {
        Ok(Value::String(value))
    }

    fn visit_unit<E>(self) -> Result<Value, E> {
        Ok(Value::Null)
    }

    fn visit_none<E>(self) -> Result<Value, E> {
        Ok(Value::Null)
    }

    fn visit_some<D: Deserializer<'de>>(self, deserializer: D) -> Result<Value, D::Error> {
        deserializer.deserialize_any(self)
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Value, A::Error> {
        let mut items = Vec::new();
        while let Some(item) = seq.next_element_seed(StrictValue)? {
            items.push(item);
        }
        Ok(Value::Array(items))
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Value, A::Error> {
        let mut object = Map::new();
        while let Some(key) = map.next_key::<String>()? {
            if object.contains_key(&key) {
                map.next_value_seed(Repeated(&key))?;
            }
            let value = map.next_value_seed(StrictValue)?;
            object.insert(key, value);
        }
        Ok(Value::Object(object))
    }
}

/// A JSON value read into typed structs as `serde_json`'s own `Value` reads it, except that a
/// struct must come as an object: serde's derived structs also take an array, field by
/// position, which the file format does not allow.
struct Strict(Value);

impl<'de> Deserializer<'de> for Strict {
    type Error = serde_json::Error;

    fn deserialize_any<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Self::Error> {
        match self.0 {
            Value::Array(items) => {
                let len = items.len();
                let mut seq = StrictSeq(items.into_iter());
                let value = visitor.visit_seq(&mut seq)?;
                // A fixed-length array (`trend`) reads only its length: the rest is refused,
                // as serde_json refuses it.
                if seq.0.len() == 0 {
                    Ok(value)
                } else {
                    Err(de::Error::invalid_length(len, &"fewer elements in array"))
                }
            }
            Value::Object(object) => visitor.visit_map(StrictMap {
                entries: object.into_iter(),
                value: None,
            }),
            other => other.deserialize_any(visitor),
        }
    }

    fn deserialize_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        _fields: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, Self::Error> {
        match self.0 {
            Value::Object(object) => visitor.visit_map(StrictMap {
                entries: object.into_iter(),
                value: None,
            }),
            other => Err(de::Error::invalid_type(unexpected(&other), &visitor)),
        }
    }

    fn deserialize_option<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Self::Error> {
        match self.0 {
            Value::Null => visitor.visit_none(),
            other => visitor.visit_some(Strict(other)),
        }
    }

    fn deserialize_enum<V: Visitor<'de>>(
        self,
        name: &'static str,
        variants: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, Self::Error> {
        // The file's enums (`units`, `source`) are strings; serde_json's `Value` would also take
        // an object `{"linear": null}`.
        match self.0 {
            Value::String(_) => self.0.deserialize_enum(name, variants, visitor),
            other => Err(de::Error::invalid_type(unexpected(&other), &visitor)),
        }
    }

    fn deserialize_newtype_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        visitor: V,
    ) -> Result<V::Value, Self::Error> {
        visitor.visit_newtype_struct(self)
    }

    serde::forward_to_deserialize_any! {
        bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string bytes byte_buf
        unit unit_struct seq tuple tuple_struct map identifier ignored_any
    }
}

struct StrictSeq(std::vec::IntoIter<Value>);

impl<'de> SeqAccess<'de> for StrictSeq {
    type Error = serde_json::Error;

    fn next_element_seed<T: DeserializeSeed<'de>>(
        &mut self,
        seed: T,
    ) -> Result<Option<T::Value>, Self::Error> {
        self.0
            .next()
            .map(|item| seed.deserialize(Strict(item)))
            .transpose()
    }

    fn size_hint(&self) -> Option<usize> {
        Some(self.0.len())
    }
}

struct StrictMap {
    entries: <Map<String, Value> as IntoIterator>::IntoIter,
    value: Option<Value>,
}

impl<'de> MapAccess<'de> for StrictMap {
    type Error = serde_json::Error;

    fn next_key_seed<K: DeserializeSeed<'de>>(
        &mut self,
        seed: K,
    ) -> Result<Option<K::Value>, Self::Error> {
        let Some((key, value)) = self.entries.next() else {
            return Ok(None);
        };
        self.value = Some(value);
        seed.deserialize(key.into_deserializer()).map(Some)
    }

    fn next_value_seed<V: DeserializeSeed<'de>>(
        &mut self,
        seed: V,
    ) -> Result<V::Value, Self::Error> {
        let value = self
            .value
            .take()
            .ok_or_else(|| de::Error::custom("a value was asked for before its key"))?;
        seed.deserialize(Strict(value))
    }
}

/// A model file as written (version [`VERSION`]): the keys in the documented order.
#[derive(Serialize)]
struct Written<'a> {
    format: &'static str,
    version: u64,
    units: Units,
    friction: &'a Friction,
    level: &'a Option<PositionTerms>,
    position_force: &'a Option<PositionTerms>,
    measurement: &'a Measurement,
    reconstruction: &'a Option<Reconstruction>,
    report: &'a Option<Report>,
}

impl<'a> From<&'a ModelFile> for Written<'a> {
    fn from(file: &'a ModelFile) -> Self {
        Written {
            format: FORMAT,
            version: VERSION,
            units: file.units,
            friction: &file.friction,
            level: &file.level,
            position_force: &file.position_force,
            measurement: &file.measurement,
            reconstruction: &file.reconstruction,
            report: &file.report,
        }
    }
}

/// The text of `file` (indented JSON, no final newline); `file` has been validated.
pub(crate) fn model_to_string(file: &ModelFile) -> String {
    serde_json::to_string_pretty(&Written::from(file))
        .expect("structs of numbers, strings and string-keyed maps always serialize")
}

/// The JSON value of `file`; `file` has been validated.
pub(crate) fn model_to_value(file: &ModelFile) -> Value {
    serde_json::to_value(Written::from(file))
        .expect("structs of numbers, strings and string-keyed maps always serialize")
}

/// The bytes of the file at `path`: a regular file of at most [`MAX_FILE_BYTES`] (a FIFO or a
/// device would block or never end), as UTF-8 text.
pub(crate) fn read_text(path: &std::path::Path) -> Result<String, FileError> {
    use std::io::Read;
    let refuse = |reason: &dyn fmt::Display| FileError::Read {
        message: format!("cannot read {}: {reason}", path.display()),
    };
    let file = std::fs::File::open(path).map_err(|reason| refuse(&reason))?;
    let metadata = file.metadata().map_err(|reason| refuse(&reason))?;
    if !metadata.is_file() {
        return Err(refuse(&"not a regular file"));
    }
    let mut bytes = Vec::new();
    file.take(MAX_FILE_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(|reason| refuse(&reason))?;
    if bytes.len() as u64 > MAX_FILE_BYTES {
        return Err(refuse(&format_args!("larger than {MAX_FILE_BYTES} bytes")));
    }
    String::from_utf8(bytes).map_err(|reason| refuse(&format_args!("not UTF-8 text: {reason}")))
}
