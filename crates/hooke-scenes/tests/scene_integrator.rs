//! The `[integrator]` table of scene files: every method by its name with
//! the integrators' own defaults.

mod common;

use hooke_explicit::DormandPrince;
use hooke_implicit::PcgSettings;
use hooke_scenes::{IntegratorSpec, Method, SolverSpec};

use common::{CLOTH, parse};

#[test]
fn defaults_are_backward_euler_cholesky_one_newton_iteration() {
    let scene = parse(CLOTH).unwrap();
    assert_eq!(scene.integrator, IntegratorSpec::backward_euler());
    assert!((scene.timing.frame_rate - 60.0).abs() < 1e-12);
    assert_eq!(scene.name, "test");
    assert_eq!(scene.system.particle_count(), 12);
}

#[test]
fn every_method_is_named_as_its_integrator_is_with_the_integrators_defaults() {
    for method in Method::ALL {
        let text = format!("[integrator]\nmethod = \"{method}\"\n{CLOTH}");
        let spec = parse(&text).unwrap().integrator;
        assert_eq!(spec, IntegratorSpec::new(method));
        assert_eq!(spec.method(), method);
        assert_eq!(spec.build().unwrap().name(), method.name());
    }
    let text = format!("[integrator]\nmethod = \"dormand-prince\"\nrtol = 1e-5\n{CLOTH}");
    assert_eq!(
        parse(&text).unwrap().integrator,
        IntegratorSpec::Adaptive {
            rtol: 1e-5,
            atol: DormandPrince::ATOL,
        }
    );
    let text = format!("[integrator]\nsolver = \"pcg\"\n{CLOTH}");
    let defaults = PcgSettings::default();
    let IntegratorSpec::Implicit { solver, .. } = parse(&text).unwrap().integrator else {
        panic!("backward Euler is the default method");
    };
    assert_eq!(
        solver,
        SolverSpec::Pcg {
            tolerance: defaults.tolerance(),
            max_iterations: defaults.max_iterations(),
        }
    );
}

#[test]
fn an_unknown_method_is_an_error_listing_every_method() {
    let error = parse(&format!("[integrator]\nmethod = \"dopri5\"\n{CLOTH}")).unwrap_err();
    let message = error.to_string();
    for method in Method::ALL {
        assert!(message.contains(&format!("\"{method}\"")), "{message}");
    }
}

#[test]
fn solvers_and_the_fast_mass_spring_iterations_are_read_and_checked() {
    let spec = |text: &str| parse(&format!("[integrator]\n{text}\n{CLOTH}"));
    let solver = |text: &str| match spec(text).unwrap().integrator {
        IntegratorSpec::Implicit { solver, .. } => solver,
        other => panic!("{other:?}"),
    };
    assert_eq!(solver(""), SolverSpec::Auto);
    assert_eq!(solver("solver = \"auto\""), SolverSpec::Auto);
    assert_eq!(
        solver("solver = \"amg\"\ntolerance = 1e-8"),
        SolverSpec::Amg {
            tolerance: 1e-8,
            max_iterations: PcgSettings::default().max_iterations(),
        }
    );
    assert!(matches!(
        solver("solver = \"lagged-cholesky\""),
        SolverSpec::LaggedCholesky { .. }
    ));
    let message = spec("solver = \"multigrid\"").unwrap_err().to_string();
    assert!(message.contains("\"amg\""), "{message}");
    assert_eq!(
        spec("method = \"fast-mass-spring\"\niterations = 3")
            .unwrap()
            .integrator,
        IntegratorSpec::FastMassSpring { iterations: 3 }
    );
    for wrong in [
        "method = \"fast-mass-spring\"\niterations = 0",
        "method = \"rk4\"\niterations = 3",
        "method = \"fast-mass-spring\"\nsolver = \"amg\"",
    ] {
        assert!(spec(wrong).is_err(), "{wrong}");
    }
}
