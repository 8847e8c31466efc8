//! The integrator of a simulation or run: a name of the scene format's one
//! list ([`Method`]) and keyword arguments under the keys of a scene
//! file's `[integrator]` table, read by the readers the scene files use
//! ([`ImplicitSettings::from_keys`] for the implicit methods), so that
//! names, defaults and checks have one source.

use hooke_core::Named;
use hooke_implicit::{ImplicitSettings, KeyValue};
use hooke_scenes::{IntegratorSpec, Method};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyString};

use crate::errors::settings_error;

/// A keyword argument's value as a settings key takes it.
enum Given {
    Name(String),
    Count(u64),
    Number(f64),
    Switch(bool),
}

impl Given {
    fn read(key: &str, value: &Bound<'_, PyAny>) -> PyResult<Self> {
        if value.is_instance_of::<PyBool>() {
            return Ok(Self::Switch(value.extract()?));
        }
        if value.is_instance_of::<PyString>() {
            return Ok(Self::Name(value.extract()?));
        }
        if value.is_instance_of::<PyInt>() {
            return Ok(match value.extract::<u64>() {
                Ok(n) => Self::Count(n),
                Err(_) => Self::Number(value.extract()?),
            });
        }
        if value.is_instance_of::<PyFloat>() {
            return Ok(Self::Number(value.extract()?));
        }
        Err(settings_error(format!(
            "{key}: got {value}, expected a name, a number, True or False"
        )))
    }

    fn key_value(&self) -> KeyValue<'_> {
        match self {
            Self::Name(name) => KeyValue::Name(name),
            Self::Count(n) => KeyValue::Count(*n),
            Self::Number(x) => KeyValue::Number(*x),
            Self::Switch(b) => KeyValue::Switch(*b),
        }
    }

    fn number(&self, key: &str) -> PyResult<f64> {
        match self {
            Self::Number(x) => Ok(*x),
            Self::Count(n) => Ok(*n as f64),
            _ => Err(settings_error(format!("{key}: expected a number"))),
        }
    }
}

/// The integrator `name` (by default `scene`'s) with the keyword
/// arguments `settings`, each a key of the scene format's `[integrator]`
/// table that applies to that integrator. For the scene's own method the
/// scene's settings are the start and the keywords replace them (the
/// scene's keys that do not apply to the solver and step the keywords
/// choose are dropped); for another, the library's defaults
/// ([`IntegratorSpec::new`]).
///
/// # Errors
/// A `hooke.SettingsError` naming an unknown integrator, a keyword the
/// integrator does not take, or a value out of range.
pub(crate) fn integrator(
    scene: &IntegratorSpec,
    name: Option<&str>,
    settings: Option<&Bound<'_, PyDict>>,
) -> PyResult<IntegratorSpec> {
    let method = match name {
        Some(name) => Method::from_name(name).ok_or_else(|| {
            settings_error(format!(
                "integrator: got \"{name}\", expected one of {}",
                Method::names()
            ))
        })?,
        None => scene.method(),
    };
    let base = if method == scene.method() {
        *scene
    } else {
        IntegratorSpec::new(method)
    };
    let mut given = Vec::new();
    if let Some(settings) = settings {
        for (key, value) in settings.iter() {
            let key: String = key.extract()?;
            let value = Given::read(&key, &value)?;
            given.push((key, value));
        }
    }
    if given.is_empty() {
        return Ok(base);
    }
    let spec = match base {
        IntegratorSpec::Implicit(base) => IntegratorSpec::Implicit(implicit(base, &given)?),
        IntegratorSpec::Adaptive { mut rtol, mut atol } => {
            for (key, value) in &given {
                match key.as_str() {
                    "rtol" => rtol = value.number(key)?,
                    "atol" => atol = value.number(key)?,
                    _ => return Err(not_taken(key, method, "`rtol` and `atol`")),
                }
            }
            IntegratorSpec::Adaptive { rtol, atol }
        }
        IntegratorSpec::FastMassSpring { mut iterations } => {
            for (key, value) in &given {
                match (key.as_str(), value) {
                    ("iterations", Given::Count(n)) => {
                        iterations = usize::try_from(*n).unwrap_or(usize::MAX);
                    }
                    ("iterations", _) => {
                        return Err(settings_error("iterations: expected a whole number ≥ 1"));
                    }
                    _ => return Err(not_taken(key, method, "`iterations`")),
                }
            }
            IntegratorSpec::FastMassSpring { iterations }
        }
        IntegratorSpec::Explicit(_) => {
            return Err(not_taken(&given[0].0, method, "no settings"));
        }
    };
    spec.build().map_err(settings_error)?;
    Ok(spec)
}

fn not_taken(key: &str, method: Method, takes: &str) -> PyErr {
    settings_error(format!(
        "{key}: integrator \"{method}\" takes no keyword `{key}`; it takes {takes}"
    ))
}

/// `base` with the keys `given`: the scheme stays the method's, the
/// keys given replace `base`'s, and `base`'s keys that do not apply to
/// the solver and step the keys choose are dropped.
fn implicit(base: ImplicitSettings, given: &[(String, Given)]) -> PyResult<ImplicitSettings> {
    if given.iter().any(|(key, _)| key == "scheme") {
        return Err(settings_error(
            "scheme: the scheme is the integrator's, e.g. integrator=\"bdf2\"",
        ));
    }
    let scheme = ("scheme", KeyValue::Name(base.scheme.name()));
    let mut kept: Vec<(&str, KeyValue<'static>)> = base
        .keys()
        .into_iter()
        .filter(|(key, _)| *key != "scheme" && !given.iter().any(|(g, _)| g == key))
        // `keys` writes the weak springs each minimiser uses by default:
        // only a choice of the scene's own carries over.
        .filter(|(key, _)| *key != "weak_springs" || base.weak_springs.is_some())
        .collect();
    loop {
        let keys = std::iter::once(scheme).chain(kept.iter().copied()).chain(
            given
                .iter()
                .map(|(key, value)| (key.as_str(), value.key_value())),
        );
        match ImplicitSettings::from_keys(keys) {
            Ok(settings) => return Ok(settings),
            Err(error) => match kept.iter().position(|(key, _)| *key == error.key) {
                Some(k) => {
                    kept.remove(k);
                }
                None => return Err(settings_error(error)),
            },
        }
    }
}

/// The settings of `spec` as a dict under the scene format's keys.
pub(crate) fn settings_dict<'py>(
    py: Python<'py>,
    spec: &IntegratorSpec,
) -> PyResult<Bound<'py, PyDict>> {
    let dict = PyDict::new(py);
    match spec {
        IntegratorSpec::Implicit(settings) => {
            for (key, value) in settings.keys() {
                match value {
                    KeyValue::Name(name) => dict.set_item(key, name)?,
                    KeyValue::Count(n) => dict.set_item(key, n)?,
                    KeyValue::Number(x) => dict.set_item(key, x)?,
                    KeyValue::Switch(b) => dict.set_item(key, b)?,
                }
            }
        }
        IntegratorSpec::Adaptive { rtol, atol } => {
            dict.set_item("rtol", rtol)?;
            dict.set_item("atol", atol)?;
        }
        IntegratorSpec::FastMassSpring { iterations } => {
            dict.set_item("iterations", iterations)?;
        }
        IntegratorSpec::Explicit(_) => {}
    }
    Ok(dict)
}
