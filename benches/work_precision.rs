//! Work against precision of the implicit steps on one cloth, measured in
//! one run: every variant's mean time and iterations per step and its
//! error at `t = 0.5 s`, and the largest over the 30 steps, against a
//! backward-Euler run converged to `10⁻⁹` with Cholesky, computed in the
//! same run; a run converged to `10⁻⁶` gives the floor below which a
//! difference is the cloth's buckling amplifying the last digits of a
//! step, not the step's error.
//!
//! `cargo bench --bench work_precision [-- N … [LABEL …]]` (default N = 50
//! 100 200; labels select the variants whose names contain them):
//! the solver benchmarks' cloth (`Sheet::cloth`) of N × N particles, 1 m,
//! 1 kg, stretch / shear / bend 5000 / 500 / 50 N/m, no damping, two
//! corners pinned, `dt = 1/60 s`, 30 steps from rest, no collision surface
//! (fast mass-spring has no contact).
//! Prints a Markdown table (`benches/README.md`).

use std::io::Write;
use std::time::Instant;

use hooke::implicit::{FastMassSpring, LinearSolver, Minimizer, PcgSettings, WeakSprings};
use hooke::prelude::*;

const DT: f64 = 1.0 / 60.0;
const STEPS: usize = 30;

/// Backward Euler converged to `tolerance` with Cholesky factoring the
/// whole matrix (the reference, and the floor).
fn converged(tolerance: f64) -> Implicit {
    Implicit::backward_euler()
        .with_solver(LinearSolver::Cholesky)
        .with_weak_springs(WeakSprings::Kept)
        .with_newton(1000, tolerance)
        .unwrap()
}

/// Where a quasi-Newton row stops each step.
#[derive(Clone, Copy)]
enum Stop {
    /// After this many iterations, accepted.
    Iterations(usize),
    /// At this relative tolerance.
    Tolerance(f64),
}

/// A variant: its label and a fresh integrator.
type Variant = (String, Box<dyn Fn() -> Box<dyn Integrator>>);

fn variants() -> Vec<Variant> {
    let mut all: Vec<Variant> = Vec::new();
    let newton = |tol: f64| {
        move || -> Box<dyn Integrator> {
            Box::new(
                Implicit::backward_euler()
                    .with_newton(ImplicitSettings::NEWTON_ITERATIONS, tol)
                    .unwrap(),
            )
        }
    };
    all.push((
        format!(
            "Newton, default ({:e}, auto)",
            ImplicitSettings::NEWTON_TOLERANCE
        ),
        Box::new(|| Box::new(Implicit::backward_euler())),
    ));
    all.push((
        format!(
            "Newton, default ({:e}, auto), weak springs routed",
            ImplicitSettings::NEWTON_TOLERANCE
        ),
        Box::new(|| Box::new(Implicit::backward_euler().with_weak_springs(WeakSprings::Routed))),
    ));
    // A converged run, for the floor: how far apart converged steps end,
    // the buckling of the cloth amplifying the last digits of each step.
    all.push((
        "Newton, Cholesky, 1e-6 (floor)".into(),
        Box::new(|| Box::new(converged(1e-6))),
    ));
    for tol in [3e-2, 1e-2, 3e-3, 1e-3, 1e-4] {
        all.push((format!("Newton, {tol:e}"), Box::new(newton(tol))));
    }
    all.push((
        "linearized".into(),
        Box::new(|| Box::new(Implicit::backward_euler().linearized())),
    ));
    for iterations in [10, 100] {
        all.push((
            format!("fast mass-spring, {iterations}"),
            Box::new(move || Box::new(FastMassSpring::new(iterations).unwrap())),
        ));
    }
    // Quasi-Newton rows: a fixed number of iterations a step (each step
    // accepted after them) or a tolerance, with the minimiser, the solver
    // that applies H₀⁻¹ and where H₀'s weak springs go (routed by default).
    let mut quasi_with = |label: String, stop: Stop, minimizer, solver, weak: Option<_>| {
        all.push((
            label,
            Box::new(move || {
                let integrator = Implicit::backward_euler()
                    .with_minimizer(minimizer)
                    .with_solver(solver)
                    .with_weak_springs(weak);
                Box::new(match stop {
                    Stop::Iterations(k) => integrator
                        .with_newton(k, 1e-12)
                        .unwrap()
                        .with_max_halvings(0),
                    Stop::Tolerance(tol) => integrator.with_newton(1000, tol).unwrap(),
                })
            }),
        ));
    };
    let (default, auto) = (Minimizer::quasi_newton(), LinearSolver::Auto);
    // H₀ as fast mass-spring's matrix, every spring in place (the default
    // before H₀ routed its weak springs).
    let kept = Some(WeakSprings::Kept);
    for k in [5, 10, 30] {
        let label = format!("quasi-Newton, {k} iterations, H₀ kept");
        quasi_with(label, Stop::Iterations(k), default, auto, kept);
    }
    for tol in [1e-2, 3e-3, 1e-3] {
        let label = format!("quasi-Newton, {tol:e}, H₀ kept");
        quasi_with(label, Stop::Tolerance(tol), default, auto, kept);
    }
    let mut quasi = |label, stop, minimizer, solver| {
        quasi_with(label, stop, minimizer, solver, None);
    };
    for k in [4, 5, 6, 7, 10, 15, 30] {
        quasi(
            format!("quasi-Newton, {k} iterations"),
            Stop::Iterations(k),
            default,
            auto,
        );
    }
    for tol in [1e-1, 3e-2, 1e-2, 3e-3, 2e-3, 1e-3] {
        quasi(
            format!("quasi-Newton, {tol:e}"),
            Stop::Tolerance(tol),
            default,
            auto,
        );
    }
    // Every step's history started afresh (Liu et al.), or all five of the
    // last step's pairs carried, against the default's newest one.
    for (carried, name) in [(0, "no pair carried"), (5, "5 pairs carried")] {
        let minimizer = Minimizer::QuasiNewton {
            history: Minimizer::HISTORY,
            carried,
        };
        for k in [5, 10, 30] {
            let label = format!("quasi-Newton, {k} iterations, {name}");
            quasi(label, Stop::Iterations(k), minimizer, auto);
        }
        for tol in [3e-2, 1e-3] {
            let label = format!("quasi-Newton, {tol:e}, {name}");
            quasi(label, Stop::Tolerance(tol), minimizer, auto);
        }
    }
    // H₀⁻¹ by its factor or by one multigrid V-cycle, whichever `auto`
    // would take at this size.
    for (name, solver) in [
        ("factored", LinearSolver::Cholesky),
        ("multigrid", LinearSolver::Amg(PcgSettings::default())),
    ] {
        let label = format!("quasi-Newton, 10 iterations, H₀ {name}");
        quasi(label, Stop::Iterations(10), default, solver);
        let label = format!("quasi-Newton, 1e-2, H₀ {name}");
        quasi(label, Stop::Tolerance(1e-2), default, solver);
    }
    for history in [2, 10] {
        let minimizer = Minimizer::QuasiNewton {
            history,
            carried: Minimizer::CARRIED,
        };
        let label = format!("quasi-Newton, 1e-2, history {history}");
        quasi(label, Stop::Tolerance(1e-2), minimizer, auto);
    }
    all
}

/// Runs `integrator` for [`STEPS`] steps; returns the positions after
/// every step, the mean seconds per step, the mean iterations per step and
/// the largest energy above the start.
fn run(system: &System, integrator: &mut dyn Integrator) -> (Vec<Vec<Vec3>>, f64, f64, f64) {
    let mut state = system.initial_state();
    let start = system.energy(&state).unwrap().total();
    let (mut iterations, mut rise) = (0, f64::NEG_INFINITY);
    let mut path = Vec::with_capacity(STEPS);
    let mut seconds = 0.0;
    for _ in 0..STEPS {
        let clock = Instant::now();
        let report = integrator.step(system, &mut state, DT).unwrap();
        seconds += clock.elapsed().as_secs_f64();
        iterations += report.newton_iterations;
        rise = rise.max(system.energy(&state).unwrap().total() - start);
        path.push(state.positions().to_vec());
    }
    let steps = STEPS as f64;
    (path, seconds / steps, iterations as f64 / steps, rise)
}

/// The largest distance of any particle between two sets of positions.
fn distance(a: &[Vec3], b: &[Vec3]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(a, b)| (a - b).norm())
        .fold(0.0, f64::max)
}

fn main() -> std::io::Result<()> {
    let mut out = std::io::stdout().lock();
    let args: Vec<String> = std::env::args().skip(1).collect();
    let sizes: Vec<usize> = args.iter().filter_map(|a| a.parse().ok()).collect();
    // Other arguments (but cargo's own flags) select variants by their label.
    let filters: Vec<&String> = args
        .iter()
        .filter(|a| a.parse::<usize>().is_err() && !a.starts_with("--"))
        .collect();
    let sizes = if sizes.is_empty() {
        vec![50, 100, 200]
    } else {
        sizes
    };
    writeln!(
        out,
        "| N | step | ms per step | iterations per step | error at 0.5 s | largest error | largest E − E₀ |"
    )?;
    writeln!(out, "|---|---|---|---|---|---|---|")?;
    for n in sizes {
        let system = Sheet::cloth(n, 0.0).system().unwrap();
        let mut reference = converged(1e-9);
        let (exact, seconds, iterations, _) = run(&system, &mut reference);
        writeln!(
            out,
            "| {n} | reference (Newton, Cholesky, 1e-9) | {:.1} | {iterations:.1} | — | — | — |",
            1e3 * seconds
        )?;
        let chosen = variants()
            .into_iter()
            .filter(|(label, _)| filters.is_empty() || filters.iter().any(|f| label.contains(*f)));
        for (label, make) in chosen {
            let mut integrator = make();
            let (path, seconds, iterations, rise) = run(&system, integrator.as_mut());
            let error = distance(&path[STEPS - 1], &exact[STEPS - 1]);
            let largest = path
                .iter()
                .zip(&exact)
                .map(|(a, b)| distance(a, b))
                .fold(0.0, f64::max);
            writeln!(
                out,
                "| {n} | {label} | {:.1} | {iterations:.1} | {error:.2e} m | {largest:.2e} m | {rise:.1e} J |",
                1e3 * seconds
            )?;
        }
    }
    Ok(())
}
