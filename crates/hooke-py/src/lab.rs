//! `stability` and `accuracy`: the lab's measurements with the command
//! line's options, their reports as dicts whose records are columns of
//! numpy arrays.

use hooke_core::Named;
use hooke_implicit::{LinearSolver, Minimizer, PcgSettings};
use hooke_lab::accuracy::StepVariant;
use hooke_lab::{AccuracyOptions, Method, Range, Shard, StabilityOptions};
use hooke_scenes::Scene;
use pyo3::prelude::*;

use crate::convert::columns;
use crate::errors::{RunError, scene_error, settings_error};
use crate::scene::scene_arg;

/// Values as the command line takes them: a string of numbers and
/// log-spaced ranges `FIRST:LAST:COUNT` separated by commas, or a sequence
/// of numbers; sorted, without repeats.
fn values(name: &str, value: &Bound<'_, PyAny>) -> PyResult<Vec<f64>> {
    let mut values = Vec::new();
    if let Ok(text) = value.extract::<String>() {
        for part in text.split(',') {
            let range = part
                .parse::<Range>()
                .map_err(|e| settings_error(format!("{name}: {e}")))?;
            values.extend(range.values());
        }
    } else {
        values = value.extract().map_err(|_| {
            settings_error(format!(
                "{name}: expected numbers or a string such as \"1e-3:1e-1:5\""
            ))
        })?;
    }
    values.sort_by(f64::total_cmp);
    values.dedup();
    Ok(values)
}

/// The options every measurement shares, as the command line's.
struct Common<'a> {
    methods: Option<Vec<String>>,
    scale_stiffness: Option<f64>,
    solver: Option<&'a str>,
    pcg_tolerance: Option<f64>,
    newton: Option<usize>,
    linearized: bool,
    shard: Option<&'a str>,
}

impl Common<'_> {
    /// The scene, its springs scaled by `scale_stiffness`.
    fn scene(&self, scene: Option<&Bound<'_, PyAny>>) -> PyResult<Scene> {
        let mut scene = scene_arg(scene)?;
        if let Some(scale) = self.scale_stiffness {
            scene.system = scene
                .system
                .with_stiffness_scale(scale)
                .map_err(|e| scene_error(format!("scale_stiffness {scale}: {e}")))?;
        }
        Ok(scene)
    }

    /// The methods' settings for `scene` with `solver`, `pcg_tolerance`,
    /// `newton` and `linearized` set on the implicit ones.
    fn settings(&self, scene: &Scene) -> PyResult<hooke_lab::Settings> {
        let mut settings = hooke_lab::Settings::from_scene(&scene.integrator);
        let implicit = &mut settings.implicit;
        match (self.solver, self.pcg_tolerance) {
            (Some(name), tolerance) => {
                let solver = LinearSolver::from_name(name).ok_or_else(|| {
                    settings_error(format!(
                        "solver: got \"{name}\", expected one of {}",
                        LinearSolver::quoted_names()
                    ))
                })?;
                implicit.solver = match (tolerance, solver.pcg()) {
                    (None, _) => solver,
                    (Some(tolerance), Some(pcg)) => solver.with_pcg(
                        PcgSettings::new(tolerance, pcg.max_iterations())
                            .map_err(settings_error)?,
                    ),
                    (Some(_), None) => {
                        return Err(settings_error(format!(
                            "pcg_tolerance: solver \"{name}\" takes no tolerance"
                        )));
                    }
                };
            }
            (None, Some(_)) => {
                return Err(settings_error("pcg_tolerance: give the solver too"));
            }
            (None, None) => {}
        }
        if let Some(n) = self.newton {
            implicit.newton_iterations = n;
        }
        if self.linearized {
            implicit.minimizer = Minimizer::Linearized;
        }
        Ok(settings)
    }

    /// The methods named, or `all`.
    fn methods(&self, all: &[Method]) -> PyResult<Vec<Method>> {
        let Some(names) = &self.methods else {
            return Ok(all.to_vec());
        };
        names
            .iter()
            .map(|name| {
                Method::from_name(name.trim()).ok_or_else(|| {
                    settings_error(format!(
                        "methods: no integrator \"{name}\"; one of {}",
                        Method::names()
                    ))
                })
            })
            .collect()
    }

    fn shard(&self) -> PyResult<Option<Shard>> {
        self.shard
            .map(|s| s.parse().map_err(|e| settings_error(format!("shard: {e}"))))
            .transpose()
    }
}

/// `report` as a dict, its records (cells, runs, limits …) as columns.
fn report_dict(py: Python<'_>, report: &impl serde::Serialize) -> PyResult<Py<PyAny>> {
    let value = serde_json::to_value(report).map_err(|e| RunError::new_err(e.to_string()))?;
    columns(py, &value)
}

/// `hooke stability`: which integrators stay stable at which stiffness
/// scale and step on `scene` (a `Scene`, a built-in scene's name, a scene
/// file's path or `None` for the default scene), with the command line's
/// options and defaults: `methods` (names; default all), `stiffness` and
/// `dt` (numbers, or strings of numbers and ranges `FIRST:LAST:COUNT`),
/// `duration` and `min_steps` per cell, `energy_bound`, `limit` (also
/// search each integrator's largest stable step at `limit_stiffness`),
/// `scale_stiffness`, the implicit methods' `solver`, `pcg_tolerance`,
/// `newton` and `linearized`, and `shard` ("I/N"). Returns the report
/// `stability.json` holds, its `cells` (and `limits`) as dicts of columns:
/// numpy arrays of numbers and booleans, lists of names.
#[pyfunction]
#[pyo3(signature = (
    scene = None, *, methods = None, stiffness = None, dt = None, duration = 1.0,
    min_steps = 1000, energy_bound = hooke_lab::stability::DEFAULT_ENERGY_BOUND,
    limit = false, limit_stiffness = 1.0, scale_stiffness = None, solver = None,
    pcg_tolerance = None, newton = None, linearized = false, shard = None,
))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn stability<'py>(
    py: Python<'py>,
    scene: Option<&Bound<'py, PyAny>>,
    methods: Option<Vec<String>>,
    stiffness: Option<&Bound<'py, PyAny>>,
    dt: Option<&Bound<'py, PyAny>>,
    duration: f64,
    min_steps: usize,
    energy_bound: f64,
    limit: bool,
    limit_stiffness: f64,
    scale_stiffness: Option<f64>,
    solver: Option<&str>,
    pcg_tolerance: Option<f64>,
    newton: Option<usize>,
    linearized: bool,
    shard: Option<&str>,
) -> PyResult<Py<PyAny>> {
    let common = Common {
        methods,
        scale_stiffness,
        solver,
        pcg_tolerance,
        newton,
        linearized,
        shard,
    };
    let scene = common.scene(scene)?;
    let mut options = StabilityOptions::for_scene(&scene);
    options.settings = common.settings(&scene)?;
    options.methods = common.methods(&Method::ALL)?;
    if let Some(stiffness) = stiffness {
        options.scales = values("stiffness", stiffness)?;
    }
    if let Some(dt) = dt {
        options.dts = values("dt", dt)?;
    }
    options.duration = duration;
    options.min_steps = min_steps;
    options.energy_bound = energy_bound;
    options.limit_scale = limit.then_some(limit_stiffness);
    options.shard = common.shard()?;
    let report = py
        .detach(|| hooke_lab::stability(&scene, &options, &|_, _| ()))
        .map_err(lab_error)?;
    report_dict(py, &report)
}

/// `hooke accuracy`: each integrator's error against a reference, its
/// observed order and its run time on `scene`, with the command line's
/// options and defaults: `methods`, `dt` and `tolerances` (numbers or
/// strings as in `stability`; default: chosen from the scene),
/// `duration` (default: the scene's), `frames`, `repeat`,
/// `reference_dt`, `variants` (backward Euler's step carried out other
/// ways: "newton:1e-2", "quasi-newton:1e-3", "linearized",
/// "fast-mass-spring:10"; an empty list for none; default: the command
/// line's list when backward Euler is measured), `variant_dt`, and the
/// options every measurement shares (see `stability`). Returns the report
/// `accuracy.json` holds, its records as dicts of columns.
#[pyfunction]
#[pyo3(signature = (
    scene = None, *, methods = None, dt = None, tolerances = None, duration = None,
    frames = 10, repeat = 3, reference_dt = None, variants = None, variant_dt = None,
    scale_stiffness = None, solver = None, pcg_tolerance = None, newton = None,
    linearized = false, shard = None,
))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn accuracy<'py>(
    py: Python<'py>,
    scene: Option<&Bound<'py, PyAny>>,
    methods: Option<Vec<String>>,
    dt: Option<&Bound<'py, PyAny>>,
    tolerances: Option<&Bound<'py, PyAny>>,
    duration: Option<f64>,
    frames: usize,
    repeat: usize,
    reference_dt: Option<f64>,
    variants: Option<Vec<String>>,
    variant_dt: Option<&Bound<'py, PyAny>>,
    scale_stiffness: Option<f64>,
    solver: Option<&str>,
    pcg_tolerance: Option<f64>,
    newton: Option<usize>,
    linearized: bool,
    shard: Option<&str>,
) -> PyResult<Py<PyAny>> {
    let common = Common {
        methods,
        scale_stiffness,
        solver,
        pcg_tolerance,
        newton,
        linearized,
        shard,
    };
    let scene = common.scene(scene)?;
    let mut options = AccuracyOptions::for_scene(&scene);
    options.settings = common.settings(&scene)?;
    options.methods = common.methods(&options.methods)?;
    if let Some(dt) = dt {
        options.dts = values("dt", dt)?;
    }
    if let Some(tolerances) = tolerances {
        options.tolerances = values("tolerances", tolerances)?;
    }
    if let Some(duration) = duration {
        options.duration = duration;
    }
    options.frames = frames;
    options.repeat = repeat;
    options.reference_dt = reference_dt;
    options.shard = common.shard()?;
    options.variants = match variants {
        Some(list) => list
            .iter()
            .map(|v| {
                v.trim()
                    .parse::<StepVariant>()
                    .map_err(|e| settings_error(format!("variants: {e}")))
            })
            .collect::<PyResult<_>>()?,
        None if options.methods.contains(&Method::BackwardEuler) => StepVariant::defaults(),
        None => Vec::new(),
    };
    if let Some(dts) = variant_dt {
        options.variant_dts = values("variant_dt", dts)?;
    }
    let report = py
        .detach(|| hooke_lab::accuracy(&scene, &options, &|_, _| ()))
        .map_err(lab_error)?;
    report_dict(py, &report)
}

/// A lab error: a settings error for a method parameter out of range,
/// otherwise a run error, with the command line's message.
fn lab_error(error: hooke_lab::LabError) -> PyErr {
    match error {
        hooke_lab::LabError::Parameter(_) => settings_error(error),
        _ => RunError::new_err(error.to_string()),
    }
}
