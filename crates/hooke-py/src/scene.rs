//! `hooke.Scene`: a scene from a TOML file or string, a built-in name or
//! arrays, with its system's arrays to read and its timing to change.

use std::path::PathBuf;

use hooke_scenes::{Timing, builtin, file};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use crate::convert::{index_array, index_list, numbers_array, vectors_array};
use crate::errors::{SceneError, scene_error};
use crate::integrator::settings_dict;
use crate::obstacles;
use crate::scene_arrays::{Arrays, World, scene_from_arrays};

/// A scene: a mass-spring system (particles, springs, pins, obstacles,
/// collision surfaces), what its bodies look like, the integrator it
/// names and its timing. Make one with `Scene.builtin`, `Scene.from_file`,
/// `Scene.from_toml` or `Scene.from_arrays`; its arrays are read-only
/// copies, its timing (`dt`, `duration`, `frame_rate`) can be set.
#[pyclass(module = "hooke", frozen)]
#[derive(Debug)]
pub(crate) struct Scene {
    pub(crate) scene: std::sync::RwLock<hooke_scenes::Scene>,
}

impl Scene {
    pub(crate) fn new(scene: hooke_scenes::Scene) -> Self {
        Self {
            scene: std::sync::RwLock::new(scene),
        }
    }

    /// A copy of the scene.
    pub(crate) fn get(&self) -> hooke_scenes::Scene {
        self.read(Clone::clone)
    }

    /// `f` of the scene.
    pub(crate) fn read<T>(&self, f: impl FnOnce(&hooke_scenes::Scene) -> T) -> T {
        match self.scene.read() {
            Ok(scene) => f(&scene),
            Err(poisoned) => f(&poisoned.into_inner()),
        }
    }

    fn set_timing(&self, change: impl FnOnce(&mut Timing), what: &str) -> PyResult<()> {
        let mut scene = match self.scene.write() {
            Ok(scene) => scene,
            Err(poisoned) => poisoned.into_inner(),
        };
        let mut timing = scene.timing;
        change(&mut timing);
        let ok = |x: f64| x.is_finite() && x > 0.0;
        if !(ok(timing.dt) && ok(timing.frame_rate) && timing.duration.is_finite())
            || timing.duration < 0.0
        {
            return Err(SceneError::new_err(format!(
                "{what}: must be positive and finite (duration: not negative)"
            )));
        }
        scene.timing = timing;
        Ok(())
    }
}

#[pymethods]
impl Scene {
    /// The built-in scene `name` (see `builtin_scenes()`); the default
    /// scene is "stiff-cloth".
    #[staticmethod]
    #[pyo3(signature = (name = hooke_cli::DEFAULT_SCENE))]
    fn builtin(py: Python<'_>, name: &str) -> PyResult<Self> {
        py.detach(|| builtin::load(name))
            .map(Self::new)
            .map_err(scene_error)
    }

    /// The scene file at `path`; mesh files it names are found relative to
    /// its folder.
    #[staticmethod]
    fn from_file(py: Python<'_>, path: PathBuf) -> PyResult<Self> {
        py.detach(|| file::load(&path))
            .map(Self::new)
            .map_err(scene_error)
    }

    /// The scene file text `text`; `path` names it in error messages, its
    /// folder is where mesh files are found, and its stem is the scene's
    /// name unless the text sets `name`.
    #[staticmethod]
    #[pyo3(signature = (text, path = PathBuf::from("scene.toml")))]
    fn from_toml(py: Python<'_>, text: &str, path: PathBuf) -> PyResult<Self> {
        py.detach(|| file::parse(text, &path))
            .map(Self::new)
            .map_err(scene_error)
    }

    /// A scene of your own system: `positions` an `(n, 3)` array (m),
    /// `masses` a number or an `(n,)` array (kg), `springs` an `(m, 2)`
    /// array of particle indices with `stiffness` (N/m), `rest_lengths`
    /// (m; default: the initial distances) and `damping` (N·s/m; default
    /// 0) each a number or an `(m,)` array; `velocities` (default 0),
    /// `pins` (particle indices), `triangles` (a `(t, 3)` array of
    /// particles: a collision surface, self-colliding unless
    /// `self_collision` is false, drawn in the frames), `gravity`,
    /// `air_damping`, `obstacles` (dicts under the keys of a scene file's
    /// `[[obstacles]]` tables, a box turned by `rotation`, a 3 × 3 matrix
    /// whose columns are its axes, as `Scene.obstacles` gives them),
    /// `contact_distance` (default: the library's), and the integrator and
    /// timing a run uses. A problem names the argument and the particle,
    /// spring or obstacle at fault.
    #[staticmethod]
    #[pyo3(signature = (
        positions, masses, springs = None, stiffness = None, rest_lengths = None,
        damping = None, *, velocities = None, pins = None, triangles = None,
        self_collision = true, gravity = (0.0, -9.81, 0.0), air_damping = 0.0,
        obstacles = None, contact_distance = None, integrator = "backward-euler",
        dt = 1.0 / 60.0, duration = 5.0, frame_rate = 60.0, name = "arrays",
    ))]
    #[allow(clippy::too_many_arguments)]
    fn from_arrays(
        positions: &Bound<'_, PyAny>,
        masses: &Bound<'_, PyAny>,
        springs: Option<&Bound<'_, PyAny>>,
        stiffness: Option<&Bound<'_, PyAny>>,
        rest_lengths: Option<&Bound<'_, PyAny>>,
        damping: Option<&Bound<'_, PyAny>>,
        velocities: Option<&Bound<'_, PyAny>>,
        pins: Option<&Bound<'_, PyAny>>,
        triangles: Option<&Bound<'_, PyAny>>,
        self_collision: bool,
        gravity: (f64, f64, f64),
        air_damping: f64,
        obstacles: Option<&Bound<'_, PyAny>>,
        contact_distance: Option<f64>,
        integrator: &str,
        dt: f64,
        duration: f64,
        frame_rate: f64,
        name: &str,
    ) -> PyResult<Self> {
        let arrays = Arrays {
            positions,
            masses,
            springs,
            stiffness,
            rest_lengths,
            damping,
            velocities,
            pins,
            triangles,
            obstacles,
        };
        let world = World {
            self_collision,
            gravity,
            air_damping,
            contact_distance,
            integrator,
            timing: Timing {
                duration,
                dt,
                frame_rate,
            },
            name,
        };
        scene_from_arrays(&arrays, &world).map(Self::new)
    }

    /// The scene's name.
    #[getter]
    fn name(&self) -> String {
        self.read(|s| s.name.clone())
    }

    /// The number of particles.
    #[getter]
    fn particle_count(&self) -> usize {
        self.read(|s| s.system.particle_count())
    }

    /// The integrator the scene names.
    #[getter]
    fn integrator(&self) -> &'static str {
        self.read(|s| s.integrator.method().name())
    }

    /// The settings of the scene's integrator, under the keys of the scene
    /// format's `[integrator]` table, defaults included.
    #[getter]
    fn settings<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        settings_dict(py, &self.read(|s| s.integrator))
    }

    /// The step, s.
    #[getter]
    fn dt(&self) -> f64 {
        self.read(|s| s.timing.dt)
    }

    #[setter]
    fn set_dt(&self, dt: f64) -> PyResult<()> {
        self.set_timing(|t| t.dt = dt, "dt")
    }

    /// The simulated duration of a run, s.
    #[getter]
    fn duration(&self) -> f64 {
        self.read(|s| s.timing.duration)
    }

    #[setter]
    fn set_duration(&self, duration: f64) -> PyResult<()> {
        self.set_timing(|t| t.duration = duration, "duration")
    }

    /// Frames written per simulated second by a run.
    #[getter]
    fn frame_rate(&self) -> f64 {
        self.read(|s| s.timing.frame_rate)
    }

    #[setter]
    fn set_frame_rate(&self, rate: f64) -> PyResult<()> {
        self.set_timing(|t| t.frame_rate = rate, "frame_rate")
    }

    /// Initial positions, an `(n, 3)` array, m.
    #[getter]
    fn positions<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        self.read(|s| vectors_array(py, s.system.initial_positions()))
    }

    /// Initial velocities, an `(n, 3)` array, m/s.
    #[getter]
    fn velocities<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        self.read(|s| vectors_array(py, s.system.initial_velocities()))
    }

    /// Particle masses, an `(n,)` array, kg.
    #[getter]
    fn masses<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        self.read(|s| numbers_array(py, s.system.masses().to_vec()))
    }

    /// The springs' particles, an `(m, 2)` int64 array.
    #[getter]
    fn springs<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        self.read(|s| {
            let ends: Vec<[usize; 2]> = s.system.springs().iter().map(|s| [s.i, s.j]).collect();
            index_array(py, &ends)
        })
    }

    /// The springs' stiffness, an `(m,)` array, N/m.
    #[getter]
    fn stiffness<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        self.read(|s| numbers_array(py, s.system.springs().iter().map(|s| s.stiffness).collect()))
    }

    /// The springs' rest lengths, an `(m,)` array, m.
    #[getter]
    fn rest_lengths<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        self.read(|s| {
            numbers_array(
                py,
                s.system.springs().iter().map(|s| s.rest_length).collect(),
            )
        })
    }

    /// The springs' axial damping, an `(m,)` array, N·s/m.
    #[getter]
    fn damping<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        self.read(|s| numbers_array(py, s.system.springs().iter().map(|s| s.damping).collect()))
    }

    /// The pinned particles, an int64 array.
    #[getter]
    fn pins<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        self.read(|s| index_list(py, s.system.pinned()))
    }

    /// The bodies' surface triangles, an `(t, 3)` int64 array of particles.
    #[getter]
    fn triangles<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        self.read(|s| {
            let triangles: Vec<[usize; 3]> = s
                .bodies
                .iter()
                .flat_map(|b| b.triangles.iter().copied())
                .collect();
            index_array(py, &triangles)
        })
    }

    /// Gravity, m/s², or `None` for a scene without.
    #[getter]
    fn gravity(&self) -> Option<(f64, f64, f64)> {
        self.read(|s| s.system.gravity().map(|g| (g.x, g.y, g.z)))
    }

    /// Air damping `γ`, N·s/m, or `None`.
    #[getter]
    fn air_damping(&self) -> Option<f64> {
        self.read(|s| s.system.air_damping())
    }

    /// The distance below which contact acts, m.
    #[getter]
    fn contact_distance(&self) -> f64 {
        self.read(|s| s.system.contact_distance())
    }

    /// The obstacles, each a dict under the keys of a scene file's
    /// `[[obstacles]]` table (what `Scene.from_arrays` takes).
    #[getter]
    fn obstacles<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let obstacles = self.read(|s| s.system.obstacles().to_vec());
        let list = PyList::empty(py);
        for obstacle in &obstacles {
            list.append(obstacles::to_dict(py, obstacle)?)?;
        }
        Ok(list)
    }

    /// The same scene with every spring's stiffness times `scale`.
    fn with_stiffness_scale(&self, scale: f64) -> PyResult<Self> {
        let mut scene = self.get();
        scene.system = scene
            .system
            .with_stiffness_scale(scale)
            .map_err(|e| scene_error(format!("scale {scale}: {e}")))?;
        Ok(Self::new(scene))
    }

    fn __repr__(&self) -> String {
        self.read(|s| {
            format!(
                "<hooke.Scene {:?}: {} particles, {} springs, {} obstacles, {}, dt = {} s, duration = {} s>",
                s.name,
                s.system.particle_count(),
                s.system.springs().len(),
                s.system.obstacles().len(),
                s.integrator.method(),
                s.timing.dt,
                s.timing.duration
            )
        })
    }
}

/// The built-in scenes: a dict of each name and a one-line description,
/// the default scene first.
#[pyfunction]
pub(crate) fn builtin_scenes(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let dict = PyDict::new(py);
    for (name, description) in builtin::NAMES {
        dict.set_item(name, description)?;
    }
    Ok(dict)
}

/// The scene an argument names: a `Scene`, a built-in scene's name, the
/// path of a scene file, or `None` for the default scene.
///
/// # Errors
/// A `hooke.SceneError` for a file or name that does not load.
pub(crate) fn scene_arg(value: Option<&Bound<'_, PyAny>>) -> PyResult<hooke_scenes::Scene> {
    let Some(value) = value.filter(|v| !v.is_none()) else {
        return builtin::load(hooke_cli::DEFAULT_SCENE).map_err(scene_error);
    };
    if let Ok(scene) = value.cast::<Scene>() {
        return Ok(scene.get().get());
    }
    if let Ok(name) = value.extract::<String>() {
        if builtin::NAMES.iter().any(|(n, _)| *n == name) {
            return builtin::load(&name).map_err(scene_error);
        }
    }
    let path: PathBuf = value.extract().map_err(|_| {
        scene_error(format!(
            "scene: got {value}, expected a hooke.Scene, a built-in scene's name or a scene file's path"
        ))
    })?;
    value.py().detach(|| file::load(&path)).map_err(scene_error)
}
