//! PCG preconditioned by the Cholesky factor of an earlier matrix: exact
//! (one iteration) on the matrix it factorized, the same solution as a fresh
//! factorization on a later one, and the integrator's steps with it match
//! plain Cholesky's.

use hooke::implicit::internals::{BlockMatrix, SparseCholesky, cg};
use hooke::implicit::{Implicit, LinearSolver, PcgSettings};
use hooke::prelude::*;

mod common;

const H: f64 = 1.0 / 60.0;

#[test]
fn a_lagged_factor_preconditions_a_later_matrix() {
    let system = Sheet {
        stiffness: 5e3,
        ..Sheet::new(20)
    }
    .system()
    .unwrap();
    // The cloth falling from rest, five steps in.
    let mut state = system.initial_state();
    let mut integrator = Implicit::backward_euler().with_solver(LinearSolver::Cholesky);
    for _ in 0..5 {
        integrator.step(&system, &mut state, H).unwrap();
    }
    let filters = common::pin_filters(&system);
    let (a0, b0, _) = common::linearised_step(&system, &state, H);
    let mut factor = SparseCholesky::new(&a0).unwrap();
    factor.factorize(&a0, &filters).unwrap();
    let settings = PcgSettings::new(1e-12, 1000).unwrap();
    let solve = |factor: &mut SparseCholesky, a: &BlockMatrix, b: &[Vec3]| {
        let mut x = vec![Vec3::zeros(); b.len()];
        let info = cg::solve(
            a,
            &factor.preconditioner(&filters),
            &filters,
            b,
            &mut x,
            settings,
            &mut Default::default(),
        )
        .unwrap();
        (x, info.iterations)
    };
    let (_, exact) = solve(&mut factor, &a0, &b0);
    assert!(exact <= 1, "{exact} iterations on the factorized matrix");
    // A step later every spring has turned and stretched a little.
    integrator.step(&system, &mut state, H).unwrap();
    let (a1, b1, _) = common::linearised_step(&system, &state, H);
    let (x, lagged) = solve(&mut factor, &a1, &b1);
    let mut expected = vec![Vec3::zeros(); b1.len()];
    SparseCholesky::new(&a1)
        .unwrap()
        .solve(&a1, &filters, &b1, &mut expected)
        .unwrap();
    let scale = expected.iter().map(|v| v.norm()).fold(0.0, f64::max);
    let difference = x
        .iter()
        .zip(&expected)
        .map(|(p, q)| (p - q).norm())
        .fold(0.0, f64::max);
    assert!(difference < 1e-9 * scale, "{difference:e} vs {scale:e}");
    // The factor is the earlier matrix's: PCG iterates, to the same answer.
    assert!(lagged > 1, "{lagged} iterations");
}

#[test]
fn lagged_cholesky_steps_match_cholesky_steps() {
    let system = Sheet {
        stiffness: 5e3,
        ..Sheet::new(16)
    }
    .system()
    .unwrap();
    let (mut a, mut b) = (system.initial_state(), system.initial_state());
    // Every Newton step solved to PCG's tolerance, so that the two solvers'
    // steps agree to it rather than to the Newton tolerance.
    let mut lagged = Implicit::backward_euler()
        .with_solver(LinearSolver::LaggedCholesky(
            PcgSettings::new(1e-10, 100).unwrap(),
        ))
        .with_inexact_newton(false);
    let mut direct = Implicit::backward_euler().with_solver(LinearSolver::Cholesky);
    let mut iterations = 0;
    for _ in 0..10 {
        let report = lagged.step(&system, &mut a, H).unwrap();
        direct.step(&system, &mut b, H).unwrap();
        assert_eq!(report.linear_solver, "lagged-cholesky");
        iterations += report.linear_iterations;
    }
    assert!(iterations > 0);
    for (p, q) in a.positions().iter().zip(b.positions()) {
        assert!((p - q).norm() < 1e-8, "{p:?} vs {q:?}");
    }
}
