//! Criterion benchmark of the default scene (`stiff-cloth`): its first
//! simulated second from the initial state under its own integrator,
//! converged, against the same integrator taking Baraff & Witkin's
//! linearised step (`default-scene/converged`, `default-scene/linearized`;
//! the time per step is the reported time over the steps of that second).
//!
//! Run with `cargo bench --bench scene`.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use hooke::implicit::Minimizer;
use hooke::prelude::*;

/// The default scene's first simulated second, from its initial state,
/// with its own integrator and with the same integrator linearised.
fn default_scene(c: &mut Criterion) {
    let scene = builtin::load("stiff-cloth").unwrap();
    let steps = (1.0 / scene.timing.dt).round() as usize;
    let mut linearized = scene.integrator;
    let IntegratorSpec::Implicit { minimizer, .. } = &mut linearized else {
        panic!("the default scene is implicit");
    };
    *minimizer = Minimizer::Linearized;
    let mut group = c.benchmark_group("default-scene");
    group.sample_size(10);
    for (label, spec) in [("converged", scene.integrator), ("linearized", linearized)] {
        group.bench_function(BenchmarkId::new(label, steps), |b| {
            b.iter(|| {
                let mut integrator = spec.build().unwrap();
                let mut state = scene.system.initial_state();
                for _ in 0..steps {
                    integrator
                        .step(&scene.system, &mut state, scene.timing.dt)
                        .unwrap();
                }
                state
            });
        });
    }
    group.finish();
}

criterion_group!(benches, default_scene);
criterion_main!(benches);
