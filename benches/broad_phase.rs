//! Criterion benchmark of the broad phase's grid cell side: the default
//! scene's cloth (1 600 particles) draped half a second in, a proximity
//! search with the reach of the contact step's widest list (`d̂` plus a
//! quarter of the mean edge) and a swept search over its next step's
//! motion, and a flat 200 × 200 cloth's proximity search at the same
//! reach in its units; each with the cell side at 1.5 and at
//! `CELL_FACTOR` (2.5) times the triangles' mean box side. The pairs
//! found do not depend on it (`collision::broad`'s tests).
//!
//! Run with `cargo bench --bench broad_phase`.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use hooke::core::Parallelism;
use hooke::core::collision::broad::{BroadPhase, CELL_FACTOR, Candidates};
use hooke::prelude::*;
use hooke::scenes::{Mass, Springs};

/// The mean length of a system's surface edges at its positions `x`.
fn mean_edge(system: &System, x: &[Vec3]) -> f64 {
    let edges = system.surfaces().edges();
    let total: f64 = edges.iter().map(|&[a, b]| (x[a] - x[b]).norm()).sum();
    total / edges.len() as f64
}

fn broad_phase(c: &mut Criterion) {
    let scene = builtin::load("stiff-cloth").unwrap();
    let (system, dt) = (&scene.system, scene.timing.dt);
    let mut integrator = scene.integrator.build().unwrap();
    let mut state = system.initial_state();
    for _ in 0..30 {
        integrator.step(system, &mut state, dt).unwrap();
    }
    let draped = state.positions().to_vec();
    integrator.step(system, &mut state, dt).unwrap();
    let next = state.positions().to_vec();
    let reach = system.contact_distance() + 0.25 * mean_edge(system, system.initial_positions());

    let flat = Cloth::grid(200, 200)
        .mass(Mass::Total(1.0))
        .stretch(Springs::per_spring(5000.0))
        .build()
        .unwrap()
        .system([0.0, -9.81, 0.0])
        .unwrap();
    let flat_x = flat.initial_positions().to_vec();
    let flat_reach = flat.contact_distance() + 0.25 * mean_edge(&flat, &flat_x);

    let mut group = c.benchmark_group("broad-phase");
    for factor in [1.5, CELL_FACTOR] {
        let mut broad = BroadPhase::new(Parallelism::Auto)
            .with_cell_factor(factor)
            .unwrap();
        let mut found = Candidates::default();
        let surfaces = system.surfaces();
        group.bench_function(BenchmarkId::new("default-scene/proximity", factor), |b| {
            b.iter(|| {
                broad.proximity(surfaces, &draped, reach, &mut found);
                found.edge_edge.len()
            });
        });
        group.bench_function(BenchmarkId::new("default-scene/swept", factor), |b| {
            b.iter(|| {
                broad.swept(
                    surfaces,
                    &draped,
                    &next,
                    system.contact_distance(),
                    &mut found,
                );
                found.edge_edge.len()
            });
        });
        group.bench_function(BenchmarkId::new("flat-200/proximity", factor), |b| {
            b.iter(|| {
                broad.proximity(flat.surfaces(), &flat_x, flat_reach, &mut found);
                found.edge_edge.len()
            });
        });
    }
    group.finish();
}

criterion_group!(benches, broad_phase);
criterion_main!(benches);
