//! The accuracy measurement checked against theory: orders of convergence
//! on the damped oscillator, its closed form, the numerical reference's
//! error estimate, and the implicit step variants' distance from the
//! converged step.

use std::ops::ControlFlow;

use hooke_core::{ObserveFn, Simulation, State, StepInfo, System, Vec3};
use hooke_implicit::LinearSolver;
use hooke_lab::accuracy::{AxialOscillator, ReferenceChoice, ReferenceKind, StepVariant};
use hooke_lab::{AccuracyOptions, LabError, Method, accuracy};
use hooke_scenes::{ExplicitMethod, builtin};

#[test]
fn every_fixed_step_method_converges_at_its_expected_order_on_the_damped_oscillator() {
    let scene = builtin::load("damped-oscillator").unwrap();
    let mut options = AccuracyOptions::for_scene(&scene);
    // The fast mass-spring method leaves spring damping out, so it
    // converges to the undamped motion, not this one.
    options
        .methods
        .retain(|&m| m.is_fixed_step() && m != Method::FastMassSpring);
    options.repeat = 1;
    let report = accuracy(&scene, &options, &|_, _| {}).unwrap();
    assert_eq!(report.reference.kind, ReferenceKind::Analytic);
    assert_eq!(report.orders.len(), 12);
    for order in &report.orders {
        let observed = order.observed_order.unwrap_or(f64::NAN);
        assert!(
            (observed - order.expected_order).abs() <= 0.15,
            "{}: observed {observed}, expected {} (steps {:?})",
            order.integrator,
            order.expected_order,
            order.steps_fitted
        );
        assert!(order.steps_fitted.len() >= 3);
    }
    assert_eq!(report.runs.len(), 12 * options.dts.len());
}

#[test]
fn the_closed_form_is_the_scene_files_motion_and_solves_the_equation() {
    // The scene's own comment: m = k = 1, c = 0.2, g = 2 along the rope,
    // a zero-length spring,
    // y(t) = −2 + e^(−ζt)(cos ω_d t + ζ/√(1−ζ²) sin ω_d t), ζ = 0.1.
    let scene = builtin::load("damped-oscillator").unwrap();
    let closed = AxialOscillator::of(&scene.system).unwrap();
    let zeta: f64 = 0.1;
    let wd = (1.0 - zeta * zeta).sqrt();
    let y = |t: f64| closed.bob_position(t).y;
    for k in 0..=60 {
        let t = 0.5 * f64::from(k);
        let expected = -2.0 + (-zeta * t).exp() * ((wd * t).cos() + zeta / wd * (wd * t).sin());
        assert!((y(t) - expected).abs() < 1e-12, "t = {t}");
        let p = closed.bob_position(t);
        assert!(p.x.abs() < 1e-15 && p.z.abs() < 1e-15);
        // m l'' = −k l − c l' + m g along the rope (L = 0), with l = −y.
        if t > 0.0 {
            let h = 1e-4;
            let l = |t: f64| -y(t);
            let rate = (l(t + h) - l(t - h)) / (2.0 * h);
            let accel = (l(t + h) - 2.0 * l(t) + l(t - h)) / (h * h);
            let residual = accel - (-l(t) - 0.2 * rate + 2.0);
            assert!(residual.abs() < 1e-5, "t = {t}: residual {residual}");
        }
    }
    assert!(AxialOscillator::of(&builtin::load("stiff-cloth").unwrap().system).is_none());
}

#[test]
fn the_richardson_estimate_is_within_a_factor_two_of_the_references_true_error() {
    let scene = builtin::load("damped-oscillator").unwrap();
    let mut options = AccuracyOptions::for_scene(&scene);
    options.methods = vec![Method::Explicit(ExplicitMethod::VelocityVerlet)];
    options.dts = vec![0.01];
    options.repeat = 1;
    options.reference = ReferenceChoice::Numerical;
    options.reference_dt = Some(0.05);
    let report = accuracy(&scene, &options, &|_, _| {}).unwrap();
    let reference = &report.reference;
    assert_eq!(reference.kind, ReferenceKind::Numerical);
    assert_eq!(reference.method, "rk4");
    let h = reference.dt.unwrap();
    assert!(h <= 0.05 && h > 0.045);
    let observed = reference.observed_order.unwrap();
    assert!((observed - 4.0).abs() <= 0.15, "reference order {observed}");
    assert!(reference.converged);

    // The reference run's true error, against the closed form, at the
    // same checkpoints.
    let closed = AxialOscillator::of(&scene.system).unwrap();
    let interval = options.duration / options.frames as f64;
    let per_frame = (interval / h).round() as usize;
    let mut integrator = options
        .settings
        .build(Method::Explicit(ExplicitMethod::Rk4), None)
        .unwrap();
    let mut true_error = 0.0_f64;
    let mut state = scene.system.initial_state();
    let mut compare = ObserveFn(|_: &System, state: &State, step: &StepInfo| {
        let t = interval * (step.index / per_frame) as f64;
        let bob: Vec3 = state.positions()[closed.bob];
        true_error = true_error.max((bob - closed.bob_position(t)).norm());
        ControlFlow::Continue(())
    });
    let run = Simulation::new(&scene.system, &mut integrator)
        .observe(per_frame, &mut compare)
        .run_to_end(&mut state, h, per_frame * options.frames);
    assert!(run.failure().is_none());
    let ratio = reference.estimated_error / true_error;
    assert!(
        (0.5..=2.0).contains(&ratio),
        "estimate {} against true error {true_error}",
        reference.estimated_error
    );
}

/// A change that makes options invalid.
type Spoil = fn(&mut AccuracyOptions);

#[test]
fn bad_options_are_errors_naming_the_option() {
    let scene = builtin::load("damped-oscillator").unwrap();
    let base = AccuracyOptions::for_scene(&scene);
    let cases: [(&str, Spoil); 9] = [
        ("frames", |o| o.frames = 0),
        ("repeat", |o| o.repeat = 0),
        ("dt", |o| o.dts[3] = -1e-3),
        ("tolerances", |o| o.tolerances.clear()),
        ("tolerance", |o| o.tolerances[0] = f64::NAN),
        ("duration", |o| o.duration = f64::INFINITY),
        ("reference dt", |o| o.reference_dt = Some(0.0)),
        ("variant steps", |o| {
            o.variants = vec![StepVariant::Linearized];
            o.variant_dts.clear();
        }),
        ("variant dt", |o| o.variant_dts = vec![f64::NAN]),
    ];
    for (option, spoil) in cases {
        let mut options = base.clone();
        spoil(&mut options);
        match accuracy(&scene, &options, &|_, _| {}) {
            Err(LabError::Invalid { name, .. }) => assert_eq!(name, option),
            other => panic!("{option}: {other:?}"),
        }
    }
    let mut options = base;
    options.methods.clear();
    let error = accuracy(&scene, &options, &|_, _| {}).unwrap_err();
    assert!(error.to_string().starts_with("methods"), "{error}");
}

/// Backward Euler's step carried out in other ways on the swinging rope
/// (a scripted pin, 1 s at the scene's step), each compared with the same
/// step converged to 10⁻⁹: the variant that is that converged step
/// (Newton to 10⁻⁹ with Cholesky) lies at distance zero; Newton's distance
/// shrinks with its tolerance; the fast mass-spring method, whose fixed
/// point is backward Euler's step, comes closer with more iterations; the
/// linearised step takes one Newton iteration.
#[test]
fn step_variants_approach_the_converged_step_as_they_converge() {
    let scene = builtin::load("swinging-rope").unwrap();
    let mut options = AccuracyOptions::for_scene(&scene);
    options.methods = vec![Method::BackwardEuler];
    options.dts = vec![scene.timing.dt];
    options.duration = 1.0;
    options.repeat = 1;
    options.settings.implicit.solver = LinearSolver::Cholesky;
    options.variants = vec![
        StepVariant::Newton(1e-9),
        StepVariant::Newton(1e-2),
        StepVariant::Newton(1e-6),
        StepVariant::FastMassSpring(10),
        StepVariant::FastMassSpring(100),
        StepVariant::FastMassSpring(1000),
        StepVariant::Linearized,
    ];
    let report = accuracy(&scene, &options, &|_, _| {}).unwrap();
    assert_eq!(report.converged.len(), 1);
    assert_eq!(report.variants.len(), options.variants.len());
    let distance = |variant| {
        let run = report
            .variants
            .iter()
            .find(|r| r.variant == variant)
            .unwrap();
        assert!(run.failure.is_none(), "{variant}: {:?}", run.failure);
        run.error_converged.unwrap()
    };
    // The same integrator as the converged run: the same positions, bit
    // for bit.
    assert!(distance(StepVariant::Newton(1e-9)) <= 0.0);
    let (loose, tight) = (
        distance(StepVariant::Newton(1e-2)),
        distance(StepVariant::Newton(1e-6)),
    );
    assert!(
        tight < 1e-2 * loose && tight < 1e-6,
        "Newton 1e-2: {loose:e} m, 1e-6: {tight:e} m"
    );
    let fms = [10, 100, 1000].map(|k| distance(StepVariant::FastMassSpring(k)));
    assert!(
        fms[0] > 2.0 * fms[1] && fms[1] > 2.0 * fms[2],
        "fast mass-spring 10 / 100 / 1000: {fms:?}"
    );
    let linearized = report
        .variants
        .iter()
        .find(|r| r.variant == StepVariant::Linearized)
        .unwrap();
    assert!((linearized.iterations_per_step - 1.0).abs() < 1e-12);
    assert!(linearized.error_converged.unwrap() > tight);
    // The converged step's own error against the reference, and each
    // variant's, are measured as a method's run is.
    let converged = &report.converged[0];
    assert_eq!(converged.unconverged_steps, 0);
    assert!(converged.error_rms.is_some_and(|e| e > 0.0));
}
