//! Implicit steps that cannot be taken fail with typed errors naming the time
//! and, where known, the particle, and leave the state as it was.

use hooke::core::{CompressedSprings, Parameter, ParameterError};
use hooke::implicit::{Implicit, LinearSolver, PcgSettings};
use hooke::prelude::*;

fn assert_unchanged(system: &System, state: &State) {
    assert_eq!(state.positions(), system.initial_positions());
    assert_eq!(state.velocities(), system.initial_velocities());
}

/// A spring compressed to a tenth of its rest length has transverse
/// stiffness `k(1 − L/l) = −9k`; with the exact blocks and `h²·9k ≫ m` the
/// free particle's diagonal block, hence the step's matrix, is indefinite.
#[test]
fn an_indefinite_system_is_reported_not_solved() {
    let mut b = SystemBuilder::new();
    b.particle(0.1, [0.0; 3]);
    b.particle(0.1, [0.1, 0.0, 0.0]);
    b.spring(0, 1, 1e4).rest_length(1.0);
    b.pin(0).gravity([0.0, -9.81, 0.0]);
    let system = b.build().unwrap();
    for solver in [LinearSolver::default(), LinearSolver::Cholesky] {
        let mut integrator = Implicit::backward_euler()
            .with_solver(solver)
            .with_compressed_springs(CompressedSprings::Exact);
        let mut state = system.initial_state();
        let error = integrator.step(&system, &mut state, 0.1).unwrap_err();
        assert_eq!(
            error,
            StepError::NotPositiveDefinite {
                time: 0.0,
                particle: Some(1)
            },
            "{solver:?}"
        );
        assert_eq!(
            error.to_string(),
            "linear system is not positive definite at particle 1 at t = 0"
        );
        assert_unchanged(&system, &state);
        // Clamped (the default), the same step is well posed.
        let mut clamped = Implicit::backward_euler().with_solver(solver);
        clamped.step(&system, &mut state, 0.1).unwrap();
    }
}

/// A force that overflows makes the linear system non-finite; the error names
/// the first free particle on the offending spring.
#[test]
fn an_overflowing_system_names_the_particle() {
    let mut b = SystemBuilder::new();
    b.particle(1.0, [0.0; 3]);
    b.particle(1.0, [1.0, 0.0, 0.0]);
    b.particle(1.0, [30.0, 0.0, 0.0]);
    b.spring(0, 1, 10.0);
    b.spring(1, 2, 1e308).rest_length(1.0);
    b.pin(0);
    let system = b.build().unwrap();
    for solver in [LinearSolver::default(), LinearSolver::Cholesky] {
        let mut state = system.initial_state();
        state.set_time(2.5);
        let error = Implicit::bdf2()
            .with_solver(solver)
            .step(&system, &mut state, 0.01)
            .unwrap_err();
        assert_eq!(
            error,
            StepError::NonFiniteSystem {
                time: 2.5,
                particle: 1
            }
        );
        assert_eq!(
            error.to_string(),
            "non-finite linear system at particle 1 at t = 2.5"
        );
    }
}

/// A flat sheet at rest is too easy (its vertical block is diagonal), so the
/// sheet starts stretched and moving.
#[test]
fn an_unconverged_solve_fails_only_in_strict_mode() {
    let system = Sheet::new(10).system().unwrap();
    let one_iteration = LinearSolver::Pcg(PcgSettings::new(1e-12, 1).unwrap());
    let mut state = system.initial_state();
    for (k, x) in state.positions_mut().iter_mut().enumerate() {
        *x *= 1.1;
        x.y = 0.01 * (k as f64).sin();
    }
    let before = (state.positions().to_vec(), state.velocities().to_vec());
    let mut strict = Implicit::backward_euler()
        .linearized()
        .with_solver(one_iteration)
        .strict(true);
    let error = strict.step(&system, &mut state, 0.01).unwrap_err();
    assert!(
        matches!(error, StepError::NoConvergence { time: 0.0, iterations: 1, residual } if residual > 1e-12),
        "{error}"
    );
    assert_eq!(
        (state.positions(), state.velocities()),
        (&before.0[..], &before.1[..])
    );
    let report = Implicit::backward_euler()
        .linearized()
        .with_solver(one_iteration)
        .step(&system, &mut state, 0.01)
        .unwrap();
    assert_eq!(
        (
            report.linear_solves,
            report.unconverged_solves,
            report.linear_iterations
        ),
        (1, 1, 1)
    );
    assert!(report.linear_residual > 1e-12);
}

#[test]
fn invalid_settings_name_the_parameter() {
    let pcg = |tolerance: f64, cap: usize| PcgSettings::new(tolerance, cap).unwrap_err().parameter;
    assert_eq!(pcg(0.0, 10), Parameter::Tolerance);
    assert_eq!(pcg(1.0, 10), Parameter::Tolerance);
    assert_eq!(pcg(f64::NAN, 10), Parameter::Tolerance);
    assert_eq!(pcg(1e-6, 0), Parameter::MaxIterations);
    let newton = |iterations: usize, tolerance: f64| -> ParameterError {
        Implicit::bdf2()
            .with_newton(iterations, tolerance)
            .unwrap_err()
    };
    assert_eq!(newton(0, 1e-3).parameter, Parameter::NewtonIterations);
    assert_eq!(newton(3, 0.0).parameter, Parameter::NewtonTolerance);
    assert_eq!(
        newton(3, f64::INFINITY).to_string(),
        "bdf2: newton_tolerance must be positive and finite, got inf"
    );
}

#[test]
fn invalid_steps_and_states_are_rejected() {
    let system = Sheet::new(4).system().unwrap();
    let other = Sheet::new(5).system().unwrap();
    for mut integrator in [
        Implicit::backward_euler(),
        Implicit::bdf2().with_solver(LinearSolver::Cholesky),
    ] {
        let mut state = system.initial_state();
        for dt in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert!(matches!(
                integrator.step(&system, &mut state, dt),
                Err(StepError::InvalidTimestep { .. })
            ));
        }
        let error = integrator.step(&other, &mut state, 0.01).unwrap_err();
        assert_eq!(
            error,
            StepError::StateMismatch {
                state: 16,
                system: 25
            }
        );
        assert_unchanged(&system, &state);
    }
}
