//! The exception classes of the package that the extension defines, and every error raised
//! from Rust as one of them with its data attached (docs/errors.md#error-data).
//!
//! Each class is made once per interpreter with `__new__(cls, message, /, *, kind=None,
//! field=None, value=None, ...)`, which stores the data as attributes of the instance, so that
//! the Python modules raise the same classes with the same data (`DataError(message,
//! kind="missing_column", field="f")`). The class attributes are the defaults (None), and
//! `__init__` is `object.__init__`, which accepts the arguments `__new__` took (the
//! `BaseException.__init__` it replaces refuses keywords). Python subclasses (`DataError`,
//! `OutputError`) inherit both and define neither, and so does `ModelFileError`, the
//! `ParameterError` of the file reader, which adds `line` and `column`.

use gms_dyn::{Details, Error, ErrorClass, Number};
use pyo3::exceptions::{PyBaseException, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::pyclass::boolean_struct::False;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyDict, PyTuple, PyType};
use pyo3::PyClass;

/// The attributes every exception of the package has, in the order of `__new__`'s keywords.
pub const DATA: [&str; 9] = [
    "kind", "field", "value", "bound", "index", "sample", "channel", "expected", "got",
];

/// The attributes `ModelFileError` adds: where in the text a syntax error is (from 1).
pub const FILE_DATA: [&str; 2] = ["line", "column"];

/// The exception classes the extension defines.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Class {
    /// `ParameterError` (a `ValueError`).
    Parameter,
    /// `InputError` (a `ValueError`).
    Input,
    /// `DivergenceError` (a `ValueError`).
    Divergence,
    /// `ConcurrentUseError` (a `RuntimeError`).
    ConcurrentUse,
    /// `ModelFileError` (a `ParameterError`): a model file or parameter file that gms-file
    /// refuses.
    ModelFile,
}

impl Class {
    /// Every class, in the order of `TYPES`.
    pub const ALL: [Class; 5] = [
        Class::Parameter,
        Class::Input,
        Class::Divergence,
        Class::ConcurrentUse,
        Class::ModelFile,
    ];

    /// The class's name in `leuven_rt`.
    pub const fn name(self) -> &'static str {
        match self {
            Class::Parameter => "ParameterError",
            Class::Input => "InputError",
            Class::Divergence => "DivergenceError",
            Class::ConcurrentUse => "ConcurrentUseError",
            Class::ModelFile => "ModelFileError",
        }
    }

    const fn qualified(self) -> &'static core::ffi::CStr {
        match self {
            Class::Parameter => c"leuven_rt.ParameterError",
            Class::Input => c"leuven_rt.InputError",
            Class::Divergence => c"leuven_rt.DivergenceError",
            Class::ConcurrentUse => c"leuven_rt.ConcurrentUseError",
            Class::ModelFile => c"leuven_rt.ModelFileError",
        }
    }

    const fn doc(self) -> &'static core::ffi::CStr {
        match self {
            Class::Parameter => {
                c"A friction-model parameter breaks its rule (docs/parameters.md#rules); `kind`, `field`, `value` (and the further data of docs/errors.md#error-data) say which and how."
            }
            Class::Input => {
                c"An input signal, step size or option is not what the function expects; `kind`, `field`, `value` (and the further data of docs/errors.md#error-data) say which and how."
            }
            Class::Divergence => {
                c"The explicit scheme blew up: the step is too large for the stiffness; `sample` is the sample whose step diverged."
            }
            Class::ConcurrentUse => {
                c"A model, mass system, compensator or online identifier was called while another thread was inside one of its calls (`run` releases the GIL): nothing was changed by this call. Give each thread its own object, or serialise the calls with a lock."
            }
            Class::ModelFile => {
                c"A model file or parameter file that the reader refuses (docs/data-and-reports.md#model-file): `kind` names what went wrong (\"not_json\", \"unknown_key\", \"static_below_coulomb\", ...), `field` the key path (\"level.ripples[0].period\") or None, `value` (and the further data of docs/errors.md#error-data) the value of a broken rule, `line` and `column` place a syntax error."
            }
        }
    }

    const fn slot(self) -> usize {
        match self {
            Class::Parameter => 0,
            Class::Input => 1,
            Class::Divergence => 2,
            Class::ConcurrentUse => 3,
            Class::ModelFile => 4,
        }
    }

    /// The class, made on first use.
    pub fn get(self, py: Python<'_>) -> PyResult<&Bound<'_, PyType>> {
        static TYPES: [PyOnceLock<Py<PyType>>; 5] = [
            PyOnceLock::new(),
            PyOnceLock::new(),
            PyOnceLock::new(),
            PyOnceLock::new(),
            PyOnceLock::new(),
        ];
        TYPES[self.slot()]
            .get_or_try_init(py, || self.make(py))
            .map(|class| class.bind(py))
    }

    fn make(self, py: Python<'_>) -> PyResult<Py<PyType>> {
        let namespace = PyDict::new(py);
        let base = match self {
            Class::ConcurrentUse => py.get_type::<PyRuntimeError>(),
            // A subclass: `__new__`, `__init__` and the data come from ParameterError.
            Class::ModelFile => Class::Parameter.get(py)?.clone(),
            _ => py.get_type::<PyValueError>(),
        };
        if self == Class::ModelFile {
            for name in FILE_DATA {
                namespace.set_item(name, py.None())?;
            }
        } else {
            namespace.set_item("__new__", wrap_pyfunction!(new_error, py)?)?;
            namespace.set_item("__init__", py.get_type::<PyAny>().getattr("__init__")?)?;
            for name in DATA {
                namespace.set_item(name, py.None())?;
            }
        }
        // `namespace` stays alive until the type is made: PyO3 0.30's `new_type` drops the
        // reference it is given before it passes the pointer on, and this one is then the last.
        PyErr::new_type(
            py,
            self.qualified(),
            Some(self.doc()),
            Some(&base),
            Some(namespace.clone().into_any().unbind()),
        )
    }
}

/// `cls(message, /, *, kind=None, field=None, value=None, bound=None, index=None, sample=None,
/// channel=None, expected=None, got=None)`: an exception with its data; the data not given
/// stay the class's None.
#[pyfunction]
#[pyo3(
    name = "__new__",
    signature = (cls, message, /, *, kind=None, field=None, value=None, bound=None, index=None, sample=None, channel=None, expected=None, got=None)
)]
#[allow(clippy::too_many_arguments)] // one keyword per datum, as Python spells the call
fn new_error<'py>(
    cls: &Bound<'py, PyType>,
    message: &Bound<'py, PyAny>,
    kind: Option<&str>,
    field: Option<&str>,
    value: Option<Bound<'py, PyAny>>,
    bound: Option<Bound<'py, PyAny>>,
    index: Option<usize>,
    sample: Option<usize>,
    channel: Option<usize>,
    expected: Option<Bound<'py, PyAny>>,
    got: Option<Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyAny>> {
    let py = cls.py();
    let error = py
        .get_type::<PyBaseException>()
        .call_method1("__new__", (cls, message))?;
    let numbers = [("index", index), ("sample", sample), ("channel", channel)];
    let objects = [
        ("value", value),
        ("bound", bound),
        ("expected", expected),
        ("got", got),
    ];
    if let Some(kind) = kind {
        error.setattr("kind", kind)?;
    }
    if let Some(field) = field {
        error.setattr("field", field)?;
    }
    for (name, number) in numbers {
        if let Some(number) = number {
            error.setattr(name, number)?;
        }
    }
    for (name, object) in objects {
        if let Some(object) = object.filter(|object| !object.is_none()) {
            error.setattr(name, object)?;
        }
    }
    Ok(error)
}

/// The kinds of this layer's own refusals: its checks of the Python arguments before they reach
/// gms-dyn.
#[derive(Clone, Copy, Debug, PartialEq, Eq, strum::IntoStaticStr, strum::VariantNames)]
#[strum(serialize_all = "snake_case")]
pub enum Kind {
    /// Not a real number (a bool, text, another object), or not a sequence of them.
    NotReal,
    /// A number outside its range (`channels` < 1).
    OutOfRange,
    /// The output or the states do not fit in memory.
    OutOfMemory,
    /// An input of other than the object's number of channels, or a one-channel call on several.
    ChannelMismatch,
    /// A name that is not one of the choices (`scheme`, `mode`).
    InvalidChoice,
    /// Arrays of other shapes than the object's (a state to restore).
    Shape,
    /// A sequence of another length than its rule asks (a level's `trend`).
    WrongLength,
    /// The object is in use by another thread.
    ConcurrentUse,
}

/// Every kind the extension raises: gms-core's, gms-dyn's, gms-fit's, gms-file's and this
/// layer's own.
pub fn kinds() -> Vec<&'static str> {
    use strum::VariantNames;
    let mut kinds: Vec<&'static str> = Error::kinds()
        .chain(gms_fit::Error::KINDS)
        .chain(gms_file::FileError::KINDS)
        .chain(Kind::VARIANTS.iter().copied())
        .collect();
    kinds.sort_unstable();
    kinds.dedup();
    kinds
}

/// A datum of a refusal: a Python object (the value that came), a number, or a count.
pub enum Datum {
    /// The object that came.
    Object(Py<PyAny>),
    /// A real number or a count.
    Number(Number),
    /// A signed integer.
    Integer(i64),
}

impl From<i64> for Datum {
    fn from(integer: i64) -> Self {
        Datum::Integer(integer)
    }
}

impl From<Number> for Datum {
    fn from(number: Number) -> Self {
        Datum::Number(number)
    }
}

impl From<usize> for Datum {
    fn from(count: usize) -> Self {
        Datum::Number(Number::Count(count))
    }
}

impl From<f64> for Datum {
    fn from(value: f64) -> Self {
        Datum::Number(Number::Real(value))
    }
}

impl From<&Bound<'_, PyAny>> for Datum {
    fn from(object: &Bound<'_, PyAny>) -> Self {
        Datum::Object(object.clone().unbind())
    }
}

impl Datum {
    fn to_python(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        Ok(match self {
            Datum::Object(object) => object.clone_ref(py),
            Datum::Number(Number::Real(value)) => value.into_pyobject(py)?.into_any().unbind(),
            Datum::Number(Number::Count(count)) => count.into_pyobject(py)?.into_any().unbind(),
            Datum::Integer(integer) => integer.into_pyobject(py)?.into_any().unbind(),
        })
    }
}

/// An exception of one of the extension's classes with its message and data, raised as a
/// `PyErr` (`Refusal::new(...).field("dt").value(dt).into()`).
pub struct Refusal {
    class: Class,
    message: String,
    kind: &'static str,
    field: Option<String>,
    data: Vec<(&'static str, Datum)>,
}

impl Refusal {
    /// A refusal of this layer's own.
    pub fn new(class: Class, kind: Kind, message: impl Into<String>) -> Self {
        Self::with_kind(class, kind.into(), message)
    }

    /// A refusal of `kind` named by another layer (gms-file's).
    pub fn with_kind(class: Class, kind: &'static str, message: impl Into<String>) -> Self {
        Refusal {
            class,
            message: message.into(),
            kind,
            field: None,
            data: Vec::new(),
        }
    }

    /// The parameter, argument or state member at fault.
    pub fn field(mut self, field: impl Into<String>) -> Self {
        self.field = Some(field.into());
        self
    }

    /// The value that came.
    pub fn value(self, value: impl Into<Datum>) -> Self {
        self.datum("value", value.into())
    }

    /// The limit the value had to reach.
    pub fn bound(self, bound: impl Into<Datum>) -> Self {
        self.datum("bound", bound.into())
    }

    /// The index of the element or entry at fault, the last index that `field` spells.
    pub fn index(self, index: usize) -> Self {
        self.datum("index", index.into())
    }

    /// The length, count or shape expected, and what came.
    pub fn lengths(self, expected: impl Into<Datum>, got: impl Into<Datum>) -> Self {
        self.datum("expected", expected.into())
            .datum("got", got.into())
    }

    fn datum(mut self, name: &'static str, datum: Datum) -> Self {
        self.data.push((name, datum));
        self
    }

    fn build(&self, py: Python<'_>) -> PyResult<PyErr> {
        let data = PyDict::new(py);
        data.set_item("kind", self.kind)?;
        if let Some(field) = &self.field {
            data.set_item("field", field)?;
        }
        for (name, datum) in &self.data {
            data.set_item(*name, datum.to_python(py)?)?;
        }
        let arguments = PyTuple::new(py, [self.message.as_str()])?;
        let error = self.class.get(py)?.call(arguments, Some(&data))?;
        Ok(PyErr::from_value(error))
    }
}

impl From<Refusal> for PyErr {
    fn from(refusal: Refusal) -> PyErr {
        Python::attach(|py| refusal.build(py).unwrap_or_else(|failure| failure))
    }
}

/// gms-dyn's error as an exception of `class`, with `message` and the error's data.
pub fn raise_as(class: Class, error: Error, message: String) -> PyErr {
    raise_details(class, error.details(), message)
}

/// An exception of `class` with `message` and the data `details`.
fn raise_details(class: Class, details: Details, message: String) -> PyErr {
    refusal_of(class, details, message).into()
}

/// A refusal of `class` with `message` and the data `details`, to complete before it is raised.
pub fn refusal_of(class: Class, details: Details, message: String) -> Refusal {
    let mut refusal = Refusal::with_kind(class, details.kind, message);
    refusal.field = details.field.map(|field| field.to_string());
    let Details {
        value,
        bound,
        index,
        sample,
        channel,
        expected,
        got,
        ..
    } = details;
    for (name, number) in [("value", value), ("bound", bound)] {
        if let Some(number) = number {
            refusal = refusal.datum(name, number.into());
        }
    }
    for (name, count) in [
        ("index", index),
        ("sample", sample),
        ("channel", channel),
        ("expected", expected),
        ("got", got),
    ] {
        if let Some(count) = count {
            refusal = refusal.datum(name, count.into());
        }
    }
    refusal
}

/// The extension's class for one of gms-dyn's.
fn class_of(class: ErrorClass) -> Class {
    match class {
        ErrorClass::Parameter => Class::Parameter,
        ErrorClass::Input => Class::Input,
        ErrorClass::Divergence => Class::Divergence,
    }
}

/// The exception of the class the error's kind calls for, with gms-dyn's message and data.
pub fn raise(error: Error) -> PyErr {
    raise_as(class_of(error.class()), error, error.to_string())
}

/// A gms-fit error, with its message and data, in the class its kind calls for.
pub fn raise_fit(error: gms_fit::Error) -> PyErr {
    raise_details(class_of(error.class()), error.details(), error.to_string())
}

/// A refused update, run or prediction of an online identifier, or refused slip responses:
/// always an `InputError`, whatever the rule.
pub fn input_error(error: Error) -> PyErr {
    raise_as(Class::Input, error, error.to_string())
}

/// The `ConcurrentUseError` for `owner`, called while another thread is inside one of its calls.
fn busy(owner: &Bound<'_, PyAny>) -> PyErr {
    let name = owner
        .get_type()
        .name()
        .map_or_else(|_| "object".to_owned(), |name| name.to_string());
    Refusal::new(
        Class::ConcurrentUse,
        Kind::ConcurrentUse,
        format!(
            "this {name} is in use by another thread (inside a call that releases the GIL, such \
             as `run`): nothing was changed; give each thread its own object or serialise the \
             calls"
        ),
    )
    .into()
}

/// `object` lent for a call that changes it, or `ConcurrentUseError` while another thread is
/// inside one of its calls (`PyO3`'s own refusal is a bare `RuntimeError`).
pub fn lend_mut<'py, T: PyClass<Frozen = False>>(
    object: &Bound<'py, T>,
) -> PyResult<PyRefMut<'py, T>> {
    object.try_borrow_mut().map_err(|_| busy(object.as_any()))
}

/// `object` lent for a call that reads it, or `ConcurrentUseError` while another thread is
/// inside a call that changes it.
pub fn lend<'py, T: PyClass>(object: &Bound<'py, T>) -> PyResult<PyRef<'py, T>> {
    object.try_borrow().map_err(|_| busy(object.as_any()))
}
