//! The package's exceptions: one base class, `hooke.HookeError`, and one
//! subclass for each kind of thing that goes wrong, each carrying the
//! message the command line prints for it.

use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;

create_exception!(
    hooke,
    HookeError,
    PyException,
    "Every error of hooke: the base class of its exceptions."
);
create_exception!(
    hooke,
    SceneError,
    HookeError,
    "A scene that cannot be read or built: a scene file or string \
     (`file:line: key: problem`), an unknown built-in scene, or arrays of \
     the wrong shape or with values out of range (naming the particle, \
     spring or obstacle)."
);
create_exception!(
    hooke,
    SettingsError,
    HookeError,
    "An integrator that does not exist, or a keyword argument it does not \
     take or whose value is out of range (naming the keyword)."
);
create_exception!(
    hooke,
    StateError,
    HookeError,
    "Positions, velocities, a time or a step that a simulation cannot take: \
     the wrong shape, not finite, or negative."
);
create_exception!(
    hooke,
    StepError,
    HookeError,
    "A step that failed: a state that became non-finite, a solver that did \
     not converge in strict mode, or surfaces in contact under an \
     integrator that cannot keep them apart. The state is the one before \
     the step."
);
create_exception!(
    hooke,
    RunError,
    HookeError,
    "A run, stability map or accuracy measurement that could not be made or \
     completed: a timing or option out of range, a file that cannot be \
     written, or a run that stopped early, whose summary is the exception's \
     `summary` attribute."
);

/// Adds the exception classes to the module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("HookeError", py.get_type::<HookeError>())?;
    m.add("SceneError", py.get_type::<SceneError>())?;
    m.add("SettingsError", py.get_type::<SettingsError>())?;
    m.add("StateError", py.get_type::<StateError>())?;
    m.add("StepError", py.get_type::<StepError>())?;
    m.add("RunError", py.get_type::<RunError>())?;
    Ok(())
}

/// A scene error with the message of `error`.
pub(crate) fn scene_error(error: impl std::fmt::Display) -> PyErr {
    SceneError::new_err(error.to_string())
}

/// A settings error with the message of `error`.
pub(crate) fn settings_error(error: impl std::fmt::Display) -> PyErr {
    SettingsError::new_err(error.to_string())
}

/// The exception for an error of the command line's layer: a scene error
/// for a scene that cannot be read or run, a settings error for a
/// parameter out of range, otherwise a run error.
pub(crate) fn cli_error(error: hooke_cli::CliError) -> PyErr {
    use hooke_cli::CliError as E;
    match error {
        E::SceneFile(_) | E::ScaleStiffness { .. } => scene_error(error),
        E::Parameter(_) | E::PcgTolerance { .. } | E::UnknownMethod { .. } => settings_error(error),
        _ => RunError::new_err(error.to_string()),
    }
}
