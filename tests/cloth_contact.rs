//! A cloth dropped on a sphere and on a floor comes to rest on it: no
//! particle ends up inside an obstacle beyond the stated tolerance, the
//! kinetic energy at the end is small, and resting particles do not jitter —
//! with backward Euler (contacts as barrier terms of its step's potential)
//! and with an explicit method (projection and velocity response).

use hooke::prelude::*;
use hooke::scenes::{Cloth, Mass};

/// How deep a particle may be inside an obstacle after a step, m.
const TOLERANCE: f64 = 1e-6;

/// A 0.8 m, 0.1 kg cloth of 15 × 15 particles, 0.3 m above `obstacle`.
fn scene(obstacle: Obstacle) -> System {
    let cloth = Cloth::grid(15, 15)
        .size(0.8, 0.8)
        .mass(Mass::Total(0.1))
        .stretch(200.0)
        .shear(200.0)
        .bend(20.0)
        .offset([-0.4, 0.3, -0.4])
        .build()
        .unwrap();
    let mut b = SystemBuilder::new();
    cloth.add_to(&mut b);
    b.gravity([0.0, -9.81, 0.0]);
    b.air_damping(2e-3);
    b.obstacle(obstacle.friction(0.4));
    b.build().unwrap()
}

fn sphere() -> Obstacle {
    Obstacle::new(Shape::Sphere {
        center: Vec3::new(0.0, 0.0, 0.0),
        radius: 0.2,
    })
}

fn floor() -> Obstacle {
    Obstacle::new(Shape::Plane {
        point: Vec3::new(0.0, 0.0, 0.0),
        normal: Vec3::y(),
    })
}

/// What a run ends with.
struct Outcome {
    deepest: f64,
    kinetic: f64,
    /// Largest distance a particle moved in one step over the last 0.5 s.
    jitter: f64,
    /// The energy (kinetic, springs, gravity) at the start and its largest
    /// value after any step.
    start: f64,
    peak: f64,
}

fn drop(system: &System, integrator: &mut dyn Integrator, dt: f64, duration: f64) -> Outcome {
    let mut state = system.initial_state();
    let steps = (duration / dt).round() as usize;
    let settle = steps - (0.5 / dt).round() as usize;
    let (mut deepest, mut jitter): (f64, f64) = (0.0, 0.0);
    let start = system.energy(&state).unwrap().total();
    let mut peak = f64::NEG_INFINITY;
    for step in 0..steps {
        let before = state.positions().to_vec();
        integrator.step(system, &mut state, dt).unwrap();
        peak = peak.max(system.energy(&state).unwrap().total());
        let t = state.time();
        for x in state.positions() {
            deepest = deepest.max(-system.obstacles()[0].distance(*x, t).0);
        }
        if step >= settle {
            for (a, b) in before.iter().zip(state.positions()) {
                jitter = jitter.max((a - b).norm());
            }
        }
    }
    let kinetic = system
        .masses()
        .iter()
        .zip(state.velocities())
        .map(|(m, v)| 0.5 * m * v.norm_squared())
        .sum();
    Outcome {
        deepest,
        kinetic,
        jitter,
        start,
        peak,
    }
}

/// Falling 0.3 m, the cloth's kinetic energy peaks near m g h = 0.3 J; at
/// rest it is a millionth of that.
fn check(name: &str, outcome: &Outcome) {
    assert!(
        outcome.deepest <= TOLERANCE,
        "{name}: a particle was {} m inside",
        outcome.deepest
    );
    assert!(
        outcome.kinetic < 1e-6,
        "{name}: kinetic energy {} J at the end",
        outcome.kinetic
    );
    assert!(
        outcome.jitter < 1e-5,
        "{name}: a particle moved {} m in one step over the last 0.5 s",
        outcome.jitter
    );
}

#[test]
fn backward_euler_rests_cloth_on_a_sphere_and_a_floor() {
    for (label, obstacle) in [("sphere", sphere()), ("floor", floor())] {
        let system = scene(obstacle);
        let mut integrator = Implicit::backward_euler();
        let outcome = drop(&system, &mut integrator, 1.0 / 60.0, 4.0);
        check(&format!("backward Euler on the {label}"), &outcome);
        // Backward Euler never gains energy, the landing included.
        assert!(
            outcome.peak <= outcome.start * (1.0 + 1e-9),
            "backward Euler on the {label}: the energy rose from {} J to {} J",
            outcome.start,
            outcome.peak
        );
    }
}

#[test]
fn an_explicit_method_rests_cloth_on_a_sphere_and_a_floor() {
    for (label, obstacle) in [("sphere", sphere()), ("floor", floor())] {
        // An explicit method cannot keep the cloth from passing through
        // itself: it runs without self-collision.
        let system = scene(obstacle).without_self_collision();
        let outcome = drop(&system, &mut VelocityVerlet::new(), 2e-4, 4.0);
        check(&format!("velocity Verlet on the {label}"), &outcome);
    }
}

/// Backward Euler at its defaults drops the cloth on the sphere
/// (friction 0.4) and runs `duration` s; returns the largest distance a
/// particle within 1 mm of the sphere moved over the last second.
fn slip_on_sphere(duration: f64) -> f64 {
    let system = scene(sphere());
    let mut integrator = Implicit::backward_euler();
    let dt = 1.0 / 60.0;
    let steps = (duration / dt).round() as usize;
    let last_second = steps - (1.0 / dt).round() as usize;
    let mut state = system.initial_state();
    let mut before = Vec::new();
    for step in 0..steps {
        if step == last_second {
            before = state.positions().to_vec();
        }
        integrator.step(&system, &mut state, dt).unwrap();
    }
    let t = state.time();
    before
        .iter()
        .zip(state.positions())
        .filter(|(_, x)| system.obstacles()[0].distance(**x, t).0 < 1e-3)
        .map(|(a, b)| (a - b).norm())
        .fold(0.0, f64::max)
}

/// Friction inside the implicit solve holds the draped cloth: its contact
/// particles stick, creeping (at most `10⁻⁵` m/s, the friction's sticking
/// speed) by micrometres, not sliding off the sphere.
#[test]
fn backward_euler_friction_holds_cloth_draped_on_a_sphere() {
    let slip = slip_on_sphere(6.0);
    assert!(
        slip < 2e-5,
        "a contact particle slipped {slip} m over the last second"
    );
}
