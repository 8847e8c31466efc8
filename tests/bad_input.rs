//! Invalid systems, steps and parameters give typed errors that name the
//! culprit, never a panic or a NaN state.

use approx::assert_abs_diff_eq;
use hooke::core::{Quantity, SpringParameter};
use hooke::explicit::fixed_step_integrators;
use hooke::prelude::*;

/// Two particles 1 m apart, one spring, to be spoiled by `spoil`.
fn build(spoil: impl FnOnce(&mut SystemBuilder)) -> Result<System, BuildError> {
    let mut b = SystemBuilder::new();
    b.particle(1.0, [0.0, 0.0, 0.0]);
    b.particle(1.0, [1.0, 0.0, 0.0]);
    b.spring(0, 1, 10.0);
    spoil(&mut b);
    b.build()
}

#[test]
fn invalid_masses_name_the_particle() {
    for mass in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let error = build(|b| {
            b.particle(mass, [2.0, 0.0, 0.0]);
        })
        .unwrap_err();
        assert!(
            matches!(error, BuildError::InvalidMass { particle: 2, .. }),
            "{error}"
        );
        assert!(error.to_string().starts_with("particle 2: mass"), "{error}");
    }
}

#[test]
fn non_finite_positions_and_velocities_name_the_particle() {
    let error = build(|b| {
        b.particle(1.0, [0.0, f64::NAN, 0.0]);
    })
    .unwrap_err();
    assert!(matches!(
        error,
        BuildError::NonFiniteParticle {
            particle: 2,
            quantity: Quantity::Position,
            ..
        }
    ));
    let error = build(|b| {
        b.particle_with_velocity(1.0, [0.0; 3], [f64::INFINITY, 0.0, 0.0]);
    })
    .unwrap_err();
    assert!(matches!(
        error,
        BuildError::NonFiniteParticle {
            particle: 2,
            quantity: Quantity::Velocity,
            ..
        }
    ));
    assert!(
        error.to_string().contains("particle 2: initial velocity"),
        "{error}"
    );
}

#[test]
fn bad_springs_name_the_spring() {
    let error = build(|b| {
        b.spring(1, 7, 1.0);
    })
    .unwrap_err();
    assert_eq!(
        error,
        BuildError::SpringEndpointOutOfRange {
            spring: 1,
            endpoint: 7,
            particles: 2
        }
    );
    let error = build(|b| {
        b.spring(1, 1, 1.0);
    })
    .unwrap_err();
    assert_eq!(
        error,
        BuildError::SelfSpring {
            spring: 1,
            particle: 1
        }
    );
    let error = build(|b| {
        b.spring(1, 0, 5.0);
    })
    .unwrap_err();
    assert_eq!(
        error,
        BuildError::DuplicateSpring {
            spring: 1,
            first: 0,
            i: 1,
            j: 0
        }
    );
    assert_eq!(
        error.to_string(),
        "spring 1: duplicates spring 0 between particles 1 and 0"
    );
}

/// Adds something wrong to a builder.
type Spoil = fn(&mut SystemBuilder);

/// The parameter named by the error that `spoil`, adding spring 0 between
/// two particles, causes.
fn spring_parameter_error(spoil: Spoil) -> SpringParameter {
    let mut b = SystemBuilder::new();
    b.particle(1.0, [0.0; 3]);
    b.particle(1.0, [1.0, 0.0, 0.0]);
    spoil(&mut b);
    let error = b.build().unwrap_err();
    let BuildError::InvalidSpringParameter {
        spring: 0,
        parameter,
        ..
    } = error
    else {
        panic!("expected a spring-parameter error, got {error}");
    };
    assert!(
        error
            .to_string()
            .starts_with(&format!("spring 0: {parameter}")),
        "{error}"
    );
    parameter
}

#[test]
fn bad_spring_parameters_name_the_field() {
    use SpringParameter::{Damping, RestLength, Stiffness};
    let cases: [(Spoil, SpringParameter); 7] = [
        (|b| _ = b.spring(0, 1, -1.0), Stiffness),
        (|b| _ = b.spring(0, 1, f64::NAN), Stiffness),
        (|b| _ = b.spring(0, 1, f64::INFINITY), Stiffness),
        (|b| _ = b.spring(0, 1, 1.0).rest_length(-0.5), RestLength),
        (
            |b| _ = b.spring(0, 1, 1.0).rest_length(f64::NAN),
            RestLength,
        ),
        (|b| _ = b.spring(0, 1, 1.0).damping(-2.0), Damping),
        (|b| _ = b.spring(0, 1, 1.0).damping(f64::INFINITY), Damping),
    ];
    for (spoil, expected) in cases {
        assert_eq!(spring_parameter_error(spoil), expected);
    }
}

#[test]
fn bad_pins_gravity_and_air_damping_are_reported() {
    assert_eq!(
        build(|b| {
            b.pin(5);
        })
        .unwrap_err(),
        BuildError::PinOutOfRange {
            particle: 5,
            particles: 2
        }
    );
    let error = build(|b| {
        b.gravity([0.0, f64::NEG_INFINITY, 0.0]);
    })
    .unwrap_err();
    assert!(
        matches!(error, BuildError::NonFiniteGravity { .. }),
        "{error}"
    );
    for gamma in [-0.1, f64::NAN] {
        let error = build(|b| {
            b.air_damping(gamma);
        })
        .unwrap_err();
        assert!(
            matches!(error, BuildError::InvalidAirDamping { .. }),
            "{error}"
        );
    }
}

/// Every integrator, the adaptive one included.
fn every_integrator() -> Vec<Box<dyn Integrator + Send>> {
    let mut all = fixed_step_integrators();
    all.push(Box::new(DormandPrince::default()));
    all
}

#[test]
fn invalid_time_steps_are_rejected_by_every_integrator() {
    let system = Oscillator::undamped(1.0, 1.0).system().unwrap();
    for mut integrator in every_integrator() {
        for dt in [0.0, -0.01, f64::NAN, f64::INFINITY] {
            let mut state = system.initial_state();
            let error = integrator.step(&system, &mut state, dt).unwrap_err();
            assert!(
                matches!(error, StepError::InvalidTimestep { .. }),
                "{}: {error}",
                integrator.name()
            );
            assert_eq!(state.positions(), system.initial_positions());
        }
    }
}

#[test]
fn a_state_of_another_system_is_rejected_everywhere() {
    let small = Oscillator::undamped(1.0, 1.0).system().unwrap();
    let large = HangingChain::new(4, 1.0, 10.0, 1.0).system().unwrap();
    let mismatch = StepError::StateMismatch {
        state: 4,
        system: 2,
    };
    for mut integrator in every_integrator() {
        let mut state = large.initial_state();
        assert_eq!(
            integrator.step(&small, &mut state, 0.01).unwrap_err(),
            mismatch
        );
    }
    let state = large.initial_state();
    assert_eq!(small.energy(&state).unwrap_err(), mismatch);
    assert_eq!(small.dissipation_power(&state).unwrap_err(), mismatch);
    assert_eq!(small.max_strain(&state).unwrap_err(), mismatch);
    let mut state = large.initial_state();
    let mut energy = EnergyLog::default();
    let run = Simulation::new(&small, &mut Rk4::new())
        .observe(1, &mut energy)
        .run(&mut state, 0.01, 10);
    assert_eq!(run.unwrap_err(), mismatch);
    assert!(energy.samples().is_empty());
}

/// A spring so stiff that its force overflows: every step must report the
/// time and the particle instead of installing infinities.
#[test]
fn an_overflowing_step_names_time_and_particle_and_keeps_the_state() {
    let mut oscillator = Oscillator::undamped(1.0, 1e308);
    oscillator.displacement = 10.0;
    let system = oscillator.system().unwrap();
    for mut integrator in every_integrator() {
        let mut state = system.initial_state();
        let error = integrator.step(&system, &mut state, 0.5).unwrap_err();
        let name = integrator.name();
        match error {
            StepError::NonFinite { particle, time, .. } => {
                assert_eq!(particle, Oscillator::BOB, "{name}");
                assert!(time > 0.0 && time <= 1.5, "{name}: time {time}");
            }
            StepError::StepSizeUnderflow { .. } | StepError::TooManySubsteps { .. } => {
                assert_eq!(name, DormandPrince::NAME, "{name}: {error}");
            }
            other => panic!("{name}: unexpected {other}"),
        }
        assert_eq!(state.positions(), system.initial_positions(), "{name}");
        assert_eq!(state.velocities(), system.initial_velocities(), "{name}");
        assert_abs_diff_eq!(state.time(), 0.0, epsilon = 0.0);
    }
}
