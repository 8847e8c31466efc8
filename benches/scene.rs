//! Criterion benchmarks of whole scenes, each over its first simulated
//! second from the initial state:
//!
//! - `default-scene`: the default scene (`stiff-cloth`) under its own
//!   integrator, converged, against the same integrator taking Baraff &
//!   Witkin's linearised step (`default-scene/converged`,
//!   `default-scene/linearized`; the time per step is the reported time
//!   over the steps of that second);
//! - `supernodes`: backward Euler with the sparse Cholesky factor's
//!   numeric factorization chosen by each rule of `Supernodes`, on the
//!   built-in scenes where the two rules choose differently (the contact
//!   scenes with their bending springs routed, the small volumetric and
//!   shell scenes, the chain).
//!
//! Run with `cargo bench --bench scene`.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use hooke::implicit::{Minimizer, Supernodes, WeakSprings};
use hooke::prelude::*;

/// The steps of a scene's first simulated second.
fn steps(scene: &Scene) -> usize {
    (1.0 / scene.timing.dt).round() as usize
}

/// The scene's first simulated second from its initial state under
/// `integrator`.
fn first_second<I: Integrator + ?Sized>(scene: &Scene, integrator: &mut I) -> State {
    let mut state = scene.system.initial_state();
    for _ in 0..steps(scene) {
        integrator
            .step(&scene.system, &mut state, scene.timing.dt)
            .unwrap();
    }
    state
}

/// The default scene's first simulated second, from its initial state,
/// with its own integrator and with the same integrator linearised.
fn default_scene(c: &mut Criterion) {
    let scene = builtin::load("stiff-cloth").unwrap();
    let steps = steps(&scene);
    let mut linearized = scene.integrator;
    let IntegratorSpec::Implicit(settings) = &mut linearized else {
        panic!("the default scene is implicit");
    };
    settings.minimizer = Minimizer::Linearized;
    let mut group = c.benchmark_group("default-scene");
    group.sample_size(10);
    for (label, spec) in [("converged", scene.integrator), ("linearized", linearized)] {
        group.bench_function(BenchmarkId::new(label, steps), |b| {
            b.iter(|| first_second(&scene, &mut *spec.build().unwrap()));
        });
    }
    group.finish();
}

/// The first simulated second of built-in scenes under backward Euler, the
/// factor's numeric factorization chosen by each rule of [`Supernodes`].
fn supernodes(c: &mut Criterion) {
    let mut group = c.benchmark_group("supernodes");
    group.sample_size(10);
    let cases = [
        ("chain", None),
        ("tet-bracket", None),
        ("obj-tube", None),
        ("layered-ball", None),
        ("cloth-on-sphere", Some(WeakSprings::Routed)),
        ("cloth-pile", Some(WeakSprings::Routed)),
        ("two-cloths", Some(WeakSprings::Routed)),
    ];
    for (name, weak) in cases {
        let scene = builtin::load(name).unwrap();
        let routed = if weak.is_some() { ", routed" } else { "" };
        for (label, rule) in [("blocks", Supernodes::Blocks), ("faer", Supernodes::Faer)] {
            let id = BenchmarkId::new(format!("{name}{routed}"), label);
            group.bench_function(id, |b| {
                b.iter(|| {
                    let mut integrator = Implicit::backward_euler()
                        .with_weak_springs(weak)
                        .with_supernodes(rule);
                    first_second(&scene, &mut integrator)
                });
            });
        }
    }
    group.finish();
}

criterion_group!(benches, default_scene, supernodes);
criterion_main!(benches);
