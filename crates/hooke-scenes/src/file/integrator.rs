//! `[simulation]` and `[integrator]`: the [`Timing`] and the
//! [`IntegratorSpec`] of a scene file.

use std::ops::Range;

use hooke_implicit::{Implicit, Scheme};
use toml::Spanned;

use super::error::{ErrorKind, SceneFileError, Source};
use super::schema::{IntegratorTable, Simulation};
use super::values::positive;
use crate::{ExplicitMethod, IntegratorSpec, SolverSpec, Timing};

/// Defaults of `[simulation]`: 5 s at 1/60 s steps, 60 frames per second.
const DEFAULT_TIMING: Timing = Timing {
    duration: 5.0,
    dt: 1.0 / 60.0,
    frame_rate: 60.0,
};

/// The method names of the implicit and adaptive integrators.
const OTHER_METHODS: [&str; 3] = ["backward-euler", "bdf2", "dormand-prince"];

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

/// The integrator: backward Euler with Cholesky and converged Newton steps
/// unless the table says otherwise. Keys that do not apply to the chosen
/// method or solver are errors.
pub(crate) fn integrator(
    src: &Source<'_>,
    table: Option<&Spanned<IntegratorTable>>,
) -> Result<IntegratorSpec, SceneFileError> {
    let Some(table) = table else {
        return Ok(IntegratorSpec::backward_euler());
    };
    let t = table.get_ref();
    let method = t
        .method
        .as_ref()
        .map_or("backward-euler", |m| m.get_ref().as_str());
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
        ("step", t.step.as_ref().map(Spanned::span)),
        (
            "newton_iterations",
            t.newton_iterations.as_ref().map(Spanned::span),
        ),
        (
            "newton_tolerance",
            t.newton_tolerance.as_ref().map(Spanned::span),
        ),
    ];
    let pcg_only = [
        ("tolerance", t.tolerance.as_ref().map(Spanned::span)),
        (
            "max_iterations",
            t.max_iterations.as_ref().map(Spanned::span),
        ),
    ];
    let adaptive_only = [
        ("rtol", t.rtol.as_ref().map(Spanned::span)),
        ("atol", t.atol.as_ref().map(Spanned::span)),
    ];
    let reject = |keys: &[(&str, Option<Range<usize>>)], applies_to: &str| {
        keys.iter()
            .find_map(|(key, span)| span.clone().map(|s| not_for(s, key, applies_to)))
            .map_or(Ok(()), Err)
    };
    let scheme = match method {
        "backward-euler" => Some(Scheme::BackwardEuler),
        "bdf2" => Some(Scheme::Bdf2),
        _ => None,
    };
    let spec = if let Some(scheme) = scheme {
        reject(&adaptive_only, "method \"dormand-prince\"")?;
        let solver = match t.solver.as_ref().map(|s| (s.get_ref().as_str(), s.span())) {
            None | Some(("cholesky", _)) => {
                reject(&pcg_only, "solver \"pcg\"")?;
                SolverSpec::Cholesky
            }
            Some(("pcg", _)) => SolverSpec::Pcg {
                tolerance: t.tolerance.as_ref().map_or(1e-6, |v| *v.get_ref()),
                max_iterations: t.max_iterations.as_ref().map_or(1000, |v| *v.get_ref()),
            },
            Some((other, span)) => {
                return Err(src.invalid(
                    span,
                    "integrator.solver",
                    format!("\"{other}\""),
                    "\"cholesky\" or \"pcg\"",
                ));
            }
        };
        let linearized = match t.step.as_ref().map(|s| (s.get_ref().as_str(), s.span())) {
            None | Some(("converged", _)) => false,
            Some(("linearized", _)) => true,
            Some((other, span)) => {
                return Err(src.invalid(
                    span,
                    "integrator.step",
                    format!("\"{other}\""),
                    "\"converged\" or \"linearized\"",
                ));
            }
        };
        IntegratorSpec::Implicit {
            scheme,
            solver,
            linearized,
            newton_iterations: t
                .newton_iterations
                .as_ref()
                .map_or(Implicit::NEWTON_ITERATIONS, |v| *v.get_ref()),
            newton_tolerance: t
                .newton_tolerance
                .as_ref()
                .map_or(Implicit::NEWTON_TOLERANCE, |v| *v.get_ref()),
        }
    } else if method == "dormand-prince" {
        reject(&implicit_only, "methods \"backward-euler\" and \"bdf2\"")?;
        reject(&pcg_only, "solver \"pcg\"")?;
        IntegratorSpec::Adaptive {
            rtol: t.rtol.as_ref().map_or(1e-6, |v| *v.get_ref()),
            atol: t.atol.as_ref().map_or(1e-9, |v| *v.get_ref()),
        }
    } else if let Some(explicit) = ExplicitMethod::ALL.iter().find(|m| m.name() == method) {
        reject(&implicit_only, "methods \"backward-euler\" and \"bdf2\"")?;
        reject(&pcg_only, "solver \"pcg\"")?;
        reject(&adaptive_only, "method \"dormand-prince\"")?;
        IntegratorSpec::Explicit(*explicit)
    } else {
        let names: Vec<String> = OTHER_METHODS
            .iter()
            .copied()
            .chain(ExplicitMethod::ALL.iter().map(|m| m.name()))
            .map(|n| format!("\"{n}\""))
            .collect();
        let span = t.method.as_ref().map_or(table.span(), Spanned::span);
        return Err(src.invalid(
            span,
            "integrator.method",
            format!("\"{method}\""),
            format!("one of {}", names.join(", ")),
        ));
    };
    // The integrators check their own parameter ranges; point at the key.
    spec.build().map_err(|e| {
        let span = [
            ("tolerance", t.tolerance.as_ref().map(Spanned::span)),
            (
                "max_iterations",
                t.max_iterations.as_ref().map(Spanned::span),
            ),
            (
                "newton_iterations",
                t.newton_iterations.as_ref().map(Spanned::span),
            ),
            (
                "newton_tolerance",
                t.newton_tolerance.as_ref().map(Spanned::span),
            ),
            ("rtol", t.rtol.as_ref().map(Spanned::span)),
            ("atol", t.atol.as_ref().map(Spanned::span)),
        ]
        .into_iter()
        .find(|(key, _)| *key == e.parameter)
        .and_then(|(_, span)| span)
        .unwrap_or(table.span());
        src.error(
            Some(span),
            format!("integrator.{}", e.parameter),
            ErrorKind::Integrator(e),
        )
    })?;
    Ok(spec)
}
