//! The adaptive Dormand–Prince integrator: it meets its tolerance, beats
//! fixed-step RK4 where the stiffness changes in time, and fails cleanly.

use approx::assert_abs_diff_eq;
use hooke::core::{Parameter, ParameterError};
use hooke::prelude::*;

/// With `rtol = atol = tol` and `|y| ≤ 1` each component is allowed an error
/// between `tol` and `2 tol`; over one period of the oscillator (where errors
/// are not amplified) the global error stays inside that band, whether the
/// period is covered in one call or in sixteen.
#[test]
fn meets_its_tolerance_over_one_period_of_the_oscillator() {
    let oscillator = Oscillator::undamped(1.0, 1.0);
    let system = oscillator.system().unwrap();
    let period = std::f64::consts::TAU;
    for tol in [1e-3, 1e-4, 1e-6, 1e-8, 1e-10] {
        for calls in [1, 16] {
            let mut dopri = DormandPrince::new(tol, tol).unwrap();
            let mut state = system.initial_state();
            let mut worst: f64 = 0.0;
            for _ in 0..calls {
                dopri
                    .step(&system, &mut state, period / f64::from(calls))
                    .unwrap();
                let (u, v) = oscillator.solution(state.time());
                let bob = Oscillator::BOB;
                worst = worst
                    .max((state.positions()[bob].x - u).abs())
                    .max((state.velocities()[bob].x - v).abs());
            }
            assert!(
                worst <= 2.0 * tol,
                "tol {tol:e} in {calls} calls: error {worst:.3e}"
            );
        }
    }
}

/// Position of the bead at every frame, and the summed report.
fn bead_frames(
    system: &System,
    integrator: &mut dyn Integrator,
    frame: f64,
    frames: usize,
    substeps: usize,
) -> (Vec<f64>, StepReport) {
    let mut state = system.initial_state();
    let mut report = StepReport::default();
    let mut positions = Vec::with_capacity(frames);
    for _ in 0..frames {
        for _ in 0..substeps {
            report += integrator
                .step(system, &mut state, frame / substeps as f64)
                .unwrap();
        }
        positions.push(state.positions()[BeadOnString::BEAD].y);
    }
    (positions, report)
}

fn max_difference(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// The damped bead on a string starts stiff (ω ≈ √(2k/m) ≈ 141 rad/s at
/// 10 m amplitude) and ends soft (its cubic restoring force fades with the
/// amplitude). Fixed-step RK4 must use the step the start demands all the
/// way; the adaptive method lengthens its step as the stiffness falls.
#[test]
fn takes_fewer_steps_than_rk4_for_the_same_error_when_stiffness_changes() {
    let bead = BeadOnString {
        mass: 1.0,
        stiffness: 1e4,
        half_span: 1.0,
        amplitude: 10.0,
        air_damping: 2.0,
    };
    let system = bead.system().unwrap();
    let (frame, frames) = (0.05, 200);

    // Reference: RK4 at dt = 1e-5 s, converged: halving its step changes it
    // by far less than the errors compared below.
    let (reference, _) = bead_frames(&system, &mut Rk4::new(), frame, frames, 5000);
    let (coarser, _) = bead_frames(&system, &mut Rk4::new(), frame, frames, 2500);
    let reference_error = max_difference(&reference, &coarser);

    let (adaptive, adaptive_report) = bead_frames(
        &system,
        &mut DormandPrince::new(1e-8, 1e-8).unwrap(),
        frame,
        frames,
        1,
    );
    let adaptive_error = max_difference(&adaptive, &reference);
    assert!(
        reference_error < 1e-3 * adaptive_error,
        "reference not converged: {reference_error:.2e}"
    );

    // The coarsest RK4 step (halving from 1 ms) that is at least as accurate.
    let mut substeps = 50;
    let rk4_report = loop {
        let (fixed, report) = bead_frames(&system, &mut Rk4::new(), frame, frames, substeps);
        if max_difference(&fixed, &reference) <= adaptive_error {
            break report;
        }
        substeps *= 2;
    };
    eprintln!(
        "dopri5: error {adaptive_error:.2e} with {adaptive_report:?}; rk4 needs {rk4_report:?}"
    );
    assert!(
        adaptive_report.rejected_steps > 0,
        "the controller never had to reject"
    );
    let adaptive_substeps = adaptive_report.accepted_steps + adaptive_report.rejected_steps;
    assert!(adaptive_substeps < rk4_report.accepted_steps);
    assert!(adaptive_report.force_evaluations < rk4_report.force_evaluations);
}

#[test]
fn rejects_invalid_tolerances() {
    for (rtol, atol, parameter) in [
        (-1e-6, 1e-6, Parameter::Rtol),
        (f64::NAN, 1e-6, Parameter::Rtol),
        (1e-6, f64::INFINITY, Parameter::Atol),
        (0.0, 0.0, Parameter::Atol),
    ] {
        let error: ParameterError = DormandPrince::new(rtol, atol).unwrap_err();
        assert_eq!(error.parameter, parameter);
        assert_eq!(error.integrator, DormandPrince::NAME);
    }
}

#[test]
fn a_capped_step_fails_with_the_state_unchanged() {
    let system = Oscillator::undamped(1.0, 1e6).system().unwrap();
    let mut state = system.initial_state();
    let before = state.positions().to_vec();
    let mut dopri = DormandPrince::new(1e-10, 1e-10).unwrap().max_substeps(5);
    let error = dopri.step(&system, &mut state, 1.0).unwrap_err();
    assert!(
        matches!(error, StepError::TooManySubsteps { substeps: 5, .. }),
        "{error}"
    );
    assert_eq!(state.positions(), &before[..]);
    assert_abs_diff_eq!(state.time(), 0.0, epsilon = 0.0);
}
