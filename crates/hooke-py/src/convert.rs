//! Values between Rust and Python: JSON-shaped reports as dicts (their
//! records, for the lab, as columns of numpy arrays), and numpy arrays of
//! vectors, numbers and indices read with their shapes checked.

use hooke_core::Vec3;
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1, PyArrayDyn, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::IntoPyObjectExt;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use serde_json::Value;

/// `value` as Python: objects as dicts, arrays as lists, numbers as
/// `int` or `float`, `null` as `None` — what `json.load` gives for the
/// same text.
pub(crate) fn plain(py: Python<'_>, value: &Value) -> PyResult<Py<PyAny>> {
    Ok(match value {
        Value::Null => py.None(),
        Value::Bool(b) => b.into_py_any(py)?,
        Value::Number(n) => match (n.as_i64(), n.as_u64()) {
            (Some(i), _) => i.into_py_any(py)?,
            (None, Some(u)) => u.into_py_any(py)?,
            (None, None) => n.as_f64().unwrap_or(f64::NAN).into_py_any(py)?,
        },
        Value::String(s) => s.into_py_any(py)?,
        Value::Array(items) => {
            let list = PyList::empty(py);
            for item in items {
                list.append(plain(py, item)?)?;
            }
            list.into_any().unbind()
        }
        Value::Object(map) => {
            let dict = PyDict::new(py);
            for (key, item) in map {
                dict.set_item(key, plain(py, item)?)?;
            }
            dict.into_any().unbind()
        }
    })
}

/// `value` as Python for numpy and matplotlib: as [`plain`], but a list of
/// whole numbers becomes an int64 array, of numbers (and `null`s, as NaN)
/// a float64 array, a list of
/// records with the same keys becomes a dict of columns, each converted
/// the same way, and a list of booleans a bool array.
pub(crate) fn columns(py: Python<'_>, value: &Value) -> PyResult<Py<PyAny>> {
    match value {
        Value::Array(items) if !items.is_empty() => {
            if items.iter().all(Value::is_i64) {
                let counts: Vec<i64> = items.iter().filter_map(Value::as_i64).collect();
                return Ok(counts.into_pyarray(py).into_any().unbind());
            }
            if items.iter().all(|v| v.is_number() || v.is_null()) {
                let numbers: Vec<f64> = items
                    .iter()
                    .map(|v| v.as_f64().unwrap_or(f64::NAN))
                    .collect();
                return Ok(numbers.into_pyarray(py).into_any().unbind());
            }
            if items.iter().all(Value::is_boolean) {
                let flags: Vec<bool> = items.iter().map(|v| v.as_bool() == Some(true)).collect();
                return Ok(flags.into_pyarray(py).into_any().unbind());
            }
            if let Some(keys) = record_keys(items) {
                let dict = PyDict::new(py);
                for key in keys {
                    let column: Vec<Value> = items.iter().map(|item| item[key].clone()).collect();
                    dict.set_item(key, columns(py, &Value::Array(column))?)?;
                }
                return Ok(dict.into_any().unbind());
            }
            let list = PyList::empty(py);
            for item in items {
                list.append(columns(py, item)?)?;
            }
            Ok(list.into_any().unbind())
        }
        Value::Object(map) => {
            let dict = PyDict::new(py);
            for (key, item) in map {
                dict.set_item(key, columns(py, item)?)?;
            }
            Ok(dict.into_any().unbind())
        }
        other => plain(py, other),
    }
}

/// The keys of `items` if every item is an object with the same keys.
fn record_keys(items: &[Value]) -> Option<Vec<&str>> {
    let first = items.first()?.as_object()?;
    let keys: Vec<&str> = first.keys().map(String::as_str).collect();
    items
        .iter()
        .all(|item| {
            item.as_object().is_some_and(|map| {
                map.len() == keys.len() && keys.iter().all(|k| map.contains_key(*k))
            })
        })
        .then_some(keys)
}

/// `vectors` as a new `(n, 3)` float64 array.
pub(crate) fn vectors_array<'py>(py: Python<'py>, vectors: &[Vec3]) -> Bound<'py, PyAny> {
    let flat: Vec<f64> = vectors.iter().flat_map(|v| [v.x, v.y, v.z]).collect();
    let array =
        Array2::from_shape_vec((vectors.len(), 3), flat).unwrap_or_else(|_| Array2::zeros((0, 3)));
    array.into_pyarray(py).into_any()
}

/// `values` as a new float64 array.
pub(crate) fn numbers_array<'py>(py: Python<'py>, values: Vec<f64>) -> Bound<'py, PyAny> {
    PyArray1::from_vec(py, values).into_any()
}

/// `rows` of indices as a new `(m, N)` int64 array.
pub(crate) fn index_array<'py, const N: usize>(
    py: Python<'py>,
    rows: &[[usize; N]],
) -> Bound<'py, PyAny> {
    let flat: Vec<i64> = rows
        .iter()
        .flatten()
        .map(|&i| i64::try_from(i).unwrap_or(i64::MAX))
        .collect();
    let array =
        Array2::from_shape_vec((rows.len(), N), flat).unwrap_or_else(|_| Array2::zeros((0, N)));
    array.into_pyarray(py).into_any()
}

/// `indices` as a new int64 array.
pub(crate) fn index_list(py: Python<'_>, indices: impl Iterator<Item = usize>) -> Bound<'_, PyAny> {
    let values: Vec<i64> = indices
        .map(|i| i64::try_from(i).unwrap_or(i64::MAX))
        .collect();
    PyArray1::from_vec(py, values).into_any()
}

/// An argument read as a float64 array of one of the shapes `expected`
/// allows; `make` builds the exception from the message, which names the
/// argument.
pub(crate) struct Reader {
    /// The argument's name, for messages.
    pub(crate) name: String,
    /// The exception for a message.
    pub(crate) make: fn(String) -> PyErr,
}

impl Reader {
    fn fail<T>(&self, problem: impl std::fmt::Display) -> PyResult<T> {
        Err((self.make)(format!("{}: {problem}", self.name)))
    }

    /// `value` as a float64 array: its shape and its values in C order.
    fn floats(&self, value: &Bound<'_, PyAny>) -> PyResult<(Vec<usize>, Vec<f64>)> {
        let numpy = value.py().import("numpy")?;
        let float64 = numpy.getattr("float64")?;
        let array = match numpy.call_method1("asarray", (value, float64, "C")) {
            Ok(array) => array,
            Err(error) => return self.fail(format!("not an array of numbers ({error})")),
        };
        let array = array.cast_into::<PyArrayDyn<f64>>()?;
        let shape = array.shape().to_vec();
        let values = array.to_vec()?;
        Ok((shape, values))
    }

    /// `value` as `n` vectors: an `(n, 3)` array, `n` given or not, every
    /// value finite (the first bad one named by its row).
    pub(crate) fn vectors(
        &self,
        value: &Bound<'_, PyAny>,
        n: Option<usize>,
    ) -> PyResult<Vec<Vec3>> {
        let (shape, values) = self.floats(value)?;
        let rows = shape.first().copied().unwrap_or(0);
        if shape.len() != 2 || shape[1] != 3 || n.is_some_and(|n| n != rows) {
            let wanted = n.map_or_else(|| "n".to_owned(), |n| n.to_string());
            return self.fail(format!(
                "expected an array of shape ({wanted}, 3), got shape {}",
                shape_text(&shape)
            ));
        }
        let vectors: Vec<Vec3> = values
            .chunks_exact(3)
            .map(|c| Vec3::new(c[0], c[1], c[2]))
            .collect();
        if let Some(row) = vectors
            .iter()
            .position(|v| !v.iter().all(|c| c.is_finite()))
        {
            let v = vectors[row];
            return self.fail(format!(
                "row {row} is not finite: [{}, {}, {}]",
                v.x, v.y, v.z
            ));
        }
        Ok(vectors)
    }

    /// `value` as one vector: three finite numbers.
    pub(crate) fn vector(&self, value: &Bound<'_, PyAny>) -> PyResult<Vec3> {
        let (shape, values) = self.floats(value)?;
        if shape != [3] {
            return self.fail(format!(
                "expected 3 numbers, got shape {}",
                shape_text(&shape)
            ));
        }
        if !values.iter().all(|c| c.is_finite()) {
            return self.fail(format!("not finite: {values:?}"));
        }
        Ok(Vec3::new(values[0], values[1], values[2]))
    }

    /// `value` as `n` numbers: a number (the same for all) or an array of
    /// shape `(n,)`.
    pub(crate) fn per_item(&self, value: &Bound<'_, PyAny>, n: usize) -> PyResult<Vec<f64>> {
        let (shape, values) = self.floats(value)?;
        match shape.as_slice() {
            [] => Ok(vec![values[0]; n]),
            [m] if *m == n => Ok(values),
            _ => self.fail(format!(
                "expected a number or an array of shape ({n},), got shape {}",
                shape_text(&shape)
            )),
        }
    }

    /// `value` as a number.
    pub(crate) fn number(&self, value: &Bound<'_, PyAny>) -> PyResult<f64> {
        let (shape, values) = self.floats(value)?;
        match shape.as_slice() {
            [] => Ok(values[0]),
            _ => self.fail(format!(
                "expected a number, got shape {}",
                shape_text(&shape)
            )),
        }
    }

    /// `value` as rows of `N` indices: an `(m, N)` array of whole numbers
    /// (an `(m,)` one for `N = 1`), each at least 0 and below `count`.
    pub(crate) fn indices<const N: usize>(
        &self,
        value: &Bound<'_, PyAny>,
        count: usize,
    ) -> PyResult<Vec<[usize; N]>> {
        let (shape, values) = self.floats(value)?;
        let rows = shape.first().copied().unwrap_or(0);
        let fits = match shape.as_slice() {
            [_] => N == 1,
            [_, n] => *n == N,
            _ => false,
        };
        if !fits && rows > 0 {
            let wanted = if N == 1 {
                "(m,)".to_owned()
            } else {
                format!("(m, {N})")
            };
            return self.fail(format!(
                "expected an array of shape {wanted}, got shape {}",
                shape_text(&shape)
            ));
        }
        let mut out = Vec::with_capacity(rows);
        for (row, chunk) in values.chunks_exact(N).enumerate() {
            let mut item = [0; N];
            for (slot, &x) in item.iter_mut().zip(chunk) {
                if x.fract() != 0.0 || !(0.0..count as f64).contains(&x) {
                    let what = if N == 1 {
                        format!("item {row}")
                    } else {
                        format!("row {row}")
                    };
                    return self.fail(format!(
                        "{what}: particle {x} does not exist (there are {count} particles)"
                    ));
                }
                *slot = x as usize;
            }
            out.push(item);
        }
        Ok(out)
    }
}

fn shape_text(shape: &[usize]) -> String {
    match shape {
        [] => "() (a number)".to_owned(),
        [n] => format!("({n},)"),
        _ => format!(
            "({})",
            shape
                .iter()
                .map(ToString::to_string)
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}
