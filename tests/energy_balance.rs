//! Energy balance on a damped, pinned, gravity-loaded mesh: the energy lost
//! equals the integral of the dissipated power, `E(t) + ∫₀ᵗ P dt = E(0)`.

use hooke::prelude::*;

/// A 5×5 grid of particles with structural and shear springs, spring and air
/// damping, gravity, two pinned corners, released stretched by 20 %.
fn stretched_mesh() -> System {
    let n = 5;
    let mut b = SystemBuilder::new();
    for row in 0..n {
        for col in 0..n {
            let (x, z) = (col as f64 * 0.25, row as f64 * 0.25);
            b.particle(0.05 + 0.01 * (row + col) as f64, [1.2 * x, 0.0, 1.2 * z]);
        }
    }
    let id = |row: usize, col: usize| row * n + col;
    for row in 0..n {
        for col in 0..n {
            let mut link = |other: usize, rest: f64| {
                b.spring(id(row, col), other, 40.0)
                    .rest_length(rest)
                    .damping(0.05);
            };
            if col + 1 < n {
                link(id(row, col + 1), 0.25);
            }
            if row + 1 < n {
                link(id(row + 1, col), 0.25);
            }
            if row + 1 < n && col + 1 < n {
                link(id(row + 1, col + 1), 0.25 * 2f64.sqrt());
            }
        }
    }
    b.pin(id(0, 0)).pin(id(0, n - 1));
    b.gravity([0.0, -9.81, 0.0]).air_damping(0.01);
    b.build().unwrap()
}

#[test]
fn energy_lost_equals_dissipated_work() {
    let system = stretched_mesh();
    let mut state = system.initial_state();
    let mut log = EnergyLog::default();
    let dt = 2e-4;
    Simulation::new(&system, &mut Rk4::new())
        .observe(1, &mut log)
        .run(&mut state, dt, 10_000)
        .unwrap();

    let samples = log.samples();
    let initial = samples[0].energy.total();
    let mut dissipated = 0.0;
    let mut worst: f64 = 0.0;
    for pair in samples.windows(2) {
        dissipated += 0.5 * dt * (pair[0].dissipation_power + pair[1].dissipation_power);
        worst = worst.max((pair[1].energy.total() + dissipated - initial).abs());
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
