//! Why a call of this crate was refused: a step of the model (gms-core's error, naming the
//! sample), or an argument of the call itself.

use core::fmt;

use gms_dyn::{Details, ErrorClass, Location, Number};

/// The output slices a call writes, as its errors name them.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Output {
    /// The forces of one run, one per sample.
    Force,
    /// The Jacobian, rows × columns, row-major.
    Jacobian,
    /// The forces of several parameter sets, sets × samples, row-major.
    Forces,
}

impl Output {
    /// The name of the output, as the errors name it.
    pub const fn name(self) -> &'static str {
        match self {
            Output::Force => "force",
            Output::Jacobian => "jacobian",
            Output::Forces => "forces",
        }
    }
}

impl fmt::Display for Output {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Why a call was refused; [`Display`](fmt::Display) writes the whole message.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Error {
    /// gms-core refused a step (a bad `dt`, a non-finite input, a diverging explicit step); the
    /// error names the sample.
    Core(gms_core::Error),
    /// gms-core refused a step of one parameter set of several.
    Set {
        /// Index of the parameter set.
        set: usize,
        /// The refusal, naming the sample.
        error: gms_core::Error,
    },
    /// The rows of the Jacobian are not strictly increasing.
    RowOrder {
        /// Position in `rows` of the first row out of order.
        index: usize,
        /// That row.
        row: usize,
        /// The row before it.
        previous: usize,
    },
    /// A row of the Jacobian beyond the signal.
    RowBeyond {
        /// Position in `rows`.
        index: usize,
        /// The row.
        row: usize,
        /// Number of samples of the signal.
        samples: usize,
    },
    /// An output slice of another length than the call writes.
    OutputLength {
        /// Which output.
        output: Output,
        /// The length the call writes.
        expected: usize,
        /// The length that came.
        got: usize,
    },
}

impl Error {
    /// The kinds of this crate's own refusals (docs/errors.md#kinds); the others are gms-core's.
    pub const KINDS: [&'static str; 3] = ["not_increasing", "out_of_range", "length_mismatch"];

    /// The exception class the error belongs to, in gms-dyn's classes.
    pub fn class(&self) -> ErrorClass {
        match *self {
            Error::Core(error) | Error::Set { error, .. } => gms_dyn::Error::Core(error).class(),
            Error::RowOrder { .. } | Error::RowBeyond { .. } | Error::OutputLength { .. } => {
                ErrorClass::Input
            }
        }
    }

    /// The rule broken, in snake case: gms-core's for a refused step, else one of
    /// [`Error::KINDS`].
    pub fn kind(&self) -> &'static str {
        self.details().kind
    }

    /// The data of the error, as the bindings attach it to an exception
    /// (docs/errors.md#error-data); for [`Error::Set`], `channel` is the parameter set.
    pub fn details(&self) -> Details {
        let own = |kind: &'static str| Details {
            kind,
            field: None,
            value: None,
            bound: None,
            index: None,
            sample: None,
            channel: None,
            expected: None,
            got: None,
        };
        match *self {
            Error::Core(error) => gms_dyn::Error::Core(error).details(),
            Error::Set { set, error } => Details {
                channel: Some(set),
                ..gms_dyn::Error::Core(error).details()
            },
            Error::RowOrder {
                index,
                row,
                previous,
            } => Details {
                field: Some(Location::Element("rows", index)),
                index: Some(index),
                value: Some(Number::Count(row)),
                bound: Some(Number::Count(previous)),
                ..own(Self::KINDS[0])
            },
            Error::RowBeyond {
                index,
                row,
                samples,
            } => Details {
                field: Some(Location::Element("rows", index)),
                index: Some(index),
                value: Some(Number::Count(row)),
                bound: Some(Number::Count(samples)),
                ..own(Self::KINDS[1])
            },
            Error::OutputLength {
                output,
                expected,
                got,
            } => Details {
                field: Some(Location::Key(output.name())),
                expected: Some(expected),
                got: Some(got),
                ..own(Self::KINDS[2])
            },
        }
    }

    /// gms-core's error from a single step, located at `index`.
    pub(crate) fn at_sample(error: gms_core::Error, index: usize) -> gms_core::Error {
        match error {
            gms_core::Error::NotFinite { field, value, .. } => gms_core::Error::NotFinite {
                field,
                index,
                value,
            },
            gms_core::Error::Diverged { .. } => gms_core::Error::Diverged { index },
            other => other,
        }
    }
}

impl From<gms_core::Error> for Error {
    fn from(error: gms_core::Error) -> Self {
        Error::Core(error)
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Error::Core(error) => error.fmt(f),
            Error::Set { set, error } => write!(f, "parameter set {set}: {error}"),
            Error::RowOrder {
                index,
                row,
                previous,
            } => write!(
                f,
                "`rows` must be strictly increasing, got rows[{index}] = {row} after rows[{}] = \
                 {previous}",
                index - 1
            ),
            Error::RowBeyond {
                index,
                row,
                samples,
            } => write!(
                f,
                "`rows` must be samples of the signal, below its length {samples}, got \
                 rows[{index}] = {row}"
            ),
            Error::OutputLength {
                output,
                expected,
                got,
            } => write!(f, "`{output}` must have length {expected}, got {got}"),
        }
    }
}

impl std::error::Error for Error {}
