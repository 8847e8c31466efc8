"""Type stubs of hooke's extension module, which the package ``hooke``
re-exports whole."""

import os
from collections.abc import Sequence
from typing import Any, Optional, Union

import numpy as np
import numpy.typing as npt

__version__: str

Float64Array = npt.NDArray[np.float64]
Int64Array = npt.NDArray[np.int64]
ArrayLike = npt.ArrayLike
SceneLike = Union["Scene", str, "os.PathLike[str]", None]
Values = Union[str, Sequence[float]]
Setting = Union[str, int, float, bool]

class HookeError(Exception):
    """Every error of hooke: the base class of its exceptions."""

class SceneError(HookeError):
    """A scene that cannot be read or built: a scene file or string
    (``file:line: key: problem``), an unknown built-in scene, or arrays of
    the wrong shape or with values out of range (naming the particle,
    spring or obstacle)."""

class SettingsError(HookeError):
    """An integrator that does not exist, or a keyword argument it does not
    take or whose value is out of range (naming the keyword)."""

class StateError(HookeError):
    """Positions, velocities, a time or a step that a simulation cannot
    take: the wrong shape, not finite, or negative."""

class StepError(HookeError):
    """A step that failed: a state that became non-finite, a solver that
    did not converge in strict mode, or surfaces in contact under an
    integrator that cannot keep them apart. The state is the one before
    the step."""

class RunError(HookeError):
    """A run, stability map or accuracy measurement that could not be made
    or completed: a timing or option out of range, a file that cannot be
    written, or a run that stopped early, whose summary is the exception's
    ``summary`` attribute."""

    summary: dict[str, Any]

class Scene:
    """A scene: a mass-spring system (particles, springs, pins, obstacles,
    collision surfaces), what its bodies look like, the integrator it
    names and its timing. Make one with ``Scene.builtin``,
    ``Scene.from_file``, ``Scene.from_toml`` or ``Scene.from_arrays``; its
    arrays are read-only copies, its timing (``dt``, ``duration``,
    ``frame_rate``) can be set."""

    @staticmethod
    def builtin(name: str = "stiff-cloth") -> Scene:
        """The built-in scene ``name`` (see ``builtin_scenes()``); the
        default scene is "stiff-cloth"."""
    @staticmethod
    def from_file(path: Union[str, os.PathLike[str]]) -> Scene:
        """The scene file at ``path``; mesh files it names are found
        relative to its folder."""
    @staticmethod
    def from_toml(text: str, path: Union[str, os.PathLike[str]] = "scene.toml") -> Scene:
        """The scene file text ``text``; ``path`` names it in error
        messages, its folder is where mesh files are found, and its stem is
        the scene's name unless the text sets ``name``."""
    @staticmethod
    def from_arrays(
        positions: ArrayLike,
        masses: ArrayLike,
        springs: Optional[ArrayLike] = None,
        stiffness: Optional[ArrayLike] = None,
        rest_lengths: Optional[ArrayLike] = None,
        damping: Optional[ArrayLike] = None,
        *,
        velocities: Optional[ArrayLike] = None,
        pins: Optional[ArrayLike] = None,
        triangles: Optional[ArrayLike] = None,
        self_collision: bool = True,
        gravity: tuple[float, float, float] = (0.0, -9.81, 0.0),
        air_damping: float = 0.0,
        obstacles: Optional[Sequence[dict[str, Any]]] = None,
        contact_distance: Optional[float] = None,
        integrator: str = "backward-euler",
        dt: float = 1.0 / 60.0,
        duration: float = 5.0,
        frame_rate: float = 60.0,
        name: str = "arrays",
    ) -> Scene:
        """A scene of your own system: ``positions`` an ``(n, 3)`` array
        (m), ``masses`` a number or an ``(n,)`` array (kg), ``springs`` an
        ``(m, 2)`` array of particle indices with ``stiffness`` (N/m),
        ``rest_lengths`` (m; default: the initial distances) and
        ``damping`` (N·s/m; default 0) each a number or an ``(m,)`` array;
        ``velocities`` (default 0), ``pins`` (particle indices),
        ``triangles`` (a ``(t, 3)`` array of particles: a collision
        surface, self-colliding unless ``self_collision`` is false, drawn
        in the frames), ``gravity``, ``air_damping``, ``obstacles`` (dicts
        under the keys of a scene file's ``[[obstacles]]`` tables, a box
        turned by ``rotation``, a 3 × 3 matrix whose columns are its axes,
        as ``Scene.obstacles`` gives them), ``contact_distance`` (default: the
        library's), and the integrator and timing a run uses. A problem
        names the argument and the particle, spring or obstacle at
        fault."""
    @property
    def name(self) -> str:
        """The scene's name."""
    @property
    def particle_count(self) -> int:
        """The number of particles."""
    @property
    def integrator(self) -> str:
        """The integrator the scene names."""
    @property
    def settings(self) -> dict[str, Setting]:
        """The settings of the scene's integrator, under the keys of the
        scene format's ``[integrator]`` table, defaults included."""
    @property
    def dt(self) -> float:
        """The step, s."""
    @dt.setter
    def dt(self, value: float) -> None: ...
    @property
    def duration(self) -> float:
        """The simulated duration of a run, s."""
    @duration.setter
    def duration(self, value: float) -> None: ...
    @property
    def frame_rate(self) -> float:
        """Frames written per simulated second by a run."""
    @frame_rate.setter
    def frame_rate(self, value: float) -> None: ...
    @property
    def positions(self) -> Float64Array:
        """Initial positions, an ``(n, 3)`` array, m."""
    @property
    def velocities(self) -> Float64Array:
        """Initial velocities, an ``(n, 3)`` array, m/s."""
    @property
    def masses(self) -> Float64Array:
        """Particle masses, an ``(n,)`` array, kg."""
    @property
    def springs(self) -> Int64Array:
        """The springs' particles, an ``(m, 2)`` int64 array."""
    @property
    def stiffness(self) -> Float64Array:
        """The springs' stiffness, an ``(m,)`` array, N/m."""
    @property
    def rest_lengths(self) -> Float64Array:
        """The springs' rest lengths, an ``(m,)`` array, m."""
    @property
    def damping(self) -> Float64Array:
        """The springs' axial damping, an ``(m,)`` array, N·s/m."""
    @property
    def pins(self) -> Int64Array:
        """The pinned particles, an int64 array."""
    @property
    def triangles(self) -> Int64Array:
        """The bodies' surface triangles, a ``(t, 3)`` int64 array of
        particles."""
    @property
    def gravity(self) -> Optional[tuple[float, float, float]]:
        """Gravity, m/s², or ``None`` for a scene without."""
    @property
    def air_damping(self) -> Optional[float]:
        """Air damping γ, N·s/m, or ``None``."""
    @property
    def contact_distance(self) -> float:
        """The distance below which contact acts, m."""
    @property
    def obstacles(self) -> list[dict[str, Any]]:
        """The obstacles, each a dict under the keys of a scene file's
        ``[[obstacles]]`` table (what ``Scene.from_arrays`` takes)."""
    def with_stiffness_scale(self, scale: float) -> Scene:
        """The same scene with every spring's stiffness times ``scale``."""

class Simulation:
    """A scene's system stepped by an integrator: ``scene`` a ``Scene``, a
    built-in scene's name, a scene file's path or ``None`` (the default
    scene); ``integrator`` any name of the scene format (default: the
    scene's); ``dt`` the step in s (default: the scene's); and ``settings``
    keyword arguments under the keys of the scene format's
    ``[integrator]`` table (``solver="pcg"``, ``step="quasi-newton"``,
    ``newton_tolerance=1e-6``, ``rtol=…`` for "dormand-prince",
    ``iterations=…`` for "fast-mass-spring"), the library's defaults where
    none is given. Each step releases the GIL."""

    def __init__(
        self,
        scene: SceneLike = None,
        integrator: Optional[str] = None,
        *,
        dt: Optional[float] = None,
        **settings: Setting,
    ) -> None: ...
    def step(self) -> dict[str, Any]:
        """Takes one step of ``dt``; returns its report (see ``report``).
        Raises ``hooke.StepError`` if the step fails, leaving the state as
        it was."""
    def advance(self, t: float) -> dict[str, Any]:
        """Takes steps of ``dt`` until the time reaches ``t`` (the last step
        may end past it by less than a step); returns their reports summed.
        Ctrl-C stops it between two steps with ``KeyboardInterrupt``."""
    def energy(self) -> dict[str, float]:
        """The energy of the state: a dict of ``kinetic``, ``elastic``
        (springs and volume elements), ``gravitational`` and their
        ``total``, J."""
    def reset(self) -> None:
        """Goes back to the scene's initial state at time 0 with a fresh
        integrator."""
    @property
    def report(self) -> Optional[dict[str, Any]]:
        """The last ``step()`` or ``advance()``'s report, or ``None`` before
        the first: ``steps``, the ``time`` reached, ``wall_s`` inside the
        steps, the ``energy`` after (J), and the step reports' counts
        summed (``newton_iterations``, ``linear_iterations``,
        ``linear_solves``, ``accepted_steps`` and ``rejected_steps`` of the
        substeps, ``unconverged_steps``, ``unconverged_solves``,
        ``energy_corrections``, ``force_evaluations``, ``contacts``;
        contact's ``proximity_queries``, ``detection_s`` of collision
        detection inside ``wall_s``, the ``truncated_particles`` that
        per-particle bounds cut and their ``bound_fallbacks`` to the global
        limit) and largest values (``newton_iterations_max``,
        ``newton_residual``, ``linear_residual``, ``energy_excess``,
        ``truncated_particles_max`` in one iteration), and the
        ``linear_solver`` used."""
    @property
    def positions(self) -> Float64Array:
        """Positions, an ``(n, 3)`` float64 array (a copy), m. Setting them
        takes any ``(n, 3)`` array of finite numbers; integrators that carry
        history restart from the new state."""
    @positions.setter
    def positions(self, value: ArrayLike) -> None: ...
    @property
    def velocities(self) -> Float64Array:
        """Velocities, an ``(n, 3)`` float64 array (a copy), m/s; set as
        positions are."""
    @velocities.setter
    def velocities(self, value: ArrayLike) -> None: ...
    @property
    def time(self) -> float:
        """The simulated time, s; settable (moving pins and obstacles are
        where their paths put them at that time)."""
    @time.setter
    def time(self, value: float) -> None: ...
    @property
    def dt(self) -> float:
        """The step, s; settable (positive and finite)."""
    @dt.setter
    def dt(self, value: float) -> None: ...
    @property
    def steps(self) -> int:
        """Steps taken since the start (or the last ``reset()``)."""
    @property
    def particle_count(self) -> int:
        """The number of particles."""
    @property
    def integrator(self) -> str:
        """The integrator's name."""
    @property
    def settings(self) -> dict[str, Setting]:
        """The integrator's settings under the scene format's keys,
        defaults included."""
    @property
    def scene(self) -> Scene:
        """The scene stepped, with this simulation's integrator."""

def builtin_scenes() -> dict[str, str]:
    """The built-in scenes: a dict of each name and a one-line description,
    the default scene first."""

def run(
    scene: SceneLike = None,
    out: Union[str, os.PathLike[str]] = "hooke-out",
    *,
    gif: bool = True,
    usd: bool = True,
    duration: Optional[float] = None,
    preview_time: Optional[float] = None,
    integrator: Optional[str] = None,
    **settings: Setting,
) -> dict[str, Any]:
    """Runs ``scene`` as ``hooke run`` does and writes its files into
    ``out``: the PLY frames, ``preview.png``, ``animation.gif`` (unless
    ``gif`` is false), ``animation.usda`` (unless ``usd`` is false) and
    ``summary.json``. Returns the summary, the dict ``summary.json`` holds.
    ``scene`` is a ``Scene``, a built-in scene's name, a scene file's path
    or ``None`` (the default scene); ``duration`` replaces the scene's,
    ``preview_time`` picks the preview's frame, and ``integrator`` and the
    keyword arguments ``settings`` replace the scene's integrator as in
    ``Simulation``. The GIL is released while it runs; Ctrl-C stops it
    between two steps with ``KeyboardInterrupt``. A run that stops early
    (a step that fails, a state that diverges) raises ``hooke.RunError``
    with the summary as its ``summary`` attribute."""

def stability(
    scene: SceneLike = None,
    *,
    methods: Optional[Sequence[str]] = None,
    stiffness: Optional[Values] = None,
    dt: Optional[Values] = None,
    duration: float = 1.0,
    min_steps: int = 1000,
    energy_bound: float = 10.0,
    limit: bool = False,
    limit_stiffness: float = 1.0,
    scale_stiffness: Optional[float] = None,
    solver: Optional[str] = None,
    pcg_tolerance: Optional[float] = None,
    newton: Optional[int] = None,
    linearized: bool = False,
    shard: Optional[str] = None,
) -> dict[str, Any]:
    """``hooke stability``: which integrators stay stable at which
    stiffness scale and step on ``scene`` (a ``Scene``, a built-in scene's
    name, a scene file's path or ``None`` for the default scene), with the
    command line's options and defaults: ``methods`` (names; default all),
    ``stiffness`` and ``dt`` (numbers, or strings of numbers and ranges
    ``FIRST:LAST:COUNT``), ``duration`` and ``min_steps`` per cell,
    ``energy_bound``, ``limit`` (also search each integrator's largest
    stable step at ``limit_stiffness``), ``scale_stiffness``, the implicit
    methods' ``solver``, ``pcg_tolerance``, ``newton`` and
    ``linearized``, and ``shard`` ("I/N"). Returns the report
    ``stability.json`` holds, its ``cells`` (and ``limits``) as dicts of
    columns: numpy arrays of numbers and booleans, lists of names."""

def accuracy(
    scene: SceneLike = None,
    *,
    methods: Optional[Sequence[str]] = None,
    dt: Optional[Values] = None,
    tolerances: Optional[Values] = None,
    duration: Optional[float] = None,
    frames: int = 10,
    repeat: int = 3,
    reference_dt: Optional[float] = None,
    variants: Optional[Sequence[str]] = None,
    variant_dt: Optional[Values] = None,
    scale_stiffness: Optional[float] = None,
    solver: Optional[str] = None,
    pcg_tolerance: Optional[float] = None,
    newton: Optional[int] = None,
    linearized: bool = False,
    shard: Optional[str] = None,
) -> dict[str, Any]:
    """``hooke accuracy``: each integrator's error against a reference, its
    observed order and its run time on ``scene``, with the command line's
    options and defaults: ``methods``, ``dt`` and ``tolerances`` (numbers
    or strings as in ``stability``; default: chosen from the scene),
    ``duration`` (default: the scene's), ``frames``, ``repeat``,
    ``reference_dt``, ``variants`` (backward Euler's step carried out other
    ways: "newton:1e-2", "quasi-newton:1e-3", "linearized",
    "fast-mass-spring:10"; an empty list for none; default: the command
    line's list when backward Euler is measured), ``variant_dt``, and the
    options every measurement shares (see ``stability``). Returns the
    report ``accuracy.json`` holds, its records as dicts of columns."""

def main(args: Optional[Sequence[str]] = None) -> int:
    """The ``hooke`` command line with the arguments ``args`` (by default
    ``sys.argv[1:]``), printing to the process's standard output and error
    as the ``hooke`` binary does; returns its exit status: 0, 1 for a
    command that failed, 2 for arguments that do not parse."""
