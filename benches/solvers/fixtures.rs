//! The fixtures the groups share: the cloth's states and linearised step
//! (the cloth itself is `Sheet::cloth`), the integrators compared and the
//! benchmark of one step.

use std::hint::black_box;

use criterion::measurement::WallTime;
use criterion::{BatchSize, BenchmarkGroup, BenchmarkId};
use hooke::implicit::internals::{BlockJacobi, BlockMatrix, Filter};
use hooke::implicit::{AmgRenewal, FastMassSpring, Implicit, LinearSolver, PcgSettings};
use hooke::prelude::*;

use crate::common;

pub const H: f64 = 1.0 / 60.0;

/// The damping of the stretch and shear springs, N·s/m.
pub const DAMPING: f64 = 0.05;

/// The sides in the environment variable `name` (comma-separated), or
/// `default`.
pub fn sides(name: &str, default: &[usize]) -> Vec<usize> {
    std::env::var(name).ok().map_or_else(
        || default.to_vec(),
        |s| {
            s.split(',')
                .filter(|n| !n.trim().is_empty())
                .map(|n| n.trim().parse().unwrap())
                .collect()
        },
    )
}

/// The backward-Euler system of one linearised step, with its pins'
/// filters.
pub struct Step {
    pub a: BlockMatrix,
    pub jacobi: BlockJacobi,
    pub b: Vec<Vec3>,
    pub filters: Vec<Filter>,
}

pub fn step_system(system: &System, state: &State) -> Step {
    let (a, b, jacobi) = common::linearised_step(system, state, H);
    Step {
        a,
        jacobi,
        b,
        filters: common::pin_filters(system),
    }
}

pub fn settings() -> PcgSettings {
    PcgSettings::new(1e-6, 100_000).unwrap()
}

/// The largest distance between the particles of two states.
pub fn distance(a: &State, b: &State) -> f64 {
    a.positions()
        .iter()
        .zip(b.positions())
        .map(|(p, q)| (p - q).norm())
        .fold(0.0, f64::max)
}

/// The cloth after ten converged steps from rest, swinging from its pins.
pub fn swinging(system: &System) -> State {
    let mut state = system.initial_state();
    let mut warm_up = Implicit::backward_euler();
    for _ in 0..10 {
        warm_up.step(system, &mut state, H).unwrap();
    }
    state
}

/// Benchmarks one step of `h` of `integrator` from `start`, printing its
/// report and, given a reference, its distance to it.
pub fn bench_step(
    group: &mut BenchmarkGroup<'_, WallTime>,
    (name, case): (&str, impl std::fmt::Display),
    (system, h): (&System, f64),
    (start, reference): (&State, Option<&State>),
    integrator: &mut dyn Integrator,
) {
    let mut state = start.clone();
    let report = integrator.step(system, &mut state, h).unwrap();
    let distance = reference.map_or(String::new(), |reference| {
        format!(", {:.1e} m from the reference", distance(&state, reference))
    });
    eprintln!(
        "{name} {case}: {} ({} Newton iterations, {} linear solves, {} linear iterations){distance}",
        report.linear_solver,
        report.newton_iterations,
        report.linear_solves,
        report.linear_iterations,
    );
    let id = BenchmarkId::new(name, &case);
    group.bench_function(id, |b| {
        b.iter_batched_ref(
            || start.clone(),
            |state| black_box(integrator.step(system, state, h).unwrap()),
            BatchSize::LargeInput,
        );
    });
    // `auto` may have changed its solver after comparing two on whole
    // steps.
    if name == LinearSolver::Auto.name() {
        let settled = integrator.step(system, &mut start.clone(), h).unwrap();
        eprintln!("{name} {case} after the samples: {}", settled.linear_solver);
    }
}

/// The solvers whose converged steps the `step` and `scene-step` groups
/// compare: `auto` and each of its candidates.
pub fn stepped_solvers() -> [LinearSolver; 4] {
    [
        LinearSolver::Auto,
        LinearSolver::Cholesky,
        LinearSolver::Amg(PcgSettings::default()),
        LinearSolver::Pcg(PcgSettings::default()),
    ]
}

/// The step tightly converged (`ε = 10⁻⁹`) from `start`.
pub fn reference_step(system: &System, start: &State, n: usize) -> State {
    let mut reference = start.clone();
    let report = Implicit::backward_euler()
        .with_newton(ImplicitSettings::NEWTON_ITERATIONS, 1e-9)
        .unwrap()
        .step(system, &mut reference, H)
        .unwrap();
    eprintln!(
        "reference {n}²: converged to ε = 1e-9 in {} Newton iterations, {} substep(s)",
        report.newton_iterations, report.accepted_steps
    );
    reference
}

/// Makes a fresh integrator.
pub type Fresh = Box<dyn Fn() -> Box<dyn Integrator>>;

/// The integrators of the `linearised-step` and `run` groups at side `n`:
/// Liu et al.'s step with 10 iterations (up to 400²), and the linearised
/// backward-Euler step with `auto`, Cholesky (up to 400²), multigrid with
/// both renewals ([`AmgRenewal`]) and block-Jacobi PCG up to side
/// `pcg_sides`.
pub fn linearised_integrators(n: usize, pcg_sides: usize) -> Vec<(&'static str, Fresh)> {
    let linearised = |solver| Implicit::backward_euler().with_solver(solver).linearized();
    let amg = LinearSolver::Amg(PcgSettings::default());
    let pcg = LinearSolver::Pcg(PcgSettings::default());
    let mut integrators: Vec<(&'static str, Fresh)> = vec![
        (
            "auto",
            Box::new(move || Box::new(linearised(LinearSolver::Auto))),
        ),
        ("amg", Box::new(move || Box::new(linearised(amg)))),
        (
            "amg-smoother-only",
            Box::new(move || Box::new(linearised(amg).with_amg_renewal(AmgRenewal::SmootherOnly))),
        ),
    ];
    if n <= 400 {
        integrators.push((
            "cholesky",
            Box::new(move || Box::new(linearised(LinearSolver::Cholesky))),
        ));
        integrators.push((
            "fast-mass-spring-10",
            Box::new(|| Box::new(FastMassSpring::default())),
        ));
    }
    if n <= pcg_sides {
        integrators.push(("pcg", Box::new(move || Box::new(linearised(pcg)))));
    }
    integrators
}

/// The rope of 10 001 particles ([`common::long_rope`]) at `h = 1/60 s` and
/// the tetrahedral cube of 17³ particles ([`common::tet_cube`]) at
/// `h = 1/240 s`.
pub fn other_scenes() -> [(&'static str, System, f64); 2] {
    [
        ("rope", common::long_rope(10_000), H),
        ("tets", common::tet_cube(16), 1.0 / 240.0),
    ]
}
