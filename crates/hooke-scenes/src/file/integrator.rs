//! `[simulation]` and `[integrator]`: the [`Timing`] and the
//! [`IntegratorSpec`] of a scene file.

use std::ops::Range;

use hooke_core::{Parameter, ParameterError};
use hooke_implicit::{ErrorControl, LinearSolver, Minimizer, PcgSettings, Scheme, WeakSprings};
use toml::Spanned;

use super::error::{ErrorKind, SceneFileError, Source};
use super::schema::{IntegratorTable, Simulation};
use super::values::positive;
use crate::integrator::quoted_list;
use crate::{IntegratorSpec, Method, Timing};

/// Defaults of `[simulation]`: 5 s at 1/60 s steps, 60 frames per second.
const DEFAULT_TIMING: Timing = Timing {
    duration: 5.0,
    dt: 1.0 / 60.0,
    frame_rate: 60.0,
};

/// The timing: every value finite and positive, the step no longer than
/// the run.
pub(crate) fn timing(
    src: &Source<'_>,
    simulation: Option<&Simulation>,
) -> Result<Timing, SceneFileError> {
    let mut timing = DEFAULT_TIMING;
    let Some(s) = simulation else {
        return Ok(timing);
    };
    if let Some(d) = &s.duration {
        timing.duration = positive(src, d, "simulation.duration", "s")?;
    }
    if let Some(dt) = &s.dt {
        timing.dt = positive(src, dt, "simulation.dt", "s")?;
    }
    if let Some(f) = &s.frame_rate {
        timing.frame_rate = positive(src, f, "simulation.frame_rate", "frames per second")?;
    }
    if timing.dt > timing.duration {
        let (span, key) = match (&s.dt, &s.duration) {
            (Some(dt), _) => (dt.span(), "simulation.dt"),
            (None, Some(d)) => (d.span(), "simulation.duration"),
            (None, None) => (0..0, "simulation"),
        };
        return Err(src.invalid(
            span,
            key,
            format!(
                "dt = {} s over a duration of {} s",
                timing.dt, timing.duration
            ),
            "a step no longer than the duration",
        ));
    }
    Ok(timing)
}

/// The integrator: backward Euler with the automatic solver choice and converged Newton steps
/// unless the table says otherwise; every default is the integrator's own
/// ([`IntegratorSpec::new`], [`PcgSettings::default`]). Keys that do not apply
/// to the chosen method or solver are errors.
pub(crate) fn integrator(
    src: &Source<'_>,
    table: Option<&Spanned<IntegratorTable>>,
) -> Result<IntegratorSpec, SceneFileError> {
    let default = Method::BackwardEuler;
    let Some(table) = table else {
        return Ok(IntegratorSpec::new(default));
    };
    let t = table.get_ref();
    let method = t
        .method
        .as_ref()
        .map_or(default.name(), |m| m.get_ref().as_str());
    let not_for = |span: Range<usize>, key: &str, applies_to: &str| {
        src.invalid(
            span,
            format!("integrator.{key}"),
            format!("`{key}` with method \"{method}\""),
            format!("`{key}` only with {applies_to}"),
        )
    };
    let implicit_only = [
        ("solver", t.solver.as_ref().map(Spanned::span)),
        ("weak_springs", t.weak_springs.as_ref().map(Spanned::span)),
        ("step", t.step.as_ref().map(Spanned::span)),
        ("history", t.history.as_ref().map(Spanned::span)),
        ("carried_pairs", t.carried_pairs.as_ref().map(Spanned::span)),
        (
            "newton_iterations",
            t.newton_iterations.as_ref().map(Spanned::span),
        ),
        (
            "newton_tolerance",
            t.newton_tolerance.as_ref().map(Spanned::span),
        ),
        ("max_halvings", t.max_halvings.as_ref().map(Spanned::span)),
        ("strict", t.strict.as_ref().map(Spanned::span)),
    ];
    let pcg_only = [
        ("tolerance", t.tolerance.as_ref().map(Spanned::span)),
        (
            "max_iterations",
            t.max_iterations.as_ref().map(Spanned::span),
        ),
    ];
    let tolerances = [
        ("rtol", t.rtol.as_ref().map(Spanned::span)),
        ("atol", t.atol.as_ref().map(Spanned::span)),
    ];
    let fast_only = [("iterations", t.iterations.as_ref().map(Spanned::span))];
    let iterative_solvers = format!("solver {}", quoted_list(LinearSolver::iterative_names()));
    let fast_name = format!("method \"{}\"", Method::FastMassSpring);
    let reject = |keys: &[(&str, Option<Range<usize>>)], applies_to: &str| {
        keys.iter()
            .find_map(|(key, span)| span.clone().map(|s| not_for(s, key, applies_to)))
            .map_or(Ok(()), Err)
    };
    let Some(chosen) = Method::from_name(method) else {
        let span = t.method.as_ref().map_or(table.span(), Spanned::span);
        return Err(src.invalid(
            span,
            "integrator.method",
            format!("\"{method}\""),
            format!("one of {}", Method::names()),
        ));
    };
    let implicit_names = format!(
        "methods \"{}\" and \"{}\"",
        Method::BackwardEuler,
        Method::Bdf2
    );
    let error_controlled = format!(
        "methods \"{}\", \"{}\" and \"{}\"",
        Method::BackwardEuler,
        Method::Bdf2,
        Method::DormandPrince
    );
    let spec = match IntegratorSpec::new(chosen) {
        IntegratorSpec::Implicit {
            scheme,
            newton_iterations,
            newton_tolerance,
            max_halvings,
            strict,
            ..
        } => {
            reject(&fast_only, &fast_name)?;
            let reject_pcg = || reject(&pcg_only, &iterative_solvers);
            let defaults = (newton_iterations, newton_tolerance, max_halvings, strict);
            implicit(src, table, scheme, defaults, reject_pcg)?
        }
        IntegratorSpec::Adaptive { rtol, atol } => {
            reject(&implicit_only, &implicit_names)?;
            reject(&pcg_only, &iterative_solvers)?;
            reject(&fast_only, &fast_name)?;
            IntegratorSpec::Adaptive {
                rtol: t.rtol.as_ref().map_or(rtol, |v| *v.get_ref()),
                atol: t.atol.as_ref().map_or(atol, |v| *v.get_ref()),
            }
        }
        explicit @ IntegratorSpec::Explicit(_) => {
            reject(&implicit_only, &implicit_names)?;
            reject(&pcg_only, &iterative_solvers)?;
            reject(&tolerances, &error_controlled)?;
            reject(&fast_only, &fast_name)?;
            explicit
        }
        IntegratorSpec::FastMassSpring { iterations } => {
            reject(&implicit_only, &implicit_names)?;
            reject(&pcg_only, &iterative_solvers)?;
            reject(&tolerances, &error_controlled)?;
            IntegratorSpec::FastMassSpring {
                iterations: t.iterations.as_ref().map_or(iterations, |v| *v.get_ref()),
            }
        }
    };
    // The integrators check their own parameter ranges; point at the key.
    spec.build().map_err(|e| out_of_range(src, table, e))?;
    Ok(spec)
}

/// The keys of an implicit method's table over the defaults `(newton
/// iterations, newton tolerance, max halvings, strict)` of `scheme`;
/// `reject_pcg` fails if the table has PCG's keys, for a solver that is
/// not iterative. `rtol` or `atol` turn error control on, the one not
/// given at its default ([`ErrorControl::RELATIVE`],
/// [`ErrorControl::ABSOLUTE`]).
fn implicit(
    src: &Source<'_>,
    table: &Spanned<IntegratorTable>,
    scheme: Scheme,
    (newton_iterations, newton_tolerance, max_halvings, strict): (usize, f64, u32, bool),
    reject_pcg: impl FnOnce() -> Result<(), SceneFileError>,
) -> Result<IntegratorSpec, SceneFileError> {
    let t = table.get_ref();
    let defaults = PcgSettings::default();
    let tolerance = t
        .tolerance
        .as_ref()
        .map_or(defaults.tolerance(), |v| *v.get_ref());
    let max_iterations = t
        .max_iterations
        .as_ref()
        .map_or(defaults.max_iterations(), |v| *v.get_ref());
    let solver = match &t.solver {
        None => LinearSolver::Auto,
        Some(name) => named(
            src,
            ("solver", name),
            LinearSolver::from_name,
            &LinearSolver::NAMES,
        )?,
    };
    if solver.pcg().is_none() {
        reject_pcg()?;
    }
    let history = t
        .history
        .as_ref()
        .map_or(Minimizer::HISTORY, |v| *v.get_ref());
    let carried = match &t.carried_pairs {
        None => Minimizer::CARRIED.min(history),
        Some(c) if *c.get_ref() > history => {
            return Err(src.invalid(
                c.span(),
                "integrator.carried_pairs",
                format!("{} with history = {history}", c.get_ref()),
                "at most `history`",
            ));
        }
        Some(c) => *c.get_ref(),
    };
    // The minimisers by their own names; "converged" is Newton's old name.
    let minimizers = [
        Minimizer::Newton,
        Minimizer::QuasiNewton { history, carried },
        Minimizer::Linearized,
    ];
    let minimizer = match t.step.as_ref().map(|s| (s.get_ref().as_str(), s.span())) {
        None | Some(("converged", _)) => Minimizer::Newton,
        Some((name, span)) => minimizers
            .into_iter()
            .find(|m| m.name() == name)
            .ok_or_else(|| {
                src.invalid(
                    span,
                    "integrator.step",
                    format!("\"{name}\""),
                    format!(
                        "{} (or \"converged\" for \"newton\")",
                        quoted_list(minimizers.iter().map(|m| m.name()))
                    ),
                )
            })?,
    };
    // Newton's and the linearised step's matrix is factorized only by
    // `auto` or `cholesky`; the quasi-Newton step's `H₀` by any solver.
    let weak_springs = match &t.weak_springs {
        None => None,
        Some(name)
            if !matches!(minimizer, Minimizer::QuasiNewton { .. })
                && !matches!(solver, LinearSolver::Auto | LinearSolver::Cholesky) =>
        {
            return Err(src.invalid(
                name.span(),
                "integrator.weak_springs",
                format!("`weak_springs` with solver \"{}\"", solver.name()),
                "`weak_springs` only with solver \"auto\" or \"cholesky\", \
                 or with step = \"quasi-newton\"",
            ));
        }
        Some(name) => Some(named(
            src,
            ("weak_springs", name),
            WeakSprings::from_name,
            &WeakSprings::NAMES,
        )?),
    };
    if !matches!(minimizer, Minimizer::QuasiNewton { .. }) {
        let keys = [
            ("history", t.history.as_ref().map(Spanned::span)),
            ("carried_pairs", t.carried_pairs.as_ref().map(Spanned::span)),
        ];
        if let Some((key, Some(span))) = keys.into_iter().find(|(_, span)| span.is_some()) {
            return Err(src.invalid(
                span,
                format!("integrator.{key}"),
                format!("`{key}` without step = \"quasi-newton\""),
                format!("`{key}` only with step = \"quasi-newton\""),
            ));
        }
    }
    let value = |key: Option<&Spanned<f64>>| key.map(|v| *v.get_ref());
    let error_control = match (value(t.rtol.as_ref()), value(t.atol.as_ref())) {
        (None, None) => None,
        (rtol, atol) => Some(
            ErrorControl::new(
                rtol.unwrap_or(ErrorControl::RELATIVE),
                atol.unwrap_or(ErrorControl::ABSOLUTE),
            )
            .map_err(|e| out_of_range(src, table, e))?,
        ),
    };
    // PCG's settings, checked after the other keys (`auto` and `cholesky`,
    // which take none, keep them at the defaults and ignore them).
    let pcg =
        PcgSettings::new(tolerance, max_iterations).map_err(|e| out_of_range(src, table, e))?;
    let solver = solver.with_pcg(pcg);
    Ok(IntegratorSpec::Implicit {
        scheme,
        solver,
        weak_springs,
        minimizer,
        newton_iterations: t
            .newton_iterations
            .as_ref()
            .map_or(newton_iterations, |v| *v.get_ref()),
        newton_tolerance: value(t.newton_tolerance.as_ref()).unwrap_or(newton_tolerance),
        max_halvings: t
            .max_halvings
            .as_ref()
            .map_or(max_halvings, |v| *v.get_ref()),
        strict: t.strict.as_ref().map_or(strict, |v| *v.get_ref()),
        error_control,
    })
}

/// The setting the value `name` of the key `integrator.key` names, found
/// by `find`; otherwise an error at it listing the names there are.
fn named<T>(
    src: &Source<'_>,
    (key, name): (&str, &Spanned<String>),
    find: impl Fn(&str) -> Option<T>,
    names: &[&str],
) -> Result<T, SceneFileError> {
    find(name.get_ref()).ok_or_else(|| {
        src.invalid(
            name.span(),
            format!("integrator.{key}"),
            format!("\"{}\"", name.get_ref()),
            quoted_list(names.iter().copied()),
        )
    })
}

/// `error`, a setting of the table's integrator out of range, at the key
/// that set it (the table itself for a setting scene files do not name).
fn out_of_range(
    src: &Source<'_>,
    table: &Spanned<IntegratorTable>,
    error: ParameterError,
) -> SceneFileError {
    let t = table.get_ref();
    let (key, span) = match error.parameter {
        Parameter::Tolerance => ("tolerance", t.tolerance.as_ref().map(Spanned::span)),
        Parameter::MaxIterations => (
            "max_iterations",
            t.max_iterations.as_ref().map(Spanned::span),
        ),
        Parameter::NewtonIterations => (
            "newton_iterations",
            t.newton_iterations.as_ref().map(Spanned::span),
        ),
        Parameter::NewtonTolerance => (
            "newton_tolerance",
            t.newton_tolerance.as_ref().map(Spanned::span),
        ),
        Parameter::Rtol | Parameter::RelativeTolerance => {
            ("rtol", t.rtol.as_ref().map(Spanned::span))
        }
        Parameter::Atol | Parameter::AbsoluteTolerance => {
            ("atol", t.atol.as_ref().map(Spanned::span))
        }
        Parameter::Iterations => ("iterations", t.iterations.as_ref().map(Spanned::span)),
        other @ (Parameter::Strength
        | Parameter::Filter
        | Parameter::SmootherDegree
        | Parameter::FineDegree
        | Parameter::CoarseUnknowns
        | Parameter::CellFactor) => (other.name(), None),
    };
    src.error(
        Some(span.unwrap_or(table.span())),
        format!("integrator.{key}"),
        ErrorKind::Integrator(error),
    )
}
