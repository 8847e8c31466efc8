//! The command line's jobs from Python: `run`, the runner of `hooke run`
//! itself, and `main`, the whole command line.

use std::ops::ControlFlow;
use std::path::PathBuf;
use std::process::ExitCode;

use hooke_cli::RunOptions;
use hooke_core::{Observer, State, StepInfo, System};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::convert::plain;
use crate::errors::{RunError, cli_error};
use crate::integrator::integrator;
use crate::scene::scene_arg;

/// Stops a run between two steps once Python has a signal to raise
/// (Ctrl-C), and keeps the exception.
#[derive(Default)]
struct Interrupt {
    error: Option<PyErr>,
}

impl Observer for Interrupt {
    fn observe(&mut self, _system: &System, _state: &State, _step: &StepInfo) -> ControlFlow<()> {
        match Python::attach(|py| py.check_signals()) {
            Ok(()) => ControlFlow::Continue(()),
            Err(error) => {
                self.error = Some(error);
                ControlFlow::Break(())
            }
        }
    }
}

/// Runs `scene` as `hooke run` does and writes its files into `out`: the
/// PLY frames, `preview.png`, `animation.gif` (unless `gif` is false),
/// `animation.usda` (unless `usd` is false) and `summary.json`. Returns
/// the summary, the dict `summary.json` holds. `scene` is a `Scene`, a
/// built-in scene's name, a scene file's path or `None` (the default
/// scene); `duration` replaces the scene's, `preview_time` picks the
/// preview's frame, and `integrator` and the keyword arguments `settings`
/// replace the scene's integrator as in `Simulation`. The GIL is released
/// while it runs; Ctrl-C stops it between two steps with
/// `KeyboardInterrupt`. A run that stops early (a step that fails, a
/// state that diverges) raises `hooke.RunError` with the summary as its
/// `summary` attribute.
#[pyfunction]
#[pyo3(signature = (
    scene = None, out = PathBuf::from("hooke-out"), *, gif = true, usd = true,
    duration = None, preview_time = None, integrator = None, **settings,
))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn run<'py>(
    py: Python<'py>,
    scene: Option<&Bound<'py, PyAny>>,
    out: PathBuf,
    gif: bool,
    usd: bool,
    duration: Option<f64>,
    preview_time: Option<f64>,
    integrator: Option<&str>,
    settings: Option<&Bound<'py, PyDict>>,
) -> PyResult<Py<PyAny>> {
    let mut scene = scene_arg(scene)?;
    if integrator.is_some() || settings.is_some_and(|s| !s.is_empty()) {
        scene.integrator = self::integrator(&scene.integrator, integrator, settings)?;
    }
    if let Some(duration) = duration {
        scene.timing.duration = duration;
    }
    let options = RunOptions::new(out)
        .gif(gif)
        .usd(usd)
        .preview_time(preview_time);
    let mut interrupt = Interrupt::default();
    let result = py.detach(|| hooke_cli::run(&scene, &options, &mut interrupt));
    if let Some(error) = interrupt.error {
        return Err(error);
    }
    let summary = result.map_err(cli_error)?;
    let value = serde_json::to_value(&summary).map_err(|e| RunError::new_err(e.to_string()))?;
    let dict = plain(py, &value)?;
    if let Some(reason) = &summary.error {
        let error = RunError::new_err(format!(
            "the run stopped after {} of {} steps: {reason}",
            summary.steps, summary.steps_planned
        ));
        error.value(py).setattr("summary", dict)?;
        return Err(error);
    }
    Ok(dict)
}

/// The `hooke` command line with the arguments `args` (by default
/// `sys.argv[1:]`), printing to the process's standard output and error
/// as the `hooke` binary does; returns its exit status: 0, 1 for a
/// command that failed, 2 for arguments that do not parse.
#[pyfunction]
#[pyo3(signature = (args = None))]
pub(crate) fn main(py: Python<'_>, args: Option<Vec<String>>) -> PyResult<u8> {
    let args = match args {
        Some(args) => args,
        None => {
            let argv: Vec<String> = py.import("sys")?.getattr("argv")?.extract()?;
            argv.into_iter().skip(1).collect()
        }
    };
    py.import("sys")?.getattr("stdout")?.call_method0("flush")?;
    let code = py.detach(|| {
        hooke_cli::run_cli(
            std::iter::once("hooke".to_owned()).chain(args),
            &mut std::io::stdout(),
            &mut std::io::stderr(),
        )
    });
    Ok(if code == ExitCode::SUCCESS {
        0
    } else if code == ExitCode::FAILURE {
        1
    } else {
        2
    })
}
