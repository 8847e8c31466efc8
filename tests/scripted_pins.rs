//! Scripted pins follow their paths exactly in every integrator, and a
//! spring hanging from a handle moving at constant velocity oscillates as
//! theory says in the handle's (inertial) frame.

use hooke::explicit::fixed_step_integrators;
use hooke::prelude::*;

const OMEGA: f64 = 2.0;
const SPEED: f64 = 0.3;

/// A handle moving along +x at `SPEED` and a bob on a zero-rest-length
/// spring with `k/m = ω²`, starting 0.5 m below the handle at rest.
fn towed() -> (System, usize, usize) {
    let mut b = SystemBuilder::new();
    let handle = b.particle(1.0, [0.0, 0.0, 0.0]);
    let bob = b.particle(1.0, [0.0, -0.5, 0.0]);
    b.spring(handle, bob, OMEGA * OMEGA).rest_length(0.0);
    b.pin_moving(
        handle,
        Path::Linear {
            velocity: Vec3::new(SPEED, 0.0, 0.0),
        },
    );
    (b.build().unwrap(), handle, bob)
}

/// In the handle's frame `r'' = −ω² r` with `r(0) = (0, −0.5, 0)` and
/// `r'(0) = (−u, 0, 0)`.
fn bob_at(t: f64) -> Vec3 {
    let handle = Vec3::new(SPEED * t, 0.0, 0.0);
    let r = Vec3::new(
        -SPEED / OMEGA * (OMEGA * t).sin(),
        -0.5 * (OMEGA * t).cos(),
        0.0,
    );
    handle + r
}

#[test]
fn a_towed_oscillator_matches_theory() {
    let (system, handle, bob) = towed();
    let mut integrators: Vec<(Box<dyn Integrator>, f64, f64)> = vec![
        (Box::new(Rk4::new()), 1e-3, 1e-9),
        (Box::new(VelocityVerlet::new()), 1e-3, 1e-6),
        (
            Box::new(Implicit::bdf2().with_newton(30, 1e-12).unwrap()),
            1e-3,
            1e-5,
        ),
    ];
    for (integrator, dt, tolerance) in &mut integrators {
        let mut state = system.initial_state();
        let steps = (2.0 / *dt).round() as usize;
        for _ in 0..steps {
            integrator.step(&system, &mut state, *dt).unwrap();
        }
        let t = state.time();
        let name = integrator.name();
        assert!(
            (state.positions()[handle] - Vec3::new(SPEED * t, 0.0, 0.0)).norm() < 1e-12,
            "{name}: handle at {:?}",
            state.positions()[handle]
        );
        let error = (state.positions()[bob] - bob_at(t)).norm();
        assert!(error < *tolerance, "{name}: bob off by {error} m");
    }
}

#[test]
fn keyframed_pins_are_where_their_path_says_after_every_step() {
    let path = Path::Keyframes(vec![
        (0.0, Vec3::zeros()),
        (0.05, Vec3::new(0.0, 0.1, 0.0)),
        (0.1, Vec3::new(0.2, 0.1, -0.1)),
    ]);
    let mut b = SystemBuilder::new();
    let handle = b.particle(1.0, [1.0, 2.0, 3.0]);
    let bob = b.particle(0.1, [1.0, 1.5, 3.0]);
    b.spring(handle, bob, 50.0);
    b.gravity([0.0, -9.81, 0.0]);
    b.pin_moving(handle, path.clone());
    let system = b.build().unwrap();
    let start = Vec3::new(1.0, 2.0, 3.0);
    let mut integrators = fixed_step_integrators();
    integrators.push(Box::new(Implicit::backward_euler()));
    for mut integrator in integrators {
        let mut state = system.initial_state();
        for _ in 0..150 {
            integrator.step(&system, &mut state, 1e-3).unwrap();
            let t = state.time();
            assert_eq!(state.positions()[handle], start + path.offset(t));
            assert_eq!(state.velocities()[handle], path.velocity(t));
        }
    }
}

#[test]
fn an_invalid_pin_path_names_the_particle() {
    let mut b = SystemBuilder::new();
    b.particle(1.0, [0.0; 3]);
    b.pin_moving(0, Path::Keyframes(Vec::new()));
    let error = b.build().unwrap_err();
    assert!(
        matches!(error, BuildError::InvalidPinPath { particle: 0, .. }),
        "{error}"
    );
    assert!(error.to_string().contains("keyframes"), "{error}");
}
