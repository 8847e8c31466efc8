//! Criterion benchmarks of the explicit side: force evaluation, sequential
//! against parallel (which sets `PARALLEL_MIN_SPRINGS`), and one step of each
//! integrator.
//!
//! Run with `cargo bench --bench explicit`.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use hooke::core::{ForceEvaluator, Parallelism};
use hooke::explicit::fixed_step_integrators;
use hooke::prelude::*;

/// A damped hanging chain of `particles`, stretched 10 % so every spring
/// carries force.
fn chain(particles: usize) -> (System, State) {
    let system = HangingChain::new(particles, 0.01, 1e3, 0.011)
        .damped(0.1, 0.01)
        .system()
        .unwrap();
    let mut state = system.initial_state();
    for (s, x) in state.positions_mut().iter_mut().enumerate() {
        x.y = -(s as f64) * 0.0121;
    }
    (system, state)
}

fn force_evaluation(c: &mut Criterion) {
    let mut group = c.benchmark_group("forces");
    for particles in [1_000, 10_000, 30_000, 100_000, 1_000_000] {
        let (system, state) = chain(particles);
        let mut out = vec![Vec3::zeros(); particles];
        group.throughput(Throughput::Elements(system.springs().len() as u64));
        for (label, parallelism) in [
            ("sequential", Parallelism::Sequential),
            ("parallel", Parallelism::Parallel),
        ] {
            let mut evaluator = ForceEvaluator::new(parallelism);
            group.bench_with_input(BenchmarkId::new(label, particles), &particles, |b, _| {
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

fn one_step(c: &mut Criterion) {
    let mut group = c.benchmark_group("step");
    let (system, initial) = chain(4096);
    let mut integrators = fixed_step_integrators();
    integrators.push(Box::new(DormandPrince::default()));
    for mut integrator in integrators {
        let mut state = initial.clone();
        group.bench_function(integrator.name(), |b| {
            b.iter(|| integrator.step(&system, &mut state, 1e-5).unwrap());
        });
    }
    group.finish();
}

criterion_group!(benches, force_evaluation, one_step);
criterion_main!(benches);
