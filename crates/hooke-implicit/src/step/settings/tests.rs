//! The settings' defaults, their tables of names and their keys.

use std::mem::discriminant;

use hooke_core::{CompressedSprings, Integrator, Named, Parameter};

use super::ImplicitSettings;
use super::keys::{Key, KeyError, KeyProblem, KeyValue};
use crate::{
    AmgRenewal, ContactLimit, ErrorControl, Implicit, LinearSolver, Minimizer, PcgSettings, Scheme,
    Supernodes, WeakSprings,
};

/// Every default is the one the fields' docs state, read from the one
/// `Default`, and the integrators' constructors start from it.
#[test]
fn each_default_is_the_one_the_docs_state() {
    let d = ImplicitSettings::default();
    assert_eq!(d.scheme, Scheme::BackwardEuler);
    assert_eq!(d.solver, LinearSolver::Auto);
    assert_eq!(d.minimizer, Minimizer::Newton);
    assert_eq!(d.newton_iterations, 100);
    assert_eq!(d.newton_tolerance.to_bits(), 5e-3_f64.to_bits());
    assert!(d.inexact_newton);
    assert_eq!(d.amg_renewal, AmgRenewal::EverySolve);
    assert_eq!(d.weak_springs, None);
    assert_eq!(d.supernodes, Supernodes::Blocks);
    assert_eq!(d.max_halvings, 10);
    assert!(!d.strict);
    assert_eq!(d.compressed, CompressedSprings::Clamped);
    assert_eq!(d.error_control, None);
    assert_eq!(d.contact_limit, ContactLimit::Global);
    assert_eq!(d.validate(), Ok(()));
    assert_eq!(*Implicit::backward_euler().settings(), d);
    let bdf2 = ImplicitSettings {
        scheme: Scheme::Bdf2,
        ..d
    };
    assert_eq!(*Implicit::bdf2().settings(), bdf2);
    assert_eq!(*Implicit::new(Scheme::Bdf2).settings(), bdf2);
    assert_eq!(*Implicit::with_settings(bdf2).unwrap().settings(), bdf2);
    // The solver's iterations and the L-BFGS history by their names.
    assert_eq!(
        LinearSolver::Pcg(PcgSettings::default()).pcg(),
        Some(PcgSettings::DEFAULT)
    );
    assert_eq!(
        Minimizer::from_name("quasi-newton"),
        Some(Minimizer::quasi_newton())
    );
}

/// `value`'s table: every entry's name reads back as that entry and the
/// entry writes that name; the names are distinct; and every one of
/// `variants` has an entry.
fn round_trips<T: Named + PartialEq + std::fmt::Debug>(variants: &[T]) {
    let names: Vec<_> = T::names().collect();
    for (i, &(value, name)) in T::TABLE.iter().enumerate() {
        assert_eq!(value.name(), name);
        assert_eq!(T::from_name(name), Some(value), "{name}");
        assert!(!names[..i].contains(&name), "{name} twice");
    }
    assert_eq!(T::from_name("none of these"), None);
    for variant in variants {
        let name = variant.name();
        let entry = T::from_name(name).unwrap_or_else(|| panic!("{variant:?} has no name"));
        assert_eq!(discriminant(&entry), discriminant(variant), "{name}");
    }
}

#[test]
fn every_name_round_trips_through_its_table() {
    let pcg = PcgSettings::new(1e-3, 7).unwrap();
    round_trips(&[Scheme::BackwardEuler, Scheme::Bdf2]);
    round_trips(&[
        LinearSolver::Auto,
        LinearSolver::Cholesky,
        LinearSolver::Pcg(pcg),
        LinearSolver::Amg(pcg),
        LinearSolver::LaggedCholesky(pcg),
    ]);
    round_trips(&[
        Minimizer::Newton,
        Minimizer::QuasiNewton {
            history: 2,
            carried: 0,
        },
        Minimizer::Linearized,
    ]);
    round_trips(&[AmgRenewal::EverySolve, AmgRenewal::SmootherOnly]);
    round_trips(&[WeakSprings::Kept, WeakSprings::Routed]);
    round_trips(&[Supernodes::Blocks, Supernodes::Faer]);
    round_trips(&[CompressedSprings::Clamped, CompressedSprings::Exact]);
    round_trips(&[ContactLimit::Particles, ContactLimit::Global]);
    let keys: Vec<Key> = Key::TABLE.iter().map(|&(key, _)| key).collect();
    round_trips(&keys);
    // The integrator's name is its scheme's.
    assert_eq!(Implicit::bdf2().name(), Scheme::Bdf2.name());
    assert_eq!(
        LinearSolver::iterative_names().collect::<Vec<_>>(),
        ["pcg", "amg", "lagged-cholesky"]
    );
}

/// Settings that between them set every field away from its default.
fn unusual() -> [ImplicitSettings; 3] {
    let d = ImplicitSettings::default();
    let pcg = PcgSettings::new(1e-4, 50).unwrap();
    [
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
            contact_limit: ContactLimit::Particles,
            ..d
        },
        ImplicitSettings {
            solver: LinearSolver::Amg(pcg),
            inexact_newton: false,
            amg_renewal: AmgRenewal::SmootherOnly,
            ..d
        },
        ImplicitSettings {
            solver: LinearSolver::LaggedCholesky(pcg),
            minimizer: Minimizer::QuasiNewton {
                history: 9,
                carried: 4,
            },
            weak_springs: Some(WeakSprings::Kept),
            ..d
        },
    ]
}

/// The keys of settings read back as the same settings (with
/// `weak_springs` as used where it applies), and between them the settings
/// above write every key.
#[test]
fn settings_written_as_keys_read_back_as_the_same_settings() {
    let mut written = Vec::new();
    for settings in unusual().into_iter().chain([ImplicitSettings::default()]) {
        let keys = settings.keys();
        written.extend(keys.iter().map(|&(key, _)| key));
        let read = ImplicitSettings::from_keys(keys.iter().copied()).unwrap();
        let applies = keys.iter().any(|&(key, _)| key == "weak_springs");
        let used = ImplicitSettings {
            weak_springs: applies.then(|| settings.weak_springs_used()),
            ..settings
        };
        assert_eq!(read, used);
    }
    for key in Key::names() {
        assert!(written.contains(&key), "{key} is never written");
    }
    // The scene file's spellings: a name quoted, numbers as TOML has them.
    let shown: Vec<String> = unusual()[0]
        .keys()
        .iter()
        .map(|(key, value)| format!("{key} = {value}"))
        .collect();
    for line in [
        "solver = \"cholesky\"",
        "newton_tolerance = 1e-6",
        "strict = true",
    ] {
        assert!(shown.iter().any(|s| s == line), "{line} in {shown:?}");
    }
}

/// `keys` as settings, or the message of their error.
fn read(keys: &[(&str, KeyValue<'_>)]) -> Result<ImplicitSettings, String> {
    ImplicitSettings::from_keys(keys.iter().copied()).map_err(|e| e.to_string())
}

#[test]
fn keys_that_do_not_apply_or_do_not_fit_are_errors_naming_them() {
    use KeyValue::{Count, Name, Number, Switch};
    for (keys, named, says) in [
        (
            vec![("solvers", Name("pcg"))],
            "solvers",
            "one of \"scheme\", \"solver\"",
        ),
        (
            vec![("solver", Name("multigrid"))],
            "solver",
            "\"auto\", \"cholesky\"",
        ),
        (
            vec![("solver", Count(3))],
            "solver",
            "got 3, expected \"auto\"",
        ),
        (
            vec![("step", Name("lbfgs"))],
            "step",
            "(or \"converged\" for \"newton\")",
        ),
        (
            vec![("tolerance", Number(1e-3))],
            "tolerance",
            "with solver \"auto\"",
        ),
        (
            vec![("history", Count(2))],
            "history",
            "only with step = \"quasi-newton\"",
        ),
        (
            vec![("solver", Name("amg")), ("weak_springs", Name("routed"))],
            "weak_springs",
            "only with solver \"auto\" or \"cholesky\", or with step = \"quasi-newton\"",
        ),
        (
            vec![("step", Name("quasi-newton")), ("supernodes", Name("faer"))],
            "supernodes",
            "step = \"newton\" or \"linearized\"",
        ),
        (
            vec![
                ("solver", Name("pcg")),
                ("amg_renewal", Name("smoother-only")),
            ],
            "amg_renewal",
            "only with solver \"auto\" or \"amg\" and step",
        ),
        (
            vec![
                ("step", Name("linearized")),
                ("inexact_newton", Switch(false)),
            ],
            "inexact_newton",
            "only with step = \"newton\"",
        ),
        (
            vec![
                ("step", Name("quasi-newton")),
                ("compressed_springs", Name("exact")),
            ],
            "compressed_springs",
            "with step = \"quasi-newton\"",
        ),
        (
            vec![
                ("step", Name("quasi-newton")),
                ("history", Count(2)),
                ("carried_pairs", Count(3)),
            ],
            "carried_pairs",
            "got 3 with history = 2, expected at most `history`",
        ),
        (
            vec![("strict", Count(1))],
            "strict",
            "expected true or false",
        ),
        (
            vec![("max_halvings", Count(1 << 40))],
            "max_halvings",
            "at most 4294967295",
        ),
        (
            vec![("newton_iterations", Number(2.0))],
            "newton_iterations",
            "a whole number",
        ),
    ] {
        let message = read(&keys).unwrap_err();
        assert!(message.starts_with(&format!("{named}: ")), "{message}");
        assert!(message.contains(says), "{message}");
    }
}

/// A value out of range is the integrator's [`ParameterError`] at the key
/// that set it.
#[test]
fn values_out_of_range_are_the_settings_range_errors_at_their_keys() {
    use KeyValue::{Count, Name, Number};
    for (keys, key, parameter) in [
        (
            vec![("newton_iterations", Count(0))],
            "newton_iterations",
            Parameter::NewtonIterations,
        ),
        (
            vec![("newton_tolerance", Number(-1.0))],
            "newton_tolerance",
            Parameter::NewtonTolerance,
        ),
        (
            vec![("solver", Name("pcg")), ("tolerance", Number(2.0))],
            "tolerance",
            Parameter::Tolerance,
        ),
        (
            vec![("solver", Name("amg")), ("max_iterations", Count(0))],
            "max_iterations",
            Parameter::MaxIterations,
        ),
        (
            vec![("rtol", Number(0.0))],
            "rtol",
            Parameter::RelativeTolerance,
        ),
        (
            vec![("atol", Number(-1.0))],
            "atol",
            Parameter::AbsoluteTolerance,
        ),
    ] {
        let error = ImplicitSettings::from_keys(keys).unwrap_err();
        let KeyError {
            key: at,
            problem: KeyProblem::OutOfRange(range),
        } = error
        else {
            panic!("{key}: {error}")
        };
        assert_eq!((at.as_str(), range.parameter), (key, parameter));
    }
    let error = Implicit::with_settings(ImplicitSettings {
        newton_tolerance: f64::NAN,
        scheme: Scheme::Bdf2,
        ..ImplicitSettings::default()
    })
    .unwrap_err();
    assert_eq!(
        (error.integrator, error.parameter),
        ("bdf2", Parameter::NewtonTolerance)
    );
}

#[test]
fn keys_read_onto_the_defaults_with_the_format_s_conventions() {
    use KeyValue::{Count, Name, Number};
    let d = ImplicitSettings::default();
    assert_eq!(read(&[]), Ok(d));
    assert_eq!(read(&[("step", Name("converged"))]), Ok(d));
    // A whole number is a number; a history below the carried default
    // carries all of it.
    assert_eq!(
        read(&[("newton_tolerance", Count(1))]).map(|s| s.newton_tolerance.to_bits()),
        Ok(1.0_f64.to_bits())
    );
    assert_eq!(
        read(&[("step", Name("quasi-newton")), ("history", Count(0))]).map(|s| s.minimizer),
        Ok(Minimizer::QuasiNewton {
            history: 0,
            carried: 0
        })
    );
    // Either tolerance turns error control on, the other at its default.
    let control = |keys: &[(&str, KeyValue<'_>)]| {
        read(keys).map(|s| s.error_control.map(|c| (c.relative(), c.absolute())))
    };
    assert_eq!(
        control(&[("atol", Number(1e-8))]),
        Ok(Some((ErrorControl::RELATIVE, 1e-8)))
    );
    assert_eq!(
        control(&[("rtol", Number(1e-4))]),
        Ok(Some((1e-4, ErrorControl::ABSOLUTE)))
    );
}

/// The builders set the fields of the settings and nothing else.
#[test]
fn the_builders_set_the_settings_fields() {
    let control = ErrorControl::new(1e-3, 1e-7).unwrap();
    let built = Implicit::bdf2()
        .with_solver(LinearSolver::Cholesky)
        .with_newton(8, 1e-6)
        .unwrap()
        .with_inexact_newton(false)
        .with_amg_renewal(AmgRenewal::SmootherOnly)
        .with_weak_springs(WeakSprings::Routed)
        .with_supernodes(Supernodes::Faer)
        .with_max_halvings(2)
        .strict(true)
        .with_compressed_springs(CompressedSprings::Exact)
        .with_error_control(control)
        .with_contact_limit(ContactLimit::Particles)
        .linearized();
    let expected = ImplicitSettings {
        scheme: Scheme::Bdf2,
        solver: LinearSolver::Cholesky,
        minimizer: Minimizer::Linearized,
        newton_iterations: 8,
        newton_tolerance: 1e-6,
        inexact_newton: false,
        amg_renewal: AmgRenewal::SmootherOnly,
        weak_springs: Some(WeakSprings::Routed),
        supernodes: Supernodes::Faer,
        max_halvings: 2,
        strict: true,
        compressed: CompressedSprings::Exact,
        error_control: Some(control),
        contact_limit: ContactLimit::Particles,
    };
    assert_eq!(*built.settings(), expected);
    // A Newton setting out of range is the settings' range error.
    let error = Implicit::backward_euler().with_newton(0, 1e-3).unwrap_err();
    assert_eq!(error.parameter, Parameter::NewtonIterations);
}
