//! The model file and the parameter file, read and written by gms-file (the reader the C library
//! uses too): text, a path or a Python object in, the validated file's plain values out as a
//! Python dict, and back. A refusal raises `ModelFileError` with the key path.

use std::path::PathBuf;

use gms_file::{FileError, Friction, ModelFile, Problem};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyMapping, PyString, PyTuple};
use serde_json::{Map, Number, Value};

use crate::errors::{refusal_of, Class, Refusal};

/// The Python exception of a refused file: `ModelFileError` with the data of
/// docs/errors.md: `kind` (what went wrong: gms-file's name for it, or the kind of the rule of
/// the model that a value breaks, with that rule's `value`, `bound` and `index`), `field` (the
/// key path, or None), and for a syntax error `line` and `column`.
fn raise(py: Python<'_>, error: &FileError, message: String) -> PyErr {
    let refusal = match error.rule() {
        // The rule's own field is replaced by the key path below.
        Some(rule) => refusal_of(
            Class::ModelFile,
            gms_dyn::Details {
                field: None,
                ..rule.details()
            },
            message,
        ),
        // gms-file names every refusal but a rule's (whose kind is the rule's, above).
        None => Refusal::with_kind(
            Class::ModelFile,
            error.kind_name().unwrap_or(error.kind().name()),
            message,
        ),
    };
    let refusal = match error.key() {
        Some(key) => refusal.field(key),
        None => refusal,
    };
    let exception = PyErr::from(refusal);
    let Some((line, column)) = error.position() else {
        return exception;
    };
    let value = exception.value(py);
    match value
        .setattr("line", line)
        .and_then(|()| value.setattr("column", column))
    {
        Ok(()) => exception,
        Err(failed) => failed,
    }
}

fn refused(py: Python<'_>, error: &FileError) -> PyErr {
    raise(py, error, error.to_string())
}

/// `value` as a Python object: dicts (in the file's key order), lists, floats, ints, str, bool,
/// None.
fn to_python<'py>(py: Python<'py>, value: &Value) -> PyResult<Bound<'py, PyAny>> {
    Ok(match value {
        Value::Null => py.None().into_bound(py),
        Value::Bool(flag) => PyBool::new(py, *flag).to_owned().into_any(),
        Value::Number(number) => {
            if let Some(whole) = number.as_i64() {
                whole.into_pyobject(py)?.into_any()
            } else if let Some(whole) = number.as_u64() {
                whole.into_pyobject(py)?.into_any()
            } else if let Some(real) = number.as_f64() {
                PyFloat::new(py, real).into_any()
            } else {
                return Err(PyTypeError::new_err(format!(
                    "a JSON number that is no double: {number}"
                )));
            }
        }
        Value::String(text) => PyString::new(py, text).into_any(),
        Value::Array(items) => {
            let list = PyList::empty(py);
            for item in items {
                list.append(to_python(py, item)?)?;
            }
            list.into_any()
        }
        Value::Object(object) => {
            let dict = PyDict::new(py);
            for (key, item) in object {
                dict.set_item(key, to_python(py, item)?)?;
            }
            dict.into_any()
        }
    })
}

/// The key path of an item of `parent`.
fn item_path(parent: &str, key: &str) -> String {
    if parent.is_empty() {
        key.to_owned()
    } else {
        format!("{parent}.{key}")
    }
}

/// A Python int as a JSON number, as JSON text would read it: exactly within i64 or u64, else
/// the nearest double, else out of range.
fn whole_number(object: &Bound<'_, PyAny>, path: &str) -> Result<Value, FileError> {
    if let Ok(whole) = object.extract::<i64>() {
        return Ok(Value::Number(whole.into()));
    }
    if let Ok(whole) = object.extract::<u64>() {
        return Ok(Value::Number(whole.into()));
    }
    object
        .extract::<f64>()
        .ok()
        .and_then(Number::from_f64)
        .map(Value::Number)
        .ok_or_else(|| {
            // str() of a long integer may itself be refused (Python's digit limit).
            let bits = object
                .call_method0("bit_length")
                .and_then(|bits| bits.extract::<u64>())
                .unwrap_or(0);
            FileError::Shape {
                key: path.to_owned(),
                problem: Problem::OutOfRange,
                message: format!(
                    "number out of range: an integer of {bits} bits is beyond the f64 range"
                ),
            }
        })
}

/// A Python object as a JSON value, refusing what JSON cannot hold (a non-finite float, an
/// integer beyond the f64 range, a key that is not text, an object of another type), naming the
/// key path. numpy arrays and scalars are taken through their `tolist()`.
fn to_value(object: &Bound<'_, PyAny>, path: &str) -> Result<Value, FileError> {
    let shape = |problem: Problem, message: String| FileError::Shape {
        key: path.to_owned(),
        problem,
        message,
    };
    if object.is_none() {
        return Ok(Value::Null);
    }
    if let Ok(flag) = object.cast::<PyBool>() {
        return Ok(Value::Bool(flag.is_true()));
    }
    if object.is_instance_of::<PyInt>() {
        return whole_number(object, path);
    }
    if let Ok(number) = object.cast::<PyFloat>() {
        let value = number.value();
        return Number::from_f64(value).map(Value::Number).ok_or_else(|| {
            shape(
                Problem::OutOfRange,
                format!(
                    "must be a finite number (JSON has no spelling for {})",
                    gms_core::Shown(value)
                ),
            )
        });
    }
    if let Ok(text) = object.cast::<PyString>() {
        return Ok(Value::String(text.to_string()));
    }
    if let Ok(dict) = object.cast::<PyDict>() {
        let mut map = Map::new();
        for (key, item) in dict.iter() {
            let Ok(key) = key.cast::<PyString>() else {
                let shown = key.repr().map(|text| text.to_string()).unwrap_or_default();
                return Err(shape(
                    Problem::WrongType,
                    format!("keys must be text, got {shown}"),
                ));
            };
            let key = key.to_string();
            let value = to_value(&item, &item_path(path, &key))?;
            map.insert(key, value);
        }
        return Ok(Value::Object(map));
    }
    let items = |sequence: Vec<Bound<'_, PyAny>>| {
        sequence
            .iter()
            .enumerate()
            .map(|(index, item)| to_value(item, &format!("{path}[{index}]")))
            .collect::<Result<Vec<_>, _>>()
            .map(Value::Array)
    };
    if let Ok(list) = object.cast::<PyList>() {
        return items(list.iter().collect());
    }
    if let Ok(tuple) = object.cast::<PyTuple>() {
        return items(tuple.iter().collect());
    }
    if let Ok(mapping) = object.cast::<PyMapping>() {
        // Another mapping (a MappingProxyType, ...): read as a dict.
        let dict = PyDict::new(object.py());
        dict.update(mapping).map_err(|error| {
            shape(
                Problem::WrongType,
                format!("cannot be read as a mapping: {error}"),
            )
        })?;
        return to_value(dict.as_any(), path);
    }
    // numpy arrays and scalars: their Python values.
    if let Ok(plain) = object.call_method0("tolist") {
        if !plain.is(object) {
            return to_value(&plain, path);
        }
    }
    let type_name = object
        .get_type()
        .name()
        .map(|name| name.to_string())
        .unwrap_or_default();
    Err(shape(
        Problem::WrongType,
        format!("must be a JSON value (dict, list, str, number, bool or None), got {type_name}"),
    ))
}

/// The validated model file's plain values, as a dict in the current version.
fn model_dict<'py>(py: Python<'py>, file: &ModelFile) -> PyResult<Bound<'py, PyAny>> {
    let value = file.to_value().map_err(|error| refused(py, &error))?;
    to_python(py, &value)
}

/// Reads the text of a model file (version 1 to 3) or of a parameter file and returns its
/// validated plain values as a dict of the current version; raises `ModelFileError`.
#[pyfunction]
pub fn model_file_from_json<'py>(py: Python<'py>, text: &str) -> PyResult<Bound<'py, PyAny>> {
    let file = ModelFile::from_json(text).map_err(|error| refused(py, &error))?;
    model_dict(py, &file)
}

/// As `model_file_from_json`, for a Python object (a dict of JSON values).
#[pyfunction]
pub fn model_file_from_object<'py>(
    py: Python<'py>,
    object: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyAny>> {
    let file = to_value(object, "")
        .and_then(ModelFile::from_value)
        .map_err(|error| refused(py, &error))?;
    model_dict(py, &file)
}

/// As `model_file_from_json`, for the file at `path` (a regular file of at most 1 MiB, UTF-8);
/// a refusal of its content names the file.
#[pyfunction]
pub fn model_file_load(py: Python<'_>, path: PathBuf) -> PyResult<Bound<'_, PyAny>> {
    let file = ModelFile::load(&path).map_err(|error| match error.kind() {
        gms_file::ErrorKind::Read => refused(py, &error),
        _ => raise(py, &error, format!("{}: {error}", path.display())),
    })?;
    model_dict(py, &file)
}

/// The text of the model file whose plain values `object` holds (a dict as `model_file_from_json`
/// returns it), in the current version; raises `ModelFileError` for what the reader would refuse.
#[pyfunction]
pub fn model_file_to_json(py: Python<'_>, object: &Bound<'_, PyAny>) -> PyResult<String> {
    to_value(object, "")
        .and_then(ModelFile::from_value)
        .and_then(|file| file.to_json())
        .map_err(|error| refused(py, &error))
}

/// Reads the text of a parameter file (the friction object alone) and returns its validated
/// plain values as a dict; raises `ModelFileError`.
#[pyfunction]
pub fn parameter_file_from_json<'py>(py: Python<'py>, text: &str) -> PyResult<Bound<'py, PyAny>> {
    let value = Friction::from_json(text)
        .and_then(|friction| friction.to_value())
        .map_err(|error| refused(py, &error))?;
    to_python(py, &value)
}

/// The text of the parameter file whose values `object` holds (a dict of its keys); raises
/// `ModelFileError` for what the reader would refuse.
#[pyfunction]
pub fn parameter_file_to_json(py: Python<'_>, object: &Bound<'_, PyAny>) -> PyResult<String> {
    to_value(object, "")
        .and_then(Friction::from_value)
        .and_then(|friction| friction.to_json())
        .map_err(|error| refused(py, &error))
}
