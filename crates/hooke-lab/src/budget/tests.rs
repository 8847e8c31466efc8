//! The budget against hand-worked energies: a bob falling under gravity,
//! a still particle set moving, and a pin dragging a spring.

use hooke_core::SystemBuilder;

use super::*;

/// `system`'s state with these positions and velocities at time `t`.
fn state_at(system: &System, x: &[Vec3], v: &[Vec3], t: f64) -> State {
    let mut state = system.initial_state();
    state.positions_mut().copy_from_slice(x);
    state.velocities_mut().copy_from_slice(v);
    state.set_time(t);
    state
}

/// The bob released at the spring's rest length under gravity, with
/// m = k = g = 1: `u(t) = 1 − cos t` below the start.
fn bob() -> System {
    let mut b = SystemBuilder::new();
    let anchor = b.particle(1.0, [0.0, 0.0, 0.0]);
    let bob = b.particle(1.0, [0.0, -1.0, 0.0]);
    b.pin(anchor);
    b.spring(anchor, bob, 1.0);
    b.gravity([0.0, -1.0, 0.0]);
    b.build().unwrap()
}

/// The bob `u` below its start moving down at `v`, at time `t`.
fn bob_at(system: &System, u: f64, v: f64, t: f64) -> State {
    state_at(
        system,
        &[Vec3::zeros(), Vec3::new(0.0, -1.0 - u, 0.0)],
        &[Vec3::zeros(), Vec3::new(0.0, -v, 0.0)],
        t,
    )
}

#[test]
fn the_exact_oscillator_has_ratio_one_on_the_way_down_and_back_up() {
    // E = ½v² + ½u² = 1 − cos t and W = u = 1 − cos t: no gain at any
    // instant, so the ratio is one throughout, also after the lowest
    // point (t = π), where max W = 2 exceeds W.
    let system = bob();
    let mut budget = EnergyBudget::new(&system);
    assert!(budget.initial().abs() < 1e-15);
    let mut deepest = 0.0_f64;
    for k in 1..=60 {
        let t = 0.1 * f64::from(k);
        let u = 1.0 - t.cos();
        deepest = deepest.max(u);
        let ratio = budget
            .record(&system, &bob_at(&system, u, t.sin(), t))
            .unwrap();
        assert!((ratio - 1.0).abs() < 1e-12, "t = {t}: ratio {ratio}");
    }
    assert!((budget.max_ratio() - 1.0).abs() < 1e-12);
    assert!(budget.max_gain().0.abs() < 1e-12);
    // The allowance is the work at the deepest point reached, where
    // E / (E(0) + max W) would have fallen to u / deepest.
    assert!((budget.allowance() - deepest).abs() < 1e-12);
    assert!(deepest > 1.99);
}

#[test]
fn a_gain_on_the_way_back_up_is_reported() {
    // Down to u = 2 (max W = 2), then back up to u = 1 with ½ J more
    // kinetic energy than the exact motion's ½ J: E = 1.5 J, W = 1 J, a
    // gain of ½ J against the allowance of 2 J. E / (E(0) + max W) =
    // 0.75 would call it no gain.
    let system = bob();
    let mut budget = EnergyBudget::new(&system);
    let lowest = budget.record(&system, &bob_at(&system, 2.0, 0.0, 1.0));
    assert!((lowest.unwrap() - 1.0).abs() < 1e-12);
    let ratio = budget
        .record(&system, &bob_at(&system, 1.0, -(2.0_f64.sqrt()), 2.0))
        .unwrap();
    assert!((ratio - 1.25).abs() < 1e-12, "ratio {ratio}");
    let (gain, time) = budget.max_gain();
    assert!((gain - 0.5).abs() < 1e-12, "gain {gain}");
    assert!((time - 2.0).abs() < 1e-15);
    assert!(!budget.exceeded());
    let mut bounded = EnergyBudget::new(&system).with_bound(1.2);
    bounded.record(&system, &bob_at(&system, 2.0, 0.0, 1.0));
    assert!(!bounded.exceeded());
    bounded.record(&system, &bob_at(&system, 1.0, -(2.0_f64.sqrt()), 2.0));
    assert!(bounded.exceeded());
}

#[test]
fn energy_from_nowhere_is_an_undefined_ratio_then_a_large_one() {
    // A free particle at rest without gravity: no budget at all.
    let mut b = SystemBuilder::new();
    b.particle(2.0, [0.0, 0.0, 0.0]);
    let system = b.build().unwrap();
    let mut budget = EnergyBudget::new(&system);
    let still = system.initial_state();
    assert_eq!(budget.record(&system, &still), None);
    let moving = state_at(&system, &[Vec3::zeros()], &[Vec3::new(1.0, 0.0, 0.0)], 0.1);
    assert_eq!(budget.record(&system, &moving), None);
    // ½·2 kg·(1 m/s)² from nowhere, at t = 0.1 s.
    assert_eq!(budget.max_gain(), (1.0, 0.1));
    let broken = state_at(
        &system,
        &[Vec3::zeros()],
        &[Vec3::new(f64::NAN, 0.0, 0.0)],
        0.2,
    );
    assert_eq!(budget.record(&system, &broken).map(f64::is_nan), Some(true));
    assert!(budget.max_ratio().is_infinite());
    assert_eq!(budget.max_gain(), (f64::INFINITY, 0.2));
}

#[test]
fn a_scripted_pin_stretching_a_spring_pays_for_its_energy() {
    // A pin moving at 1 m/s drags a spring (k = 4) whose other end is
    // pinned: the pin's work ∫ −v·f dt = ½ k s² is all elastic energy.
    let mut b = SystemBuilder::new();
    let fixed = b.particle(1.0, [0.0, 0.0, 0.0]);
    let dragged = b.particle(1.0, [1.0, 0.0, 0.0]);
    b.pin(fixed);
    b.pin_moving(
        dragged,
        Path::Linear {
            velocity: Vec3::new(1.0, 0.0, 0.0),
        },
    );
    b.spring(fixed, dragged, 4.0);
    let system = b.build().unwrap();
    let mut budget = EnergyBudget::new(&system);
    for k in 1..=100 {
        let t = 0.01 * f64::from(k);
        let state = state_at(
            &system,
            &[Vec3::zeros(), Vec3::new(1.0 + t, 0.0, 0.0)],
            &[Vec3::zeros(), Vec3::new(1.0, 0.0, 0.0)],
            t,
        );
        let ratio = budget.record(&system, &state).unwrap();
        // The trapezoidal rule is exact for the linear power 4t.
        assert!((ratio - 1.0).abs() < 1e-12, "t = {t}: ratio {ratio}");
    }
}
