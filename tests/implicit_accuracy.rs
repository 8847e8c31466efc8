//! Backward Euler and BDF2 against theory: the exact amplitude factor of one
//! step, convergence orders, agreement of the two linear solvers, and Newton
//! iterations that solve the nonlinear step equations.

mod common;

use hooke::core::reference::Chain;
use hooke::core::{At, CompressedSprings, ForceEvaluator};
use hooke::implicit::internals::{BlockJacobi, BlockMatrix, Filter, Pattern, SparseCholesky, cg};
use hooke::implicit::{ErrorControl, Implicit, LinearSolver, PcgSettings, Terms};
use hooke::prelude::*;

fn pcg(tolerance: f64) -> LinearSolver {
    LinearSolver::Pcg(PcgSettings::new(tolerance, 10_000).unwrap())
}

/// `√(x² + v²/ω²)` of the bob.
fn amplitude(state: &State, omega: f64) -> f64 {
    let (x, v) = (
        state.positions()[Oscillator::BOB].x,
        state.velocities()[Oscillator::BOB].x,
    );
    (x * x + v * v / (omega * omega)).sqrt()
}

/// On `x'' = −ω² x` backward Euler maps `ωx + iv` to itself divided by
/// `1 + iθ`, so one step multiplies the amplitude by exactly `1/√(1 + θ²)`:
/// to 1e-10, plus the `ε θ²` rounding of forming `v₀ + Δv` when `Δv ≈ −v₀`.
/// Baraff & Witkin's linearised step is exact on this linear spring; the
/// converged step (the default) solves the same equations.
#[test]
fn one_backward_euler_step_scales_the_amplitude_by_theory() {
    let mut oscillator = Oscillator::undamped(2.0, 200.0); // ω = 10 rad/s
    oscillator.displacement = 0.3;
    oscillator.velocity = -4.0;
    let system = oscillator.system().unwrap();
    let omega = oscillator.omega();
    for theta in [1e-3, 0.1, 1.0, 10.0, 1e4] {
        let tolerance = 1e-10 + 1e-15 * theta * theta;
        for solver in [LinearSolver::Cholesky, pcg(1e-13)] {
            for step in [
                Implicit::backward_euler().linearized(),
                Implicit::backward_euler(),
            ] {
                let mut state = system.initial_state();
                let before = amplitude(&state, omega);
                let mut integrator = step.with_solver(solver);
                let linearized = integrator.is_linearized();
                integrator.step(&system, &mut state, theta / omega).unwrap();
                let ratio = amplitude(&state, omega) / before;
                let theory = 1.0 / (1.0 + theta * theta).sqrt();
                assert!(
                    (ratio - theory).abs() <= tolerance * theory,
                    "θ = {theta}, linearised {linearized}: ratio {ratio}, theory {theory}"
                );
            }
        }
    }
}

/// A pendulum chain — four 0.1 kg particles on 100 N/m springs of 0.25 m,
/// pinned at the top and released horizontal, so that the springs swing
/// through large angles — with, if `floor`, a floor 10 m below that it
/// never comes near.
fn pendulum_chain(floor: bool) -> System {
    let mut b = Chain::pendulum(5, 0.1, 100.0, 0.25).builder();
    if floor {
        b.obstacle(Obstacle::new(Shape::Plane {
            point: Vec3::new(0.0, -10.0, 0.0),
            normal: Vec3::y(),
        }));
    }
    b.build().unwrap()
}

/// The observed order of `scheme`'s positions on `system` after 0.5 s
/// against RK4's at 10⁻⁵ s (an independent, fourth-order reference) on
/// the chain without a floor, at steps of 4, 2, 1 and 0.5 ms, and the
/// errors.
fn chain_order(system: &System, scheme: fn() -> Implicit) -> (f64, Vec<f64>) {
    let duration = 0.5;
    let positions = |system: &System, integrator: &mut dyn Integrator, dt: f64| {
        let mut state = system.initial_state();
        for _ in 0..(duration / dt).round() as usize {
            integrator.step(system, &mut state, dt).unwrap();
        }
        state.positions().to_vec()
    };
    let reference = positions(&pendulum_chain(false), &mut Rk4::new(), 1e-5);
    let dts = [4e-3, 2e-3, 1e-3, 5e-4];
    let errors: Vec<f64> = dts
        .iter()
        .map(|&dt| {
            let x = positions(system, &mut scheme(), dt);
            let squares: f64 = x
                .iter()
                .zip(&reference)
                .map(|(a, b)| (a - b).norm_squared())
                .sum();
            (squares / x.len() as f64).sqrt()
        })
        .collect();
    (common::log_log_slope(&dts, &errors), errors)
}

/// Converged backward Euler's positions on the pendulum chain approach
/// the reference to first order in the step.
#[test]
fn converged_backward_euler_is_first_order_on_a_pendulum_chain() {
    let (order, errors) = chain_order(&pendulum_chain(false), Implicit::backward_euler);
    assert!(
        (order - 1.0).abs() <= 0.1,
        "observed order {order:.3}, errors {errors:?}"
    );
}

/// BDF2 keeps its second order in a system with an obstacle. Before each
/// step, particles inside an obstacle are moved out; that pass marked the
/// state as changed even when it moved nothing, and BDF2, finding its
/// history gone, took every step as its backward-Euler start (observed
/// order 0.94, the errors of backward Euler's to ten digits).
#[test]
fn bdf2_is_second_order_beside_an_obstacle_it_never_touches() {
    for floor in [false, true] {
        let (order, errors) = chain_order(&pendulum_chain(floor), Implicit::bdf2);
        assert!(
            (order - 2.0).abs() <= 0.15,
            "floor {floor}: observed order {order:.3}, errors {errors:?}"
        );
    }
}

/// On a damped oscillator (ω = 10 rad/s, ζ = 0.5, released 1 m out) whose
/// motion dies down, error-controlled BDF2 (relative 10⁻², absolute 10⁻⁴ m)
/// stays within 1 cm of the exact solution at every frame (0.1 s) for 5 s,
/// and does it in fewer steps than fixed-step BDF2: the same number of
/// equal steps misses by more.
#[test]
fn error_controlled_bdf2_needs_fewer_steps_than_fixed_steps() {
    let oscillator = Oscillator::damped(1.0, 100.0, 10.0);
    let system = oscillator.system().unwrap();
    let (frame, frames) = (0.1, 50);
    let run = |mut integrator: Implicit, substeps: usize| {
        let mut state = system.initial_state();
        let (mut steps, mut worst) = (0, 0.0_f64);
        for _ in 0..frames {
            for _ in 0..substeps {
                steps += integrator
                    .step(&system, &mut state, frame / substeps as f64)
                    .unwrap()
                    .accepted_steps;
            }
            let (u, _) = oscillator.solution(state.time());
            worst = worst.max((state.positions()[Oscillator::BOB].x - u).abs());
        }
        (steps, worst)
    };
    let control = ErrorControl::new(1e-2, 1e-4).unwrap();
    let (steps, error) = run(Implicit::bdf2().with_error_control(control), 1);
    assert!(error <= 1e-2, "error-controlled BDF2 missed by {error} m");
    let per_frame = steps.div_ceil(frames);
    let (fixed_steps, fixed_error) = run(Implicit::bdf2(), per_frame);
    assert!(
        fixed_steps >= steps && fixed_error > 1e-2,
        "{steps} controlled steps: {error} m; {fixed_steps} fixed steps: {fixed_error} m"
    );
}

/// Observed orders on the damped oscillator: 1 for backward Euler, 2 for BDF2.
#[test]
fn backward_euler_is_first_order_and_bdf2_second() {
    let oscillator = Oscillator::damped(1.0, 1.0, 0.2);
    let dts: Vec<f64> = (0..4).map(|k| 0.05 / f64::from(1 << k)).collect();
    for (scheme, expected) in [
        (Implicit::backward_euler as fn() -> Implicit, 1.0),
        (Implicit::bdf2, 2.0),
    ] {
        let errors: Vec<f64> = dts
            .iter()
            .map(|&dt| {
                let mut integrator = scheme().with_solver(LinearSolver::Cholesky);
                common::oscillator_error(&mut integrator, &oscillator, dt, 10.0)
            })
            .collect();
        let order = common::log_log_slope(&dts, &errors);
        let name = scheme().name();
        eprintln!("{name}: observed order {order:.3}, errors {errors:?}");
        assert!(
            (order - expected).abs() <= 0.15,
            "{name}: observed order {order:.3}, expected {expected}"
        );
    }
}

/// BDF2 preserves the undamped oscillator's amplitude to second order: the
/// amplitude error after 10 s falls fourfold when the step halves (its
/// backward-Euler start loses `O(h²)` once; each BDF2 step only `O(h⁴)`).
#[test]
fn bdf2_preserves_the_amplitude_to_second_order() {
    let oscillator = Oscillator::undamped(1.0, 1.0);
    let system = oscillator.system().unwrap();
    let dts: Vec<f64> = (0..4).map(|k| 0.05 / f64::from(1 << k)).collect();
    let errors: Vec<f64> = dts
        .iter()
        .map(|&dt| {
            let mut integrator = Implicit::bdf2().with_solver(LinearSolver::Cholesky);
            let mut state = system.initial_state();
            for _ in 0..(10.0 / dt).round() as usize {
                integrator.step(&system, &mut state, dt).unwrap();
            }
            (1.0 - amplitude(&state, 1.0)).abs()
        })
        .collect();
    let order = common::log_log_slope(&dts, &errors);
    assert!(
        (order - 2.0).abs() <= 0.15,
        "amplitude order {order:.3}, errors {errors:?}"
    );
}

/// A stretched, damped, moving sheet with gravity and pins.
fn busy_sheet(n: usize) -> (System, State) {
    let system = Sheet {
        stiffness: 500.0,
        damping: 0.2,
        air_damping: 0.05,
        ..Sheet::new(n)
    }
    .system()
    .unwrap();
    let mut state = system.initial_state();
    for (k, x) in state.positions_mut().iter_mut().enumerate() {
        *x *= 1.05;
        x.y = 0.02 * (k as f64 * 0.7).sin();
    }
    for (k, v) in state.velocities_mut().iter_mut().enumerate() {
        *v = Vec3::new((k as f64).sin(), (k as f64 * 1.3).cos(), 0.5);
    }
    (system, state)
}

/// The two solvers compute the same step: with every Newton step solved
/// to PCG's own tolerance, velocities agree to that tolerance; with the
/// default inexact Newton (loose solves while far from the answer), within
/// the Newton tolerance in the mass norm; pinned particles keep their
/// velocity exactly.
#[test]
fn pcg_and_cholesky_give_the_same_step() {
    let (system, start) = busy_sheet(12);
    let masses = system.masses();
    let mass_norm = |v: &[Vec3]| {
        v.iter()
            .zip(masses)
            .map(|(v, m)| m * v.norm_squared())
            .sum::<f64>()
            .sqrt()
    };
    for scheme in [Implicit::backward_euler as fn() -> Implicit, Implicit::bdf2] {
        let (mut a, mut b, mut c) = (start.clone(), start.clone(), start.clone());
        let (mut exact_pcg, mut with_cholesky, mut inexact_pcg) = (
            scheme().with_solver(pcg(1e-12)).with_inexact_newton(false),
            scheme().with_solver(LinearSolver::Cholesky),
            scheme().with_solver(pcg(1e-12)),
        );
        let steps = 3;
        for _ in 0..steps {
            exact_pcg.step(&system, &mut a, 0.02).unwrap();
            with_cholesky.step(&system, &mut b, 0.02).unwrap();
            inexact_pcg.step(&system, &mut c, 0.02).unwrap();
        }
        let scale = b.velocities().iter().map(|v| v.norm()).fold(0.0, f64::max);
        for (i, (va, vb)) in a.velocities().iter().zip(b.velocities()).enumerate() {
            assert!(
                (va - vb).norm() <= 1e-9 * scale,
                "particle {i}: {va:?} vs {vb:?}"
            );
        }
        let difference: Vec<Vec3> = c
            .velocities()
            .iter()
            .zip(b.velocities())
            .map(|(vc, vb)| vc - vb)
            .collect();
        let bound = steps as f64 * ImplicitSettings::NEWTON_TOLERANCE * mass_norm(b.velocities());
        assert!(
            mass_norm(&difference) <= bound,
            "inexact Newton: {:.3e} against {bound:.3e}",
            mass_norm(&difference)
        );
        for pinned in system.pinned() {
            for state in [&a, &b, &c] {
                assert_eq!(state.velocities()[pinned], start.velocities()[pinned]);
            }
        }
    }
}

/// The same system with its springs declared in reverse order and each
/// spring's ends swapped: the matrix stores springs by their endpoints, so
/// the order of declaration must not change a step beyond rounding.
fn redeclared(system: &System) -> System {
    let mut b = SystemBuilder::new();
    for (m, x) in system.masses().iter().zip(system.initial_positions()) {
        b.particle(*m, *x);
    }
    for s in system.springs().iter().rev() {
        b.spring(s.j, s.i, s.stiffness)
            .rest_length(s.rest_length)
            .damping(s.damping);
    }
    for p in system.pinned() {
        b.pin(p);
    }
    if let Some(g) = system.gravity() {
        b.gravity(g);
    }
    if let Some(gamma) = system.air_damping() {
        b.air_damping(gamma);
    }
    b.build().unwrap()
}

#[test]
fn the_order_springs_are_declared_in_does_not_change_a_step() {
    let (system, start) = busy_sheet(9);
    let reversed = redeclared(&system);
    for solver in [pcg(1e-12), LinearSolver::Cholesky] {
        let (mut a, mut b) = (start.clone(), start.clone());
        let integrator = || {
            Implicit::backward_euler()
                .with_solver(solver)
                .with_newton(30, 1e-12)
                .unwrap()
        };
        let (mut one, mut other) = (integrator(), integrator());
        for _ in 0..3 {
            one.step(&system, &mut a, 0.02).unwrap();
            other.step(&reversed, &mut b, 0.02).unwrap();
        }
        let scale = a.velocities().iter().map(|v| v.norm()).fold(0.0, f64::max);
        for (i, (va, vb)) in a.velocities().iter().zip(b.velocities()).enumerate() {
            assert!(
                (va - vb).norm() <= 1e-9 * scale,
                "particle {i}: {va:?} vs {vb:?}"
            );
        }
    }
}

/// With every kind of filter — free, plane, line, fixed — the filtered PCG
/// and the Cholesky of `S A S + I − S` solve the same constrained system, and
/// the solution has no component in a constrained direction.
#[test]
fn filtered_solvers_agree_for_every_kind_of_constraint() {
    let (system, state) = busy_sheet(8);
    let n = system.particle_count();
    let mut a = BlockMatrix::zeros(Pattern::new(&system).unwrap());
    let (mut jacobi, mut rhs) = (BlockJacobi::default(), vec![Vec3::zeros(); n]);
    let u: Vec<Vec3> = state.velocities().iter().map(|v| 0.05 * v).collect();
    let at = At {
        x: state.positions(),
        v: state.velocities(),
        v_tilde: state.velocities(),
        beta_h: 0.05,
        displacement: Some(&u),
        compressed: CompressedSprings::Clamped,
    };
    Terms::new(&system)
        .unwrap()
        .assemble(&system, &at, &mut a, &mut jacobi, &mut rhs, 0.0)
        .unwrap();
    let normal = Vec3::new(1.0, 2.0, 2.0) / 3.0;
    let filters: Vec<Filter> = (0..n)
        .map(|i| match i % 5 {
            1 => Filter::Plane(normal),
            2 => Filter::Line(normal),
            3 if i < 20 => Filter::Fixed,
            _ => Filter::Free,
        })
        .collect();
    let mut iterative = vec![Vec3::zeros(); n];
    let settings = PcgSettings::new(1e-13, 10_000).unwrap();
    cg::solve(
        &a,
        &jacobi,
        &filters,
        &rhs,
        &mut iterative,
        settings,
        &mut Default::default(),
    )
    .unwrap();
    let mut direct = vec![Vec3::zeros(); n];
    SparseCholesky::new(&a)
        .unwrap()
        .solve(&a, &filters, &rhs, &mut direct)
        .unwrap();
    let scale = direct.iter().map(|x| x.norm()).fold(0.0, f64::max);
    for (i, ((p, c), f)) in iterative.iter().zip(&direct).zip(&filters).enumerate() {
        assert!(
            (p - c).norm() <= 1e-9 * scale,
            "particle {i}: {p:?} vs {c:?}"
        );
        assert!(
            (f.apply(*c) - c).norm() <= 1e-15 * scale,
            "particle {i} leaves its constraint"
        );
    }
    // The free part is a solution: S(b − A x) = 0.
    let mut ax = vec![Vec3::zeros(); n];
    a.apply(&direct, &mut ax);
    let b_scale = rhs.iter().map(|b| b.norm()).fold(0.0, f64::max);
    for (i, f) in filters.iter().enumerate() {
        assert!(
            f.apply(rhs[i] - ax[i]).norm() <= 1e-10 * b_scale,
            "particle {i}: residual"
        );
    }
}

/// With enough Newton iterations the step solves the backward-Euler
/// equations themselves: `M(v₁ − v₀) = h f(x₁, v₁)` with `x₁ = x₀ + h v₁`,
/// checked with the explicit side's independent force evaluation.
#[test]
fn newton_iterations_solve_the_nonlinear_step() {
    // Large amplitude and step: the bead's restoring force is far from linear.
    let bead = BeadOnString {
        mass: 1.0,
        stiffness: 1e4,
        half_span: 1.0,
        amplitude: 3.0,
        air_damping: 5.0,
    };
    let system = bead.system().unwrap();
    let h = 0.05;
    let residual = |mut integrator: Implicit| {
        let mut state = system.initial_state();
        let report = integrator.step(&system, &mut state, h).unwrap();
        let mut f = vec![Vec3::zeros(); 3];
        ForceEvaluator::default().forces(&system, state.positions(), state.velocities(), &mut f);
        let i = BeadOnString::BEAD;
        let momentum = bead.mass * (state.velocities()[i] - system.initial_velocities()[i]);
        ((momentum - h * f[i]).norm(), report)
    };
    let (linearised, _) = residual(Implicit::backward_euler().linearized());
    let (converged, report) = residual(Implicit::backward_euler().with_newton(30, 1e-12).unwrap());
    assert!(
        linearised > 1.0,
        "the linearised step should miss: residual {linearised}"
    );
    assert!(
        converged <= 1e-9,
        "Newton residual {converged} N·s ({report:?})"
    );
    assert_eq!(
        (report.accepted_steps, report.unconverged_steps),
        (1, 0),
        "{report:?}"
    );
    assert!(report.newton_iterations < 30, "{report:?}");
}
