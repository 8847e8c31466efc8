//! The `hooke` command and its output layer: running a scene and writing
//! the files of the run into its `--out DIR`.
//!
//! [`run`] steps a [`Scene`](hooke_scenes::Scene) from start to end with
//! the integrator it names, timing every step, and writes:
//!
//! | file | written by | format |
//! | --- | --- | --- |
//! | `frame_00000.ply`, `frame_00001.ply`, ... | [`write_frame`] | binary little-endian PLY, one file per written frame ([`frame_file_name`]) |
//! | `preview.png` | [`Renderer::render`] + [`save_png`] | an RGBA PNG picture of one frame |
//! | `animation.gif` | [`AnimationWriter`] | a looping GIF of the rendered frames, at most [`MAX_GIF_WIDTH`] pixels wide and about [`MAX_GIF_FRAMES`] frames long |
//! | `summary.json` | [`run`] | the [`Summary`]: what ran, how long each step took, solver work, energy, strain, whether the state stayed finite |
//!
//! The bodies of a scene become one [`Mesh`] ([`scene_mesh`]) and its
//! obstacles drawable [`Shape`]s ([`obstacles_at`]); the camera frames
//! [`run_bounds`] for the whole run.
//!
//! # PLY frames
//!
//! The topology is given once as a [`Mesh`] (vertex count, triangles,
//! edges); each frame then passes only its positions. A frame file is
//! readable by Blender, MeshLab and ParaView. Its header, for a mesh of `N`
//! vertices, `F` triangles and `E` edges, is
//!
//! ```text
//! ply
//! format binary_little_endian 1.0
//! comment written by hooke
//! element vertex N
//! property float x
//! property float y
//! property float z
//! element face F
//! property list uchar int vertex_indices
//! element edge E
//! property int vertex1
//! property int vertex2
//! end_header
//! ```
//!
//! followed by the `N` positions as three little-endian `f32` each, the `F`
//! faces as the byte `3` and three little-endian `i32` indices each, and the
//! `E` edges as two little-endian `i32` indices each. The `face` lines are
//! left out when the mesh has no triangles (ropes, lattices) and the `edge`
//! lines when it has no edges. Positions are rounded from `f64` to `f32`,
//! the precision those tools read.
//!
//! # Pictures
//!
//! The [`Renderer`] draws a frame with a perspective [`Camera`]: triangles
//! flat-shaded (Lambert with ambient light, two-sided), edges as thin lines,
//! and the obstacles of the scene as [`Shape`]s: spheres, capsules and boxes
//! shaded like the bodies, and infinite planes as a checkered floor around
//! the scene. The camera looks at the centre of a [`Bounds`] from a [`View`]
//! (by default azimuth 35°, elevation 25°, +y up) at the distance where the
//! scene fills 80 % of the shorter image side; framing the union of the
//! first and last frames' bounds keeps it still over a run.
//!
//! ```
//! use hooke_cli::{Bounds, Camera, Mesh, Renderer, View};
//! use hooke_core::Vec3;
//! let mesh = Mesh::new(3, vec![[0, 1, 2]], Vec::new())?;
//! let positions = [Vec3::zeros(), Vec3::x(), Vec3::y()];
//! let bounds = Bounds::of_scene(&positions, &[]).expect("three points");
//! let camera = Camera::new(&bounds, 320, 240, &View::default())?;
//! let picture = Renderer::new(camera).render(&mesh, &positions, &[])?;
//! assert_eq!((picture.width(), picture.height()), (320, 240));
//! # Ok::<(), hooke_cli::OutputError>(())
//! ```
//!
//! # The command
//!
//! [`main`] is the `hooke` binary; [`run_cli`] is the same with its
//! arguments and output streams passed in, so it can be tested in-process.
//!
//! ```text
//! hooke [run] [SCENE.toml] [--builtin NAME] [--out DIR] [--no-gif] [--duration S] [--quiet]
//! hooke scenes                 # the built-in scenes
//! hooke check SCENE.toml       # validate a scene file and say what it holds
//! hooke stability [SCENE.toml] [--builtin NAME] [--methods A,B] [--stiffness VALUES]
//!                 [--dt VALUES] [--duration S] [--min-steps N] [--energy-bound B]
//!                 [--limit] [--limit-stiffness S] [--out DIR] [--quiet]
//! hooke accuracy  [SCENE.toml] [--builtin NAME] [--methods A,B] [--dt VALUES]
//!                 [--tolerances VALUES] [--duration S] [--frames N] [--repeat N]
//!                 [--reference-dt S] [--out DIR] [--quiet]
//! ```
//!
//! `VALUES` is a comma-separated list of numbers and log-spaced ranges
//! `FIRST:LAST:COUNT`. Both lab commands also take `--scale-stiffness S`
//! (every spring's stiffness times `S` first), `--solver cholesky|pcg` and
//! `--newton N` (the implicit methods' solver and Newton iterations). They
//! run `hooke-lab`'s measurements and write into `--out DIR`:
//!
//! | command | files |
//! | --- | --- |
//! | `hooke stability` | `stability.json` (the `StabilityReport`: every cell, and with `--limit` each integrator's largest stable step), `stability.png` (one stable/unstable map per integrator over stiffness × step, with the line `h·ω_max = 2`) |
//! | `hooke accuracy` | `accuracy.json` (the `AccuracyReport`: the reference, every run's error, wall time and work, each integrator's observed order), `work_precision.png` (error against wall time), `convergence.png` (error against step) |
//!
//! # Errors
//!
//! The output layer returns [`OutputError`]s, the command [`CliError`]s
//! (which wrap them); I/O failures name the
//! file concerned, and bad input (indices out of range, non-finite
//! positions, degenerate obstacles) names the offending item. Nothing here
//! panics on user input.

mod animation;
mod bounds;
mod camera;
mod cli;
mod cli_error;
mod describe;
mod error;
mod frames;
mod framing;
mod lab;
mod mesh;
mod ply;
mod render;
mod runner;
mod scene_mesh;
mod shape;
mod step_record;
mod style;
mod summary;
mod tessellate;

pub use animation::{AnimationWriter, MAX_GIF_FRAMES, MAX_GIF_WIDTH};
pub use bounds::Bounds;
pub use camera::{Camera, MAX_IMAGE_SIDE, Projected, View};
pub use cli::{DEFAULT_SCENE, main, run_cli};
pub use cli_error::CliError;
pub use describe::describe;
pub use error::{OutputError, Primitive};
pub use framing::run_bounds;
pub use mesh::Mesh;
pub use ply::{frame_file_name, write_frame, write_ply};
pub use render::{Renderer, save_png};
pub use runner::{ANIMATION_FILE, PREVIEW_FILE, RunOptions, SUMMARY_FILE, run};
pub use scene_mesh::{obstacles_at, scene_mesh};
pub use shape::Shape;
pub use style::{Rgb, Style};
pub use summary::Summary;
pub use tiny_skia::Pixmap;
