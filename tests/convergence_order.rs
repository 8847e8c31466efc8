//! Observed convergence order of every fixed-step integrator against the
//! exact solution of the damped oscillator.

mod common;

use hooke::explicit::fixed_step_integrators;
use hooke::prelude::*;

/// The order each method's theory gives, by name.
fn expected_order(name: &str) -> f64 {
    match name {
        "explicit-euler" | "symplectic-euler" => 1.0,
        "leapfrog" | "velocity-verlet" | "position-verlet" | "midpoint" | "heun" | "beeman" => 2.0,
        "rk4" | "gear" => 4.0,
        other => panic!("no expected order for {other}"),
    }
}

#[test]
fn observed_orders_match_theory_on_the_damped_oscillator() {
    // ω = 1 rad/s, ζ = 0.1: the damping force depends on velocity, which the
    // Verlet family, Beeman and Gear must handle without losing order.
    let oscillator = Oscillator::damped(1.0, 1.0, 0.2);
    let dts: Vec<f64> = (0..4).map(|k| 0.05 / f64::from(1 << k)).collect();
    let mut report = Vec::new();
    for mut integrator in fixed_step_integrators() {
        let errors: Vec<f64> = dts
            .iter()
            .map(|&dt| common::oscillator_error(integrator.as_mut(), &oscillator, dt, 10.0))
            .collect();
        let order = common::log_log_slope(&dts, &errors);
        report.push((
            integrator.name(),
            order,
            expected_order(integrator.name()),
            errors,
        ));
    }
    for (name, order, expected, errors) in &report {
        let errors: Vec<String> = errors.iter().map(|e| format!("{e:.2e}")).collect();
        eprintln!("{name:18} observed order {order:.3} (expected {expected}), errors {errors:?}");
    }
    for (name, order, expected, _) in &report {
        assert!(
            (order - expected).abs() <= 0.15,
            "{name}: observed order {order:.3}, expected {expected}"
        );
    }
}
