//! Criterion benchmark of one volume element ([`Tet`]): its energy,
//! gradient and Hessian blocks of each kind ([`TetHessian`]) — the exact
//! one, the Gauss–Newton part, and the projected one, which takes an SVD
//! of the deformation gradient and a 3 × 3 symmetric eigensolve — over
//! 1 024 deformations of a tetrahedron (each vertex moved by up to 0.6 of
//! the edge, inverted elements among them), as the step's assembly asks
//! for them (`Tet::blocks`). The time is per element.
//!
//! Run with `cargo bench --bench volume`.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use hooke::core::{Tet, TetHessian, Vec3};

/// The element and its deformations, from a fixed seed.
fn deformations() -> (Tet, Vec<[Vec3; 4]>) {
    let rest = [
        Vec3::new(0.1, 0.0, 0.05),
        Vec3::new(1.1, 0.2, 0.0),
        Vec3::new(0.3, 0.9, 0.1),
        Vec3::new(0.2, 0.3, 1.2),
    ];
    let tet = Tet::at_rest([0, 1, 2, 3], 1e3, rest).expect("a proper tetrahedron");
    let mut seed = 7_u64;
    let mut unit = move || {
        seed = seed.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1);
        (seed >> 11) as f64 / (1_u64 << 53) as f64 - 0.5
    };
    let moved = (0..1024)
        .map(|_| rest.map(|p| p + 1.2 * Vec3::new(unit(), unit(), unit())))
        .collect();
    (tet, moved)
}

fn tet_hessians(c: &mut Criterion) {
    let (tet, moved) = deformations();
    let mut group = c.benchmark_group("tet-hessian");
    group.throughput(Throughput::Elements(moved.len() as u64));
    for (label, kind) in [
        ("exact", TetHessian::Exact),
        ("gauss-newton", TetHessian::GaussNewton),
        ("projected", TetHessian::Projected),
    ] {
        group.bench_function(BenchmarkId::from_parameter(label), |b| {
            b.iter(|| {
                moved
                    .iter()
                    .map(|x| tet.blocks(x, kind, 1.0).diagonal[0][(0, 0)])
                    .sum::<f64>()
            });
        });
    }
    group.finish();
}

criterion_group!(benches, tet_hessians);
criterion_main!(benches);
