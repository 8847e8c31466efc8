//! Where an implicit (sub)step's minimisation starts ([`Start`]): from
//! feasible positions where barriers hold, otherwise from `vₙ` and, for a
//! minimiser that assembles Newton's matrix, from Baraff & Witkin's
//! linearised step. Every candidate carries the scripted pins' prescribed
//! velocity changes `z`, so every later step lies in the free directions.

use hooke_core::{At, StepError, StepReport, StepStart, System, Vec3};

use crate::linear::solver::solve::Solve;
use crate::linear::solver::topology::Topology;
use crate::linear::vector::for_each_row;
use crate::minimize::bounds::bound_start;
use crate::minimize::minimizer::Start;
use crate::minimize::newton::Linear;
use crate::minimize::terms::Terms;
use crate::step::pins::Pins;
use crate::step::predictor::Predictor;
use crate::step::settings::ImplicitSettings;
use crate::step::work::Work;

/// Fills the starting candidates of the (sub)step of `system` from `step`
/// into the work's iterate and trial point and says which they are
/// (`pinned`: whether the system has scripted pins):
///
/// - with barriers ([`Start::Feasible`]): the feasible positions the
///   barriers give ([`Terms::start`]), and the inertial predictor
///   `vₙ + z` as far towards it as no pair comes closer than a tenth of
///   its gap;
/// - for a minimiser that assembles no matrix ([`Start::Current`]):
///   `vₙ + z` alone;
/// - otherwise ([`Start::Linearized`]): Baraff & Witkin's linearised step
///   ([`linearized`]) and `vₙ + z`.
///
/// # Errors
/// Assembly and solver errors of the linearised solve.
pub(crate) fn candidates(
    settings: &ImplicitSettings,
    (system, terms): (&System, &mut Terms),
    step: &StepStart<'_>,
    (pins, pinned): (&mut Pins, bool),
    topology: &mut Topology,
    work: &mut Work,
    report: &mut StepReport,
) -> Result<Start, StepError> {
    let (v0, beta_h) = (step.v, step.beta_h);
    let (x_tilde, it) = (&work.predictor.x_tilde, &mut work.iterates);
    if let Some(start) = terms.start() {
        let prescribed = &pins.prescribed;
        for_each_row(&mut it.v, |i, v| {
            *v = if system.is_pinned(i) {
                v0[i] + prescribed[i]
            } else {
                (start[i] - x_tilde[i]) / beta_h
            };
        });
        let (v, ahead, x) = (&it.v, &mut it.ahead, &mut work.x);
        for_each_row(&mut it.trial, |i, t| *t = v0[i] + prescribed[i] - v[i]);
        for_each_row(x, |i, x| *x = x_tilde[i] + beta_h * v[i]);
        let trial = &it.trial;
        for_each_row(ahead, |i, a| *a = beta_h * trial[i]);
        bound_start(
            terms,
            system,
            settings.contact_limit,
            (x, ahead),
            (v, &mut it.trial),
        );
        return Ok(Start::Feasible);
    }
    if !settings.minimizer.assembles() {
        let prescribed = &pins.prescribed;
        for_each_row(&mut it.v, |i, v| *v = v0[i] + prescribed[i]);
        return Ok(Start::Current);
    }
    let linear = Linear {
        solve: Solve::new(system, settings.strict, step.time),
        topology,
        pcg: &mut work.pcg,
        b: &mut work.b,
        report,
    };
    let predictor = &work.predictor;
    linearized(
        (terms, linear),
        (step, predictor),
        (pins, pinned),
        settings,
        &mut work.dv,
    )?;
    let (dv, it, prescribed) = (&work.dv, &mut work.iterates, &pins.prescribed);
    for_each_row(&mut it.v, |i, v| *v = v0[i] + dv[i] + prescribed[i]);
    for_each_row(&mut it.trial, |i, t| *t = v0[i] + prescribed[i]);
    Ok(Start::Linearized)
}

/// Baraff & Witkin's linearised step `Δv = y + z` from `step`: one solve
/// of the system linearised at `xₙ` (compressed springs as the settings
/// say; the predictor's displacement `u` moves the linearisation from
/// `x̃ + βh vₙ` to `xₙ`), `S A y = S (b − A z)` with the pins' prescribed
/// `z` where the system has scripted pins (`pinned`), into `dv` (a warm
/// start on entry).
///
/// # Errors
/// Assembly and solver errors.
fn linearized(
    (terms, mut linear): (&mut Terms, Linear<'_>),
    (step, predictor): (&StepStart<'_>, &Predictor),
    (pins, pinned): (&mut Pins, bool),
    settings: &ImplicitSettings,
    dv: &mut [Vec3],
) -> Result<(), StepError> {
    let at = At {
        x: step.x,
        v: step.v,
        v_tilde: &predictor.v_tilde,
        beta_h: step.beta_h,
        displacement: Some(&predictor.u),
        compressed: settings.compressed,
    };
    linear.assemble(terms, &at)?;
    if pinned {
        pins.prescribe(linear.topology.matrix(), linear.b);
    }
    linear.solve(step.x, dv)
}
