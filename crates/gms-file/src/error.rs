//! Why a file was refused: one error type for every reader and binding, naming the key path.

use core::fmt;

use crate::{FORMAT, VERSION};

/// What a [`FileError`] is about, for the bindings that sort errors (Python's `kind`, C's
/// status).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ErrorKind {
    /// The file could not be read (missing, not a regular file, too large, not UTF-8).
    Read,
    /// The text is not JSON.
    Syntax,
    /// The text is JSON, but `format` or `version` is not one this reader reads.
    Format,
    /// A key is unknown, missing or given twice, a value has the wrong type or is out of the
    /// f64 range, or the text is not an object.
    Shape,
    /// A value breaks a rule (of the model, checked by gms-core, or of the file).
    Value,
}

impl ErrorKind {
    /// The name the bindings show: `"read"`, `"syntax"`, `"format"`, `"shape"` or `"value"`.
    pub const fn name(self) -> &'static str {
        match self {
            ErrorKind::Read => "read",
            ErrorKind::Syntax => "syntax",
            ErrorKind::Format => "format",
            ErrorKind::Shape => "shape",
            ErrorKind::Value => "value",
        }
    }
}

/// What is wrong with a key or its value, for [`FileError::Shape`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Problem {
    /// A key the format does not have there.
    UnknownKey,
    /// A required key is missing.
    MissingKey,
    /// A key is given twice in the same object.
    Repeated,
    /// A value of the wrong type (a string for a number, `null` where null is not allowed, an
    /// array for an object, a string that is not one of the choices).
    WrongType,
    /// An array of the wrong length (`trend`).
    WrongLength,
    /// A number beyond the f64 range, or (from a binding's object) not finite.
    OutOfRange,
}

impl Problem {
    /// The name of the problem, as the bindings give it (`"unknown_key"`, `"missing_key"`,
    /// `"repeated"`, `"wrong_type"`, `"wrong_length"`, `"out_of_range"`).
    pub const fn name(self) -> &'static str {
        match self {
            Problem::UnknownKey => "unknown_key",
            Problem::MissingKey => "missing_key",
            Problem::Repeated => "repeated",
            Problem::WrongType => "wrong_type",
            Problem::WrongLength => "wrong_length",
            Problem::OutOfRange => "out_of_range",
        }
    }
}

/// Why a model file or a parameter file was refused; [`Display`](fmt::Display) writes the whole
/// message, with the key path (`level.ripples[0].period`, `friction.W[2]`) where there is one.
#[derive(Clone, Debug, PartialEq)]
pub enum FileError {
    /// The file could not be read.
    Read {
        /// The path and the reason.
        message: String,
    },
    /// The text is not JSON (NaN and Infinity are not JSON either).
    Syntax {
        /// Line of the error, from 1.
        line: usize,
        /// Column of the error, from 1.
        column: usize,
        /// What the parser expected or found.
        message: String,
    },
    /// The text is JSON, but not an object.
    NotAnObject {
        /// What came, in JSON's words (`a sequence`, `a string`, ...).
        got: String,
    },
    /// `format` is not `"leuven-rt model"`.
    Format {
        /// The value that came, as JSON.
        got: String,
    },
    /// `version` is missing, or not a whole number from 1 to [`VERSION`].
    Version {
        /// The value that came, as JSON (`None` when the key is missing).
        got: Option<String>,
    },
    /// `version` is later than this reader's [`VERSION`]: the file was written by a newer
    /// leuven-rt.
    Newer {
        /// The version that came.
        version: u64,
    },
    /// A key is unknown, missing or given twice, or its value has the wrong type or is out of
    /// the f64 range.
    Shape {
        /// The key path.
        key: String,
        /// What is wrong.
        problem: Problem,
        /// What is wrong, in words, with the line and column when the input was text.
        message: String,
    },
    /// A value breaks a rule of the model (gms-core's, through gms-dyn).
    Rule {
        /// The key path of the value.
        key: String,
        /// The rule broken, with the value.
        error: gms_dyn::Error,
    },
    /// A value breaks a rule of the file (a measurement term, a reconstruction cutoff, a
    /// ripple's harmonics).
    Invalid {
        /// The key path of the value.
        key: String,
        /// The rule, named as gms-core names its own (`"not_finite_value"`, `"not_positive"`,
        /// `"harmonic_lengths"`).
        rule: &'static str,
        /// The rule and the value.
        message: String,
    },
}

impl FileError {
    /// Every name [`FileError::kind_name`] gives: the bindings list them beside gms-core's and
    /// gms-dyn's kinds, which a [`FileError::Rule`] has (Python's `_core.ERROR_KINDS`).
    pub const KINDS: [&'static str; 12] = [
        "unreadable_file",
        "not_json",
        "wrong_type",
        "invalid_choice",
        "missing_key",
        "unknown_key",
        "repeated",
        "wrong_length",
        "out_of_range",
        "harmonic_lengths",
        "not_finite_value",
        "not_positive",
    ];

    /// What the error is about.
    pub fn kind(&self) -> ErrorKind {
        match self {
            FileError::Read { .. } => ErrorKind::Read,
            FileError::Syntax { .. } => ErrorKind::Syntax,
            FileError::Format { .. } | FileError::Version { .. } | FileError::Newer { .. } => {
                ErrorKind::Format
            }
            FileError::NotAnObject { .. } | FileError::Shape { .. } => ErrorKind::Shape,
            FileError::Rule { .. } | FileError::Invalid { .. } => ErrorKind::Value,
        }
    }

    /// The name of what went wrong, as the bindings give it: `"unreadable_file"`, `"not_json"`,
    /// `"wrong_type"` (not an object), `"invalid_choice"` (`format`, `version`), `"missing_key"`
    /// (`version`), a [`Problem::name`], or the rule of [`FileError::Invalid`]: one of
    /// [`FileError::KINDS`]. `None` for [`FileError::Rule`], whose gms-dyn error names its own
    /// rule (`gms_dyn::Error::kind`).
    pub fn kind_name(&self) -> Option<&'static str> {
        Some(match self {
            FileError::Read { .. } => "unreadable_file",
            FileError::Syntax { .. } => "not_json",
            FileError::NotAnObject { .. } => "wrong_type",
            FileError::Format { .. }
            | FileError::Newer { .. }
            | FileError::Version { got: Some(_) } => "invalid_choice",
            FileError::Version { got: None } => "missing_key",
            FileError::Shape { problem, .. } => problem.name(),
            FileError::Invalid { rule, .. } => rule,
            FileError::Rule { .. } => return None,
        })
    }

    /// The key path the error is about (`friction.W[2]`), if it is about one.
    pub fn key(&self) -> Option<&str> {
        match self {
            FileError::Format { .. } => Some("format"),
            FileError::Version { .. } | FileError::Newer { .. } => Some("version"),
            FileError::Shape { key, .. }
            | FileError::Rule { key, .. }
            | FileError::Invalid { key, .. } => (!key.is_empty()).then_some(key.as_str()),
            FileError::Read { .. } | FileError::Syntax { .. } | FileError::NotAnObject { .. } => {
                None
            }
        }
    }

    /// The same error with its key path under `parent` (`W[2]` under `friction` is
    /// `friction.W[2]`).
    #[must_use]
    pub fn under(self, parent: &str) -> Self {
        let join = |key: String| {
            if key.is_empty() {
                parent.to_owned()
            } else if key.starts_with('[') {
                format!("{parent}{key}")
            } else {
                format!("{parent}.{key}")
            }
        };
        match self {
            FileError::Shape {
                key,
                problem,
                message,
            } => FileError::Shape {
                key: join(key),
                problem,
                message,
            },
            FileError::Rule { key, error } => FileError::Rule {
                key: join(key),
                error,
            },
            FileError::Invalid { key, rule, message } => FileError::Invalid {
                key: join(key),
                rule,
                message,
            },
            other => other,
        }
    }

    /// The rule of the model broken, for [`FileError::Rule`].
    pub fn rule(&self) -> Option<gms_dyn::Error> {
        match self {
            FileError::Rule { error, .. } => Some(*error),
            _ => None,
        }
    }

    /// Line and column of a syntax error.
    pub fn position(&self) -> Option<(usize, usize)> {
        match self {
            FileError::Syntax { line, column, .. } => Some((*line, *column)),
            _ => None,
        }
    }
}

impl fmt::Display for FileError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FileError::Read { message } => f.write_str(message),
            FileError::Syntax {
                line,
                column,
                message,
            } => write!(f, "not JSON: {message} at line {line}, column {column}"),
            FileError::NotAnObject { got } => write!(
                f,
                "a model file or parameter file must be a JSON object, got {got}"
            ),
            FileError::Format { got } => write!(f, "`format` must be {FORMAT:?}, got {got}"),
            FileError::Version { got: None } => write!(
                f,
                "`version` is missing: a model file must give its version (1 to {VERSION})"
            ),
            FileError::Version { got: Some(got) } => write!(
                f,
                "`version` must be a whole number from 1 to {VERSION}, got {got}"
            ),
            FileError::Newer { version } => write!(
                f,
                "`version` is {version}: the file was written by a newer leuven-rt, and this one \
                 reads versions 1 to {VERSION}; upgrade leuven-rt to read it"
            ),
            FileError::Shape { key, message, .. } | FileError::Invalid { key, message, .. }
                if key.is_empty() =>
            {
                f.write_str(message)
            }
            FileError::Rule { key, error } if key.is_empty() => write!(f, "{error}"),
            FileError::Shape { key, message, .. } | FileError::Invalid { key, message, .. } => {
                write!(f, "`{key}`: {message}")
            }
            FileError::Rule { key, error } => write!(f, "`{key}`: {error}"),
        }
    }
}

impl std::error::Error for FileError {}
