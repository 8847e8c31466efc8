//! The implicit integrators at their defaults across stiffness and step
//! size: backward Euler never gains energy and every step is finite and
//! converged; BDF2 stays finite and within 5 % of its initial energy — on
//! the extreme table (24×24 cloth, stiffness 10⁻² … 10¹² N/m, steps
//! 10⁻⁴ … 1 s), on a 50×50 sheet large enough for the default solver to be
//! chosen by a timed trial, on a tet-lattice cube dropped onto a floor and
//! on a chain whose neighbours' masses differ by 10⁶; and a spinning
//! compressed spring, whose steps gain energy, is held to the energy test
//! up to the Newton tolerance's allowance.
//!
//! `cargo run --release --example extreme_table` prints the table's Newton
//! iterations, substeps and time per step.

use hooke::core::reference::Chain;
use hooke::implicit::{AutoSettings, Implicit};
use hooke::prelude::*;
use hooke::scenes::{Lattice, Mass, TetSplit};

/// The table's stiffnesses, N/m.
const STIFFNESS: [f64; 5] = [1e-2, 1.0, 1e4, 1e8, 1e12];
/// The table's steps, s.
const STEPS: [f64; 4] = [1e-4, 1e-2, 0.1, 1.0];

/// What a run did: its initial, peak and last energies and the summed
/// reports.
struct Run {
    initial: f64,
    peak: f64,
    last: f64,
    report: StepReport,
}

/// Runs `steps` steps of `dt`; panics on an error or a non-finite state.
fn run(system: &System, integrator: &mut dyn Integrator, dt: f64, steps: usize) -> Run {
    let mut state = system.initial_state();
    let initial = system.energy(&state).unwrap().total();
    let (mut peak, mut last, mut report) = (f64::NEG_INFINITY, initial, StepReport::default());
    for _ in 0..steps {
        report += integrator.step(system, &mut state, dt).unwrap();
        assert!(
            state
                .positions()
                .iter()
                .chain(state.velocities())
                .all(|p| p.iter().all(|c| c.is_finite())),
            "{}: non-finite state at t = {}",
            integrator.name(),
            state.time()
        );
        last = system.energy(&state).unwrap().total();
        peak = peak.max(last);
    }
    Run {
        initial,
        peak,
        last,
        report,
    }
}

/// Two steps per cell, so that each step size is taken from rest and from
/// motion; one at 1 s, where one step is already a second of swinging.
fn steps(dt: f64) -> usize {
    if dt < 1.0 { 2 } else { 1 }
}

/// Backward Euler's claim: never above the initial energy (relative 1e-9),
/// every step converged, no energy removed by the last resort.
fn assert_backward_euler(label: &str, run: &Run) {
    let Run {
        initial,
        peak,
        report,
        ..
    } = run;
    assert!(
        *peak <= initial + 1e-9 * initial.abs(),
        "{label}: energy rose from {initial} J to {peak} J ({report:?})"
    );
    assert_eq!(report.unconverged_steps, 0, "{label}: {report:?}");
    assert_eq!(report.energy_corrections, 0, "{label}: {report:?}");
}

#[test]
fn backward_euler_at_its_defaults_never_gains_energy_on_the_extreme_table() {
    for k in STIFFNESS {
        let system = Sheet::conservative(k).system().unwrap();
        for dt in STEPS {
            let run = run(&system, &mut Implicit::backward_euler(), dt, steps(dt));
            assert_backward_euler(&format!("k = {k:e} N/m, dt = {dt} s"), &run);
        }
    }
}

/// From [`AutoSettings::trial_particles`](hooke::implicit::AutoSettings::trial_particles) on, the default solver is
/// chosen by a timed trial; on a 50×50 sheet at 10⁴ N/m and 0.1 s (where
/// multigrid and the factor solve the trial about as fast, and multigrid's
/// later solves can reach their cap) backward Euler at its defaults still
/// never gains energy, and no linear solve stops at its cap.
#[test]
fn backward_euler_at_its_defaults_on_a_sheet_large_enough_for_the_trial() {
    let system = Sheet {
        mass: 0.1,
        stiffness: 1e4,
        damping: 0.0,
        air_damping: 0.0,
        height: 1.0,
        ..Sheet::new(50)
    }
    .system()
    .unwrap();
    assert!(system.particle_count() >= AutoSettings::DEFAULT.trial_particles);
    let run = run(&system, &mut Implicit::backward_euler(), 0.1, 2);
    assert_backward_euler("50×50 sheet, k = 1e4 N/m, dt = 0.1 s", &run);
    assert_eq!(run.report.unconverged_solves, 0, "{:?}", run.report);
}

#[test]
fn bdf2_at_its_defaults_stays_finite_and_near_its_initial_energy() {
    for k in STIFFNESS {
        let system = Sheet::conservative(k).system().unwrap();
        for dt in STEPS {
            let Run {
                initial,
                peak,
                report,
                ..
            } = run(&system, &mut Implicit::bdf2(), dt, steps(dt));
            assert!(
                peak <= initial + 0.05 * initial.abs(),
                "k = {k:e} N/m, dt = {dt} s: energy rose from {initial} J to {peak} J ({report:?})"
            );
        }
    }
}

/// A 0.2 m tet-lattice cube of 5³ particles, 1 kg, 10⁵ N/m springs,
/// dropped from 0.3 m onto a floor in 1/30 s steps for 1.5 s.
#[test]
fn a_tet_lattice_cube_dropped_on_a_floor_never_gains_energy() {
    let cube = Lattice::tets(4, 4, 4, TetSplit::Six)
        .size([0.2, 0.2, 0.2])
        .origin([-0.1, 0.3, -0.1])
        .mass(Mass::Total(1.0))
        .edges(1e5)
        .build()
        .unwrap();
    let mut b = SystemBuilder::new();
    cube.add_to(&mut b);
    b.gravity([0.0, -9.81, 0.0]);
    b.obstacle(Obstacle::new(Shape::Plane {
        point: Vec3::zeros(),
        normal: Vec3::y(),
    }));
    let system = b.build().unwrap();
    let run = run(&system, &mut Implicit::backward_euler(), 1.0 / 30.0, 45);
    assert_backward_euler("tet cube on a floor", &run);
    // It fell and landed: the drop's m g · 0.3 m went mostly into the
    // inelastic landing and backward Euler's damping.
    assert!(
        run.last < run.initial - 0.5 * 9.81 * 0.3,
        "{} J at the end of a drop from {} J",
        run.last,
        run.initial
    );
}

/// Ten particles alternating 1 kg and 1 mg on 10³ N/m springs, the first
/// pinned, under gravity, released horizontal 1 m up.
#[test]
fn a_chain_with_a_million_fold_mass_ratio_never_gains_energy() {
    let system = Chain {
        odd_particle_mass: Some(1e-6),
        height: 1.0,
        ..Chain::pendulum(10, 1.0, 1e3, 0.3)
    }
    .system()
    .unwrap();
    for dt in [1e-3, 1.0 / 30.0, 0.5] {
        let be = run(&system, &mut Implicit::backward_euler(), dt, 30);
        assert_backward_euler(&format!("mass-ratio chain, dt = {dt} s"), &be);
        let bdf2 = run(&system, &mut Implicit::bdf2(), dt, 30);
        assert!(
            bdf2.peak <= bdf2.initial + 0.05 * bdf2.initial.abs(),
            "mass-ratio chain, dt = {dt} s: BDF2's energy rose from {} J to {} J",
            bdf2.initial,
            bdf2.peak
        );
    }
}

/// Two 1 kg particles 1 m apart on a spring of 1 N/m and rest length 1.1 m
/// (compressed), spinning at 1 rad/s about their centre, without gravity or
/// damping. A backward-Euler step of `h` gains about
/// `½h² [k (L/l − 1) w² − F²/μ] = 0.04 h²` J (the chord of the rotation
/// lengthens the compressed spring; `w = 1 m/s` the relative speed,
/// `F = 0.1 N`, `μ = ½ kg`), while scaling the velocities within the
/// Newton tolerance `η` absorbs about `η ‖v‖²_M = η · 0.5` J. At
/// `η = 10⁻⁴` a step of 0.1 s gains ≈ 4·10⁻⁴ J, eight times that: it is
/// rejected and halved until the gain is absorbed (`h ≤ 0.035 s`), with
/// no last-resort correction; at `η = 10⁻¹⁰` only the floor takes the
/// steps, each corrected by the last resort. Without the allowance every
/// step would be cut to the floor, as at `η = 10⁻¹⁰`. At the default
/// `η = 5·10⁻³` the allowance, 2.5·10⁻³ J, takes the 0.1 s step whole.
#[test]
fn a_spinning_compressed_spring_gains_are_absorbed_only_within_the_newton_tolerance() {
    let mut b = SystemBuilder::new();
    b.particle_with_velocity(1.0, [-0.5, 0.0, 0.0], [0.0, -0.5, 0.0]);
    b.particle_with_velocity(1.0, [0.5, 0.0, 0.0], [0.0, 0.5, 0.0]);
    b.spring(0, 1, 1.0).rest_length(1.1);
    let system = b.build().unwrap();
    let run = |tolerance: f64| {
        let mut state = system.initial_state();
        let start = system.energy(&state).unwrap().total();
        let mut integrator = Implicit::backward_euler()
            .with_newton(ImplicitSettings::NEWTON_ITERATIONS, tolerance)
            .unwrap()
            .with_max_halvings(6);
        let report = integrator.step(&system, &mut state, 0.1).unwrap();
        let end = system.energy(&state).unwrap().total();
        assert!(
            end <= start + 1e-9 * start,
            "energy rose from {start} J to {end} J"
        );
        report
    };
    let default = run(ImplicitSettings::NEWTON_TOLERANCE);
    assert_eq!(default.accepted_steps, 1, "{default:?}");
    assert_eq!(default.energy_corrections, 0, "{default:?}");
    let whole = 0.04 * 0.1 * 0.1;
    assert!(
        default.energy_excess > 0.5 * whole && default.energy_excess < whole,
        "gain {} J, predicted about {whole} J",
        default.energy_excess
    );
    let report = run(1e-4);
    // 0.1 s and 0.05 s rejected, four substeps of 0.025 s taken, each
    // gaining about 0.04 · 0.025² J that the kinetic energy absorbed.
    assert_eq!(report.accepted_steps, 4, "{report:?}");
    assert_eq!(report.energy_corrections, 0, "{report:?}");
    let predicted = 0.04 * 0.025 * 0.025;
    assert!(
        (report.energy_excess - predicted).abs() <= 0.1 * predicted,
        "gain {} J, predicted {predicted} J",
        report.energy_excess
    );
    let strict = run(1e-10);
    assert_eq!(strict.accepted_steps, 64, "{strict:?}");
    assert!(strict.energy_corrections > 0, "{strict:?}");
}
