//! The runs of an accuracy measurement: the reference, the jobs and the
//! timed runs that measure each job's error.

use std::ops::ControlFlow;

use hooke_core::{
    Integrator, ObserveFn, Observer, ParameterError, Run as Simulated, Simulation, State, StepInfo,
    System,
};

use super::reference::{
    AxialOscillator, Checkpoints, REFERENCE_METHOD, numerical, rms, steps_per_interval,
};
use super::{AccuracyOptions, ReferenceChoice, ReferenceKind, ReferenceReport, Run};
use crate::{LabError, Method};

/// Every run of `options`, by method, then step or tolerance, with
/// checkpoints `interval` apart.
pub(super) fn jobs(options: &AccuracyOptions, interval: f64) -> Vec<Job> {
    options
        .methods
        .iter()
        .flat_map(|&method| -> Vec<Job> {
            if method.is_fixed_step() {
                options
                    .dts
                    .iter()
                    .map(|&dt| {
                        let per_frame = steps_per_interval(interval, dt);
                        Job {
                            method,
                            dt: Some(dt),
                            tolerance: None,
                            per_frame,
                            step: interval / per_frame as f64,
                        }
                    })
                    .collect()
            } else {
                options
                    .tolerances
                    .iter()
                    .map(|&tolerance| Job {
                        method,
                        dt: None,
                        tolerance: Some(tolerance),
                        per_frame: 1,
                        step: interval,
                    })
                    .collect()
            }
        })
        .collect()
}

/// A run to make.
#[derive(Debug, Clone, Copy)]
pub(super) struct Job {
    method: Method,
    dt: Option<f64>,
    tolerance: Option<f64>,
    per_frame: usize,
    step: f64,
}

/// The reference's positions at the checkpoints, and its report.
pub(super) fn reference(
    system: &System,
    free: &[usize],
    options: &AccuracyOptions,
    omega: f64,
) -> Result<(Checkpoints, ReferenceReport), LabError> {
    let times = (1..=options.frames).map(|k| options.duration * k as f64 / options.frames as f64);
    if options.reference == ReferenceChoice::Auto {
        if let Some(closed) = AxialOscillator::of(system) {
            let checkpoints: Checkpoints = times.map(|t| closed.positions(t)).collect();
            let scale = largest_distance(free, &checkpoints);
            return Ok((
                checkpoints,
                ReferenceReport {
                    kind: ReferenceKind::Analytic,
                    method: "closed-form".to_owned(),
                    dt: None,
                    estimated_error: f64::EPSILON * scale,
                    observed_order: None,
                    converged: true,
                },
            ));
        }
    }
    let requested = options.reference_dt.unwrap_or_else(|| {
        let smallest = options.dts.iter().copied().fold(f64::INFINITY, f64::min);
        let stable = if omega > 0.0 {
            0.5 / omega
        } else {
            f64::INFINITY
        };
        let h = stable.min(smallest / 4.0);
        if h.is_finite() {
            h
        } else {
            options.duration / options.frames as f64 / 1000.0
        }
    });
    let found = numerical(system, free, options.duration, options.frames, requested)?;
    Ok((
        found.checkpoints,
        ReferenceReport {
            kind: ReferenceKind::Numerical,
            method: REFERENCE_METHOD.name().to_owned(),
            dt: Some(found.step),
            estimated_error: found.estimated_error,
            observed_order: found.observed_order,
            converged: true,
        },
    ))
}

/// `X`: the largest distance of a free particle from the origin at a
/// checkpoint.
pub(super) fn largest_distance(free: &[usize], checkpoints: &Checkpoints) -> f64 {
    checkpoints
        .iter()
        .flat_map(|x| free.iter().map(|&i| x[i].norm()))
        .fold(0.0, f64::max)
}

/// Runs `job` `repeat` times (once if it fails) and measures the first
/// run's error.
pub(super) fn measure(
    system: &System,
    free: &[usize],
    job: &Job,
    options: &AccuracyOptions,
    checkpoints: &Checkpoints,
) -> Result<Run, LabError> {
    let mut errors = Vec::with_capacity(options.frames);
    let mut measure_error = ObserveFn(|_: &System, state: &State, step: &StepInfo| {
        if let Some(x) = checkpoints.get(step.index / job.per_frame - 1) {
            errors.push(rms(free, state.positions(), x));
        }
        ControlFlow::Continue(())
    });
    let (first, wall_s) = repeated(
        system,
        &|| options.settings.build(job.method, job.tolerance),
        (job.step, job.per_frame),
        options,
        &mut measure_error,
    )?;
    let complete = first.failure().is_none() && errors.len() == options.frames;
    let finite = |e: f64| (complete && e.is_finite()).then_some(e);
    let error_rms = errors.last().copied().and_then(finite);
    let error_max = errors.iter().copied().reduce(f64::max).and_then(finite);
    let (run_steps, step) = if job.method.is_fixed_step() {
        (first.steps, job.step)
    } else {
        let substeps = first.report.accepted_steps;
        (substeps, options.duration / substeps.max(1) as f64)
    };
    Ok(Run {
        integrator: job.method,
        dt: job.dt,
        step,
        tolerance: job.tolerance,
        steps: run_steps,
        error_rms,
        error_max,
        wall_s,
        force_evaluations: first.report.force_evaluations,
        linear_iterations: first.report.linear_iterations,
        linear_solves: first.report.linear_solves,
        failure: first.failure().map(ToString::to_string),
        resolved: false,
    })
}

/// Runs `build`'s integrator from rest for `options.frames` intervals of
/// `per_frame` steps of `step`, calling `observer` at the end of each
/// interval, then `options.repeat − 1` more times unobserved for their
/// wall time (none if the first run failed): the first run, and the median
/// of all the runs' wall times inside the steps, s.
pub(super) fn repeated(
    system: &System,
    build: &dyn Fn() -> Result<Box<dyn Integrator + Send>, ParameterError>,
    (step, per_frame): (f64, usize),
    options: &AccuracyOptions,
    observer: &mut dyn Observer,
) -> Result<(Simulated, f64), LabError> {
    let steps = per_frame * options.frames;
    let mut integrator = build()?;
    let mut state = system.initial_state();
    let first = Simulation::new(system, &mut integrator)
        .observe(per_frame, observer)
        .run_to_end(&mut state, step, steps);
    let mut walls = vec![first.wall.as_secs_f64()];
    if first.failure().is_none() {
        for _ in 1..options.repeat {
            let mut integrator = build()?;
            let mut state = system.initial_state();
            let again =
                Simulation::new(system, &mut integrator).run_to_end(&mut state, step, steps);
            walls.push(again.wall.as_secs_f64());
        }
    }
    Ok((first, median(&mut walls)))
}

/// The median of `values` (the mean of the middle two for an even count).
fn median(values: &mut [f64]) -> f64 {
    values.sort_by(f64::total_cmp);
    let n = values.len();
    match n {
        0 => 0.0,
        n if n % 2 == 1 => values[n / 2],
        n => 0.5 * (values[n / 2 - 1] + values[n / 2]),
    }
}
