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
//! sets up. `benches/README.md` has the measured table.

use std::hint::black_box;
use std::time::{Duration, Instant};

use criterion::measurement::WallTime;
use criterion::{
    BatchSize, BenchmarkGroup, BenchmarkId, Criterion, criterion_group, criterion_main,
};
use hooke::implicit::internals::{
    Amg, AmgSettings, BlockJacobi, BlockMatrix, Filter, SparseCholesky, cg,
};
use hooke::implicit::{AmgRenewal, FastMassSpring, Implicit, LinearSolver, PcgSettings};
use hooke::prelude::*;
use hooke::scenes::{Corner, Mass, Springs};

#[allow(dead_code)] // the benches use a few of the tests' helpers
#[path = "../tests/common/mod.rs"]
mod common;

const H: f64 = 1.0 / 60.0;

/// The damping of the stretch and shear springs, N·s/m.
const DAMPING: f64 = 0.05;

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

/// The cloth of `n`×`n` particles, its stretch and shear springs
/// damped by `damping` (N·s/m).
fn cloth(n: usize, damping: f64) -> System {
    Cloth::grid(n, n)
        .mass(Mass::Total(1.0))
        .stretch(Springs::per_spring(5000.0).damping(damping))
        .shear(Springs::per_spring(500.0).damping(damping))
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

/// The backward-Euler system of one linearised step, with its pins'
/// filters.
struct Step {
    a: BlockMatrix,
    jacobi: BlockJacobi,
    b: Vec<Vec3>,
    filters: Vec<Filter>,
}

fn step_system(system: &System, state: &State) -> Step {
    let (a, b, jacobi) = common::linearised_step(system, state, H);
    Step {
        a,
        jacobi,
        b,
        filters: common::pin_filters(system),
    }
}

fn settings() -> PcgSettings {
    PcgSettings::new(1e-6, 100_000).unwrap()
}

fn linear(c: &mut Criterion) {
    let mut setup = c.benchmark_group("setup");
    setup.sample_size(10);
    let mut cases = Vec::new();
    for n in sides("HOOKE_SOLVER_SIDES", &[50, 100, 200, 400, 1000]) {
        let system = cloth(n, DAMPING);
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

/// The largest distance between the particles of two states.
fn distance(a: &State, b: &State) -> f64 {
    a.positions()
        .iter()
        .zip(b.positions())
        .map(|(p, q)| (p - q).norm())
        .fold(0.0, f64::max)
}

/// The most iterations of Liu et al.'s step that [`iterations_to_reach`]
/// tries.
const MAX_LIU_ITERATIONS: usize = 1 << 16;

/// The fewest iterations (to within an eighth) with which Liu et al.'s
/// step from `start` comes within `target` of `reference`, doubling from
/// its default 10 up to [`MAX_LIU_ITERATIONS`], then bisecting; if even
/// that many do not, the distance they reach and the time that step
/// takes (its one factorization included).
fn iterations_to_reach(
    system: &System,
    start: &State,
    reference: &State,
    target: f64,
) -> Result<usize, (f64, Duration)> {
    let gap = |iterations: usize| {
        let mut state = start.clone();
        FastMassSpring::new(iterations)
            .unwrap()
            .step(system, &mut state, H)
            .unwrap();
        distance(&state, reference)
    };
    let (mut low, mut high) = (0, FastMassSpring::ITERATIONS);
    loop {
        let started = Instant::now();
        let reached = gap(high);
        if reached <= target {
            break;
        }
        if high == MAX_LIU_ITERATIONS {
            return Err((reached, started.elapsed()));
        }
        (low, high) = (high, (2 * high).min(MAX_LIU_ITERATIONS));
    }
    while high - low > high / 8 {
        let middle = (low + high) / 2;
        if gap(middle) <= target {
            high = middle;
        } else {
            low = middle;
        }
    }
    Ok(high)
}

/// The cloth after ten converged steps from rest, swinging from its pins.
fn swinging(system: &System) -> State {
    let mut state = system.initial_state();
    let mut warm_up = Implicit::backward_euler();
    for _ in 0..10 {
        warm_up.step(system, &mut state, H).unwrap();
    }
    state
}

/// Benchmarks one step of `h` of `integrator` from `start`, printing its
/// report and, given a reference, its distance to it.
fn bench_step(
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
fn stepped_solvers() -> [LinearSolver; 4] {
    [
        LinearSolver::Auto,
        LinearSolver::Cholesky,
        LinearSolver::Amg(PcgSettings::default()),
        LinearSolver::Pcg(PcgSettings::default()),
    ]
}

/// The step tightly converged (`ε = 10⁻⁹`) from `start`.
fn reference_step(system: &System, start: &State, n: usize) -> State {
    let mut reference = start.clone();
    let report = Implicit::backward_euler()
        .with_newton(Implicit::NEWTON_ITERATIONS, 1e-9)
        .unwrap()
        .step(system, &mut reference, H)
        .unwrap();
    eprintln!(
        "reference {n}²: converged to ε = 1e-9 in {} Newton iterations, {} substep(s)",
        report.newton_iterations, report.accepted_steps
    );
    reference
}

/// One converged backward-Euler step of the cloth swinging from its pins
/// (after ten steps from rest), the integrator (and its factor or
/// hierarchy) kept across samples, and one step of Liu et al.'s fast
/// mass-spring method with its 10 local/global iterations; each one's
/// distance to the tightly converged step is printed.
fn steps(c: &mut Criterion) {
    let mut group = c.benchmark_group("step");
    group.sample_size(10);
    for n in sides("HOOKE_STEP_SIDES", &[50, 100]) {
        let system = cloth(n, DAMPING);
        let start = swinging(&system);
        let reference = reference_step(&system, &start, n);
        let mut integrators: Vec<(&str, Box<dyn Integrator>)> =
            vec![("fast-mass-spring-10", Box::new(FastMassSpring::default()))];
        if n <= 200 {
            for solver in stepped_solvers() {
                integrators.push((
                    solver.name(),
                    Box::new(Implicit::backward_euler().with_solver(solver)),
                ));
            }
        }
        if n <= 100 {
            integrators.push((
                "amg-exact-solves",
                Box::new(
                    Implicit::backward_euler()
                        .with_solver(LinearSolver::Amg(PcgSettings::default()))
                        .with_inexact_newton(false),
                ),
            ));
        }
        for (name, mut integrator) in integrators {
            bench_step(
                &mut group,
                (name, n),
                (&system, H),
                (&start, Some(&reference)),
                integrator.as_mut(),
            );
        }
    }
    group.finish();
}

/// Makes a fresh integrator.
type Fresh = Box<dyn Fn() -> Box<dyn Integrator>>;

/// The integrators of the `linearised-step` and `run` groups at side `n`:
/// Liu et al.'s step with 10 iterations (up to 400²), and the linearised
/// backward-Euler step with `auto`, Cholesky (up to 400²), multigrid with
/// both renewals ([`AmgRenewal`]) and block-Jacobi PCG up to side
/// `pcg_sides`.
fn linearised_integrators(n: usize, pcg_sides: usize) -> Vec<(&'static str, Fresh)> {
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

/// Baraff & Witkin's linearised step from the wavy state, the issue's
/// measure, with [`linearised_integrators`] (block-Jacobi PCG up to 200²),
/// the integrator kept across samples.
fn linearised_steps(c: &mut Criterion) {
    let mut group = c.benchmark_group("linearised-step");
    group.sample_size(10);
    for n in sides("HOOKE_SOLVER_SIDES", &[50, 100, 200, 400, 1000]) {
        let system = cloth(n, DAMPING);
        let start = wavy(&system);
        for (name, integrator) in linearised_integrators(n, 200) {
            bench_step(
                &mut group,
                (name, n),
                (&system, H),
                (&start, None),
                integrator().as_mut(),
            );
        }
    }
    group.finish();
}

/// Steps in a sample of the `run` group.
const RUN_STEPS: usize = 20;

/// A run of [`RUN_STEPS`] linearised steps of the cloth falling from its
/// wavy state, each sample with a fresh integrator (its factor, hierarchy
/// or trial included, as in any run), with [`linearised_integrators`]
/// (block-Jacobi PCG, which stops at its cap from 100², left out). Unlike
/// `linearised-step`, every step starts where the last one ended, so a
/// factor or hierarchy kept from earlier steps meets the matrices of a
/// moving cloth.
fn runs(c: &mut Criterion) {
    let mut group = c.benchmark_group("run");
    group.sample_size(10);
    for n in sides("HOOKE_RUN_SIDES", &[50, 100]) {
        let system = cloth(n, DAMPING);
        let start = wavy(&system);
        for (name, integrator) in linearised_integrators(n, 0) {
            let mut state = start.clone();
            let mut fresh = integrator();
            let (mut iterations, mut solvers) = (0, Vec::new());
            for _ in 0..RUN_STEPS {
                let report = fresh.step(&system, &mut state, H).unwrap();
                iterations += report.linear_iterations;
                solvers.push(report.linear_solver);
            }
            solvers.dedup();
            eprintln!(
                "{name} {n}: {RUN_STEPS} steps, {iterations} linear iterations, solvers {solvers:?}"
            );
            group.bench_function(BenchmarkId::new(name, n), |b| {
                b.iter_batched(
                    || (start.clone(), integrator()),
                    |(mut state, mut integrator)| {
                        for _ in 0..RUN_STEPS {
                            black_box(integrator.step(&system, &mut state, H).unwrap());
                        }
                    },
                    BatchSize::LargeInput,
                );
            });
        }
    }
    group.finish();
}

/// Equal accuracy: on the cloth without spring damping (which Liu et
/// al.'s method leaves out, so that with it the method converges to
/// another step), one converged backward-Euler step at the defaults, and
/// one step of the fast mass-spring method with as many iterations as it
/// needs to come as close to the tightly converged step.
fn equal_accuracy(c: &mut Criterion) {
    let mut group = c.benchmark_group("equal-accuracy");
    group.sample_size(10);
    for n in sides("HOOKE_EQUAL_SIDES", &[50, 100]) {
        let system = cloth(n, 0.0);
        let start = swinging(&system);
        let reference = reference_step(&system, &start, n);
        let mut converged = start.clone();
        Implicit::backward_euler()
            .step(&system, &mut converged, H)
            .unwrap();
        let target = distance(&converged, &reference);
        bench_step(
            &mut group,
            ("backward-euler", n),
            (&system, H),
            (&start, Some(&reference)),
            &mut Implicit::backward_euler(),
        );
        match iterations_to_reach(&system, &start, &reference, target) {
            Ok(iterations) => bench_step(
                &mut group,
                (&format!("fast-mass-spring-{iterations}"), n),
                (&system, H),
                (&start, Some(&reference)),
                &mut FastMassSpring::new(iterations).unwrap(),
            ),
            Err((reached, time)) => eprintln!(
                "fast mass-spring {n}²: {reached:.1e} m from the reference after {MAX_LIU_ITERATIONS} iterations ({:.1} s), not within {target:.1e} m",
                time.as_secs_f64()
            ),
        }
    }
    group.finish();
}

/// The rope of 10 001 particles ([`common::long_rope`]) at `h = 1/60 s` and
/// the tetrahedral cube of 17³ particles ([`common::tet_cube`]) at
/// `h = 1/240 s`.
fn other_scenes() -> [(&'static str, System, f64); 2] {
    [
        ("rope", common::long_rope(10_000), H),
        ("tets", common::tet_cube(16), 1.0 / 240.0),
    ]
}

/// `auto` off the cloth: one converged step of the rope and of the
/// tetrahedral lattice ([`other_scenes`]) three steps after release, with
/// each solver and with `auto`.
fn other_scene_steps(c: &mut Criterion) {
    let mut group = c.benchmark_group("scene-step");
    group.sample_size(10);
    for (scene, system, h) in other_scenes() {
        let mut start = system.initial_state();
        let mut warm_up = Implicit::backward_euler().with_solver(LinearSolver::Cholesky);
        for _ in 0..3 {
            warm_up.step(&system, &mut start, h).unwrap();
        }
        for solver in stepped_solvers() {
            bench_step(
                &mut group,
                (solver.name(), scene),
                (&system, h),
                (&start, None),
                &mut Implicit::backward_euler().with_solver(solver),
            );
        }
    }
    group.finish();
}

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
