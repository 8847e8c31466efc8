//! Obstacles and contact response: signed distances against geometry,
//! normals against finite differences, Coulomb friction and restitution
//! against their laws, moving obstacles, and invalid obstacles.

use hooke::core::{Mat3, respond_to_contact};
use hooke::explicit::fixed_step_integrators;
use hooke::prelude::*;
use hooke::scenes::{Lattice, Mass, Springs, TetSplit, Volume};

fn shapes() -> Vec<Shape> {
    let rotation = *nalgebra::Rotation3::from_euler_angles(0.3, -0.5, 1.1).matrix();
    vec![
        Shape::Plane {
            point: Vec3::new(0.0, 0.2, 0.0),
            normal: Vec3::new(0.3, 2.0, -0.1),
        },
        Shape::Sphere {
            center: Vec3::new(0.1, -0.2, 0.3),
            radius: 0.7,
        },
        Shape::Box {
            center: Vec3::new(-0.1, 0.0, 0.2),
            half_extents: Vec3::new(0.5, 0.3, 0.8),
            rotation,
        },
        Shape::Capsule {
            a: Vec3::new(-0.4, 0.0, 0.0),
            b: Vec3::new(0.5, 0.3, -0.2),
            radius: 0.35,
        },
    ]
}

/// Points on a deterministic scatter through [-1.5, 1.5]³.
fn points() -> impl Iterator<Item = Vec3> {
    (0..400).map(|k| {
        let f = |a: f64| 1.5 * (a * k as f64 + 0.1).sin();
        Vec3::new(f(0.7371), f(1.3113), f(2.0777))
    })
}

#[test]
fn normals_are_the_gradient_of_the_signed_distance() {
    let eps = 1e-6;
    for shape in shapes() {
        let mut checked = 0;
        for x in points() {
            let (phi, n) = shape.distance(x);
            let gradient = Vec3::from_fn(|k, _| {
                let mut e = Vec3::zeros();
                e[k] = eps;
                (shape.distance(x + e).0 - shape.distance(x - e).0) / (2.0 * eps)
            });
            // Skip points within eps of a kink of the distance field.
            if (gradient.norm() - 1.0).abs() > 1e-6 {
                continue;
            }
            assert!(
                (gradient - n).norm() < 1e-6,
                "{shape:?} at {x:?}: n = {n:?}, ∇φ = {gradient:?}"
            );
            // Moving by -φ along the normal lands on the surface.
            assert!(
                shape.distance(x - phi * n).0.abs() < 1e-9,
                "{shape:?} at {x:?}"
            );
            checked += 1;
        }
        assert!(checked > 350, "{shape:?}: only {checked} smooth points");
    }
}

#[test]
fn distances_match_the_geometry() {
    let sphere = Shape::Sphere {
        center: Vec3::zeros(),
        radius: 1.0,
    };
    assert!((sphere.distance(Vec3::new(0.0, 3.0, 4.0)).0 - 4.0).abs() < 1e-15);
    let cube = Shape::Box {
        center: Vec3::zeros(),
        half_extents: Vec3::new(1.0, 1.0, 1.0),
        rotation: Mat3::identity(),
    };
    // Outside a corner: the distance to the corner; inside: to the nearest face.
    assert!((cube.distance(Vec3::new(2.0, 2.0, 2.0)).0 - 3f64.sqrt()).abs() < 1e-15);
    let (phi, n) = cube.distance(Vec3::new(0.1, -0.7, 0.2));
    assert!((phi + 0.3).abs() < 1e-15 && (n + Vec3::y()).norm() < 1e-15);
    let capsule = Shape::Capsule {
        a: Vec3::zeros(),
        b: Vec3::new(2.0, 0.0, 0.0),
        radius: 0.5,
    };
    assert!((capsule.distance(Vec3::new(1.0, 1.0, 0.0)).0 - 0.5).abs() < 1e-15);
    assert!((capsule.distance(Vec3::new(3.0, 0.0, 0.0)).0 - 0.5).abs() < 1e-15);
}

/// Continuous collision detection against each shape: a particle thrown
/// through it stops with a tenth of its distance kept, never closer on the
/// way, and not much farther.
#[test]
fn advancement_stops_a_fast_particle_at_the_kept_gap_and_never_crosses() {
    for shape in shapes() {
        for k in 0..200 {
            let f = |a: f64| 2.0 * (a * f64::from(k) + 0.3).sin();
            let x = Vec3::new(f(0.71), f(1.37), f(2.11));
            let phi = shape.distance(x).0;
            if phi <= 0.01 {
                continue;
            }
            // Through the shape's centre region and far beyond it.
            let dx = 10.0 * (Vec3::new(0.05, -0.1, 0.2) - x);
            let target = 0.1 * phi;
            let tau = shape.advance(x, dx, target);
            for j in 0..=1000 {
                let s = tau * f64::from(j) / 1000.0;
                assert!(
                    shape.distance(x + s * dx).0 >= target - 1e-9,
                    "{shape:?} from {x:?}: crossed at {s} < τ = {tau}"
                );
            }
            if tau < 1.0 {
                // Not absurdly conservative: within 1 % of the gap kept.
                let reached = shape.distance(x + tau * dx).0;
                assert!(
                    reached - target <= 0.01 * (phi - target) + 1e-12,
                    "{shape:?}: stopped at φ = {reached}, target {target}"
                );
            }
        }
    }
}

const DT: f64 = 1e-4;

/// A particle released at rest on a plane tilted by `angle` about z with
/// friction `mu`; returns its displacement along the slope after `time`.
fn slide(angle: f64, mu: f64, time: f64, integrator: &mut dyn Integrator) -> f64 {
    let normal = Vec3::new(-angle.sin(), angle.cos(), 0.0);
    let mut b = SystemBuilder::new();
    b.particle(0.1, [0.0, 0.0, 0.0]);
    b.gravity([0.0, -9.81, 0.0]);
    b.obstacle(
        Obstacle::new(Shape::Plane {
            point: Vec3::zeros(),
            normal,
        })
        .friction(mu),
    );
    let system = b.build().unwrap();
    let mut state = system.initial_state();
    let steps = (time / DT).round() as usize;
    for _ in 0..steps {
        integrator.step(&system, &mut state, DT).unwrap();
    }
    let x = state.positions()[0];
    assert!(x.dot(&normal) > -1e-12, "the particle sank: {x:?}");
    // Down the slope is −(cos θ, sin θ, 0).
    -x.dot(&Vec3::new(angle.cos(), angle.sin(), 0.0))
}

/// Every fixed-step method with the tolerance on its sliding distance, and
/// the implicit ones with the linearised step and converged (with both
/// linear solvers).
/// The linearised step is one Newton step on `Φ`, whose friction term is
/// exact for a sliding contact (its force is constant along the slide), so
/// it slides within 0.17 % of the law here, as the converged step does.
fn every_method() -> Vec<(Box<dyn Integrator + Send>, f64)> {
    let mut all: Vec<(Box<dyn Integrator + Send>, f64)> = fixed_step_integrators()
        .into_iter()
        .map(|integrator| (integrator, 1e-2))
        .collect();
    all.push((Box::new(Implicit::backward_euler().linearized()), 2e-3));
    all.push((Box::new(Implicit::bdf2().linearized()), 2e-3));
    all.push((Box::new(Implicit::backward_euler()), 2e-3));
    all.push((
        Box::new(Implicit::bdf2().with_solver(LinearSolver::Pcg(PcgSettings::default()))),
        2e-3,
    ));
    all
}

#[test]
fn coulomb_friction_holds_below_tan_angle_equal_mu_and_slides_above() {
    let (mu, g, time) = (0.5, 9.81, 1.0);
    for (mut integrator, tolerance) in every_method() {
        let name = integrator.name();
        // Below the limit a first-order method may creep by O(g dt) per
        // second, as a step's projection back to the plane keeps its
        // tangential part: 1 mm here, against 0.42 m of sliding above it.
        let stuck = slide(0.4f64.atan(), mu, time, integrator.as_mut());
        assert!(
            stuck.abs() < g * DT * time,
            "{name}: moved {stuck} m below the limit"
        );
        let angle = 0.6f64.atan();
        let slid = slide(angle, mu, time, integrator.as_mut());
        let theory = 0.5 * g * (angle.sin() - mu * angle.cos()) * time * time;
        assert!(
            (slid - theory).abs() < tolerance * theory,
            "{name}: slid {slid} m, theory {theory} m"
        );
    }
}

#[test]
fn restitution_sets_the_rebound_speed() {
    let floor = Obstacle::new(Shape::Plane {
        point: Vec3::zeros(),
        normal: Vec3::y(),
    });
    for e in [0.0, 0.5, 1.0] {
        let o = floor.clone().restitution(e);
        let (mut x, mut v) = (Vec3::new(0.0, -1e-3, 0.0), Vec3::new(0.3, -2.0, 0.0));
        assert!(respond_to_contact(&o, &mut x, &mut v, 0.0, true));
        assert!(
            (v - Vec3::new(0.3, 2.0 * e, 0.0)).norm() < 1e-15,
            "e = {e}: {v:?}"
        );
    }
    // A particle dropped from 1 m rebounds to e² m.
    let mut b = SystemBuilder::new();
    b.particle(1.0, [0.0, 1.0, 0.0]);
    b.gravity([0.0, -9.81, 0.0]);
    b.obstacle(floor.restitution(0.5));
    let system = b.build().unwrap();
    let mut state = system.initial_state();
    let mut integrator = VelocityVerlet::new();
    let mut highest_after_bounce: f64 = 0.0;
    let mut bounced = false;
    for _ in 0..9000 {
        let report = integrator.step(&system, &mut state, 1e-4).unwrap();
        bounced |= report.contacts > 0;
        if bounced {
            highest_after_bounce = highest_after_bounce.max(state.positions()[0].y);
        }
    }
    assert!(
        (highest_after_bounce - 0.25).abs() < 5e-3,
        "rebound to {highest_after_bounce} m"
    );
}

/// A body pressed into the floor by its own elasticity does not bounce off
/// it: restitution applies to new contacts only, so a dropped jelly cube
/// never gains energy, with an explicit and an implicit method.
#[test]
fn restitution_does_not_pump_energy_into_a_resting_body() {
    let springs = Springs::modulus(2e4).damping(0.5);
    let cube = Lattice::tets(3, 3, 3, TetSplit::Six)
        .size([0.2, 0.2, 0.2])
        .origin([-0.1, 0.3, -0.1])
        .mass(Mass::Density(1000.0))
        .edges(springs)
        .face_diagonals(springs)
        .body_diagonals(springs)
        // Springs only: the bound below counts their stiffness `k`.
        .volume(Volume::Off)
        .build()
        .unwrap();
    let mut b = SystemBuilder::new();
    cube.add_to(&mut b);
    b.gravity([0.0, -9.81, 0.0]);
    b.obstacle(
        Obstacle::new(Shape::Plane {
            point: Vec3::zeros(),
            normal: Vec3::y(),
        })
        .restitution(0.9),
    );
    let system = b.build().unwrap();
    let start = system.energy(&system.initial_state()).unwrap().total();
    // Backward Euler never gains energy and comes to rest, 0.1 m up (the
    // cube's centre): E = M g · 0.1 m. Velocity Verlet's projection out of
    // the floor stores up to ½k(h v)² per contact, under 1 % here, and it
    // keeps bouncing at e = 0.9.
    let rest = 8.0 * 9.81 * 0.1;
    let runs: Vec<(Box<dyn Integrator>, f64, f64, f64)> = vec![
        (Box::new(VelocityVerlet::new()), 2e-4, 1e-2, f64::INFINITY),
        (
            Box::new(Implicit::backward_euler()),
            1.0 / 240.0,
            1e-9,
            1.01 * rest,
        ),
    ];
    for (mut integrator, dt, gain, end) in runs {
        let name = integrator.name();
        let mut state = system.initial_state();
        let mut highest = start;
        for _ in 0..(1.5 / dt) as usize {
            integrator.step(&system, &mut state, dt).unwrap();
            highest = highest.max(system.energy(&state).unwrap().total());
        }
        assert!(
            highest <= start * (1.0 + gain),
            "{name}: energy rose from {start} J to {highest} J"
        );
        let last = system.energy(&state).unwrap().total();
        assert!(last <= end, "{name}: {last} J at the end, at rest {rest} J");
    }
}

#[test]
fn a_moving_obstacle_carries_particles_along() {
    let lift = 0.5;
    let mut b = SystemBuilder::new();
    b.particle(1.0, [0.0, 0.0, 0.0]);
    b.gravity([0.0, -9.81, 0.0]);
    b.obstacle(
        Obstacle::new(Shape::Plane {
            point: Vec3::zeros(),
            normal: Vec3::y(),
        })
        .moving(Path::Linear {
            velocity: Vec3::new(0.0, lift, 0.0),
        }),
    );
    let system = b.build().unwrap();
    let mut state = system.initial_state();
    let mut integrator = SymplecticEuler::new();
    for _ in 0..2000 {
        integrator.step(&system, &mut state, 1e-3).unwrap();
        let floor = lift * state.time();
        assert!(state.positions()[0].y >= floor - 1e-12);
    }
    assert!((state.positions()[0].y - lift * 2.0).abs() < 1e-9);
    assert!((state.velocities()[0].y - lift).abs() < 1e-9);
}

#[test]
fn invalid_obstacles_name_the_obstacle_and_the_field() {
    let cases = [
        (
            Obstacle::new(Shape::Sphere {
                center: Vec3::zeros(),
                radius: -1.0,
            }),
            "sphere radius",
        ),
        (
            Obstacle::new(Shape::Plane {
                point: Vec3::zeros(),
                normal: Vec3::zeros(),
            }),
            "plane normal",
        ),
        (
            Obstacle::new(Shape::Box {
                center: Vec3::zeros(),
                half_extents: Vec3::new(1.0, 1.0, 1.0),
                rotation: 2.0 * Mat3::identity(),
            }),
            "box rotation",
        ),
        (
            Obstacle::new(Shape::Capsule {
                a: Vec3::new(f64::NAN, 0.0, 0.0),
                b: Vec3::zeros(),
                radius: 1.0,
            }),
            "capsule ends",
        ),
        (
            Obstacle::new(Shape::Sphere {
                center: Vec3::zeros(),
                radius: 1.0,
            })
            .friction(-0.1),
            "friction",
        ),
        (
            Obstacle::new(Shape::Sphere {
                center: Vec3::zeros(),
                radius: 1.0,
            })
            .restitution(1.5),
            "restitution",
        ),
        (
            Obstacle::new(Shape::Sphere {
                center: Vec3::zeros(),
                radius: 1.0,
            })
            .moving(Path::Keyframes(vec![
                (1.0, Vec3::zeros()),
                (0.5, Vec3::zeros()),
            ])),
            "keyframe times",
        ),
    ];
    for (obstacle, field) in cases {
        let mut b = SystemBuilder::new();
        b.particle(1.0, [0.0, 2.0, 0.0]);
        b.obstacle(Obstacle::new(Shape::Plane {
            point: Vec3::zeros(),
            normal: Vec3::y(),
        }));
        b.obstacle(obstacle);
        let error = b.build().unwrap_err();
        assert!(
            matches!(error, BuildError::InvalidObstacle { obstacle: 1, .. }),
            "{error}"
        );
        let message = error.to_string();
        assert!(
            message.starts_with("obstacle 1: ") && message.contains(field),
            "{message}"
        );
    }
}
