//! `hooke.Simulation`: a scene's system stepped by an integrator, its
//! state read and set as numpy arrays, each step run with the GIL
//! released.

use std::sync::{Mutex, MutexGuard};
use std::time::{Duration, Instant};

use hooke_core::{Integrator, State, StepReport};
use hooke_scenes::IntegratorSpec;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::convert::{Reader, vectors_array};
use crate::errors::{StateError, StepError};
use crate::integrator::{integrator, settings_dict};
use crate::scene::{Scene, scene_arg};

/// A scene's system stepped by an integrator: `scene` a `Scene`, a
/// built-in scene's name, a scene file's path or `None` (the default
/// scene); `integrator` any name of the scene format (default: the
/// scene's); `dt` the step in s (default: the scene's); and `settings`
/// keyword arguments under the keys of the scene format's `[integrator]`
/// table (`solver="pcg"`, `step="quasi-newton"`, `newton_tolerance=1e-6`,
/// `rtol=…` for "dormand-prince", `iterations=…` for "fast-mass-spring"),
/// the library's defaults where none is given. Each step releases the
/// GIL.
#[pyclass(module = "hooke", frozen)]
pub(crate) struct Simulation {
    inner: Mutex<Inner>,
}

/// What a simulation steps and where it is.
struct Inner {
    scene: hooke_scenes::Scene,
    spec: IntegratorSpec,
    integrator: Box<dyn Integrator + Send>,
    state: State,
    dt: f64,
    /// Steps taken since the start (or the last reset).
    steps: usize,
    /// What the last `step` or `advance` did: its reports summed, its
    /// steps, its wall time inside the steps and the energy after it.
    last: Option<(StepReport, usize, Duration, f64)>,
}

impl Simulation {
    fn lock(&self) -> MutexGuard<'_, Inner> {
        match self.inner.lock() {
            Ok(inner) => inner,
            Err(poisoned) => poisoned.into_inner(),
        }
    }

    /// One step with the GIL released: its report and wall time.
    fn one_step(&self, py: Python<'_>) -> PyResult<(StepReport, Duration)> {
        py.detach(|| {
            let mut inner = self.lock();
            let Inner {
                scene,
                integrator,
                state,
                dt,
                steps,
                ..
            } = &mut *inner;
            let started = Instant::now();
            let result = integrator.step(&scene.system, state, *dt);
            let wall = started.elapsed();
            let report = result.map_err(|e| StepError::new_err(e.to_string()))?;
            *steps += 1;
            Ok((report, wall))
        })
    }

    /// Records the last call's work and returns it as a dict.
    fn finish<'py>(
        &self,
        py: Python<'py>,
        report: StepReport,
        steps: usize,
        wall: Duration,
    ) -> PyResult<Bound<'py, PyDict>> {
        let mut inner = self.lock();
        let energy = inner
            .scene
            .system
            .energy(&inner.state)
            .map_or(f64::NAN, |e| e.total());
        inner.last = Some((report, steps, wall, energy));
        report_dict(py, &inner, &report, steps, wall, energy)
    }
}

/// A step report as a dict: the `StepReport`'s fields, the steps it sums,
/// the time reached, the wall time inside the steps and the energy after.
fn report_dict<'py>(
    py: Python<'py>,
    inner: &Inner,
    r: &StepReport,
    steps: usize,
    wall: Duration,
    energy: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let dict = PyDict::new(py);
    dict.set_item("steps", steps)?;
    dict.set_item("time", inner.state.time())?;
    dict.set_item("wall_s", wall.as_secs_f64())?;
    dict.set_item("energy", energy)?;
    dict.set_item("force_evaluations", r.force_evaluations)?;
    dict.set_item("accepted_steps", r.accepted_steps)?;
    dict.set_item("rejected_steps", r.rejected_steps)?;
    dict.set_item("newton_iterations", r.newton_iterations)?;
    dict.set_item("newton_iterations_max", r.newton_iterations_max)?;
    dict.set_item("newton_residual", r.newton_residual)?;
    dict.set_item("linear_iterations", r.linear_iterations)?;
    dict.set_item("linear_solves", r.linear_solves)?;
    dict.set_item("unconverged_solves", r.unconverged_solves)?;
    dict.set_item("linear_residual", r.linear_residual)?;
    let solver = (!r.linear_solver.is_empty()).then_some(r.linear_solver);
    dict.set_item("linear_solver", solver)?;
    dict.set_item("unconverged_steps", r.unconverged_steps)?;
    dict.set_item("energy_corrections", r.energy_corrections)?;
    dict.set_item("energy_excess", r.energy_excess)?;
    dict.set_item("contacts", r.contacts)?;
    dict.set_item("proximity_queries", r.proximity_queries)?;
    dict.set_item("detection_s", r.detection_seconds)?;
    dict.set_item("truncated_particles", r.truncated_particles)?;
    dict.set_item("truncated_particles_max", r.truncated_particles_max)?;
    dict.set_item("bound_fallbacks", r.bound_fallbacks)?;
    Ok(dict)
}

fn positive_step(dt: f64) -> PyResult<f64> {
    if dt.is_finite() && dt > 0.0 {
        Ok(dt)
    } else {
        Err(StateError::new_err(format!(
            "dt: must be positive and finite, got {dt}"
        )))
    }
}

fn state_reader(name: &str) -> Reader {
    Reader {
        name: name.to_owned(),
        make: StateError::new_err,
    }
}

#[pymethods]
impl Simulation {
    #[new]
    #[pyo3(signature = (scene = None, integrator = None, *, dt = None, **settings))]
    fn new(
        scene: Option<&Bound<'_, PyAny>>,
        integrator: Option<&str>,
        dt: Option<f64>,
        settings: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Self> {
        let mut scene = scene_arg(scene)?;
        let spec = self::integrator(&scene.integrator, integrator, settings)?;
        scene.integrator = spec;
        let dt = positive_step(dt.unwrap_or(scene.timing.dt))?;
        let built = spec.build().map_err(crate::errors::settings_error)?;
        Ok(Self {
            inner: Mutex::new(Inner {
                state: scene.system.initial_state(),
                scene,
                spec,
                integrator: built,
                dt,
                steps: 0,
                last: None,
            }),
        })
    }

    /// Takes one step of `dt`; returns its report (see `report`). Raises
    /// `hooke.StepError` if the step fails, leaving the state as it was.
    fn step<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let (report, wall) = self.one_step(py)?;
        self.finish(py, report, 1, wall)
    }

    /// Takes steps of `dt` until the time reaches `t` (the last step may
    /// end past it by less than a step); returns their reports summed.
    /// Ctrl-C stops it between two steps with `KeyboardInterrupt`.
    fn advance<'py>(&self, py: Python<'py>, t: f64) -> PyResult<Bound<'py, PyDict>> {
        if !t.is_finite() {
            return Err(StateError::new_err(format!("t: must be finite, got {t}")));
        }
        let (time, dt) = {
            let inner = self.lock();
            (inner.state.time(), inner.dt)
        };
        let x = (t - time) / dt;
        let steps = if (x - x.round()).abs() <= 1e-9 * x.abs().max(1.0) {
            x.round()
        } else {
            x.ceil()
        };
        let steps = steps.max(0.0) as usize;
        let (mut total, mut wall) = (StepReport::default(), Duration::ZERO);
        for _ in 0..steps {
            let (report, took) = self.one_step(py)?;
            total += report;
            wall += took;
            py.check_signals()?;
        }
        self.finish(py, total, steps, wall)
    }

    /// The energy of the state: a dict of `kinetic`, `elastic` (springs
    /// and volume elements), `gravitational` and their `total`, J.
    fn energy<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let inner = self.lock();
        let e = inner
            .scene
            .system
            .energy(&inner.state)
            .map_err(|e| StateError::new_err(e.to_string()))?;
        let dict = PyDict::new(py);
        dict.set_item("kinetic", e.kinetic)?;
        dict.set_item("elastic", e.elastic)?;
        dict.set_item("gravitational", e.gravitational)?;
        dict.set_item("total", e.total())?;
        Ok(dict)
    }

    /// Goes back to the scene's initial state at time 0 with a fresh
    /// integrator.
    fn reset(&self) -> PyResult<()> {
        let mut inner = self.lock();
        inner.integrator = inner.spec.build().map_err(crate::errors::settings_error)?;
        inner.state = inner.scene.system.initial_state();
        inner.steps = 0;
        inner.last = None;
        Ok(())
    }

    /// The last `step()` or `advance()`'s report, or `None` before the
    /// first: `steps`, the `time` reached, `wall_s` inside the steps, the
    /// `energy` after (J), and the step reports' counts summed
    /// (`newton_iterations`, `linear_iterations`, `linear_solves`,
    /// `accepted_steps` and `rejected_steps` of the substeps,
    /// `unconverged_steps`, `unconverged_solves`, `energy_corrections`,
    /// `force_evaluations`, `contacts`; contact's `proximity_queries`,
    /// `detection_s` of collision detection inside `wall_s`, the
    /// `truncated_particles` that per-particle bounds cut and their
    /// `bound_fallbacks` to the global limit) and largest values
    /// (`newton_iterations_max`, `newton_residual`, `linear_residual`,
    /// `energy_excess`, `truncated_particles_max` in one iteration), and
    /// the `linear_solver` used.
    #[getter]
    fn report<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyDict>>> {
        let inner = self.lock();
        inner
            .last
            .map(|(report, steps, wall, energy)| {
                report_dict(py, &inner, &report, steps, wall, energy)
            })
            .transpose()
    }

    /// Positions, an `(n, 3)` float64 array (a copy), m. Setting them takes
    /// any `(n, 3)` array of finite numbers; integrators that carry history
    /// restart from the new state.
    #[getter]
    fn positions<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        vectors_array(py, self.lock().state.positions())
    }

    #[setter]
    fn set_positions(&self, value: &Bound<'_, PyAny>) -> PyResult<()> {
        let n = self.lock().state.len();
        let x = state_reader("positions").vectors(value, Some(n))?;
        self.lock().state.positions_mut().copy_from_slice(&x);
        Ok(())
    }

    /// Velocities, an `(n, 3)` float64 array (a copy), m/s; set as
    /// positions are.
    #[getter]
    fn velocities<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        vectors_array(py, self.lock().state.velocities())
    }

    #[setter]
    fn set_velocities(&self, value: &Bound<'_, PyAny>) -> PyResult<()> {
        let n = self.lock().state.len();
        let v = state_reader("velocities").vectors(value, Some(n))?;
        self.lock().state.velocities_mut().copy_from_slice(&v);
        Ok(())
    }

    /// The simulated time, s; settable (moving pins and obstacles are
    /// where their paths put them at that time).
    #[getter]
    fn time(&self) -> f64 {
        self.lock().state.time()
    }

    #[setter]
    fn set_time(&self, time: f64) -> PyResult<()> {
        if !time.is_finite() {
            return Err(StateError::new_err(format!(
                "time: must be finite, got {time}"
            )));
        }
        self.lock().state.set_time(time);
        Ok(())
    }

    /// The step, s; settable (positive and finite).
    #[getter]
    fn dt(&self) -> f64 {
        self.lock().dt
    }

    #[setter]
    fn set_dt(&self, dt: f64) -> PyResult<()> {
        self.lock().dt = positive_step(dt)?;
        Ok(())
    }

    /// Steps taken since the start (or the last `reset()`).
    #[getter]
    fn steps(&self) -> usize {
        self.lock().steps
    }

    /// The number of particles.
    #[getter]
    fn particle_count(&self) -> usize {
        self.lock().state.len()
    }

    /// The integrator's name.
    #[getter]
    fn integrator(&self) -> &'static str {
        self.lock().spec.method().name()
    }

    /// The integrator's settings under the scene format's keys, defaults
    /// included.
    #[getter]
    fn settings<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        settings_dict(py, &self.lock().spec)
    }

    /// The scene stepped, with this simulation's integrator.
    #[getter]
    fn scene(&self) -> Scene {
        Scene::new(self.lock().scene.clone())
    }

    fn __repr__(&self) -> String {
        let inner = self.lock();
        format!(
            "<hooke.Simulation of {:?}: {}, dt = {} s, t = {} s after {} steps>",
            inner.scene.name,
            inner.spec.method(),
            inner.dt,
            inner.state.time(),
            inner.steps
        )
    }
}
