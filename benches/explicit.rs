//! Criterion benchmarks of the explicit side on cloth sheets: force
//! evaluation, sequential against parallel (which sets
//! `PARALLEL_MIN_SPRINGS`), and one step of each integrator on a 64×64 sheet.
//!
//! Run with `cargo bench --bench explicit`.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
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

fn one_step(c: &mut Criterion) {
    let mut group = c.benchmark_group("step");
    let (system, initial) = sheet(64);
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
