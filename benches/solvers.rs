//! Criterion benchmarks of the linear solvers on the cloth: N×N
//! particles, 1 m, 1 kg, stretch / shear / bend springs of 5 000 / 500 /
//! 50 N/m with light damping, two corners pinned, one backward-Euler
//! system at `h = 1/60 s` from a wavy state, solved to a relative residual
//! of 10⁻⁶:
//!
//! - `setup`: what a solver builds once per topology (Cholesky's symbolic
//!   analysis, the multigrid hierarchy);
//! - `solve`: one solve as a Newton iteration pays it (Cholesky: refill,
//!   numeric factorization and solve; multigrid: the refresh of every
//!   level's values and PCG; block-Jacobi: PCG);
//! - `step` (a converged step of this cloth takes from 8 Newton solves at
//!   50² to over a hundred at 100²): one converged backward-Euler
//!   step of the integrator, the hierarchy or factor kept from the steps
//!   before, and one step of Liu et al.'s fast mass-spring method (10
//!   iterations).
//!
//! The sides come from `HOOKE_SOLVER_SIDES` (comma-separated, default
//! `50,100,200,400,1000`) and, for `step`, `HOOKE_STEP_SIDES` (default
//! `50,100`; empty for none); Cholesky runs up to 400², block-Jacobi PCG up to
//! 200² (beyond, its thousands of iterations take minutes per sample). The
//! iteration counts and the hierarchies' sizes are printed as the benchmark
//! sets up. `benches/README.md` has the measured table.

use std::hint::black_box;

use criterion::{BatchSize, BenchmarkId, Criterion, criterion_group, criterion_main};
use hooke::core::CompressedSprings;
use hooke::implicit::{
    Amg, AmgSettings, Assembler, BlockJacobi, BlockMatrix, FastMassSpring, Filter, Implicit,
    LinearSolver, Linearization, Pattern, PcgSettings, SparseCholesky, cg,
};
use hooke::prelude::*;
use hooke::scenes::{Corner, Mass, Springs};

const H: f64 = 1.0 / 60.0;

/// The sides in the environment variable `name` (comma-separated), or
/// `default`.
fn sides(name: &str, default: &[usize]) -> Vec<usize> {
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

/// The cloth of `n`×`n` particles.
fn cloth(n: usize) -> System {
    Cloth::grid(n, n)
        .mass(Mass::Total(1.0))
        .stretch(Springs::per_spring(5000.0).damping(0.05))
        .shear(Springs::per_spring(500.0).damping(0.05))
        .bend(Springs::per_spring(50.0))
        .pin_corners([Corner::TopLeft, Corner::TopRight])
        .build()
        .unwrap()
        .system([0.0, -9.81, 0.0])
        .unwrap()
}

/// The cloth in a wavy state (a flat one has no out-of-plane stiffness).
fn wavy(system: &System) -> State {
    let mut state = system.initial_state();
    for x in state.positions_mut() {
        x.y = 0.02 * (7.0 * x.x).sin() * (5.0 * x.z).cos();
    }
    state
}

/// The backward-Euler system of one linearised step.
struct Step {
    a: BlockMatrix,
    jacobi: BlockJacobi,
    b: Vec<Vec3>,
    filters: Vec<Filter>,
}

fn step_system(system: &System, state: &State) -> Step {
    let n = system.particle_count();
    let mut out = Step {
        a: BlockMatrix::zeros(Pattern::new(system).unwrap()),
        jacobi: BlockJacobi::default(),
        b: vec![Vec3::zeros(); n],
        filters: (0..n)
            .map(|i| {
                if system.is_pinned(i) {
                    Filter::Fixed
                } else {
                    Filter::Free
                }
            })
            .collect(),
    };
    let u: Vec<Vec3> = state.velocities().iter().map(|v| H * v).collect();
    let lin = Linearization {
        positions: state.positions(),
        velocities: state.velocities(),
        displacement: Some(&u),
        inertia: &vec![Vec3::zeros(); n],
        beta_h: H,
        compressed: CompressedSprings::Clamped,
        freeze_directions: true,
    };
    Assembler::default()
        .assemble(system, &lin, &mut out.a, &mut out.jacobi, &mut out.b, 0.0)
        .unwrap();
    out
}

fn settings() -> PcgSettings {
    PcgSettings::new(1e-6, 100_000).unwrap()
}

fn linear(c: &mut Criterion) {
    let mut setup = c.benchmark_group("setup");
    setup.sample_size(10);
    let mut cases = Vec::new();
    for n in sides("HOOKE_SOLVER_SIDES", &[50, 100, 200, 400, 1000]) {
        let system = cloth(n);
        let state = wavy(&system);
        let s = step_system(&system, &state);
        if n <= 400 {
            setup.bench_with_input(BenchmarkId::new("cholesky", n), &n, |b, _| {
                b.iter(|| SparseCholesky::new(&s.a).unwrap());
            });
        }
        setup.bench_with_input(BenchmarkId::new("amg", n), &n, |b, _| {
            b.iter(|| {
                Amg::build(&s.a, &s.filters, state.positions(), AmgSettings::default()).unwrap()
            });
        });
        cases.push((n, system, state, s));
    }
    setup.finish();
    let mut solve = c.benchmark_group("solve");
    solve.sample_size(10);
    for (n, _, state, s) in &cases {
        let n = *n;
        let mut x = vec![Vec3::zeros(); s.b.len()];
        let mut workspace = cg::PcgWorkspace::default();
        if n <= 400 {
            let mut cholesky = SparseCholesky::new(&s.a).unwrap();
            solve.bench_with_input(BenchmarkId::new("cholesky", n), &n, |b, _| {
                b.iter(|| cholesky.solve(&s.a, &s.filters, &s.b, &mut x).unwrap());
            });
        }
        let mut amg =
            Amg::build(&s.a, &s.filters, state.positions(), AmgSettings::default()).unwrap();
        x.fill(Vec3::zeros());
        let info = cg::solve(
            &s.a,
            &amg.cycle(&s.a, &s.filters),
            &s.filters,
            &s.b,
            &mut x,
            settings(),
            &mut workspace,
        )
        .unwrap();
        eprintln!(
            "amg {n}²: levels {:?}, {} bytes per particle, {} iterations to {:.1e}",
            amg.unknowns(),
            amg.bytes() / s.b.len(),
            info.iterations,
            info.residual
        );
        solve.bench_with_input(BenchmarkId::new("amg", n), &n, |b, _| {
            b.iter(|| {
                amg.refresh(&s.a, &s.filters).unwrap();
                x.fill(Vec3::zeros());
                cg::solve(
                    &s.a,
                    &amg.cycle(&s.a, &s.filters),
                    &s.filters,
                    &s.b,
                    &mut x,
                    settings(),
                    &mut workspace,
                )
                .unwrap()
            });
        });
        if n <= 200 {
            x.fill(Vec3::zeros());
            let info = cg::solve(
                &s.a,
                &s.jacobi,
                &s.filters,
                &s.b,
                &mut x,
                settings(),
                &mut workspace,
            )
            .unwrap();
            eprintln!("block-Jacobi {n}²: {} iterations", info.iterations);
            solve.bench_with_input(BenchmarkId::new("block-jacobi", n), &n, |b, _| {
                b.iter(|| {
                    x.fill(Vec3::zeros());
                    cg::solve(
                        &s.a,
                        &s.jacobi,
                        &s.filters,
                        &s.b,
                        &mut x,
                        settings(),
                        &mut workspace,
                    )
                    .unwrap()
                });
            });
        }
    }
    solve.finish();
}

/// One converged backward-Euler step of the cloth swinging from its pins
/// (after ten steps from rest), the integrator (and its factor or
/// hierarchy) kept across samples; and the step of Liu et al.'s
/// fast mass-spring method with its 10 local/global iterations, whose
/// distance to the converged step is printed.
fn steps(c: &mut Criterion) {
    let mut group = c.benchmark_group("step");
    group.sample_size(10);
    for n in sides("HOOKE_STEP_SIDES", &[50, 100]) {
        let system = cloth(n);
        let mut start = system.initial_state();
        let mut warm_up = Implicit::backward_euler();
        for _ in 0..10 {
            warm_up.step(&system, &mut start, H).unwrap();
        }
        let mut converged = start.clone();
        Implicit::backward_euler()
            .step(&system, &mut converged, H)
            .unwrap();
        let mut integrators: Vec<(&str, Box<dyn Integrator>)> =
            vec![("fast-mass-spring-10", Box::new(FastMassSpring::default()))];
        if n <= 100 {
            for (name, solver) in [
                ("auto", LinearSolver::Auto),
                ("cholesky", LinearSolver::Cholesky),
                ("amg", LinearSolver::Amg(PcgSettings::default())),
            ] {
                integrators.push((
                    name,
                    Box::new(Implicit::backward_euler().with_solver(solver)),
                ));
            }
        }
        for (name, mut integrator) in integrators {
            let mut state = start.clone();
            let report = integrator.step(&system, &mut state, H).unwrap();
            let distance = state
                .positions()
                .iter()
                .zip(converged.positions())
                .map(|(p, q)| (p - q).norm())
                .fold(0.0, f64::max);
            eprintln!(
                "step {name} {n}²: {} ({} Newton iterations, {} linear iterations), {distance:.1e} m from the converged step",
                report.linear_solver, report.newton_iterations, report.linear_iterations
            );
            group.bench_with_input(BenchmarkId::new(name, n), &n, |b, _| {
                b.iter_batched_ref(
                    || start.clone(),
                    |state| black_box(integrator.step(&system, state, H).unwrap()),
                    BatchSize::LargeInput,
                );
            });
        }
    }
    group.finish();
}

criterion_group!(benches, linear, steps);
criterion_main!(benches);
