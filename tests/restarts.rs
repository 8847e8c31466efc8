//! Integrators that carry history between steps restart from the state
//! alone when handed a state they did not produce, and Gear rescales its
//! history when only the step size changes.

mod common;

use hooke::prelude::*;

fn with_history() -> Vec<fn() -> Box<dyn Integrator>> {
    vec![
        || Box::new(Leapfrog::new()),
        || Box::new(VelocityVerlet::new()),
        || Box::new(PositionVerlet::new()),
        || Box::new(Beeman::new()),
        || Box::new(Gear::new()),
        || Box::new(DormandPrince::default()),
    ]
}

/// After the state is edited, the next step equals a fresh integrator's first
/// step from the edited state, bit for bit.
#[test]
fn an_edited_state_restarts_the_integrator() {
    let system = HangingChain::new(5, 0.2, 300.0, 0.2)
        .damped(0.1, 0.0)
        .system()
        .unwrap();
    for make in with_history() {
        let mut used = make();
        let mut state = system.initial_state();
        for _ in 0..5 {
            used.step(&system, &mut state, 1e-3).unwrap();
        }
        state.velocities_mut()[3].x += 0.5;
        let mut copy = state.clone();
        used.step(&system, &mut state, 1e-3).unwrap();
        make().step(&system, &mut copy, 1e-3).unwrap();
        assert_eq!(state.positions(), copy.positions(), "{}", used.name());
        assert_eq!(state.velocities(), copy.velocities(), "{}", used.name());
    }
}

/// One integrator alternating between two systems behaves like two.
#[test]
fn alternating_systems_do_not_share_history() {
    let first = HangingChain::new(4, 0.2, 300.0, 0.2).system().unwrap();
    let second = HangingChain::new(4, 0.3, 200.0, 0.2).system().unwrap();
    for make in with_history() {
        let (mut shared, mut only_first, mut only_second) = (make(), make(), make());
        let (mut a, mut b) = (first.initial_state(), second.initial_state());
        let (mut a_alone, mut b_alone) = (first.initial_state(), second.initial_state());
        for _ in 0..10 {
            shared.step(&first, &mut a, 1e-3).unwrap();
            shared.step(&second, &mut b, 1e-3).unwrap();
            only_first.step(&first, &mut a_alone, 1e-3).unwrap();
            only_second.step(&second, &mut b_alone, 1e-3).unwrap();
        }
        let name = shared.name();
        let close = |x: &[Vec3], y: &[Vec3]| x.iter().zip(y).all(|(p, q)| (p - q).norm() <= 1e-6);
        assert!(close(a.positions(), a_alone.positions()), "{name}");
        assert!(close(b.positions(), b_alone.positions()), "{name}");
    }
}

/// Halving Gear's step mid-run rescales its Nordsieck vector instead of
/// restarting; the run stays fourth-order accurate: its error lies between
/// those of constant-step runs at the two step sizes.
#[test]
fn gear_rescales_its_history_when_the_step_changes() {
    let oscillator = Oscillator::damped(1.0, 1.0, 0.2);
    let system = oscillator.system().unwrap();
    let (h, t_end) = (0.05, 10.0);
    let mut gear = Gear::new();
    let mut state = system.initial_state();
    let mut report = StepReport::default();
    for _ in 0..100 {
        report += gear.step(&system, &mut state, h).unwrap();
    }
    for _ in 0..200 {
        report += gear.step(&system, &mut state, h / 2.0).unwrap();
    }
    let (u, _) = oscillator.solution(t_end);
    let changed = (state.positions()[Oscillator::BOB].x - u).abs();
    // One start (16 evaluations) and one evaluation per step: no restart.
    assert_eq!(report.force_evaluations, 16 + 300);
    let coarse = common::oscillator_error(&mut Gear::new(), &oscillator, h, t_end);
    let fine = common::oscillator_error(&mut Gear::new(), &oscillator, h / 2.0, t_end);
    assert!(
        changed < coarse && changed > 0.5 * fine,
        "{fine:.2e} < {changed:.2e} < {coarse:.2e}?"
    );
}
