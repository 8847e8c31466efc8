//! The conclusions of an accuracy measurement: which runs the reference
//! resolves and each method's observed order.

use super::fit;
use super::{AccuracyReport, Order, ReferenceKind, Run};
use crate::Method;

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

/// What bounds the asymptotic range.
pub(super) struct Scales {
    /// `ε_ref`, m.
    pub(super) reference_error: f64,
    /// `X`, m.
    pub(super) position: f64,
    /// `S`, m.
    pub(super) motion: f64,
    /// `ω_max`, rad/s.
    pub(super) omega_max: f64,
}

/// Completes `report` from its runs: whether the reference resolves the
/// smallest error, which runs it resolves, and each method's order (the
/// methods in the order of their first run). An unsharded measurement and
/// [`merge`](crate::merge) both end here.
pub(crate) fn conclude(report: &mut AccuracyReport) {
    let reference = &mut report.reference;
    let smallest = report
        .runs
        .iter()
        .filter_map(|r| r.error_rms)
        .fold(f64::INFINITY, f64::min);
    reference.converged = reference.kind == ReferenceKind::Analytic
        || CONVERGED_FACTOR * reference.estimated_error <= smallest;
    for run in &mut report.runs {
        run.resolved = run
            .error_rms
            .is_some_and(|e| e >= CONVERGED_FACTOR * reference.estimated_error);
    }
    let scales = Scales {
        reference_error: reference.estimated_error,
        position: report.position_scale,
        motion: report.motion_scale,
        omega_max: report.omega_max,
    };
    let mut methods: Vec<Method> = Vec::new();
    for run in &report.runs {
        if !methods.contains(&run.integrator) {
            methods.push(run.integrator);
        }
    }
    report.orders = orders(&methods, &report.runs, &scales);
}

/// Each method's order fitted over its runs in the asymptotic range.
fn orders(methods: &[Method], runs: &[Run], scales: &Scales) -> Vec<Order> {
    methods
        .iter()
        .map(|&method| {
            let mut points: Vec<(f64, f64)> = runs
                .iter()
                .filter(|r| r.integrator == method)
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
                integrator: method,
                observed_order: fit::slope(&points),
                expected_order: method.expected_order(),
                steps_fitted: points.iter().map(|p| p.0).collect(),
            }
        })
        .collect()
}
