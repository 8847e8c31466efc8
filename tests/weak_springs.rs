//! Weak springs routed (`WeakSprings::Routed`) change the matrix a step
//! factorizes, not the step: in Newton's Cholesky factor, which then
//! preconditions CG on the step's matrix, and in the quasi-Newton step's
//! `H₀` (its default), converged steps are the same minimiser of `Φ` as
//! with every spring in place.

use hooke::implicit::{Implicit, LinearSolver, Minimizer, WeakSprings};
use hooke::prelude::*;

/// The solver benchmarks' cloth ([`Sheet::cloth`]) of 14 × 14 particles,
/// undamped: its bending springs are a hundredth as stiff as its stretch
/// springs, so a factor routes them.
fn cloth() -> System {
    Sheet::cloth(14, 0.0).system().unwrap()
}

/// Twelve steps of 1/60 s of `integrator` on `system` from rest: the state
/// they end in and each step's report.
fn run(system: &System, integrator: &mut Implicit) -> (State, Vec<StepReport>) {
    let mut state = system.initial_state();
    let reports = (0..12)
        .map(|_| integrator.step(system, &mut state, 1.0 / 60.0).unwrap())
        .collect();
    (state, reports)
}

/// The largest distance between the particles of two states.
fn farthest(a: &State, b: &State) -> f64 {
    a.positions()
        .iter()
        .zip(b.positions())
        .map(|(x, y)| (x - y).norm())
        .fold(0.0, f64::max)
}

#[test]
fn routed_and_kept_factors_take_the_same_converged_steps() {
    let system = cloth();
    let newton = |weak: WeakSprings| {
        let mut integrator = Implicit::backward_euler()
            .with_solver(LinearSolver::Cholesky)
            .with_weak_springs(weak)
            .with_newton(200, 1e-9)
            .unwrap();
        let (state, reports) = run(&system, &mut integrator);
        let linear_iterations: usize = reports.iter().map(|r| r.linear_iterations).sum();
        (state, linear_iterations)
    };
    let (routed, cg_iterations) = newton(WeakSprings::Routed);
    let (kept, direct_iterations) = newton(WeakSprings::Kept);
    // The routed factor is of another matrix, so CG iterates; the kept one
    // solves directly.
    assert!(cg_iterations > 0);
    assert_eq!(direct_iterations, 0);
    // The cloth has swung down by a fair part of a metre; the two runs
    // end within a micrometre of each other.
    let fallen = kept.positions().iter().map(|x| -x.y).fold(0.0, f64::max);
    assert!(fallen > 0.1, "{fallen}");
    let apart = farthest(&routed, &kept);
    assert!(apart < 1e-6, "{apart} m apart");
}

#[test]
fn routed_and_kept_initial_hessians_take_the_same_converged_quasi_newton_steps() {
    let system = cloth();
    let quasi_newton = |weak: Option<WeakSprings>| {
        let mut integrator = Implicit::backward_euler()
            .with_minimizer(Minimizer::quasi_newton())
            .with_weak_springs(weak)
            .with_newton(2000, 1e-9)
            .unwrap();
        let (state, reports) = run(&system, &mut integrator);
        assert!(reports.iter().all(|r| r.unconverged_steps == 0));
        let iterations: Vec<usize> = reports.iter().map(|r| r.newton_iterations).collect();
        (state, iterations)
    };
    let (routed, routed_iterations) = quasi_newton(Some(WeakSprings::Routed));
    let (kept, kept_iterations) = quasi_newton(Some(WeakSprings::Kept));
    let (default, default_iterations) = quasi_newton(None);
    // Two initial Hessians, two sequences of iterates; the default is the
    // routed one.
    assert_ne!(routed_iterations, kept_iterations);
    assert_eq!(default_iterations, routed_iterations);
    assert_eq!(default.positions(), routed.positions());
    // Both end where Newton's converged steps end.
    let mut newton = Implicit::backward_euler()
        .with_solver(LinearSolver::Cholesky)
        .with_newton(200, 1e-10)
        .unwrap();
    let (reference, _) = run(&system, &mut newton);
    for (name, state) in [("routed", &routed), ("kept", &kept)] {
        let apart = farthest(state, &reference);
        assert!(apart < 1e-5, "{name}: {apart} m from Newton's steps");
    }
}
