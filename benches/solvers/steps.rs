//! The groups of whole steps: `linearised-step`, `run`, `step`,
//! `equal-accuracy` and `scene-step`.

use std::hint::black_box;
use std::time::{Duration, Instant};

use criterion::{BatchSize, BenchmarkId, Criterion};
use hooke::implicit::{FastMassSpring, Implicit, LinearSolver, PcgSettings};
use hooke::prelude::*;

use crate::fixtures::{
    DAMPING, H, bench_step, distance, linearised_integrators, other_scenes, reference_step, sides,
    stepped_solvers, swinging,
};

/// The most iterations of Liu et al.'s step that [`iterations_to_reach`]
/// tries.
pub const MAX_LIU_ITERATIONS: usize = 1 << 16;

/// The fewest iterations (to within an eighth) with which Liu et al.'s
/// step from `start` comes within `target` of `reference`, doubling from
/// its default 10 up to [`MAX_LIU_ITERATIONS`], then bisecting; if even
/// that many do not, the distance they reach and the time that step
/// takes (its one factorization included).
pub fn iterations_to_reach(
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

/// One converged backward-Euler step of the cloth swinging from its pins
/// (after ten steps from rest), the integrator (and its factor or
/// hierarchy) kept across samples, and one step of Liu et al.'s fast
/// mass-spring method with its 10 local/global iterations; each one's
/// distance to the tightly converged step is printed.
pub fn steps(c: &mut Criterion) {
    let mut group = c.benchmark_group("step");
    group.sample_size(10);
    for n in sides("HOOKE_STEP_SIDES", &[50, 100]) {
        let system = Sheet::cloth(n, DAMPING).system().unwrap();
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

/// Baraff & Witkin's linearised step from the wavy state, the issue's
/// measure, with [`linearised_integrators`] (block-Jacobi PCG up to 200²),
/// the integrator kept across samples.
pub fn linearised_steps(c: &mut Criterion) {
    let mut group = c.benchmark_group("linearised-step");
    group.sample_size(10);
    for n in sides("HOOKE_SOLVER_SIDES", &[50, 100, 200, 400, 1000]) {
        let sheet = Sheet::cloth(n, DAMPING);
        let system = sheet.system().unwrap();
        let start = sheet.wavy(&system);
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
pub const RUN_STEPS: usize = 20;

/// A run of [`RUN_STEPS`] linearised steps of the cloth falling from its
/// wavy state, each sample with a fresh integrator (its factor, hierarchy
/// or trial included, as in any run), with [`linearised_integrators`]
/// (block-Jacobi PCG, which stops at its cap from 100², left out). Unlike
/// `linearised-step`, every step starts where the last one ended, so a
/// factor or hierarchy kept from earlier steps meets the matrices of a
/// moving cloth.
pub fn runs(c: &mut Criterion) {
    let mut group = c.benchmark_group("run");
    group.sample_size(10);
    for n in sides("HOOKE_RUN_SIDES", &[50, 100]) {
        let sheet = Sheet::cloth(n, DAMPING);
        let system = sheet.system().unwrap();
        let start = sheet.wavy(&system);
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
pub fn equal_accuracy(c: &mut Criterion) {
    let mut group = c.benchmark_group("equal-accuracy");
    group.sample_size(10);
    for n in sides("HOOKE_EQUAL_SIDES", &[50, 100]) {
        let system = Sheet::cloth(n, 0.0).system().unwrap();
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

/// `auto` off the cloth: one converged step of the rope and of the
/// tetrahedral lattice ([`other_scenes`]) three steps after release, with
/// each solver and with `auto`.
pub fn other_scene_steps(c: &mut Criterion) {
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
