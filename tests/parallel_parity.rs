//! The parallel force evaluation agrees with the sequential one.
#![cfg(feature = "parallel")]

use hooke::core::{ForceEvaluator, Parallelism};
use hooke::prelude::*;

/// A ragged random mesh: particles on a jittered line, each joined to a few
/// later ones, with damping, gravity, air damping and pins.
fn random_mesh(particles: usize) -> (System, State) {
    let mut seed = 0x9E37_79B9_7F4A_7C15_u64;
    let mut uniform = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut b = SystemBuilder::new();
    for i in 0..particles {
        let jitter = [uniform(), uniform(), uniform()].map(|u| u - 0.5);
        let velocity = [uniform(), uniform(), uniform()].map(|u| 2.0 * u - 1.0);
        b.particle_with_velocity(
            0.1 + uniform(),
            [i as f64 * 0.1 + jitter[0], jitter[1], jitter[2]],
            velocity,
        );
    }
    for i in 0..particles {
        for offset in [1, 2, 7] {
            if i + offset < particles {
                b.spring(i, i + offset, 10.0 + 100.0 * uniform())
                    .rest_length(0.1 * offset as f64)
                    .damping(uniform());
            }
        }
    }
    b.pin(0)
        .pin(particles / 2)
        .gravity([0.0, -9.81, 0.0])
        .air_damping(0.02);
    let system = b.build().unwrap();
    let state = system.initial_state();
    (system, state)
}

#[test]
fn parallel_and_sequential_forces_agree() {
    let (system, state) = random_mesh(5000);
    let (x, v) = (state.positions(), state.velocities());
    let n = system.particle_count();
    let (mut sequential, mut parallel) = (vec![Vec3::zeros(); n], vec![Vec3::zeros(); n]);
    ForceEvaluator::new(Parallelism::Sequential).accelerations(&system, x, v, &mut sequential);
    ForceEvaluator::new(Parallelism::Parallel).accelerations(&system, x, v, &mut parallel);
    for (i, (s, p)) in sequential.iter().zip(&parallel).enumerate() {
        assert!(
            (s - p).norm() <= 1e-12 * (1.0 + s.norm()),
            "particle {i}: {s:?} vs {p:?}"
        );
    }
    assert_eq!(
        sequential[0],
        Vec3::zeros(),
        "pinned particles do not accelerate"
    );
}
