//! A damped chain released unstretched comes to rest in the configuration
//! statics predicts, with every particle's forces in balance.

use hooke::core::ForceEvaluator;
use hooke::prelude::*;

#[test]
fn damped_chain_settles_where_spring_forces_balance_gravity() {
    let chain = HangingChain::new(10, 0.1, 1000.0, 0.1).damped(0.5, 0.5);
    let system = chain.system().unwrap();
    let mut state = system.initial_state();
    // ω_max ≈ 2√(k/m) = 200 rad/s: symplectic Euler needs h < 0.01 s.
    let mut integrator = SymplecticEuler::new();
    let dt = 1e-3;
    while state.time() < 60.0 {
        integrator.step(&system, &mut state, dt).unwrap();
    }
    let weight = chain.particle_mass * chain.gravity;

    let mut forces = vec![Vec3::zeros(); system.particle_count()];
    ForceEvaluator::default().forces(&system, state.positions(), state.velocities(), &mut forces);
    for (i, f) in forces.iter().enumerate().skip(1) {
        assert!(
            f.norm() <= 1e-9 * weight,
            "particle {i}: net force {:.3e} N",
            f.norm()
        );
    }
    // The pin holds the whole chain: the force it resists is the weight of
    // every particle, its own included.
    let total = chain.particles as f64 * weight;
    assert!(
        (forces[0].y + total).abs() <= 1e-9 * total,
        "force on the pin {:?}",
        forces[0]
    );

    for (i, (x, rest)) in state
        .positions()
        .iter()
        .zip(chain.rest_positions())
        .enumerate()
    {
        assert!(
            (x - rest).norm() <= 1e-9,
            "particle {i}: at {x:?}, statics says {rest:?}"
        );
    }
    for s in 0..chain.particles - 1 {
        let spring = system.springs()[s];
        let (xi, xj) = (state.positions()[spring.i], state.positions()[spring.j]);
        let tension = spring.stiffness * (spring.length(xi, xj) - spring.rest_length);
        assert!(
            (tension - chain.tension(s)).abs() <= 1e-8 * weight,
            "spring {s}: tension {tension}"
        );
    }
}
