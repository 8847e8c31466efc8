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

/// A 1 m × 1 m cloth of 9 × 9 particles hung from its top edge in the
/// x–y plane, facing a wind of 2 m/s along +z (drag 0.5 N·s/m³), stepped
/// by `method` at `dt`.
fn windy_cloth(method: &str, dt: f64) -> hooke_scenes::Scene {
    let text = format!(
        r#"
        [simulation]
        duration = 1.0
        dt = {dt}

        [integrator]
        method = "{method}"

        [world]
        wind = {{ velocity = [0.0, 0.0, 2.0], drag = 0.5 }}

        [[bodies]]
        type = "cloth"
        columns = 9
        rows = 9
        size = [1.0, 1.0]
        plane = "vertical"
        density = 0.2
        stretch = {{ stiffness = 1e3 }}
        shear = {{ stiffness = 1e2 }}
        bend = {{ stiffness = 0.1 }}
        self_collision = false
        pins = ["top"]
        "#
    );
    hooke_scenes::file::parse(&text, std::path::Path::new("windy.toml")).unwrap()
}

/// Runs `scene` for its duration under its budget; returns the budget,
/// the largest gain `E(t) − E(0) − W(t)` with the terms' work left out,
/// and the wind's work `∫ Σᵢ fᵢ·w dt` by the trapezoidal rule on its force
/// ([`Term::force`]), computed apart from [`Term::work`].
fn windy_run(scene: &hooke_scenes::Scene) -> (EnergyBudget, f64, f64) {
    let system = &scene.system;
    let wind = Vec3::new(0.0, 0.0, 2.0);
    let power = |state: &State| {
        let mut f = vec![Vec3::zeros(); system.particle_count()];
        system.terms()[0].force(system, state.positions(), state.velocities(), &mut f);
        f.iter().map(|fi| fi.dot(&wind)).sum::<f64>()
    };
    let mut integrator = scene.integrator.build().unwrap();
    let mut state = system.initial_state();
    let mut budget = EnergyBudget::new(system);
    let (mut without_terms, mut trapezoid) = (f64::NEG_INFINITY, 0.0);
    let dt = scene.timing.dt;
    for _ in 0..scene.timing.steps() {
        let before = power(&state);
        integrator.step(system, &mut state, dt).unwrap();
        trapezoid += 0.5 * (before + power(&state)) * dt;
        budget.record(system, &state);
        let work = budget.gravity_work(&state) + budget.pin_work;
        let gain = budget.energy(system, &state) - budget.initial() - work;
        without_terms = without_terms.max(gain);
    }
    (budget, without_terms, trapezoid)
}

/// A cloth hung in a wind, set swinging by it, under symplectic Euler and
/// backward Euler: the drag dissipates energy, so with the wind's work
/// counted the budget's gain stays at most zero (below 10⁻⁶ of the
/// allowance, hooke's warning threshold); the work it counts is the
/// wind's, within 1% of the trapezoidal rule on its force (2·10⁻⁴ and
/// 2·10⁻³ off at the two steps: the term's own rule, the drag at each
/// step's end, is first order in `h`); and without it the wind's 1.3 J
/// would show as a gain of about 0.18 J, 15% of the allowance.
#[test]
fn a_windy_cloth_gains_no_energy_beyond_the_winds_work() {
    for (method, dt) in [("symplectic-euler", 1e-3), ("backward-euler", 1e-2)] {
        let (budget, without_terms, trapezoid) = windy_run(&windy_cloth(method, dt));
        let (gain, _) = budget.max_gain();
        let allowance = budget.allowance();
        let work = budget.term_work;
        assert!(
            gain <= 1e-6 * allowance,
            "{method}: gain {gain} J of {allowance} J"
        );
        assert!(
            (work - trapezoid).abs() <= 1e-2 * trapezoid,
            "{method}: the wind's work {work} J against {trapezoid} J"
        );
        assert!(
            without_terms > 0.1 * allowance && work > without_terms,
            "{method}: a gain of {without_terms} J without the wind's {work} J"
        );
    }
}
