//! Criterion benchmarks of the linear solvers on the cloth
//! (`Sheet::cloth`): N×N particles, 1 m, 1 kg, stretch / shear / bend
//! springs of 5 000 / 500 / 50 N/m with light damping, two corners pinned,
//! one backward-Euler system at `h = 1/60 s` from a wavy state
//! (`Sheet::wavy`), solved to a relative residual of 10⁻⁶:
//!
//! - `setup`: what a solver builds once per topology (Cholesky's symbolic
//!   analysis, the multigrid hierarchy);
//! - `solve`: one solve as a Newton iteration pays it (Cholesky: refill,
//!   numeric factorization and solve, in the particles' fill-reducing order,
//!   `cholesky`, and in faer's order of the scalar unknowns,
//!   `cholesky-scalar-amd`, the solver before; multigrid: the refresh of
//!   every level's values and PCG; block-Jacobi: PCG);
//! - `linearised-step`: Baraff & Witkin's step as the issue measures it —
//!   one linear solve from the wavy state to 10⁻⁶, assembly included — of
//!   the integrator (`Implicit::linearized`), the factor or hierarchy kept
//!   across samples, with each solver, multigrid with both renewals and
//!   `auto`, beside Liu et al.'s fast mass-spring step with 10 iterations
//!   from the same state;
//! - `run`: [`RUN_STEPS`] linearised steps of the cloth falling from the
//!   wavy state, a fresh integrator per sample, with each solver, multigrid
//!   with both renewals ([`AmgRenewal`]), `auto` and Liu et al.'s step
//!   (sides from `HOOKE_RUN_SIDES`, default `50,100`);
//! - `step` (a converged step of this cloth takes 8 linear solves at 50²
//!   and about 26 at 100²): one converged backward-Euler step of the
//!   integrator, the hierarchy or factor kept from the steps before, with
//!   each solver and `auto` (up to 200²; at 100² also multigrid with every
//!   Newton step solved to PCG's own tolerance, `amg-exact-solves`, against
//!   the default inexact Newton), and Liu et al.'s fast mass-spring step
//!   with 10 iterations;
//! - `equal-accuracy`: on the cloth without spring damping, the converged
//!   step against the fast mass-spring step with as many iterations as it
//!   needs to be as accurate (up to 65 536);
//! - `scene-step`: converged steps of a rope and a tetrahedral lattice with
//!   each solver and `auto`, whose best choice is not the cloth's.
//!
//! The sides come from `HOOKE_SOLVER_SIDES` (comma-separated, default
//! `50,100,200,400,1000`), for `step`, `HOOKE_STEP_SIDES`, and for
//! `equal-accuracy`, `HOOKE_EQUAL_SIDES` (both default `50,100`; empty for
//! none: their setup runs even when a filter leaves the group out);
//! Cholesky runs up to 400², block-Jacobi PCG up to 200² (beyond, its thousands of iterations take minutes per sample). The
//! iteration counts and the hierarchies' sizes are printed as the benchmark
//! sets up. `benches/README.md` has the measured table. The fixtures are in
//! `fixtures.rs`, the groups of linear solves in `linear.rs`, those of
//! whole steps in `steps.rs`.

mod fixtures;
mod linear;
mod steps;

use criterion::{criterion_group, criterion_main};

#[allow(dead_code)] // the benches use a few of the tests' helpers
#[path = "../../tests/common/mod.rs"]
mod common;

use self::linear::linear;
use self::steps::{equal_accuracy, linearised_steps, other_scene_steps, runs, steps};

criterion_group!(
    benches,
    linear,
    linearised_steps,
    runs,
    steps,
    equal_accuracy,
    other_scene_steps
);
criterion_main!(benches);
