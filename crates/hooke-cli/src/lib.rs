//! The `hooke` command: running a scene and writing the files of the run
//! into its `--out DIR`, and the lab's commands.
//!
//! [`run`] steps a [`Scene`](hooke_scenes::Scene) from start to end with
//! the integrator it names, as a [`Simulation`](hooke_core::Simulation)
//! whose observers write:
//!
//! | file | format |
//! | --- | --- |
//! | `frame_00000.ply`, `frame_00001.ply`, ... | binary little-endian PLY, one file per written frame (see `hooke-viz`) |
//! | `preview.png` | an RGBA PNG picture of the frame where the bodies rest on the obstacles |
//! | `animation.gif` | a looping GIF of the rendered frames |
//! | `animation.usda` | the frames as one USD animation, for Blender, Houdini and usdview: every body a mesh (curves for a rope) with its points sampled at every frame, the obstacles as their shapes (see `hooke_viz::usd`) |
//! | `summary.json` | the [`Summary`]: what ran, how long each step took, solver work, energy, strain, how close the collision surfaces came, how many volume elements turned inside out, whether the state stayed finite |
//!
//! The pictures and files themselves are drawn and written by `hooke-viz`.
//! This crate holds the `hooke` binary, so the library facade `hooke`
//! does not depend on the command line: `hooke` alone depends on 109
//! crates, without clap, indicatif, tiny-skia, gif and font8x8 (`cargo
//! tree -p hooke -e normal`), against 151 when the facade held the binary.
//! `default-members` in the workspace manifest makes `cargo run` from the
//! root run this binary; a `cli` feature of the facade was the alternative,
//! but it would have kept the binary, and with it the command line's
//! dependencies, in the package that library users depend on.
//!
//! # The command
//!
//! [`main`] is the `hooke` binary; [`run_cli`] is the same with its
//! arguments and output streams passed in, so it can be tested in-process.
//!
//! ```text
//! hooke [run] [SCENE.toml] [--builtin NAME] [--out DIR] [--no-gif] [--no-usd] [--duration S] [--preview-time S] [--quiet]
//! hooke scenes                 # the built-in scenes
//! hooke check SCENE.toml       # validate a scene file and say what it holds
//! hooke stability [SCENE.toml] [--builtin NAME] [--methods A,B] [--stiffness VALUES]
//!                 [--dt VALUES] [--duration S] [--min-steps N] [--energy-bound B]
//!                 [--limit] [--limit-stiffness S] [--out DIR] [--quiet]
//! hooke accuracy  [SCENE.toml] [--builtin NAME] [--methods A,B] [--dt VALUES]
//!                 [--tolerances VALUES] [--duration S] [--frames N] [--repeat N]
//!                 [--reference-dt S] [--out DIR] [--quiet]
//! hooke merge DIR... [--out DIR]   # combine the partial reports of --shard runs
//! ```
//!
//! Both lab commands also take `--shard I/N` (see below).
//! `VALUES` is a comma-separated list of numbers and log-spaced ranges
//! `FIRST:LAST:COUNT`. Both lab commands also take `--scale-stiffness S`
//! (every spring's stiffness times `S` first), `--solver cholesky|pcg` and
//! `--newton N` (the implicit methods' solver and Newton iterations). They
//! run `hooke-lab`'s measurements and write into `--out DIR`:
//!
//! | command | files |
//! | --- | --- |
//! | `hooke stability` | `stability.json` (the `StabilityReport`: every cell, and with `--limit` each integrator's largest stable step), `stability.csv` (the cells), `stability.png` and `stability.svg` (one stable/unstable map per integrator over stiffness × step, with the line `h·ω_max = 2`) |
//! | `hooke accuracy` | `accuracy.json` (the `AccuracyReport`: the reference, every run's error, wall time and work, each integrator's observed order), `accuracy.csv` (the runs), `work_precision.png`/`.svg` (error against wall time), `convergence.png`/`.svg` (error against step) |
//! | `… --shard I/N` | `stability.shard-I-of-N.json` or `accuracy.shard-I-of-N.json`, with its CSV: part `I` of `N` of the sweep, the jobs numbered `k ≡ I (mod N)` |
//! | `hooke merge DIR…` | from the partial reports found in the directories, the files of the unsharded command |
//!
//! # Collision surfaces
//!
//! For a scene with collision surfaces (see `docs/scene-format.md`),
//! `summary.json` also holds `contact_distance`, `close_pairs_max`,
//! `smallest_distance`, `intersecting_triangle_pairs` and, by the bodies
//! they belong to, `intersections` ([`Summary`]), and `hooke run` prints
//! them as `contact: at most N close pairs, smallest distance D m (contact
//! distance d̂ m), K intersecting triangle pairs at the end`, followed where
//! K is not 0 by the bodies, e.g. `(cube with itself: 96)`. An integrator that cannot keep surfaces apart (every one but
//! backward Euler and BDF2) fails on a scene whose surfaces collide at its
//! first step: the command exits with status 1 and `summary.json`'s
//! `error` says why. The lab commands run such integrators on the scene
//! without self-collision when that leaves no surfaces colliding (one
//! cloth), and otherwise report their stability cells not applicable
//! (`"applicable": false`, the reason in `stopped`); `hooke accuracy`
//! measures everything without self-collision, since its reference is
//! classical Runge–Kutta, and refuses a scene whose bodies collide with
//! each other. Either prints what it did once, as `note: …`, and writes it
//! in its report's `note`.
//!
//! # Volume elements
//!
//! For a scene with volume elements (its lattices, tet meshes and layered
//! bodies, see `hooke_scenes::Volume`), `summary.json` also holds
//! `inverted_elements_max`, the most elements inverted at once (volume
//! ratio `J = V/V₀ ≤ 0`), and `volume_ratio_min`, the smallest `J`
//! reached, over the initial state and every step ([`Summary`]); both are
//! `null` without volume elements. `hooke run` prints them as `volume: at
//! most N elements inverted at once, smallest volume ratio J`, and `hooke
//! check` gives each body's elements and their modulus.
//!
//! # Errors
//!
//! Every command returns a [`CliError`] (wrapping the output layer's
//! errors), naming the file, option or value at fault. Nothing here panics
//! on user input.

mod cli;
mod cli_error;
mod describe;
mod frames;
mod lab;
mod pictures;
mod run_options;
mod runner;
mod scene_source;
mod settings_keys;
mod step_record;
mod summary;
mod surface_record;
mod usd_file;
mod volume_record;

pub use cli::{main, run_cli};
pub use cli_error::CliError;
pub use describe::describe;
pub use run_options::{ANIMATION_FILE, PREVIEW_FILE, RunOptions, SUMMARY_FILE, USD_FILE};
pub use runner::run;
pub use scene_source::DEFAULT_SCENE;
pub use summary::{SolverName, Summary};
