//! The Python package `hooke`: the library and the command line for
//! Python, with numpy arrays in and out. This crate is its extension
//! module, `hooke._hooke`, which maturin builds into the package (see
//! `pyproject.toml`; `python/hooke/` holds the package's Python files and
//! type stubs). The library crates know nothing of Python.
//!
//! | Python | what it is |
//! | --- | --- |
//! | `hooke.Scene` | a scene: from a TOML file or string, a built-in name, or arrays (positions, masses, springs, pins, triangles, obstacles) |
//! | `hooke.Simulation` | a scene stepped by any integrator of the scene format, the implicit settings as keyword arguments; positions and velocities as `(n, 3)` float64 arrays, read and set |
//! | `hooke.run` | `hooke run`: the frames, pictures, `animation.usda` and the summary, returned as the dict `summary.json` holds |
//! | `hooke.stability`, `hooke.accuracy` | the lab's measurements as dicts, records as columns of numpy arrays |
//! | `hooke.main` | the `hooke` command line itself (`python -m hooke`) |
//! | `hooke.HookeError` … | the exceptions, each carrying the command line's message |
//!
//! Every step runs with the GIL released, so other Python threads run
//! meanwhile, and a long run checks for Ctrl-C between its steps
//! (`KeyboardInterrupt`). One `Simulation.step()` is one call of the
//! integrator's step on the same system and state as `hooke run` steps:
//! the same numbers to the last bit.

mod convert;
mod errors;
mod integrator;
mod jobs;
mod lab;
mod obstacles;
mod scene;
mod scene_arrays;
mod simulation;

use pyo3::prelude::*;

/// The extension module `hooke._hooke`; the package `hooke` re-exports
/// everything in it.
#[pymodule]
fn _hooke(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    errors::register(m)?;
    m.add_class::<scene::Scene>()?;
    m.add_class::<simulation::Simulation>()?;
    m.add_function(wrap_pyfunction!(scene::builtin_scenes, m)?)?;
    m.add_function(wrap_pyfunction!(jobs::run, m)?)?;
    m.add_function(wrap_pyfunction!(jobs::main, m)?)?;
    m.add_function(wrap_pyfunction!(lab::stability, m)?)?;
    m.add_function(wrap_pyfunction!(lab::accuracy, m)?)?;
    Ok(())
}
