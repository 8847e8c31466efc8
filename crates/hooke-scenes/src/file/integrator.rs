//! `[simulation]` and `[integrator]`: the [`Timing`] and the
//! [`IntegratorSpec`] of a scene file.

use std::ops::Range;

use hooke_core::{Named, Parameter, ParameterError, quoted_list};
use hooke_implicit::{ImplicitSettings, KeyError, KeyProblem, KeyValue, LinearSolver};
use toml::Spanned;

use super::error::{ErrorKind, SceneFileError, Source};
use super::schema::{IntegratorTable, Simulation};
use super::values::positive;
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

/// The integrator: backward Euler with the default [`ImplicitSettings`]
/// unless the table says otherwise; every default is the integrator's own
/// ([`IntegratorSpec::new`]). The implicit methods' keys set their
/// [`ImplicitSettings`] through [`ImplicitSettings::from_keys`], which
/// rejects the keys that do not apply to the chosen solver or step; keys
/// that do not apply to the chosen method are errors here.
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
    let settings_keys = settings_keys(t);
    let given = |keys: &[&str]| -> Vec<(&str, Option<Range<usize>>)> {
        settings_keys
            .iter()
            .filter(|(key, ..)| keys.contains(key))
            .map(|(key, _, span)| (*key, Some(span.clone())))
            .collect()
    };
    let pcg_only = given(&["tolerance", "max_iterations"]);
    let tolerances = given(&["rtol", "atol"]);
    let implicit_only: Vec<_> = settings_keys
        .iter()
        .filter(|(key, ..)| !["tolerance", "max_iterations", "rtol", "atol"].contains(key))
        .map(|(key, _, span)| (*key, Some(span.clone())))
        .collect();
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
        IntegratorSpec::Implicit(defaults) => {
            reject(&fast_only, &fast_name)?;
            let scheme = ("scheme", KeyValue::Name(defaults.scheme.name()));
            let keys = settings_keys.iter().map(|&(key, value, _)| (key, value));
            let settings = ImplicitSettings::from_keys(std::iter::once(scheme).chain(keys))
                .map_err(|error| key_error(src, table, &settings_keys, error))?;
            IntegratorSpec::Implicit(settings)
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

/// A value and its place in the file.
type Entry<'t> = (&'static str, KeyValue<'t>, Range<usize>);

/// The keys of the table that name [`ImplicitSettings`]' fields (every key
/// but `method` and `iterations`), with their values and places, in the
/// order the table's schema lists them.
fn settings_keys(t: &IntegratorTable) -> Vec<Entry<'_>> {
    fn entry<'t, T: AsKeyValue>(
        key: &'static str,
        value: Option<&'t Spanned<T>>,
    ) -> Option<Entry<'t>> {
        value.map(|v| (key, v.get_ref().as_key_value(), v.span()))
    }
    [
        entry("solver", t.solver.as_ref()),
        entry("weak_springs", t.weak_springs.as_ref()),
        entry("supernodes", t.supernodes.as_ref()),
        entry("amg_renewal", t.amg_renewal.as_ref()),
        entry("step", t.step.as_ref()),
        entry("history", t.history.as_ref()),
        entry("carried_pairs", t.carried_pairs.as_ref()),
        entry("tolerance", t.tolerance.as_ref()),
        entry("max_iterations", t.max_iterations.as_ref()),
        entry("newton_iterations", t.newton_iterations.as_ref()),
        entry("newton_tolerance", t.newton_tolerance.as_ref()),
        entry("inexact_newton", t.inexact_newton.as_ref()),
        entry("max_halvings", t.max_halvings.as_ref()),
        entry("strict", t.strict.as_ref()),
        entry("compressed_springs", t.compressed_springs.as_ref()),
        entry("rtol", t.rtol.as_ref()),
        entry("atol", t.atol.as_ref()),
        entry("contact_limit", t.contact_limit.as_ref()),
    ]
    .into_iter()
    .flatten()
    .collect()
}

/// A value of the table as the implicit settings' keys take it.
trait AsKeyValue {
    fn as_key_value(&self) -> KeyValue<'_>;
}

impl AsKeyValue for String {
    fn as_key_value(&self) -> KeyValue<'_> {
        KeyValue::Name(self)
    }
}

impl AsKeyValue for usize {
    fn as_key_value(&self) -> KeyValue<'_> {
        KeyValue::Count(*self as u64)
    }
}

impl AsKeyValue for u32 {
    fn as_key_value(&self) -> KeyValue<'_> {
        KeyValue::Count(u64::from(*self))
    }
}

impl AsKeyValue for f64 {
    fn as_key_value(&self) -> KeyValue<'_> {
        KeyValue::Number(*self)
    }
}

impl AsKeyValue for bool {
    fn as_key_value(&self) -> KeyValue<'_> {
        KeyValue::Switch(*self)
    }
}

/// `error`, a key of the implicit settings that cannot set them, at the
/// key (the table itself for a key the file does not give).
fn key_error(
    src: &Source<'_>,
    table: &Spanned<IntegratorTable>,
    keys: &[Entry<'_>],
    error: KeyError,
) -> SceneFileError {
    let span = keys
        .iter()
        .find(|(key, ..)| *key == error.key)
        .map_or(table.span(), |(_, _, span)| span.clone());
    let key = format!("integrator.{}", error.key);
    match error.problem {
        KeyProblem::Invalid { value, expected } => src.invalid(span, key, value, expected),
        KeyProblem::OutOfRange(error) => src.error(Some(span), key, ErrorKind::Integrator(error)),
    }
}

/// `error`, a setting of the table's explicit, adaptive or fast
/// mass-spring integrator out of range, at the key that set it (the table
/// itself for a setting scene files do not name).
fn out_of_range(
    src: &Source<'_>,
    table: &Spanned<IntegratorTable>,
    error: ParameterError,
) -> SceneFileError {
    let t = table.get_ref();
    let (key, span) = match error.parameter {
        Parameter::Rtol => ("rtol", t.rtol.as_ref().map(Spanned::span)),
        Parameter::Atol => ("atol", t.atol.as_ref().map(Spanned::span)),
        Parameter::Iterations => ("iterations", t.iterations.as_ref().map(Spanned::span)),
        other => (other.name(), None),
    };
    src.error(
        Some(span.unwrap_or(table.span())),
        format!("integrator.{key}"),
        ErrorKind::Integrator(error),
    )
}
