//! The keys that name [`ImplicitSettings`]' fields — those of a scene
//! file's `[integrator]` table, of `summary.json`'s `implicit_settings`,
//! of keyword arguments — and the rule of which keys apply to which
//! solver and step: one reader ([`ImplicitSettings::from_keys`]) and one
//! writer ([`ImplicitSettings::keys`]) for all of them.
//!
//! A setting the settings gain is one more field, one more [`Key`] (its
//! name, its value, where it applies) and, for an enum, its table of names
//! ([`Named`]); scene files, reports and the command line's description of
//! a scene then read and write it.

use std::fmt;
use std::mem::discriminant;

use hooke_core::{Named, ParameterError, quoted_list};
use thiserror::Error;

use super::ImplicitSettings;
use crate::linear::cg::PcgSettings;
use crate::linear::solver::LinearSolver;
use crate::minimize::minimizer::Minimizer;

/// A key's value as a scene file, a report or a keyword argument gives
/// it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum KeyValue<'a> {
    /// A name from a setting's table: `"cholesky"`, `"quasi-newton"` …
    Name(&'a str),
    /// A whole number.
    Count(u64),
    /// A number (a [`KeyValue::Count`] is one too).
    Number(f64),
    /// `true` or `false`.
    Switch(bool),
}

/// Written as in a scene file: `"cholesky"`, `100`, `0.005`, `true`.
impl fmt::Display for KeyValue<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Name(name) => write!(f, "\"{name}\""),
            Self::Count(n) => write!(f, "{n}"),
            Self::Number(x) => write!(f, "{x:?}"),
            Self::Switch(b) => write!(f, "{b}"),
        }
    }
}

/// A key that cannot set [`ImplicitSettings`]: the key and what is wrong
/// with it, read `key: problem`.
#[derive(Debug, Clone, PartialEq, Error)]
#[error("{key}: {problem}")]
pub struct KeyError {
    /// The key at fault, as given.
    pub key: String,
    /// What is wrong.
    pub problem: KeyProblem,
}

/// What is wrong with a key ([`KeyError`]).
#[derive(Debug, Clone, PartialEq, Error)]
pub enum KeyProblem {
    /// An unknown key or name, a value of the wrong kind, a key that does
    /// not apply to the chosen solver or step, or keys that contradict
    /// each other.
    #[error("got {value}, expected {expected}")]
    Invalid {
        /// What was given.
        value: String,
        /// What the key takes.
        expected: String,
    },
    /// A value outside the setting's range.
    #[error("{0}")]
    OutOfRange(ParameterError),
}

impl KeyError {
    pub(super) fn invalid(
        key: impl Into<String>,
        value: impl fmt::Display,
        expected: String,
    ) -> Self {
        Self {
            key: key.into(),
            problem: KeyProblem::Invalid {
                value: value.to_string(),
                expected,
            },
        }
    }

    pub(super) fn out_of_range(key: Key, error: ParameterError) -> Self {
        Self {
            key: key.name().to_owned(),
            problem: KeyProblem::OutOfRange(error),
        }
    }
}

/// A key of the settings, in the order reports list them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Key {
    Scheme,
    Solver,
    Tolerance,
    MaxIterations,
    Step,
    History,
    CarriedPairs,
    NewtonIterations,
    NewtonTolerance,
    InexactNewton,
    AmgRenewal,
    WeakSprings,
    Supernodes,
    MaxHalvings,
    Strict,
    CompressedSprings,
    Rtol,
    Atol,
    ContactLimit,
}

impl Named for Key {
    const TABLE: &'static [(Self, &'static str)] = &[
        (Self::Scheme, "scheme"),
        (Self::Solver, "solver"),
        (Self::Tolerance, "tolerance"),
        (Self::MaxIterations, "max_iterations"),
        (Self::Step, "step"),
        (Self::History, "history"),
        (Self::CarriedPairs, "carried_pairs"),
        (Self::NewtonIterations, "newton_iterations"),
        (Self::NewtonTolerance, "newton_tolerance"),
        (Self::InexactNewton, "inexact_newton"),
        (Self::AmgRenewal, "amg_renewal"),
        (Self::WeakSprings, "weak_springs"),
        (Self::Supernodes, "supernodes"),
        (Self::MaxHalvings, "max_halvings"),
        (Self::Strict, "strict"),
        (Self::CompressedSprings, "compressed_springs"),
        (Self::Rtol, "rtol"),
        (Self::Atol, "atol"),
        (Self::ContactLimit, "contact_limit"),
    ];
}

/// Where a key means anything: to the solvers listed (every solver where
/// none is) and to the steps with a property (every step where none is
/// given), both or either (see [`Key::scope`]).
struct Scope {
    solvers: &'static [LinearSolver],
    steps: Option<fn(Minimizer) -> bool>,
    either: bool,
}

/// The solvers that factor Newton's matrix.
const FACTORED: &[LinearSolver] = &[LinearSolver::Auto, LinearSolver::Cholesky];
/// The PCG iterations.
const ITERATIVE: &[LinearSolver] = &[
    LinearSolver::Pcg(PcgSettings::DEFAULT),
    LinearSolver::Amg(PcgSettings::DEFAULT),
    LinearSolver::LaggedCholesky(PcgSettings::DEFAULT),
];
/// The solvers that may run multigrid on Newton's matrix.
const MULTIGRID: &[LinearSolver] = &[LinearSolver::Auto, LinearSolver::Amg(PcgSettings::DEFAULT)];
/// The steps that assemble Newton's matrix.
const ASSEMBLED: Option<fn(Minimizer) -> bool> = Some(Minimizer::assembles);
/// The steps that keep an L-BFGS history.
const HISTORY: Option<fn(Minimizer) -> bool> = Some(|m| m.history().is_some());
/// Newton's method.
const NEWTON: Option<fn(Minimizer) -> bool> = Some(|m| m == Minimizer::Newton);

impl Key {
    /// Where the key means anything, `None` for everywhere: PCG's keys to
    /// a PCG iteration, the L-BFGS history to the quasi-Newton step, the
    /// factorization's keys to Newton's sparse Cholesky (`weak_springs`
    /// also to the quasi-Newton step's `H₀`), `amg_renewal` to Newton's
    /// multigrid, the forcing term to Newton's iterations, the compressed
    /// springs' clamp to the steps that assemble the spring Hessian.
    fn scope(self) -> Option<Scope> {
        let (solvers, steps, either) = match self {
            Self::Tolerance | Self::MaxIterations => (ITERATIVE, None, false),
            Self::History | Self::CarriedPairs => (&[][..], HISTORY, false),
            Self::WeakSprings => (FACTORED, HISTORY, true),
            Self::Supernodes => (FACTORED, ASSEMBLED, false),
            Self::AmgRenewal => (MULTIGRID, ASSEMBLED, false),
            Self::InexactNewton => (&[][..], NEWTON, false),
            Self::CompressedSprings => (&[][..], ASSEMBLED, false),
            _ => return None,
        };
        Some(Scope {
            solvers,
            steps,
            either,
        })
    }

    /// Whether the key means anything to settings with `s`'s solver and
    /// step ([`Key::scope`]).
    pub(super) fn applies(self, s: &ImplicitSettings) -> bool {
        self.in_scope(s).is_ok()
    }

    /// Nothing if the key applies to settings with `s`'s solver and step
    /// ([`Key::scope`]).
    ///
    /// # Errors
    /// A [`KeyError`] naming the key, the solver and step it was given
    /// with, and where it applies.
    pub(super) fn in_scope(self, s: &ImplicitSettings) -> Result<(), KeyError> {
        let Some(scope) = self.scope() else {
            return Ok(());
        };
        let solver = scope.solvers.is_empty() || of_kind(scope.solvers, &s.solver);
        let step = scope.steps.is_none_or(|of| of(s.minimizer));
        if (scope.either && (solver || step)) || (solver && step) {
            return Ok(());
        }
        let (mut found, mut wanted) = (Vec::new(), Vec::new());
        if !scope.solvers.is_empty() {
            found.push(format!("solver \"{}\"", s.solver.name()));
            let names = scope.solvers.iter().map(|&v| v.name());
            wanted.push(format!("solver {}", quoted_list(names)));
        }
        if let Some(of) = scope.steps {
            found.push(format!("step = \"{}\"", s.minimizer.name()));
            let steps = Minimizer::TABLE.iter().filter(|&&(m, _)| of(m));
            wanted.push(format!(
                "step = {}",
                quoted_list(steps.map(|&(_, name)| name))
            ));
        }
        let key = self.name();
        let join = if scope.either { ", or with " } else { " and " };
        Err(KeyError::invalid(
            key,
            format!("`{key}` with {}", found.join(" and ")),
            format!("`{key}` only with {}", wanted.join(join)),
        ))
    }
}

/// Whether `value` is of the kind (the enum variant) of one of `list`.
fn of_kind<T>(list: &[T], value: &T) -> bool {
    list.iter().any(|v| discriminant(v) == discriminant(value))
}

impl ImplicitSettings {
    /// The settings as keys and values, in the order of the keys' table:
    /// every key that applies to these settings' solver and step, the
    /// defaults included, so that a report shows every setting a run used
    /// (`weak_springs` as [`ImplicitSettings::weak_springs_used`]; `rtol`
    /// and `atol` only with error control). Reading them back
    /// ([`ImplicitSettings::from_keys`]) gives the same settings, but for
    /// `weak_springs`, read back as the one used where it applies and as
    /// unset where it does not: settings that step alike.
    ///
    /// ```
    /// use hooke_implicit::{ImplicitSettings, KeyValue, WeakSprings};
    /// let defaults = ImplicitSettings::default();
    /// let keys = defaults.keys();
    /// assert_eq!(keys[1], ("solver", KeyValue::Name("auto")));
    /// assert!(keys.contains(&("newton_iterations", KeyValue::Count(100))));
    /// assert!(keys.contains(&("weak_springs", KeyValue::Name("kept"))));
    /// assert!(!keys.iter().any(|(key, _)| *key == "history"));
    /// let read = ImplicitSettings::from_keys(keys)?;
    /// assert_eq!(read, ImplicitSettings { weak_springs: Some(WeakSprings::Kept), ..defaults });
    /// # Ok::<(), hooke_implicit::KeyError>(())
    /// ```
    #[must_use]
    pub fn keys(&self) -> Vec<(&'static str, KeyValue<'static>)> {
        Key::TABLE
            .iter()
            .filter(|(key, _)| key.applies(self))
            .filter_map(|&(key, name)| self.value(key).map(|value| (name, value)))
            .collect()
    }

    /// The value of `key`; `None` where the settings hold none (the PCG
    /// keys of a direct solver, the history of a step without one, the
    /// tolerances without error control).
    fn value(&self, key: Key) -> Option<KeyValue<'static>> {
        let count = |n: usize| KeyValue::Count(n as u64);
        let history = self.minimizer.history();
        let pcg = self.solver.pcg();
        Some(match key {
            Key::Scheme => KeyValue::Name(self.scheme.name()),
            Key::Solver => KeyValue::Name(self.solver.name()),
            Key::Tolerance => KeyValue::Number(pcg?.tolerance()),
            Key::MaxIterations => count(pcg?.max_iterations()),
            Key::Step => KeyValue::Name(self.minimizer.name()),
            Key::History => count(history?.0),
            Key::CarriedPairs => count(history?.1),
            Key::NewtonIterations => count(self.newton_iterations),
            Key::NewtonTolerance => KeyValue::Number(self.newton_tolerance),
            Key::InexactNewton => KeyValue::Switch(self.inexact_newton),
            Key::AmgRenewal => KeyValue::Name(self.amg_renewal.name()),
            Key::WeakSprings => KeyValue::Name(self.weak_springs_used().name()),
            Key::Supernodes => KeyValue::Name(self.supernodes.name()),
            Key::MaxHalvings => KeyValue::Count(u64::from(self.max_halvings)),
            Key::Strict => KeyValue::Switch(self.strict),
            Key::CompressedSprings => KeyValue::Name(self.compressed.name()),
            Key::Rtol => KeyValue::Number(self.error_control?.relative()),
            Key::Atol => KeyValue::Number(self.error_control?.absolute()),
            Key::ContactLimit => KeyValue::Name(self.contact_limit.name()),
        })
    }
}
