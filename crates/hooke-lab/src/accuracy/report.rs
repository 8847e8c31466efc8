//! [`AccuracyReport`]: what an accuracy measurement found, as written to
//! `accuracy.json`.

use serde::{Deserialize, Serialize};

use super::{ConvergedRun, StepVariant, VariantRun};
use crate::{Method, Shard};

/// The kind of reference.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ReferenceKind {
    /// The closed form of a single oscillator.
    Analytic,
    /// A fine classical Runge–Kutta run.
    Numerical,
}

/// The reference the runs were measured against.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ReferenceReport {
    /// Analytic or numerical.
    pub kind: ReferenceKind,
    /// `"closed-form"`, or the numerical reference's method (`"rk4"`).
    pub method: String,
    /// The numerical reference's step `h_ref`, s.
    pub dt: Option<f64>,
    /// Its estimated error, m, largest over the checkpoints: Richardson's
    /// `D₁/(2^q − 1)`, with `D₁ = max_k e_{2h,h}(t_k)` the largest RMS
    /// difference between the runs at `2h_ref` and `h_ref`,
    /// `D₂ = max_k e_{4h,2h}(t_k)`, `p = log₂(D₂/D₁)` and `q = min(p, 4)`;
    /// when `p ≤ 0` the differences no longer shrink with the step (they
    /// are rounding, on stiff scenes about 10⁻⁹ m) and the estimate is `D₁`
    /// itself. `ε·X` for the closed form.
    #[serde(deserialize_with = "crate::json::number")]
    pub estimated_error: f64,
    /// `p`, the numerical reference's observed order.
    pub observed_order: Option<f64>,
    /// Whether `estimated_error` is at most a tenth of the smallest
    /// `error_rms` measured (always for the closed form, exact up to
    /// rounding).
    pub converged: bool,
}

/// One run: a method at one step or tolerance.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Run {
    /// The method.
    pub integrator: Method,
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
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Order {
    /// The method.
    pub integrator: Method,
    /// The least-squares slope, or `null` with fewer than three runs in the
    /// asymptotic range.
    pub observed_order: Option<f64>,
    /// [`Method::expected_order`].
    pub expected_order: f64,
    /// The steps `h` of the runs fitted, s.
    pub steps_fitted: Vec<f64>,
}

/// The measurement; serialises to `accuracy.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AccuracyReport {
    /// The scene's name.
    pub scene: String,
    /// Simulated time, s.
    pub duration: f64,
    /// Checkpoints.
    pub frames: usize,
    /// Timed repeats of each run.
    pub repeat: usize,
    /// The methods measured, in report order.
    pub methods: Vec<Method>,
    /// The requested steps of the fixed-step methods, s.
    pub dts: Vec<f64>,
    /// The tolerances of the adaptive method.
    pub tolerances: Vec<f64>,
    /// `ω_max` of the scene, rad/s.
    pub omega_max: f64,
    /// `S`, the size of the motion, m.
    #[serde(deserialize_with = "crate::json::number")]
    pub motion_scale: f64,
    /// `X`, the largest distance of a free particle from the origin at a
    /// checkpoint of the reference, m.
    #[serde(deserialize_with = "crate::json::number")]
    pub position_scale: f64,
    /// The reference.
    pub reference: ReferenceReport,
    /// Every run, by method, then step or tolerance.
    pub runs: Vec<Run>,
    /// Each method's observed order (none in a partial report).
    pub orders: Vec<Order>,
    /// What the measurement did differently on a scene whose surfaces
    /// collide (it ran without self-collision).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
    /// Backward Euler tightly converged at each variant step (empty without
    /// variants).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub converged: Vec<ConvergedRun>,
    /// The step variants' runs, by step, then variant.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub variants: Vec<VariantRun>,
    /// The part of the runs this report holds, if it is partial: its runs
    /// are not yet marked resolved and it has no orders until
    /// [`merge`](crate::merge) combines it with the other parts.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shard: Option<Shard>,
}

/// One method's points for a plot.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// The method.
    pub integrator: Method,
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

    /// Each step variant's points `(wall_s, y)` over its steps, runs
    /// without a `y` left out: `y` the error against the converged step
    /// ([`VariantRun::error_converged`]) or against the reference
    /// ([`VariantRun::error_rms`]).
    #[must_use]
    pub fn variant_series(
        &self,
        y: impl Fn(&VariantRun) -> Option<f64>,
    ) -> Vec<(StepVariant, Vec<(f64, f64)>)> {
        let mut series: Vec<(StepVariant, Vec<(f64, f64)>)> = Vec::new();
        for r in &self.variants {
            let index = match series.iter().position(|(v, _)| *v == r.variant) {
                Some(i) => i,
                None => {
                    series.push((r.variant, Vec::new()));
                    series.len() - 1
                }
            };
            if let Some(e) = y(r) {
                series[index].1.push((r.wall_s, e));
            }
        }
        series
    }

    /// Each method's least wall time among its runs with
    /// `error_rms ≤ error`, resolved or not (a run below the reference's
    /// resolution is below `error` too when `error` is resolved); `None`
    /// if no run got there.
    #[must_use]
    pub fn least_wall_time(&self, error: f64) -> Vec<(Method, Option<f64>)> {
        let mut least: Vec<(Method, Option<f64>)> = Vec::new();
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
