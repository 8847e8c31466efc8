//! The `[integrator]` table of scene files: every method by its name with
//! the integrators' own defaults, and every implicit setting by its key.

mod common;

use hooke_core::reference::Sheet;
use hooke_core::{CompressedSprings, Integrator, Named};
use hooke_explicit::DormandPrince;
use hooke_implicit::{
    AmgRenewal, ContactLimit, ErrorControl, Implicit, ImplicitSettings, LinearSolver, Minimizer,
    PcgSettings, Scheme, Supernodes, WeakSprings,
};
use hooke_scenes::{IntegratorSpec, Method};

use common::{CLOTH, parse};

#[test]
fn defaults_are_converged_backward_euler_with_the_automatic_solver() {
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
    let IntegratorSpec::Implicit(settings) = parse(&text).unwrap().integrator else {
        panic!("backward Euler is the default method");
    };
    assert_eq!(settings.solver, LinearSolver::Pcg(defaults));
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
        IntegratorSpec::Implicit(settings) => settings.solver,
        other => panic!("{other:?}"),
    };
    assert_eq!(solver(""), LinearSolver::Auto);
    assert_eq!(solver("solver = \"auto\""), LinearSolver::Auto);
    assert_eq!(
        solver("solver = \"amg\"\ntolerance = 1e-8"),
        LinearSolver::Amg(PcgSettings::new(1e-8, PcgSettings::default().max_iterations()).unwrap())
    );
    assert!(matches!(
        solver("solver = \"lagged-cholesky\""),
        LinearSolver::LaggedCholesky(_)
    ));
    let message = spec("solver = \"multigrid\"").unwrap_err().to_string();
    for name in LinearSolver::names() {
        assert!(message.contains(&format!("\"{name}\"")), "{message}");
    }
    // Every name of the table reads back as its solver, PCG's keys going
    // to the iterative ones and refused by the others.
    let pcg = PcgSettings::new(1e-7, 30).unwrap();
    for name in LinearSolver::names() {
        let keys = format!("solver = \"{name}\"\ntolerance = 1e-7\nmax_iterations = 30");
        match LinearSolver::from_name(name) {
            Some(expected) if expected.pcg().is_some() => {
                assert_eq!(solver(&keys), expected.with_pcg(pcg));
            }
            Some(expected) => {
                assert_eq!(solver(&format!("solver = \"{name}\"")), expected);
                let message = spec(&keys).unwrap_err().to_string();
                for iterative in LinearSolver::iterative_names() {
                    assert!(message.contains(&format!("\"{iterative}\"")), "{message}");
                }
            }
            None => panic!("{name} is not in the table"),
        }
    }
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

#[test]
fn rtol_atol_strict_and_max_halvings_control_the_implicit_substeps() {
    let spec = |keys: &str| {
        let text = format!("[integrator]\nmethod = \"bdf2\"\n{keys}\n{CLOTH}");
        match parse(&text).unwrap().integrator {
            IntegratorSpec::Implicit(s) => (s.max_halvings, s.strict, s.error_control),
            other => panic!("bdf2 is implicit, got {other:?}"),
        }
    };
    let defaults = spec("");
    assert_eq!(defaults, (ImplicitSettings::MAX_HALVINGS, false, None));
    assert_eq!(spec("max_halvings = 3\nstrict = true"), (3, true, None));
    let controlled = |keys| spec(keys).2.map(|c| (c.relative(), c.absolute()));
    assert_eq!(
        controlled("rtol = 1e-4"),
        Some((1e-4, ErrorControl::ABSOLUTE))
    );
    assert_eq!(
        controlled("atol = 1e-8"),
        Some((ErrorControl::RELATIVE, 1e-8))
    );
    assert_eq!(controlled("rtol = 0.01\natol = 0.0"), Some((0.01, 0.0)));
    // The built integrator is the one the keys describe.
    let text = format!("[integrator]\nmethod = \"bdf2\"\nrtol = 1e-4\n{CLOTH}");
    assert_eq!(
        parse(&text).unwrap().integrator.build().unwrap().name(),
        "bdf2"
    );
}

#[test]
fn implicit_step_keys_out_of_range_or_misplaced_are_errors_naming_the_key() {
    for (keys, named) in [
        ("method = \"bdf2\"\nrtol = 2.0", "integrator.rtol"),
        (
            "method = \"backward-euler\"\natol = -1e-3",
            "integrator.atol",
        ),
        ("method = \"rk4\"\nstrict = true", "integrator.strict"),
        ("method = \"rk4\"\nrtol = 1e-3", "integrator.rtol"),
        (
            "method = \"dormand-prince\"\nmax_halvings = 2",
            "integrator.max_halvings",
        ),
        ("method = \"bdf2\"\nmax_halvings = -1", "max_halvings"),
        ("step = \"lbfgs\"", "integrator.step"),
        ("history = 3", "integrator.history"),
        ("step = \"newton\"\nhistory = 3", "integrator.history"),
        ("method = \"rk4\"\nhistory = 3", "integrator.history"),
        ("carried_pairs = 1", "integrator.carried_pairs"),
        (
            "step = \"quasi-newton\"\nhistory = 2\ncarried_pairs = 3",
            "integrator.carried_pairs",
        ),
    ] {
        let error = parse(&format!("[integrator]\n{keys}\n{CLOTH}")).unwrap_err();
        let message = error.to_string();
        assert!(message.contains(named), "{keys}: {message}");
    }
}

#[test]
fn the_step_key_names_the_minimiser_and_history_its_memory() {
    for (keys, expected) in [
        ("", Minimizer::Newton),
        ("step = \"converged\"", Minimizer::Newton),
        ("step = \"newton\"", Minimizer::Newton),
        ("step = \"linearized\"", Minimizer::Linearized),
        ("step = \"quasi-newton\"", Minimizer::quasi_newton()),
        (
            "step = \"quasi-newton\"\nhistory = 12",
            Minimizer::QuasiNewton {
                history: 12,
                carried: Minimizer::CARRIED,
            },
        ),
        (
            "step = \"quasi-newton\"\nhistory = 12\ncarried_pairs = 0",
            Minimizer::QuasiNewton {
                history: 12,
                carried: 0,
            },
        ),
        (
            "step = \"quasi-newton\"\nhistory = 0",
            Minimizer::QuasiNewton {
                history: 0,
                carried: 0,
            },
        ),
    ] {
        let text = format!("[integrator]\n{keys}\n{CLOTH}");
        let spec = parse(&text).unwrap().integrator;
        let IntegratorSpec::Implicit(settings) = spec else {
            panic!("{keys}: {spec:?}");
        };
        assert_eq!(settings.minimizer, expected, "{keys}");
    }
}

#[test]
fn weak_springs_are_read_for_the_factorization_and_checked() {
    let weak = |text: &str| match parse(&format!("[integrator]\n{text}\n{CLOTH}"))
        .map(|scene| scene.integrator)
    {
        Ok(IntegratorSpec::Implicit(settings)) => Ok(settings.weak_springs),
        Ok(other) => panic!("{other:?}"),
        Err(e) => Err(e.to_string()),
    };
    assert_eq!(weak(""), Ok(None));
    assert_eq!(
        weak("weak_springs = \"routed\""),
        Ok(Some(WeakSprings::Routed))
    );
    assert_eq!(
        weak("solver = \"cholesky\"\nweak_springs = \"kept\""),
        Ok(Some(WeakSprings::Kept))
    );
    // The quasi-Newton step's H₀ is factorized or a hierarchy's, whatever
    // the solver.
    assert_eq!(
        weak("step = \"quasi-newton\"\nsolver = \"amg\"\nweak_springs = \"kept\""),
        Ok(Some(WeakSprings::Kept))
    );
    // A name it does not know: the error names the key and lists both.
    let message = weak("weak_springs = \"bent\"").unwrap_err();
    assert!(message.contains("integrator.weak_springs"), "{message}");
    for name in WeakSprings::names() {
        assert!(message.contains(&format!("\"{name}\"")), "{message}");
    }
    // Only a factorization has weak springs to route in Newton's matrix.
    let message = weak("solver = \"amg\"\nweak_springs = \"routed\"").unwrap_err();
    assert!(message.contains("integrator.weak_springs"), "{message}");
    // Nor does an explicit method take it.
    let message = weak("method = \"rk4\"\nweak_springs = \"routed\"").unwrap_err();
    assert!(message.contains("weak_springs"), "{message}");
}

/// Two tables that between them set every implicit setting away from its
/// default, with the settings each must give.
fn every_setting() -> [(&'static str, ImplicitSettings); 2] {
    let d = ImplicitSettings::default();
    [
        (
            r#"method = "bdf2"
            solver = "cholesky"
            weak_springs = "routed"
            supernodes = "faer"
            step = "linearized"
            newton_iterations = 7
            newton_tolerance = 1e-6
            max_halvings = 3
            strict = true
            compressed_springs = "exact"
            rtol = 1e-2
            atol = 0.0"#,
            ImplicitSettings {
                scheme: Scheme::Bdf2,
                solver: LinearSolver::Cholesky,
                minimizer: Minimizer::Linearized,
                newton_iterations: 7,
                newton_tolerance: 1e-6,
                weak_springs: Some(WeakSprings::Routed),
                supernodes: Supernodes::Faer,
                max_halvings: 3,
                strict: true,
                compressed: CompressedSprings::Exact,
                error_control: Some(ErrorControl::new(1e-2, 0.0).unwrap()),
                ..d
            },
        ),
        (
            r#"solver = "amg"
            tolerance = 1e-4
            max_iterations = 50
            inexact_newton = false
            amg_renewal = "smoother-only""#,
            ImplicitSettings {
                solver: LinearSolver::Amg(PcgSettings::new(1e-4, 50).unwrap()),
                inexact_newton: false,
                amg_renewal: AmgRenewal::SmootherOnly,
                ..d
            },
        ),
    ]
}

/// A scene file sets every field of the implicit settings, the spec
/// carries them to the integrator it builds (which steps as one built
/// from the same settings does, and unlike one with the defaults), and the
/// settings written as keys read back from a scene file as themselves.
#[test]
fn a_scene_file_sets_every_implicit_setting_and_the_spec_carries_it() {
    let system = Sheet::new(5).system().unwrap();
    let run = |integrator: &mut dyn Integrator| {
        let mut state = system.initial_state();
        for _ in 0..3 {
            integrator.step(&system, &mut state, 0.02).unwrap();
        }
        state.positions().to_vec()
    };
    for (keys, expected) in every_setting() {
        let spec = parse(&format!("[integrator]\n{keys}\n{CLOTH}"))
            .unwrap()
            .integrator;
        assert_eq!(spec, IntegratorSpec::Implicit(expected), "{keys}");
        let built = run(&mut *spec.build().unwrap());
        assert_eq!(built, run(&mut Implicit::with_settings(expected).unwrap()));
        assert_ne!(built, run(&mut Implicit::new(expected.scheme)));
        // Written as keys, the settings are a table that reads back as them.
        let table: Vec<String> = expected
            .keys()
            .into_iter()
            .map(|(key, value)| match key {
                "scheme" => format!("method = {value}"),
                _ => format!("{key} = {value}"),
            })
            .collect();
        let text = format!("[integrator]\n{}\n{CLOTH}", table.join("\n"));
        assert_eq!(parse(&text).unwrap().integrator, spec, "{text}");
    }
}

/// The keys added with the settings type are read by their tables' names,
/// and each is refused where it does not apply, naming the key.
#[test]
fn the_factorization_multigrid_and_newton_keys_are_read_and_checked() {
    let settings = |text: &str| match parse(&format!("[integrator]\n{text}\n{CLOTH}")) {
        Ok(scene) => match scene.integrator {
            IntegratorSpec::Implicit(settings) => Ok(settings),
            other => panic!("{other:?}"),
        },
        Err(e) => Err(e.to_string()),
    };
    for name in Supernodes::names() {
        let read = settings(&format!("supernodes = \"{name}\"")).unwrap();
        assert_eq!(read.supernodes.name(), name);
    }
    for name in CompressedSprings::names() {
        let read = settings(&format!("compressed_springs = \"{name}\"")).unwrap();
        assert_eq!(read.compressed.name(), name);
    }
    for name in ContactLimit::names() {
        let read = settings(&format!("contact_limit = \"{name}\"")).unwrap();
        assert_eq!(read.contact_limit.name(), name);
    }
    for name in AmgRenewal::names() {
        let read = settings(&format!("solver = \"amg\"\namg_renewal = \"{name}\"")).unwrap();
        assert_eq!(read.amg_renewal.name(), name);
    }
    for (text, key) in [
        ("supernodes = \"simplicial\"", "integrator.supernodes"),
        (
            "solver = \"pcg\"\nsupernodes = \"faer\"",
            "integrator.supernodes",
        ),
        (
            "solver = \"cholesky\"\namg_renewal = \"smoother-only\"",
            "integrator.amg_renewal",
        ),
        (
            "step = \"linearized\"\ninexact_newton = false",
            "integrator.inexact_newton",
        ),
        (
            "step = \"quasi-newton\"\ncompressed_springs = \"exact\"",
            "integrator.compressed_springs",
        ),
        (
            "method = \"rk4\"\ninexact_newton = true",
            "integrator.inexact_newton",
        ),
        (
            "method = \"fast-mass-spring\"\nsupernodes = \"faer\"",
            "integrator.supernodes",
        ),
    ] {
        let message = settings(text).unwrap_err();
        assert!(message.contains(key), "{text}: {message}");
    }
}
