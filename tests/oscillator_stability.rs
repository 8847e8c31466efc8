//! Stability of the explicit integrators on the undamped oscillator
//! `x'' = −ω² x`, against the limits theory gives for `θ = hω`.

use hooke::prelude::*;

/// Energy after each of `steps` steps of size `θ/ω`, relative to the initial
/// energy; stops early (with `inf`) once the step fails or the energy has
/// grown past `1e12`.
fn energy_ratios(integrator: &mut dyn Integrator, theta: f64, steps: usize) -> Vec<f64> {
    let oscillator = Oscillator::undamped(2.0, 8.0); // ω = 2 rad/s
    let system = oscillator.system().unwrap();
    let mut state = system.initial_state();
    let initial = oscillator.energy(0.0);
    let measured = system.energy(&state).unwrap().total();
    assert!(
        (measured - initial).abs() <= 1e-15 * initial,
        "energy {measured}, closed form {initial}"
    );
    let dt = theta / oscillator.omega();
    let mut ratios = Vec::with_capacity(steps);
    for _ in 0..steps {
        let ratio = match integrator.step(&system, &mut state, dt) {
            Ok(_) => system.energy(&state).unwrap().total() / initial,
            Err(_) => f64::INFINITY,
        };
        ratios.push(ratio);
        if ratio > 1e12 {
            break;
        }
    }
    ratios
}

/// Makes a fresh integrator.
type Make = fn() -> Box<dyn Integrator>;

fn max(values: &[f64]) -> f64 {
    values.iter().copied().fold(0.0, f64::max)
}

/// Bounded below the limit: the energy stays within `bound` of its initial
/// value and the second half of a long run peaks no higher than the first
/// (to 1e-3: the orbit is sampled at quasi-periodic points, so its peak is
/// approached from below).
/// Unstable above: the energy passes `1e6` within a few thousand steps.
fn assert_limit(make: Make, limit: f64, bound: f64) {
    let name = make().name();
    let below = energy_ratios(make().as_mut(), 0.98 * limit, 20_000);
    let (first, second) = below.split_at(below.len() / 2);
    assert!(
        max(&below) <= bound,
        "{name} at 0.98×limit: energy ratio reached {:.3e}",
        max(&below)
    );
    assert!(
        max(second) <= max(first) * (1.0 + 1e-3),
        "{name} at 0.98×limit: energy still growing ({:.6} then {:.6})",
        max(first),
        max(second)
    );
    let above = energy_ratios(make().as_mut(), 1.02 * limit, 5_000);
    assert!(
        max(&above) > 1e6,
        "{name} at 1.02×limit: energy ratio only {:.3e}",
        max(&above)
    );
}

/// Below `θ = 2` each symplectic method conserves a quadratic form exactly,
/// which bounds the energy (`w = v/ω`):
/// - symplectic Euler conserves `x² + w² − θ x w`; from rest at `x = 1` the
///   energy ratio peaks at `1/(1 − θ/2)`, 50 at `θ = 1.96`;
/// - the Verlet family conserves `(1 − θ²/4) x² + w²`; from rest at `x = 1`
///   the energy never exceeds its initial value;
/// - Beeman's positions are Verlet's and its velocities a fixed combination
///   of three of them; its linear map peaks near 15.6 at `θ = 1.96`.
#[test]
fn symplectic_methods_are_stable_exactly_below_two() {
    let rounding = 1.0 + 1e-9;
    assert_limit(
        || Box::new(SymplecticEuler::new()),
        2.0,
        rounding / (1.0 - 0.98),
    );
    assert_limit(|| Box::new(Leapfrog::new()), 2.0, rounding);
    assert_limit(|| Box::new(VelocityVerlet::new()), 2.0, rounding);
    assert_limit(|| Box::new(PositionVerlet::new()), 2.0, rounding);
    assert_limit(|| Box::new(Beeman::new()), 2.0, 16.0);
}

#[test]
fn rk4_is_stable_exactly_up_to_two_root_two() {
    assert_limit(|| Box::new(Rk4::new()), 2.0 * 2f64.sqrt(), 1.0 + 1e-12);
}

/// One step of a Runge–Kutta method multiplies `ωx + iv` by its stability
/// function `R(−iθ)`, so the energy by `|R(iθ)|²` exactly: `1 + θ²` for
/// Euler, `1 + θ⁴/4` for midpoint and Heun. Both exceed 1 at every `θ > 0`.
#[test]
fn euler_midpoint_and_heun_gain_the_predicted_energy_every_step() {
    assert_gain_per_step(|| Box::new(ExplicitEuler::new()), |t| 1.0 + t * t);
    assert_gain_per_step(|| Box::new(Midpoint::new()), |t| 1.0 + t.powi(4) / 4.0);
    assert_gain_per_step(|| Box::new(Heun::new()), |t| 1.0 + t.powi(4) / 4.0);
}

fn assert_gain_per_step(make: Make, gain: fn(f64) -> f64) {
    let name = make().name();
    for theta in [0.01, 0.1, 0.5, 1.0, 2.0, 3.0] {
        let mut previous = 1.0;
        for ratio in energy_ratios(make().as_mut(), theta, 8) {
            assert!(ratio > previous, "{name} at θ = {theta}: energy fell");
            let per_step = ratio / previous;
            assert!(
                (per_step - gain(theta)).abs() <= 1e-9 * gain(theta),
                "{name} at θ = {theta}: energy gain {per_step} per step, theory {}",
                gain(theta)
            );
            previous = ratio;
        }
    }
}

/// Gear's step has spectral radius above 1 at every `θ > 0` (by about
/// `0.037 θ⁶` for small `θ`): over a long run the energy creeps upward.
#[test]
fn gear_gains_energy_slowly_at_every_step() {
    for (theta, steps) in [(0.1, 40_000), (0.3, 4_000), (1.0, 1_000)] {
        let ratios = energy_ratios(&mut Gear::new(), theta, steps);
        let window = steps / 10;
        let early = max(&ratios[..window]);
        let late = max(&ratios[ratios.len() - window..]);
        assert!(
            late > early,
            "gear at θ = {theta}: energy peak {early:.9} then {late:.9}"
        );
    }
}
