//! The implicit step's variants against its tightly converged step.
//!
//! Backward Euler's step is one minimisation of the incremental potential
//! `Φ`; how far it is carried decides its cost. A [`StepVariant`] is one
//! way of carrying it: Newton's method or L-BFGS stopped at a tolerance,
//! Baraff & Witkin's linearised step (one Newton step), or the fast
//! mass-spring method's fixed number of local/global iterations, whose
//! fixed point is the same step. Each variant runs at each of the
//! measurement's variant steps `h` and is compared, checkpoint by
//! checkpoint, with backward Euler at the same `h` converged tightly
//! (Newton, sparse Cholesky, `newton_tolerance` = 10⁻⁹; its own
//! `unconverged_steps` reported). That difference,
//!
//! ```text
//! e_conv(t) = √( Σ_free |xᵢ(t) − x̄ᵢ(t)|² / n_free ),
//! ```
//!
//! with `x̄` the converged run, is what stopping early costs — the time
//! discretisation's own error, the same for every variant at one `h`, is
//! left out — and its largest value over the checkpoints is the variant's
//! `error_converged`. Its `error_rms` is the error at the end against the
//! measurement's reference, as a method's run has, so the variants take
//! their place in the work-precision diagram too.

use std::ops::ControlFlow;
use std::str::FromStr;

use hooke_core::{Integrator, ObserveFn, ParameterError, State, StepInfo, System};
use hooke_implicit::{FastMassSpring, ImplicitSettings, LinearSolver, Minimizer};
use hooke_scenes::IntegratorSpec;
use serde::{Deserialize, Serialize};

use super::AccuracyOptions;
use super::measure::repeated;
use super::reference::{Checkpoints, rms, steps_per_interval};
use crate::{LabError, Method, Settings};

/// The relative Newton tolerance of the converged step the variants are
/// compared with.
pub const CONVERGED_TOLERANCE: f64 = 1e-9;

/// One way of carrying out backward Euler's step.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(into = "String", try_from = "String")]
pub enum StepVariant {
    /// Newton's method to a relative tolerance.
    Newton(f64),
    /// L-BFGS (the default history) to a relative tolerance.
    QuasiNewton(f64),
    /// Baraff & Witkin's linearised step.
    Linearized,
    /// The fast mass-spring method with this many iterations a step.
    FastMassSpring(usize),
}

impl StepVariant {
    /// The variants `hooke accuracy` measures by default: Newton at 10⁻²
    /// and at the library's default tolerance, L-BFGS at 10⁻² and 10⁻³, the
    /// linearised step, and fast mass-spring at 10 and 100 iterations.
    #[must_use]
    pub fn defaults() -> Vec<Self> {
        vec![
            Self::Newton(1e-2),
            Self::Newton(ImplicitSettings::NEWTON_TOLERANCE),
            Self::QuasiNewton(1e-2),
            Self::QuasiNewton(1e-3),
            Self::Linearized,
            Self::FastMassSpring(10),
            Self::FastMassSpring(100),
        ]
    }

    /// The integrator of this variant; Newton and L-BFGS take the rest of
    /// their parameters (solver, iteration cap) from `settings`.
    ///
    /// # Errors
    /// [`ParameterError`] for a tolerance or iteration count out of range.
    pub fn build(self, settings: &Settings) -> Result<Box<dyn Integrator + Send>, ParameterError> {
        let (minimizer, newton_tolerance) = match self {
            Self::Newton(tolerance) => (Minimizer::Newton, tolerance),
            Self::QuasiNewton(tolerance) => (Minimizer::quasi_newton(), tolerance),
            Self::Linearized => (Minimizer::Linearized, settings.implicit.newton_tolerance),
            Self::FastMassSpring(iterations) => {
                return IntegratorSpec::FastMassSpring { iterations }.build();
            }
        };
        Settings {
            implicit: ImplicitSettings {
                minimizer,
                newton_tolerance,
                ..settings.implicit
            },
            ..*settings
        }
        .build(Method::BackwardEuler, None)
    }
}

/// Written `newton:1e-2`, `quasi-newton:1e-3`, `linearized`,
/// `fast-mass-spring:10`.
impl std::fmt::Display for StepVariant {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Newton(t) => write!(f, "newton:{t:e}"),
            Self::QuasiNewton(t) => write!(f, "quasi-newton:{t:e}"),
            Self::Linearized => f.write_str("linearized"),
            Self::FastMassSpring(k) => write!(f, "{}:{k}", FastMassSpring::NAME),
        }
    }
}

impl FromStr for StepVariant {
    type Err = String;

    /// Parses what [`Display`](std::fmt::Display) writes.
    ///
    /// ```
    /// use hooke_lab::accuracy::StepVariant;
    /// assert_eq!("newton:1e-2".parse(), Ok(StepVariant::Newton(1e-2)));
    /// assert_eq!("fast-mass-spring:10".parse(), Ok(StepVariant::FastMassSpring(10)));
    /// assert!("newton".parse::<StepVariant>().is_err());
    /// ```
    fn from_str(text: &str) -> Result<Self, Self::Err> {
        let expected = "newton:TOL, quasi-newton:TOL, linearized or fast-mass-spring:ITERATIONS";
        let fail = || format!("step variant \"{text}\": expected {expected}");
        let tolerance = |value: &str| {
            value
                .parse::<f64>()
                .ok()
                .filter(|t| t.is_finite() && *t > 0.0)
                .ok_or_else(|| format!("step variant \"{text}\": a tolerance must be a number > 0"))
        };
        match text.split_once(':') {
            None if text == "linearized" => Ok(Self::Linearized),
            Some(("newton", value)) => tolerance(value).map(Self::Newton),
            Some(("quasi-newton", value)) => tolerance(value).map(Self::QuasiNewton),
            Some((name, value)) if name == FastMassSpring::NAME => value
                .parse::<usize>()
                .ok()
                .filter(|&k| k > 0)
                .map(Self::FastMassSpring)
                .ok_or_else(|| {
                    format!("step variant \"{text}\": the iterations must be a whole number > 0")
                }),
            _ => Err(fail()),
        }
    }
}

impl From<StepVariant> for String {
    fn from(variant: StepVariant) -> Self {
        variant.to_string()
    }
}

impl TryFrom<String> for StepVariant {
    type Error = String;

    fn try_from(text: String) -> Result<Self, Self::Error> {
        text.parse()
    }
}

/// One variant's run at one step.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct VariantRun {
    /// The variant.
    pub variant: StepVariant,
    /// The requested step, s.
    pub dt: f64,
    /// The step taken, `h ≤ dt`, s.
    pub step: f64,
    /// `max_k e_conv(t_k)`, m (`null` if the run failed).
    pub error_converged: Option<f64>,
    /// The RMS error at the end against the measurement's reference, m.
    pub error_rms: Option<f64>,
    /// Median wall time inside the steps, s.
    pub wall_s: f64,
    /// Newton, L-BFGS or fast mass-spring iterations per step.
    pub iterations_per_step: f64,
    /// Steps accepted without meeting the variant's tolerance (at their
    /// step floor).
    pub unconverged_steps: usize,
    /// Substeps rejected and retried smaller.
    pub rejected_steps: usize,
    /// Why the run stopped early, if it did.
    pub failure: Option<String>,
}

/// The tightly converged step at one `h`, which the variants there are
/// compared with.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ConvergedRun {
    /// The requested step, s.
    pub dt: f64,
    /// The step taken, s.
    pub step: f64,
    /// Median wall time inside the steps, s.
    pub wall_s: f64,
    /// Newton iterations per step.
    pub iterations_per_step: f64,
    /// Steps accepted without meeting the tolerance (at their step floor).
    pub unconverged_steps: usize,
    /// Substeps rejected and retried smaller.
    pub rejected_steps: usize,
    /// The RMS error at the end against the measurement's reference, m.
    pub error_rms: Option<f64>,
    /// Why the run stopped early, if it did: the variants at this step are
    /// then not run, having nothing to be compared with.
    pub failure: Option<String>,
}

/// What a timed run gives: its checkpoints, median wall time, iterations
/// per step, unconverged and rejected steps, and failure.
struct Timed {
    checkpoints: Checkpoints,
    wall_s: f64,
    iterations_per_step: f64,
    unconverged_steps: usize,
    rejected_steps: usize,
    failure: Option<String>,
}

/// Runs `build`'s integrator `per_frame · frames` steps of `step` from
/// rest, `repeat` times (once if it fails, [`repeated`]), keeping the first
/// run's positions at the checkpoints.
fn timed(
    system: &System,
    build: &dyn Fn() -> Result<Box<dyn Integrator + Send>, ParameterError>,
    per_frame: usize,
    step: f64,
    options: &AccuracyOptions,
) -> Result<Timed, LabError> {
    let mut checkpoints = Vec::with_capacity(options.frames);
    let mut keep = ObserveFn(|_: &System, state: &State, _: &StepInfo| {
        checkpoints.push(state.positions().to_vec());
        ControlFlow::Continue(())
    });
    let (first, wall_s) = repeated(system, build, (step, per_frame), options, &mut keep)?;
    let failure = first
        .failure()
        .map(ToString::to_string)
        .or_else(|| (checkpoints.len() != options.frames).then(|| "stopped early".to_owned()));
    Ok(Timed {
        checkpoints,
        wall_s,
        iterations_per_step: first.report.newton_iterations as f64 / first.steps.max(1) as f64,
        unconverged_steps: first.report.unconverged_steps,
        rejected_steps: first.report.rejected_steps,
        failure,
    })
}

/// The largest RMS distance between two runs' checkpoints, if both are
/// complete and it is finite.
fn largest_difference(free: &[usize], a: &Checkpoints, b: &Checkpoints) -> Option<f64> {
    (a.len() == b.len())
        .then(|| {
            a.iter()
                .zip(b)
                .map(|(x, y)| rms(free, x, y))
                .fold(0.0, f64::max)
        })
        .filter(|e| e.is_finite())
}

/// The converged runs and the variants' runs at every variant step, the
/// error at the end against `reference`'s last checkpoint. Where the
/// converged run fails, its step has no variant runs.
pub(super) fn measure_variants(
    system: &System,
    free: &[usize],
    options: &AccuracyOptions,
    reference: &Checkpoints,
    progress: &mut dyn FnMut(),
) -> Result<(Vec<ConvergedRun>, Vec<VariantRun>), LabError> {
    let interval = options.duration / options.frames as f64;
    // Cholesky rather than `auto`: the run every variant is measured
    // against solves each step exactly, whatever a timed trial would pick.
    let converged_settings = Settings {
        implicit: ImplicitSettings {
            solver: LinearSolver::Cholesky,
            minimizer: Minimizer::Newton,
            newton_tolerance: CONVERGED_TOLERANCE,
            ..options.settings.implicit
        },
        ..options.settings
    };
    let end_error = |checkpoints: &Checkpoints| match (checkpoints.last(), reference.last()) {
        (Some(x), Some(r)) if checkpoints.len() == options.frames => {
            Some(rms(free, x, r)).filter(|e| e.is_finite())
        }
        _ => None,
    };
    let (mut converged, mut variants) = (Vec::new(), Vec::new());
    for &dt in &options.variant_dts {
        let per_frame = steps_per_interval(interval, dt);
        let step = interval / per_frame as f64;
        let tight = timed(
            system,
            &|| converged_settings.build(Method::BackwardEuler, None),
            per_frame,
            step,
            options,
        )?;
        progress();
        let failed = tight.failure.is_some();
        converged.push(ConvergedRun {
            dt,
            step,
            wall_s: tight.wall_s,
            iterations_per_step: tight.iterations_per_step,
            unconverged_steps: tight.unconverged_steps,
            rejected_steps: tight.rejected_steps,
            error_rms: end_error(&tight.checkpoints).filter(|_| !failed),
            failure: tight.failure,
        });
        if failed {
            options.variants.iter().for_each(|_| progress());
            continue;
        }
        for &variant in &options.variants {
            let run = timed(
                system,
                &|| variant.build(&options.settings),
                per_frame,
                step,
                options,
            )?;
            progress();
            let complete = run.failure.is_none();
            variants.push(VariantRun {
                variant,
                dt,
                step,
                error_converged: largest_difference(free, &run.checkpoints, &tight.checkpoints)
                    .filter(|_| complete),
                error_rms: end_error(&run.checkpoints).filter(|_| complete),
                wall_s: run.wall_s,
                iterations_per_step: match variant {
                    StepVariant::FastMassSpring(k) => k as f64,
                    _ => run.iterations_per_step,
                },
                unconverged_steps: run.unconverged_steps,
                rejected_steps: run.rejected_steps,
                failure: run.failure,
            });
        }
    }
    Ok((converged, variants))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn variants_are_written_as_they_are_parsed() {
        for variant in StepVariant::defaults() {
            assert_eq!(variant.to_string().parse(), Ok(variant));
        }
        for bad in [
            "newton:0",
            "newton:-1",
            "quasi-newton:x",
            "fast-mass-spring:0",
            "bdf2",
            "linearized:1",
        ] {
            let error = bad.parse::<StepVariant>().unwrap_err();
            assert!(error.contains(bad), "{error}");
        }
    }
}
