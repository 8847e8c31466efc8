//! [`run`]: a scene stepped from start to end, with its frames, pictures
//! and [`Summary`] written into an output directory as it goes.

use std::fs;
use std::path::{Path, PathBuf};
use std::time::Instant;

use hooke_core::{State, StepError, StepReport, System, Vec3};
use hooke_scenes::{IntegratorSpec, Scene, Timing};

use crate::animation::{AnimationWriter, MAX_GIF_FRAMES};
use crate::bounds::Bounds;
use crate::camera::{Camera, View};
use crate::cli_error::CliError;
use crate::framing::run_bounds;
use crate::mesh::Mesh;
use crate::ply::write_frame;
use crate::render::{Renderer, save_png};
use crate::scene_mesh::{obstacles_at, scene_mesh};
use crate::summary::{Summary, median};

/// The file name of the run summary in the output directory.
pub const SUMMARY_FILE: &str = "summary.json";
/// The file name of the picture of the last frame.
pub const PREVIEW_FILE: &str = "preview.png";
/// The file name of the animation of the frames.
pub const ANIMATION_FILE: &str = "animation.gif";

/// Where a [`run`] writes and what.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RunOptions {
    /// The output directory, created if missing.
    pub out: PathBuf,
    /// Whether to write [`ANIMATION_FILE`].
    pub gif: bool,
    /// Width and height of [`PREVIEW_FILE`], pixels.
    pub preview_size: (u32, u32),
    /// Width and height of the animation's frames, pixels.
    pub gif_size: (u32, u32),
}

impl RunOptions {
    /// Writes everything into `out`: a 960×720 preview and a 480×360
    /// animation.
    ///
    /// ```
    /// let options = hooke_cli::RunOptions::new("hooke-out");
    /// assert!(options.gif);
    /// ```
    #[must_use]
    pub fn new(out: impl Into<PathBuf>) -> Self {
        Self {
            out: out.into(),
            gif: true,
            preview_size: (960, 720),
            gif_size: (480, 360),
        }
    }

    /// The same options with the animation written or not.
    ///
    /// ```
    /// let options = hooke_cli::RunOptions::new("hooke-out").gif(false);
    /// assert!(!options.gif);
    /// ```
    #[must_use]
    pub fn gif(self, gif: bool) -> Self {
        Self { gif, ..self }
    }
}

/// Runs `scene` and writes its output into `options.out`:
///
/// - `frame_00000.ply`, ...: the state before the first step and after
///   every [`Timing::steps_per_frame`]-th step, and the last state if it
///   does not fall on a frame (frames an earlier run left in the directory
///   are removed first);
/// - [`ANIMATION_FILE`]: the frames rendered with a camera fixed before the
///   run from [`run_bounds`], subsampled to at most
///   [`MAX_GIF_FRAMES`](crate::MAX_GIF_FRAMES) pictures that play in about
///   real time;
/// - [`PREVIEW_FILE`]: the last state, rendered larger;
/// - [`SUMMARY_FILE`]: the [`Summary`], which is also returned.
///
/// Each step is timed on its own with [`Instant`]; energy and strain are
/// sampled at the written frames. `progress(done, total)` is called after
/// every step.
///
/// A step that fails (a non-finite state, a solver failure) or leaves a
/// position beyond what a frame file holds (`|x| > f32::MAX`: the run has
/// diverged) ends the run without an error: the last state that can be
/// written is the final frame and the preview, and the summary records the
/// failure in [`Summary::error`] (and, for a state that went non-finite or
/// diverged, `finite: false`).
///
/// # Errors
///
/// [`CliError::InvalidTiming`] and [`CliError::Parameter`] for a scene that
/// cannot be run, [`CliError::Output`] for bodies that cannot be meshed or
/// files that cannot be written, [`CliError::CreateDir`] and
/// [`CliError::WriteSummary`] naming the path that failed.
pub fn run(
    scene: &Scene,
    options: &RunOptions,
    mut progress: impl FnMut(usize, usize),
) -> Result<Summary, CliError> {
    let started = Instant::now();
    check_timing(&scene.timing)?;
    let system = &scene.system;
    let mut integrator = scene.integrator.build()?;
    let mesh = scene_mesh(scene)?;
    prepare_directory(&options.out)?;

    let timing = scene.timing;
    let steps = timing.steps();
    let every = timing.steps_per_frame();
    let bounds = run_bounds(system, timing.duration)
        .unwrap_or_else(|| Bounds::new(Vec3::zeros(), Vec3::zeros()));
    let animation = if options.gif {
        Some(Animation::new(
            &options.out,
            &bounds,
            options.gif_size,
            timing.frame_rate,
            steps / every + 1,
        )?)
    } else {
        None
    };
    let mut state = system.initial_state();
    let mut output = Output {
        system,
        dir: &options.out,
        mesh,
        animation,
        frames: 0,
        last_positions: Vec::new(),
        last_time: 0.0,
        energy_max: f64::NEG_INFINITY,
        max_strain: 0.0,
    };
    let energy_initial = energy(system, &state);
    output.frame(&state)?;

    let mut step_ms = Vec::new();
    let mut total = StepReport::default();
    let mut contacts_max = 0;
    let mut failure = None;
    for step in 1..=steps {
        let start = Instant::now();
        match integrator.step(system, &mut state, timing.dt) {
            Ok(report) => {
                step_ms.push(start.elapsed().as_secs_f64() * 1e3);
                contacts_max = contacts_max.max(report.contacts);
                total += report;
            }
            Err(error) => {
                let non_finite = matches!(
                    error,
                    StepError::NonFinite { .. } | StepError::NonFiniteSystem { .. }
                );
                failure = Some((error.to_string(), non_finite));
                break;
            }
        }
        if let Some(particle) = beyond_frame_range(&state) {
            failure = Some((
                format!(
                    "diverged: particle {particle} is beyond the range of the frame files \
                     (|x| > {:.1e} m) at t = {}",
                    f32::MAX,
                    state.time()
                ),
                true,
            ));
            break;
        }
        if step % every == 0 {
            output.frame(&state)?;
        }
        progress(step, steps);
    }
    let taken = step_ms.len();
    let last_good = beyond_frame_range(&state).is_none();
    if last_good && taken % every != 0 {
        output.frame(&state)?;
    }
    let (shown, time) = if last_good {
        (state.positions(), state.time())
    } else {
        (&output.last_positions[..], output.last_time)
    };
    let camera = Camera::new(
        &bounds,
        options.preview_size.0,
        options.preview_size.1,
        &View::default(),
    )?;
    let picture = Renderer::new(camera).render(&output.mesh, shown, &obstacles_at(system, time))?;
    save_png(&picture, &options.out.join(PREVIEW_FILE))?;
    if let Some(animation) = output.animation.take() {
        animation.writer.finish()?;
    }

    let implicit = matches!(scene.integrator, IntegratorSpec::Implicit { .. });
    let per_step = |count: usize| implicit.then(|| mean(count, taken));
    let summary = Summary {
        scene: scene.name.clone(),
        integrator: integrator.name().to_owned(),
        dt: timing.dt,
        steps: taken,
        steps_planned: steps,
        time: state.time(),
        frames: output.frames,
        particles: system.particle_count(),
        springs: system.springs().len(),
        wall_s: started.elapsed().as_secs_f64(),
        step_ms_median: median(&step_ms),
        step_ms_max: step_ms.iter().copied().fold(0.0, f64::max),
        linear_iterations_mean: per_step(total.linear_iterations),
        newton_iterations_mean: per_step(total.newton_iterations),
        linear_solves: total.linear_solves,
        unconverged_solves: total.unconverged_solves,
        contacts_max,
        energy_initial,
        energy_final: energy(system, &state),
        energy_max: output.energy_max,
        max_strain: output.max_strain,
        finite: !failure.as_ref().is_some_and(|(_, non_finite)| *non_finite),
        error: failure.map(|(message, _)| message),
        out: options.out.clone(),
    };
    write_json(&options.out.join(SUMMARY_FILE), &summary)?;
    Ok(summary)
}

/// Checks that a run of `timing` has a step, a duration and a frame rate
/// it can use.
pub(crate) fn check_timing(timing: &Timing) -> Result<(), CliError> {
    let fail = |reason| Err(CliError::InvalidTiming { reason });
    if !(timing.dt.is_finite() && timing.dt > 0.0) {
        return fail("dt must be positive and finite");
    }
    if !(timing.duration.is_finite() && timing.duration >= 0.0) {
        return fail("duration must be finite and non-negative");
    }
    if !(timing.frame_rate.is_finite() && timing.frame_rate > 0.0) {
        return fail("frame_rate must be positive and finite");
    }
    Ok(())
}

/// Creates `dir` if needed and removes the frames an earlier run left in it.
fn prepare_directory(dir: &Path) -> Result<(), CliError> {
    let failed = |source| CliError::CreateDir {
        path: dir.to_path_buf(),
        source,
    };
    fs::create_dir_all(dir).map_err(failed)?;
    for entry in fs::read_dir(dir).map_err(failed)? {
        let path = entry.map_err(failed)?.path();
        let is_frame = path
            .file_name()
            .and_then(|name| name.to_str())
            .and_then(|name| name.strip_prefix("frame_")?.strip_suffix(".ply"))
            .is_some_and(|digits| digits.len() >= 5 && digits.bytes().all(|b| b.is_ascii_digit()));
        if is_frame && path.is_file() {
            fs::remove_file(&path).map_err(failed)?;
        }
    }
    Ok(())
}

/// Writes `value` to `path` as indented JSON: `summary.json` and the lab's
/// reports.
pub(crate) fn write_json(path: &Path, value: &impl serde::Serialize) -> Result<(), CliError> {
    let failed = |source| CliError::WriteSummary {
        path: path.to_path_buf(),
        source,
    };
    let text = serde_json::to_string_pretty(value).map_err(|e| failed(e.into()))?;
    fs::write(path, text + "\n").map_err(failed)
}

/// Total mechanical energy of `state`, J.
fn energy(system: &System, state: &State) -> f64 {
    system.energy(state).map_or(f64::NAN, |e| e.total())
}

/// The first particle whose position a frame file cannot hold: not finite,
/// or beyond the largest single-precision number.
fn beyond_frame_range(state: &State) -> Option<usize> {
    let limit = f64::from(f32::MAX);
    state
        .positions()
        .iter()
        .position(|p| !p.iter().all(|c| c.abs() <= limit))
}

fn mean(count: usize, steps: usize) -> f64 {
    if steps == 0 {
        0.0
    } else {
        count as f64 / steps as f64
    }
}

/// The animation being written and the renderer of its pictures.
struct Animation {
    writer: AnimationWriter,
    renderer: Renderer,
    /// Every how many written frames one is pictured.
    stride: usize,
}

impl Animation {
    /// An animation of about `frames` frames at `frame_rate` per simulated
    /// second, subsampled here (rather than in the writer) so that frames
    /// left out are not rendered at all.
    fn new(
        dir: &Path,
        bounds: &Bounds,
        (width, height): (u32, u32),
        frame_rate: f64,
        frames: usize,
    ) -> Result<Self, CliError> {
        let stride = frames.div_ceil(MAX_GIF_FRAMES).max(1);
        let camera = Camera::new(bounds, width, height, &View::default())?;
        let writer = AnimationWriter::new(
            &dir.join(ANIMATION_FILE),
            width,
            height,
            frame_rate / stride as f64,
            frames.div_ceil(stride),
        )?;
        Ok(Self {
            writer,
            renderer: Renderer::new(camera),
            stride,
        })
    }
}

/// The files written while a run goes, and what is sampled at each frame.
struct Output<'a> {
    system: &'a System,
    dir: &'a Path,
    mesh: Mesh,
    animation: Option<Animation>,
    frames: usize,
    /// Positions and time of the last written frame.
    last_positions: Vec<Vec3>,
    last_time: f64,
    energy_max: f64,
    max_strain: f64,
}

impl Output<'_> {
    /// Writes `state` as the next frame, pictures it for the animation if it
    /// is due, and samples its energy and strain.
    fn frame(&mut self, state: &State) -> Result<(), CliError> {
        let positions = state.positions();
        write_frame(self.dir, self.frames, &self.mesh, positions)?;
        if let Some(animation) = &mut self.animation {
            if self.frames % animation.stride == 0 {
                let obstacles = obstacles_at(self.system, state.time());
                let picture = animation
                    .renderer
                    .render(&self.mesh, positions, &obstacles)?;
                animation.writer.push(&picture)?;
            }
        }
        self.frames += 1;
        self.last_positions.clear();
        self.last_positions.extend_from_slice(positions);
        self.last_time = state.time();
        self.energy_max = self.energy_max.max(energy(self.system, state));
        if let Ok(strain) = self.system.max_strain(state) {
            self.max_strain = self.max_strain.max(strain);
        }
        Ok(())
    }
}
