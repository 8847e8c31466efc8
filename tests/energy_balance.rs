//! Energy balance on a damped, pinned, gravity-loaded mesh: the energy lost
//! equals the integral of the dissipated power, `E(t) + ∫₀ᵗ P dt = E(0)`.

use hooke::prelude::*;

/// A 6×6 cloth sheet with spring and air damping, gravity and two pinned
/// corners, released stretched by 20 %.
fn stretched_sheet() -> (System, State) {
    let sheet = Sheet {
        stiffness: 40.0,
        damping: 0.05,
        air_damping: 0.01,
        ..Sheet::new(6)
    };
    let system = sheet.system().unwrap();
    let mut state = system.initial_state();
    for x in state.positions_mut() {
        *x *= 1.2;
    }
    (system, state)
}

#[test]
fn energy_lost_equals_dissipated_work() {
    let (system, mut state) = stretched_sheet();
    let mut log = EnergyLog::default();
    let dt = 2e-4;
    Simulation::new(&system, &mut Rk4::new())
        .observe(1, &mut log)
        .run(&mut state, dt, 10_000)
        .unwrap();

    // Composite Simpson over pairs of steps, O(h⁴) like RK4 itself.
    let samples = log.samples();
    let initial = samples[0].energy.total();
    let mut dissipated = 0.0;
    let mut worst: f64 = 0.0;
    for triple in samples.windows(3).step_by(2) {
        let [p0, p1, p2] = [0, 1, 2].map(|k| triple[k].dissipation_power);
        dissipated += dt / 3.0 * (p0 + 4.0 * p1 + p2);
        worst = worst.max((triple[2].energy.total() + dissipated - initial).abs());
    }
    let elastic = samples[0].energy.elastic;
    assert!(
        dissipated > 0.1 * elastic,
        "the dampers did little: {dissipated} J of {elastic} J"
    );
    assert!(
        worst <= 1e-6 * elastic,
        "energy balance off by {worst:.3e} J (elastic {elastic:.3} J)"
    );
}
