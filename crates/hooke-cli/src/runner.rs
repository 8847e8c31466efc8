//! [`run`]: a scene stepped from start to end by a [`Simulation`] whose
//! observers write its frames, pictures and [`Summary`] into an output
//! directory as it goes.

use std::fs;
use std::path::Path;
use std::time::{Duration, Instant};

use hooke_core::collision::intersect::intersecting_triangle_pairs_by_surface;
use hooke_core::{
    EnergyLog, Observer, Simulation, State, StepError, StepReport, StrainLog, System, Vec3,
};
use hooke_lab::EnergyBudget;
use hooke_scenes::{IntegratorSpec, Scene, Timing};
use hooke_viz::{run_bounds, scene_mesh};

use crate::cli_error::CliError;
use crate::frames::FrameWriter;
use crate::pictures::write_pictures;
use crate::run_options::{RunOptions, SUMMARY_FILE};
use crate::step_record::StepRecord;
use crate::summary::{Intersections, Summary, median};
use crate::surface_record::SurfaceRecord;
use crate::usd_file::write_usd;
use crate::volume_record::VolumeRecord;

/// Runs `scene` and writes its output into `options.out`:
///
/// - `frame_00000.ply`, ...: the state before the first step and after
///   every [`Timing::steps_per_frame`]-th step, and the last state if it
///   does not fall on a frame (frames an earlier run left in the directory
///   are removed first), written as the run goes;
/// - [`PREVIEW_FILE`](crate::PREVIEW_FILE): the frame that shows the bodies resting on the
///   obstacles — of the frames with at least half the run's most
///   particle–obstacle contacts, the one with the least kinetic energy
///   (without contacts, the last frame), or with
///   [`RunOptions::preview_time`] the frame nearest that time — recorded
///   in [`Summary::preview_frame`];
/// - [`ANIMATION_FILE`](crate::ANIMATION_FILE): the frames subsampled to at most
///   [`MAX_GIF_FRAMES`](hooke_viz::MAX_GIF_FRAMES) pictures that play in
///   about real time;
/// - [`USD_FILE`](crate::USD_FILE) (unless [`RunOptions::usd`] is off):
///   every written frame in one USD animation, read back from the frame
///   files after the run;
/// - [`SUMMARY_FILE`]: the [`Summary`], which is also returned.
///
/// Both pictures are drawn after the run, from the frame files, by one
/// camera framing the bodies at the preview frame with the obstacles (for
/// a run without contacts, every frame's bodies), so the animation shows
/// the bodies falling into the place where they come to rest. A particle
/// is in contact when it lies within 0.2 % of the scene's size (the radius
/// of [`run_bounds`]) of an obstacle's surface.
///
/// The run is a [`Simulation`] with observers: the frame writer, a record
/// of every step's wall time and contacts, a record of how close the
/// collision surfaces came after every step (see
/// [`Summary::close_pairs_max`]), a record of the volume elements
/// inverted after every step ([`Summary::inverted_elements_max`]), an
/// [`EnergyLog`] and a [`StrainLog`] sampled at the written frames, and
/// `progress`, the caller's (a progress bar, or a check for an interrupt),
/// called after every step; it may stop the run (`ControlFlow::Break`),
/// which then ends as if that step were its last. For a system with
/// collision surfaces the last state's intersecting triangles are counted,
/// in all and by the bodies they belong to
/// ([`Summary::intersecting_triangle_pairs`], [`Summary::intersections`]).
/// The wall time spent writing frames, pictures and the USD animation is
/// [`Summary::output_s`].
///
/// A step that fails (a non-finite state, a solver failure) or leaves a
/// position beyond what a frame file holds (`|x| > f32::MAX`: the run has
/// diverged) ends the run without an error: the last state that can be
/// written is the final frame, the pictures are drawn from the frames
/// written, and the summary records the
/// failure in [`Summary::error`] (and, for a state that went non-finite or
/// diverged, `finite: false`).
///
/// # Errors
///
/// [`CliError::InvalidTiming`] and [`CliError::Parameter`] for a scene that
/// cannot be run (or a preview time that is negative or not finite), [`CliError::Output`] for bodies that cannot be meshed or
/// files that cannot be written, [`CliError::CreateDir`] and
/// [`CliError::WriteSummary`] naming the path that failed.
pub fn run(
    scene: &Scene,
    options: &RunOptions,
    progress: &mut dyn Observer,
) -> Result<Summary, CliError> {
    let started = Instant::now();
    check_timing(&scene.timing)?;
    if options
        .preview_time
        .is_some_and(|t| !(t.is_finite() && t >= 0.0))
    {
        return Err(CliError::InvalidTiming {
            reason: "the preview time must be finite and non-negative",
        });
    }
    let system = &scene.system;
    let mut integrator = scene.integrator.build()?;
    let mesh = scene_mesh(scene)?;
    prepare_directory(&options.out)?;

    let timing = scene.timing;
    let steps = timing.steps();
    let every = timing.steps_per_frame();
    let size = run_bounds(system, timing.duration).map_or(0.0, |b| b.radius());
    let mut frames = FrameWriter::new(&options.out, mesh, CONTACT_DISTANCE * size);
    let mut record = StepRecord::default();
    let mut surfaces = SurfaceRecord::default();
    let mut volumes = VolumeRecord::default();
    let (mut energy, mut strain) = (EnergyLog::default(), StrainLog::default());
    let mut budget = EnergyBudget::new(system);
    let mut state = system.initial_state();
    let run = Simulation::new(system, &mut integrator)
        .observe(1, &mut record)
        .observe(1, &mut budget)
        .observe(1, &mut surfaces)
        .observe(1, &mut volumes)
        .observe(every, &mut frames)
        .observe(every, &mut energy)
        .observe(every, &mut strain)
        .observe(1, progress)
        .run_to_end(&mut state, timing.dt, steps);
    let (mesh, frames, frames_wall) = frames.into_result()?;
    let pictures = write_pictures(
        &options.out,
        &mesh,
        system,
        &frames,
        timing.frame_rate,
        options,
    )?;
    let usd = if options.usd && !frames.is_empty() {
        write_usd(&options.out, scene, &mesh, &frames)?
    } else {
        Duration::ZERO
    };
    let output = frames_wall + pictures.map_or(Duration::ZERO, |p| p.wall) + usd;

    let failure = match (run.failure(), record.diverged.take()) {
        (Some(error), _) => Some((
            error.to_string(),
            matches!(
                error,
                StepError::NonFinite { .. } | StepError::NonFiniteSystem { .. }
            ),
        )),
        (None, Some(diverged)) => Some((diverged, true)),
        (None, None) => None,
    };
    let taken = run.steps;
    let total = run.report;
    let implicit_settings = match scene.integrator {
        IntegratorSpec::Implicit(settings) => Some(settings),
        _ => None,
    };
    let implicit = implicit_settings.is_some();
    let per_step = |count: usize| implicit.then(|| mean(count, taken));
    let energies = energy.samples();
    let (mut energy_gain, energy_gain_time) = budget.max_gain();
    if energy_gain == f64::NEG_INFINITY {
        // The run stopped before its first step: it gained nothing.
        energy_gain = 0.0;
    }
    let warnings = warnings(&total, &record, &budget);
    let has_surfaces = system.surface_count() > 0;
    let finite_end = state
        .positions()
        .iter()
        .all(|x| x.iter().all(|c| c.is_finite()));
    let intersections =
        (has_surfaces && finite_end).then(|| intersections(scene, state.positions()));
    let summary = Summary {
        scene: scene.name.clone(),
        integrator: integrator.name().to_owned(),
        implicit_settings,
        dt: timing.dt,
        steps: taken,
        steps_planned: steps,
        time: state.time(),
        frames: frames.len(),
        preview_frame: pictures.map(|p| p.preview),
        preview_time: pictures.map(|p| p.preview_time),
        particles: system.particle_count(),
        springs: system.springs().len(),
        wall_s: started.elapsed().as_secs_f64(),
        simulation_s: record.step_ms.iter().sum::<f64>() * 1e-3,
        output_s: output.as_secs_f64(),
        step_ms_median: median(&record.step_ms),
        step_ms_max: record.step_ms.iter().copied().fold(0.0, f64::max),
        linear_iterations_mean: per_step(total.linear_iterations),
        newton_iterations_mean: per_step(total.newton_iterations),
        linear_solves: total.linear_solves,
        linear_solver: (!total.linear_solver.is_empty()).then_some(total.linear_solver),
        unconverged_solves: total.unconverged_solves,
        substeps: total.accepted_steps,
        rejected_steps: total.rejected_steps,
        newton_iterations_max: implicit.then_some(total.newton_iterations_max),
        newton_residual_max: implicit.then_some(total.newton_residual),
        unconverged_steps: total.unconverged_steps,
        energy_corrections: total.energy_corrections,
        energy_excess_max: implicit.then_some(total.energy_excess),
        energy_gain,
        energy_gain_time,
        warnings,
        proximity_queries: implicit.then_some(total.proximity_queries),
        detection_share: implicit
            .then(|| total.detection_seconds / (record.step_ms.iter().sum::<f64>() * 1e-3)),
        truncated_particles_mean: implicit
            .then(|| total.truncated_particles as f64 / total.newton_iterations.max(1) as f64),
        truncated_particles_max: implicit.then_some(total.truncated_particles_max),
        bound_fallbacks: implicit.then_some(total.bound_fallbacks),
        contacts_max: record.contacts_max,
        contact_distance: has_surfaces.then(|| system.contact_distance()),
        close_pairs_max: has_surfaces.then_some(surfaces.close_pairs_max),
        smallest_distance: surfaces.smallest_distance,
        intersecting_triangle_pairs: intersections
            .as_ref()
            .map(|all| all.iter().map(|i| i.pairs).sum()),
        intersections,
        inverted_elements_max: volumes.inverted_max,
        volume_ratio_min: volumes.smallest_ratio,
        energy_initial: energies.first().map_or(f64::NAN, |s| s.energy.total()),
        energy_final: energy_of(system, &state),
        energy_max: energies
            .iter()
            .map(|s| s.energy.total())
            .fold(f64::NEG_INFINITY, f64::max),
        max_strain: strain.max(),
        finite: !failure.as_ref().is_some_and(|(_, non_finite)| *non_finite),
        error: failure.map(|(message, _)| message),
        out: options.out.clone(),
    };
    write_json(&options.out.join(SUMMARY_FILE), &summary)?;
    Ok(summary)
}

/// The distance from an obstacle within which a particle counts as in
/// contact, as a fraction of the radius of the scene's [`run_bounds`].
const CONTACT_DISTANCE: f64 = 2e-3;

/// The largest energy gain, relative to `E(0) + max W`, that a run may
/// show without a warning: rounding, and the implicit methods' own energy
/// test (relative 1e-9 per step), stay far below it.
pub const ENERGY_GAIN_WARNING: f64 = 1e-6;

/// The warning lines of a run whose steps summed to `total`: steps accepted
/// unconverged, linear solves stopped at their cap, energy removed by the
/// last resort or gained beyond [`ENERGY_GAIN_WARNING`].
fn warnings(total: &StepReport, record: &StepRecord, budget: &EnergyBudget) -> Vec<String> {
    let mut lines = Vec::new();
    if let Some((time, residual)) = record.first_unconverged {
        lines.push(format!(
            "{} steps did not converge, the first ending at t = {time:.4} s with Newton \
             residual {residual:.2e}; `strict = true` in [integrator] makes this an error",
            total.unconverged_steps
        ));
    }
    if let Some((time, residual)) = record.first_capped_solve {
        lines.push(format!(
            "{} linear solves stopped at their iteration cap, the first in the step ending \
             at t = {time:.4} s with relative residual {residual:.2e}",
            total.unconverged_solves
        ));
    }
    if total.energy_corrections > 0 {
        lines.push(format!(
            "{} steps gained energy at their smallest substep and had it removed from the \
             kinetic energy, at most {:.3e} J",
            total.energy_corrections, total.energy_excess
        ));
    }
    let (gain, time) = budget.max_gain();
    let allowance = budget.allowance();
    if gain > ENERGY_GAIN_WARNING * allowance.abs() {
        lines.push(format!(
            "energy rose {gain:.3e} J above its initial value plus the work of gravity, \
             pins and the system's own terms ({allowance:.3e} J) at t = {time:.4} s"
        ));
    }
    lines
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
fn energy_of(system: &System, state: &State) -> f64 {
    system.energy(state).map_or(f64::NAN, |e| e.total())
}

fn mean(count: usize, steps: usize) -> f64 {
    if steps == 0 {
        0.0
    } else {
        count as f64 / steps as f64
    }
}

/// The intersecting triangle pairs of `scene`'s surfaces at `positions`, by
/// the bodies the surfaces belong to (the body holding a surface's first
/// triangle's first particle; `surface g` for a surface no body places).
fn intersections(scene: &Scene, positions: &[Vec3]) -> Vec<Intersections> {
    let mesh = scene.system.surfaces();
    let mut names: Vec<Option<String>> = vec![None; scene.system.surface_count()];
    for (t, triangle) in mesh.triangles().iter().enumerate() {
        let name = &mut names[mesh.triangle_group(t)];
        if name.is_none() {
            *name = scene
                .bodies
                .iter()
                .find(|b| b.placement.range().contains(&triangle[0]))
                .map(|b| b.name.clone());
        }
    }
    let name = |g: usize| names[g].clone().unwrap_or_else(|| format!("surface {g}"));
    intersecting_triangle_pairs_by_surface(mesh, positions)
        .into_iter()
        .map(|((g, h), pairs)| Intersections {
            bodies: [name(g), name(h)],
            pairs,
            collide: mesh.collides(g, h),
        })
        .collect()
}
