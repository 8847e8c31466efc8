"""hooke: mass-spring simulation with measured integrators.

Scenes come from TOML files or strings, built-in names, or numpy arrays
(:class:`Scene`); a :class:`Simulation` steps one with any integrator of
the scene format, its positions and velocities ``(n, 3)`` float64 arrays
that can be read and set; :func:`run` is ``hooke run`` (frames, pictures,
``animation.usda`` and the summary as a dict), :func:`stability` and
:func:`accuracy` the lab's measurements as dicts of numpy arrays, and
:func:`main` the ``hooke`` command line itself (``python -m hooke``).

Every error is a :class:`HookeError` carrying the command line's message.

>>> import hooke
>>> sim = hooke.Simulation("oscillator", "rk4")
>>> report = sim.advance(1.0)
>>> round(sim.time, 6), report["steps"]
(1.0, 100)
"""

from ._hooke import (
    HookeError,
    RunError,
    Scene,
    SceneError,
    SettingsError,
    Simulation,
    StateError,
    StepError,
    __version__,
    accuracy,
    builtin_scenes,
    main,
    run,
    stability,
)

__all__ = [
    "HookeError",
    "RunError",
    "Scene",
    "SceneError",
    "SettingsError",
    "Simulation",
    "StateError",
    "StepError",
    "__version__",
    "accuracy",
    "builtin_scenes",
    "main",
    "run",
    "stability",
]


def _console() -> int:
    """The ``hooke`` console script: the command line, Ctrl-C ending the
    process at once as it ends the ``hooke`` binary."""
    import signal

    signal.signal(signal.SIGINT, signal.SIG_DFL)
    return main()
