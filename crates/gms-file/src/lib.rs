//! # gms-file: the model file and the parameter file of leuven-rt
//!
//! One reader and one writer of the files that hold a friction model, used by the Python
//! package (through gms-py) and the C library (gms-ffi) alike, so that both accept and refuse
//! exactly the same texts. The specification is `docs/data-and-reports.md#model-file`; what it
//! does not allow is refused.
//!
//! - A **model file** is a JSON object with `"format": "leuven-rt model"` and a `version` (this
//!   crate writes [`VERSION`] 3 and reads 1 to 3; a later one is refused with "upgrade
//!   leuven-rt"): `units`, `friction`, `level`, `position_force`, `measurement`,
//!   `reconstruction` and `report`.
//! - A **parameter file** is the `friction` object alone (docs/parameters.md#keys); it reads as
//!   a model file whose other keys take their defaults.
//!
//! Reading is strict: a key given twice (anywhere, the report included), an unknown key, a
//! missing required key, a value of the wrong type, a number beyond the f64 range and text that
//! is not JSON (`NaN` and `Infinity` are not) are refused with a [`FileError`] that names the key
//! path (`level.ripples[0].period`, `friction.W[2]`), or the line and column of a syntax error.
//!
//! Reading gives plain values ([`ModelFile`]); [`ModelFile::validate`] then has each value
//! checked by the layer that owns its rule (the friction by gms-dyn's
//! [`RawParams::validate`](gms_dyn::RawParams::validate), the level by gms-core's
//! [`Level::new`](gms_core::Level::new)) and returns the validated objects, a refusal still
//! naming the key.
//!
//! ```
//! use gms_file::ModelFile;
//!
//! let text = r#"{"format": "leuven-rt model", "version": 3, "units": "linear",
//!     "friction": {"Fc": 1.0, "Fs": 1.5, "Vs": 0.001, "delta": 2.0, "n": 2.0, "sigma0": 1e5}}"#;
//! let file = ModelFile::from_json(text)?;
//! let model = file.validate()?; // a gms-dyn ParameterSet and a gms-core Level
//! assert_eq!(model.params.elements(), 0);
//! assert_eq!(ModelFile::from_json(&file.to_json()?)?, file);
//!
//! let refused = ModelFile::from_json(&text.replace("\"n\"", "\"N\"")).unwrap_err();
//! assert_eq!(refused.key(), Some("friction.N"));
//! # Ok::<(), gms_file::FileError>(())
//! ```

#![forbid(unsafe_code)]

mod error;
mod file;
mod read;
mod validate;

use std::path::Path;

use serde_json::Value;

pub use error::{ErrorKind, FileError, Problem};
pub use file::{
    Friction, Measurement, ModelFile, PositionTerms, Reconstruction, Report, Ripple, Source, Units,
};
pub use validate::Model;

// The workspace README's Rust snippets run as doctests of this crate, so the README cannot drift
// from the API: its snippet reads a model file (this crate) into a compensator (gms-dyn, gms-core).
#[cfg(doctest)]
#[doc = include_str!("../../../README.md")]
struct ReadmeSnippets;

/// The value of `format` that marks a model file.
pub const FORMAT: &str = "leuven-rt model";

/// The version this crate writes, and the latest it reads (it reads every version from 1).
pub const VERSION: u64 = 3;

/// The largest file [`ModelFile::load`] reads: far above any real model file, small enough that
/// a path to a device or a huge file cannot exhaust memory.
pub const MAX_FILE_BYTES: u64 = 1 << 20;

impl ModelFile {
    /// Reads the text of a model file (version 1 to 3) or of a parameter file.
    pub fn from_json(text: &str) -> Result<Self, FileError> {
        read::model_from_value(read::parse(text)?)
    }

    /// As [`ModelFile::from_json`], for bytes that must be UTF-8 text.
    pub fn from_slice(bytes: &[u8]) -> Result<Self, FileError> {
        let text = core::str::from_utf8(bytes).map_err(|reason| FileError::Read {
            message: format!("the text is not UTF-8: {reason}"),
        })?;
        Self::from_json(text)
    }

    /// Reads a JSON value that a binding built from its own objects (a Python dict), with the
    /// same rules as the text; a value has no duplicate keys and no non-finite numbers.
    pub fn from_value(value: Value) -> Result<Self, FileError> {
        read::model_from_value(value)
    }

    /// Reads the model file or parameter file at `path`: a regular file of at most
    /// [`MAX_FILE_BYTES`], UTF-8 text.
    pub fn load(path: impl AsRef<Path>) -> Result<Self, FileError> {
        Self::from_json(&read::read_text(path.as_ref())?)
    }

    /// The text of the file, in the current [`VERSION`] (indented JSON, keys in the documented
    /// order, no final newline). The file is validated first, so that nothing is written that
    /// the reader would refuse.
    ///
    /// # Panics
    /// Never: structs of finite numbers, strings and string-keyed maps always serialize.
    pub fn to_json(&self) -> Result<String, FileError> {
        self.validate()?;
        Ok(read::model_to_string(self))
    }

    /// The JSON value of [`ModelFile::to_json`]'s text.
    ///
    /// # Panics
    /// Never: structs of finite numbers, strings and string-keyed maps always serialize.
    pub fn to_value(&self) -> Result<Value, FileError> {
        self.validate()?;
        Ok(read::model_to_value(self))
    }
}

impl Friction {
    /// Reads the text of a parameter file: the friction object alone, no other key.
    pub fn from_json(text: &str) -> Result<Self, FileError> {
        read::friction_from_value(read::parse(text)?)
    }

    /// Reads a parameter file's JSON value (see [`ModelFile::from_value`]).
    pub fn from_value(value: Value) -> Result<Self, FileError> {
        read::friction_from_value(value)
    }

    /// The text of the parameter file (indented JSON, unset optional keys left out, no final
    /// newline), validated first.
    ///
    /// # Panics
    /// Never: structs of finite numbers, strings and string-keyed maps always serialize.
    pub fn to_json(&self) -> Result<String, FileError> {
        self.validate()?;
        Ok(serde_json::to_string_pretty(self)
            .expect("structs of numbers and lists of numbers always serialize"))
    }

    /// The JSON value of [`Friction::to_json`]'s text.
    ///
    /// # Panics
    /// Never: structs of finite numbers, strings and string-keyed maps always serialize.
    pub fn to_value(&self) -> Result<Value, FileError> {
        self.validate()?;
        Ok(serde_json::to_value(self)
            .expect("structs of numbers and lists of numbers always serialize"))
    }
}
