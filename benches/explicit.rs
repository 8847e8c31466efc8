//! Criterion benchmarks of the explicit side on cloth sheets: force
//! evaluation, sequential against parallel (which sets
//! `PARALLEL_MIN_SPRINGS`), and 50 steps of each integrator on a 64×64 sheet.
//!
//! Run with `cargo bench --bench explicit`.

use criterion::{BatchSize, BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use hooke::core::{ForceEvaluator, Parallelism};
use hooke::explicit::fixed_step_integrators;
use hooke::prelude::*;

/// A `n`×`n` cloth sheet and a state stretched 10 % so every spring
/// carries force.
fn sheet(n: usize) -> (System, State) {
    let system = Sheet::new(n).system().unwrap();
    let mut state = system.initial_state();
    for x in state.positions_mut() {
        *x *= 1.1;
    }
    (system, state)
}

fn force_evaluation(c: &mut Criterion) {
    let mut group = c.benchmark_group("forces");
    for n in [32, 64, 128, 256, 512] {
        let (system, state) = sheet(n);
        let mut out = vec![Vec3::zeros(); system.particle_count()];
        group.throughput(Throughput::Elements(system.springs().len() as u64));
        let springs = system.springs().len();
        for (label, parallelism) in [
            ("sequential", Parallelism::Sequential),
            ("parallel", Parallelism::Parallel),
        ] {
            let mut evaluator = ForceEvaluator::new(parallelism);
            group.bench_with_input(BenchmarkId::new(label, springs), &springs, |b, _| {
                b.iter(|| {
                    evaluator.accelerations(
                        &system,
                        state.positions(),
                        state.velocities(),
                        &mut out,
                    )
                });
            });
        }
    }
    group.finish();
}

/// 50 steps of each integrator from the stretched 64×64 sheet. Every
/// iteration starts from a fresh copy of the state (explicit Euler gains
/// energy at every step and would eventually overflow), so the multistep
/// methods pay one start per 50 steps.
fn fifty_steps(c: &mut Criterion) {
    const STEPS: usize = 50;
    let mut group = c.benchmark_group("fifty_steps");
    let (system, initial) = sheet(64);
    let mut integrators = fixed_step_integrators();
    integrators.push(Box::new(DormandPrince::default()));
    for mut integrator in integrators {
        group.bench_function(integrator.name(), |b| {
            b.iter_batched_ref(
                || initial.clone(),
                |state| {
                    for _ in 0..STEPS {
                        integrator.step(&system, state, 1e-5).unwrap();
                    }
                },
                BatchSize::LargeInput,
            );
        });
    }
    group.finish();
}

criterion_group!(benches, force_evaluation, fifty_steps);
criterion_main!(benches);
