//! The Python exception classes, and gms-dyn errors sorted into them.

use gms_dyn::{Error, ErrorKind};
use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::PyErr;

create_exception!(
    leuven_rt,
    ParameterError,
    PyValueError,
    "A friction-model parameter breaks its rule (docs/parameters.md#rules)."
);
create_exception!(
    leuven_rt,
    InputError,
    PyValueError,
    "An input signal, step size or option is not what the function expects."
);
create_exception!(
    leuven_rt,
    DivergenceError,
    PyValueError,
    "The explicit scheme blew up: the step is too large for the stiffness."
);

/// The exception of the class the error's kind calls for, with gms-dyn's message.
pub fn raise(error: Error) -> PyErr {
    of_kind(error.kind(), error.to_string())
}

/// A gms-fit error, sorted into the same classes by the same kinds.
pub fn raise_fit(error: gms_fit::Error) -> PyErr {
    of_kind(error.kind(), error.to_string())
}

fn of_kind(kind: ErrorKind, message: String) -> PyErr {
    match kind {
        ErrorKind::Parameter => ParameterError::new_err(message),
        ErrorKind::Input => InputError::new_err(message),
        ErrorKind::Divergence => DivergenceError::new_err(message),
    }
}
