//! The `setup` and `solve` groups: what each linear solver builds once per
//! topology, and one solve as a Newton iteration pays it.

use criterion::{BenchmarkId, Criterion};
use hooke::implicit::internals::{Amg, AmgSettings, FillOrdering, SparseCholesky, cg};
use hooke::prelude::*;

use crate::fixtures::{DAMPING, settings, sides, step_system};

pub fn linear(c: &mut Criterion) {
    let mut setup = c.benchmark_group("setup");
    setup.sample_size(10);
    let mut cases = Vec::new();
    for n in sides("HOOKE_SOLVER_SIDES", &[50, 100, 200, 400, 1000]) {
        let sheet = Sheet::cloth(n, DAMPING);
        let system = sheet.system().unwrap();
        let state = sheet.wavy(&system);
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
            for (name, ordering) in [
                ("cholesky", FillOrdering::Particles),
                ("cholesky-scalar-amd", FillOrdering::Scalar),
            ] {
                let mut cholesky = SparseCholesky::with_ordering(&s.a, ordering).unwrap();
                let factor = cholesky.info();
                eprintln!(
                    "{name} {n}²: {} factor entries, {} bytes per particle",
                    factor.factor_nonzeros,
                    factor.bytes / s.b.len()
                );
                solve.bench_with_input(BenchmarkId::new(name, n), &n, |b, _| {
                    b.iter(|| cholesky.solve(&s.a, &s.filters, &s.b, &mut x).unwrap());
                });
            }
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
        let hierarchy = amg.info();
        eprintln!(
            "amg {n}²: levels {:?}, {} bytes per particle, {} iterations to {:.1e}",
            hierarchy.unknowns,
            hierarchy.bytes / s.b.len(),
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
