//! Criterion benchmarks of the implicit side on cloth sheets of 32² … 256²
//! particles at two stiffnesses, `k h²/m = 1e2` and `1e6` with `h = 1/30 s`:
//! pattern build, value refill (assembly), matrix-vector product (the block
//! storage against faer's scalar compressed columns), one PCG solve,
//! Cholesky numeric factorization and solve, and one full backward-Euler
//! step; and a STREAM triad, so the product's bandwidth can be read as a
//! fraction of the machine's.
//!
//! Run with `cargo bench --bench implicit`; `benches/README.md` has the
//! measured table. The PCG iteration counts are printed as the benchmark
//! sets up.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use faer::sparse::linalg::matmul::sparse_dense_matmul;
use faer::{Accum, MatMut, MatRef, Par};
use hooke::core::{At, CompressedSprings, StepStart};
use hooke::implicit::internals::{BlockJacobi, BlockMatrix, Filter, Pattern, SparseCholesky, cg};
use hooke::implicit::{Implicit, PcgSettings, Terms};
use hooke::prelude::*;

#[allow(dead_code)] // the benches use a few of the tests' helpers
#[path = "../tests/common/mod.rs"]
mod common;

const H: f64 = 1.0 / 30.0;
const SIDES: [usize; 4] = [32, 64, 128, 256];
const STIFFNESS: [(&str, f64); 2] = [("soft", 1e2), ("stiff", 1e6)];

/// A `side`² sheet with `k h²/m = ratio`, in a wavy, stretched, moving state
/// (a flat sheet at rest would make the vertical solve trivial).
fn sheet(side: usize, ratio: f64) -> (System, State) {
    let system = Sheet {
        damping: 1e-3,
        ..Sheet::new(side).with_stiffness_ratio(ratio, H)
    }
    .system()
    .unwrap();
    let mut state = system.initial_state();
    for x in state.positions_mut() {
        *x *= 1.02;
        x.y = 0.02 * (7.0 * x.x).sin() * (5.0 * x.z).cos();
    }
    for (v, x) in state
        .velocities_mut()
        .iter_mut()
        .zip(system.initial_positions())
    {
        *v = Vec3::new(0.1 * (3.0 * x.z).sin(), -0.5, 0.1 * (2.0 * x.x).cos());
    }
    (system, state)
}

/// A system assembled for one backward-Euler step from `state`.
struct Assembled {
    matrix: BlockMatrix,
    jacobi: BlockJacobi,
    rhs: Vec<Vec3>,
    filters: Vec<Filter>,
}

/// Baraff & Witkin's linearised step at the start of a step from `state`
/// (the dampers' directions frozen there), assembled by `terms`.
fn assemble(system: &System, state: &State, terms: &mut Terms, out: &mut Assembled) {
    let (x, v) = (state.positions(), state.velocities());
    let u: Vec<Vec3> = v.iter().map(|v| H * v).collect();
    let step = StepStart {
        x,
        v,
        time: 0.0,
        h: H,
        beta_h: H,
    };
    terms.begin(system, &step);
    let at = At {
        x,
        v,
        v_tilde: v,
        beta_h: H,
        displacement: Some(&u),
        compressed: CompressedSprings::Clamped,
    };
    terms
        .assemble(
            system,
            &at,
            &mut out.matrix,
            &mut out.jacobi,
            &mut out.rhs,
            0.0,
        )
        .unwrap();
}

fn assembled(system: &System, state: &State) -> Assembled {
    let (matrix, rhs, jacobi) = common::linearised_step(system, state, H);
    Assembled {
        matrix,
        jacobi,
        rhs,
        filters: common::pin_filters(system),
    }
}

/// Bytes a product must move at least: per particle its mass term, row
/// start, `x` read and `y` written (with its write-allocate read); per spring
/// its block and column index.
fn block_product_bytes(system: &System) -> u64 {
    let (n, m) = (
        system.particle_count() as u64,
        system.springs().len() as u64,
    );
    n * (8 + 4 + 24 + 48) + m * (48 + 4)
}

/// The same for a scalar compressed-column matrix with 64-bit indices.
fn scalar_product_bytes(system: &System) -> u64 {
    let (n, m) = (
        system.particle_count() as u64,
        system.springs().len() as u64,
    );
    (9 * n + 18 * m) * 16 + (3 * n + 1) * 8 + 3 * n * 8 * 3
}

/// STREAM triad `a = b + s c` on arrays far larger than the caches, single
/// threaded and on every core.
fn stream(c: &mut Criterion) {
    const LEN: usize = 1 << 23;
    let (mut a, b, d) = (vec![0.0f64; LEN], vec![1.0f64; LEN], vec![2.0f64; LEN]);
    let mut group = c.benchmark_group("stream");
    group
        .throughput(Throughput::Bytes((4 * 8 * LEN) as u64))
        .sample_size(20);
    group.bench_function("triad/1-thread", |bench| {
        bench.iter(|| {
            for ((ai, bi), di) in a.iter_mut().zip(&b).zip(&d) {
                *ai = bi + 3.0 * di;
            }
        });
    });
    group.bench_function("triad/all-threads", |bench| {
        use rayon::prelude::*;
        bench.iter(|| {
            a.par_chunks_mut(1 << 16)
                .zip(b.par_chunks(1 << 16))
                .zip(d.par_chunks(1 << 16))
                .for_each(|((a, b), d)| {
                    for ((ai, bi), di) in a.iter_mut().zip(b).zip(d) {
                        *ai = bi + 3.0 * di;
                    }
                });
        });
    });
    group.finish();
}

fn pattern_and_refill(c: &mut Criterion) {
    let mut group = c.benchmark_group("pattern");
    for side in SIDES {
        let (system, _) = sheet(side, 1e2);
        group.bench_with_input(BenchmarkId::from_parameter(side), &side, |b, _| {
            b.iter(|| Pattern::new(&system).unwrap());
        });
    }
    group.finish();
    let mut group = c.benchmark_group("refill");
    for side in SIDES {
        for (label, ratio) in STIFFNESS {
            let (system, state) = sheet(side, ratio);
            let mut out = assembled(&system, &state);
            let mut terms = Terms::new(&system).unwrap();
            group.bench_with_input(BenchmarkId::new(label, side), &side, |b, _| {
                b.iter(|| assemble(&system, &state, &mut terms, &mut out));
            });
        }
    }
    group.finish();
}

fn products(c: &mut Criterion) {
    let mut group = c.benchmark_group("spmv");
    for side in SIDES {
        let (system, state) = sheet(side, 1e6);
        let a = assembled(&system, &state);
        let n = system.particle_count();
        let x = state.velocities().to_vec();
        let mut y = vec![Vec3::zeros(); n];
        group.throughput(Throughput::Bytes(block_product_bytes(&system)));
        group.bench_with_input(BenchmarkId::new("block3", side), &side, |b, _| {
            b.iter(|| a.matrix.apply(&x, &mut y));
        });
        let scalar = a.matrix.to_scalar();
        let flat: Vec<f64> = x.iter().flat_map(|v| v.iter().copied()).collect();
        let mut out = vec![0.0; 3 * n];
        group.throughput(Throughput::Bytes(scalar_product_bytes(&system)));
        group.bench_with_input(BenchmarkId::new("faer-csc", side), &side, |b, _| {
            b.iter(|| {
                sparse_dense_matmul(
                    MatMut::from_column_major_slice_mut(&mut out, 3 * n, 1),
                    Accum::Replace,
                    scalar.as_ref(),
                    MatRef::from_column_major_slice(&flat, 3 * n, 1),
                    1.0,
                    Par::Seq,
                );
            });
        });
    }
    group.finish();
}

fn solves(c: &mut Criterion) {
    let mut group = c.benchmark_group("pcg");
    group.sample_size(10);
    for side in SIDES {
        for (label, ratio) in STIFFNESS {
            let (system, state) = sheet(side, ratio);
            let a = assembled(&system, &state);
            let n = system.particle_count();
            let settings = PcgSettings::new(1e-6, 100_000).unwrap();
            let mut workspace = cg::PcgWorkspace::default();
            let mut x = vec![Vec3::zeros(); n];
            let info = cg::solve(
                &a.matrix,
                &a.jacobi,
                &a.filters,
                &a.rhs,
                &mut x,
                settings,
                &mut workspace,
            )
            .unwrap();
            eprintln!(
                "pcg {label} {side}²: {} iterations to relative residual {:.1e}",
                info.iterations, info.residual
            );
            group.bench_with_input(BenchmarkId::new(label, side), &side, |b, _| {
                b.iter(|| {
                    x.fill(Vec3::zeros());
                    cg::solve(
                        &a.matrix,
                        &a.jacobi,
                        &a.filters,
                        &a.rhs,
                        &mut x,
                        settings,
                        &mut workspace,
                    )
                    .unwrap()
                });
            });
        }
    }
    group.finish();
    let mut group = c.benchmark_group("cholesky");
    group.sample_size(10);
    for side in SIDES {
        for (label, ratio) in STIFFNESS {
            let (system, state) = sheet(side, ratio);
            let a = assembled(&system, &state);
            let mut factor = SparseCholesky::new(&a.matrix).unwrap();
            let mut x = vec![Vec3::zeros(); system.particle_count()];
            group.bench_with_input(BenchmarkId::new(label, side), &side, |b, _| {
                b.iter(|| factor.solve(&a.matrix, &a.filters, &a.rhs, &mut x).unwrap());
            });
        }
    }
    group.finish();
}

/// Consecutive linearised backward-Euler steps (PCG, warm-started) of a
/// falling sheet.
fn full_step(c: &mut Criterion) {
    let mut group = c.benchmark_group("step");
    group.sample_size(10);
    for side in SIDES {
        for (label, ratio) in STIFFNESS {
            let (system, _) = sheet(side, ratio);
            let mut state = system.initial_state();
            let mut integrator = Implicit::backward_euler();
            integrator.step(&system, &mut state, H).unwrap();
            group.bench_with_input(BenchmarkId::new(label, side), &side, |b, _| {
                b.iter(|| integrator.step(&system, &mut state, H).unwrap());
            });
        }
    }
    group.finish();
}

criterion_group!(
    benches,
    stream,
    pattern_and_refill,
    products,
    solves,
    full_step
);
criterion_main!(benches);
