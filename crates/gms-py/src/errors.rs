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
    ModelFileError,
    ParameterError,
    "A model file or parameter file that the reader refuses (docs/data-and-reports.md#model-file): \
     `kind` names what went wrong (\"not_json\", \"unknown_key\", \"static_below_coulomb\", ...), \
     `field` the key path (\"level.ripples[0].period\") or None, `line` and `column` place a \
     syntax error."
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
    let message = error.to_string();
    match error.kind() {
        ErrorKind::Parameter => ParameterError::new_err(message),
        ErrorKind::Input => InputError::new_err(message),
        ErrorKind::Divergence => DivergenceError::new_err(message),
    }
}
