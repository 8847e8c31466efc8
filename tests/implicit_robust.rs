//! The implicit integrators at their defaults across stiffness and step
//! size: backward Euler never gains energy, every step is finite and
//! converged; BDF2 stays finite and near its initial energy.
//!
//! The cells run here are those whose converged steps are cheap enough for
//! the test suite; `cargo run --release --example extreme_table` runs the
//! whole table (stiffness 10⁻² … 10¹² N/m × steps 10⁻⁴ … 1 s) and prints
//! Newton iterations, substeps and time per step.

use hooke::implicit::Implicit;
use hooke::prelude::*;

/// The (stiffness in N/m, step in s) cells of the table run here.
const CELLS: [(f64, f64); 9] = [
    (1e-2, 1e-4),
    (1e-2, 1e-2),
    (1e-2, 0.1),
    (1.0, 1e-4),
    (1.0, 1e-2),
    (1e4, 1e-4),
    (1e4, 1e-2),
    (1e8, 1e-4),
    (1e12, 1e-4),
];
/// Steps taken in every cell of the table.
const STEPS_PER_CELL: usize = 3;

/// A 24×24 cloth, 1 m, 0.1 kg, pinned at two corners, no damping, every
/// spring of stiffness `k`, under gravity.
fn cloth(k: f64) -> System {
    Sheet {
        mass: 0.1,
        stiffness: k,
        damping: 0.0,
        air_damping: 0.0,
        ..Sheet::new(24)
    }
    .system()
    .unwrap()
}

/// The largest total energy over `steps` steps of `dt` and the summed
/// reports; panics on a non-finite state.
fn run(
    system: &System,
    integrator: &mut dyn Integrator,
    dt: f64,
    steps: usize,
) -> (f64, f64, StepReport) {
    let mut state = system.initial_state();
    let initial = system.energy(&state).unwrap().total();
    let (mut peak, mut total) = (f64::NEG_INFINITY, StepReport::default());
    for _ in 0..steps {
        total += integrator.step(system, &mut state, dt).unwrap();
        assert!(
            state
                .positions()
                .iter()
                .chain(state.velocities())
                .all(|p| p.iter().all(|c| c.is_finite()))
        );
        peak = peak.max(system.energy(&state).unwrap().total());
    }
    (initial, peak, total)
}

#[test]
fn backward_euler_at_its_defaults_never_gains_energy_on_the_extreme_table() {
    for (k, dt) in CELLS {
        let system = cloth(k);
        {
            let mut integrator = Implicit::backward_euler();
            let (initial, peak, report) = run(&system, &mut integrator, dt, STEPS_PER_CELL);
            let label = format!("k = {k:e} N/m, dt = {dt} s");
            assert!(
                peak <= initial + 1e-9 * initial.abs(),
                "{label}: energy rose from {initial} to {peak} J"
            );
            assert_eq!(report.unconverged_steps, 0, "{label}: {report:?}");
            assert_eq!(report.energy_corrections, 0, "{label}: {report:?}");
            assert_eq!(report.unconverged_solves, 0, "{label}: {report:?}");
        }
    }
}

#[test]
fn bdf2_at_its_defaults_stays_finite_and_near_its_initial_energy() {
    for (k, dt) in CELLS {
        let system = cloth(k);
        {
            let mut integrator = Implicit::bdf2();
            let (initial, peak, report) = run(&system, &mut integrator, dt, STEPS_PER_CELL);
            assert!(
                peak <= initial + 0.05 * initial.abs(),
                "k = {k:e} N/m, dt = {dt} s: energy rose from {initial} to {peak} J ({report:?})"
            );
        }
    }
}
