//! Error against run time, and the observed order of convergence.
//!
//! # Runs
//!
//! The run time `T` is split into `F` frame intervals ending at the
//! checkpoints ("written frames") `t_k = T k / F`, `k = 1…F`. A fixed-step
//! method asked for a step `dt` takes the largest step that divides a frame
//! interval, `h = (T/F) / ⌈(T/F)/dt⌉ ≤ dt`, so it lands on every
//! checkpoint; the report gives both `dt` and `h` (`step`). Adaptive
//! Dormand–Prince is called once per frame interval (its own substeps
//! inside) for each tolerance; its `step` is the mean accepted substep
//! `T / steps`.
//!
//! # Error
//!
//! On the free (unpinned) particles, with `x` the run and `x̂` the
//! reference,
//!
//! ```text
//! e(t) = √( Σ_free |xᵢ(t) − x̂ᵢ(t)|² / n_free ),
//! error_rms = e(T),   error_max = max_k e(t_k).
//! ```
//!
//! Both are `null` for a run that failed (a non-finite state, a solver
//! that broke down) or whose error is not finite.
//!
//! # Reference
//!
//! **Analytic** where the scene is a single oscillator moving along its
//! spring ([`AxialOscillator`]); its estimated error is the rounding of the
//! closed form, `ε·X`, with `ε` the machine epsilon and `X` the largest
//! distance of a free particle from the origin. Otherwise **numerical**:
//! classical Runge–Kutta at a step `h_ref` (by default
//! `min(0.5/ω_max, dt_min/4)`, `ω_max` from [`omega_max`]
//! and `dt_min` the smallest `dt`), checked against runs at `2h_ref` and
//! `4h_ref` by Richardson's estimate (see [`ReferenceReport`]). The
//! reference is reported `converged` when its estimated error is at most a
//! tenth of the smallest `error_rms` measured; each run is marked
//! `resolved` when its `error_rms` is at least ten times the reference's
//! estimated error, and only resolved runs are plotted (and count in the
//! least wall time to an error), so every error plotted lies at least ten
//! times above the reference's own.
//!
//! # Observed order
//!
//! For each method, the slope of the least-squares line through
//! `(ln h, ln error_max)` over its runs in the *asymptotic range*:
//!
//! ```text
//! 100 · max(ε_ref, N ε X)  <  error_max  <  S / 100,   h ω_max ≤ 1,
//! ```
//!
//! where `ε_ref` is the reference's estimated error, `N` the run's steps
//! (`N ε X` bounds the rounding error accumulated over `N` steps), and `S`
//! the size of the motion: the largest RMS displacement of the free
//! particles from their initial positions at a checkpoint of the reference.
//! Above the ceiling the error is no longer small against the motion
//! (phase errors of a radian, growth near a stability limit); below the
//! floor the reference's error or rounding dominates. Above `h ω_max = 1`
//! the fastest modes are not resolved: an implicit method damps them out
//! and its error against the reference stalls at their amplitude (on the
//! stiff cloth backward Euler's error falls by only 2.4× over the 11× in
//! `h` from `hω_max = 0.47` to `5.2`). The fit uses `error_max` rather than
//! `error_rms` because one oscillation's error at one instant can pass
//! near zero: on `damped-oscillator`, backward Euler's error at the end
//! time falls from 1.6 mm to 1.1 mm as `h` grows from 0.05 to 0.09 s,
//! while its largest error over the frames grows from 77 to 126 mm. At least three runs
//! must lie in the range, else the order is `null`. For Dormand–Prince, `h`
//! is its mean substep and the order only indicative.
//!
//! # Timing
//!
//! Each run is repeated `repeat` times and its wall time is the median of
//! the repeats' time inside the steps ([`Run::wall`](hooke_core::Run::wall));
//! the reference is not timed. The runs go one after another, so that no
//! two compete for the cores (the integrators may use them all on large
//! systems); only the three reference runs, which are not timed, run in
//! parallel with the `parallel` feature. A run that failed is not
//! repeated.
//!
//! # Example
//!
//! ```
//! use hooke_lab::{AccuracyOptions, Method, accuracy};
//! let scene = hooke_scenes::builtin::load("damped-oscillator")?;
//! let mut options = AccuracyOptions::for_scene(&scene);
//! options.methods = vec![Method::from_name("velocity-verlet").unwrap()];
//! options.dts = vec![0.01, 0.02, 0.04];
//! options.repeat = 1;
//! let report = accuracy(&scene, &options, &|_, _| {})?;
//! let order = report.orders[0].observed_order.unwrap();
//! assert!((order - 2.0).abs() < 0.05);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod fit;
mod reference;

use serde::Serialize;

use std::ops::ControlFlow;

use hooke_core::{ObserveFn, Simulation, State, StepInfo, System};
use hooke_scenes::Scene;

pub use reference::AxialOscillator;
use reference::{Checkpoints, REFERENCE_METHOD, numerical, rms, steps_per_interval};

use crate::spectrum::omega_max;
use crate::{LabError, Range};
use crate::{Method, Settings};

/// How far above the reference's error and the rounding error a run's
/// error must lie to count in the order fit.
const FLOOR_FACTOR: f64 = 100.0;
/// The fraction of the motion's size a run's error must stay below to
/// count in the order fit.
const CEILING_FRACTION: f64 = 1e-2;
/// The largest `h·ω_max` of a fixed-step run in the order fit.
const MAX_H_OMEGA: f64 = 1.0;
/// How far below the smallest measured error a converged reference's
/// estimated error lies.
const CONVERGED_FACTOR: f64 = 10.0;

/// Where the reference comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ReferenceChoice {
    /// The closed form where the scene has one, else numerical.
    Auto,
    /// Always the numerical reference.
    Numerical,
}

/// What to measure.
#[derive(Debug, Clone, PartialEq)]
pub struct AccuracyOptions {
    /// The methods, in report order.
    pub methods: Vec<Method>,
    /// Requested steps of the fixed-step methods, s.
    pub dts: Vec<f64>,
    /// Tolerances of the adaptive method.
    pub tolerances: Vec<f64>,
    /// Simulated time, s.
    pub duration: f64,
    /// Checkpoints ("written frames"), evenly spaced, the last at `duration`.
    pub frames: usize,
    /// Timed repeats of each run.
    pub repeat: usize,
    /// The methods' parameters.
    pub settings: Settings,
    /// Where the reference comes from.
    pub reference: ReferenceChoice,
    /// The numerical reference's step, s (`None`: `min(0.5/ω_max, dt_min/4)`).
    pub reference_dt: Option<f64>,
}

impl AccuracyOptions {
    /// Every method; 13 steps over three decades up to
    /// `dt_max = max(scene dt, 0.5/ω_max)` (the scene's own step for the
    /// implicit methods, the explicit methods well resolved at the small
    /// end); tolerances 10⁻³…10⁻⁹; the scene's duration; 10 frames; 3
    /// repeats; the scene's implicit and adaptive parameters; the automatic
    /// reference.
    #[must_use]
    pub fn for_scene(scene: &Scene) -> Self {
        let omega = omega_max(&scene.system).omega_max;
        let mut largest = scene.timing.dt;
        if omega > 0.0 {
            largest = largest.max(0.5 / omega);
        }
        Self {
            methods: Method::ALL.to_vec(),
            dts: Range::new(largest / 1000.0, largest, 13).values(),
            tolerances: Range::new(1e-3, 1e-9, 7).values(),
            duration: scene.timing.duration,
            frames: 10,
            repeat: 3,
            settings: Settings::from_scene(&scene.integrator),
            reference: ReferenceChoice::Auto,
            reference_dt: None,
        }
    }

    fn check(&self) -> Result<(), LabError> {
        let (positive, at_least_one) = (LabError::positive, LabError::at_least_one);
        at_least_one("methods", self.methods.len())?;
        if self.methods.iter().any(|m| m.is_fixed_step()) {
            at_least_one("dt values", self.dts.len())?;
        }
        if self.methods.contains(&Method::DormandPrince) {
            at_least_one("tolerances", self.tolerances.len())?;
        }
        self.dts.iter().try_for_each(|&dt| positive("dt", dt))?;
        self.tolerances
            .iter()
            .try_for_each(|&t| positive("tolerance", t))?;
        positive("duration", self.duration)?;
        at_least_one("frames", self.frames)?;
        at_least_one("repeat", self.repeat)?;
        self.reference_dt
            .map_or(Ok(()), |dt| positive("reference dt", dt))
    }
}

/// The kind of reference.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum ReferenceKind {
    /// The closed form of a single oscillator.
    Analytic,
    /// A fine classical Runge–Kutta run.
    Numerical,
}

/// The reference the runs were measured against.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ReferenceReport {
    /// Analytic or numerical.
    pub kind: ReferenceKind,
    /// `"closed-form"`, or the numerical reference's method (`"rk4"`).
    pub method: &'static str,
    /// The numerical reference's step `h_ref`, s.
    pub dt: Option<f64>,
    /// Its estimated error, m, largest over the checkpoints: Richardson's
    /// `D₁/(2^q − 1)`, with `D₁ = max_k e_{2h,h}(t_k)` the largest RMS
    /// difference between the runs at `2h_ref` and `h_ref`,
    /// `D₂ = max_k e_{4h,2h}(t_k)`, `p = log₂(D₂/D₁)` and `q = min(p, 4)`;
    /// when `p ≤ 0` the differences no longer shrink with the step (they
    /// are rounding, on stiff scenes about 10⁻⁹ m) and the estimate is `D₁`
    /// itself. `ε·X` for the closed form.
    pub estimated_error: f64,
    /// `p`, the numerical reference's observed order.
    pub observed_order: Option<f64>,
    /// Whether `estimated_error` is at most a tenth of the smallest
    /// `error_rms` measured (always for the closed form, exact up to
    /// rounding).
    pub converged: bool,
}

/// One run: a method at one step or tolerance.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Run {
    /// The method's name.
    pub integrator: &'static str,
    /// The requested step, s (`null` for the adaptive method).
    pub dt: Option<f64>,
    /// The step taken, `h ≤ dt`, s (the adaptive method: its mean substep).
    pub step: f64,
    /// The adaptive method's tolerance.
    pub tolerance: Option<f64>,
    /// Steps taken (the adaptive method: accepted substeps).
    pub steps: usize,
    /// `e(T)`, m.
    pub error_rms: Option<f64>,
    /// `max_k e(t_k)`, m.
    pub error_max: Option<f64>,
    /// Median wall time inside the steps, s.
    pub wall_s: f64,
    /// Force evaluations (for the implicit methods: assemblies).
    pub force_evaluations: usize,
    /// Iterations of an iterative linear solver.
    pub linear_iterations: usize,
    /// Linear systems solved.
    pub linear_solves: usize,
    /// Why the run stopped early, if it did.
    pub failure: Option<String>,
    /// Whether the reference resolves the error: `error_rms` is at least
    /// ten times the reference's estimated error. Plots leave out the
    /// runs that are not.
    pub resolved: bool,
}

/// A method's observed order of convergence.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Order {
    /// The method's name.
    pub integrator: &'static str,
    /// The least-squares slope, or `null` with fewer than three runs in the
    /// asymptotic range.
    pub observed_order: Option<f64>,
    /// [`Method::expected_order`].
    pub expected_order: f64,
    /// The steps `h` of the runs fitted, s.
    pub steps_fitted: Vec<f64>,
}

/// The measurement; serialises to `accuracy.json`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AccuracyReport {
    /// The scene's name.
    pub scene: String,
    /// Simulated time, s.
    pub duration: f64,
    /// Checkpoints.
    pub frames: usize,
    /// Timed repeats of each run.
    pub repeat: usize,
    /// `ω_max` of the scene, rad/s.
    pub omega_max: f64,
    /// `S`, the size of the motion, m.
    pub motion_scale: f64,
    /// The reference.
    pub reference: ReferenceReport,
    /// Every run, by method, then step or tolerance.
    pub runs: Vec<Run>,
    /// Each method's observed order.
    pub orders: Vec<Order>,
}

/// One method's points for a plot.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// The method's name.
    pub integrator: &'static str,
    /// `(x, error)`, runs without an error left out.
    pub points: Vec<(f64, f64)>,
}

impl AccuracyReport {
    fn series(&self, x: impl Fn(&Run) -> f64, y: impl Fn(&Run) -> Option<f64>) -> Vec<Series> {
        let mut series: Vec<Series> = Vec::new();
        for r in &self.runs {
            let index = match series.iter().position(|s| s.integrator == r.integrator) {
                Some(i) => i,
                None => {
                    series.push(Series {
                        integrator: r.integrator,
                        points: Vec::new(),
                    });
                    series.len() - 1
                }
            };
            if let Some(e) = y(r).filter(|&e| r.resolved && e <= self.motion_scale) {
                series[index].points.push((x(r), e));
            }
        }
        series
    }

    /// The work–precision data: `(wall_s, error_rms)` per method, resolved
    /// runs whose error is at most the size of the motion `S` only (a
    /// larger error means no accuracy at all, typically a run that blew
    /// up).
    #[must_use]
    pub fn work_precision(&self) -> Vec<Series> {
        self.series(|r| r.wall_s, |r| r.error_rms)
    }

    /// The convergence data: `(step, error_max)` per method, the error
    /// the orders are fitted to, with the runs of
    /// [`AccuracyReport::work_precision`].
    #[must_use]
    pub fn convergence(&self) -> Vec<Series> {
        self.series(|r| r.step, |r| r.error_max)
    }

    /// Each method's least wall time among its runs with
    /// `error_rms ≤ error`, resolved or not (a run below the reference's
    /// resolution is below `error` too when `error` is resolved); `None`
    /// if no run got there.
    #[must_use]
    pub fn least_wall_time(&self, error: f64) -> Vec<(&'static str, Option<f64>)> {
        let mut least: Vec<(&'static str, Option<f64>)> = Vec::new();
        for r in &self.runs {
            let wall = r.error_rms.filter(|&e| e <= error).map(|_| r.wall_s);
            match least.iter_mut().find(|(name, _)| *name == r.integrator) {
                Some((_, best)) => {
                    *best = match (*best, wall) {
                        (Some(a), Some(b)) => Some(a.min(b)),
                        (a, b) => a.or(b),
                    };
                }
                None => least.push((r.integrator, wall)),
            }
        }
        least
    }
}

/// A run to make.
#[derive(Debug, Clone, Copy)]
struct Job {
    method: Method,
    dt: Option<f64>,
    tolerance: Option<f64>,
    per_frame: usize,
    step: f64,
}

/// The reference's positions at the checkpoints, and its report.
fn reference(
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
                    method: "closed-form",
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
            method: REFERENCE_METHOD.name(),
            dt: Some(found.step),
            estimated_error: found.estimated_error,
            observed_order: found.observed_order,
            converged: true,
        },
    ))
}

/// `X`: the largest distance of a free particle from the origin at a
/// checkpoint.
fn largest_distance(free: &[usize], checkpoints: &Checkpoints) -> f64 {
    checkpoints
        .iter()
        .flat_map(|x| free.iter().map(|&i| x[i].norm()))
        .fold(0.0, f64::max)
}

/// Runs `job` `repeat` times (once if it fails) and measures the first
/// run's error.
fn measure(
    system: &System,
    free: &[usize],
    job: &Job,
    options: &AccuracyOptions,
    checkpoints: &Checkpoints,
) -> Result<Run, LabError> {
    let steps = job.per_frame * options.frames;
    let mut errors = Vec::with_capacity(options.frames);
    let mut integrator = options.settings.build(job.method, job.tolerance)?;
    let mut state = system.initial_state();
    let mut measure_error = ObserveFn(|_: &System, state: &State, step: &StepInfo| {
        if let Some(x) = checkpoints.get(step.index / job.per_frame - 1) {
            errors.push(rms(free, state.positions(), x));
        }
        ControlFlow::Continue(())
    });
    let first = Simulation::new(system, &mut integrator)
        .observe(job.per_frame, &mut measure_error)
        .run_to_end(&mut state, job.step, steps);
    let mut walls = vec![first.wall.as_secs_f64()];
    if first.failure().is_none() {
        for _ in 1..options.repeat {
            let mut integrator = options.settings.build(job.method, job.tolerance)?;
            let mut state = system.initial_state();
            let again =
                Simulation::new(system, &mut integrator).run_to_end(&mut state, job.step, steps);
            walls.push(again.wall.as_secs_f64());
        }
    }
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
        integrator: job.method.name(),
        dt: job.dt,
        step,
        tolerance: job.tolerance,
        steps: run_steps,
        error_rms,
        error_max,
        wall_s: median(&mut walls),
        force_evaluations: first.report.force_evaluations,
        linear_iterations: first.report.linear_iterations,
        linear_solves: first.report.linear_solves,
        failure: first.failure().map(ToString::to_string),
        resolved: false,
    })
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

/// Measures `options.methods` on `scene` (see the module docs), calling
/// `progress(done, total)` after the reference and after each run.
///
/// # Errors
/// [`LabError::Invalid`] naming an option out of range,
/// [`LabError::Parameter`] for a method parameter out of range,
/// [`LabError::Reference`] if the numerical reference run fails.
pub fn accuracy(
    scene: &Scene,
    options: &AccuracyOptions,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<AccuracyReport, LabError> {
    options.check()?;
    let system = &scene.system;
    let free: Vec<usize> = (0..system.particle_count())
        .filter(|&i| !system.is_pinned(i))
        .collect();
    let omega = omega_max(system).omega_max;
    let interval = options.duration / options.frames as f64;
    let jobs: Vec<Job> = options
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
        .collect();
    let total = jobs.len() + 1;
    let (checkpoints, mut reference) = reference(system, &free, options, omega)?;
    progress(1, total);
    let mut runs = Vec::with_capacity(jobs.len());
    for (done, job) in jobs.iter().enumerate() {
        runs.push(measure(system, &free, job, options, &checkpoints)?);
        progress(done + 2, total);
    }

    let initial = system.initial_positions();
    let motion_scale = checkpoints
        .iter()
        .map(|x| rms(&free, x, initial))
        .fold(0.0, f64::max);
    let position_scale = largest_distance(&free, &checkpoints);
    let smallest = runs
        .iter()
        .filter_map(|r| r.error_rms)
        .fold(f64::INFINITY, f64::min);
    reference.converged = reference.kind == ReferenceKind::Analytic
        || CONVERGED_FACTOR * reference.estimated_error <= smallest;
    for run in &mut runs {
        run.resolved = run
            .error_rms
            .is_some_and(|e| e >= CONVERGED_FACTOR * reference.estimated_error);
    }
    let scales = Scales {
        reference_error: reference.estimated_error,
        position: position_scale,
        motion: motion_scale,
        omega_max: omega,
    };
    let orders = orders(&options.methods, &runs, &scales);
    Ok(AccuracyReport {
        scene: scene.name.clone(),
        duration: options.duration,
        frames: options.frames,
        repeat: options.repeat,
        omega_max: omega,
        motion_scale,
        reference,
        runs,
        orders,
    })
}

/// What bounds the asymptotic range.
struct Scales {
    /// `ε_ref`, m.
    reference_error: f64,
    /// `X`, m.
    position: f64,
    /// `S`, m.
    motion: f64,
    /// `ω_max`, rad/s.
    omega_max: f64,
}

/// Each method's order fitted over its runs in the asymptotic range.
fn orders(methods: &[Method], runs: &[Run], scales: &Scales) -> Vec<Order> {
    let mut seen: Vec<Method> = Vec::new();
    methods
        .iter()
        .filter(|&&m| {
            let new = !seen.contains(&m);
            seen.push(m);
            new
        })
        .map(|&method| {
            let mut points: Vec<(f64, f64)> = runs
                .iter()
                .filter(|r| r.integrator == method.name())
                .filter_map(|r| {
                    let rounding = r.steps as f64 * f64::EPSILON * scales.position;
                    let floor = FLOOR_FACTOR * scales.reference_error.max(rounding);
                    let resolved =
                        !method.is_fixed_step() || r.step * scales.omega_max <= MAX_H_OMEGA;
                    let e = r.error_max?;
                    (resolved && e > floor && e < CEILING_FRACTION * scales.motion)
                        .then_some((r.step, e))
                })
                .collect();
            points.sort_by(|a, b| a.0.total_cmp(&b.0));
            points.dedup_by(|a, b| a.0.total_cmp(&b.0).is_eq());
            Order {
                integrator: method.name(),
                observed_order: fit::slope(&points),
                expected_order: method.expected_order(),
                steps_fitted: points.iter().map(|p| p.0).collect(),
            }
        })
        .collect()
}
